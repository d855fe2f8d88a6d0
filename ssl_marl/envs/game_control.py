"""SSL game control of the match task: referee commands, free kicks and fouls.

Switched on by ``MatchRules.ssl_restarts`` (commands and free kicks) and
``MatchRules.fouls`` (the fouls below); both off, the match task restarts play as in
:mod:`ssl_marl.envs.referee` and nothing here runs. Rules from the SSL rules
(RoboCup-SSL/ssl-rules; docs/references.md, "SSL rules"):

Commands (:class:`RefereeState`, field frame)
    ``RUNNING``: play on. ``KICKOFF(team)``: after a goal (to the team that conceded)
    and at the start of each half (blue first, yellow after half-time). ``STOP``: before
    every free kick, ``stop_s`` long, announcing it (``next_command``, ``next_team``); all
    robots keep ``RESTART_CLEARANCE`` (0.5 m) from the ball. ``FREE_KICK(team)``: the
    kicking team's robots may approach the ball, the other team keeps 0.5 m. A kickoff or
    free kick is taken once the ball has moved ``IN_PLAY_DISTANCE`` (0.05 m, the rules'
    "ball in play") from its spot; after ``free_kick_timeout_s`` without that, play runs
    on (the rules' timeout for taking a free kick, 10 s in Division B). While STOP holds, a ball moved by a
    robot is put back on its spot.
Free kick after ball out, no progress or a foul
    To the team that did not touch the ball last. Ball placement is automatic: the
    ball is put on the spot of :func:`~ssl_marl.envs.referee.free_kick_spot` with
    ``ssl_restarts`` (as the SSL game controller places it: where the foul or the
    stalled ball was, or where the ball left over a touch line, 0.2 m inside the lines
    and at least 1 m outside both defense areas; over a goal line, the corner spot 0.2 m
    from the touch line and 0.2 m from the goal line, or 1 m from it for the goal kick
    of the team defending that goal), else of :func:`~ssl_marl.envs.referee.placement_point`
    (0.2 m inside the lines and out of both defense areas); robots within 0.5 m are
    moved out to 0.5 m (plus up to ``restart_jitter_m``, at a seeded random angle offset).
Touches
    A robot touches the ball when the ball is on its dribbler face or its centre is
    within robot radius + ball radius + ``TOUCH_MARGIN`` of the ball's centre, or when
    it kicks. The last toucher's team decides free kicks.
Fouls (event ``foul`` with ``foul``: the name below, ``team``: the offender's team;
free kick for the other team at the foul's spot)
    ``excessive_dribbling``: a robot keeps touching the ball while it has moved more
    than ``MAX_DRIBBLE_M`` (1 m) from where the robot gained it. ``double_touch``: the
    robot that took a kickoff or free kick touches the ball again (after letting go of
    it) before any other robot has, or is still in contact with the ball when it has
    moved ``IN_PLAY_DISTANCE`` from its spot (the rules: "remaining in contact with the
    ball for more than 0.05 m counts as double touch"): on its dribbler, or in body
    contact with the ball not leaving it faster than ``SEPARATING_M_S`` (radially,
    relative to the robot; a kick in that step lets go). ``attacker_in_defense_area``: a
    robot touches the ball while the ball is inside the opponent's defense area.
    ``defender_too_close``: while a kickoff or free kick is not taken yet, a robot of
    the other team comes closer to the ball than :data:`DEFENDER_TOO_CLOSE_M` (the
    rules' "Defender Too Close To Ball"). The centre distance is measured, as the
    placement measures its 0.5 m (the rules measure from the robot's body; the
    placement would break that at once), less 0.02 m of tolerance (TIGERs' autoref
    margin). Consequence: STOP, then the same kickoff or free kick again (ER-Force's
    autoref, docs/references.md), robots within 0.5 m moved out as at every restart.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..physics.field import FieldGeometry
from ..physics.params import RobotParams
from ..physics.state import WorldState
from .referee import RESTART_CLEARANCE, placement_spot

RUNNING, STOP, KICKOFF, FREE_KICK = "RUNNING", "STOP", "KICKOFF", "FREE_KICK"
COMMANDS = (RUNNING, STOP, KICKOFF, FREE_KICK)
IN_PLAY_DISTANCE = 0.05  #: m the ball moves from its spot for a kickoff / free kick to be taken (rules)
#: m/s: a ball leaving a robot faster than this (radially, relative to it) is let go, not carried
SEPARATING_M_S = 0.3
MAX_DRIBBLE_M = 1.0  #: m: the rules' limit on dribbling the ball
#: the env options that switch SSL game control on (commands, free kicks and fouls)
SSL_GAME_CONTROL = {"ssl_restarts": True, "fouls": True}
TOUCH_MARGIN = 0.01  #: m of slack on body contact (solver slop and one tick of motion)
TOUCH_MAX_HEIGHT_M = 0.15  #: m: a ball higher than this passes over the robots (rules: robots fit under 0.15 m)
#: m, ball to robot centre: closer than this at the other team's kickoff or free kick is a foul
DEFENDER_TOO_CLOSE_M = RESTART_CLEARANCE - 0.02


def touch_reach(robot_radius: float, ball_radius: float) -> float:
    """Centre distance (m) within which a robot body touches the ball."""
    return robot_radius + ball_radius + TOUCH_MARGIN


def touching_robots(pos: np.ndarray, ball_pos: np.ndarray, ball_height: float, on_dribbler: np.ndarray,
                    reach: float) -> np.ndarray:
    """(n,) bool: robots at ``pos`` (n, 2) that touch the ball at ``ball_pos`` (2,), ``ball_height``
    (m) high: the ball on the dribbler (``on_dribbler`` (n,)), or a ball no higher than
    :data:`TOUCH_MAX_HEIGHT_M` within ``reach`` (:func:`touch_reach`) of the robot's centre."""
    d = pos - ball_pos[None, :]
    return ((d[:, 0] ** 2 + d[:, 1] ** 2 <= reach ** 2) & (ball_height <= TOUCH_MAX_HEIGHT_M)) | on_dribbler
