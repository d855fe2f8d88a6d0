"""SetPieceKick: take a kickoff or free kick with one kick, as the SSL rules require.

A set piece is taken once the ball has moved 0.05 m; its kicker may not touch the ball
again before another robot has, and remaining in contact with the ball for more than
0.05 m counts as that double touch (SSL rules, as TIGERs' autoref quotes them;
docs/references.md). So the kicker does not take the ball onto its dribbler: it walks
to a point behind the ball on the line ball -> target
(:func:`~ssl_marl.plays.pass_tactic.behind_ball_waypoint`, round the ball's side when
it starts in front), then drives straight at the ball with its kicker armed, and the
kick fires as the ball reaches the kicker face.

State machine (team frame)::

    APPROACH --(behind the ball on the line, facing the target, its sideways speed at
                most settle_speed, not hold)--> KICK   (the aim locks)
    KICK --(the ball has left its spot: moved IN_PLAY_DISTANCE from where it lay)--> DONE
    KICK --(off the line by more than 2 behind_tol_m, or the heading off by more than
            2 kick_align_tol, before the kick)--> APPROACH
    DONE: stop; terminal until :meth:`~ssl_marl.plays.tactic_base.Tactic.reset`

The target (``target_point``, team frame, m, with ``kick_strength``) is set by a play;
None lets :func:`set_piece_choice` choose (re-chosen every ``rechoose_s`` while the
robot walks up, locked once it drives at the ball): a shot at the widest open part of the
goal mouth when one is open, else a flat pass to the teammate with the safest lane
(farthest forward among the safe ones), else a shot at the goal centre. Uses no
swappable skill: the walk is point navigation and the kick a fixed command.

The walk keeps :data:`BALL_CLEARANCE_M` between body and ball (straight back first when
nearer, round the ball when the straight path passes it) and may go into the run-off
beyond the lines (a ball placed 0.2 m inside them) and into the defense areas (SSL free
kicks lie 1 m outside them, :func:`~ssl_marl.envs.referee.free_kick_spot`; a ball placed
nearer, kicked away from the area, would have its kicker's staging point inside it).
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from ..envs.game_control import IN_PLAY_DISTANCE
from ..physics.state import WorldState, wrap_angle
from ..skills.base import make_action
from ..skills.motion import velocity_command
from ..skills.navigation import NavigateToPoint, NavParams, detour_waypoint, facing_towards, line_frame
from .pass_decision import DecisionParams, open_goal_interval, pass_kick_speeds, path_margins
from .tactic_base import Tactic, check_field_point


class BehindParams(Protocol):
    """What :func:`behind_ball_waypoint` reads (m, m, rad): the pass tactic's and the
    set-piece kick's parameters both have it."""

    behind_gap_m: float
    behind_tol_m: float
    kick_align_tol: float


#: m: a robot going round the ball to its staging point keeps this far off the pass line
BESIDE_M = 0.35


def behind_ball_waypoint(pos: np.ndarray, heading: float, ball: np.ndarray, target: np.ndarray, rp, bp,
                         params: BehindParams, wait: bool = False) -> np.ndarray | None:
    """Where a robot at ``pos`` (heading rad) walks to take ``ball`` towards ``target``
    (team frame, m): None once it stands behind the ball on the line (lateral offset
    within ``behind_tol_m``, facing the target within ``kick_align_tol``) and need not
    ``wait`` (for a receiver): then the caller drives straight on (the pass tactic's
    go-to-ball skill, the set-piece kick's armed drive). Else the
    staging point ``behind_gap_m`` behind the ball (front face to ball surface); a robot
    not yet as far back as that goes round the ball at ``BESIDE_M`` off the pass line on
    its own side: first straight sideways while nearer the line than that, then back
    level with the staging point, so that it never pushes the ball on its way."""
    ball = np.asarray(ball, float)
    frame = line_frame(ball, target, pos)
    if frame is None:
        return None
    u, _, along, lateral = frame
    along, lateral = float(along), float(lateral)
    back = rp.front_distance + bp.radius + params.behind_gap_m
    face = abs(wrap_angle(math.atan2(u[1], u[0]) - heading))
    if along < -rp.front_distance and abs(lateral) <= params.behind_tol_m and face <= params.kick_align_tol \
            and not wait:
        return None
    if along > -back + params.behind_tol_m:
        side = np.array([-u[1], u[0]]) * (1.0 if lateral >= 0.0 else -1.0)
        if abs(lateral) < BESIDE_M - 0.05:
            return ball + BESIDE_M * side + along * u  # sideways first
        return ball + BESIDE_M * side - back * u  # then back, beside the ball
    return ball - back * u


