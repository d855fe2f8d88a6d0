"""How SSL-format set pieces are taken: kicked, or carried off in contact (a double touch by the rules).

Plays ``--format ssl`` matches (``ssl_marl.runners.match.play_match``) and classifies every
kickoff and free kick (``<team>_kickoff_<how>``, ``<team>_free_kick_<how>``; code before
commit 85a739f announced no kickoff among the step's events, so its records count free kicks
only) by the step in which the referee sees it taken (the ball 0.05 m from its spot) or lets
it run on after its timeout:

* ``kick``: the kicking team kicked the ball in that step or since the command (a pass
  kicked at 2-3 m/s moves less than 0.05 m in its first step);
* ``released``: no kick, and the team's robot nearest the ball is no longer in contact, or
  the ball leaves it faster than ``SEPARATING_M_S`` (a bump that lets the ball go);
* ``carried``: no kick, and that robot still holds the ball
  (:meth:`~ssl_marl.envs.game_control.TouchWatch.carries`: on its dribbler, or in body
  contact with the ball not leaving it): the ball has moved 0.05 m in the kicker's contact,
  which the SSL rules count as a double touch ("Remaining in contact with the ball for more
  than 0.05 meters also counts as double touch", the rules' text as TIGERs' autoref quotes it;
  docs/references.md) and the referee calls (``fouls``);
* ``timeout``: nobody took it within the free kick's timeout.

    python benchmarks/set_piece_probe.py --seeds 61910-61911 --out results/tuning/set_piece_probe.json
"""

from __future__ import annotations

import sys
from collections import Counter
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from ball_out_probe import probe_args, write_probe  # noqa: E402  (the probes' shared command line)

def classify(truth, team: str, kicked_by_team: bool, watch) -> str:
    """How the set piece of ``team`` was taken in the step whose ground truth is ``truth``
    (``watch``: a :class:`~ssl_marl.envs.game_control.TouchWatch` of the match's robots)."""
    if kicked_by_team:
        return "kick"
    ts = truth.team(team)
    i = int(np.argmin(np.hypot(*(np.asarray(ts.pos) - truth.ball_pos).T)))
    row = i + (truth.blue.n if team == "yellow" else 0)  # blue's rows come first
    return "carried" if watch.carries(truth, row) else "released"


def probe_match(blue: str, yellow: str, seconds: float, seed: int) -> Counter:
    """The counts of one SSL-format match (module docstring): ``<team>_<kind>_<how>``."""
    from ssl_marl.envs.game_control import FREE_KICK, KICKOFF, RUNNING, TouchWatch
    from ssl_marl.physics.params import BallParams, RobotParams
    from ssl_marl.runners import match as match_runner

    counts: Counter = Counter()
    watch = TouchWatch(6, 6, RobotParams().radius, BallParams().radius)
    # (command, team) of the set piece not yet taken, its ball spot, the teams that kicked since its command
    state = {"set_piece": None, "spot": None, "kicked": set()}
    original = match_runner.MatchStats.record

    def record(self, events, truth):
        original(self, events, truth)
        kickers = {e["agent"].split("_")[0] for e in events if e["type"] == "kick"}
        state["kicked"] |= kickers
        for e in events:
            if e["type"] != "referee":
                continue
            pending = state["set_piece"]
            if e["command"] in (KICKOFF, FREE_KICK):
                state["set_piece"], state["kicked"] = (e["command"], e["team"]), set(kickers)
            elif e["command"] == RUNNING and pending is not None:
                command, team = pending
                spot_left = state["spot"] is None or float(np.hypot(*(truth.ball_pos - state["spot"]))) > 0.05
                how = classify(truth, team, team in state["kicked"], watch) if spot_left else "timeout"
                counts[f"{team}_{command.lower()}_{how}"] += 1
                state["set_piece"] = None
            else:
                state["set_piece"] = None
            if e["command"] in (KICKOFF, FREE_KICK) and e.get("position") is not None:
                state["spot"] = np.asarray(e["position"], float)

    match_runner.MatchStats.record = record
    try:
        match_runner.play_match(blue, yellow, robots=6, seconds=seconds, seed=seed, render=None, progress=False,
                                env_kwargs=match_runner.format_options("ssl", seconds))
    finally:
        match_runner.MatchStats.record = original
    return counts


def main(argv: list[str] | None = None) -> int:
    args = probe_args(__doc__.splitlines()[0], "61910-61911", "JSON output (counts per match and in all)", argv)
    per_match = {s: probe_match(args.blue, args.yellow, args.seconds, s) for s in args.seeds}
    total = sum(per_match.values(), Counter())
    write_probe(args, {"summary": dict(sorted(total.items())),
                       "matches": {str(s): dict(sorted(c.items())) for s, c in per_match.items()}})
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
