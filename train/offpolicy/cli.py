"""The skill command line: ``python -m train SKILL --seed 0 --out runs/NAME [--algo td3] [--config X.json]
[--resume] [--samples N] [--set k=v ...]`` (the same as ``ssl-marl train SKILL ...``).

SKILL (go-to-ball, aim-to-shoot, pass, receive, pendulum, ...) picks the default config in
``train/configs/``; ``--config`` replaces it, ``--set`` overrides single keys, values parsed
as JSON; ``SECTION.KEY`` sets a key of the ``ddpg``, ``td3`` or ``exploration`` section
(``--set ddpg.actor_hidden=[64,64] --set exploration.kind=gaussian --set demo_fn=null``;
layout: :mod:`train.offpolicy.config`). ``--algo`` picks the learning algorithm (same as
``--set algo=NAME``; default: the config's, ``ddpg``). With ``--resume`` the config stored in
OUT's checkpoint is used (``--samples`` and ``--set`` still apply on top, e.g. to extend a
finished run).
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from train.offpolicy.config import ALGO_NAMES, SKILL_CONFIGS, apply_overrides, default_config, load_config


def build_parser(prog: str = "python -m train") -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog=prog, description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("skill", choices=sorted(SKILL_CONFIGS), help="which default config to start from")
    p.add_argument("--config", type=Path, default=None, help="JSON config (default: train/configs/<skill>.json)")
    p.add_argument("--algo", choices=sorted(ALGO_NAMES), default=None,
                   help="learning algorithm (default: the config's 'algo', ddpg); same as --set algo=NAME")
    p.add_argument("--seed", type=int, default=0, help="training seed (evaluation during training uses seed + 1000)")
    p.add_argument("--out", type=Path, required=True, help="run folder (logs, checkpoints, actor.pt)")
    p.add_argument("--resume", action="store_true", help="continue from OUT/checkpoint.pt")
    p.add_argument("--samples", type=int, default=None, help="override total_samples (env samples)")
    p.add_argument("--set", dest="overrides", action="append", default=[], metavar="KEY=VALUE",
                   help="override one config key (repeatable); SECTION.KEY=V for a key of ddpg, td3 or exploration")
    p.add_argument("--no-progress", action="store_true", help="no progress bar (e.g. in CI logs)")
    return p


def main(argv: list[str] | None = None, prog: str = "python -m train") -> int:
    """Train a skill per the command line ``argv`` (``prog`` names the command in messages)."""
    args = build_parser(prog).parse_args(argv)
    from train.offpolicy.loop import load_run_config, train  # heavy imports after argument errors

    if args.resume:
        cfg, saved_seed = load_run_config(args.out)
        if saved_seed != args.seed:
            print(f"note: resuming with the checkpoint's seed {saved_seed} (not --seed {args.seed})")
        seed = saved_seed
    else:
        cfg = load_config(args.config) if args.config else default_config(args.skill)
        seed = args.seed
    overrides = list(args.overrides) + ([f"total_samples={args.samples}"] if args.samples is not None else []) \
        + ([f"algo={args.algo}"] if args.algo is not None else [])
    cfg = apply_overrides(cfg, overrides)
    result = train(cfg, seed, args.out, resume=args.resume, progress=not args.no_progress)
    summary = {k: result[k] for k in ("mean_return", "std_return", "mean_length", "success_rate", "wall_time_s")}
    print(json.dumps({"out": str(args.out), **summary}))
    return 0


