"""CLI: ``python -m train mappo --task TASK --seed S --out DIR [--resume] [--decisions N] [--set k=v ...]``.

TASK: keepaway, attack-3v2, attack-drill, attack-drill-ssl, attack-drill-defended, attack-match, pass-and-score, toy-signal, toy-tempo (:mod:`train.mappo.tasks`),
each starting from its default run config; ``--set`` overrides one key of
:class:`train.mappo.loop.MAPPORunConfig` (values parsed as JSON; ``algo.NAME=V`` sets a
:class:`train.mappo.algorithm.MAPPOConfig` field, e.g. ``--set algo.lr=3e-4 --set num_envs=16``).
With ``--resume`` the config and seed stored in DIR/checkpoint.pt are used (``--decisions``
still applies, e.g. to extend a finished run). Interrupt any time: ``--resume`` continues from
the last checkpoint exactly as the uninterrupted run would.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import Any

from train.mappo.tasks import MARL_TASKS


def build_parser(prog: str = "python -m train mappo") -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog=prog, description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--task", choices=sorted(MARL_TASKS), required=True, help="multi-agent task to train on")
    p.add_argument("--seed", type=int, default=0, help="training seed (MAPPO runs use 0, 1, 2)")
    p.add_argument("--out", type=Path, required=True, help="run folder (CSV logs, checkpoint.pt, actors/)")
    p.add_argument("--resume", action="store_true", help="continue from OUT/checkpoint.pt")
    p.add_argument("--decisions", "--samples", dest="decisions", type=int, default=None,
                   help="training budget in agent decisions (overrides total_decisions)")
    p.add_argument("--set", dest="overrides", action="append", default=[], metavar="KEY=VALUE",
                   help="override one run-config key (repeatable); algo.NAME=V for a MAPPO hyperparameter")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    return p


def parse_overrides(items: list[str]) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for item in items:
        key, sep, raw = item.partition("=")
        if not sep:
            raise ValueError(f"--set expects KEY=VALUE, got {item!r}")
        try:
            val = json.loads(raw)
        except json.JSONDecodeError:
            val = raw
        if key.startswith("algo."):
            out.setdefault("algo", {})[key[5:]] = val
        else:
            out[key] = val
    return out


def main(argv: list[str] | None = None, prog: str = "python -m train mappo") -> int:
    args = build_parser(prog).parse_args(argv)
    from dataclasses import replace

    from train.mappo.loop import load_mappo_run, task_config, train_mappo

    if args.resume:
        cfg, seed = load_mappo_run(args.out)
        if seed != args.seed:
            print(f"note: resuming with the checkpoint's seed {seed} (not --seed {args.seed})")
        if args.overrides:
            print("note: --set is ignored with --resume (the checkpoint's config is used)")
    else:
        cfg, seed = task_config(args.task, **parse_overrides(args.overrides)), args.seed
    if args.decisions is not None:
        cfg = replace(cfg, total_decisions=int(args.decisions))
    row = train_mappo(cfg, seed, args.out, resume=args.resume, progress=not args.no_progress)
    print(json.dumps({"out": str(args.out), **{k: row.get(k) for k in
                                                ("decisions", "agent_steps", "wall_time", "mean_score")}}))
    return 0