FOULS = ("excessive_dribbling", "double_touch", "attacker_in_defense_area", "defender_too_close")


def too_close_to_kick_point(pos: np.ndarray, spot: np.ndarray, limit: float = DEFENDER_TOO_CLOSE_M) -> int | None:
    """Index of the robot of ``pos`` (n, 2; m, the defending team) nearest the ball's
    ``spot`` (2,) if it is closer than ``limit`` (m, centre distance), else None."""
    if len(pos) == 0:
        return None
    d2 = (pos[:, 0] - spot[0]) ** 2 + (pos[:, 1] - spot[1]) ** 2
    i = int(np.argmin(d2))
    return i if d2[i] < limit * limit else None


def kicked_rows(events: list[dict], agent_index) -> list[int]:
    """Rows (``agent_index(agent)``, blue first) of the robots that kicked in ``events``."""
    return [agent_index(e["agent"]) for e in events if e["type"] == "kick"]


def other(team: str) -> str:
    return "yellow" if team == "blue" else "blue"


@dataclass(frozen=True)
class RefereeState:
    """What the referee tells the teams (field frame).

    Attributes:
        command: one of ``COMMANDS``.
        team: the team a KICKOFF / FREE_KICK is for (None for RUNNING and STOP).
        position: the designated ball position (m, field frame) of a restart, or None.
        since: simulated time (s) the command was given.
        next_command, next_team: during a STOP, the set piece that follows it and its team
            (the SSL referee message's ``next_command``), else None.
    """

    command: str = RUNNING
    team: str | None = None
    position: tuple[float, float] | None = None
    since: float = 0.0
    next_command: str | None = None
    next_team: str | None = None

    def must_keep_clear(self, team: str) -> bool:
        """True when ``team``'s robots must keep 0.5 m from the ball: STOP, or a
        kickoff / free kick for the other team."""
        return self.command == STOP or (self.command in (KICKOFF, FREE_KICK) and self.team != team)

    def is_set_piece_for(self, team: str) -> bool:
        """True during a kickoff or free kick for ``team`` (not yet taken)."""
        return self.command in (KICKOFF, FREE_KICK) and self.team == team

    def to_dict(self) -> dict:
        return {"command": self.command, "team": self.team,
                "position": None if self.position is None else list(self.position), "since": self.since,
                "next_command": self.next_command, "next_team": self.next_team}


