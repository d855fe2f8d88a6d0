"""Who dribbles too far: every excessive-dribbling foul of a few SSL-format matches, classified.

For each ``excessive_dribbling`` foul the referee calls in ``ssl-marl match --format ssl``
matches (the same runner, :func:`ssl_marl.runners.match.play_match`), this records what the
offending team's controller was doing on the tick before the call: the offender's role and
its tactic's state (e.g. ``attacker``/KEEP, ``passer``/HOLD, ``goalie``/CLEAR_KICK), the pass
coordinator's last decision (shoot / pass / keep and whether it was a committed one), and the
team's own account of the dribble (:attr:`~ssl_marl.plays.play.PlayContext.dribbled_m`).
The summary counts fouls per team and by role/state.

    python benchmarks/dribble_foul_probe.py --blue attack-learned-decision --yellow attack-learned \\
        --seconds 600 --seeds 61710-61711 --out results/tuning/dribble_foul_probe.json
"""

from __future__ import annotations

import sys
from collections import Counter
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from benchmarks.ball_out_probe import probe_args, write_probe  # noqa: E402


def _controller_view(ctrl, robot: int) -> dict:
    """The offender's role, tactic state and the team's last carrier decision."""
    role = (ctrl.assignment.robots.get(robot) if getattr(ctrl, "assignment", None) else None)
    tactic = ctrl.tactic(robot) if hasattr(ctrl, "tactic") else None
    status = getattr(tactic, "status", None)
    state = getattr(getattr(status, "state", None), "name", None)
    coord = None
    play = getattr(ctrl, "play", None)
    if play is not None:
        coord = getattr(play.prepare, "coordinator", None)
    d = getattr(coord, "decision", None)
    ctx = getattr(ctrl, "context", None)
    dribbled = None if ctx is None or ctx.dribbled_m is None else float(ctx.dribbled_m[robot])
    return {"role": role, "state": state, "play": getattr(play, "name", None),
            "decision": None if d is None else d.choice.name, "committed": None if d is None else d.commit_s > 0,
            "team_dribbled_m": dribbled, "time_in_state_s": getattr(status, "time_in_state", None),
            **_plan_view(coord)}


def _plan_view(coord) -> dict:
    """The pass plan open at the call: its phase, whether it is a set piece's, whether it is urgent."""
    plan = getattr(coord, "plan", None)
    if plan is None:
        return {"plan": None}
    return {"plan": plan.phase.name, "plan_restart": bool(plan.restart), "plan_urgent": bool(plan.urgent)}


def probe_match(blue: str, yellow: str, seconds: float, seed: int) -> list[dict]:
    """The excessive-dribbling fouls of one SSL-format match (module docstring)."""
    from ssl_marl.runners import match as match_runner

    ctrls: dict[str, object] = {}
    fouls: list[dict] = []
    make, record = match_runner.make_controller, match_runner.MatchStats.record

    def make_controller(kind, team, *a, **kw):
        ctrls[team] = c = make(kind, team, *a, **kw)
        return c

    def record_hook(self, events, truth):
        for e in events:
            if e.get("type") == "foul" and e.get("foul") == "excessive_dribbling":
                team, robot = e["agent"].rsplit("_", 1)
                fouls.append({"seed": seed, "t": float(e["t"]), "team": team, "robot": int(robot),
                              **_controller_view(ctrls[team], int(robot))})
        return record(self, events, truth)

    match_runner.make_controller, match_runner.MatchStats.record = make_controller, record_hook
    try:
        match_runner.play_match(blue=blue, yellow=yellow, seconds=seconds, seed=seed, progress=False,
                                env_kwargs=match_runner.format_options("ssl", seconds))
    finally:
        match_runner.make_controller, match_runner.MatchStats.record = make, record
    return fouls


def summarize(fouls: list[dict], matches: int) -> dict:
    by = Counter(f"{f['team']} {f['role']}/{f['state']} decision={f['decision']}"
                 f"{' committed' if f['committed'] else ''}"
                 f"{'' if f.get('plan') is None else ' plan=' + f['plan'] + (' set-piece' if f['plan_restart'] else '')}"
                 for f in fouls)
    return {"matches": matches, "fouls": len(fouls),
            "per_team": {t: sum(f["team"] == t for f in fouls) for t in ("blue", "yellow")},
            "by_role_state": dict(by.most_common())}


def main(argv: list[str] | None = None) -> int:
    args = probe_args(__doc__.splitlines()[0], "61710-61711", "JSON output (summary and every foul)", argv)
    fouls = [f for s in args.seeds for f in probe_match(args.blue, args.yellow, args.seconds, s)]
    write_probe(args, {"summary": summarize(fouls, len(args.seeds)), "fouls": fouls})
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
