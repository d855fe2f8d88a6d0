"""Per-CPU throughput of the keepaway decision env: control ticks, simulated
seconds and decisions per CPU-second (``time.process_time``, so a shared machine's load
does not enter), hand-coded keepers, and the engine alone for comparison.

    python benchmarks/keepaway_speed.py [--episodes 10] [--seed 44990]
"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np

from ssl_marl.decisions import make_decision_env, make_decision_policy
from ssl_marl.decisions.policies import run_episode


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--episodes", type=int, default=10, help="timed episodes (default 10)")
    ap.add_argument("--seed", type=int, default=44990, help="first episode seed (default 44990)")
    ap.add_argument("--policy", default="handcoded", help="decision policy (default handcoded)")
    a = ap.parse_args()
    env = make_decision_env("keepaway")
    pol = make_decision_policy(a.policy, "keepaway")
    run_episode(env, pol, seed=a.seed - 1)  # warm-up
    c0 = time.process_time()
    sim = dec = ticks = 0
    for s in range(a.episodes):
        r = run_episode(env, pol, seed=a.seed + s)
        sim += r["t_s"]
        dec += r["decisions"]
        ticks += env.ticks
    cpu = time.process_time() - c0
    eng = env.engine
    zero = {n: np.zeros(5, np.float32) for n in eng.possible_agents}
    eng.reset(seed=1)
    c0 = time.process_time()
    for _ in range(ticks):
        eng.step(zero)
        if not eng.agents:
            eng.reset(seed=1)
    cpu_engine = time.process_time() - c0
    print(json.dumps({"policy": a.policy, "episodes": a.episodes, "ticks": ticks, "sim_s": sim, "decisions": dec,
                      "cpu_s": cpu, "ticks_per_cpu_s": ticks / cpu, "sim_s_per_cpu_s": sim / cpu,
                      "decisions_per_cpu_s": dec / cpu, "engine_only_ticks_per_cpu_s": ticks / cpu_engine,
                      "engine_share": cpu_engine / cpu}, indent=1))


if __name__ == "__main__":
    main()
