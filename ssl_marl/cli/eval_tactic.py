"""``ssl-marl eval-tactic``: the paper's go-to-ball-and-shoot tactic evaluation (section 5.2)."""

from __future__ import annotations

import argparse

from .options import FIELDS, SKILL_SOURCE_HELP, add_backend, add_tracker_option, positive_int, skill_source, workers


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``eval-tactic`` subparser."""
    t = subparsers.add_parser("eval-tactic", help="the paper's go-to-ball-and-shoot tactic evaluation (section 5.2)",
                              description="One robot and the ball at random; run go-to-ball-and-shoot until a goal "
                                          "or 15 s. Writes OUT/results.json and OUT/time_hist.png.")
    t.add_argument("--skills", choices=("learned", "baseline"), default="learned",
                   help="skills inside the tactic (default learned)")
    t.add_argument("--tactic", choices=("go-to-ball-and-shoot", "dribble-and-shoot"), default="go-to-ball-and-shoot",
                   help="the tactic: the paper's go-to-ball-and-shoot (default) or dribble-and-shoot (take the ball "
                        "gently, dribble it to a shooting window, aim, shoot)")
    t.add_argument("--realtime", action="store_true",
                   help="hold the tactic to the 1/60 s control deadline: a command computed too slowly is dropped "
                        "(the robot keeps the previous one) and counted as a missed deadline")
    t.add_argument("--skill", type=skill_source, action="append", default=[], metavar="SKILL=SOURCE",
                   help="replace one skill of --skills: " + SKILL_SOURCE_HELP)
    t.add_argument("--episodes", type=positive_int("--episodes"), default=500, help="episodes (default 500)")
    t.add_argument("--seed", type=int, default=20_000, help="evaluation seed (default 20000)")
    t.add_argument("--workers", type=positive_int("--workers"), default=None,
                   help="worker processes (default 1; with --backend ray: tasks in flight, default the cluster's CPUs)")
    t.add_argument("--realism", choices=("none", "realistic", "randomized"), default="none",
                   help="noise / latency preset; randomized: each episode draws its own latency, noise, command "
                        "loss, robot speed / acceleration and ball model (ssl_marl/envs/randomization.py)")
    t.add_argument("--out", default=None,
                   help="output folder for results.json and time_hist.png, created if missing (default: none)")
    t.add_argument("--field", choices=FIELDS, default="div_b", help="field geometry (default div_b)")
    add_backend(t, "the episodes")
    t.add_argument("--quiet", action="store_true", help="no progress bar")
    add_tracker_option(t)
    t.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Evaluate the tactic and print its success rate and time to goal."""
    from ..io import prepare_output_dir
    from ..runners.controllers import team_skills
    from ..runners.tactic_eval import evaluate_tactic

    if args.out:
        prepare_output_dir(args.out, "--out")
    skills = team_skills(args.skills, dict(args.skill), where="--skill") if args.skill else args.skills
    s = evaluate_tactic(skills=skills, episodes=args.episodes, seed=args.seed, workers=workers(args),
                        realism=args.realism, out=args.out, field=args.field, progress=not args.quiet,
                        backend=args.backend, address=args.address, tracker=args.tracker,
                        tactic=args.tactic, realtime=args.realtime)
    t = s["time_s"]
    lo, hi = s["success_ci95"]
    mean = "n/a" if t["mean"] is None else f"{t['mean']:.2f} +/- {t['std']:.2f} s"
    missed = f", missed deadlines {s['missed_deadlines']}" if args.realtime else ""
    print(f"{args.tactic} ({args.skills} skills): success {s['success_rate']:.3f} [95% CI {lo:.3f}-{hi:.3f}] "
          f"over {s['episodes']} episodes, time to goal {mean}, failures {s['failures']} "
          f"(paper: 0.755, 7.49 +/- 3.87 s){missed}" + (f" -> {args.out}/results.json" if args.out else ""))
    return 0
