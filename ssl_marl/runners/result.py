"""The outcome of a match and the summary of a series (plain data, JSON-ready)."""

from __future__ import annotations

from dataclasses import asdict, dataclass, field

import numpy as np


@dataclass
class MatchResult:
    """Outcome of one match.

    Attributes:
        score: goals per team.
        goals: [{"team": scorer, "t": simulated time (s)}] in order.
        shots: kick events per team (every kick, not only shots on goal).
        possession: fraction of control steps in which a robot of the team held the
            ball on its dribbler (ground truth; the two may sum to less than 1).
        steps: control steps simulated. sim_time_s: simulated seconds.
        wall_time_s: wall-clock seconds for the whole match (env + controllers).
        act_time_ms: mean wall time of each team's ``act`` (ms).
        missed_deadlines: real-time mode: ticks whose command was lost, per team.
        seed: env seed. config: the match options.
        stats: per team, from :class:`~ssl_marl.plays.stats.MatchStatsTracker`: kicks,
            shots (kicks aimed at the goal), goals, passes attempted / completed /
            intercepted / lost, interceptions, pass_completion; ``"events"``: the
            tracker's log of passes (with outcomes) and shots, in time order.
    """

    score: dict[str, int]
    goals: list[dict] = field(default_factory=list)
    shots: dict[str, int] = field(default_factory=dict)
    possession: dict[str, float] = field(default_factory=dict)
    steps: int = 0
    sim_time_s: float = 0.0
    wall_time_s: float = 0.0
    act_time_ms: dict[str, float] = field(default_factory=dict)
    missed_deadlines: dict[str, int] = field(default_factory=dict)
    seed: int = 0
    config: dict = field(default_factory=dict)
    stats: dict = field(default_factory=dict)

    @property
    def winner(self) -> str | None:
        """"blue", "yellow" or None for a draw."""
        b, y = self.score.get("blue", 0), self.score.get("yellow", 0)
        return None if b == y else ("blue" if b > y else "yellow")

    def to_dict(self) -> dict:
        d = asdict(self)
        d["winner"] = self.winner
        return d


def summarize(results: list[MatchResult]) -> dict:
    """Table summary from blue's side: wins / draws / losses, goals for / against, ...;
    ``stats``: per-team totals of the match statistics (:func:`~ssl_marl.plays.stats.summarize_stats`)."""
    from ..plays.stats import summarize_stats

    n = len(results)
    wins = sum(r.winner == "blue" for r in results)
    losses = sum(r.winner == "yellow" for r in results)
    gf = sum(r.score["blue"] for r in results)
    ga = sum(r.score["yellow"] for r in results)
    mean = (lambda xs: float(np.mean(xs)) if xs else 0.0)
    return {"matches": n, "blue": results[0].config.get("blue") if n else None,
            "yellow": results[0].config.get("yellow") if n else None,
            "wins": wins, "draws": n - wins - losses, "losses": losses, "goals_for": gf, "goals_against": ga,
            "goal_diff_mean": (gf - ga) / n if n else 0.0,
            "shots_blue_mean": mean([r.shots["blue"] for r in results]),
            "shots_yellow_mean": mean([r.shots["yellow"] for r in results]),
            "possession_blue_mean": mean([r.possession["blue"] for r in results]),
            "possession_yellow_mean": mean([r.possession["yellow"] for r in results]),
            "missed_deadlines_blue": sum(r.missed_deadlines["blue"] for r in results),
            "missed_deadlines_yellow": sum(r.missed_deadlines["yellow"] for r in results),
            "wall_time_s_total": float(sum(r.wall_time_s for r in results)),
            "stats": summarize_stats([r.stats for r in results if r.stats])}
