"""The pass and receive skills, hand-coded and learned, behind the one
:class:`~ssl_marl.skills.base.Skill` protocol.

* **pass**: a robot with the ball on its dribbler turns towards a target point (team
  frame, m; :meth:`PassSkill.set_target`) and kicks at a speed chosen so that the ball
  can be received there. SUCCEEDED once it has kicked; FAILED if the ball leaves the
  dribbler before the kick, or after ``max_time_s`` without a kick.
* **receive**: a robot intercepts a moving ball and brings it under control on its
  dribbler; SUCCEEDED once the ball has stayed on the dribbler for ``hold_s`` (0.5 s);
  FAILED if the ball leaves the field.

The learned variants run a trained DDPG actor over the features of
:mod:`ssl_marl.skills.passing_features` (the tasks' observations), exactly as the
paper's skills do in :mod:`ssl_marl.skills.learned`.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..physics import ball_model
from ..physics.field import FieldGeometry
from ..physics.params import BallParams, RobotParams
from ..physics.state import WorldState, wrap_angle
from .base import KickSkill, SkillBase, SkillStatus, make_action
from .baseline import GoToBallBaseline
from .motion import velocity_command
from .passing_features import (
    RECEIVE_ACTION_FORMS,
    RECEIVE_RESIDUAL_FORMS,
    SLOW_BALL,
    ball_line_geometry,
    check_point,
    check_receive_action_form,
    expand_pass_action,
    expand_receive_action,
    pass_aim_error,
    pass_features,
    receive_features,
    receive_press_active,
    receive_pressed_features,
    receive_residual_action,
    receive_task_action,
)

#: Arrival speed (m/s) a pass aims for: TIGERs rate a pass 0 below 1 m/s at the receiver and
#: 1 from 2 m/s (team-play notes, section A); our receive holds balls closing at <= ~2 m/s.
DEFAULT_ARRIVAL_SPEED = 1.5


def load_passing_policy(skill: str, checkpoint: str | Path | None = None):
    """(NumpyActor, metadata) of the shipped (or given) actor of ``skill`` ("pass" or
    "receive"), checking its skill name and observation spec (the registry's
    :func:`~ssl_marl.skills.learned.load_policy`)."""
    from .learned import load_policy

    return load_policy(skill, checkpoint)


# ---------------------------------------------------------------------- pass
class PassSkill(KickSkill):
    """pass, hand-coded or learned. Call :meth:`set_target` before the first
    :meth:`act` (and whenever the receiver moves). Subclasses implement :meth:`aim`."""

    name = "pass"

    def __init__(self, field: FieldGeometry, robot: RobotParams | None = None, ball: BallParams | None = None,
                 target=None, target_vel=None, max_time_s: float | None = None) -> None:
        super().__init__(field, robot, ball, max_time_s)
        self.target: np.ndarray | None = None
        self.target_vel: np.ndarray | None = None
        if target is not None:
            self.set_target(target, target_vel)
        self.kick_speed: float | None = None  #: m/s of the kick, once kicked

    def set_target(self, point_xy, velocity=None) -> None:
        """Pass to ``point_xy`` (team frame, m), e.g. the receiver's position;
        ``velocity`` (m/s, team frame): the receiver's, if it moves (the hand-coded
        pass leads it). ValueError for a non-finite point or one outside the field."""
        p = check_point("pass target", point_xy)
        if not bool(self.field.in_field(p)):
            raise ValueError(f"pass target {p.tolist()} lies outside the {self.field.name} field "
                             f"(|x| <= {self.field.half_length}, |y| <= {self.field.half_width} m)")
        self.target = p
        self.target_vel = None if velocity is None else check_point("pass target velocity", velocity)

    def reset(self) -> None:
        super().reset()
        self.kick_speed = None

    def act(self, world: WorldState, robot: int) -> np.ndarray:
        if self.target is None:
            raise ValueError(f"{type(self).__name__}: no pass target; call set_target(point_xy) first")
        return super().act(world, robot)

    def fires(self, world: WorldState, robot: int, action: np.ndarray, kicks: bool) -> bool:
        """A pass counts only when the kicker is charged and the ball is on the face; its
        speed (m/s) is recorded in :attr:`kick_speed`."""
        team = world.team(world.frame)
        kicks = kicks and bool(team.kick_ready[robot]) and bool(team.ball_on_dribbler[robot])
        if kicks:
            self.kick_speed = float(action[4]) * self.rp.kick_speed_max
        return kicks

    def aim(self, world: WorldState, robot: int) -> tuple[np.ndarray, bool]:
        raise NotImplementedError


def face_distance(ball_pos: np.ndarray, target: np.ndarray, rp: RobotParams, bp: BallParams) -> float:
    """Distance (m) the ball rolls from ``ball_pos`` to the face of a receiver centred at
    ``target`` (team frame, m): the centre distance less its face reach."""
    return max(float(np.hypot(*(np.asarray(target, float) - ball_pos))) - rp.front_distance - bp.radius, 0.0)


class PassBaseline(PassSkill):
    """Hand-coded pass: turn (dribbler on, at most ``max_turn_rate`` rad/s so the ball
    stays on) towards the target, led by the target's velocity over the ball's travel
    time; kick once the heading is within ``aim_tolerance`` of it, at the speed the
    ball model (:func:`ssl_marl.physics.ball_model.kick_speed_for_arrival`) says
    arrives at the receiver's dribbler at ``arrival_speed`` (1.5 m/s)."""

    def __init__(self, field, robot=None, ball=None, target=None, target_vel=None, max_time_s=None,
                 arrival_speed: float = DEFAULT_ARRIVAL_SPEED, max_turn_rate: float = 5.0, turn_gain: float = 8.0,
                 aim_tolerance_m: float = 0.08) -> None:
        super().__init__(field, robot, ball, target, target_vel, max_time_s)
        self.arrival_speed, self.max_turn_rate, self.turn_gain = arrival_speed, max_turn_rate, turn_gain
        self.aim_tolerance_m = aim_tolerance_m

    def plan(self, world: WorldState) -> tuple[np.ndarray, float]:
        """(aim point (team frame, m), kick speed (m/s)) for the current target."""
        aim = np.asarray(self.target, float)
        speed = self.rp.kick_speed_max
        for _ in range(3 if self.target_vel is not None else 1):
            d = face_distance(world.ball_pos, aim, self.rp, self.bp)
            speed = ball_model.kick_speed_for_arrival(d, self.arrival_speed, self.bp, self.rp.kick_speed_max)
            if self.target_vel is None:
                break
            t = ball_model.time_to_distance(speed, d, self.bp)
            aim = self.target + self.target_vel * (t if math.isfinite(t) else 0.0)
        return aim, speed

    def aim(self, world: WorldState, robot: int) -> tuple[np.ndarray, bool]:
        aim, speed = self.plan(world)
        err = pass_aim_error(world, robot, aim)
        d = float(np.hypot(*(aim - world.ball_pos)))
        tol = min(0.06, max(0.015, math.atan2(self.aim_tolerance_m, max(d, 1e-6))))
        omega_now = float(world.team(world.frame).omega[robot])
        if abs(err) < tol and abs(omega_now) < 1.0:
            return make_action(dribble=True, kick=speed / self.rp.kick_speed_max), True
        omega = float(np.clip(self.turn_gain * err, -self.max_turn_rate, self.max_turn_rate))
        return make_action(omega=omega / self.rp.max_omega, dribble=True), False


