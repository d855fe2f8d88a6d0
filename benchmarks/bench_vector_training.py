"""Skill training through the batched vector env vs today's trainer set-up; prints JSON.

    python benchmarks/bench_vector_training.py [--steps 2000] [--collect-steps 20000] [--rounds 1]
                                               [--out results/bench_vector_training.json]

Runs :class:`train.offpolicy.loop.Trainer` on ``ssl_marl/GoToBall-v0`` (the shipped go-to-ball
config without demos, evaluations or checkpoints; see ``bench_training.py``, whose
timed trainer this reuses) in these set-ups, one after the other in each round:

* ``today``: one env through Gymnasium's ``SyncVectorEnv`` (the shipped config);
* ``sync_N`` / ``batched_N``: N envs through ``SyncVectorEnv`` or through
  :class:`ssl_marl.skills.vector.SkillVectorEnv` (``vector_mode="batched"``).

Each with the paper's one gradient update per sample (``--steps`` timed samples) and
collection only (``updates_per_sample`` 0 after the warm-up: actor inference with
noise, env steps, replay inserts; ``--collect-steps`` timed samples). Reported:
samples/s and updates/s in the timed window (median over rounds).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import sys
import tempfile
from dataclasses import replace
from datetime import datetime, timezone
from pathlib import Path

import torch

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))
sys.path.insert(0, str(HERE))

from bench_training import TimedTrainer, bench_config  # noqa: E402

from ssl_marl.io import atomic_write_json  # noqa: E402

SETUPS = {"today": (1, "sync"), "sync_16": (16, "sync"), "batched_1": (1, "batched"), "batched_16": (16, "batched"),
          "batched_64": (64, "batched")}


def run(num_envs: int, mode: str, steps: int, warmup: int, updates_per_sample: float, seed: int) -> dict:
    cfg = replace(bench_config(steps, warmup, 1), num_envs=num_envs, vector_mode=mode,
                  updates_per_sample=updates_per_sample, max_episode_steps=None)
    with tempfile.TemporaryDirectory(prefix="bench_vec_") as out:
        tr = TimedTrainer(cfg, seed, out, progress=False)
        tr.run()
    secs = tr.t1 - tr.t0
    return {"samples_per_s": round((tr.s1 - tr.s0) / secs, 1), "updates_per_s": round((tr.u1 - tr.u0) / secs, 1),
            "seconds": round(secs, 2)}


def main(argv: list[str] | None = None) -> dict:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--steps", type=int, default=2000, help="timed samples with 1 update per sample (default 2000)")
    p.add_argument("--collect-steps", type=int, default=20000, help="timed samples, collection only (default 20000)")
    p.add_argument("--warmup", type=int, default=1024, help="untimed warm-up samples (default 1024)")
    p.add_argument("--rounds", type=int, default=1, help="rounds; median reported (default 1)")
    p.add_argument("--setups", nargs="+", choices=list(SETUPS), default=list(SETUPS), help="set-ups to run")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--out", default="results/bench_vector_training.json", help="output JSON")
    args = p.parse_args(argv)
    torch.set_num_threads(1)
    res: dict = {"date_utc": datetime.now(timezone.utc).isoformat(timespec="seconds"),
                 "machine": f"{platform.machine()}, {os.cpu_count()} cores", "python": platform.python_version(),
                 "torch": torch.__version__, "threads": 1, "load_avg_before": os.getloadavg(), "results": {}}
    for mode_name, ups, steps in (("train_1_update_per_sample", 1.0, args.steps), ("collect_only", 0.0,
                                                                                   args.collect_steps)):
        rows: dict[str, list[dict]] = {k: [] for k in args.setups}
        for r in range(args.rounds):
            for name in args.setups:
                n, mode = SETUPS[name]
                rows[name].append(run(n, mode, steps, args.warmup, ups, args.seed + r))
                print(mode_name, name, rows[name][-1], flush=True)
        res["results"][mode_name] = {k: {"samples_per_s": statistics.median(x["samples_per_s"] for x in v),
                                         "updates_per_s": statistics.median(x["updates_per_s"] for x in v),
                                         "rounds": v} for k, v in rows.items()}
    res["load_avg_after"] = os.getloadavg()
    atomic_write_json(args.out, res)
    print(json.dumps(res["results"], indent=1))
    return res


if __name__ == "__main__":
    main()
