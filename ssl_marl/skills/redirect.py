"""The redirect (one-touch) skill: meet a moving ball and send it on towards the open
part of the opponent goal without stopping it, hand-coded and learned.

In this physics a kick sets the ball's velocity along the robot's heading (at the kick
speed), whatever the ball's incoming velocity, so the heading at contact *is* the
outgoing direction; with ``RobotParams.kick_on_contact`` an armed kicker fires at the
first physics sub-step the ball reaches the face. A redirect is therefore: be on the
ball's path with the face towards the target before the ball arrives, kicker armed.
(On a real robot the ball's incoming speed adds to the kick and the face's normal has
to be turned part of the way back towards the incoming line; TIGERs rate a redirect
fully useful up to 0.9 rad of deflection and useless beyond 1.2 rad,
docs/references.md, "Passing and pass rating".)

State (spec ``redirect/v1``, 14 values, float32; robot frame: +x forward, +y left; m, m/s, rad/s):

====  ==================  ==========================================================
  0-1  ball_x, ball_y      ball position
  2-3  ball_vx, ball_vy    ball velocity
  4-5  robot_vx, robot_vy  robot velocity
  6    robot_omega         robot turn rate
  7-8  target_x, target_y  the aim point in the goal mouth (:func:`open_goal_target`)
 9-10  keeper_x, keeper_y  the opponent nearest its goal (goal centre when none)
  11   line_offset         signed distance of the robot centre from the ball's line
  12   gap                 distance along the line from the ball to the face point
  13   closing_speed       ball speed minus the robot's speed along the ball's direction
====  ==================  ==========================================================

Action (three forms): ``direct`` (``redirect/v1``): (vx, vy, omega), robot frame,
fractions of the robot's limits; ``residual`` (``redirect/v2``): a correction (at most
:data:`REDIRECT_RESIDUAL_SCALE` of each limit) added to :class:`RedirectBaseline`'s
(vx, vy, omega); ``aim`` (``redirect/v3``): one value, the aim point's y along the goal
mouth (:func:`redirect_aim_point`: -1 / +1 = :data:`REDIRECT_AIM_POST_MARGIN` inside the
right / left post), which :class:`RedirectBaseline`'s contact planner executes. The
kicker is always armed at full strength, the dribbler off.

The ``aim`` form's state (``redirect/v3``, 21 values) is the 14 above followed by
seven team-frame values (+x towards the opponent goal; m, m/s):

======  ======================  =======================================================
 14-15  robot_fx, robot_fy      robot position
 16-17  keeper_fx, keeper_fy    the keeper's position (:func:`keeper_position`)
 18-19  keeper_fvx, keeper_fvy  the keeper's velocity (zero when the opponents have none)
   20   hand_aim_y              y of the hand-coded aim point (:func:`open_goal_target`
                                from the robot's position)
======  ======================  =======================================================
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..physics import ball_model
from ..physics.field import FieldGeometry
from ..physics.params import BallParams, RobotParams
from ..physics.state import WorldState, wrap_angle
from .base import SkillBase, SkillStatus, make_action
from .baseline import GoToBallBaseline
from .features import rotate_to_robot, to_robot_frame
from .motion import approach_speed, velocity_command
from .passing_features import ball_line_geometry
from .receive_task import robot_travel_time

REDIRECT_SPEC = "redirect/v1"
REDIRECT_SPEC_RESIDUAL = "redirect/v2"
REDIRECT_SPEC_AIM = "redirect/v3"
#: action forms (the registry's action-mapping names) -> spec strings; "direct" first (the default)
REDIRECT_ACTION_FORMS = {"direct": REDIRECT_SPEC, "residual": REDIRECT_SPEC_RESIDUAL, "aim": REDIRECT_SPEC_AIM}
#: largest correction (fraction of each velocity / turn-rate limit) a residual action adds
REDIRECT_RESIDUAL_SCALE = 0.5
REDIRECT_NAMES = ("ball_x", "ball_y", "ball_vx", "ball_vy", "robot_vx", "robot_vy", "robot_omega", "target_x",
                  "target_y", "keeper_x", "keeper_y", "line_offset", "gap", "closing_speed")
REDIRECT_ACTIONS = ("vx", "vy", "omega")
REDIRECT_AIM_NAMES = REDIRECT_NAMES + ("robot_fx", "robot_fy", "keeper_fx", "keeper_fy", "keeper_fvx", "keeper_fvy",
                                      "hand_aim_y")
REDIRECT_AIM_ACTIONS = ("aim_y",)
#: distance (m) inside each post of the outermost aim points (the hand-coded aim's margin)
REDIRECT_AIM_POST_MARGIN = 0.04
#: the kick strength a redirect arms (full: kick_speed_max)
REDIRECT_KICK = 1.0


def check_redirect_action_form(form: str) -> str:
    """``form`` if it is a known action form; ValueError listing them otherwise."""
    if form not in REDIRECT_ACTION_FORMS:
        raise ValueError(f"redirect action_form must be one of {tuple(REDIRECT_ACTION_FORMS)}, got {form!r}")
    return form


def keeper_index(world: WorldState, field: FieldGeometry) -> int | None:
    """Index among the opponents of the one nearest the opponent goal's centre (+x,
    team frame), or None when the opponents have no robot."""
    opp = world.opponents(world.frame).pos
    if len(opp) == 0:
        return None
    return int(np.argmin(np.hypot(*(opp - np.array([field.half_length, 0.0])).T)))


def keeper_position(world: WorldState, field: FieldGeometry) -> np.ndarray:
    """Team-frame position (m) of the opponent :func:`keeper_index` picks, or the
    opponent goal's centre when the opponents have no robot."""
    k = keeper_index(world, field)
    if k is None:
        return np.array([field.half_length, 0.0])
    return world.opponents(world.frame).pos[k].astype(float)


