"""Go-to-ball with a rolling ball: the skill task's rolling-ball scene.

The go-to-ball task (``ssl_marl/GoToBall-v0``) starts with the ball at rest by default
(the paper's); in matches the ball is mostly rolling when a robot goes for it. This
probe plays the task's rolling start in every episode (``rolling=1``: the ball at
``U(speed_lo, speed_hi)`` m/s in a uniformly random direction, the robot ``U(1, 4)`` m
from it with a random heading; :class:`~ssl_marl.skills.wrappers.GoToBallTask`) and
reports, per policy, the fraction of episodes in which the ball is on the dribbler
within ``max_time_s`` and the mean time to it::

    python benchmarks/go_to_ball_rolling_probe.py --episodes 300 --seed 10000 --out results/tuning/go_to_ball_rolling.json
    python benchmarks/go_to_ball_rolling_probe.py --policy baseline learned runs/X/actors/actor-N.pt \\
        --field div_a --realism realistic --out ...

A policy is ``baseline``, ``learned`` (the shipped actor) or an actor checkpoint; a
learned actor reads the state its checkpoint names (go_to_ball/v1 or v2). Episode i
uses ``ssl_marl.io.episode_seed(seed, i)`` for every policy (the same scenes).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np
from tqdm import tqdm

from ssl_marl.io import atomic_write_json, episode_seed
from ssl_marl.runners.provenance import build_manifest
from ssl_marl.skills import get_skill, make_skill
from ssl_marl.skills.wrappers import GoToBallEnv


def run(policy: str, episodes: int, seed: int, speed: tuple[float, float], max_time_s: float, field: str,
        realism: str, progress: bool = True) -> dict:
    """One policy over ``episodes`` rolling-ball episodes; the tracker reads vision under realism."""
    env = GoToBallEnv(max_time_s=max_time_s, rolling=1.0, rolling_speed=speed, field=field, realism=realism,
                      tracker=realism != "none")
    kind, checkpoint = (policy, None) if policy in ("baseline", "learned") else ("learned", policy)
    task = get_skill("go_to_ball").task
    skill = make_skill("go_to_ball", kind, env.field, env.robot_params, env.ball_params, checkpoint=checkpoint)
    wins, times = 0, []
    for i in tqdm(range(episodes), desc=f"rolling go-to-ball ({policy})", unit="ep", disable=not progress):
        env.reset(seed=episode_seed(seed, i))
        skill.reset()
        while True:
            _, _, terminated, truncated, info = env.step(task.skill_action(env, skill))
            if terminated or truncated:
                break
        if info["is_success"]:
            wins += 1
            times.append(info["time_s"])
    env.close()
    return {"policy": policy, "kind": kind, "episodes": episodes, "success": wins, "success_rate": wins / episodes,
            "mean_time_s": float(np.mean(times)) if times else None}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--policy", nargs="+", default=["baseline", "learned"],
                    help="policies: baseline, learned (the shipped actor) or actor checkpoint paths")
    ap.add_argument("--episodes", type=int, default=300, help="episodes per policy")
    ap.add_argument("--seed", type=int, default=10000, help="evaluation seed")
    ap.add_argument("--speed", type=float, nargs=2, default=(1.0, 3.0), metavar=("LO", "HI"),
                    help="the ball's start speed range (m/s)")
    ap.add_argument("--max-time", type=float, default=5.0, help="episode limit (s)")
    ap.add_argument("--field", choices=("div_a", "div_b"), default="div_b", help="field geometry")
    ap.add_argument("--realism", choices=("none", "realistic", "randomized"), default="none",
                    help="realism preset (the tracker reads vision when not none)")
    ap.add_argument("--quiet", action="store_true", help="no progress bars")
    ap.add_argument("--out", required=True, help="result JSON")
    a = ap.parse_args(argv)
    for p in a.policy:
        if p not in ("baseline", "learned") and not Path(p).is_file():
            ap.error(f"--policy {p!r}: not baseline, learned or an existing checkpoint")
    rows = [run(p, a.episodes, a.seed, tuple(a.speed), a.max_time, a.field, a.realism, not a.quiet)
            for p in a.policy]
    for r in rows:
        print(r, flush=True)
    actors = [p for p in a.policy if p not in ("baseline", "learned")]
    atomic_write_json(a.out, {"rows": rows, "speed_range": list(a.speed), "max_time_s": a.max_time,
                              "field": a.field, "realism": a.realism,
                              "manifest": build_manifest(rules={"probe": "go_to_ball_rolling", "field": a.field,
                                                                "realism": a.realism},
                                                         seeds={"seed": a.seed, "episodes": a.episodes},
                                                         actor_files=actors)})
    return 0


if __name__ == "__main__":
    sys.exit(main())