class LearnedPass(PassSkill):
    """Learned pass: the trained actor maps :func:`pass_features` to (omega, kick, speed)."""

    def __init__(self, field, robot=None, ball=None, target=None, target_vel=None, max_time_s=None,
                 checkpoint: str | Path | None = None, policy=None) -> None:
        super().__init__(field, robot, ball, target, target_vel, max_time_s)
        self.policy = policy if policy is not None else load_passing_policy("pass", checkpoint)[0]

    def aim(self, world: WorldState, robot: int) -> tuple[np.ndarray, bool]:
        a3 = self.policy(pass_features(world, robot, self.target, self.target_vel))
        a = expand_pass_action(a3, self.rp)
        return a, bool(a[4] > 0)


# ------------------------------------------------------------------- receive
class ReceiveSkill(SkillBase):
    """receive, hand-coded or learned: SUCCEEDED once the ball has been on the dribbler
    for ``hold_s`` (s, continuously); FAILED if the ball leaves the field. Subclasses
    implement :meth:`control`."""

    name = "receive"

    def __init__(self, field: FieldGeometry, robot: RobotParams | None = None, ball: BallParams | None = None,
                 hold_s: float = 0.5) -> None:
        super().__init__(field, robot, ball)
        if not (math.isfinite(hold_s) and hold_s >= 0):
            raise ValueError(f"hold_s must be a finite time >= 0 s, got {hold_s!r}")
        self.hold_s = hold_s
        self._hold_t0: float | None = None

    def reset(self) -> None:
        super().reset()
        self._hold_t0 = None

    def held_for(self, world: WorldState) -> float:
        """Seconds the ball has been on the dribbler without interruption (0 if not on it)."""
        return 0.0 if self._hold_t0 is None else world.t - self._hold_t0

    def act(self, world: WorldState, robot: int) -> np.ndarray:
        on = bool(world.team(world.frame).ball_on_dribbler[robot])
        if on and self._hold_t0 is None:
            self._hold_t0 = world.t
        elif not on:
            self._hold_t0 = None
        if on and world.t - self._hold_t0 >= self.hold_s - 1e-9:
            self.status = SkillStatus.SUCCEEDED
        elif not bool(self.field.in_field(world.ball_pos, -self.bp.radius)):
            self.status = SkillStatus.FAILED
        else:
            self.status = SkillStatus.RUNNING
        return self.control(world, robot)

    def control(self, world: WorldState, robot: int) -> np.ndarray:
        raise NotImplementedError