#: rad: the open part of the goal mouth a set piece is shot at must be at least this wide
SHOT_OPEN_MIN_RAD = 0.04
#: s: a pass lane with at least this interception margin counts as safe
SAFE_MARGIN_S = 0.15
#: m between the robot's body and the ball a kicker keeps while it walks round the ball
BALL_CLEARANCE_M = 0.05
#: m: a kicker this close to the ball keeps its choice (a new line would send it round the ball)
KEEP_CHOICE_M = 0.35
#: the pass model of :func:`set_piece_choice` (the passing plays' default decision)
_PASS_MODEL = DecisionParams()


@dataclass(frozen=True)
class SetPieceChoice:
    """What a set piece's kick does: ``kind`` ("shot" or "pass"), ``target`` (team frame,
    m), ``strength`` (ball speed as a fraction of ``kick_speed_max``), ``teammate`` (the
    receiver's index for a pass, else None)."""

    kind: str
    target: np.ndarray
    strength: float
    teammate: int | None = None


def set_piece_shot_interval(ball: np.ndarray, kicker: int, ours: np.ndarray, opponents: np.ndarray, field, rp,
                            bp) -> tuple[float, float]:
    """(open_angle, aim_angle) in rad (team frame) of a set-piece shot from ``ball`` by
    robot ``kicker``: the widest part of the opponent goal mouth that no other robot
    (``ours`` but the kicker, ``opponents``; (n, 2) and (k, 2) centres, m) shadows
    (:func:`~ssl_marl.plays.pass_decision.open_goal_interval`). A set piece is shot when
    ``open_angle`` is at least :data:`SHOT_OPEN_MIN_RAD`."""
    ours = np.asarray(ours, float).reshape(-1, 2)
    others = np.concatenate([np.delete(ours, kicker, axis=0), np.asarray(opponents, float).reshape(-1, 2)])
    return open_goal_interval(np.asarray(ball, float), others, field, rp, bp)


def set_piece_choice(ball: np.ndarray, kicker: int, ours: np.ndarray, opponents: np.ndarray, field, rp, bp,
                     receivers: tuple[int, ...] | None = None) -> SetPieceChoice:
    """The kick of a set piece taken by robot ``kicker`` (team frame, m; ``ours`` (n, 2) and
    ``opponents`` (k, 2) robot centres): a full-strength shot at the centre of the widest
    open part of the goal mouth if it is at least :data:`SHOT_OPEN_MIN_RAD` wide; else a
    pass to one of ``receivers`` (default: our robots but the kicker and, in a team of two
    or more, the goalie 0) 1-6 m away, kicked to arrive at 2 m/s, on the lane with the
    largest interception margin (the passing plays' model,
    :func:`~ssl_marl.plays.pass_decision.path_margins`), the farthest forward of those
    with at least :data:`SAFE_MARGIN_S`; else (no lane open) the full-strength shot at the
    goal centre."""
    ball = np.asarray(ball, float)
    ours = np.asarray(ours, float).reshape(-1, 2)
    opponents = np.asarray(opponents, float).reshape(-1, 2)
    open_angle, aim = set_piece_shot_interval(ball, kicker, ours, opponents, field, rp, bp)
    reach = max(field.half_length - float(ball[0]), 1.0) / max(math.cos(aim), 0.2)
    shot = SetPieceChoice("shot", ball + reach * np.array([math.cos(aim), math.sin(aim)]), 1.0)
    if open_angle >= SHOT_OPEN_MIN_RAD:
        return shot
    if receivers is None:
        first = 1 if len(ours) >= 2 else 0
        receivers = tuple(k for k in range(first, len(ours)) if k != kicker)
    p = _PASS_MODEL
    cands = [k for k in receivers if p.min_pass_m <= float(np.hypot(*(ours[k] - ball))) <= p.max_pass_m
             and bool(field.in_field(ours[k]))]
    if cands:
        ends = ours[cands]
        v0 = pass_kick_speeds(np.hypot(*(ends - ball).T), bp, rp, p)
        margins = path_margins(ball, ends, v0, opponents, rp, bp, p, receivers=ends)
        safe = np.flatnonzero(margins >= SAFE_MARGIN_S)
        j = int(safe[np.argmax(ends[safe, 0])]) if safe.size else int(np.argmax(margins))
        if margins[j] > 0.0:
            return SetPieceChoice("pass", ends[j].copy(), float(min(v0[j] / rp.kick_speed_max, 1.0)), cands[j])
    return shot


class SetPieceState(enum.Enum):
    APPROACH = "approach"
    KICK = "kick"
    DONE = "done"


