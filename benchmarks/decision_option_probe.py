"""Which options each team's carrier decision takes in matches: the attacking plays' decision counters.

For each SSL-format match (the runner of ``ssl-marl match --format ssl``,
:func:`ssl_marl.runners.match.play_match`) this reads, at the final whistle, both teams'
carrier deciders (the pass coordinator's ``decider``): its
:class:`~ssl_marl.plays.attack_play.AttackCounters` (requests answered shoot / flat pass /
chip / redirect / dribble: the coordinator asks on every request, so a held ball counts
more than once), and for a learned decider (:class:`~ssl_marl.decisions.match_decider.PolicyAttackDecider`)
how many requests its policy answered and how many of those had the dribbles masked. The
summary adds the teams' goals and the statistics' shots.

    python benchmarks/decision_option_probe.py --blue attack-learned --blue-decision learned --yellow attack-learned \\
        --seconds 600 --seeds 61740-61741 --out results/tuning/decision_option_probe.json
"""

from __future__ import annotations

import dataclasses
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from benchmarks.ball_out_probe import probe_args, write_probe  # noqa: E402

COUNTS = ("shoot", "pass_", "chip", "redirect", "dribble")


def _decider_view(ctrl) -> dict:
    """The team's carrier decider: its kind and counters (empty for a team without a coordinator)."""
    from ssl_marl.plays.passing_play import coordinator_of

    selector = getattr(ctrl, "selector", None)
    coord = coordinator_of(selector.plays) if selector is not None else None
    dec = getattr(coord, "decider", None)
    counters = getattr(dec, "counters", None)
    view = {"decider": type(dec).__name__ if dec is not None else None}
    if counters is not None:
        view.update({k: int(getattr(counters, k)) for k in COUNTS})
    for k in ("decisions", "dribbles_masked"):
        if hasattr(dec, k):
            view[k] = int(getattr(dec, k))
    return view


def probe_match(blue: str, yellow: str, seconds: float, seed: int, blue_decision: str | None,
                yellow_decision: str | None) -> dict:
    """Both teams' decision counters, goals and shots of one SSL-format match."""
    from ssl_marl.runners import match as match_runner

    ctrls: dict[str, object] = {}
    make = match_runner.make_controller

    def make_controller(kind, team, *a, **kw):
        ctrls[team] = c = make(kind, team, *a, **kw)
        return c

    match_runner.make_controller = make_controller
    try:
        res = match_runner.play_match(blue=blue, yellow=yellow, seconds=seconds, seed=seed, progress=False,
                                      blue_decision=blue_decision, yellow_decision=yellow_decision,
                                      env_kwargs=match_runner.format_options("ssl", seconds))
    finally:
        match_runner.make_controller = make
    res = res if isinstance(res, dict) else dataclasses.asdict(res)
    return {"seed": seed, "score": res["score"],
            **{team: {**_decider_view(ctrls[team]), "shots": res["stats"][team]["shots"]} for team in ("blue", "yellow")}}


def summarize(rows: list[dict]) -> dict:
    out = {"matches": len(rows)}
    for team in ("blue", "yellow"):
        tot = {k: sum(r[team].get(k, 0) for r in rows) for k in (*COUNTS, "decisions", "dribbles_masked", "shots")}
        n = sum(tot[k] for k in COUNTS)
        out[team] = {"goals": sum(r["score"][team] for r in rows), **tot,
                     "shares": {k: round(tot[k] / n, 3) if n else None for k in COUNTS}}
    return out


def main(argv: list[str] | None = None) -> int:
    def extra(ap):
        ap.add_argument("--blue-decision", default=None, help="blue's carrier decision (as ssl-marl match)")
        ap.add_argument("--yellow-decision", default=None, help="yellow's carrier decision (as ssl-marl match)")

    args = probe_args(__doc__.splitlines()[0], "61740-61741", "JSON output (summary and every match)", argv, extra)
    rows = [probe_match(args.blue, args.yellow, args.seconds, s, args.blue_decision, args.yellow_decision)
            for s in args.seeds]
    write_probe(args, {"summary": summarize(rows), "matches": rows})
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
