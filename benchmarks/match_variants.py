"""Tuning probe: the attacking team's matches under variants of the restarts and of the carrier's keep rule.

Plays ``--matches`` 600 s matches of ``--blue`` (default attack-learned) against ``--yellow``
(default baseline), 6v6 Division B (``--robots``, ``--field``), no realism, seeds ``--seed`` + i, as ``ssl-marl
match`` does (:func:`ssl_marl.runners.match.play_match`), under one variant:

* ``plain``: the plain format (play restarts at once after an out; the default of ``ssl-marl match``);
* ``free-kick``: SSL restarts without a STOP (``ssl_restarts``, ``stop_s`` 0): the ball
  goes to the team that did not touch it last, its opponents keep 0.5 m until it is taken;
* ``free-kick-stop``: the same after a 1 s STOP (``stop_s`` 1), one period, no fouls;
* ``free-kick-stop-fouls``: the same with fouls called (``--format ssl`` without half-time);
* ``keep-2s`` / ``keep-inf``: the plain format with the attacking plays' ``max_keep_s``
  (``ATTACK_PASSING``; how long the carrier keeps the ball before an expired keep turns into a
  shot) at 2 s / never;
* ``keep-pass``: the plain format with ``keep_expiry="pass"`` (an expired keep becomes the
  decision's best eligible pass while the shot is worth less than ``shoot_fallback``);
* ``keep-near-4`` / ``keep-near-6``: the plain format with ``keep_shot_max_m`` 4 / 6 m (an
  expired keep turns into a shot only with the ball within that distance of the opponent goal
  centre; farther out the carrier keeps dribbling until its decision shoots or passes);
* ``tap-0.7`` / ``ssl-tap-0.7``: the plain / SSL format with ``keep_tap_m`` 0.7 (the attacker taps
  the ball ahead during a keep once it lies 0.7 m from where its touch began, so that it does not
  dribble further than SSL's 1 m);
* ``contested-kick``: the plain format with ``contested_kick`` (an opponent's dribbler on the
  ball during a pass setup turns the plan urgent instead of dropping it);
* ``press-0.6``: that and ``press_urgent_m`` 0.6 (an opponent within 0.6 m of the ball during
  an open-play setup turns the plan urgent: the passer kicks once it faces the receive point);
* ``aim-reach``: the plain format with the carrier's shots aimed at the line the opponents
  reach last (``PassingParams.aim_reach``; :mod:`ssl_marl.plays.shot_lines`) instead of the
  widest open part of the goal mouth;
* ``reach-shot``: the plain format with the carrier's decision shooting also when, within
  3.5 m of the goal centre, the best shot line has a margin of at least 0.05 s
  (``AttackParams.reach_shot_s``; :mod:`ssl_marl.plays.shot_lines`), whatever the open goal
  interval (the shot itself as before);
* ``receiver-guard``: the plain format with the decisions' ``receiver_guard_m`` at 1 m (a
  pass's last metre is the receiver's where it gets there before the opponents);
* ``pass-0.5`` / ``pass-0.65``: the plain format with the decisions' ``min_pass_success`` at
  0.5 / 0.65 (default 0.35: a pass rated less likely to arrive is not considered);
* ``pass-8m``: the plain format with passes up to 8 m long (the decisions' ``max_pass_m``, default
  6 m; on Division A's 12 m field the supports' spots often lie farther than 6 m from the ball);
* ``redirect-4.5``: the plain format with passes into a redirect kicked, and rated, to arrive
  at 4.5 m/s (``AttackParams.redirect_arrive_speed``, default 2.5; ``ATTACK_PARAMS``);
* ``ssl`` / ``ssl-receiver-guard``: the SSL format (``--format ssl``: halves, STOP, free kicks,
  fouls), without and with the 1 m receiver guard;
* ``edge-spots``: the plain format with the supports' spot grid extended by spots on the
  opponent defence area's border (``SpotParams.edge_spots`` 5; ``ATTACK_SPOTS``), where no
  marker can stand on the goal side;
* ``ssl-mark-0.25``: the SSL format with the attacking team's marks turned a quarter towards the
  ball (``ATTACK_MARK_BIAS`` 0.25, as the passing and standard plays' marks) instead of standing on
  the marked opponent's line to our goal centre (0);
* ``ssl-opp-area`` / ``ssl-in-opp-area``: the SSL format with the attacking team's attacker waiting
  outside the opponent's defense area while the ball is in it (``keep_out_of_opp_area`` True, the
  attacking plays' default; touching the ball there is a foul) / going for the ball there too (False);
* ``ssl-arrive-2.5`` / ``ssl-arrive-3``: the SSL format with the attacking team's flat passes kicked, and
  rated, to arrive at 2.5 / 3 m/s (the decisions' ``pass_arrive_speed``, default 2: a firmer pass gives the
  opponents less time to reach the lane; the receive skill was trained on passes kicked at 1.5-6 m/s);
* ``ssl-shoot-0.15``: the SSL format with the attacking team's decisions shooting at once from a shot value of
  0.15 in open play (``shoot_threshold``, default 0.25; set pieces unchanged): more shots near the goal, whose
  rebounds the supports may take;
* ``ssl-long-shot-5`` / ``ssl-long-shot-6``: the SSL format with a learned carrier decision's shot offered,
  with the ball farther than 5 / 6 m from the opponent goal centre, only when no other option is legal
  (``ssl_marl.decisions.long_shot.LONG_SHOT_MASK_M``; the attack drill's carrier never stands that far out);
  ``ssl-long-shot-off``: the same without the rule (the shot always offered);
* ``ssl-spots-goal-0.5``: the SSL format with the supports' spots valuing nearness to the goal more
  (``SpotParams.w_goal`` 0.5, default 0.2; ``ATTACK_SPOTS``): supports closer to the goal mouth;
* ``ssl-restart-redirect-1.5`` / ``-2`` / ``-3``: the SSL format with the attacking team's set pieces
  weighting a pass into a redirect (one-touch shot) 1.5 / 2 / 3 times the receiver's shot value
  (``AttackParams.restart_w_redirect``; open play keeps ``w_redirect`` 1; ``ATTACK_PARAMS``);
* ``ssl-restart-pass-0.6`` / ``-0.7``: the SSL format with the attacking team's set pieces passing only where
  the pass is rated at least 0.6 / 0.7 likely to arrive (``min_pass_success`` of ``ATTACK_PASSING.restart_decision``,
  default 0.5; open play keeps 0.35); without such a pass the set piece is one kick;
* ``ssl-restart-chip-2.5`` / ``-3``: the SSL format with the attacking team's set-piece chips ones the receiver
  can take on its dribbler, arriving at most 2.5 / 3 m/s fast (``AttackParams.restart_chip_arrive_speed``;
  default None: the shortest-flight chip, whose ball may still hop above the dribbler bar at the receiver);
* ``ssl-defender-1-opp-2`` / ``ssl-defender-1-always``: the SSL format with the attacking plays' second defender
  playing only while two or more opponents stand in our half or the ball lies there (``ATTACK_DEFENDER_1_OPPONENTS``
  2), its robot a support otherwise / always (0, as the default None);
* ``opp-one-defender`` / ``opp-no-defender``: the plain format against a weakened defence: the
  standard plays (the ``baseline`` / ``learned`` teams' plays) keep only their first defender /
  none of their defenders on the ball-goal line (the robots freed take the plays' next roles:
  marks and supports); the goalie is unchanged. A probe of what limits scoring, not a team.

Writes per match the score, both teams' statistics, the referee's counts and the fouls by team, and a
summary: :func:`ssl_marl.runners.statistics.series_statistics` (win-draw-loss, goals, the goal
difference per 600 s with its 95 % interval), ball-outs and blue shots per match.

    python benchmarks/match_variants.py free-kick-stop --seed 61500 --matches 10 \\
        --out results/tuning/match_variants/free-kick-stop.json
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

#: env options of each variant (the rest of the match as ``ssl-marl match`` plays it)
RULES = {"plain": {}, "free-kick": {"ssl_restarts": True, "stop_s": 0.0},
         "free-kick-stop": {"ssl_restarts": True, "stop_s": 1.0},
         "free-kick-stop-fouls": {"ssl_restarts": True, "stop_s": 1.0, "fouls": True},
         "keep-2s": {}, "keep-inf": {}, "keep-pass": {}, "keep-near-4": {}, "keep-near-6": {}, "tap-0.7": {},
         "receiver-guard": {},
         "contested-kick": {}, "press-0.6": {}, "aim-reach": {}, "reach-shot": {}}
#: the match format of each variant (:func:`ssl_marl.runners.match.format_options`; default plain)
FORMAT = {"ssl": "ssl", "ssl-receiver-guard": "ssl", "ssl-tap-0.7": "ssl", "ssl-mark-0.25": "ssl", "ssl-opp-area": "ssl",
          "ssl-in-opp-area": "ssl", "ssl-arrive-2.5": "ssl", "ssl-arrive-3": "ssl",
          "ssl-shoot-0.15": "ssl", "ssl-spots-goal-0.5": "ssl",
          **{f"ssl-restart-redirect-{w}": "ssl" for w in ("1.5", "2", "3")},
          **{f"ssl-restart-pass-{v}": "ssl" for v in ("0.6", "0.7")},
          **{f"ssl-restart-chip-{v}": "ssl" for v in ("2.5", "3")}, "ssl-defender-1-opp-2": "ssl", "ssl-defender-1-always": "ssl",
          "ssl-long-shot-5": "ssl", "ssl-long-shot-6": "ssl", "ssl-long-shot-off": "ssl"}
#: the attacking plays' mark bias of each variant (``ATTACK_MARK_BIAS``)
MARK_BIAS = {"ssl-mark-0.25": 0.25}
#: the attacking plays' ``ATTACK_DEFENDER_1_OPPONENTS`` of each variant
DEFENDER_1_OPPONENTS = {"ssl-defender-1-opp-2": 2, "ssl-defender-1-always": 0}
#: ``LONG_SHOT_MASK_M`` of the learned attacking deciders in each variant
LONG_SHOT = {"ssl-long-shot-5": 5.0, "ssl-long-shot-6": 6.0, "ssl-long-shot-off": None}
#: ``ATTACK_PASSING`` fields of each variant
PASSING = {"keep-2s": {"max_keep_s": 2.0}, "keep-inf": {"max_keep_s": math.inf}, "keep-pass": {"keep_expiry": "pass"},
           "keep-near-4": {"keep_shot_max_m": 4.0}, "keep-near-6": {"keep_shot_max_m": 6.0},
           "tap-0.7": {"keep_tap_m": 0.7}, "ssl-tap-0.7": {"keep_tap_m": 0.7},
           "contested-kick": {"contested_kick": True},
           "press-0.6": {"contested_kick": True, "press_urgent_m": 0.6},
           "aim-reach": {"aim_reach": True}, "ssl-opp-area": {"keep_out_of_opp_area": True},
           "ssl-in-opp-area": {"keep_out_of_opp_area": False}}
#: ``ATTACK_PASSING.decision`` and ``.restart_decision`` fields of each variant
DECISION = {"receiver-guard": {"receiver_guard_m": 1.0}, "ssl-receiver-guard": {"receiver_guard_m": 1.0},
            "pass-0.5": {"min_pass_success": 0.5}, "pass-0.65": {"min_pass_success": 0.65},
            "pass-8m": {"max_pass_m": 8.0}, "ssl-arrive-2.5": {"pass_arrive_speed": 2.5},
            "ssl-arrive-3": {"pass_arrive_speed": 3.0}}
#: ``ATTACK_PASSING.decision`` fields of each variant (open play only; the set pieces' decision unchanged)
OPEN_PLAY_DECISION = {"ssl-shoot-0.15": {"shoot_threshold": 0.15}}
#: ``ATTACK_PASSING.restart_decision`` fields of each variant (set pieces only; open play unchanged)
RESTART_DECISION = {f"ssl-restart-pass-{v}": {"min_pass_success": float(v)} for v in ("0.6", "0.7")}
#: ``ATTACK_PARAMS`` fields of each variant
ATTACK = {"redirect-4.5": {"redirect_arrive_speed": 4.5}, "reach-shot": {"reach_shot_s": 0.05},
          **{f"ssl-restart-redirect-{w}": {"restart_w_redirect": float(w)} for w in ("1.5", "2", "3")},
          **{f"ssl-restart-chip-{v}": {"restart_chip_arrive_speed": float(v)} for v in ("2.5", "3")}}
#: ``ATTACK_SPOTS`` fields of each variant
SPOTS = {"edge-spots": {"edge_spots": 5}, "ssl-spots-goal-0.5": {"w_goal": 0.5}}
#: defenders the standard plays keep in each variant (the rest of their roles unchanged)
OPP_DEFENDERS = {"opp-one-defender": 1, "opp-no-defender": 0}


def set_attack_spots(fields: dict | None = None) -> None:
    """Replace the attacking plays' ``ATTACK_SPOTS`` (read when a team is built) by a copy
    with the ``fields``."""
    from ssl_marl.plays import attack_play

    attack_play.ATTACK_SPOTS = dataclasses.replace(attack_play.ATTACK_SPOTS, **(fields or {}))


def set_attack_constant(name: str, value: float | int | None) -> None:
    """Replace the attacking plays' module constant ``name`` (``ATTACK_MARK_BIAS``,
    ``ATTACK_DEFENDER_1_OPPONENTS``; read when a team is built); None: unchanged."""
    if value is not None:
        from ssl_marl.plays import attack_play

        setattr(attack_play, name, value)


def set_standard_defenders(n: int | None) -> None:
    """Make the standard plays (:func:`ssl_marl.plays.play.standard_plays`, as the
    ``baseline`` and ``learned`` teams build them) keep only their first ``n`` defender roles
    (None: unchanged)."""
    if n is None:
        return
    from ssl_marl.plays import play, team

    def kept(r) -> bool:
        return not (r.name.startswith("defender_") and int(r.name.rsplit("_", 1)[1]) >= n)

    team.standard_plays = lambda: tuple(dataclasses.replace(p, roles=tuple(filter(kept, p.roles)))
                                        for p in play.standard_plays())


def set_attack_passing(passing: dict | None = None, decision: dict | None = None,
                       open_decision: dict | None = None, restart_decision: dict | None = None) -> None:
    """Replace the attacking plays' ``ATTACK_PASSING`` (read when a team is built) by a copy
    with the ``passing`` fields, in both its open-play and restart decision parameters the
    ``decision`` fields, in the open-play ones also the ``open_decision`` fields and in the
    restart ones the ``restart_decision`` fields."""
    from ssl_marl.plays import attack_play

    ap = dataclasses.replace(attack_play.ATTACK_PASSING, **(passing or {}))
    if decision:
        ap = dataclasses.replace(ap, decision=dataclasses.replace(ap.decision, **decision),
                                 restart_decision=dataclasses.replace(ap.restart_decision, **decision))
    if open_decision:
        ap = dataclasses.replace(ap, decision=dataclasses.replace(ap.decision, **open_decision))
    if restart_decision:
        ap = dataclasses.replace(ap, restart_decision=dataclasses.replace(ap.restart_decision, **restart_decision))
    attack_play.ATTACK_PASSING = ap


def set_attack_params(fields: dict | None = None) -> None:
    """Replace the attacking plays' ``ATTACK_PARAMS`` (read when a team is built) by a copy
    with the ``fields``."""
    from ssl_marl.plays import attack_play

    attack_play.ATTACK_PARAMS = dataclasses.replace(attack_play.ATTACK_PARAMS, **(fields or {}))


def summarize(rows: list[dict], seconds: float) -> dict:
    from ssl_marl.runners.statistics import series_statistics

    stats = series_statistics([r["score"]["blue"] for r in rows], [r["score"]["yellow"] for r in rows], seconds)
    return {**stats, "ball_outs_per_match": float(np.mean([r["referee"].get("ball_out", 0) for r in rows])),
            "blue_shots_per_match": float(np.mean([r["blue"]["shots"] for r in rows]))}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("variant", choices=sorted({*RULES, *FORMAT, *DECISION, *OPEN_PLAY_DECISION, *RESTART_DECISION, *ATTACK,
                                               *SPOTS, *OPP_DEFENDERS, *MARK_BIAS,
                                               *DEFENDER_1_OPPONENTS, *LONG_SHOT}),
                    help="the variant (module docstring)")
    ap.add_argument("--blue", default="attack-learned", help="blue team kind (default attack-learned)")
    ap.add_argument("--yellow", default="baseline", help="yellow team kind (default baseline)")
    ap.add_argument("--seed", type=int, default=61500, help="first seed (tuning seeds; default 61500)")
    ap.add_argument("--matches", type=int, default=10, help="matches (default 10)")
    ap.add_argument("--seconds", type=float, default=600.0, help="match length, s (default 600)")
    ap.add_argument("--robots", type=int, default=6, help="robots per team (default 6)")
    ap.add_argument("--field", choices=("div_a", "div_b"), default="div_b", help="field (default div_b)")
    ap.add_argument("--out", required=True, help="JSON output (rewritten after every match)")
    args = ap.parse_args(argv)
    from ssl_marl.io import atomic_write_json
    from ssl_marl.runners.match import format_options, play_match
    from ssl_marl.runners.provenance import build_manifest

    env = {**format_options(FORMAT.get(args.variant, "plain"), args.seconds), **RULES.get(args.variant, {})}
    set_attack_passing(PASSING.get(args.variant), DECISION.get(args.variant), OPEN_PLAY_DECISION.get(args.variant),
                       RESTART_DECISION.get(args.variant))
    set_attack_params(ATTACK.get(args.variant))
    set_attack_spots(SPOTS.get(args.variant))
    set_standard_defenders(OPP_DEFENDERS.get(args.variant))
    set_attack_constant("ATTACK_MARK_BIAS", MARK_BIAS.get(args.variant))
    set_attack_constant("ATTACK_DEFENDER_1_OPPONENTS", DEFENDER_1_OPPONENTS.get(args.variant))
    from ssl_marl.decisions import long_shot

    if args.variant in LONG_SHOT:
        long_shot.LONG_SHOT_MASK_M = LONG_SHOT[args.variant]
    manifest = build_manifest(rules={"variant": args.variant, "env": env,
                                     "attack_passing": {k: str(v) for k, v in PASSING.get(args.variant, {}).items()},
                                     "decision": DECISION.get(args.variant, {}),
                                     "open_play_decision": OPEN_PLAY_DECISION.get(args.variant, {}),
                                     "restart_decision": RESTART_DECISION.get(args.variant, {}),
                                     "attack": ATTACK.get(args.variant, {}),
                                     "spots": SPOTS.get(args.variant, {}),
                                     "standard_plays_defenders": OPP_DEFENDERS.get(args.variant),
                                     "attack_mark_bias": MARK_BIAS.get(args.variant),
                                     "attack_defender_1_opponents": DEFENDER_1_OPPONENTS.get(args.variant),
                                     "long_shot_mask_m": long_shot.LONG_SHOT_MASK_M,
                                     "blue": args.blue, "yellow": args.yellow, "seconds": args.seconds,
                                     "robots": args.robots, "field": args.field},
                              seeds={"seed": args.seed, "matches": args.matches})
    rows = []
    for i in range(args.matches):
        t0 = time.time()
        r = play_match(args.blue, args.yellow, robots=args.robots, field=args.field, seconds=args.seconds,
                       seed=args.seed + i, render=None, progress=False, env_kwargs=dict(env))
        rows.append({"seed": args.seed + i, "score": r.score, "blue": dict(r.stats["blue"]),
                     "yellow": dict(r.stats["yellow"]),
                     "referee": r.stats.get("referee", {}), "fouls": r.stats.get("fouls", {}),
                     "wall_s": round(time.time() - t0, 1)})
        print(args.variant, args.seed + i, r.score, flush=True)
        atomic_write_json(args.out, {"summary": summarize(rows, args.seconds), "matches": rows, "manifest": manifest})
    print(json.dumps(summarize(rows, args.seconds), indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
