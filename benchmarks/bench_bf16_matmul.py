"""Does this CPU run bfloat16 matrix products natively? Prints JSON.

    python benchmarks/bench_bf16_matmul.py [--repeats 200] [--threads 1]

Times the go-to-ball networks' largest product (batch 256: 256x300 @ 300x400) in float32 and
in bfloat16, interleaved, keeping the fastest of ``repeats`` rounds of 20 products each (the
minimum is the figure least disturbed by other jobs on a shared machine), and reports the
CPU's bf16-related flags (``/proc/cpuinfo``), torch's CPU capability and the trainer's
``autocast_bf16`` default (:func:`train.offpolicy.config.cpu_has_fast_bf16`). With AMX or AVX512-BF16
the bf16 product is several times (AMX) or about 2x (AVX512-BF16) faster; without either,
torch emulates bf16 and it is slower than float32.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import sys
import time
from pathlib import Path

import torch

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from train.offpolicy.config import cpu_has_fast_bf16  # noqa: E402


def cpu_flags(names: tuple[str, ...] = ("amx_bf16", "amx_tile", "avx512_bf16", "avx512f", "avx2")) -> dict[str, bool]:
    try:
        line = next(line for line in open("/proc/cpuinfo") if line.startswith("flags"))
        flags = set(line.split(":", 1)[1].split())
    except (OSError, StopIteration):
        flags = set()
    return {n: n in flags for n in names}


def cpu_model() -> str:
    try:
        return next(line.split(":", 1)[1].strip() for line in open("/proc/cpuinfo") if line.startswith("model name"))
    except (OSError, StopIteration):
        return platform.processor() or "unknown"


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--repeats", type=int, default=200, help="rounds of 20 products per dtype")
    p.add_argument("--threads", type=int, default=1, help="torch threads")
    a = p.parse_args(argv)
    torch.set_num_threads(a.threads)
    a32, b32 = torch.randn(256, 300), torch.randn(300, 400)
    pairs = {"float32": (a32, b32), "bfloat16": (a32.bfloat16(), b32.bfloat16())}
    best = dict.fromkeys(pairs, float("inf"))
    for _ in range(a.repeats):
        for k, (x, y) in pairs.items():
            t = time.perf_counter()
            for _ in range(20):
                x @ y
            best[k] = min(best[k], (time.perf_counter() - t) / 20)
    print(json.dumps({"product": "256x300 @ 300x400", "threads": a.threads,
                      "us": {k: round(v * 1e6, 1) for k, v in best.items()},
                      "float32_over_bfloat16": round(best["float32"] / best["bfloat16"], 2),
                      "cpu": cpu_model(), "flags": cpu_flags(),
                      "torch_cpu_capability": torch.backends.cpu.get_cpu_capability(), "torch": torch.__version__,
                      "autocast_bf16_default": cpu_has_fast_bf16(),
                      "load_avg": [round(x, 2) for x in os.getloadavg()]}, indent=2))


if __name__ == "__main__":
    main()
