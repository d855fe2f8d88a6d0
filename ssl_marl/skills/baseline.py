"""Hand-coded skills: the paper's baselines and the fixed skills tactics need.

All implement :class:`ssl_marl.skills.base.Skill`: ``act(world, robot)`` with a
team-frame snapshot, returning a normalised (5,) action, and a ``status``. Their motion
primitives are in :mod:`ssl_marl.skills.motion`; the move-to-point skill is
:class:`ssl_marl.skills.navigation.MoveToPoint`.
"""

from __future__ import annotations

import math

import numpy as np

from ..physics.state import WorldState, wrap_angle
from .base import AimToShootSkill, GoToBallSkill, SkillBase, SkillStatus, make_action
from .features import goal_post_angles
from .motion import approach_speed, robot_motion, velocity_command


class GoToBallBaseline(GoToBallSkill):
    """The paper's existing go-to-ball: move in a straight line to the ball while
    turning to face it; slow down to touch it with the dribbler.

    The robot drives straight at the contact point in front of the (slightly led)
    ball, turns towards the ball with a proportional controller, and, if it is not yet
    facing the ball when it gets close, holds a 0.15 m stand-off until it is.
    Succeeds when the ball is on the dribbler.
    """

    name = "go_to_ball"

    def __init__(self, field, robot=None, ball=None, turn_gain: float = 6.0, touch_speed: float = 0.6):
        super().__init__(field, robot, ball)
        self.turn_gain, self.touch_speed = turn_gain, touch_speed

    def approach(self, world: WorldState, robot: int) -> np.ndarray:
        pos, h, _ = robot_motion(world, robot)
        rp = self.rp
        reach = rp.front_distance + self.bp.radius
        d_ball = world.ball_pos - pos
        dist = float(np.hypot(*d_ball))
        lead = min(dist / rp.max_speed, 0.5)
        target_ball = world.ball_pos + world.ball_vel * lead
        to_ball = target_ball - pos
        dist_t = float(np.hypot(*to_ball))
        u = to_ball / max(dist_t, 1e-9)
        ang = math.atan2(to_ball[1], to_ball[0])
        err = float(wrap_angle(ang - h))
        standoff = 0.0 if abs(err) < 0.25 else 0.15
        gap = dist_t - reach - standoff
        speed = approach_speed(gap, rp, v_end=self.touch_speed if standoff == 0.0 else 0.0)
        if gap <= 0.0 and standoff > 0.0:
            speed = 0.0
        v = u * speed + (world.ball_vel if dist < 0.5 else 0.0)
        omega = float(np.clip(self.turn_gain * err, -rp.max_omega, rp.max_omega))
        return velocity_command(world, robot, v, omega, rp, dribble=True)


class AimToShootBaseline(AimToShootSkill):
    """The paper's existing aim-to-shoot: turn towards the goal with the dribbler on
    and shoot at full strength at the first opportunity, i.e. as soon as the heading
    lies between the posts. Turns at most ``max_turn_rate`` (rad/s), slow enough to
    keep the ball. Succeeds on the kick (the tactic then watches the ball); fails if
    the ball leaves the dribbler before the kick."""

    name = "aim_to_shoot"

    def __init__(self, field, robot=None, ball=None, max_turn_rate: float = 5.0, turn_gain: float = 8.0,
                 post_margin: float = 0.0):
        super().__init__(field, robot, ball)
        self.max_turn_rate, self.turn_gain, self.post_margin = max_turn_rate, turn_gain, post_margin

    def aim(self, world: WorldState, robot: int) -> tuple[np.ndarray, bool]:
        al, ar = goal_post_angles(world, robot, self.field)
        if al - self.post_margin > 0.0 > ar + self.post_margin and bool(world.team(world.frame).kick_ready[robot]):
            return make_action(dribble=True, kick=1.0), True
        err = float(wrap_angle((al + ar) / 2.0)) if abs(al - ar) < math.pi else al
        omega = float(np.clip(self.turn_gain * err, -self.max_turn_rate, self.max_turn_rate))
        return make_action(omega=omega / self.rp.max_omega, dribble=True), False


class DriveForward(SkillBase):
    """The paper's fixed skill: dribbler on, drive forward for ``duration_s`` (1 s) at
    ``speed`` (m/s). Succeeds when the time is up. The speed ramps down linearly over the
    last ``ramp_s`` (0.3 s) so that the robot is nearly at rest when the next skill
    starts: stopping at the full 6 m/s^2 braking limit would throw the ball off the
    dribbler (its bounded force holds it up to 5 m/s^2)."""

    name = "drive_forward"

    def __init__(self, field, robot=None, ball=None, duration_s: float = 1.0, speed: float = 0.5,
                 dt: float = 1.0 / 60.0, ramp_s: float = 0.3):
        super().__init__(field, robot, ball)
        self.duration_s, self.speed, self.dt, self.ramp_s = duration_s, speed, dt, ramp_s
        self.elapsed = 0.0

    def reset(self) -> None:
        super().reset()
        self.elapsed = 0.0

    def act(self, world: WorldState, robot: int) -> np.ndarray:
        remaining = self.duration_s - self.elapsed
        self.elapsed += self.dt
        if self.elapsed >= self.duration_s - 1e-9:
            self.status = SkillStatus.SUCCEEDED
        ramp = min(1.0, max(remaining - self.dt, 0.0) / self.ramp_s) if self.ramp_s > 0 else 1.0
        return make_action(vx=self.speed * ramp / self.rp.max_speed, dribble=True)

