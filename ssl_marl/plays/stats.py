"""Match statistics from what the referee sees: kicks, shots, passes, interceptions, goals.

:class:`MatchStatsTracker` observes every step's ground-truth world (field frame) and the
env's events (``"kick"`` with the kicking agent, ``"goal"``, ``"ball_out"``,
``"no_progress"``); it knows
nothing of either team's plans, so it rates a passing team and a no-pass team by the
same rules:

* **Pass attempt**: a kick whose straight path passes within ``pass_lane_m`` of a
  teammate (not the kicker) standing between ``min_pass_m`` and the ball's stop
  distance (+ ``pass_lane_m``) ahead; for a kick towards the goal mouth the teammate
  must be within ``goal_lane_m`` (it stands right on the line: a pass, not a shot). A
  flat kick must also reach that teammate no faster than ``pass_max_arrive_speed``
  (4 m/s, by the ball model): TIGERs kick a straight pass to arrive at <= 3.2 m/s
  (docs/references.md, "Passing and pass rating"), so a full-power clearance or a stray
  shot that runs past a teammate is not a pass. A chip (``ball_vz > 0``) towards a
  teammate is a pass at any speed (its ground speed drops at each bounce).
* **Shot**: any other kick whose straight path crosses the opponent goal line within
  the posts widened by ``shot_margin_m`` on each side and that would reach that line
  (the ball model's stop distance covers the path to it; a chip, ``ball_vz > 0``,
  counts at any speed): a tap that dies on the way, e.g. a dribbler's push ahead of
  the 1 m dribbling limit, is not a shot. Kicks aimed at nobody and not at the goal
  (clearances) and taps short of the goal count only as kicks.
* **Control**: a robot holds the ball on its dribbler for ``control_steps``
  consecutive steps (0.1 s at 60 Hz), so a deflection is not control.
* A pass ends at the first control or kick by another robot (robots taking control in the same
  step: the one nearest the ball first, whatever its team): a teammate -> **completed**
  (a one-touch redirect counts); an opponent -> **intercepted** (the opponent's
  ``interceptions`` + 1). A goal, the ball leaving the field, the kicker itself taking
  the ball back, or ``pass_timeout_s`` without a control end it as **lost** (the log's
  ``pass_lost`` entry says which: ``why`` "goal", "ball_out", "no_progress", "foul",
  "kicker" or "timeout").
* **Goals** come from the referee's goal events.
* **Kinds** of kicks, from what the physics reports of a kick (the kick event, the
  ball's vertical velocity ``ball_vz`` right after it, the ball's speed the step
  before): a **chip** when ``ball_vz > 0`` after the kick (the kick had a chip
  angle); a **redirect** when the ball arrived at more than ``redirect_speed``
  (1 m/s) and was not on the kicker's dribbler the step before -- a kick fired
  on contact with a moving ball, the one-touch play; else **direct**. Passes are ``chip`` or ``flat`` (every other pass). Shots are
  ``redirect``, ``after_chip_pass`` (the kicker received a completed chip pass
  and kept the ball until the shot) or ``direct``. A goal takes the kind of its
  team's last shot since the last restart (``other`` without one). A shot's log entry
  says where it was taken (:meth:`MatchStatsTracker.shot_geometry`: distance to the goal
  centre, the open goal angle).

Per team (:meth:`MatchStatsTracker.summary`): ``kicks``, ``shots``, ``goals``,
``passes_attempted``, ``passes_completed``, ``passes_intercepted`` (own passes the
opponent took), ``passes_lost``, ``interceptions`` (opponent passes this team took),
``pass_completion`` (completed / attempted, None without attempts); by kind:
``shots_direct`` / ``_redirect`` / ``_after_chip_pass``, ``goals_direct`` / ``_redirect``
/ ``_after_chip_pass`` / ``_other``, ``passes_flat_attempted`` / ``_completed``,
``passes_chip_attempted`` / ``_completed`` and the completions ``pass_completion_flat`` /
``pass_completion_chip``. Under SSL game control (``referee`` events): ``set_pieces``
(kickoffs and free kicks awarded), ``set_piece_passes`` / ``set_piece_chips`` /
``set_piece_shots`` (what the team's first kick after one was; chips are among the
passes) and ``goals_set_piece`` (goals of a possession that began with the team's
set-piece kick: no restart and no opponent kick or control in between).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..envs.game_control import FREE_KICK, KICKOFF
from ..physics import ball_model
from ..physics.field import FieldGeometry
from ..physics.params import BallParams, RobotParams
from ..physics.state import TEAMS, WorldState, to_team_frame


@dataclass(frozen=True)
class StatsParams:
    """Attributes: shot_margin_m (m beyond each post that still counts as a shot),
    pass_lane_m (teammate within this of the kick's path: a pass, m), goal_lane_m (the
    same for kicks towards the goal mouth, m), min_pass_m (m),
    control_steps (consecutive dribbler steps for control), pass_timeout_s (s),
    redirect_speed (a kick of a ball arriving faster than this is a redirect, m/s),
    pass_max_arrive_speed (a flat kick reaching the teammate faster than this is not a
    pass, m/s)."""

    shot_margin_m: float = 0.25
    pass_lane_m: float = 0.5
    goal_lane_m: float = 0.2
    min_pass_m: float = 0.3
    control_steps: int = 6
    pass_timeout_s: float = 4.0
    redirect_speed: float = 1.0
    pass_max_arrive_speed: float = 4.0


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
    shots_direct: int = 0
    shots_redirect: int = 0
    shots_after_chip_pass: int = 0
    goals_direct: int = 0
    goals_redirect: int = 0
    goals_after_chip_pass: int = 0
    goals_other: int = 0
    passes_flat_attempted: int = 0
    passes_flat_completed: int = 0
    passes_chip_attempted: int = 0
    passes_chip_completed: int = 0
    set_pieces: int = 0
    set_piece_passes: int = 0
    set_piece_chips: int = 0
    set_piece_shots: int = 0
    goals_set_piece: int = 0

    def to_dict(self) -> dict:
        d = dict(self.__dict__)
        return {**d, **completions(d)}


def completions(d: dict) -> dict:
    """pass_completion (all), pass_completion_flat, pass_completion_chip from the counts
    in ``d`` (None without attempts)."""
    rate = (lambda done, tried: done / tried if tried else None)
    return {"pass_completion": rate(d["passes_completed"], d["passes_attempted"]),
            "pass_completion_flat": rate(d["passes_flat_completed"], d["passes_flat_attempted"]),
            "pass_completion_chip": rate(d["passes_chip_completed"], d["passes_chip_attempted"])}


@dataclass
class _OpenPass:
    team: str
    kicker: int
    t: float
    kind: str = "flat"


def kick_path_offsets(world: WorldState, team: str, kicker: int) -> list[tuple[int, float, float]]:
    """``(teammate, along, lateral)`` for each of ``team``'s robots but ``kicker``: its
    distance along the ball's straight path from the ball and its distance from that path
    (m, field frame); empty while the ball is still."""
    p = np.asarray(world.ball_pos, float)
    v = np.asarray(world.ball_vel, float)
    sp = float(np.hypot(*v))
    if sp < 1e-6:
        return []
    u = v / sp
    out = []
    for k, m in enumerate(world.team(team).pos):
        if k != kicker:
            rel = np.asarray(m, float) - p
            out.append((k, float(rel @ u), abs(float(rel[0] * u[1] - rel[1] * u[0]))))
    return out


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
        self._prev_speed = 0.0  # m/s, ball speed at the previous observation
        self._chip_receiver: tuple[str, int] | None = None  # got a completed chip pass, has not kicked since
        self._last_shot_kind: dict[str, str | None] = {t: None for t in TEAMS}
        self._set_piece_for: str | None = None  # awarded a kickoff / free kick, not kicked yet
        self._set_piece_chain: str | None = None  # its possession began with its set-piece kick

    # -------------------------------------------------------------- helpers
    def shot_geometry(self, world: WorldState, team: str, kicker: int) -> dict:
        """Where ``team``'s robot ``kicker`` shoots from (field frame): ``dist_m``, the ball's
        distance to the centre of the goal it attacks (m), and ``open_rad``, the widest part
        of that goal mouth not shadowed by another robot, seen from the ball (rad;
        :func:`~ssl_marl.plays.pass_decision.open_goal_interval`, robots of the default size)."""
        from .pass_decision import open_goal_interval

        tw = to_team_frame(world, team)  # the goal it attacks at +x
        ball = np.asarray(tw.ball_pos, float)
        others = np.concatenate([np.delete(tw.team(team).pos, kicker, axis=0), tw.opponents(team).pos]).reshape(-1, 2)
        open_rad, _ = open_goal_interval(ball, others, self.field, RobotParams(), self.ball)
        return {"dist_m": round(float(np.hypot(*(self.field.goal_center(+1) - ball))), 3),
                "open_rad": round(float(open_rad), 4)}

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
        at_goal, to_goal = False, np.inf
        if u[0] * side > 1e-6:
            to_goal = (x_goal - p[0]) / u[0]
            y = p[1] + to_goal * u[1]
            at_goal = abs(y) <= self.field.goal_width / 2.0 + self.params.shot_margin_m
        stop = ball_model.stop_distance(sp, self.ball)
        reach = stop + self.params.pass_lane_m
        lane = self.params.goal_lane_m if at_goal else self.params.pass_lane_m
        for _, along, lateral in kick_path_offsets(world, team, kicker):
            if self.params.min_pass_m <= along <= reach and lateral <= lane and (
                    world.ball_vz > 0.0
                    or ball_model.speed_at_distance(sp, along, self.ball) <= self.params.pass_max_arrive_speed):
                return "pass"
        reaches_goal = world.ball_vz > 0.0 or stop >= to_goal
        return "shot" if at_goal and reaches_goal else "clear"

    def _close(self, outcome: str, by: tuple[str, int] | None, t: float, why: str | None = None) -> None:
        """End the open pass as "completed", "intercepted" or "lost" (``why``: what ended a
        lost pass, logged: "kicker", "timeout", "goal", "ball_out", "no_progress", "foul")."""
        op = self._open
        if op is None:
            return
        s = self.teams[op.team]
        if outcome == "completed":
            s.passes_completed += 1
            setattr(s, f"passes_{op.kind}_completed", getattr(s, f"passes_{op.kind}_completed") + 1)
            if op.kind == "chip" and by is not None:
                self._chip_receiver = by
        elif outcome == "intercepted":
            s.passes_intercepted += 1
            if by is not None:
                self.teams[by[0]].interceptions += 1
        else:
            s.passes_lost += 1
        self.log.append({"t": t, "type": "pass_" + outcome, "team": op.team, "kicker": op.kicker,
                         "by": list(by) if by else None, **({"why": why} if why else {})})
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
            self._close("lost", (team, idx), t, "kicker")

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
                redirect = self._prev_speed > self.params.redirect_speed and (team, idx) not in self._held
                if what == "shot":
                    s.shots += 1
                    shot = ("redirect" if redirect else "after_chip_pass" if self._chip_receiver == (team, idx)
                            else "direct")
                    setattr(s, f"shots_{shot}", getattr(s, f"shots_{shot}") + 1)
                    self._last_shot_kind[team] = shot
                    self.log.append({"t": t, "type": "shot", "team": team, "kicker": idx, "kind": shot,
                                     **self.shot_geometry(world, team, idx)})
                elif what == "pass":
                    s.passes_attempted += 1
                    pk = "chip" if world.ball_vz > 0.0 else "flat"
                    setattr(s, f"passes_{pk}_attempted", getattr(s, f"passes_{pk}_attempted") + 1)
                    self._open = _OpenPass(team, idx, t, pk)
                    self.log.append({"t": t, "type": "pass", "team": team, "kicker": idx, "kind": pk})
                self._set_piece_kick(team, what, world)
                if self._chip_receiver == (team, idx):
                    self._chip_receiver = None
                self._held.clear()
            elif kind == "referee" and e.get("command") in (KICKOFF, FREE_KICK) and e.get("team") in TEAMS:
                self.teams[e["team"]].set_pieces += 1
                self._set_piece_for, self._set_piece_chain = e["team"], None
            elif kind == "goal":
                gs = self.teams[e["team"]]
                gs.goals += 1
                gs.goals_set_piece += int(self._set_piece_chain == e["team"])
                gk = self._last_shot_kind[e["team"]] or "other"
                setattr(gs, f"goals_{gk}", getattr(gs, f"goals_{gk}") + 1)
                self.log.append({"t": t, "type": "goal", "team": e["team"], "kind": gk})
                self._restarted()
                self._close("lost", None, t, "goal")
                self._held.clear()
            elif kind in ("ball_out", "no_progress", "foul"):  # the referee restarts play
                self._restarted()
                self._close("lost", None, t, kind)
                if kind == "no_progress":
                    self.log.append({"t": t, "type": "no_progress"})
                self._held.clear()
        held, controls = {}, []
        for team in TEAMS:
            pos = world.team(team).pos
            for i in np.flatnonzero(world.team(team).ball_on_dribbler):
                key = (team, int(i))
                held[key] = self._held.get(key, 0) + 1
                if held[key] == self.params.control_steps:
                    controls.append((float(np.hypot(*(pos[i] - world.ball_pos))), key))
        for _, (team, i) in sorted(controls):  # robots taking control in the same step: the nearest first
            self._touch(team, i, t)
            self._end_set_piece_chain_unless(team)
        self._held = held
        if self._open is not None and t - self._open.t > self.params.pass_timeout_s:
            self._close("lost", None, t, "timeout")
        self._prev_speed = float(np.hypot(*world.ball_vel))

    def _set_piece_kick(self, team: str, what: str, world: WorldState) -> None:
        """A kick by ``team`` ("shot" / "pass" / "clear"): the awarded set piece's kick, or
        the opponent's kick that ends a set-piece possession."""
        if self._set_piece_for is not None:
            if team == self._set_piece_for:
                s = self.teams[team]
                s.set_piece_shots += int(what == "shot")
                s.set_piece_passes += int(what == "pass")
                s.set_piece_chips += int(what == "pass" and world.ball_vz > 0.0)
                self._set_piece_chain = team
            self._set_piece_for = None
        else:
            self._end_set_piece_chain_unless(team)

    def _end_set_piece_chain_unless(self, team: str) -> None:
        """``team`` kicked or controlled the ball: a set-piece possession of the other team ends."""
        if self._set_piece_chain not in (None, team):
            self._set_piece_chain = None

    def _restarted(self) -> None:
        self._set_piece_chain = None
        self._chip_receiver = None
        self._last_shot_kind = {t: None for t in TEAMS}

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
        tot.update(completions(tot))
        tot["goals_per_match"] = tot["goals"] / n
        tot["passes_per_match"] = tot["passes_attempted"] / n
        out[team] = tot
    return out


__all__ = ["StatsParams", "TeamStats", "MatchStatsTracker", "summarize_stats"]
