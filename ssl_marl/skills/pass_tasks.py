"""Gymnasium tasks of the pass and receive skills (``ssl_marl/Pass-v0``,
``ssl_marl/Receive-v0``), in the style of :mod:`ssl_marl.skills.wrappers`: the full-field
env underneath with the referee off, features from what the robot sees
(``env.vision_state``), rewards and outcomes from the ground truth, ``realism=...``
passed through. States, actions and rewards: :mod:`ssl_marl.skills.passing_features`.

Also the demonstration generators (the hand-coded skills, successful episodes only) for
the trainer's replay burn-in and behaviour-cloning term.
"""

from __future__ import annotations

import math
from typing import Any, Iterator

import gymnasium
import numpy as np
from gymnasium.utils import EzPickle

from ..envs.observation import clip_to_bounds, position_extent, speed_caps
from ..envs.ssl_env import SSLParallelEnv
from ..physics import ball_model
from ..physics.field import FieldGeometry
from ..physics.params import BallParams, RobotParams
from ..physics.state import WorldState, to_team_frame
from .base import make_action
from .demos import Transition, successful_skill_demos
from .features import BALL_LOST_DISTANCE, dribbler_ball_distance
from .motion import velocity_command
from .passing import PassBaseline, ReceiveBaseline
from .passing_features import (
    PASS_SPEC,
    RECEIVE_ACTION_FORMS,
    RECEIVE_SPEC,
    check_point,
    check_receive_action_form,
    expand_pass_action,
    expand_receive_action,
    pass_aim_error,
    pass_features,
    pass_reward,
    pass_task_action,
    receive_features,
    receive_outcome_reward,
    receive_residual_action,
    receive_residual_of,
    receive_reward,
    receive_task_action,
)

PASSER, RECEIVER = "blue_0", "blue_1"


def _check_action(action: Any, dim: int) -> np.ndarray:
    a = np.asarray(action, dtype=np.float64)
    if a.shape != (dim,):
        raise ValueError(f"action must have shape ({dim},), got {a.shape}")
    if not np.isfinite(a).all():
        raise ValueError(f"action contains NaN or inf: {a.tolist()}")
    return np.clip(a, -1.0, 1.0)


def _positive(name: str, v: float) -> float:
    if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
        raise ValueError(f"{name} must be a positive finite number, got {v!r}")
    return float(v)


class _PassingEnv(gymnasium.Env, EzPickle):
    """Shared plumbing: an inner full-field env with ``n_blue`` blue robots and no referee."""

    metadata = {"render_modes": ["rgb_array", "human"], "render_fps": 60}
    spec_version = ""

    def __init__(self, n_blue: int, field: str = "div_b", realism: Any = "none", realtime: bool = False,
                 render_mode: str | None = None, **env_kwargs: Any) -> None:
        self.render_mode = render_mode
        self.env = SSLParallelEnv(n_blue=n_blue, n_yellow=0, field=field, realism=realism, realtime=realtime,
                                  referee=False, max_time_s=1e9, render_mode=render_mode, obs_max_teammates=0,
                                  obs_max_opponents=0, **env_kwargs)
        self.field: FieldGeometry = self.env.field
        self.robot_params: RobotParams = self.env.config.robot
        self.ball_params: BallParams = self.env.config.ball
        self.dt = self.env.config.dt

    @property
    def t(self) -> float:
        """Simulated time since the episode started (s)."""
        return self.env.world_state().t

    def seen(self) -> WorldState:
        return self.env.vision_state("blue")

    def truth(self) -> WorldState:
        return to_team_frame(self.env.world_state(), "blue")

    def _reset_inner(self, seed: int | None, robots: dict, ball_pos, ball_vel=None) -> None:
        opts = {"robots": robots, "ball": {"pos": tuple(ball_pos),
                                           "vel": tuple(np.zeros(2) if ball_vel is None else ball_vel)}}
        self.env.reset(seed=None if seed is None else int(self.np_random.integers(2 ** 31)), options=opts)

    def _ball_out(self, truth: WorldState) -> bool:
        return not bool(self.field.in_field(truth.ball_pos, -self.ball_params.radius))

    def render(self):
        return self.env.render()

    def close(self) -> None:
        self.env.close()


# ---------------------------------------------------------------------- receive