class ReceiveBaseline(ReceiveSkill):
    """Hand-coded receive: move onto the ball's line of travel, face the ball with the
    dribbler on, and cushion.

    * Sideways: towards the ball's line with a stopping-distance profile
      (``sqrt(2 a |offset|)``, at most ``lateral_gain`` x offset).
    * Along the line: the robot lets the ball close in at no more than
      ``sqrt(contact_speed^2 + 2 closing_decel gap)``, i.e. it backs away along the
      ball's direction as the ball comes (the cushion), so that the ball meets the
      dribbler at about ``contact_speed`` (0.6 m/s) relative speed: a ball arriving at
      over ~1.5 m/s relative to a standing robot bounces off (restitution 0.3) faster
      than the dribbler's 5 m/s^2 can pull it back. It never walks into a ball that
      reaches it anyway, and steps towards a ball that would stop short.
    * Heading: against the ball's direction of travel (the face square to the ball).
    * Backing away is capped so that the robot can stop (at ``settle_decel``) before
      the ball, on its dribbler, would cross a field line (``boundary_margin`` 0.25 m).
    * With the ball on the dribbler: brake at ``settle_decel`` (4 m/s^2, inside the
      dribbler's 5 m/s^2 hold), keep facing the ball.
    * A ball that is slow, has passed the robot or moves away: fetch it with the
      go-to-ball baseline.
    """

    def __init__(self, field, robot=None, ball=None, hold_s: float = 0.5, contact_speed: float = 0.6,
                 closing_decel: float = 2.0, lateral_accel: float = 4.0, lateral_gain: float = 8.0,
                 turn_gain: float = 6.0, settle_decel: float = 4.0, boundary_margin: float = 0.25,
                 dt: float = 1.0 / 60.0) -> None:
        super().__init__(field, robot, ball, hold_s)
        self.boundary_margin = boundary_margin
        self.contact_speed, self.closing_decel = contact_speed, closing_decel
        self.lateral_accel, self.lateral_gain, self.turn_gain = lateral_accel, lateral_gain, turn_gain
        self.settle_decel, self.dt = settle_decel, dt
        self._fetch = GoToBallBaseline(field, self.rp, self.bp)

    def control(self, world: WorldState, robot: int) -> np.ndarray:
        ts = world.team(world.frame)
        rp = self.rp
        pos, h, vel = ts.pos[robot], float(ts.heading[robot]), ts.vel[robot]
        to_ball = world.ball_pos - pos
        face_ball = float(wrap_angle(math.atan2(to_ball[1], to_ball[0]) - h))
        if bool(ts.ball_on_dribbler[robot]):
            sp = float(np.hypot(*vel))
            v = vel * max(0.0, 1.0 - self.settle_decel * self.dt / sp) if sp > 1e-6 else np.zeros(2)
            omega = float(np.clip(self.turn_gain * face_ball, -3.0, 3.0))
            return velocity_command(world, robot, v, omega, rp, dribble=True)
        offset, gap, _, u = ball_line_geometry(world, robot, rp, self.bp)
        ball_speed = float(np.hypot(*world.ball_vel))
        if ball_speed < 0.3 or gap < -0.02 or not np.any(u):
            return self._fetch.approach(world, robot)
        n = np.array([-u[1], u[0]])  # left of the ball's direction; offset = (pos - ball) . n
        v_n = -math.copysign(min(math.sqrt(2.0 * self.lateral_accel * abs(offset)), self.lateral_gain * abs(offset),
                                 rp.max_speed), offset)
        g = max(gap, 0.0)
        closing_max = math.sqrt(self.contact_speed ** 2 + 2.0 * self.closing_decel * g)
        v_u = ball_speed - closing_max  # > 0: back away along the ball's direction
        reaches = ball_model.stop_distance(ball_speed, self.bp, sliding=False) > g + 0.05
        if reaches:
            v_u = max(v_u, 0.0)
        # never back away faster than the robot can stop before the ball would leave the field
        behind = _ray_to_field_edge(self.field, pos, u, self.boundary_margin)
        v_u = min(v_u, math.sqrt(2.0 * self.settle_decel * behind))
        room = math.sqrt(max(rp.max_speed ** 2 - v_n ** 2, 0.0))
        v_u = float(np.clip(v_u, -room, room))
        v = v_n * n + v_u * u
        heading_err = float(wrap_angle(math.atan2(-u[1], -u[0]) - h))
        omega = float(np.clip(self.turn_gain * heading_err, -rp.max_omega, rp.max_omega))
        return velocity_command(world, robot, v, omega, rp, dribble=True)


