"""Multi-core scaling of the sharded batched env: 1 vs 2 worker processes.

    python benchmarks/bench_scaling.py [--worlds 64] [--seconds 3] [--rounds 3] [--out results/bench_scaling.json]

Per configuration (1v0 Div B, 6v6 Div B, 11v11 Div A), alternating round by round:
``in_process`` (one :class:`BatchedSSLEnv` with ``--worlds`` worlds in this process),
``sharded_1`` (:class:`ShardedBatchedEnv`, 1 worker x ``--worlds``) and ``sharded_2``
(2 workers x ``--worlds`` each: twice the worlds, as a user with twice the cores
would run). Reports world-steps/s (median over rounds), the speed-up
sharded_2 / sharded_1, the load average and the busiest other processes before and
after (the machine may be shared), and world-steps per CPU second of the stepping
processes (workers' ``process_time``): its ratio 2 / 1 says how linear the scaling
would be with a free core per worker, whatever else runs. Random actions,
``randomize_reset``.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import subprocess
import sys
import time
from datetime import datetime, timezone
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from ssl_marl.envs.batched_env import BatchedSSLEnv  # noqa: E402
from ssl_marl.envs.sharded import ShardedBatchedEnv  # noqa: E402
from ssl_marl.io import atomic_write_json  # noqa: E402

CONFIGS = {"1v0_div_b": dict(n_blue=1, n_yellow=0, field="div_b"),
           "6v6_div_b": dict(n_blue=6, n_yellow=6, field="div_b"),
           "11v11_div_a": dict(n_blue=11, n_yellow=11, field="div_a")}


def busiest_processes(k: int = 6) -> list[str]:
    """The k processes using the most CPU right now (ps), to say what else ran."""
    try:
        out = subprocess.run(["ps", "-eo", "pcpu,etime,args", "--sort=-pcpu"], capture_output=True, text=True,
                             timeout=10).stdout.splitlines()
        return [" ".join(line.split())[:160] for line in out[1:k + 1]]
    except (OSError, subprocess.SubprocessError):
        return []


def _cpu(env) -> float:
    """CPU seconds used so far by the processes that step ``env``'s worlds."""
    return float(env.worker_cpu_seconds().sum()) if hasattr(env, "worker_cpu_seconds") else time.process_time()


def _rate(env, acts: np.ndarray, seconds: float) -> tuple[float, float, float]:
    """(world-steps per wall second, world-steps per CPU second of the stepping processes,
    CPU microseconds of this driving process per world-step: for a sharded env the
    driver's own share - writing actions, signalling, waiting, reading results)."""
    calls, t0, c0, d0 = 0, time.perf_counter(), _cpu(env), time.process_time()
    while True:
        for _ in range(5):
            env.step(acts[calls % len(acts)])
            calls += 1
        el = time.perf_counter() - t0
        if el >= seconds:
            n = calls * env.K
            return n / el, n / max(_cpu(env) - c0, 1e-9), 1e6 * (time.process_time() - d0) / n


def measure(config: dict, worlds: int, seconds: float, rounds: int) -> dict:
    n = config["n_blue"] + config["n_yellow"]
    envs = {"in_process": BatchedSSLEnv(worlds, **config, randomize_reset=True, max_time_s=1e9),
            "sharded_1": ShardedBatchedEnv(1, worlds, **config, randomize_reset=True, max_time_s=1e9),
            "sharded_2": ShardedBatchedEnv(2, worlds, **config, randomize_reset=True, max_time_s=1e9)}
    rng = np.random.default_rng(0)
    acts = {k: rng.uniform(-1, 1, (16, e.K, n, 5)) for k, e in envs.items()}
    for e in envs.values():
        e.reset(seed=0)
    rates: dict[str, list[float]] = {k: [] for k in envs}
    cpu_rates: dict[str, list[float]] = {k: [] for k in envs}
    driver_us: dict[str, list[float]] = {k: [] for k in envs}
    try:
        for r in range(rounds + 1):
            for k, e in envs.items():
                x, c, d = _rate(e, acts[k], seconds if r else 0.3)
                if r:
                    rates[k].append(x)
                    cpu_rates[k].append(c)
                    driver_us[k].append(d)
    finally:
        for k in ("sharded_1", "sharded_2"):
            envs[k].close()
    out = {k: {"world_steps_per_s": round(statistics.median(v)), "rounds": [round(x) for x in v],
               "world_steps_per_cpu_s": round(statistics.median(cpu_rates[k])),
               "driver_cpu_us_per_world_step": round(statistics.median(driver_us[k]), 2)} for k, v in rates.items()}
    out["speedup_2_over_1"] = round(statistics.median(rates["sharded_2"]) / statistics.median(rates["sharded_1"]), 3)
    # per CPU second: 1.0 means a second worker costs no extra CPU per world-step, i.e. with a free
    # core each, 2 workers would run 2x the world-steps of one
    out["cpu_efficiency_2_over_1"] = round(statistics.median(cpu_rates["sharded_2"]) /
                                           statistics.median(cpu_rates["sharded_1"]), 3)
    return out


def main(argv: list[str] | None = None) -> dict:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--worlds", type=int, default=64, help="worlds per process (default 64)")
    p.add_argument("--seconds", type=float, default=3.0, help="timed seconds per variant and round (default 3)")
    p.add_argument("--rounds", type=int, default=3, help="interleaved rounds, median reported (default 3)")
    p.add_argument("--configs", nargs="+", choices=sorted(CONFIGS), default=list(CONFIGS), help="configurations")
    p.add_argument("--out", default="results/bench_scaling.json", help="output JSON")
    args = p.parse_args(argv)
    res: dict = {"date_utc": datetime.now(timezone.utc).isoformat(timespec="seconds"),
                 "machine": f"{platform.machine()}, {os.cpu_count()} cores", "python": platform.python_version(),
                 "load_avg_before": os.getloadavg(), "other_processes_before": busiest_processes(),
                 "worlds_per_process": args.worlds, "configs": {}}
    for name in args.configs:
        res["configs"][name] = measure(CONFIGS[name], args.worlds, args.seconds, args.rounds)
        print(name, json.dumps(res["configs"][name]), flush=True)
    res["load_avg_after"] = os.getloadavg()
    res["other_processes_after"] = busiest_processes()
    atomic_write_json(args.out, res)
    return res


if __name__ == "__main__":
    main()
