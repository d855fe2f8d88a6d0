"""Cost of the referee's no-progress call in the batched env: ``BatchedSSLEnv`` 6v6 Division B
with the call on (``no_progress_s=10``, the default) and off (None), random actions,
interleaved rounds in one process; prints the time per world-step of each and the ratio.

    python benchmarks/bench_no_progress.py [--worlds 256] [--steps 300] [--rounds 5]
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time

import numpy as np


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--worlds", type=int, default=256)
    ap.add_argument("--steps", type=int, default=300)
    ap.add_argument("--rounds", type=int, default=5)
    args = ap.parse_args(argv)
    from ssl_marl.envs.batched_env import BatchedSSLEnv

    envs = {name: BatchedSSLEnv(args.worlds, n_blue=6, n_yellow=6, randomize_reset=True, no_progress_s=v)
            for name, v in (("on", 10.0), ("off", None))}
    rng = np.random.default_rng(0)
    acts = rng.uniform(-1, 1, (args.steps, args.worlds, 12, 5))
    times: dict[str, list[float]] = {k: [] for k in envs}
    for _ in range(args.rounds):
        for name, env in envs.items():
            env.reset(seed=0)
            t0 = time.perf_counter()
            for a in acts:
                env.step(a)
            times[name].append((time.perf_counter() - t0) / (args.steps * args.worlds))
    med = {k: statistics.median(v) for k, v in times.items()}
    for k, v in med.items():
        print(f"no-progress call {k}: {1e6 * v:.1f} us per world-step (median of {args.rounds} rounds)")
    print(f"on / off: {med['on'] / med['off']:.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
