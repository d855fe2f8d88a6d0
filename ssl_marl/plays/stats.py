"""Match statistics from what the referee sees: kicks, shots, passes, interceptions, goals.

:class:`MatchStatsTracker` observes every step's ground-truth world (field frame) and the
env's events (``"kick"`` with the kicking agent, ``"goal"``, ``"ball_out"``,
``"no_progress"``); it knows
nothing of either team's plans, so it rates a passing team and a no-pass team by the
same rules:

* **Pass attempt**: a kick whose straight path passes within ``pass_lane_m`` of a
  teammate (not the kicker) standing between ``min_pass_m`` and the ball's stop
  distance (+ ``pass_lane_m``) ahead; for a kick towards the goal mouth the teammate
  must be within ``goal_lane_m`` (it stands right on the line: a pass, not a shot).
* **Shot**: any other kick whose straight path crosses the opponent goal line within
  the posts widened by ``shot_margin_m`` on each side. Kicks aimed at nobody and not
  at the goal (clearances) count only as kicks.
* **Control**: a robot holds the ball on its dribbler for ``control_steps``
  consecutive steps (0.1 s at 60 Hz), so a deflection is not control.
* A pass ends at the first control or kick by another robot: a teammate -> **completed**
  (a one-touch redirect counts); an opponent -> **intercepted** (the opponent's
  ``interceptions`` + 1). A goal, the ball leaving the field, the kicker itself taking
  the ball back, or ``pass_timeout_s`` without a control end it as **lost**.
* **Goals** come from the referee's goal events.

Per team (:meth:`MatchStatsTracker.summary`): ``kicks``, ``shots``, ``goals``,
``passes_attempted``, ``passes_completed``, ``passes_intercepted`` (own passes the
opponent took), ``passes_lost``, ``interceptions`` (opponent passes this team took),
``pass_completion`` (completed / attempted, None without attempts).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..physics import ball_model
from ..physics.field import FieldGeometry
from ..physics.params import BallParams
from ..physics.state import TEAMS, WorldState


@dataclass(frozen=True)
class StatsParams:
    """Attributes: shot_margin_m (m beyond each post that still counts as a shot),
    pass_lane_m (teammate within this of the kick's path: a pass, m), goal_lane_m (the
    same for kicks towards the goal mouth, m), min_pass_m (m),
    control_steps (consecutive dribbler steps for control), pass_timeout_s (s)."""

    shot_margin_m: float = 0.25
    pass_lane_m: float = 0.5
    goal_lane_m: float = 0.2
    min_pass_m: float = 0.3
    control_steps: int = 6
    pass_timeout_s: float = 4.0


@dataclass
class TeamStats:
    kicks: int = 0
    shots: int = 0
    goals: int = 0
    passes_attempted: int = 0
    passes_completed: int = 0
    passes_intercepted: int = 0
    passes_lost: int = 0
    interceptions: int = 0

    def to_dict(self) -> dict:
        d = dict(self.__dict__)
        d["pass_completion"] = (self.passes_completed / self.passes_attempted) if self.passes_attempted else None
        return d


@dataclass
class _OpenPass:
    team: str
    kicker: int
    t: float


@dataclass
class MatchStatsTracker:
    """Event tracker over a match (see the module docstring). Call :meth:`observe` once
    per env step with ``env.world_state()`` and that step's events."""

    field: FieldGeometry
    ball: BallParams = field(default_factory=BallParams)
    params: StatsParams = field(default_factory=StatsParams)

    def __post_init__(self) -> None:
        self.reset()

    def reset(self) -> None:
        self.teams = {t: TeamStats() for t in TEAMS}
        self._open: _OpenPass | None = None
        self._held: dict[tuple[str, int], int] = {}
        self.log: list[dict] = []  # [{"t", "type", "team", ...}] of passes, shots and goals, in order

    # -------------------------------------------------------------- helpers
    def classify_kick(self, world: WorldState, team: str, kicker: int) -> str:
        """"shot", "pass" or "clear" for a kick by ``team``'s robot ``kicker`` (field frame)."""
        p = np.asarray(world.ball_pos, float)
        v = np.asarray(world.ball_vel, float)
        sp = float(np.hypot(*v))
        if sp < 1e-6:
            return "clear"
        u = v / sp
        side = 1.0 if team == "blue" else -1.0
        x_goal = side * self.field.half_length
        at_goal = False
        if u[0] * side > 1e-6:
            y = p[1] + (x_goal - p[0]) / u[0] * u[1]
            at_goal = abs(y) <= self.field.goal_width / 2.0 + self.params.shot_margin_m
        reach = ball_model.stop_distance(sp, self.ball) + self.params.pass_lane_m
        lane = self.params.goal_lane_m if at_goal else self.params.pass_lane_m
        mates = world.team(team).pos
        for k, m in enumerate(mates):
            if k == kicker:
                continue
            rel = np.asarray(m, float) - p
            along = float(rel @ u)
            lateral = abs(float(rel[0] * u[1] - rel[1] * u[0]))
            if self.params.min_pass_m <= along <= reach and lateral <= lane:
                return "pass"
        return "shot" if at_goal else "clear"

    def _close(self, outcome: str, by: tuple[str, int] | None, t: float) -> None:
        op = self._open
        if op is None:
            return
        s = self.teams[op.team]
        if outcome == "completed":
            s.passes_completed += 1
        elif outcome == "intercepted":
            s.passes_intercepted += 1
            if by is not None:
                self.teams[by[0]].interceptions += 1
        else:
            s.passes_lost += 1
        self.log.append({"t": t, "type": "pass_" + outcome, "team": op.team, "kicker": op.kicker,
                         "by": list(by) if by else None})
        self._open = None

    def _touch(self, team: str, idx: int, t: float) -> None:
        """Robot (team, idx) took control of or kicked the ball: ends an open pass."""
        op = self._open
        if op is None:
            return
        if team != op.team:
            self._close("intercepted", (team, idx), t)
        elif idx != op.kicker:
            self._close("completed", (team, idx), t)
        else:
            self._close("lost", (team, idx), t)

    # ------------------------------------------------------------- the step
    def observe(self, world: WorldState, events: list[dict] | tuple = ()) -> None:
        if world.frame != "field":
            raise ValueError(f"MatchStatsTracker.observe needs a field-frame snapshot, got frame={world.frame!r}")
        t = float(world.t)
        for e in events:
            kind = e.get("type")
            if kind == "kick":
                team, idx = e["agent"].rsplit("_", 1)
                idx = int(idx)
                self._touch(team, idx, t)
                s = self.teams[team]
                s.kicks += 1
                what = self.classify_kick(world, team, idx)
                if what == "shot":
                    s.shots += 1
                    self.log.append({"t": t, "type": "shot", "team": team, "kicker": idx})
                elif what == "pass":
                    s.passes_attempted += 1
                    self._open = _OpenPass(team, idx, t)
                    self.log.append({"t": t, "type": "pass", "team": team, "kicker": idx})
                self._held.clear()
            elif kind == "goal":
                self.teams[e["team"]].goals += 1
                self.log.append({"t": t, "type": "goal", "team": e["team"]})
                self._close("lost", None, t)
                self._held.clear()
            elif kind in ("ball_out", "no_progress"):  # the referee restarts play
                self._close("lost", None, t)
                if kind == "no_progress":
                    self.log.append({"t": t, "type": "no_progress"})
                self._held.clear()
        held = {}
        for team in TEAMS:
            for i in np.flatnonzero(world.team(team).ball_on_dribbler):
                key = (team, int(i))
                held[key] = self._held.get(key, 0) + 1
                if held[key] == self.params.control_steps:
                    self._touch(team, int(i), t)
        self._held = held
        if self._open is not None and t - self._open.t > self.params.pass_timeout_s:
            self._close("lost", None, t)

    def summary(self) -> dict[str, dict]:
        """{team: TeamStats as a dict with pass_completion}."""
        return {t: s.to_dict() for t, s in self.teams.items()}


def summarize_stats(per_match: list[dict[str, dict]]) -> dict:
    """Series totals from per-match :meth:`MatchStatsTracker.summary` dicts:
    ``{"blue": {...sums..., "pass_completion", "goals_per_match"}, "yellow": {...}}``."""
    out: dict[str, dict] = {}
    n = max(len(per_match), 1)
    for team in TEAMS:
        keys = [k for k in TeamStats().__dict__]
        tot = {k: int(sum(m.get(team, {}).get(k, 0) for m in per_match)) for k in keys}
        tot["pass_completion"] = (tot["passes_completed"] / tot["passes_attempted"]) if tot["passes_attempted"] else None
        tot["goals_per_match"] = tot["goals"] / n
        tot["passes_per_match"] = tot["passes_attempted"] / n
        out[team] = tot
    return out


__all__ = ["StatsParams", "TeamStats", "MatchStatsTracker", "summarize_stats"]