def keeper_velocity(world: WorldState, field: FieldGeometry) -> np.ndarray:
    """Team-frame velocity (m/s) of the opponent :func:`keeper_index` picks (zero when
    the opponents have no robot)."""
    k = keeper_index(world, field)
    return np.zeros(2) if k is None else world.opponents(world.frame).vel[k].astype(float)


def open_goal_target(from_xy: np.ndarray, world: WorldState, field: FieldGeometry, rp: RobotParams,
                     bp: BallParams, post_margin: float = 0.04, n: int = 21) -> np.ndarray:
    """The point of the opponent goal mouth (team frame, x = half_length) whose shot
    line from ``from_xy`` passes farthest from the keeper (:func:`keeper_position`);
    candidates ``n`` points between the posts, ``post_margin`` (m) inside them."""
    half = field.goal_width / 2.0 - post_margin
    ys = np.linspace(-half, half, n)
    keeper = keeper_position(world, field)
    a = np.asarray(from_xy, float)
    best, best_d = np.array([field.half_length, 0.0]), -math.inf
    for y in ys:
        b = np.array([field.half_length, y])
        ab = b - a
        s = float(np.clip((keeper - a) @ ab / max(float(ab @ ab), 1e-9), 0.0, 1.0))
        d = float(np.hypot(*(a + s * ab - keeper)))
        if d > best_d + 1e-9:
            best, best_d = b, d
    return best


def redirect_features(world: WorldState, robot: int, field: FieldGeometry, robot_params: RobotParams,
                      ball_params: BallParams) -> np.ndarray:
    """The 14 redirect state values (float32), see the module table."""
    ts = world.team(world.frame)
    pos, h = ts.pos[robot], float(ts.heading[robot])
    target = open_goal_target(pos, world, field, robot_params, ball_params)
    offset, gap, closing, _ = ball_line_geometry(world, robot, robot_params, ball_params)
    return np.concatenate([
        to_robot_frame(world.ball_pos, pos, h), rotate_to_robot(world.ball_vel, h), rotate_to_robot(ts.vel[robot], h),
        [float(ts.omega[robot])], to_robot_frame(target, pos, h),
        to_robot_frame(keeper_position(world, field), pos, h), [offset, gap, closing]]).astype(np.float32)


def redirect_aim_features(world: WorldState, robot: int, field: FieldGeometry, robot_params: RobotParams,
                          ball_params: BallParams) -> np.ndarray:
    """The 21 ``redirect/v3`` state values (float32): :func:`redirect_features` and the
    seven team-frame values of the module's second table."""
    pos = world.team(world.frame).pos[robot]
    hand_aim = open_goal_target(pos, world, field, robot_params, ball_params)
    return np.concatenate([redirect_features(world, robot, field, robot_params, ball_params), pos,
                           keeper_position(world, field), keeper_velocity(world, field),
                           [hand_aim[1]]]).astype(np.float32)