@dataclass(frozen=True)
class SetPieceKickParams:
    """Attributes:
        target_point: (x, y) the kick goes towards (m, team frame); None:
            :func:`set_piece_choice` chooses (module docstring).
        kick_strength: the kick's ball speed as a fraction of ``kick_speed_max`` (0, 1]
            with a ``target_point`` (the choice brings its own).
        hold: wait behind the ball, do not drive at it yet (a pass waiting for its
            receiver; set each tick by the tactic that runs this one).
        rechoose_s: without a ``target_point``, the choice is made again at most this
            often while the robot walks up (s), and not once it is within
            :data:`KEEP_CHOICE_M` of the ball.
        kick_speed: the drive's speed at contact in KICK (m/s): slow enough that the face
            meets the ball within a control period of the kick firing (0.5 m/s moves 8 mm
            per 60 Hz tick, against the 50 mm that put the ball in play); farther out the
            drive may be faster, braking at ``kick_decel`` (m/s^2) to arrive at it.
        kick_align_tol: APPROACH -> KICK with the heading within this of the target (rad).
        behind_gap_m: the staging point's gap between the robot's front and the ball (m).
        behind_tol_m: behind the ball within this lateral offset from the line (m).
        settle_speed: APPROACH -> KICK only while the robot's speed across the line is at
            most this (m/s): a robot still sliding sideways overshoots the line.
        turn_gain: heading gain in KICK (1/s).
    """

    target_point: tuple[float, float] | None = None
    kick_strength: float = 1.0
    hold: bool = False
    rechoose_s: float = 0.5
    kick_speed: float = 0.5
    kick_decel: float = 2.5
    kick_align_tol: float = 0.08
    behind_gap_m: float = 0.06
    behind_tol_m: float = 0.025
    settle_speed: float = 0.2
    turn_gain: float = 6.0

    def __post_init__(self) -> None:
        if not (isinstance(self.kick_strength, (int, float)) and 0.0 < self.kick_strength <= 1.0):
            raise ValueError(f"SetPieceKickParams.kick_strength must lie in (0, 1], got {self.kick_strength!r}")
        if not (isinstance(self.kick_speed, (int, float)) and 0.0 < self.kick_speed <= 2.0):
            raise ValueError(f"SetPieceKickParams.kick_speed must lie in (0, 2] m/s, got {self.kick_speed!r}")


@dataclass(frozen=True)
class SetPieceKickInputs:
    """Attributes: behind (the robot stands behind the ball on the line to the target,
    facing it), off_line (in KICK: drifted off the line or the aim), ball_left (in KICK:
    the ball lies more than ``IN_PLAY_DISTANCE`` from where it lay when KICK began; the
    armed kicker fires on contact, so the command alone says nothing)."""

    behind: bool = False
    off_line: bool = False
    ball_left: bool = False