def passing_observation_bounds(task: str, field: FieldGeometry, robot: RobotParams) -> tuple[np.ndarray, np.ndarray]:
    """(low, high) float32 bounds of the pass (10 values) or receive (11 values) state,
    from the rules of the full-field env (:mod:`ssl_marl.envs.observation`): robot-frame
    points and distances within D, the largest distance between two observable positions;
    velocities within the speed caps x safety factor; sin/cos in [-1, 1]; flags in [0, 1].
    Wide enough that they never bind in play; observations are clipped into them."""
    x, y = position_extent(field)
    d = math.hypot(2 * x, 2 * y)
    v, w, vb = speed_caps(robot)
    if task == "pass":  # target xy, target v, dist, sin/cos bearing, ball xy, omega
        high = [d, d, v, v, d, 1, 1, d, d, w]
        low = [-d, -d, -v, -v, 0.0, -1, -1, -d, -d, -w]
    elif task == "receive":  # ball xy, ball v, robot v, omega, line offset, gap, closing speed, on dribbler
        high = [d, d, vb, vb, v, v, w, d, d, vb + v, 1]
        low = [-d, -d, -vb, -vb, -v, -v, -w, -d, -d, -(vb + v), 0]
    else:
        raise ValueError(f"unknown passing task {task!r}; expected 'pass' or 'receive'")
    return np.array(low, dtype=np.float32), np.array(high, dtype=np.float32)

def robot_travel_time(distance: float, rp: RobotParams) -> float:
    """Shortest time (s) for a robot at rest to cover ``distance`` (m) in a straight line
    (accelerating at ``max_accel`` up to ``max_speed``, no need to stop)."""
    d_acc = rp.max_speed ** 2 / (2.0 * rp.max_accel)
    if distance <= d_acc:
        return math.sqrt(2.0 * distance / rp.max_accel)
    return rp.max_speed / rp.max_accel + (distance - d_acc) / rp.max_speed


def receive_feasible(robot_xy: np.ndarray, ball_xy: np.ndarray, ball_vel: np.ndarray, rp: RobotParams,
                     bp: BallParams, field: FieldGeometry, margin_s: float = 0.3, max_closing: float = 1.5,
                     ds: float = 0.05) -> bool:
    """True if a robot at rest at ``robot_xy`` can be on the path of a just-kicked ball
    (sliding, at ``ball_xy`` with ``ball_vel``; team frame, m, m/s) at some point before
    the ball, inside the field, while the ball there is slow enough to catch moving at
    most the robot's top speed along it (ball speed <= ``max_speed + max_closing``).
    The robot's time is :func:`robot_travel_time` of the straight-line distance to its
    receiving position plus ``margin_s`` (to turn and settle)."""
    v = float(np.hypot(*ball_vel))
    if v <= 0:
        return False
    u = np.asarray(ball_vel, float) / v
    reach = rp.front_distance + bp.radius
    s_stop = ball_model.stop_distance(v, bp)
    for s in np.arange(0.0, s_stop + ds, ds):
        p = ball_xy + u * s
        if not bool(field.in_field(p, 0.15)):
            break
        t_ball = ball_model.time_to_distance(v, s, bp)
        speed = ball_model.speed_at_distance(v, s, bp)
        centre = p + u * reach
        if speed <= rp.max_speed + max_closing and \
                robot_travel_time(float(np.hypot(*(centre - robot_xy))), rp) + margin_s <= t_ball:
            return True
    return False