def redirect_aim_point(action1: np.ndarray, field: FieldGeometry,
                       post_margin: float = REDIRECT_AIM_POST_MARGIN) -> np.ndarray:
    """The ``aim`` action (one value, clipped to [-1, 1]) -> the team-frame aim point
    (half_length, a * (goal_width / 2 - post_margin)) (m); ValueError for NaN or inf."""
    a = np.asarray(action1, dtype=np.float64).reshape(1)
    if not np.isfinite(a).all():
        raise ValueError(f"redirect aim action contains NaN or inf: {a.tolist()}")
    half = field.goal_width / 2.0 - post_margin
    return np.array([field.half_length, float(np.clip(a[0], -1.0, 1.0)) * half])


def redirect_aim_of(target: np.ndarray | None, field: FieldGeometry,
                    post_margin: float = REDIRECT_AIM_POST_MARGIN) -> np.ndarray:
    """Inverse of :func:`redirect_aim_point` (float32 (1,), clipped to [-1, 1]); 0 (the
    goal centre) when ``target`` is None."""
    if target is None:
        return np.zeros(1, dtype=np.float32)
    half = field.goal_width / 2.0 - post_margin
    return np.array([np.clip(float(target[1]) / half, -1.0, 1.0)], dtype=np.float32)


def redirect_task_action(action5: np.ndarray) -> np.ndarray:
    """A full (5,) env action -> the task's (vx, vy, omega)."""
    return np.asarray(action5, dtype=np.float32).reshape(5)[:3].copy()


def expand_redirect_action(action3: np.ndarray) -> np.ndarray:
    """The task's (vx, vy, omega) (clipped to [-1, 1]) -> a (5,) env action, dribbler
    off, kicker armed at :data:`REDIRECT_KICK`."""
    a = np.clip(np.asarray(action3, dtype=np.float64).reshape(3), -1.0, 1.0)
    return make_action(a[0], a[1], a[2], dribble=False, kick=REDIRECT_KICK)


def redirect_residual_action(base3: np.ndarray, correction3: np.ndarray,
                             scale: float = REDIRECT_RESIDUAL_SCALE) -> np.ndarray:
    """The ``residual`` action: ``clip(base3 + scale * clip(correction3), -1, 1)``."""
    c = np.clip(np.asarray(correction3, dtype=np.float64).reshape(3), -1.0, 1.0)
    return np.clip(np.asarray(base3, dtype=np.float64).reshape(3) + scale * c, -1.0, 1.0).astype(np.float32)


def redirect_residual_of(base3: np.ndarray, action3: np.ndarray, scale: float = REDIRECT_RESIDUAL_SCALE) -> np.ndarray:
    """Inverse of :func:`redirect_residual_action` (clipped to [-1, 1]; 0 when equal)."""
    d = (np.asarray(action3, dtype=np.float64).reshape(3) - np.asarray(base3, dtype=np.float64).reshape(3)) / scale
    return np.clip(d, -1.0, 1.0).astype(np.float32)


class RedirectSkill(SkillBase):
    """redirect, hand-coded or learned: RUNNING until the robot has kicked the ball
    (SUCCEEDED; the kicker fires on contact, so success is the touch, not the goal)."""

    name = "redirect"

    def act(self, world: WorldState, robot: int) -> np.ndarray:
        if self.status is SkillStatus.SUCCEEDED:
            return make_action()
        ts = world.team(world.frame)
        if not bool(ts.kick_ready[robot]):  # the kicker is recharging: it has just fired
            self.status = SkillStatus.SUCCEEDED
            return make_action()
        return self.control(world, robot)

    def control(self, world: WorldState, robot: int) -> np.ndarray:
        raise NotImplementedError


