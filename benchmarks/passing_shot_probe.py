"""Where a passing team shoots from: every kick by a blue robot of ``--team``
(``passing-learned`` by default; ``attack-learned`` plays in a chip env) against an
opponent, with the kicker's role, its distance to the goal centre (m), its heading error
to the goal centre (rad) and the widest open part of the goal mouth seen from the ball
(rad; :func:`~ssl_marl.plays.pass_decision.open_goal_interval`, every other robot
shadowing); and the pass coordinator's plans (planned, kicked, completed, aborted).

    python benchmarks/passing_shot_probe.py --seeds 45200-45203 --opponent baseline --out results/tuning/shot_probe.json
    python benchmarks/passing_shot_probe.py --team attack-learned --seconds 600 --seeds 61000-61001 --out results/tuning/attack_shot_probe.json
"""

from __future__ import annotations

import argparse
import sys

import numpy as np


class KickLog:
    """Wraps a team controller; records the kicks its robots command with the ball on the dribbler."""

    def __init__(self, inner, kicks: list) -> None:
        self.inner, self.agents, self.kicks = inner, inner.agents, kicks

    def reset(self) -> None:
        self.inner.reset()

    def act(self, env):
        from ssl_marl.plays.pass_decision import open_goal_interval

        a = self.inner.act(env)
        c = self.inner
        w, ctx = c.context.world, c.context
        ts = w.team(ctx.team)
        goal = np.array([c.field.half_length, 0.0])
        for i in range(len(ts.pos)):
            if a[f"{c.team}_{i}"][4] > 0 and ts.ball_on_dribbler[i] and ts.kick_ready[i]:
                p = ts.pos[i]
                err = abs((np.arctan2(goal[1] - p[1], goal[0] - p[0]) - ts.heading[i] + np.pi) % (2 * np.pi) - np.pi)
                others = np.concatenate([ctx.opp_pos, np.delete(ts.pos, i, 0)])
                open_angle, _ = open_goal_interval(w.ball_pos, others, c.field, c.rp, c.bp)
                self.kicks.append(dict(t=float(w.t), role=c.roles.get(i), dist=float(np.hypot(*(goal - p))),
                                       heading_err=float(err), open_angle=float(open_angle)))
        return a


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", default="45200-45203", help="first-last match seed")
    ap.add_argument("--opponent", default="baseline", help="yellow team kind")
    ap.add_argument("--team", default="passing-learned", help="blue team kind (a passing or attacking team)")
    ap.add_argument("--seconds", type=float, default=90.0, help="simulated seconds per match")
    ap.add_argument("--out", required=True, help="output JSON")
    args = ap.parse_args(argv)
    from ssl_marl.io import atomic_write_json
    from ssl_marl.envs.config import EnvConfig
    from ssl_marl.runners.controllers import CHIP_KINDS, make_controller
    from ssl_marl.runners.match import play_match
    from ssl_marl.runners.provenance import build_manifest

    lo, hi = (int(x) for x in args.seeds.split("-"))
    matches = []
    for seed in range(lo, hi + 1):
        kicks: list = []
        chip = args.team in CHIP_KINDS
        cfg = EnvConfig(chip_kicks=chip)
        blue = KickLog(make_controller(args.team, "blue", 6, "div_b", seed=seed, robot=cfg.robot, ball=cfg.ball,
                                       dt=cfg.dt), kicks)
        r = play_match(blue, args.opponent, robots=6, field="div_b", seconds=args.seconds, seed=seed, progress=False,
                       env_kwargs={"chip_kicks": True} if chip else None)
        coord = next((p.prepare.coordinator for p in blue.inner.selector.plays
                      if getattr(p.prepare, "coordinator", None) is not None), None)
        plans = None if coord is None else vars(coord.counters)
        matches.append(dict(seed=seed, score=r.score, goals=r.goals, kicks=kicks, pass_plans=plans))
    att = [k for m in matches for k in m["kicks"] if k["role"] == "attacker"]
    summary = dict(attacker_kicks=len(att), farther_than_4m=sum(k["dist"] > 4.0 for k in att),
                   open_below_0_05rad=sum(k["open_angle"] < 0.05 for k in att),
                   median_dist_m=float(np.median([k["dist"] for k in att])) if att else None,
                   goals=sum(m["score"]["blue"] for m in matches),
                   pass_plans={k: sum(m["pass_plans"][k] for m in matches) for k in ("planned", "kicked", "completed",
                                                                                      "aborted")}
                   if all(m["pass_plans"] for m in matches) else None)
    atomic_write_json(args.out, {"seeds": [lo, hi], "team": args.team, "opponent": args.opponent,
                                 "seconds": args.seconds, "summary": summary, "matches": matches,
                                 "manifest": build_manifest(rules={"team": args.team, "opponent": args.opponent,
                                                                   "seconds": args.seconds},
                                                            seeds={"first": lo, "last": hi})})
    print(summary)
    return 0


if __name__ == "__main__":
    sys.exit(main())
