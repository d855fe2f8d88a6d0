"""Dribble-and-shoot: take the ball, carry it to a shooting window, aim, shoot.

What limits the paper's go-to-ball-and-shoot (``docs/RESULTS.md`` section 3): the ball is
lost between the phases (the 1 s drive-forward pushes it away, a learned go-to-ball hits
it at ~2.6 m/s), and the learned aim-to-shoot never shoots from far. This tactic keeps
the ball on the dribbler from the first touch to the kick, and moves the shot to where
aim-to-shoot scores.

State machine (``d_db``: dribbler-ball distance, :func:`~ssl_marl.skills.features.dribbler_ball_distance`;
``held``: the world's ball-on-dribbler flag, the tracker's inference under realism)::

    GO_TO_BALL --(held or d_db <= near_ball_m)--> CONTROL
    GO_TO_BALL --(no progress: the robot-ball distance has not shrunk by stall_progress_m in stall_s)--> RECOVER
    RECOVER --(held or d_db <= near_ball_m)--> CONTROL;  RECOVER --(recover_s passed)--> GO_TO_BALL
    CONTROL --(held for secure_s, robot speed <= secure_speed)--> DRIBBLE, or AIM if the ball is in the window
    CONTROL --(d_db > control_lost_m, or control_timeout_s without securing)--> GO_TO_BALL
    DRIBBLE --(ball within arrive_tol_m of the shooting point, speed <= arrive_speed)--> AIM
    DRIBBLE --(d_db > lost_ball_m)--> GO_TO_BALL
    AIM --(kick commanded)--> GO_TO_BALL            (status.kicks += 1)
    AIM --(skill FAILED, ball still within near_ball_m)--> DRIBBLE (the next window is closer)
    AIM --(skill FAILED, ball gone)--> GO_TO_BALL

* GO_TO_BALL runs the go-to-ball skill (learned or baseline) under an approach-speed
  governor (speed <= sqrt(v_touch^2 + 2 a gap)): the robot touches the ball at
  ``touch_speed`` (0.5 m/s) instead of hitting it. Dribbler on.
* RECOVER: the tactic's own approach when the go-to-ball skill stalls (a learned policy
  outside its training distribution, e.g. a Division A corner beyond Division B's lines,
  can dither in place): turn to the ball, drive straight at it with a stopping profile
  that ends at ``touch_speed``. ``stalls`` counts how often it was entered.
* CONTROL: dribbler on, face the ball and creep onto it at ``control_push_speed`` while the
  commanded velocity is brought down at ``control_decel`` (below the dribbler's 5 m/s^2
  holding force, so braking does not throw the ball off).
* DRIBBLE: carry the ball to the shooting point (see :func:`shooting_point`): turn in place
  towards the travel direction when it is more than ``dribble_turn_first_rad`` off,
  otherwise drive forward at up to ``dribble_speed`` with the commanded velocity
  rate-limited to ``dribble_accel`` and a stopping profile at the end; within
  ``face_goal_dist_m`` of the point the heading turns to the goal centre. Turn rate
  <= ``dribble_turn_rate``.
* AIM runs the aim-to-shoot skill (learned or baseline) from rest, facing the goal.

Shooting window: the ball's target is on the ray from the opponent goal centre towards
the ball, the ray's angle to the goal axis clamped to ``window_max_angle_rad``, at
``shoot_distance_m`` from the goal centre, pushed out of the opponent defense area by
``defense_margin_m``. A ball already inside the window (no farther than the shooting
distance + ``window_slack_m``, within the angle) is aimed from where it is. After each
aim that ends without a kick, the next shooting distance is ``retry_step_m`` shorter.

The tactic reads whatever snapshot it is given: under realism the runners give it the
vision tracker's predicted state (``TrackedVisionEnv.vision_state``), as for
:class:`~ssl_marl.plays.shoot.GoToBallAndShoot`.
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass

import numpy as np

from ..physics.field import FieldGeometry
from ..physics.state import WorldState, wrap_angle
from ..skills.base import SkillStatus
from ..skills.features import BALL_LOST_DISTANCE, dribbler_ball_distance
from ..skills.motion import velocity_command
from .shoot import govern_approach
from .tactic_base import NEAR_BALL_M, Tactic, skill_status


class DribbleState(enum.Enum):
    GO_TO_BALL = "go_to_ball"
    RECOVER = "recover"
    CONTROL = "control"
    DRIBBLE = "dribble"
    AIM = "aim"


@dataclass(frozen=True)
class DribbleParams:
    """Every threshold of :class:`DribbleAndShoot` (SI units: m, s, m/s, m/s^2, rad, rad/s).

    Attributes:
        near_ball_m: GO_TO_BALL -> CONTROL when d_db <= this (the paper's 35 mm), or
            when the ball is flagged on the dribbler.
        touch_speed: approach governor's speed at contact (m/s); the learned go-to-ball
            alone hits the ball at ~2.6 m/s.
        approach_decel: governor's deceleration before contact (m/s^2).
        stall_s: GO_TO_BALL -> RECOVER when the robot-ball distance has not shrunk by
            ``stall_progress_m`` (m) within this time (s) ...
        stall_progress_m: ... (m).
        recover_s: RECOVER -> GO_TO_BALL after this long (s) without reaching the ball.
        face_gap_m: GO_TO_BALL: within this gap (m) between the face and the ball ...
        face_before_touch_rad: ... the robot may not move towards the ball while the
            ball is more than this off its heading (rad): touching it sideways pushes it away.
        control_push_speed: CONTROL's forward creep towards the ball (m/s).
        control_decel: CONTROL's limit on how fast the commanded velocity may change
            (m/s^2), below the dribbler's 5 m/s^2.
        secure_s: the ball must be on the dribbler this long (s) before CONTROL ends.
        secure_speed: ... and the robot no faster than this (m/s).
        control_lost_m: CONTROL -> GO_TO_BALL when d_db exceeds this (m).
        control_timeout_s: CONTROL -> GO_TO_BALL after this long without securing (s).
        dribble_speed: top dribbling speed (m/s).
        dribble_accel: limit on the change of the commanded velocity while dribbling
            (m/s^2; the robot's own limit is 3; the dribbler holds at most 5 m/s^2 when
            the robot brakes or turns the velocity).
        dribble_brake: deceleration of the stopping profile at the shooting point (m/s^2).
        dribble_turn_rate: turn-rate cap with the ball (rad/s); the design notes find
            <= 6 rad/s keeps the ball.
        turn_gain: proportional gain of the heading controller (1/s).
        dribble_turn_first_rad: turn in place (no translation) while the heading is
            farther than this from the travel direction (rad).
        face_goal_dist_m: within this distance of the shooting point the heading
            target becomes the goal centre (m).
        arrive_tol_m: DRIBBLE -> AIM when the ball is this close to the shooting point (m).
        arrive_speed: ... and the robot no faster than this (m/s).
        lost_ball_m: DRIBBLE -> GO_TO_BALL when d_db exceeds this (m) (the skills'
            "ball lost" distance).
        shoot_distance_goal_widths: distance from the opponent goal centre to the
            shooting point, in goal widths (1.8: 1.8 m on Division B, 3.24 m on A) ...
        shoot_distance_m: ... or in metres when set (None: goal widths).
        window_max_angle_rad: largest angle between the goal axis (-x from the goal)
            and the ray from the goal centre to the shooting point (rad).
        window_slack_m: a ball up to this much farther than the shooting distance (and
            within the angle) is already in the window (m).
        defense_margin_m: the shooting point keeps this far outside the opponent
            defense area along its ray (m).
        retry_step_m: after an aim without a kick, the next shooting distance is this
            much shorter (m) ...
        min_shoot_distance_m: ... but never below this (m).
        field_margin_m: the shooting point stays this far inside the field lines (m).
    """

    near_ball_m: float = NEAR_BALL_M
    touch_speed: float = 0.5
    approach_decel: float = 2.5
    stall_s: float = 1.0
    stall_progress_m: float = 0.05
    recover_s: float = 2.0
    face_gap_m: float = 0.1
    face_before_touch_rad: float = 0.35
    control_push_speed: float = 0.15
    control_decel: float = 2.0
    secure_s: float = 0.1
    secure_speed: float = 0.35
    control_lost_m: float = 0.06
    control_timeout_s: float = 1.0
    dribble_speed: float = 3.0
    dribble_accel: float = 3.0
    dribble_brake: float = 2.5
    dribble_turn_rate: float = 4.0
    turn_gain: float = 6.0
    dribble_turn_first_rad: float = 0.5
    face_goal_dist_m: float = 0.5
    arrive_tol_m: float = 0.12
    arrive_speed: float = 0.3
    lost_ball_m: float = BALL_LOST_DISTANCE
    shoot_distance_goal_widths: float = 1.8
    shoot_distance_m: float | None = None
    window_max_angle_rad: float = 0.7
    window_slack_m: float = 0.5
    defense_margin_m: float = 0.35
    retry_step_m: float = 0.4
    min_shoot_distance_m: float = 0.9
    field_margin_m: float = 0.3

    def __post_init__(self) -> None:
        for name, value in self.__dict__.items():
            if name == "shoot_distance_m" and value is None:
                continue
            if not (isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)
                    and value >= 0):
                raise ValueError(f"DribbleParams.{name} must be a non-negative finite number, got {value!r}")
        if self.control_lost_m < self.near_ball_m:
            raise ValueError("DribbleParams.control_lost_m must be >= near_ball_m (hysteresis)")
        if self.window_max_angle_rad >= math.pi / 2:
            raise ValueError("DribbleParams.window_max_angle_rad must be below pi/2")


@dataclass(frozen=True)
class DribbleInputs:
    """What :meth:`DribbleAndShoot.transition` reads (team frame).

    Attributes:
        d_db: dribbler-ball distance (m).
        held: the ball is flagged on the robot's dribbler.
        held_s: how long (s) it has been flagged without a break.
        speed: robot speed (m/s).
        time_in_state: seconds since the current state was entered.
        to_target_m: distance from the ball to the current shooting point (m).
        in_window: the ball lies in the shooting window.
        skill_status: status of the running skill after its last tick.
        kicked: a kick was commanded on the previous tick.
        stalled: in GO_TO_BALL, the robot-ball distance has not shrunk by
            ``stall_progress_m`` for ``stall_s``.
    """

    d_db: float
    held: bool = False
    held_s: float = 0.0
    speed: float = 0.0
    time_in_state: float = 0.0
    to_target_m: float = math.inf
    in_window: bool = False
    skill_status: SkillStatus = SkillStatus.RUNNING
    kicked: bool = False
    stalled: bool = False


def _ray_exit(depth: float, half_width: float, cos_a: float, sin_a: float) -> float:
    """Distance along a ray from the goal centre (angle a to the goal axis) to the edge
    of the defense rectangle (depth along the axis, half_width across)."""
    t = math.inf
    if cos_a > 1e-9:
        t = min(t, depth / cos_a)
    if abs(sin_a) > 1e-9:
        t = min(t, half_width / abs(sin_a))
    return t


def shooting_point(field: FieldGeometry, ball: np.ndarray, params: DribbleParams,
                   distance: float | None = None) -> tuple[np.ndarray, bool]:
    """(shooting point (2,), ball already in the window) in the team frame (opponent goal at +x).

    The point lies on the ray from the opponent goal centre towards ``ball``, its angle
    to the goal axis clamped to ``window_max_angle_rad``, at ``distance`` (default
    ``shoot_distance_m``) from the goal centre or farther if that is needed to stay
    ``defense_margin_m`` outside the defense area; then clamped ``field_margin_m`` inside
    the field lines. Default distance: ``shoot_distance_m``, or
    ``shoot_distance_goal_widths`` x the goal width when that is None."""
    p = params
    g = field.goal_center(+1)
    d = np.asarray(ball, float) - g
    ang = math.atan2(d[1], -d[0])  # 0: straight in front of the goal
    a = float(np.clip(ang, -p.window_max_angle_rad, p.window_max_angle_rad))
    ca, sa = math.cos(a), math.sin(a)
    r_min = _ray_exit(field.defense_depth, field.defense_width / 2.0, ca, sa) + p.defense_margin_m
    if distance is None:
        distance = p.shoot_distance_m if p.shoot_distance_m is not None else p.shoot_distance_goal_widths * field.goal_width
    r = max(distance, r_min)
    point = g + r * np.array([-ca, sa])
    lim = np.array([field.half_length - p.field_margin_m, field.half_width - p.field_margin_m])
    point = np.clip(point, -lim, lim)
    dist_ball = float(np.hypot(*d))
    in_window = abs(ang) <= p.window_max_angle_rad and r_min <= dist_ball <= r + p.window_slack_m \
        and d[0] < 0.0
    return point, bool(in_window)


class DribbleAndShoot(Tactic):
    """Take the ball gently, dribble it to a shooting window, aim and shoot (module docstring)."""

    name = "dribble_and_shoot"
    uses_skills = ("go_to_ball", "aim_to_shoot")
    State = DribbleState
    Params = DribbleParams
    Inputs = DribbleInputs
    initial_state = DribbleState.GO_TO_BALL

    def __init__(self, field, robot=None, ball=None, skills="baseline", dt: float = 1.0 / 60.0, **params) -> None:
        self.go_to_ball = None
        super().__init__(field, robot, ball, skills, dt, **params)
        self.go_to_ball = self._skill("go_to_ball")
        self.aim_to_shoot = self._skill("aim_to_shoot")
        self._v_cmd = np.zeros(2)  # last commanded team-frame velocity (m/s) in CONTROL / DRIBBLE
        self._held_s = 0.0
        self._retries = 0
        self._target: np.ndarray | None = None
        self._best: tuple[float, float] | None = None  # (closest robot-ball distance, time) in GO_TO_BALL
        self.stalls = 0
        self.on_enter(self.state)

    def reset(self) -> None:
        self._v_cmd = np.zeros(2)
        self._held_s = 0.0
        self._retries = 0
        self._target = None
        self._best = None
        self.stalls = 0
        super().reset()

    # ------------------------------------------------------------ helpers
    def shoot_distance(self) -> float:
        """The current shooting distance (m): shorter after each aim without a kick."""
        p = self.params
        base = p.shoot_distance_m if p.shoot_distance_m is not None else p.shoot_distance_goal_widths * self.field.goal_width
        return max(base - self._retries * p.retry_step_m, p.min_shoot_distance_m)

    def _current_skill(self):
        return {DribbleState.GO_TO_BALL: self.go_to_ball, DribbleState.AIM: self.aim_to_shoot}.get(self.state)

    # ----------------------------------------------------------- machine
    def observe(self, world: WorldState, robot: int) -> DribbleInputs:
        ts = world.team(world.frame)
        held = bool(ts.ball_on_dribbler[robot])
        self._held_s = self._held_s + self.dt if held else 0.0
        point, in_window = shooting_point(self.field, world.ball_pos, self.params, self.shoot_distance())
        self._target = point
        skill = self._current_skill()
        dist = float(np.hypot(*(world.ball_pos - ts.pos[robot])))
        stalled = False
        if self.state is DribbleState.GO_TO_BALL:
            if self._best is None or dist < self._best[0] - self.params.stall_progress_m:
                self._best = (dist, self._time_in_state)
            stalled = self._time_in_state - self._best[1] > self.params.stall_s
        return DribbleInputs(d_db=dribbler_ball_distance(world, robot, self.rp, self.bp), held=held,
                             held_s=self._held_s, speed=float(np.hypot(*ts.vel[robot])),
                             time_in_state=self._time_in_state,
                             to_target_m=float(np.hypot(*(world.ball_pos - point))), in_window=in_window,
                             skill_status=skill_status(skill) if skill is not None else SkillStatus.RUNNING,
                             kicked=self._kicked, stalled=stalled)

    @staticmethod
    def transition(state: DribbleState, inputs: DribbleInputs, params: DribbleParams) -> DribbleState:
        S, p, i = DribbleState, params, inputs
        if state in (S.GO_TO_BALL, S.RECOVER):
            if i.held or i.d_db <= p.near_ball_m:
                return S.CONTROL
            if state is S.GO_TO_BALL:
                return S.RECOVER if i.stalled else S.GO_TO_BALL
            return S.GO_TO_BALL if i.time_in_state > p.recover_s else S.RECOVER
        if state is S.CONTROL:
            if i.d_db > p.control_lost_m or (i.time_in_state > p.control_timeout_s and not i.held):
                return S.GO_TO_BALL
            if i.held and i.held_s >= p.secure_s - 1e-9 and i.speed <= p.secure_speed:
                return S.AIM if i.in_window else S.DRIBBLE
            return S.CONTROL
        if state is S.DRIBBLE:
            if i.d_db > p.lost_ball_m:
                return S.GO_TO_BALL
            if (i.to_target_m <= p.arrive_tol_m or i.in_window) and i.speed <= p.arrive_speed:
                return S.AIM
            return S.DRIBBLE
        if state is S.AIM:
            if i.kicked:
                return S.GO_TO_BALL
            if i.skill_status is SkillStatus.FAILED:
                return S.DRIBBLE if i.d_db <= p.near_ball_m else S.GO_TO_BALL
            if i.skill_status is SkillStatus.SUCCEEDED:
                return S.GO_TO_BALL
            return S.AIM
        raise ValueError(f"unknown state {state!r}")

    def on_enter(self, state: DribbleState) -> None:
        if self.go_to_ball is None:  # called from the base constructor before the skills exist
            return
        if state is DribbleState.GO_TO_BALL:
            self._retries = 0
            self._best = None
        if state is DribbleState.RECOVER:
            self.stalls += 1
        skill = self._current_skill()
        if skill is not None:
            skill.reset()
        self._v_cmd = None  # re-initialised from the measured velocity on the next tick

    def act(self, world: WorldState, robot: int) -> np.ndarray:
        prev = self.state
        a = super().act(world, robot)
        if prev is DribbleState.AIM and self.state is DribbleState.DRIBBLE:
            self._retries += 1
        return a

    def execute(self, world: WorldState, robot: int, inputs: DribbleInputs) -> np.ndarray:
        S, p = DribbleState, self.params
        if self.state is S.GO_TO_BALL:
            action = self.go_to_ball.act(world, robot)
            action = govern_approach(action, world, robot, self.rp, self.bp, p.touch_speed, p.approach_decel)
            action = self._face_before_touch(world, robot, action)
            action[3] = 1.0  # dribbler on: a learned policy's choice does not matter before contact
            return action
        if self.state is S.AIM:
            return self.aim_to_shoot.act(world, robot)
        ts = world.team(world.frame)
        pos, h = ts.pos[robot], float(ts.heading[robot])
        if self._v_cmd is None:
            self._v_cmd = np.array(ts.vel[robot], dtype=float)
        if self.state is S.RECOVER:
            to_ball = world.ball_pos - pos
            dist = float(np.hypot(*to_ball))
            u = to_ball / max(dist, 1e-9)
            ang = float(math.atan2(u[1], u[0]))
            gap = dist - self.rp.front_distance - self.bp.radius
            speed = math.sqrt(p.touch_speed ** 2 + 2.0 * p.approach_decel * max(gap, 0.0))
            speed = min(speed, self.rp.max_speed)
            if abs(float(wrap_angle(ang - h))) > p.dribble_turn_first_rad and gap < 0.3:
                speed = 0.0  # face the ball before touching it
            return self._command(world, robot, u * speed, self._turn(ang, h, limit=self.rp.max_omega),
                                 self.rp.max_accel)
        if self.state is S.CONTROL:
            to_ball = world.ball_pos - pos
            u = to_ball / max(float(np.hypot(*to_ball)), 1e-9)
            desired = u * p.control_push_speed
            omega = self._turn(float(math.atan2(u[1], u[0])), h)
            return self._command(world, robot, desired, omega, p.control_decel)
        # DRIBBLE: move the ball (held at the face) to the shooting point
        reach = self.rp.front_distance + self.bp.radius
        ball_pt = pos + reach * np.array([math.cos(h), math.sin(h)])
        to_t = self._target - ball_pt
        dist = float(np.hypot(*to_t))
        if dist > p.face_goal_dist_m:
            h_des = math.atan2(to_t[1], to_t[0])
        else:
            g = self.field.goal_center(+1) - ball_pt
            h_des = math.atan2(g[1], g[0])
        err_travel = abs(float(wrap_angle(math.atan2(to_t[1], to_t[0]) - h))) if dist > 1e-6 else 0.0
        speed = min(p.dribble_speed, math.sqrt(2.0 * p.dribble_brake * max(dist - 0.02, 0.0)))
        if dist > p.face_goal_dist_m and err_travel > p.dribble_turn_first_rad:
            speed = 0.0
        desired = to_t / max(dist, 1e-9) * speed
        return self._command(world, robot, desired, self._turn(h_des, h), p.dribble_accel)

    def _face_before_touch(self, world: WorldState, robot: int, action: np.ndarray) -> np.ndarray:
        """Within ``face_gap_m`` of contact, remove the velocity component towards the ball
        while the ball is more than ``face_before_touch_rad`` off the heading: a skill that
        reaches the ball sideways pushes it away with the robot's side or a face corner."""
        p = self.params
        ts = world.team(world.frame)
        pos, h = ts.pos[robot], float(ts.heading[robot])
        to_ball = world.ball_pos - pos
        dist = float(np.hypot(*to_ball))
        gap = dist - self.rp.front_distance - self.bp.radius
        bearing = abs(float(wrap_angle(math.atan2(to_ball[1], to_ball[0]) - h)))
        if gap > p.face_gap_m or bearing <= p.face_before_touch_rad:
            return action
        a = np.array(action, dtype=np.float32, copy=True)
        c, s_ = math.cos(h), math.sin(h)
        v_field = np.array([c * a[0] - s_ * a[1], s_ * a[0] + c * a[1]])
        u = to_ball / max(dist, 1e-9)
        toward = float(v_field @ u)
        if toward > 0.0:
            v_field = v_field - toward * u
        a[0], a[1] = c * v_field[0] + s_ * v_field[1], -s_ * v_field[0] + c * v_field[1]
        return a

    def _turn(self, h_des: float, h: float, limit: float | None = None) -> float:
        p = self.params
        lim = p.dribble_turn_rate if limit is None else limit
        return float(np.clip(p.turn_gain * float(wrap_angle(h_des - h)), -lim, lim))

    def _command(self, world: WorldState, robot: int, desired: np.ndarray, omega: float, accel: float) -> np.ndarray:
        """Move the commanded velocity towards ``desired`` by at most accel * dt; dribbler on."""
        dv = np.asarray(desired, float) - self._v_cmd
        n = float(np.hypot(*dv))
        lim = accel * self.dt
        if n > lim:
            dv *= lim / n
        self._v_cmd = self._v_cmd + dv
        return velocity_command(world, robot, self._v_cmd, omega, self.rp, dribble=True)


__all__ = ["DribbleState", "DribbleParams", "DribbleInputs", "DribbleAndShoot", "shooting_point"]
