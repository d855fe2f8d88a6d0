"""Go-to-ball with a rolling ball: the skill task's scene with the ball already moving.

The go-to-ball task (``ssl_marl/GoToBall-v0``, the paper's) starts with the ball at
rest; in matches the ball is mostly rolling when a robot goes for it. This probe plays
the task's scene with the ball kicked at ``U(speed_lo, speed_hi)`` m/s in a uniformly
random direction (the robot ``U(1, 4)`` m from the ball, random heading) and reports,
per skill kind, the fraction of episodes in which the ball is on the dribbler within
``max_time_s`` and the mean time to it::

    python benchmarks/go_to_ball_rolling_probe.py --episodes 300 --seed 10000 --out results/tuning/go_to_ball_rolling.json

Episode i uses ``ssl_marl.io.episode_seed(seed, i)`` for both kinds (the same scenes).
"""

from __future__ import annotations

import argparse
import math
import sys

import numpy as np

from ssl_marl.io import atomic_write_json, episode_seed
from ssl_marl.runners.provenance import build_manifest
from ssl_marl.skills import get_skill, make_skill
from ssl_marl.skills.robot_env import OneRobotSkillEnv, Start
from ssl_marl.skills.wrappers import GoToBallTask


class RollingGoToBallTask(GoToBallTask):
    """:class:`~ssl_marl.skills.wrappers.GoToBallTask` with the ball rolling at the start."""

    def __init__(self, speed: tuple[float, float], max_time_s: float) -> None:
        super().__init__(max_time_s=max_time_s)
        self.speed = speed

    def sample_start(self, rng: np.random.Generator, options: dict) -> Start:
        f = self.field
        ball = f.random_free_point(rng, margin=1.0)
        ang = rng.uniform(-math.pi, math.pi)
        robot = ball + rng.uniform(1.0, 4.0) * np.array([math.cos(ang), math.sin(ang)])
        robot = np.clip(robot, [-f.half_length + 0.2, -f.half_width + 0.2], [f.half_length - 0.2, f.half_width - 0.2])
        d = rng.uniform(-math.pi, math.pi)
        vel = rng.uniform(*self.speed) * np.array([math.cos(d), math.sin(d)])
        return Start(np.array([robot[0], robot[1], rng.uniform(-math.pi, math.pi)]), ball, vel)


def run(kind: str, episodes: int, seed: int, speed: tuple[float, float], max_time_s: float) -> dict:
    env = OneRobotSkillEnv(RollingGoToBallTask(speed, max_time_s))
    task = get_skill("go_to_ball").task
    wins, times = 0, []
    for i in range(episodes):
        env.reset(seed=episode_seed(seed, i))
        skill = make_skill("go_to_ball", kind, env.field, env.robot_params, env.ball_params)
        while True:
            _, _, terminated, truncated, info = env.step(task.skill_action(env, skill))
            if terminated or truncated:
                break
        if info["is_success"]:
            wins += 1
            times.append(info["time_s"])
    env.close()
    return {"kind": kind, "episodes": episodes, "success": wins, "success_rate": wins / episodes,
            "mean_time_s": float(np.mean(times)) if times else None}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--episodes", type=int, default=300, help="episodes per skill kind")
    ap.add_argument("--seed", type=int, default=10000, help="evaluation seed")
    ap.add_argument("--speed", type=float, nargs=2, default=(1.0, 3.0), metavar=("LO", "HI"),
                    help="the ball's start speed range (m/s)")
    ap.add_argument("--max-time", type=float, default=5.0, help="episode limit (s)")
    ap.add_argument("--out", required=True, help="result JSON")
    a = ap.parse_args(argv)
    rows = [run(k, a.episodes, a.seed, tuple(a.speed), a.max_time) for k in ("baseline", "learned")]
    for r in rows:
        print(r, flush=True)
    atomic_write_json(a.out, {"rows": rows, "speed_range": list(a.speed), "max_time_s": a.max_time,
                              "manifest": build_manifest(rules={"probe": "go_to_ball_rolling"},
                                                         seeds={"seed": a.seed, "episodes": a.episodes})})
    return 0


if __name__ == "__main__":
    sys.exit(main())
