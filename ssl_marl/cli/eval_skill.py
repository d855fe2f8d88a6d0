"""``ssl-marl eval-skill``: the paper's skill evaluation protocol (section 5.1)."""

from __future__ import annotations

import argparse

from ..skills.registry import cli_choices
from .options import FIELDS, add_backend, add_tracker_option, positive_int, workers


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``eval-skill`` subparser."""
    e = subparsers.add_parser("eval-skill", help="the paper's skill evaluation protocol (section 5.1)",
                              description="Run a skill from random spawns for N episodes; writes OUT/results.json "
                                          "(success rate with 95% CI, times, failure reasons) and "
                                          "OUT/time_hist.png.")
    e.add_argument("skill", choices=cli_choices(), help="which skill (every registered skill with a task)")
    e.add_argument("--policy", default="baseline",
                   help="'baseline' (hand-coded), 'learned' (shipped actor) or a path to an actor checkpoint")
    e.add_argument("--episodes", type=positive_int("--episodes"), default=1000, help="episodes (default 1000)")
    e.add_argument("--seed", type=int, default=10_000, help="evaluation seed (default 10000; training uses < 1000)")
    e.add_argument("--workers", type=positive_int("--workers"), default=None,
                   help="worker processes (default 1; with --backend ray: tasks in flight, default the cluster's CPUs)")
    e.add_argument("--out", default=None,
                   help="output folder for results.json and time_hist.png, created if missing (default: none)")
    e.add_argument("--realism", choices=("none", "realistic", "randomized"), default="none",
                   help="vision noise / latency preset (default none); randomized: each episode draws its own "
                        "latency, noise, command loss, robot speed / acceleration and ball model "
                        "(ssl_marl/envs/randomization.py)")
    e.add_argument("--realtime", action="store_true", help="run in real-time mode (slow: 60 steps per second)")
    e.add_argument("--field", choices=FIELDS, default="div_b", help="field geometry (default div_b)")
    add_backend(e, "the episodes")
    e.add_argument("--quiet", action="store_true", help="no progress bar")
    add_tracker_option(e)
    e.add_argument("--task-option", action="append", default=[], metavar="KEY=VALUE", type=task_option,
                   help="a keyword of the task's env, VALUE parsed as JSON (repeatable), e.g. "
                        "'receive --task-option interceptors=1 --task-option hold_s=0.1' (the pass pressed by an "
                        "interceptor, held 0.1 s as the passing plays count it)")
    e.set_defaults(handler=run)


def task_option(text: str) -> tuple[str, object]:
    """``KEY=VALUE`` -> (key, JSON value, or the text itself if it is not JSON)."""
    import json

    key, sep, value = text.partition("=")
    if not sep or not key.isidentifier():
        raise argparse.ArgumentTypeError(f"--task-option wants KEY=VALUE with KEY a name, got {text!r}")
    try:
        return key, json.loads(value)
    except ValueError:
        return key, value


def run(args: argparse.Namespace) -> int:
    """Evaluate one skill and print its success rate and times."""
    from ..io import prepare_output_dir
    from ..runners.skill_eval import evaluate_skill

    if args.out:
        prepare_output_dir(args.out, "--out")
    s = evaluate_skill(args.skill, args.policy, episodes=args.episodes, seed=args.seed, workers=workers(args),
                       out=args.out, realism=args.realism, field=args.field, progress=not args.quiet,
                       realtime=args.realtime, backend=args.backend, address=args.address, tracker=args.tracker,
                       task_options=dict(args.task_option))
    t = s["time_to_success_s"]
    lo, hi = s["success_ci95"]
    mean = "n/a" if t["mean"] is None else f"{t['mean']:.2f} +/- {t['std']:.2f} s"
    print(f"{args.skill} ({args.policy}): success {s['success_rate']:.3f} [95% CI {lo:.3f}-{hi:.3f}] over "
          f"{s['episodes']} episodes, time to success {mean}, failures {s['failure_reasons']}"
          + (f" -> {args.out}/results.json" if args.out else ""))
    return 0
