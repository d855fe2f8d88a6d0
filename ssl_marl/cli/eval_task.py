"""``ssl-marl eval-task``: a decision policy on keepaway, attack-3v2 or an attack drill."""

from __future__ import annotations

import argparse

from .options import FIELDS, add_backend, add_tracker_option, positive_int, workers


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``eval-task`` subparser."""
    from ..runners.task_eval import DEFAULT_SEEDS, TASK_SCORES

    k = subparsers.add_parser("eval-task", help="evaluate a decision policy on keepaway, attack-3v2 or an attack drill",
                              description="Episodes of a decision-level multi-agent task (ssl_marl/decisions) with "
                                          "one policy for all learning agents; episode i uses seed SEED+i, so "
                                          "results do not depend on --workers. Writes OUT/results.json (keepaway: "
                                          "mean_duration_s, attack-3v2 / attack drills: goal_rate, with 95% intervals, outcomes, "
                                          "every episode) and OUT/duration_hist.png.")
    k.add_argument("task", choices=tuple(TASK_SCORES),
                   help="the decision task (attack-drill: the attacking plays' options; attack-drill-ssl: the "
                        "same under SSL rules, the attackers' fouls ending the attack; attack-drill-defended: "
                        "under SSL rules against the match's defence, a goalie, two defenders, a presser and two marks; "
                        "attack-drill-mix: one of the last two drawn per episode, half of each)")
    k.add_argument("--policy", choices=("learned", "handcoded", "random", "always-hold", "improved"),
                   default="handcoded",
                   help="decision policy: learned (ssl_marl.decisions.learned, the shipped actor or --actor), "
                        "handcoded (the task's benchmark), random (uniform over legal options), always-hold "
                        "(keepaway only), improved (handcoded, except at an episode's first K decisions, where a "
                        "value actor's best option is played if its logit, the predicted log-odds of a goal, exceeds "
                        "the benchmark option's by more than M; K and M "
                        "as the value actor file records them, else 1 and 0.1) "
                        "(default handcoded)")
    k.add_argument("--actor", default=None, metavar="PATH",
                   help="decision actor file (.pt, loaded with weights_only=True); with --policy learned the "
                        "policy's actor (default: ssl_marl/decisions/pretrained/TASK.pt, attack_drill.pt for the other attack drills), with --policy improved "
                        "the value actor (python -m train.mappo_rollout_pi fit; default: "
                        "ssl_marl/decisions/pretrained/TASK_value.pt)")
    k.add_argument("--episodes", type=positive_int("--episodes"), default=1000, help="episodes (default 1000)")
    k.add_argument("--seed", type=int, default=None,
                   help="evaluation seed: episode i uses SEED+i (default "
                        + ", ".join(f"{seed} {task}" for task, seed in DEFAULT_SEEDS.items()) + ")")
    k.add_argument("--workers", type=positive_int("--workers"), default=None,
                   help="worker processes (default 1; with --backend ray: tasks in flight, default the cluster's CPUs)")
    k.add_argument("--realism", choices=("none", "realistic"), default="none", help="noise / latency preset")
    k.add_argument("--field", choices=FIELDS, default="div_b",
                   help="field around the task's area (robot parameters are the same on both; default div_b)")
    k.add_argument("--out", default=None,
                   help="output folder for results.json and duration_hist.png, created if missing (default: none)")
    add_backend(k, "the episodes")
    k.add_argument("--quiet", action="store_true", help="no progress bar")
    add_tracker_option(k)
    k.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Evaluate the decision policy and print its score and outcomes."""
    from ..io import prepare_output_dir
    from ..runners.task_eval import evaluate_task

    if args.out:
        prepare_output_dir(args.out, "--out")
    s = evaluate_task(args.task, args.policy, episodes=args.episodes, seed=args.seed, workers=workers(args),
                      realism=args.realism, field=args.field, actor=args.actor, out=args.out,
                      progress=not args.quiet, backend=args.backend, address=args.address, tracker=args.tracker)
    oc = ", ".join(f"{k} {v}" for k, v in s["outcomes"].items())
    if "mean_duration_s" in s:
        lo, hi = s["mean_duration_ci95"]
        score = f"mean duration {s['mean_duration_s']:.2f} s [95% CI {lo:.2f}-{hi:.2f}]"
    else:
        lo, hi = s["goal_rate_ci95"]
        score = f"goal rate {s['goal_rate']:.3f} [95% CI {lo:.3f}-{hi:.3f}]"
    print(f"{args.task} ({args.policy}): {score} over {s['episodes']} episodes (seeds {s['seed']}+i); "
          f"outcomes: {oc}" + (f" -> {args.out}/results.json" if args.out else ""))
    return 0
