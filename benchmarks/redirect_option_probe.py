"""Where a pass into a redirect is possible: the attacking carrier's options at every decision of a few matches.

For each SSL-format match (the runner of ``ssl-marl match --format ssl``,
:func:`ssl_marl.runners.match.play_match`) this wraps the attacking plays' carrier decider
(:meth:`ssl_marl.plays.attack_play.AttackDecider.decide` and the learned deciders' of
:mod:`ssl_marl.decisions.match_decider`, restarts and open play alike) and, at every request, evaluates the cost decision's options on the request's
scene and parameters (:func:`ssl_marl.plays.attack_decision.decide_attack`; a learned decider's
open-play choice is its policy's, the options are what the cost decision would see). Per request
it records whether it was a restart (kickoff, free kick), the ball's x (team frame, m), the chosen
kind, and for the passes into a redirect the cost decision rated: how many had a usable deflection
and receiver shot (value > 0), how many were also rated safe enough to be played (success >=
``min_pass_success``); and for every teammate a pass could go to, the deflection a redirect there
would need (rad; the redirect rating's limit is ``redirect_zero`` = 1.2 rad, TIGERs'). The summary
splits restarts from open play and counts requests by ball x band.

    python benchmarks/redirect_option_probe.py --blue attack-learned-decision --yellow attack-learned-decision \\
        --seeds 61860-61861 --out results/tuning/redirect_option_probe.json
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from benchmarks.ball_out_probe import probe_args, write_probe  # noqa: E402

#: ball x bands (team frame, m: the opponent goal at +x)
BANDS = ((-np.inf, 0.0), (0.0, 2.0), (2.0, 3.5), (3.5, np.inf))


def probe_match(blue: str, yellow: str, seconds: float, seed: int) -> list[dict]:
    """One row per carrier request of either attacking team in one SSL-format match."""
    from ssl_marl.decisions import match_decider
    from ssl_marl.plays import attack_play
    from ssl_marl.plays.attack_decision import AttackChoice, decide_attack, redirect_geometry
    from ssl_marl.plays.pass_decision import teammates_except
    from ssl_marl.runners import match as match_runner

    rows: list[dict] = []
    classes = (attack_play.AttackDecider, match_decider.PolicyAttackDecider, match_decider.ImprovedAttackDecider)
    originals = {cls: cls.__dict__["decide"] for cls in classes}
    inside: set[int] = set()  # deciders inside a wrapped decide (a subclass calls its parent's: one row)

    def wrap(original):
        def decide(self, request):
            if id(self) in inside:
                return original(self, request)
            inside.add(id(self))
            try:
                return record(self, request, original)
            finally:
                inside.discard(id(self))
        return decide

    def record(self, request, original):
        ctx = request.ctx
        ours = ctx.world.team(ctx.team)
        params = self.request_params(request)
        d = decide_attack(ctx.ball, request.carrier, ours.pos, ctx.opp_pos, ctx.field, ctx.robot, request.ball,
                          params, candidates=request.candidates, heading=request.heading)
        out = original(self, request)
        mates = np.asarray(ours.pos, float)
        opp = np.asarray(ctx.opp_pos, float).reshape(-1, 2)
        deflections = []
        for k in request.candidates:
            if k == request.carrier:
                continue
            obstacles = np.concatenate([opp, teammates_except(mates, k)])
            deflections.append(float(redirect_geometry(mates[k], ctx.ball, obstacles, ctx.field, ctx.robot,
                                                       request.ball)[1]))
        red = [o for o in d.options if o.kind is AttackChoice.REDIRECT and o.value > 0]
        opt = getattr(self, "option", None)
        chosen = opt.kind.value if out.choice.value == "pass" and opt is not None else out.choice.value
        rows.append({"team": ctx.team, "restart": bool(request.restart), "ball_x": float(ctx.ball[0]),
                     "cost_choice": d.choice.value, "chosen": chosen,
                     "redirects_usable": len(red),
                     "redirects_safe": sum(o.success >= params.decision.min_pass_success for o in red),
                     "redirects": [{"teammate": o.teammate, "success": round(o.success, 3), "value": round(o.value, 3),
                                    "deflection": round(o.deflection, 3),
                                    "flat_success": round(max([f.success for f in d.options if f.kind is AttackChoice.PASS
                                                               and f.teammate == o.teammate] or [0.0]), 3)}
                                   for o in red],
                     "deflections": [round(x, 3) for x in deflections]})
        return out

    for cls, original in originals.items():
        cls.decide = wrap(original)
    try:
        match_runner.play_match(blue=blue, yellow=yellow, seconds=seconds, seed=seed, progress=False,
                                env_kwargs=match_runner.format_options("ssl", seconds))
    finally:
        for cls, original in originals.items():
            cls.decide = original
    return [{**r, "seed": seed} for r in rows]


def summarize(rows: list[dict], zero: float) -> dict:
    out: dict = {"requests": len(rows)}
    for name, sel in (("restart", [r for r in rows if r["restart"]]), ("open_play", [r for r in rows if not r["restart"]])):
        defl = np.array([x for r in sel for x in r["deflections"]], float)
        out[name] = {
            "requests": len(sel),
            "with_usable_redirect": sum(r["redirects_usable"] > 0 for r in sel),
            "with_safe_redirect": sum(r["redirects_safe"] > 0 for r in sel),
            "cost_chose_redirect": sum(r["cost_choice"] == "redirect" for r in sel),
            "chose_redirect": sum(r["chosen"] == "redirect" for r in sel),
            "teammate_deflection_within_limit": round(float(np.mean(defl <= zero)), 3) if defl.size else None,
            "teammate_deflection_median_rad": round(float(np.median(defl)), 3) if defl.size else None,
            "by_ball_x": {f"{lo:g}..{hi:g}": {"requests": sum(lo <= r["ball_x"] < hi for r in sel),
                                              "with_safe_redirect": sum(lo <= r["ball_x"] < hi and r["redirects_safe"] > 0
                                                                        for r in sel)}
                          for lo, hi in BANDS},
        }
    return out


def main(argv: list[str] | None = None) -> int:
    from ssl_marl.plays.attack_play import ATTACK_PARAMS

    args = probe_args(__doc__.splitlines()[0], "61860-61861", "JSON output (summary and every request)", argv)
    rows = [r for s in args.seeds for r in probe_match(args.blue, args.yellow, args.seconds, s)]
    write_probe(args, {"summary": summarize(rows, ATTACK_PARAMS.redirect_zero), "requests": rows})
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
