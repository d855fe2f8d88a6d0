"""Pass(target robot): get the ball, wait for the receiver, kick it to the receive point.

State machine (team frame; d_{d-b}: dribbler-ball distance)::

    GET_BALL --(d_db <= 35 mm)--> HOLD
    HOLD --(receiver_ready, a target set, facing it, nearly still or kick_moving)--> KICK   (the handshake)
    HOLD --(d_db > 50 mm: ball lost)--> GET_BALL
    HOLD --(waited max_wait_s)--> FAILED
    KICK --(kick commanded / pass skill SUCCEEDED)--> DONE
    KICK --(pass skill FAILED: ball lost before the kick)--> FAILED
    GET_BALL --(strike, a target set)--> STRIKE
    STRIKE --(the ball has left its spot)--> DONE
    DONE, FAILED: terminal until :meth:`~ssl_marl.plays.tactic_base.Tactic.reset`

The play sets the parameters every tick: ``target_robot`` (teammate index),
``target_point`` (where the receiver will take the ball, m) and ``receiver_ready``
(the receiver's tactic reports READY: the passer commits only then). While it waits
(HOLD) the robot keeps the ball on the dribbler, brakes gently (``hold_decel``: the
dribbler holds the ball up to 5 m/s^2) and turns towards the target at a gentle rate;
it commits once it faces the target within ``kick_align_tol`` and moves slower than
``settle_speed``, so the pass skill has little turning left. KICK runs the pass skill
(learned or baseline, :mod:`ssl_marl.plays.skillset`), which chooses the kick speed
from the ball model. The play reads :attr:`status` (``state``; ``kicks``).

A set piece's pass (``strike``, with ``approach_behind``) never takes the ball onto the
dribbler: the kicker may not touch the ball again before another robot has, and
remaining in contact with it for more than 0.05 m counts as that double touch (SSL
rules). STRIKE runs :class:`~ssl_marl.plays.set_piece_kick.SetPieceKick` towards the
receive point: it walks behind the ball on the line, waits there (``hold``) until the
receiver is ready, then drives at the ball with the kicker armed; the kick's speed chosen
from the ball model for ``arrival_speed`` at the receive point as the hand-coded pass
skill does (:meth:`strike_kick`).
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass

import numpy as np

from ..physics import ball_model
from ..physics.state import WorldState, wrap_angle
from ..skills.base import SkillStatus, make_action
from ..skills.features import BALL_LOST_DISTANCE, dribbler_ball_distance
from ..skills.motion import velocity_command
from ..skills.passing import DEFAULT_ARRIVAL_SPEED, face_distance
from ..skills.navigation import NavigateToPoint, NavParams, facing_towards
from .set_piece_kick import SetPieceKick, SetPieceState, behind_ball_waypoint
from .shoot import govern_approach
from .tactic_base import NEAR_BALL_M, Tactic, check_field_point, skill_status


class PassState(enum.Enum):
    GET_BALL = "get_ball"
    HOLD = "hold"
    KICK = "kick"
    STRIKE = "strike"
    DONE = "done"
    FAILED = "failed"


@dataclass(frozen=True)
class PassParams:
    """Attributes:
        target_robot: the receiver's index in the team (None: no receiver chosen yet).
        target_point: (x, y) receive point (m, team frame) or None.
        receiver_ready: the receiver reports READY (handshake; set by the play).
        max_wait_s: HOLD longer than this without a ready receiver -> FAILED (s).
        near_ball_m: GET_BALL -> HOLD threshold on d_{d-b} (m; the paper's 35 mm).
        lost_ball_m: HOLD -> GET_BALL when d_{d-b} exceeds this (m).
        hold_turn_rate: turn rate towards the target while holding (rad/s; slow
            enough for the dribbler to keep the ball, cf. aim-to-shoot's 5 rad/s).
        hold_turn_gain: proportional gain of that turn (1/s).
        approach_speed, approach_decel: the go-to-ball speed governor (m/s, m/s^2),
            as in :class:`~ssl_marl.plays.shoot.GoToBallAndShoot`.
        kick_align_tol: HOLD -> KICK only with the heading within this of the target (rad).
        settle_speed: ... and the robot slower than this (m/s).
        hold_decel: braking while holding (m/s^2).
        arrival_speed: speed (m/s) at which the pass should reach the receiver, handed to
            a pass skill that takes one (the hand-coded one; None = the skill's default,
            1.5 m/s). 2 m/s: TIGERs rate passability 1 from 2 m/s, and a faster ball
            gives the opponents less time (the decision uses the same figure).
        hold_alpha: change of the turn rate while holding (rad/s^2; at the robot's 50
            rad/s^2 the face accelerates the ball at 4 m/s^2 sideways, near the
            dribbler's 5 m/s^2 grip).
        approach_behind: GET_BALL with a target set walks first to a point behind the
            ball on the line ball -> target (:func:`behind_ball_waypoint`, around the
            ball's side when it starts in front), so that the robot takes the ball already
            facing the target and HOLD has no turn left (a set piece; False: the go-to-ball
            skill from wherever the robot is). It waits there, off the ball, until the
            receiver is ready: touching a free kick's ball puts it in play.
        behind_gap_m: the staging point's gap between the robot's front and the ball (m).
        behind_tol_m: the robot counts as behind the ball (go-to-ball takes over) within
            this lateral offset from the line (m) and facing the target within
            ``kick_align_tol``.
        strike: with ``approach_behind``, kick from behind the ball without taking it onto
            the dribbler (STRIKE; a set piece, module docstring).
        kick_moving: HOLD -> KICK without the ``settle_speed`` condition (a passer whose
            dribble nears SSL's 1 m limit, e.g. pushed along by an opponent, kicks as soon as
            it faces the target).
    """

    target_robot: int | None = None
    target_point: tuple[float, float] | None = None
    receiver_ready: bool = False
    max_wait_s: float = 2.0
    near_ball_m: float = NEAR_BALL_M
    lost_ball_m: float = BALL_LOST_DISTANCE
    hold_turn_rate: float = 4.0
    hold_turn_gain: float = 6.0
    approach_speed: float | None = 0.8
    approach_decel: float = 3.0
    kick_align_tol: float = 0.35
    settle_speed: float = 0.3
    hold_decel: float = 2.5
    hold_alpha: float = 20.0
    arrival_speed: float | None = 2.0
    approach_behind: bool = False
    behind_gap_m: float = 0.08
    behind_tol_m: float = 0.05
    strike: bool = False
    kick_moving: bool = False


@dataclass(frozen=True)
class PassInputs:
    """Attributes: d_db (m), skill_status (the pass skill's, KICK state), kicked (a kick
    was commanded on the previous tick), receiver_ready, has_target, time_in_state (s),
    aim_err (|heading error| to the target, rad), speed (m/s), strike_state (the
    STRIKE kick's :class:`~ssl_marl.plays.set_piece_kick.SetPieceState` after its last
    tick, or None)."""

    d_db: float
    skill_status: SkillStatus = SkillStatus.RUNNING
    kicked: bool = False
    receiver_ready: bool = False
    has_target: bool = True
    time_in_state: float = 0.0
    aim_err: float = 0.0
    speed: float = 0.0
    strike_state: SetPieceState | None = None


class Pass(Tactic):
    """Pass the ball to a teammate (see the module docstring)."""

    name = "pass"
    State = PassState
    Params = PassParams
    Inputs = PassInputs
    initial_state = PassState.GET_BALL
    uses_skills = ("go_to_ball", "pass")
    takes_ball = True

    def __init__(self, field, robot=None, ball=None, skills="baseline", dt: float = 1.0 / 60.0, **params) -> None:
        self.go_to_ball = None
        super().__init__(field, robot, ball, skills, dt, **params)
        self.go_to_ball = self._skill("go_to_ball")
        self.pass_skill = self._skill("pass")
        self.nav = NavigateToPoint(self.field, self.rp, self.bp, NavParams(), tolerance=0.03)
        self.striker = SetPieceKick(self.field, self.rp, self.bp, dt=self.dt)
        self.strike_chip = 0.0  #: the STRIKE's chip entry on the last tick (:meth:`strike_kick`)
        self.on_enter(self.state)

    @property
    def wants_ball(self) -> bool:
        """Only before an open-play kick (GET_BALL, HOLD, KICK): a STRIKE's kick takes the
        set piece and its robot walks no more to the ball, nor once the pass is kicked or
        given up (DONE, FAILED: the robot stands still)."""
        return self.state in (PassState.GET_BALL, PassState.HOLD, PassState.KICK)

    def kick_skill(self):
        """The skill the KICK state runs: the pass skill."""
        return self.pass_skill

    def set_params(self, **changes) -> None:
        """As :meth:`Tactic.set_params`; points (target_point) must be two finite
        numbers inside the field (ValueError naming the parameter)."""
        for name in ('target_point',):
            if changes.get(name) is not None:
                changes[name] = check_field_point(f"{type(self).__name__}.{name}", changes[name], self.field)
        super().set_params(**changes)

    def observe(self, world: WorldState, robot: int) -> PassInputs:
        p = self.params
        status = skill_status(self.kick_skill()) if self.state is PassState.KICK else SkillStatus.RUNNING
        has_target = p.target_point is not None and p.target_robot is not None
        ts = world.team(world.frame)
        return PassInputs(d_db=dribbler_ball_distance(world, robot, self.rp, self.bp), skill_status=status,
                          kicked=self._kicked, receiver_ready=bool(p.receiver_ready), has_target=has_target,
                          time_in_state=self._time_in_state,
                          aim_err=heading_error_to(world, robot, p.target_point) if has_target else math.pi,
                          speed=float(np.hypot(*ts.vel[robot])),
                          strike_state=self.striker.state if self.state is PassState.STRIKE else None)

    @staticmethod
    def transition(state: PassState, inputs: PassInputs, params: PassParams) -> PassState:
        S = PassState
        if state in (S.DONE, S.FAILED):
            return state
        if state is S.GET_BALL:
            if params.strike and params.approach_behind and inputs.has_target:
                return S.STRIKE
            return S.HOLD if inputs.d_db <= params.near_ball_m else S.GET_BALL
        if state is S.STRIKE:
            return S.DONE if inputs.strike_state is SetPieceState.DONE else S.STRIKE
        if state is S.HOLD:
            if inputs.d_db > params.lost_ball_m:
                return S.GET_BALL
            if (inputs.receiver_ready and inputs.has_target and inputs.aim_err <= params.kick_align_tol
                    and (inputs.speed <= params.settle_speed or params.kick_moving)):
                return S.KICK
            return S.FAILED if inputs.time_in_state > params.max_wait_s else S.HOLD
        if state is S.KICK:
            if inputs.kicked or inputs.skill_status is SkillStatus.SUCCEEDED:
                return S.DONE
            if inputs.skill_status is SkillStatus.FAILED:
                return S.FAILED
            return S.KICK
        raise ValueError(f"unknown state {state!r}")

    def on_enter(self, state: PassState) -> None:
        if self.go_to_ball is None:  # base constructor: skills not built yet
            return
        if state is PassState.GET_BALL:
            self.go_to_ball.reset()
        elif state is PassState.KICK:
            self.kick_skill().reset()
        elif state is PassState.STRIKE:
            self.striker.reset()

    def execute(self, world: WorldState, robot: int, inputs: PassInputs) -> np.ndarray:
        S, p = PassState, self.params
        if self.state is S.GET_BALL:
            if p.approach_behind and p.target_point is not None:
                ts = world.team(world.frame)
                way = behind_ball_waypoint(ts.pos[robot], float(ts.heading[robot]), world.ball_pos,
                                           np.asarray(p.target_point, float), self.rp, self.bp, p,
                                           wait=not p.receiver_ready)
                if way is not None:
                    self.nav.target = way
                    self.nav.facing = facing_towards(world.ball_pos, np.asarray(p.target_point, float))
                    return self.nav.act(world, robot)
            a = self.go_to_ball.act(world, robot)
            if p.approach_speed is not None:
                a = govern_approach(a, world, robot, self.rp, self.bp, p.approach_speed, p.approach_decel)
            return a
        if self.state is S.HOLD:
            ts = world.team(world.frame)
            vel = ts.vel[robot]
            sp = float(np.hypot(*vel))
            v = vel * max(0.0, 1.0 - p.hold_decel * self.dt / sp) if sp > 1e-6 else np.zeros(2)
            omega = 0.0
            if p.target_point is not None:
                err = wrap_angle(facing_towards(ts.pos[robot], np.asarray(p.target_point, float))
                                 - float(ts.heading[robot]))
                omega = float(np.clip(p.hold_turn_gain * err, -p.hold_turn_rate, p.hold_turn_rate))
            w0 = float(ts.omega[robot])  # change the turn rate gently: the dribbler face would shed the ball
            omega = w0 + float(np.clip(omega - w0, -p.hold_alpha * self.dt, p.hold_alpha * self.dt))
            return velocity_command(world, robot, v, omega, self.rp, dribble=True)
        if self.state is S.STRIKE:
            strength, self.strike_chip = self.strike_kick(world)
            self.striker.set_params(target_point=p.target_point, kick_strength=strength, hold=not p.receiver_ready)
            return self.striker.act(world, robot)
        if self.state is S.KICK:
            skill = self.kick_skill()
            skill.set_target(np.asarray(p.target_point, float))
            if p.arrival_speed is not None and hasattr(skill, "arrival_speed"):
                skill.arrival_speed = float(p.arrival_speed)
            return skill.act(world, robot)
        return make_action()

    def strike_kick(self, world: WorldState) -> tuple[float, float]:
        """(kick strength (fraction of ``kick_speed_max``), chip entry (elevation fraction of
        ``chip_angle_max``, 0 flat)) of the STRIKE: flat, at the speed that reaches the
        receiver's face at ``arrival_speed`` (default 1.5 m/s), by the ball model."""
        p = self.params
        d = face_distance(world.ball_pos, p.target_point, self.rp, self.bp)
        arrive = DEFAULT_ARRIVAL_SPEED if p.arrival_speed is None else float(p.arrival_speed)
        speed = ball_model.kick_speed_for_arrival(d, arrive, self.bp, self.rp.kick_speed_max)
        return min(max(speed / self.rp.kick_speed_max, 1e-3), 1.0), 0.0


def heading_error_to(world: WorldState, robot: int, point) -> float:
    """|heading error| (rad) of ``robot`` towards ``point`` (team frame)."""
    ts = world.team(world.frame)
    return abs(wrap_angle(facing_towards(ts.pos[robot], np.asarray(point, float)) - float(ts.heading[robot])))


__all__ = ["PassState", "PassParams", "PassInputs", "Pass", "heading_error_to"]
