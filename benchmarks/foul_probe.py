"""Who commits the fouls: every foul of a few SSL-format matches, with the offender's role.

6v6 Division B, SSL format (``ssl_marl.runners.match.format_options("ssl", ...)``: game control, fouls,
halves), teams as ``ssl-marl match`` builds them. For each ``foul`` event of the env
(:mod:`ssl_marl.envs.game_control`: ``attacker_in_defense_area``, ``excessive_dribbling``,
``double_touch``, ``defender_too_close``) it records the offending team, the foul, the offender's
role and its tactic's state on the tick before the foul (the STP team's assignment; "-" for teams
without roles), where the ball lay (field frame, m) and the referee's command then. Variants of the
attacking plays' passing parameters can be set as in ``benchmarks/match_variants.py``
(``--passing FIELD=VALUE``, e.g. ``keep_out_of_opp_area=true``).

    python benchmarks/foul_probe.py --seeds 61800-61801 --out results/tuning/foul_probe.json
"""

from __future__ import annotations

import dataclasses
import json
import sys
from collections import Counter
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from ball_out_probe import probe_args, write_probe  # noqa: E402  (the probes' shared command line)


def probe_match(blue: str, yellow: str, seconds: float, seed: int) -> list[dict]:
    """The fouls of one SSL-format match (module docstring)."""
    from ssl_marl.plays.team import TeamController
    from ssl_marl.runners import match as match_runner

    last: dict[str, dict[int, tuple[str, str]]] = {"blue": {}, "yellow": {}}  #: team -> robot -> (role, state)
    fouls: list[dict] = []
    original_act, original_record = TeamController.act, match_runner.MatchStats.record

    def act(self, env_or_world, referee=None):
        out = original_act(self, env_or_world, referee=referee)
        last[self.team] = {i: (role, str(getattr(self.tactic(i), "state", "-")).split(".")[-1])
                           for i, role in self.roles.items()}
        return out

    def record(self, events, truth):
        for e in events:
            if e.get("type") == "foul":
                team, agent = e["team"], e.get("agent")
                robot = int(agent.rsplit("_", 1)[1]) if agent else None
                role, state = last[team].get(robot, ("-", "-")) if robot is not None else ("-", "-")
                fouls.append({"seed": seed, "t": float(truth.t), "team": team, "foul": e["foul"], "robot": robot,
                              "role": role, "state": state,
                              "ball": np.asarray(truth.ball_pos, float).round(3).tolist()})
        return original_record(self, events, truth)

    TeamController.act, match_runner.MatchStats.record = act, record
    try:
        match_runner.play_match(blue=blue, yellow=yellow, robots=6, field="div_b", seconds=seconds, seed=seed,
                                progress=False, render=None, env_kwargs=match_runner.format_options("ssl", seconds))
    finally:
        TeamController.act, match_runner.MatchStats.record = original_act, original_record
    return fouls


def role_kind(role: str) -> str:
    """A role's name without its index (``support_2`` -> ``support``)."""
    head, _, tail = role.rpartition("_")
    return head if tail.isdigit() else role


def summarize(fouls: list[dict], matches: int) -> dict:
    out: dict = {"matches": matches}
    for team in ("blue", "yellow"):
        mine = [f for f in fouls if f["team"] == team]
        out[team] = {"fouls": len(mine), "by_foul": dict(Counter(f["foul"] for f in mine)),
                     "by_foul_and_role": {k: dict(Counter(f"{role_kind(f['role'])} ({f['state']})" for f in mine
                                                          if f["foul"] == k))
                                          for k in sorted({f["foul"] for f in mine})}}
    return out


def main(argv: list[str] | None = None) -> int:
    def extra(ap):
        ap.add_argument("--passing", action="append", default=[], metavar="FIELD=VALUE",
                        help="an attacking-plays PassingParams field (ATTACK_PASSING), e.g. keep_out_of_opp_area=true")
    args = probe_args(__doc__.splitlines()[0], "61800-61801", "JSON output (summary and every foul)", argv,
                      extra=extra)
    if args.passing:
        from ssl_marl.plays import attack_play

        fields = {k: json.loads(v) for k, _, v in (p.partition("=") for p in args.passing)}
        attack_play.ATTACK_PASSING = dataclasses.replace(attack_play.ATTACK_PASSING, **fields)
    fouls = [f for s in args.seeds for f in probe_match(args.blue, args.yellow, args.seconds, s)]
    write_probe(args, {"summary": {**summarize(fouls, len(args.seeds)), "passing": args.passing}, "fouls": fouls})
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
