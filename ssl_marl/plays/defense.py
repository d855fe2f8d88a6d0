"""Defensive tactics: Goalie, Defender, Mark (team frame: own goal at -x; m, m/s, rad).

Geometry lives in pure functions (:func:`goalie_guard_position`,
:func:`block_position`, :func:`mark_position`) so plays can use the same points as
role-assignment targets.

Clearing (Goalie and Defender) is one shared sub-behaviour, :mod:`.clearing`: the
go-to-ball skill (learned or baseline) fetches the ball; once it is within 35 mm of
the dribbler the robot turns (dribbler on, at a gentle ``turn_rate``) until its
heading lies within ``kick_cone`` of +x (towards the opponent half) and kicks.

Numbers: defaults marked "hand-tuned" were set by watching matches in this simulator
(Division B field, default robot); the others cite their source.
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass

import numpy as np

from ..physics.field import FieldGeometry
from ..physics.params import RobotParams
from ..physics.state import WorldState
from ..skills.features import dribbler_ball_distance
from ..skills.navigation import NavigateToPoint, NavParams, defense_rect, facing_towards, push_out_of_rect
from .clearing import BallClearing, ClearPhase, clear_phase
from .tactic_base import NEAR_BALL_M, Tactic


# ----------------------------------------------------------------- geometry
def goalie_guard_position(ball_pos: np.ndarray, ball_vel: np.ndarray, field: FieldGeometry, rp: RobotParams,
                          radius: float = 0.4, shot_speed: float = 0.5, line_gap_m: float = 0.02,
                          mouth_margin_m: float = 0.1, ball_gap_m: float = 0.15) -> np.ndarray:
    """Where the goalie stands (team frame, m).

    * Shot: if the ball moves towards the own goal faster than ``shot_speed`` (m/s)
      and its straight path crosses the goal mouth (+ ``mouth_margin_m``), the point
      where the path meets the line just in front of the goal
      (x = -L/2 + robot radius + ``line_gap_m``).
    * Otherwise: on the arc of ``radius`` around the own goal centre, on the line from
      the goal centre to the ball (at most ``ball_gap_m`` short of the ball), kept in
      front of the goal line and within the posts.
    """
    L2, hw = field.half_length, field.goal_width / 2.0
    x_line = -L2 + rp.radius + line_gap_m
    b, v = np.asarray(ball_pos, float), np.asarray(ball_vel, float)
    if v[0] < -shot_speed and b[0] > x_line:
        t = (x_line - b[0]) / v[0]
        y = b[1] + v[1] * t
        if abs(y) <= hw + mouth_margin_m:
            return np.array([x_line, min(max(y, -hw), hw)])
    g = field.goal_center(-1)
    d = b - g
    dist = float(np.hypot(*d))
    u = d / dist if dist > 1e-6 else np.array([1.0, 0.0])
    r = min(radius, max(dist - ball_gap_m, 0.0))
    p = g + u * r
    return np.array([max(float(p[0]), x_line), min(max(float(p[1]), -hw), hw)])


def block_position(ball_pos: np.ndarray, field: FieldGeometry, standoff: float = 0.12,
                   lane_offset: float = 0.0) -> np.ndarray:
    """Defender spot (team frame, m): on the shot lane from the own goal centre to the
    ball, where it leaves the defense area grown by ``standoff`` (robot centre outside
    the area), shifted sideways by ``lane_offset`` (m, + = left looking from the goal
    to the ball) so that two defenders stand side by side, and kept outside the area."""
    gx = -field.half_length
    dx, dy = max(float(ball_pos[0]) - gx, 0.05), float(ball_pos[1])
    n = math.hypot(dx, dy)
    ux, uy = dx / n, dy / n
    hw = field.defense_width / 2.0 + standoff
    t = (field.defense_depth + standoff) / ux
    if abs(uy) > 1e-9:
        t = min(t, hw / abs(uy))
    p = np.array([gx + ux * t - lane_offset * uy, uy * t + lane_offset * ux])
    p = push_out_of_rect(p, defense_rect(field, -1, standoff))
    return field.clamp_to_field(p)


def mark_position(opp_pos: np.ndarray, ball_pos: np.ndarray, field: FieldGeometry, distance: float = 0.35,
                  ball_bias: float = 0.25) -> np.ndarray:
    """Marking spot (team frame, m): ``distance`` from the opponent towards the own goal
    centre, turned by ``ball_bias`` (0..1) towards the ball (to cut passes to it)."""
    ox, oy = float(opp_pos[0]), float(opp_pos[1])

    def unit(x: float, y: float) -> tuple[float, float]:
        n = math.hypot(x, y)
        return (x / n, y / n) if n > 1e-9 else (-1.0, 0.0)

    gx, gy = unit(-field.half_length - ox, -oy)
    bx, by = unit(float(ball_pos[0]) - ox, float(ball_pos[1]) - oy)
    dx, dy = unit((1.0 - ball_bias) * gx + ball_bias * bx, (1.0 - ball_bias) * gy + ball_bias * by)
    return field.clamp_to_field(np.array([ox + distance * dx, oy + distance * dy]))


# ------------------------------------------------------------------ Goalie
class GoalieState(enum.Enum):
    GUARD = "guard"
    CLEAR_APPROACH = "clear_approach"
    CLEAR_KICK = "clear_kick"


@dataclass(frozen=True)
class GoalieParams:
    """Attributes:
        guard_radius: arc radius around the own goal centre (m); hand-tuned: 0.4 m
            keeps the goalie inside the Division B defense area (1.0 m deep).
        shot_speed: ball speed towards the goal (m/s) above which it intercepts the
            path; hand-tuned (a rolling ball slower than this stops ~0.5 m later).
        line_gap_m, mouth_margin_m, ball_gap_m: :func:`goalie_guard_position`'s gaps
            (m); hand-tuned: 2 cm off the goal line, 10 cm beyond the posts, 15 cm
            short of the ball.
        slow_ball_speed: clear only a ball slower than this (m/s) inside the area;
            hand-tuned (a faster ball is intercepted instead).
        area_margin_m: the ball still counts as "near the area" up to this far
            outside it (m): hysteresis so a ball on the line does not flip
            guard/clear every tick; hand-tuned.
        guard_tolerance_m: position tolerance of the guard spot (m); hand-tuned.
        near_ball_m: d_{d-b} at which the ball counts as taken (m); the paper's 35 mm.
        kick_cone: clear when the heading is within this of +x (rad); hand-tuned:
            ~70 degrees, any kick into the opponent half's direction clears.
        kick_strength: clearing kick strength (0..1]; full.
        turn_rate: turning rate with the ball (rad/s); hand-tuned: slow enough that
            the dribbler keeps the ball.
    """

    guard_radius: float = 0.4
    shot_speed: float = 0.5
    line_gap_m: float = 0.02
    mouth_margin_m: float = 0.1
    ball_gap_m: float = 0.15
    slow_ball_speed: float = 0.6
    area_margin_m: float = 0.1
    guard_tolerance_m: float = 0.02
    near_ball_m: float = NEAR_BALL_M
    kick_cone: float = 1.2
    kick_strength: float = 1.0
    turn_rate: float = 3.0


@dataclass(frozen=True)
class GoalieInputs:
    """Attributes: ball_in_area (inside the own defense area), ball_near_area (inside it
    grown by ``area_margin_m``; hysteresis), ball_speed (m/s), d_db (m), kicked (last tick)."""

    ball_in_area: bool
    ball_near_area: bool
    ball_speed: float
    d_db: float
    kicked: bool = False


class Goalie(Tactic):
    """Stays between ball and own goal on an arc in front of it (inside the defense
    area); clears a slow ball out of the defense area towards the opponent half."""

    name = "goalie"
    uses_skills = ("go_to_ball",)
    State = GoalieState
    Params = GoalieParams
    Inputs = GoalieInputs
    initial_state = GoalieState.GUARD

    def __init__(self, field, robot=None, ball=None, skills="baseline", dt: float = 1.0 / 60.0, **params) -> None:
        super().__init__(field, robot, ball, skills, dt, **params)
        self.go_to_ball = self._skill("go_to_ball")
        self.clearing = BallClearing(self.go_to_ball, self.rp)
        self.nav = NavigateToPoint(field, self.rp, self.bp, NavParams(avoid_own_defense=False,
                                                                      avoid_opp_defense=True),
                                   tolerance=self.params.guard_tolerance_m)

    def observe(self, world: WorldState, robot: int) -> GoalieInputs:
        b = world.ball_pos
        return GoalieInputs(ball_in_area=bool(self.field.in_defense_area(b, -1)),
                            ball_near_area=bool(self.field.in_defense_area(b, -1, margin=self.params.area_margin_m)),
                            ball_speed=float(np.hypot(*world.ball_vel)),
                            d_db=dribbler_ball_distance(world, robot, self.rp, self.bp), kicked=self._kicked)

    @staticmethod
    def transition(state: GoalieState, inputs: GoalieInputs, params: GoalieParams) -> GoalieState:
        S = GoalieState
        if state is S.GUARD:
            if inputs.ball_in_area and inputs.ball_speed <= params.slow_ball_speed:
                return S.CLEAR_APPROACH
            return S.GUARD
        if state is S.CLEAR_APPROACH:
            if not inputs.ball_near_area:
                return S.GUARD
            phase = clear_phase(False, inputs.d_db, inputs.kicked, params)
            return S.CLEAR_KICK if phase is ClearPhase.KICK else S.CLEAR_APPROACH
        if state is S.CLEAR_KICK:
            phase = clear_phase(True, inputs.d_db, inputs.kicked, params)
            if phase is ClearPhase.DONE:
                return S.GUARD
            if phase is ClearPhase.LOST:
                return S.CLEAR_APPROACH if inputs.ball_near_area else S.GUARD
            return S.CLEAR_KICK
        raise ValueError(f"unknown state {state!r}")

    def on_enter(self, state: GoalieState) -> None:
        if state is GoalieState.CLEAR_APPROACH and hasattr(self, "clearing"):
            self.clearing.reset()

    def guard_target(self, world: WorldState) -> np.ndarray:
        p = self.params
        return goalie_guard_position(world.ball_pos, world.ball_vel, self.field, self.rp, p.guard_radius,
                                     p.shot_speed, p.line_gap_m, p.mouth_margin_m, p.ball_gap_m)

    def execute(self, world: WorldState, robot: int, inputs: GoalieInputs) -> np.ndarray:
        if self.state in (GoalieState.CLEAR_APPROACH, GoalieState.CLEAR_KICK):
            return self.clearing.act(self.state is GoalieState.CLEAR_KICK, world, robot, self.params)
        pos = world.team(world.frame).pos[robot]
        self.nav.target = self.guard_target(world)
        self.nav.facing = facing_towards(pos, world.ball_pos)
        return self.nav.act(world, robot)


# ---------------------------------------------------------------- Defender
class DefenderState(enum.Enum):
    BLOCK = "block"
    CLEAR_APPROACH = "clear_approach"
    CLEAR_KICK = "clear_kick"


@dataclass(frozen=True)
class DefenderParams:
    """Attributes:
        lane_offset: sideways shift from the goal-ball lane (m); +-0.11 for two defenders.
        standoff: robot centre distance outside the defense area (m).
        standoff: robot centre distance outside the defense area (m); hand-tuned:
            robot radius (0.09 m) + 3 cm.
        challenge_radius: go for a slow ball closer than this (m) if no teammate holds
            it and it is outside the defense area; 0 disables; hand-tuned.
        abort_factor: give a challenge up when the ball is further than this times
            ``challenge_radius`` (hysteresis); hand-tuned.
        defense_margin_m: the ball counts as in the own defense area (the goalie's)
            up to this far outside it (m); hand-tuned.
        slow_ball_speed: "slow" for a challenge (m/s); hand-tuned.
        near_ball_m, kick_cone, kick_strength, turn_rate: as for the goalie's clear.
    """

    lane_offset: float = 0.0
    standoff: float = 0.12
    challenge_radius: float = 0.4
    abort_factor: float = 2.0
    defense_margin_m: float = 0.05
    slow_ball_speed: float = 1.0
    near_ball_m: float = NEAR_BALL_M
    kick_cone: float = 1.2
    kick_strength: float = 1.0
    turn_rate: float = 3.0


@dataclass(frozen=True)
class DefenderInputs:
    """Attributes: ball_dist (robot centre to ball, m), ball_speed (m/s), ball_in_own_defense,
    teammate_has_ball (another robot of the team holds it), d_db (m), kicked (last tick)."""

    ball_dist: float
    ball_speed: float
    ball_in_own_defense: bool
    teammate_has_ball: bool
    d_db: float
    kicked: bool = False


class Defender(Tactic):
    """Blocks the shot lane between ball and own goal centre just outside the defense
    area; challenges a slow ball that comes close (clears it towards the opponent half)."""

    name = "defender"
    uses_skills = ("go_to_ball",)
    State = DefenderState
    Params = DefenderParams
    Inputs = DefenderInputs
    initial_state = DefenderState.BLOCK

    def __init__(self, field, robot=None, ball=None, skills="baseline", dt: float = 1.0 / 60.0, **params) -> None:
        super().__init__(field, robot, ball, skills, dt, **params)
        self.go_to_ball = self._skill("go_to_ball")
        self.clearing = BallClearing(self.go_to_ball, self.rp)
        self.nav = NavigateToPoint(field, self.rp, self.bp, NavParams())

    def observe(self, world: WorldState, robot: int) -> DefenderInputs:
        ts = world.team(world.frame)
        holders = np.flatnonzero(ts.ball_on_dribbler)
        return DefenderInputs(ball_dist=float(np.hypot(*(world.ball_pos - ts.pos[robot]))),
                              ball_speed=float(np.hypot(*world.ball_vel)),
                              ball_in_own_defense=bool(self.field.in_defense_area(
                                  world.ball_pos, -1, margin=self.params.defense_margin_m)),
                              teammate_has_ball=bool(np.any(holders != robot)),
                              d_db=dribbler_ball_distance(world, robot, self.rp, self.bp), kicked=self._kicked)

    @staticmethod
    def transition(state: DefenderState, inputs: DefenderInputs, params: DefenderParams) -> DefenderState:
        S = DefenderState
        if state is S.BLOCK:
            if (params.challenge_radius > 0 and inputs.ball_dist < params.challenge_radius
                    and inputs.ball_speed < params.slow_ball_speed and not inputs.ball_in_own_defense
                    and not inputs.teammate_has_ball):
                return S.CLEAR_APPROACH
            return S.BLOCK
        abort = (inputs.ball_in_own_defense or inputs.teammate_has_ball
                 or inputs.ball_dist > params.abort_factor * params.challenge_radius)
        if state is S.CLEAR_APPROACH:
            if abort:
                return S.BLOCK
            phase = clear_phase(False, inputs.d_db, inputs.kicked, params)
            return S.CLEAR_KICK if phase is ClearPhase.KICK else S.CLEAR_APPROACH
        if state is S.CLEAR_KICK:
            if inputs.ball_in_own_defense:
                return S.BLOCK
            phase = clear_phase(True, inputs.d_db, inputs.kicked, params)
            if phase is ClearPhase.DONE:
                return S.BLOCK
            return S.CLEAR_APPROACH if phase is ClearPhase.LOST else S.CLEAR_KICK
        raise ValueError(f"unknown state {state!r}")

    def on_enter(self, state: DefenderState) -> None:
        if state is DefenderState.CLEAR_APPROACH and hasattr(self, "clearing"):
            self.clearing.reset()

    def block_target(self, world: WorldState) -> np.ndarray:
        return block_position(world.ball_pos, self.field, self.params.standoff, self.params.lane_offset)

    def execute(self, world: WorldState, robot: int, inputs: DefenderInputs) -> np.ndarray:
        if self.state in (DefenderState.CLEAR_APPROACH, DefenderState.CLEAR_KICK):
            return self.clearing.act(self.state is DefenderState.CLEAR_KICK, world, robot, self.params)
        pos = world.team(world.frame).pos[robot]
        self.nav.target = self.block_target(world)
        self.nav.facing = facing_towards(pos, world.ball_pos)
        return self.nav.act(world, robot)


# -------------------------------------------------------------------- Mark
class MarkState(enum.Enum):
    MARK = "mark"
    NO_TARGET = "no_target"


@dataclass(frozen=True)
class MarkParams:
    """Attributes:
        opponent: index of the opponent to shadow (in its team), or None.
        distance: distance from the opponent towards the own goal (m).
        ball_bias: 0..1, turn the marking direction towards the ball.
    """

    opponent: int | None = None
    distance: float = 0.35
    ball_bias: float = 0.25


@dataclass(frozen=True)
class MarkInputs:
    """Attributes: opponent_valid (the opponent index exists this tick)."""

    opponent_valid: bool


class Mark(Tactic):
    """Shadows opponent ``opponent`` on its goal side (between it and the own goal),
    facing the ball; holds position (NO_TARGET) while the index is None or invalid."""

    name = "mark"
    State = MarkState
    Params = MarkParams
    Inputs = MarkInputs
    initial_state = MarkState.NO_TARGET

    def __init__(self, field, robot=None, ball=None, skills="baseline", dt: float = 1.0 / 60.0, **params) -> None:
        super().__init__(field, robot, ball, skills, dt, **params)
        self.nav = NavigateToPoint(field, self.rp, self.bp, NavParams())

    def observe(self, world: WorldState, robot: int) -> MarkInputs:
        k = self.params.opponent
        n_opp = world.opponents(world.frame).n
        return MarkInputs(opponent_valid=k is not None and 0 <= int(k) < n_opp)

    @staticmethod
    def transition(state: MarkState, inputs: MarkInputs, params: MarkParams) -> MarkState:
        return MarkState.MARK if inputs.opponent_valid else MarkState.NO_TARGET

    def mark_target(self, world: WorldState) -> np.ndarray | None:
        k = self.params.opponent
        opp = world.opponents(world.frame)
        if k is None or not 0 <= int(k) < opp.n:
            return None
        return mark_position(opp.pos[int(k)], world.ball_pos, self.field, self.params.distance,
                             self.params.ball_bias)

    def execute(self, world: WorldState, robot: int, inputs: MarkInputs) -> np.ndarray:
        pos = world.team(world.frame).pos[robot]
        target = self.mark_target(world) if self.state is MarkState.MARK else None
        self.nav.target = pos if target is None else target
        self.nav.facing = facing_towards(pos, world.ball_pos)
        return self.nav.act(world, robot)