class TouchWatch:
    """Who touches the ball, the last toucher, and the dribbling and double-touch
    fouls (module docstring). One world; robots in the engine's row order (blue first)."""

    def __init__(self, n_blue: int, n_yellow: int, robot_radius: float, ball_radius: float) -> None:
        self.teams = np.array(["blue"] * n_blue + ["yellow"] * n_yellow)
        self.reach = touch_reach(robot_radius, ball_radius)
        self.reset()

    def reset(self) -> None:
        """Forget every touch (after a placement)."""
        self.last_robot: int | None = None
        self.dribbler: int | None = None
        self.dribble_start = np.zeros(2)
        self.guard: int | None = None  #: the taker of the last restart, until another robot touches
        self.guard_released = False  #: the taker has let go of the ball since taking it

    def touching(self, ws: WorldState, kicked: list[int]) -> np.ndarray:
        """(n,) bool: robots touching the ball in snapshot ``ws`` (field frame) or
        kicking it this step (rows in ``kicked``)."""
        touch = touching_robots(np.concatenate([ws.blue.pos, ws.yellow.pos]), ws.ball_pos, ws.ball_height,
                                np.concatenate([ws.blue.ball_on_dribbler, ws.yellow.ball_on_dribbler]), self.reach)
        for i in kicked:
            touch[i] = True
        return touch

    def last_team(self) -> str | None:
        return None if self.last_robot is None else str(self.teams[self.last_robot])

    def update(self, ws: WorldState, touch: np.ndarray, field: FieldGeometry, fouls: bool,
               kicked: list[int] | tuple[int, ...] = ()) -> tuple[str, int] | None:
        """Record this tick's touches (``kicked``: rows that kicked the ball this tick);
        returns (foul name, offending robot row) or None. Of several robots that come into
        contact in one tick, the last toucher is the one that kicked, else the one nearest
        the ball (exact ties: the lower row), so the robot order favours neither team."""
        idx = np.flatnonzero(touch)
        if self.guard is not None and self.guard not in idx:
            self.guard_released = True
        foul = None
        for i in idx.tolist():
            if fouls and self._in_opponent_defense(ws.ball_pos, field, str(self.teams[i])):
                foul = foul or ("attacker_in_defense_area", i)
            if self.guard is not None:
                if i != self.guard:
                    self.guard = None
                elif self.guard_released and fouls:
                    foul = foul or ("double_touch", i)
        if self.dribbler is not None and self.dribbler not in idx:
            self.dribbler = None
        if self.dribbler is None and idx.size == 1:
            self.dribbler, self.dribble_start = int(idx[0]), ws.ball_pos.copy()
        elif idx.size > 1:
            self.dribbler = None  # a contested ball is nobody's dribble
        if fouls and self.dribbler is not None and np.hypot(*(ws.ball_pos - self.dribble_start)) > MAX_DRIBBLE_M:
            foul = foul or ("excessive_dribbling", self.dribbler)
        fresh = [i for i in idx.tolist() if i != self.last_robot]
        if fresh:  # the latest robot to come into contact is the last toucher
            fresh = [i for i in fresh if i in kicked] or fresh
            if len(fresh) > 1:
                pos = np.concatenate([ws.blue.pos, ws.yellow.pos])[fresh]
                fresh = [fresh[int(np.argmin(((pos - ws.ball_pos[None, :]) ** 2).sum(1)))]]
            self.last_robot = int(fresh[0])
        return foul

    def taken_by(self, robot: int | None) -> None:
        """A kickoff / free kick was taken by ``robot`` (row): guard against its double touch."""
        self.guard, self.guard_released = robot, False

    def carries(self, ws: WorldState, robot: int, kicked: list[int] | tuple[int, ...] = ()) -> bool:
        """Whether ``robot`` (row) holds the ball in snapshot ``ws`` (field frame): the ball
        on its dribbler, or in body contact not leaving it faster than
        :data:`SEPARATING_M_S`; never when it kicked the ball this step (``kicked`` rows)."""
        if robot in kicked:
            return False
        pos = np.concatenate([ws.blue.pos, ws.yellow.pos])[robot]
        vel = np.concatenate([ws.blue.vel, ws.yellow.vel])[robot]
        on = bool(np.concatenate([ws.blue.ball_on_dribbler, ws.yellow.ball_on_dribbler])[robot])
        if not touching_robots(pos[None, :], ws.ball_pos, ws.ball_height, np.array([on]), self.reach)[0]:
            return False
        d = ws.ball_pos - pos
        radial = float((ws.ball_vel - vel) @ d) / max(float(np.hypot(*d)), 1e-9)
        return on or radial < SEPARATING_M_S

    @staticmethod
    def _in_opponent_defense(ball_pos: np.ndarray, field: FieldGeometry, team: str) -> bool:
        return bool(field.in_defense_area(ball_pos, 1 if team == "blue" else -1))


