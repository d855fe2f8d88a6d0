"""``ssl-marl eval-drill``: passing drills (pass-endurance: two robots pass back and forth)."""

from __future__ import annotations

import argparse

from .options import FIELDS, positive_float, positive_int


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``eval-drill`` subparser."""
    dr = subparsers.add_parser("eval-drill", help="passing drills (pass-endurance: two robots pass back and forth)",
                               description="Run a drill with the pass and receive skills; writes OUT/results.json "
                                           "(passes attempted and completed, losses by reason).")
    dr.add_argument("drill", choices=("pass-endurance",), help="which drill")
    dr.add_argument("--policy", choices=("baseline", "learned"), default="baseline",
                    help="hand-coded or shipped learned pass and receive skills (default baseline)")
    dr.add_argument("--receive-policy", choices=("baseline", "learned"), default=None,
                    help="receive skill, if different from --policy (default: as --policy)")
    dr.add_argument("--runs", type=positive_int("--runs"), default=10, help="drill runs (default 10)")
    dr.add_argument("--duration", type=positive_float("--duration"), default=60.0,
                    help="simulated seconds per run (default 60)")
    dr.add_argument("--seed", type=int, default=10_000, help="seed (default 10000)")
    dr.add_argument("--out", default=None, help="output folder for results.json, created if missing (default: none)")
    dr.add_argument("--realism", choices=("none", "realistic"), default="none",
                    help="vision noise / latency preset (default none)")
    dr.add_argument("--field", choices=FIELDS, default="div_b", help="field geometry (default div_b)")
    dr.add_argument("--quiet", action="store_true", help="no progress bar")
    dr.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Run the drill and print its pass completion."""
    from ..io import prepare_output_dir
    from ..runners.drills import evaluate_drill

    if args.out:
        prepare_output_dir(args.out, "--out")
    s = evaluate_drill(args.drill, args.policy, runs=args.runs, seed=args.seed, duration_s=args.duration,
                       realism=args.realism, field=args.field, out=args.out, progress=not args.quiet,
                       receive_policy=args.receive_policy)
    lo, hi = s["completion_ci95"]
    rate = "n/a" if s["completion_rate"] is None else f"{s['completion_rate']:.3f} [95% CI {lo:.3f}-{hi:.3f}]"
    print(f"{args.drill} (pass {args.policy}, receive {s['receive_policy']}): {s['completed']} of {s['attempts']} passes completed ({rate}) in "
          f"{s['runs']} runs of {args.duration:g} s, {s['passes_per_minute']:.1f} per minute, losses {s['losses']}"
          + (f" -> {args.out}/results.json" if args.out else ""))
    return 0
