"""Env throughput of two checkouts side by side (e.g. before and after a refactor).

    python benchmarks/bench_two_checkouts.py OLD_ROOT NEW_ROOT [--steps 3000] [--rounds 3]

Runs ``ssl_marl.cli.bench.bench_env`` (random actions, 60 Hz) for 1v0 Division B and 6v6
Division B, and the go-to-ball task env (baseline skill acting) in a fresh process per
measurement, alternating OLD and NEW for ``rounds`` rounds so both see the same machine
load; prints JSON with the median steps/s of each and the ratio NEW / OLD.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys

PROBE = r"""
import json, sys, time
try:
    from ssl_marl.cli.bench import CONFIGS, bench_env
except ImportError:  # a checkout whose benchmark module is ssl_marl.bench
    from ssl_marl.bench import CONFIGS, bench_env
steps = int(sys.argv[1])
out = {name: bench_env(CONFIGS[name], steps, 5)["steps_per_s"] for name in ("1v0_div_b", "6v6_div_b")}
from ssl_marl.skills import make_skill
from ssl_marl.skills.wrappers import GoToBallEnv, task_action
env = GoToBallEnv()
skill = make_skill("go_to_ball", "baseline", env.field)
env.reset(seed=0); skill.reset(); n = 0
t0 = time.perf_counter()
while n < steps:
    _, _, term, trunc, _ = env.step(task_action("go-to-ball", skill.act(env.seen(), 0)))
    n += 1
    if term or trunc:
        env.reset(seed=n); skill.reset()
out["go_to_ball_task"] = round(steps / (time.perf_counter() - t0))
print(json.dumps(out))
"""


def measure(root: str, steps: int) -> dict:
    res = subprocess.run([sys.executable, "-c", PROBE, str(steps)], env={"PYTHONPATH": root, "SDL_VIDEODRIVER": "dummy",
                                                                           "OMP_NUM_THREADS": "1"},
                         capture_output=True, text=True, check=True)
    return json.loads(res.stdout.strip().splitlines()[-1])


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("old_root", help="source root of the old checkout (PYTHONPATH)")
    p.add_argument("new_root", help="source root of the new checkout (PYTHONPATH)")
    p.add_argument("--steps", type=int, default=3000, help="env steps per measurement (default 3000)")
    p.add_argument("--rounds", type=int, default=3, help="alternating rounds (default 3)")
    a = p.parse_args()
    runs: dict[str, list[dict]] = {"old": [], "new": []}
    for _ in range(a.rounds):
        runs["old"].append(measure(a.old_root, a.steps))
        runs["new"].append(measure(a.new_root, a.steps))
    keys = runs["old"][0].keys()
    med = {w: {k: statistics.median(r[k] for r in runs[w]) for k in keys} for w in runs}
    print(json.dumps({"steps": a.steps, "rounds": a.rounds, "median_steps_per_s": med,
                      "ratio_new_over_old": {k: round(med["new"][k] / med["old"][k], 3) for k in keys}}, indent=1))


if __name__ == "__main__":
    main()