class ReceiveEnv(_PassingEnv):
    """receive: intercept a moving ball and hold it on the dribbler for 0.5 s.

    Observation
        ``Box(-inf, inf, (11,), float32)``, spec ``receive/v1``:
        :func:`ssl_marl.skills.passing_features.receive_features`.
    Action
        ``Box(-1, 1, (3,), float32)``, dribbler on; ``action_form``:
        ``"direct"`` (spec ``receive/v1``, default): (vx, vy, omega), robot frame,
        fractions of the robot's limits; ``"residual"`` (spec ``receive/v2``): a
        correction added to the hand-coded receive's (vx, vy, omega) in the state the
        robot sees (:func:`ssl_marl.skills.passing_features.receive_residual_action`;
        0 = the hand-coded receive). :meth:`from_direct` converts a direct action.
    Reward
        ``reward_form="shaped"`` (default): line + facing + contact + outcome
        (:func:`ssl_marl.skills.passing_features.receive_reward`); ``"outcome"``: +1 on
        success, -1 on failure, else 0
        (:func:`~ssl_marl.skills.passing_features.receive_outcome_reward`). Per-term
        values in ``info["reward_terms"]``.
    Spawn
        The robot at rest, uniformly in the field 0.5 m inside the lines, facing the
        ball's start +- U(0.5) rad. The ball ``U(2, 8)`` m away in a uniformly random
        direction (inside the field, 0.1 m margin), kicked (so sliding first) at
        ``U(1.5, 6)`` m/s towards a point ``U(-0.8, 0.8)`` m to the side of the robot's
        start. Spawns no robot could intercept are redrawn
        (:func:`receive_feasible`: a ball faster than 4.5 m/s where the robot could meet
        it, or one the robot cannot reach before it, inside the field); the
        acceptance rate is in ``docs/DESIGN.md``.
    Termination
        Success (terminated, ``is_success``): the ball has stayed on the dribbler for
        ``hold_s`` (0.5 s). Failure (terminated): "out" when the ball leaves the field.
        Failure (truncated): "timeout" at ``max_time_s`` (6 s).
    Reset options
        ``robot_pose`` (x, y, heading), ``ball_pos`` (x, y), ``ball_vel`` (vx, vy): any of
        them overrides the spawn. A ball slower than 0.1 m/s is an error (a receive needs
        a moving ball; use go-to-ball for a resting one).
    """

    spec_version = RECEIVE_SPEC
    REWARD_FORMS = ("shaped", "outcome")

    def __init__(self, max_time_s: float = 6.0, hold_s: float = 0.5, speed_range: tuple[float, float] = (1.5, 6.0),
                 distance_range: tuple[float, float] = (2.0, 8.0), max_side_offset: float = 0.8,
                 heading_noise: float = 0.5, action_form: str = "direct", reward_form: str = "shaped",
                 **kwargs: Any) -> None:
        self.action_form = check_receive_action_form(action_form)
        if reward_form not in self.REWARD_FORMS:
            raise ValueError(f"ReceiveEnv reward_form must be one of {self.REWARD_FORMS}, got {reward_form!r}")
        self.reward_form = reward_form
        super().__init__(n_blue=1, **kwargs)
        EzPickle.__init__(self, max_time_s=max_time_s, hold_s=hold_s, speed_range=speed_range,
                          distance_range=distance_range, max_side_offset=max_side_offset,
                          heading_noise=heading_noise, action_form=action_form, reward_form=reward_form, **kwargs)
        self.spec_version = RECEIVE_ACTION_FORMS[self.action_form]
        self.max_time_s = _positive("max_time_s", max_time_s)
        self.hold_s = _positive("hold_s", hold_s)
        self.speed_range = tuple(float(v) for v in speed_range)
        self.distance_range = tuple(float(v) for v in distance_range)
        if not 0 < self.speed_range[0] <= self.speed_range[1] <= self.robot_params.kick_speed_max:
            raise ValueError(f"speed_range must satisfy 0 < lo <= hi <= {self.robot_params.kick_speed_max} m/s, "
                             f"got {speed_range!r}")
        if not 0 < self.distance_range[0] <= self.distance_range[1]:
            raise ValueError(f"distance_range must satisfy 0 < lo <= hi (m), got {distance_range!r}")
        self.max_side_offset = float(max_side_offset)
        self.heading_noise = float(heading_noise)
        self.observation_space = gymnasium.spaces.Box(*passing_observation_bounds("receive", self.field,
                                                                                  self.robot_params), (11,), np.float32)
        self.action_space = gymnasium.spaces.Box(-1.0, 1.0, (3,), np.float32)
        self._hold_t0: float | None = None
        #: the hand-coded receive that a residual action corrects (only its stateless control() is used)
        self._base = ReceiveBaseline(self.field, self.robot_params, self.ball_params, hold_s=self.hold_s)
        self.spawn_draws = 0  #: spawns drawn since construction (rejection-sampling statistics)
        self.spawn_accepted = 0
        self.spawn_off_field = 0  #: draws rejected because the ball would start outside the field

    def _sample_spawn(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        f, rng, rp, bp = self.field, self.np_random, self.robot_params, self.ball_params
        for _ in range(10_000):
            self.spawn_draws += 1
            robot = f.random_free_point(rng, margin=0.5)
            ang = rng.uniform(-math.pi, math.pi)
            dist = rng.uniform(*self.distance_range)
            ball = robot + dist * np.array([math.cos(ang), math.sin(ang)])
            if not bool(f.in_field(ball, 0.1)):
                self.spawn_off_field += 1
                continue
            side = rng.uniform(-self.max_side_offset, self.max_side_offset)
            to_robot = (robot - ball) / dist
            aim = robot + side * np.array([-to_robot[1], to_robot[0]])
            d_aim = aim - ball
            vel = rng.uniform(*self.speed_range) * d_aim / float(np.hypot(*d_aim))
            if not receive_feasible(robot, ball, vel, rp, bp, f):
                continue
            self.spawn_accepted += 1
            heading = ang + rng.uniform(-self.heading_noise, self.heading_noise)
            return np.array([robot[0], robot[1], heading]), ball, vel
        raise RuntimeError("ReceiveEnv: no feasible spawn in 10,000 draws; check the spawn ranges")

    def reset(self, *, seed: int | None = None, options: dict | None = None):
        super().reset(seed=seed)
        options = dict(options or {})
        unknown = set(options) - {"robot_pose", "ball_pos", "ball_vel"}
        if unknown:
            raise ValueError(f"ReceiveEnv.reset: unknown option(s) {sorted(unknown)}; "
                             "known: ['ball_pos', 'ball_vel', 'robot_pose']")
        pose, ball, vel = self._sample_spawn()
        if "ball_vel" in options:
            vel = check_point("ball_vel", options["ball_vel"])
            if float(np.hypot(*vel)) < 0.1:
                raise ValueError(f"ReceiveEnv.reset: ball_vel {vel.tolist()} is (nearly) at rest: a receive needs "
                                 "a moving ball (>= 0.1 m/s); use go-to-ball for a resting one")
        if "ball_pos" in options:
            ball = check_point("ball_pos", options["ball_pos"])
        if "robot_pose" in options:
            pose = np.asarray(options["robot_pose"], float).reshape(3)
        for name, p in (("ball_pos", ball), ("robot_pose", pose[:2])):
            if not bool(self.field.in_field(p)):
                raise ValueError(f"ReceiveEnv.reset: {name} {np.asarray(p).tolist()} lies outside the field")
        self._reset_inner(seed, {PASSER: tuple(pose)}, ball, vel)
        self._hold_t0 = None
        return self._receive_obs(), {"reward_terms": {}}

    def base_action(self) -> np.ndarray:
        """The hand-coded receive's (vx, vy, omega) in the state the robot sees now."""
        return receive_task_action(self._base.control(self.seen(), 0))

    def from_direct(self, action3: np.ndarray) -> np.ndarray:
        """This env's action for a direct (vx, vy, omega) action: itself, or the residual
        correction from the hand-coded receive's action (clipped to [-1, 1])."""
        if self.action_form == "direct":
            return np.asarray(action3, dtype=np.float32)
        return receive_residual_of(self.base_action(), action3)

    def step(self, action):
        a = _check_action(action, 3)
        if self.action_form == "residual":
            a = receive_residual_action(self.base_action(), a)
        self.env.step({PASSER: expand_receive_action(a)})
        truth = self.truth()
        on = bool(truth.blue.ball_on_dribbler[0])
        if on and self._hold_t0 is None:
            self._hold_t0 = self.t
        elif not on:
            self._hold_t0 = None
        success = on and self.t - self._hold_t0 >= self.hold_s - 1e-9
        out = (not success) and self._ball_out(truth)
        timeout = not (success or out) and self.t >= self.max_time_s - 1e-9
        outcome = "success" if success else ("out" if out else ("timeout" if timeout else None))
        if self.reward_form == "outcome":
            terms = receive_outcome_reward(outcome)
        else:
            terms = receive_reward(truth, 0, self.robot_params, self.ball_params, outcome)
        info: dict[str, Any] = {"reward_terms": terms, "t": self.t,
                                "held_s": 0.0 if self._hold_t0 is None else self.t - self._hold_t0}
        if outcome:
            info.update(is_success=success, failure_reason=None if success else outcome, time_s=self.t)
        return self._receive_obs(), float(sum(terms.values())), bool(success or out), bool(timeout), info

    def _receive_obs(self) -> np.ndarray:
        obs = receive_features(self.seen(), 0, self.robot_params, self.ball_params)
        return clip_to_bounds(obs, self.observation_space.low, self.observation_space.high)


# ------------------------------------------------------------------------- pass
class PassEnv(_PassingEnv):
    """pass: with the ball on the dribbler, turn and kick so that a teammate can receive it.

    Observation
        ``Box(-inf, inf, (10,), float32)``, spec ``pass/v1``:
        :func:`ssl_marl.skills.passing_features.pass_features`, with the target = the
        receiver's seen position and velocity.
    Action
        ``Box(-1, 1, (3,), float32)``: (omega, kick, speed), see
        :func:`ssl_marl.skills.passing_features.expand_pass_action`.
    Reward
        aim + kick + outcome (:func:`ssl_marl.skills.passing_features.pass_reward`).
    Spawn
        The passer uniformly in the field 0.5 m inside the lines with a uniformly random
        heading, the ball resting on its dribbler. The receiver (``blue_1``) ``U(1, 6)`` m
        away in a uniformly random direction, 0.3 m inside the lines, facing the passer;
        standing (probability 1/2) or moving slowly (``U(0.1, 0.5)`` m/s in a uniformly
        random direction that keeps it 0.3 m inside the field for 4 s) until the kick.
    Episode
        Before the kick: failure "ball_lost" (terminated) if the ball leaves the
        dribbler (more than 0.05 m), "timeout" (truncated) after ``max_time_s`` (2 s)
        without a kick. The kick step resolves the pass (``resolve_after_kick``, default):
        the env runs on, the passer standing still with the dribbler off and the
        receiver driven by :class:`~ssl_marl.skills.passing.ReceiveBaseline`, until
        success (terminated, ``is_success``): the ball has stayed on the receiver's
        dribbler for ``hold_s`` (0.1 s; TIGERs count a reception 0.1 s after the ball
        breaks the light barrier), or a failure (terminated): "out" (ball left the
        field), "stopped_short" (ball at rest, not on the receiver's dribbler),
        "not_received" (``post_kick_time_s`` = 4 s passed). With
        ``resolve_after_kick=False`` the post-kick steps are returned one by one (the
        actions are then ignored).
    Reset options
        ``passer_pose`` (x, y, heading), ``target`` (the receiver's position, x, y) and
        ``receiver_vel`` (vx, vy). A target outside the field is an error.
    """

    spec_version = PASS_SPEC

    def __init__(self, max_time_s: float = 2.0, post_kick_time_s: float = 4.0, hold_s: float = 0.1,
                 distance_range: tuple[float, float] = (1.0, 6.0), max_receiver_speed: float = 0.5,
                 resolve_after_kick: bool = True, **kwargs: Any) -> None:
        super().__init__(n_blue=2, **kwargs)
        EzPickle.__init__(self, max_time_s=max_time_s, post_kick_time_s=post_kick_time_s, hold_s=hold_s,
                          distance_range=distance_range, max_receiver_speed=max_receiver_speed,
                          resolve_after_kick=resolve_after_kick, **kwargs)
        self.max_time_s = _positive("max_time_s", max_time_s)
        self.post_kick_time_s = _positive("post_kick_time_s", post_kick_time_s)
        self.hold_s = _positive("hold_s", hold_s)
        self.distance_range = tuple(float(v) for v in distance_range)
        if not 0 < self.distance_range[0] <= self.distance_range[1]:
            raise ValueError(f"distance_range must satisfy 0 < lo <= hi (m), got {distance_range!r}")
        self.max_receiver_speed = float(max_receiver_speed)
        self.resolve_after_kick = bool(resolve_after_kick)
        self.observation_space = gymnasium.spaces.Box(*passing_observation_bounds("pass", self.field,
                                                                                  self.robot_params), (10,), np.float32)
        self.action_space = gymnasium.spaces.Box(-1.0, 1.0, (3,), np.float32)
        self.receiver = ReceiveBaseline(self.field, self.robot_params, self.ball_params, hold_s=self.hold_s)
        self._kick_t: float | None = None
        self._receiver_vel = np.zeros(2)
        self._hold_t0: float | None = None
        self.kick_speed: float | None = None

    # --- spawn ------------------------------------------------------------------
    def _sample_spawn(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        f, rng = self.field, self.np_random
        for _ in range(10_000):
            passer = f.random_free_point(rng, margin=0.5)
            ang = rng.uniform(-math.pi, math.pi)
            recv = passer + rng.uniform(*self.distance_range) * np.array([math.cos(ang), math.sin(ang)])
            if not bool(f.in_field(recv, 0.3)):
                continue
            vel = np.zeros(2)
            if rng.uniform() < 0.5:
                a = rng.uniform(-math.pi, math.pi)
                vel = rng.uniform(0.1, self.max_receiver_speed) * np.array([math.cos(a), math.sin(a)])
                if not bool(f.in_field(recv + 4.0 * vel, 0.3)):
                    continue
            return np.array([passer[0], passer[1], rng.uniform(-math.pi, math.pi)]), recv, vel
        raise RuntimeError("PassEnv: no spawn found in 10,000 draws; check distance_range")

    def reset(self, *, seed: int | None = None, options: dict | None = None):
        super().reset(seed=seed)
        options = dict(options or {})
        unknown = set(options) - {"passer_pose", "target", "receiver_vel"}
        if unknown:
            raise ValueError(f"PassEnv.reset: unknown option(s) {sorted(unknown)}; "
                             "known: ['passer_pose', 'receiver_vel', 'target']")
        pose, recv, vel = self._sample_spawn()
        if "target" in options:
            recv = check_point("target", options["target"])
            if not bool(self.field.in_field(recv)):
                raise ValueError(f"PassEnv.reset: pass target {recv.tolist()} lies outside the {self.field.name} "
                                 f"field (|x| <= {self.field.half_length}, |y| <= {self.field.half_width} m)")
        if "receiver_vel" in options:
            vel = check_point("receiver_vel", options["receiver_vel"])
        if "passer_pose" in options:
            pose = np.asarray(options["passer_pose"], float).reshape(3)
            if not bool(self.field.in_field(pose[:2])):
                raise ValueError(f"PassEnv.reset: passer_pose {pose.tolist()} lies outside the field")
        reach = self.robot_params.front_distance + self.ball_params.radius
        ball = pose[:2] + reach * np.array([math.cos(pose[2]), math.sin(pose[2])])
        face = math.atan2(pose[1] - recv[1], pose[0] - recv[0])
        self._reset_inner(seed, {PASSER: tuple(pose), RECEIVER: (recv[0], recv[1], face)}, ball)
        self._receiver_vel = vel
        self._kick_t = None
        self._hold_t0 = None
        self.kick_speed = None
        self.receiver.reset()
        return self._obs(), {"reward_terms": {}}

    # --- helpers ----------------------------------------------------------------
    def target(self, world: WorldState) -> tuple[np.ndarray, np.ndarray]:
        """The pass target (the receiver's position, m) and its velocity (m/s) as seen."""
        return world.blue.pos[1].copy(), world.blue.vel[1].copy()

    def _obs(self) -> np.ndarray:
        seen = self.seen()
        tgt, tv = self.target(seen)
        return clip_to_bounds(pass_features(seen, 0, tgt, tv), self.observation_space.low, self.observation_space.high)

    def _receiver_action(self, seen: WorldState) -> np.ndarray:
        if self._kick_t is None:  # walk on, facing the ball
            to_ball = seen.ball_pos - seen.blue.pos[1]
            err = math.atan2(to_ball[1], to_ball[0]) - float(seen.blue.heading[1])
            err = math.atan2(math.sin(err), math.cos(err))
            return velocity_command(seen, 1, self._receiver_vel, 6.0 * err, self.robot_params, dribble=True)
        return self.receiver.act(seen, 1)

    def _post_kick_outcome(self, truth: WorldState) -> str | None:
        on = bool(truth.blue.ball_on_dribbler[1])
        if on and self._hold_t0 is None:
            self._hold_t0 = self.t
        elif not on:
            self._hold_t0 = None
        if on and self.t - self._hold_t0 >= self.hold_s - 1e-9:
            return "success"
        if self._ball_out(truth):
            return "out"
        if not on and float(np.hypot(*truth.ball_vel)) < 0.02:
            return "stopped_short"
        if self.t - self._kick_t >= self.post_kick_time_s - 1e-9:
            return "not_received"
        return None

    def step(self, action):
        a = _check_action(action, 3)
        seen = self.seen()
        passer_action = expand_pass_action(a, self.robot_params) if self._kick_t is None else make_action()
        aim_err = pass_aim_error(seen, 0, self.target(seen)[0])
        _, _, _, _, infos = self.env.step({PASSER: passer_action, RECEIVER: self._receiver_action(seen)})
        kicked_now = False
        if self._kick_t is None:
            for ev in infos[PASSER]["events"]:
                if ev["type"] == "kick" and ev["agent"] == PASSER:
                    self._kick_t, self.kick_speed, kicked_now = self.t, float(ev["speed"]), True
        truth = self.truth()
        outcome, truncated = None, False
        if self._kick_t is None:
            if dribbler_ball_distance(truth, 0, self.robot_params, self.ball_params) > BALL_LOST_DISTANCE:
                outcome = "ball_lost"
            elif self.t >= self.max_time_s - 1e-9:
                outcome, truncated = "timeout", True
        else:
            outcome = self._post_kick_outcome(truth)
            while outcome is None and self.resolve_after_kick:
                seen = self.seen()
                self.env.step({PASSER: make_action(), RECEIVER: self._receiver_action(seen)})
                outcome = self._post_kick_outcome(self.truth())
        terms = pass_reward(aim_err, kicked_now, outcome)
        info: dict[str, Any] = {"reward_terms": terms, "t": self.t, "kicked": self._kick_t is not None,
                                "kick_speed": self.kick_speed}
        if outcome:
            success = outcome == "success"
            info.update(is_success=success, failure_reason=None if success else outcome, time_s=self.t)
        return self._obs(), float(sum(terms.values())), bool(outcome) and not truncated, truncated, info


# ------------------------------------------------------------------ evaluation hooks
def make_task_env(task: str, env_kwargs: dict | None = None):
    """The task env of ``task`` ("pass" or "receive")."""
    if task == "pass":
        return PassEnv(**(env_kwargs or {}))
    if task == "receive":
        return ReceiveEnv(**(env_kwargs or {}))
    raise ValueError(f"unknown passing task {task!r}; expected 'pass' or 'receive'")


def skill_task_action(task: str, env, skill) -> np.ndarray:
    """One step of a pass / receive skill (hand-coded or learned) in its task env: the
    skill's (5,) action projected onto the task's action space. The pass skill's target
    is the receiver's seen position and velocity, updated every step."""
    seen = env.seen()
    if task == "pass":
        tgt, tv = env.target(seen)
        skill.set_target(env.field.clamp_to_field(tgt), tv)
        return pass_task_action(skill.act(seen, 0), env.robot_params)
    if task == "receive":  # a residual-form env takes the correction from its hand-coded receive
        return env.from_direct(receive_task_action(skill.act(seen, 0)))
    raise ValueError(f"unknown passing task {task!r}; expected 'pass' or 'receive'")


# ------------------------------------------------------------------ demonstrations
def pass_baseline_demos(n_steps: int, seed: int = 0, **env_kwargs: Any) -> Iterator[Transition]:
    """``n_steps`` pass transitions (obs (10,), action (3,)) from :class:`PassBaseline`
    on the task's own spawns; successful episodes only."""
    env = PassEnv(**env_kwargs)
    skill = PassBaseline(env.field, env.robot_params, env.ball_params)
    return successful_skill_demos(env, skill, lambda e, sk: skill_task_action("pass", e, sk), n_steps, seed)


def receive_baseline_demos(n_steps: int, seed: int = 0, **env_kwargs: Any) -> Iterator[Transition]:
    """``n_steps`` receive transitions (obs (11,), action (3,)) from :class:`ReceiveBaseline`
    on the task's own spawns; successful episodes only. With ``action_form="residual"``
    the actions are the (zero) corrections of the env's own hand-coded receive."""
    env = ReceiveEnv(**env_kwargs)
    skill = ReceiveBaseline(env.field, env.robot_params, env.ball_params)
    return successful_skill_demos(env, skill, lambda e, sk: skill_task_action("receive", e, sk), n_steps, seed)


__all__ = ["PassEnv", "ReceiveEnv", "make_task_env", "pass_baseline_demos", "receive_baseline_demos",
           "receive_feasible", "robot_travel_time", "skill_task_action"]
