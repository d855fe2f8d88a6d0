"""Multi-seed training sweeps: ``python -m train.sweep SKILL --seeds 0 1 2 --out runs/NAME``.

Runs ``python -m train`` once per seed (same config, overrides and sample budget),
each into ``OUT/seed_<S>/``, spread over the runners' one worker pool
(:func:`ssl_marl.runners.pool.run_pool`): local processes (``--workers``, default 1)
or a Ray cluster (``--backend ray [--address HOST:6379]``, one CPU per training run).
A seed whose folder already holds a checkpoint is resumed (so an interrupted sweep
is re-run with the same command), a finished one only re-evaluated. Each run is
seeded by its own seed only, so where it ran does not change it; on a cluster
``OUT`` must be a shared filesystem path (or use the same path on every node and
collect the folders afterwards).

Writes ``OUT/sweep.json``: per seed the run folder and its final evaluation
(mean return, success rate, wall time), plus the mean and std across seeds.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path
from typing import Any

from train.offpolicy.config import SKILL_CONFIGS, apply_overrides, default_config, load_config


def run_seed(job: tuple[dict, int, str]) -> dict[str, Any]:
    """Train (or resume) one seed; returns its summary. ``job`` = (config dict, seed, run folder)."""
    from train.offpolicy.config import config_from_dict
    from train.offpolicy.loop import CHECKPOINT, train

    cfg_dict, seed, out = job
    resume = (Path(out) / CHECKPOINT).exists()
    result = train(config_from_dict(cfg_dict), seed, out, resume=resume, progress=False)
    keep = ("mean_return", "std_return", "mean_length", "success_rate", "wall_time_s")
    return {"seed": seed, "out": str(out), "resumed": resume, **{k: result.get(k) for k in keep}}


def sweep(cfg: Any, seeds: list[int], out: str | Path, workers: int | None = 1, backend: str = "local",
          address: str | None = None, progress: bool = True) -> dict[str, Any]:
    """Train ``cfg`` for every seed in ``seeds`` (see the module docstring); returns
    the sweep summary (also written to ``OUT/sweep.json``)."""
    import numpy as np

    from ssl_marl.io import atomic_write_json
    from ssl_marl.runners.pool import run_pool

    if not seeds or len(set(seeds)) != len(seeds):
        raise ValueError(f"seeds must be a non-empty list of distinct integers, got {seeds!r}")
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    jobs = [(cfg.to_dict(), int(s), str(out / f"seed_{s}")) for s in seeds]
    runs = run_pool(run_seed, jobs, workers, f"sweep {cfg.skill}", progress, unit="run", backend=backend,
                    address=address)
    summary: dict[str, Any] = {"skill": cfg.skill, "seeds": list(seeds), "config": cfg.to_dict(), "runs": runs}
    for key in ("mean_return", "success_rate"):
        vals = [r[key] for r in runs if r.get(key) is not None]
        if vals:
            summary[f"{key}_mean"] = float(np.mean(vals))
            summary[f"{key}_std"] = float(np.std(vals))
    atomic_write_json(out / "sweep.json", summary)
    return summary


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="python -m train.sweep", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("skill", choices=sorted(SKILL_CONFIGS), help="which default config to start from")
    p.add_argument("--seeds", type=int, nargs="+", required=True, help="training seeds (0-9 by the project's rule)")
    p.add_argument("--out", type=Path, required=True, help="sweep folder; seed S trains into OUT/seed_S")
    p.add_argument("--config", type=Path, default=None, help="JSON config (default: train/configs/<skill>.json)")
    p.add_argument("--samples", type=int, default=None, help="override total_samples (env samples)")
    p.add_argument("--set", dest="overrides", action="append", default=[], metavar="KEY=VALUE",
                   help="override one config key (repeatable)")
    p.add_argument("--workers", type=int, default=None,
                   help="training runs at once (default 1; with --backend ray: the cluster's CPUs)")
    p.add_argument("--backend", choices=("local", "ray"), default="local",
                   help="local process pool (default) or a Ray cluster")
    p.add_argument("--address", default=None, metavar="ADDR",
                   help="Ray cluster address (HOST:6379 or auto; default: a local Ray instance)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    return p


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    cfg = load_config(args.config) if args.config else default_config(args.skill)
    overrides = list(args.overrides) + ([f"total_samples={args.samples}"] if args.samples is not None else [])
    cfg = apply_overrides(cfg, overrides)
    workers = args.workers if args.workers is not None else (None if args.backend == "ray" else 1)
    try:
        s = sweep(cfg, args.seeds, args.out, workers=workers, backend=args.backend, address=args.address,
                  progress=not args.quiet)
    except (ValueError, FileNotFoundError) as exc:
        print(f"train.tools.sweep: error: {exc}", file=sys.stderr)
        return 2
    print(json.dumps({k: v for k, v in s.items() if k not in ("config", "runs")} | {"out": str(args.out)}))
    return 0
