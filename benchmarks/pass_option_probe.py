"""Why the attacking carrier rarely passes: every pass option its decision rated in a few matches, counted.

Wraps :func:`ssl_marl.plays.attack_decision.decide_attack` (the hand-coded attack decision
of ``--blue``, an attacking team) in matches against ``--yellow`` and counts, over every
decision that rated passes: the flat pass options, those with success >= the decision's
``min_pass_success`` (0.35), the passes into a redirect (deflection under 1.2 rad and a
receiver shot value >= ``min_redirect_shot``), and the decisions' choices. With
``--receiver-guard M`` the attacking plays rate passes with ``receiver_guard_m`` = M
(:class:`~ssl_marl.plays.pass_decision.DecisionParams`).

    python benchmarks/pass_option_probe.py --seeds 61620-61621 --out results/tuning/pass_option_probe.json
"""

from __future__ import annotations

import sys
from collections import Counter
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from ball_out_probe import probe_args, write_probe  # noqa: E402  (the probes' shared command line)
from match_variants import set_attack_passing  # noqa: E402


def probe_match(blue: str, yellow: str, seconds: float, seed: int) -> Counter:
    """The counts of one match (module docstring)."""
    from ssl_marl.plays import attack_decision, attack_play
    from ssl_marl.runners.match import play_match

    counts: Counter = Counter()
    original = attack_play.decide_attack

    def decide(*args, **kwargs):
        d = original(*args, **kwargs)
        params = kwargs.get("params") or args[7]
        counts["decisions"] += 1
        counts[f"choice_{d.choice.value}"] += 1
        flat = [o for o in d.options if o.kind is attack_decision.AttackChoice.PASS]
        redirect = [o for o in d.options if o.kind is attack_decision.AttackChoice.REDIRECT]
        counts["flat_options"] += len(flat)
        counts["flat_options_eligible"] += sum(o.success >= params.decision.min_pass_success for o in flat)
        counts["redirect_options"] += len(redirect)
        counts["redirect_options_eligible"] += sum(o.success >= params.decision.min_pass_success for o in redirect)
        return d

    attack_play.decide_attack = decide
    try:
        play_match(blue, yellow, robots=6, seconds=seconds, seed=seed, render=None, progress=False)
    finally:
        attack_play.decide_attack = original
    return counts


def main(argv: list[str] | None = None) -> int:
    def extra(ap):
        ap.add_argument("--receiver-guard", type=float, default=0.0, metavar="M",
                        help="rate the attacking plays' passes with receiver_guard_m = M (m; default 0)")

    args = probe_args(__doc__.splitlines()[0], "61620-61621", "JSON output (summary per match and in all)", argv, extra)
    guard = args.receiver_guard
    if guard:
        set_attack_passing(decision={"receiver_guard_m": guard})
    per_match = {s: probe_match(args.blue, args.yellow, args.seconds, s) for s in args.seeds}
    total = sum(per_match.values(), Counter())
    write_probe(args, {"summary": {"receiver_guard_m": guard, **dict(total)},
                       "matches": {str(s): dict(c) for s, c in per_match.items()}})
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