def _ray_to_field_edge(field: FieldGeometry, p: np.ndarray, u: np.ndarray, margin: float) -> float:
    """Distance (m) from ``p`` along unit ``u`` to the field lines shrunk by ``margin``
    (0 if ``p`` is already outside)."""
    t = math.inf
    for k, half in ((0, field.half_length - margin), (1, field.half_width - margin)):
        if u[k] > 1e-9:
            t = min(t, (half - p[k]) / u[k])
        elif u[k] < -1e-9:
            t = min(t, (-half - p[k]) / u[k])
    return max(t, 0.0)


class LearnedReceive(ReceiveSkill):
    """Learned receive: the trained actor maps :func:`receive_features` to (vx, vy, omega),
    dribbler on. The checkpoint's spec picks the action form: ``receive/v1`` ("direct")
    the action itself, ``receive/v2`` ("residual") a correction of the hand-coded
    receive's action in the same state, ``receive/v3`` ("pressed") that correction from
    the state with the opponent nearest the ball's path
    (:func:`~ssl_marl.skills.passing_features.receive_residual_action`). With ``policy``
    given directly, ``action_form`` says which."""

    def __init__(self, field, robot=None, ball=None, hold_s: float = 0.5, checkpoint: str | Path | None = None,
                 policy=None, action_form: str = "direct") -> None:
        super().__init__(field, robot, ball, hold_s)
        if policy is None:
            policy, meta = load_passing_policy("receive", checkpoint)
            action_form = next(k for k, v in RECEIVE_ACTION_FORMS.items() if v == meta["obs_spec"])
        self.policy, self.action_form = policy, check_receive_action_form(action_form)
        residual = self.action_form in RECEIVE_RESIDUAL_FORMS
        self._base = ReceiveBaseline(field, self.rp, self.bp, hold_s) if residual else None
        self._features = receive_pressed_features if self.action_form == "pressed" else receive_features

    def control(self, world: WorldState, robot: int) -> np.ndarray:
        x = self._features(world, robot, self.rp, self.bp)
        if self.action_form == "pressed" and not receive_press_active(x):
            return self._base.control(world, robot)  # outside the press: the hand-coded receive
        a3 = self.policy(x)
        if self._base is not None:
            a3 = receive_residual_action(receive_task_action(self._base.control(world, robot)), a3)
        return expand_receive_action(a3)


__all__ = ["DEFAULT_ARRIVAL_SPEED", "face_distance", "LearnedPass", "LearnedReceive", "PassBaseline", "PassSkill",
           "ReceiveBaseline", "ReceiveSkill", "load_passing_policy", "SLOW_BALL"]
