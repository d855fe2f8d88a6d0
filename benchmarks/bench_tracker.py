"""Cost of the vision tracker per control step, side by side with raw vision; prints JSON.

    python benchmarks/bench_tracker.py [--steps 3000] [--rounds 3]

Runs the same env (realistic preset) and the same actions twice per round: once reading
``env.vision_state(team)`` (raw), once through :class:`ssl_marl.envs.tracking.TrackedVisionEnv`
(every frame filtered and the state predicted 4 steps ahead for each team that has robots).
Configurations: 1 v 0 (the skill and tactic evaluations) and 6 v 6 (both teams tracked).
Reports the median round's microseconds per step and the ratio tracked / raw (the machine may
be shared: see ``load_avg``).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from ssl_marl.envs import parallel_env
from ssl_marl.envs.tracking import TrackedVisionEnv


def run(n: int, steps: int, tracked: bool) -> float:
    env = parallel_env(n_blue=n, n_yellow=n if n > 1 else 0, realism="realistic", max_time_s=1e9)
    if tracked:
        env = TrackedVisionEnv(env)
    env.reset(seed=0)
    rng = np.random.default_rng(0)
    acts = rng.uniform(-0.5, 0.5, (steps, len(env.possible_agents), 5)).astype(np.float32)
    teams = [t for t in ("blue", "yellow") if any(a.startswith(t) for a in env.possible_agents)]
    t0 = time.perf_counter()
    for k in range(steps):
        for team in teams:
            env.vision_state(team)
        env.step(dict(zip(env.possible_agents, acts[k])))
    return 1e6 * (time.perf_counter() - t0) / steps


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--steps", type=int, default=3000, help="steps per measurement (default 3000)")
    p.add_argument("--rounds", type=int, default=3, help="interleaved rounds; the median is reported (default 3)")
    args = p.parse_args()
    out = {"machine": {"platform": platform.platform(), "cpus": os.cpu_count(), "load_avg": list(os.getloadavg())},
           "steps": args.steps, "rounds": args.rounds, "configs": {}}
    for n, name in ((1, "1v0"), (6, "6v6")):
        raw, trk = [], []
        for _ in range(args.rounds):
            raw.append(run(n, args.steps, False))
            trk.append(run(n, args.steps, True))
        r, t = statistics.median(raw), statistics.median(trk)
        out["configs"][name] = {"raw_us_per_step": r, "tracked_us_per_step": t, "ratio": t / r,
                                "tracker_us_per_step": t - r}
    out["load_avg_end"] = list(os.getloadavg())
    print(json.dumps(out, indent=2))


if __name__ == "__main__":
    main()