def jittered_clearance(point: np.ndarray, robot_pos: np.ndarray, field: FieldGeometry, clearance: float,
                       jitter_m: float, rng: np.random.Generator, robot_radius: float | None = None) -> np.ndarray:
    """Robots within ``clearance`` of ``point`` moved out to ``clearance`` + U(0,
    ``jitter_m``) m, in their own direction turned by a random angle of up to +-0.5
    rad (seeded ``rng``); kept inside the walled area and clear of the other robots of
    radius ``robot_radius`` (m, default :class:`~ssl_marl.physics.params.RobotParams`'s;
    :func:`~ssl_marl.envs.referee.placement_spot`). Returns new (n, 2) positions."""
    robot_radius = RobotParams().radius if robot_radius is None else robot_radius
    pos = np.array(robot_pos, dtype=float, copy=True)
    d = pos - point[None, :]
    dist = np.hypot(d[:, 0], d[:, 1])
    for i in np.flatnonzero(dist < clearance):
        a = (np.arctan2(d[i, 1], d[i, 0]) if dist[i] > 1e-9 else rng.uniform(-np.pi, np.pi)) + rng.uniform(-0.5, 0.5)
        r = clearance + rng.uniform(0.0, jitter_m)
        pos[i] = placement_spot(point, float(a), float(r), pos, int(i), field, robot_radius)
    return pos


def jittered_kickoff(poses: np.ndarray, n_blue: int, field: FieldGeometry, jitter_m: float,
                     rng: np.random.Generator, robot_radius: float) -> np.ndarray:
    """Kickoff poses (field frame, (n, 3), blue rows first) each moved by U(-j, j) m in
    x and y and U(-0.2, 0.2) rad, then held in the legal region: the own half (at
    least a robot radius from the half-way line), outside the centre circle, outside
    the own defense area (the keeper, row 0 of each team, stays inside it), and
    inside the field."""
    out = np.array(poses, dtype=float, copy=True)
    n = len(out)
    out[:, 0:2] += rng.uniform(-jitter_m, jitter_m, (n, 2))
    out[:, 2] += rng.uniform(-0.2, 0.2, n)
    L2, W2 = field.half_length, field.half_width
    for i in range(n):
        side = -1.0 if i < n_blue else 1.0  # own half
        keeper = i in (0, n_blue)
        x, y = out[i, 0], out[i, 1]
        x = side * min(max(side * x, robot_radius), L2 - robot_radius)
        y = float(np.clip(y, -W2 + robot_radius, W2 - robot_radius))
        if keeper:
            x = side * min(max(side * x, L2 - field.defense_depth + robot_radius), L2 - robot_radius)
            y = float(np.clip(y, -field.defense_width / 2 + robot_radius, field.defense_width / 2 - robot_radius))
        else:
            if field.in_defense_area(np.array([x, y]), int(side), margin=robot_radius):
                x = side * (L2 - field.defense_depth - robot_radius - 0.01)
            r = np.hypot(x, y)
            keep = field.center_circle_radius + robot_radius + 0.01
            if r < keep:
                u = np.array([x, y]) / r if r > 1e-9 else np.array([side, 0.0])
                if u[0] * side < 0.1:
                    u = np.array([side, u[1]]) / np.hypot(side, u[1])
                x, y = keep * u
        out[i, 0], out[i, 1] = x, y
    return out


__all__ = ["RefereeState", "TouchWatch", "SSL_GAME_CONTROL", "kicked_rows", "jittered_clearance", "jittered_kickoff", "too_close_to_kick_point",
           "COMMANDS", "FOULS", "DEFENDER_TOO_CLOSE_M", "RUNNING",
           "STOP", "KICKOFF", "FREE_KICK", "IN_PLAY_DISTANCE", "SEPARATING_M_S", "MAX_DRIBBLE_M", "other"]