class RedirectBaseline(RedirectSkill):
    """Hand-coded redirect.

    * Aim point: :func:`open_goal_target` seen from the contact point, or ``aim`` (a
      team-frame point, m) when it is set (the ``aim`` action form sets it each step).
    * Contact point Q on the ball's predicted path (:mod:`ssl_marl.physics.ball_model`):
      the first point, from the robot's projection onto the line on, that the robot can
      reach (:func:`robot_travel_time` + ``margin_s``) before the ball does (0.1 s,
      hand-tuned on development episodes: a longer margin meets fast passes later, farther
      from the goal, and the goalie saves more of those shots). The point is kept while
      the ball's path passes within 0.1 m of it, ahead of the ball, and moved onto the
      path as seen each step (same distance along it): a path first estimated from noisy
      or delayed vision shifts by a few cm as the ball comes, and a face left on the
      first estimate lets the ball pass in front of it or glance off its edge. The robot's
      centre goes to ``Q - (front_distance + ball radius) * heading``, heading = the
      direction from Q to the aim point, so the face meets the ball square on the path.
    * Motion: straight to that spot braking in time (``approach_speed``), at most
      ``gain`` x distance; turn at ``turn_gain`` x heading error.
    * Kicker armed at full strength throughout, dribbler off; a ball slower than
      ``slow_ball`` (m/s), or one that has passed the robot, is fetched with the
      go-to-ball baseline (kicker still armed: it fires towards the current heading).
    """

    def __init__(self, field: FieldGeometry, robot: RobotParams | None = None, ball: BallParams | None = None,
                 margin_s: float = 0.1, gain: float = 6.0, turn_gain: float = 8.0, slow_ball: float = 0.3,
                 ds: float = 0.05) -> None:
        super().__init__(field, robot, ball)
        self.margin_s, self.gain, self.turn_gain, self.slow_ball, self.ds = margin_s, gain, turn_gain, slow_ball, ds
        self._fetch = GoToBallBaseline(field, self.rp, self.bp)
        self._contact: np.ndarray | None = None  #: the contact point chosen (team frame, m)
        self.aim: np.ndarray | None = None  #: fixed aim point (team frame, m); None: open_goal_target
        self.last_target: np.ndarray | None = None  #: the aim point of the last plan (None: no plan)

    def reset(self) -> None:
        super().reset()
        self._contact = None
        self.last_target = None

    def _target(self, q: np.ndarray, world: WorldState) -> np.ndarray:
        """The aim point (team frame, m) for a contact at ``q``."""
        if self.aim is not None:
            return self.aim
        return open_goal_target(q, world, self.field, self.rp, self.bp)

    def aim_action(self) -> np.ndarray:
        """The last plan's aim point as an ``aim`` action (:func:`redirect_aim_of`)."""
        return redirect_aim_of(self.last_target, self.field)

    def contact_plan(self, world: WorldState, robot: int) -> tuple[np.ndarray, float] | None:
        """(robot centre target (m), heading (rad)) for the contact, or None when the
        ball is slow or has passed the robot."""
        ts = world.team(world.frame)
        pos = ts.pos[robot]
        v = float(np.hypot(*world.ball_vel))
        if v < self.slow_ball:
            return None
        u = world.ball_vel / v
        reach = self.rp.front_distance + self.bp.radius
        s0 = float((pos - world.ball_pos) @ u)
        if s0 < -0.05:
            return None
        s_stop = ball_model.stop_distance(v, self.bp, sliding=False)
        if self._contact is not None:  # keep the chosen contact point while it stays on the ball's path, ahead
            d = self._contact - world.ball_pos
            s_c = float(d @ u)
            if abs(float(u[0] * d[1] - u[1] * d[0])) < 0.1 and 0.0 < s_c < s_stop:
                self._contact = world.ball_pos + u * s_c  # onto the ball's path as now seen
                tgt = self.last_target = self._target(self._contact, world)
                h = math.atan2(tgt[1] - self._contact[1], tgt[0] - self._contact[0])
                return self._contact - reach * np.array([math.cos(h), math.sin(h)]), h
        plan = None
        for s in np.arange(max(s0 - reach, 0.0), s_stop, self.ds):
            q = world.ball_pos + u * s
            if not bool(self.field.in_field(q, 0.05)):
                break
            tgt = self._target(q, world)
            h = math.atan2(tgt[1] - q[1], tgt[0] - q[0])
            centre = q - reach * np.array([math.cos(h), math.sin(h)])
            plan = (centre, h)
            self.last_target = tgt
            self._contact = q
            t_ball = ball_model.time_to_distance(v, s, self.bp, sliding=False)
            if robot_travel_time(float(np.hypot(*(centre - pos))), self.rp) + self.margin_s <= t_ball:
                return plan
        return plan

    def control(self, world: WorldState, robot: int) -> np.ndarray:
        plan = self.contact_plan(world, robot)
        if plan is None:
            self.last_target = None
            a = self._fetch.approach(world, robot)
            a[3], a[4] = -1.0, REDIRECT_KICK
            return a
        centre, h_goal = plan
        ts = world.team(world.frame)
        pos, h = ts.pos[robot], float(ts.heading[robot])
        d = centre - pos
        dist = float(np.hypot(*d))
        speed = min(approach_speed(dist, self.rp), self.gain * dist)
        v = d / dist * speed if dist > 1e-9 else np.zeros(2)
        omega = float(np.clip(self.turn_gain * float(wrap_angle(h_goal - h)), -self.rp.max_omega, self.rp.max_omega))
        return velocity_command(world, robot, v, omega, self.rp, dribble=False, kick=REDIRECT_KICK)

    def task_action(self, world: WorldState, robot: int) -> np.ndarray:
        """The hand-coded (vx, vy, omega) in ``world`` (stateless; the residual's base)."""
        return redirect_task_action(self.control(world, robot))