class SetPieceKick(Tactic):
    """Take a set piece with one kick (module docstring)."""

    name = "set_piece_kick"
    State = SetPieceState
    Params = SetPieceKickParams
    Inputs = SetPieceKickInputs
    initial_state = SetPieceState.APPROACH
    uses_skills = ()

    def __init__(self, field, robot=None, ball=None, skills="baseline", dt: float = 1.0 / 60.0, **params) -> None:
        self._choice: SetPieceChoice | None = None  # the kick chosen (locked in KICK)
        self._choice_t = -math.inf  # world time it was chosen (s)
        self._spot: np.ndarray | None = None  # where the ball lay when KICK began
        super().__init__(field, robot, ball, skills, dt, **params)
        run_off = max(self.field.boundary_width - self.rp.radius - 0.02, 0.0)  # up to 2 cm from the wall
        self.nav = NavigateToPoint(self.field, self.rp, self.bp, NavParams(
            avoid_own_defense=False, avoid_opp_defense=False, run_off=run_off), tolerance=0.02)

    def set_params(self, **changes) -> None:
        """As :meth:`Tactic.set_params`; ``target_point`` must be two finite numbers inside
        the field (ValueError naming it)."""
        if changes.get("target_point") is not None:
            changes["target_point"] = check_field_point("SetPieceKick.target_point", changes["target_point"],
                                                        self.field)
        super().set_params(**changes)

    def choice(self, world: WorldState, robot: int) -> SetPieceChoice:
        """The kick (target and strength): the play's ``target_point``, else
        :func:`set_piece_choice`'s, kept ``rechoose_s`` and locked in KICK."""
        p = self.params
        if p.target_point is not None:
            return SetPieceChoice("target", np.asarray(p.target_point, float), float(p.kick_strength))
        c = self._choice
        ts = world.team(world.frame)
        close = float(np.hypot(*(ts.pos[robot] - world.ball_pos))) < KEEP_CHOICE_M
        if c is not None and (self.state is SetPieceState.KICK or close or world.t - self._choice_t < p.rechoose_s):
            return c
        self._choice = set_piece_choice(world.ball_pos, robot, ts.pos, world.opponents(world.frame).pos, self.field,
                                        self.rp, self.bp)
        self._choice_t = world.t
        return self._choice

    def observe(self, world: WorldState, robot: int) -> SetPieceKickInputs:
        ts = world.team(world.frame)
        pos, heading = ts.pos[robot], float(ts.heading[robot])
        target = self.choice(world, robot).target
        p = self.params
        frame = line_frame(world.ball_pos, target, pos)
        sideways = 0.0 if frame is None else abs(float(ts.vel[robot] @ np.array([-frame[0][1], frame[0][0]])))
        behind = not p.hold and sideways <= p.settle_speed and behind_ball_waypoint(
            pos, heading, world.ball_pos, target, self.rp, self.bp, p) is None
        off = left = False
        if self.state is SetPieceState.KICK:
            left = self._spot is not None and float(np.hypot(*(world.ball_pos - self._spot))) > IN_PLAY_DISTANCE
            face = abs(wrap_angle(facing_towards(world.ball_pos, target) - heading))
            off = frame is None or abs(float(frame[3])) > 2 * p.behind_tol_m or face > 2 * p.kick_align_tol
        return SetPieceKickInputs(behind=behind, off_line=off, ball_left=left)

    @staticmethod
    def transition(state: SetPieceState, inputs: SetPieceKickInputs, params: SetPieceKickParams) -> SetPieceState:
        S = SetPieceState
        if state is S.DONE:
            return state
        if state is S.APPROACH:
            return S.KICK if inputs.behind else S.APPROACH
        if state is S.KICK:
            if inputs.ball_left:
                return S.DONE
            return S.APPROACH if inputs.off_line else S.KICK
        raise ValueError(f"unknown state {state!r}")

    def on_enter(self, state: SetPieceState) -> None:
        if state is SetPieceState.APPROACH:
            self._spot = None

    def execute(self, world: WorldState, robot: int, inputs: SetPieceKickInputs) -> np.ndarray:
        S, p = SetPieceState, self.params
        ts = world.team(world.frame)
        pos, heading = ts.pos[robot], float(ts.heading[robot])
        if self.state is S.DONE:
            return make_action()
        c = self.choice(world, robot)
        ball = world.ball_pos
        u = (c.target - ball) / max(float(np.hypot(*(c.target - ball))), 1e-9)
        if self.state is S.KICK:
            if self._spot is None:
                self._spot = np.array(ball, float)
            frame = line_frame(ball, c.target, pos)
            lateral = float(frame[3]) if frame is not None else 0.0
            gap = max(-float(frame[2]) - self.rp.front_distance - self.bp.radius, 0.0) if frame is not None else 0.0
            speed = min(math.sqrt(p.kick_speed ** 2 + 2.0 * p.kick_decel * gap), self.rp.max_speed)
            v = speed * u - 2.0 * lateral * np.array([-u[1], u[0]])  # on along the line, back onto it sideways
            err = wrap_angle(facing_towards(ball, c.target) - heading)
            omega = float(np.clip(p.turn_gain * err, -self.rp.max_omega, self.rp.max_omega))
            return velocity_command(world, robot, v, omega, self.rp, kick=c.strength)
        way = behind_ball_waypoint(pos, heading, ball, c.target, self.rp, self.bp, p)
        goal = ball - (self.rp.front_distance + self.bp.radius + p.behind_gap_m) * u if way is None else way
        self.nav.target = self.keep_off_ball(pos, ball, goal) if way is not None else goal
        self.nav.facing = facing_towards(ball, c.target)
        return self.nav.act(world, robot)

    def keep_off_ball(self, pos: np.ndarray, ball: np.ndarray, goal: np.ndarray) -> np.ndarray:
        """The point to head for on the way to ``goal`` without touching the ball (team
        frame, m): straight back from the ball while nearer than :data:`BALL_CLEARANCE_M`
        plus the touch reach, else round it (a detour beside it) when the straight path
        passes it closer than that."""
        clear = self.rp.radius + self.bp.radius + BALL_CLEARANCE_M
        d = pos - ball
        dist = float(np.hypot(*d))
        if dist < clear - 0.02:
            return ball + d / max(dist, 1e-9) * (clear + 0.05)
        detour = detour_waypoint(pos, goal, ball[None, :], clear, 0.03)
        return goal if detour is None else detour


__all__ = ["BehindParams", "BESIDE_M", "behind_ball_waypoint", "SHOT_OPEN_MIN_RAD", "SAFE_MARGIN_S",
           "set_piece_shot_interval",
           "SetPieceChoice", "set_piece_choice", "SetPieceState", "SetPieceKickParams", "SetPieceKickInputs",
           "SetPieceKick"]
