"""The attacking plays' aimed shot in the attack drill: which kick rule scores.

The attacking plays' attacker aims its shot at the widest open part of the goal mouth
(``ShootParams.aim_open_goal``). This probe plays the attack drill (``ssl_marl.decisions.attack_drill``,
the hand-coded cost decision for the carrier) with the attacker's kick rule replaced by one of:

* ``snap``: no aiming; the snap shot kicks as soon as the heading lies between the posts;
* ``edge``: aim at gaps of at least 0.06 rad, kick once the heading lies inside the gap less
  0.02 rad from its edges (a kick near the edge closest to the turning robot's heading);
* ``centre:MIN:WINDOW``: aim at gaps of at least MIN rad, kick once the heading lies within
  WINDOW x half the gap's width of its centre (the shipped rule is ``centre:0.15:0.3``);

and reports the goal rate and outcomes per rule on the same episodes (episode i: seed
``SEED + i`` as ``ssl-marl eval-task``)::

    python benchmarks/attack_drill_aim_probe.py --rules snap edge centre:0.06:0.3 centre:0.10:0.3 centre:0.15:0.3 \\
        centre:0.25:0.3 --episodes 200 --seed 46000 --out results/tuning/attack_drill_aim.json
"""

from __future__ import annotations

import argparse
import sys
from collections import Counter

import numpy as np
from tqdm import tqdm

from ssl_marl.decisions.attack_drill import AttackDrillEnv, HandcodedAttackDrillPolicy
from ssl_marl.decisions.policies import run_episode
from ssl_marl.io import atomic_write_json
from ssl_marl.plays import shoot
from ssl_marl.runners.provenance import build_manifest


def kick_rule(rule: str):
    """``GoToBallAndShoot.open_goal_action`` replacement for ``rule`` (module docstring); None for snap."""
    if rule == "snap":
        return lambda self, world, robot: None
    if rule == "edge":
        lo, window, margin = 0.06, None, 0.02
    elif rule.startswith("centre:"):
        _, lo_s, win_s = rule.split(":")
        lo, window, margin = float(lo_s), float(win_s), None
    else:
        raise ValueError(f"unknown rule {rule!r}: snap, edge or centre:MIN:WINDOW")

    def action(self, world, robot):
        ts = world.team(world.frame)
        others = np.concatenate([np.delete(ts.pos, robot, axis=0), world.opponents(world.frame).pos])
        open_angle, aim = shoot.open_goal_interval(world.ball_pos, others, self.field, self.rp, self.bp)
        if open_angle < lo:
            return None
        err = float(shoot.wrap_angle(aim - float(ts.heading[robot])))
        tol = max(open_angle / 2.0 - margin, 0.0) if window is None else window * open_angle / 2.0
        if abs(err) <= tol and bool(ts.kick_ready[robot]):
            return shoot.make_action(dribble=True, kick=1.0)
        omega = float(np.clip(6.0 * err, -self.params.open_aim_turn_rate, self.params.open_aim_turn_rate))
        return shoot.make_action(omega=omega / self.rp.max_omega, dribble=True)

    return action


def drill_outcomes(env: AttackDrillEnv, episodes: int, seed: int, desc: str, progress: bool) -> Counter:
    """Outcome counts of ``episodes`` drill episodes (seeds ``seed + i``) with the hand-coded decision."""
    policy, outcomes = HandcodedAttackDrillPolicy(), Counter()
    for i in tqdm(range(episodes), desc=desc, disable=not progress, leave=False):
        outcomes[run_episode(env, policy, seed=seed + i)["outcome"]] += 1
    return outcomes


def run(rule: str, episodes: int, seed: int, progress: bool) -> dict:
    original = shoot.GoToBallAndShoot.open_goal_action
    shoot.GoToBallAndShoot.open_goal_action = kick_rule(rule)
    try:
        outcomes = drill_outcomes(AttackDrillEnv(), episodes, seed, rule, progress)
    finally:
        shoot.GoToBallAndShoot.open_goal_action = original
    return {"rule": rule, "episodes": episodes, "goal_rate": outcomes["goal"] / episodes, "outcomes": dict(outcomes)}


def add_drill_options(ap: argparse.ArgumentParser, per: str) -> None:
    """The drill probes' shared options: --episodes (per ``per``), --seed, --out, --quiet."""
    ap.add_argument("--episodes", type=int, default=200, help=f"episodes per {per} (default 200)")
    ap.add_argument("--seed", type=int, default=46000, help="episode i uses SEED + i (default 46000, tuning seeds)")
    ap.add_argument("--out", required=True, help="JSON file to write")
    ap.add_argument("--quiet", action="store_true", help="no progress bar")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--rules", nargs="+", default=["snap", "edge", "centre:0.15:0.3"],
                    help="kick rules: snap, edge, centre:MIN:WINDOW (default: snap edge centre:0.15:0.3)")
    add_drill_options(ap, "rule")
    a = ap.parse_args(argv)
    for r in a.rules:
        kick_rule(r)  # bad rules fail before anything runs
    rows = [run(r, a.episodes, a.seed, not a.quiet) for r in a.rules]
    for r in rows:
        print(r, flush=True)
    atomic_write_json(a.out, {"rows": rows, "manifest": build_manifest(
        rules={"probe": "attack_drill_aim", "skills": "learned"}, seeds={"seed": a.seed, "episodes": a.episodes})})
    return 0


if __name__ == "__main__":
    sys.exit(main())