class LearnedRedirect(RedirectSkill):
    """Learned redirect: the trained actor maps :func:`redirect_features` to (vx, vy,
    omega); the checkpoint's spec picks the action form (``redirect/v2``: a correction of
    :class:`RedirectBaseline`'s action; ``redirect/v3``: the actor maps
    :func:`redirect_aim_features` to the aim point, :class:`RedirectBaseline`'s contact
    planner moves the robot). With ``policy`` given directly, ``action_form`` says which."""

    def __init__(self, field: FieldGeometry, robot: RobotParams | None = None, ball: BallParams | None = None,
                 checkpoint: str | Path | None = None, policy=None, action_form: str = "direct") -> None:
        super().__init__(field, robot, ball)
        if policy is None:
            from .learned import load_policy

            policy, meta = load_policy("redirect", checkpoint)
            action_form = next(k for k, v in REDIRECT_ACTION_FORMS.items() if v == meta["obs_spec"])
        self.policy, self.action_form = policy, check_redirect_action_form(action_form)
        self._base = RedirectBaseline(field, self.rp, self.bp) if self.action_form != "direct" else None

    def reset(self) -> None:
        """As :meth:`SkillBase.reset`, with a fresh hand-coded planner: its contact point and
        aim are per-run state, and copies of one learned prototype (the tactics' skills,
        :mod:`ssl_marl.plays.skillset`) must not share them."""
        super().reset()
        if self._base is not None:
            self._base = RedirectBaseline(self.field, self.rp, self.bp)

    def aim_action(self) -> np.ndarray:
        """The ``aim`` form's last aim as an action (:func:`redirect_aim_of`); ValueError
        for the other forms, which choose no aim point."""
        if self.action_form != "aim":
            raise ValueError(f"a {self.action_form!r} learned redirect chooses no aim point")
        return self._base.aim_action()

    def control(self, world: WorldState, robot: int) -> np.ndarray:
        if self.action_form == "aim":
            aim = self.policy(redirect_aim_features(world, robot, self.field, self.rp, self.bp))
            self._base.aim = redirect_aim_point(aim, self.field)
            return self._base.control(world, robot)
        a3 = self.policy(redirect_features(world, robot, self.field, self.rp, self.bp))
        if self._base is not None:
            a3 = redirect_residual_action(self._base.task_action(world, robot), a3)
        return expand_redirect_action(a3)


__all__ = ["LearnedRedirect", "REDIRECT_ACTIONS", "REDIRECT_ACTION_FORMS", "REDIRECT_AIM_ACTIONS", "REDIRECT_AIM_NAMES",
           "REDIRECT_AIM_POST_MARGIN", "REDIRECT_NAMES", "REDIRECT_SPEC", "REDIRECT_SPEC_AIM", "REDIRECT_SPEC_RESIDUAL",
           "RedirectBaseline", "RedirectSkill", "expand_redirect_action", "keeper_index", "keeper_position", "keeper_velocity",
           "open_goal_target", "redirect_aim_features", "redirect_aim_of", "redirect_aim_point", "redirect_features",
           "redirect_residual_action", "redirect_residual_of", "redirect_task_action"]
