"""The receive skill's Gymnasium task (``ssl_marl/Receive-v0``): :class:`ReceiveTask` on
the per-robot wrapper (:class:`~ssl_marl.skills.robot_env.RobotSkillEnv`) over the
passing tasks' full-field env (:func:`passing_world`: no referee, no time limit;
``realism=...`` and ``tracker=...`` pass through); features from what the robot sees,
rewards and outcomes from the ground truth. The pass task: :mod:`.pass_tasks`.
"""

from __future__ import annotations

import math
from typing import Any

import gymnasium
import numpy as np
from gymnasium.utils import EzPickle

from ..envs.observation import position_extent, speed_caps
from ..envs.ssl_env import SSLParallelEnv
from ..envs.tracking import with_tracker
from ..physics import ball_model
from ..physics.field import FieldGeometry
from ..physics.params import BallParams, RobotParams
from ..physics.state import WorldState
from .passing import ReceiveBaseline
from .passing_features import (
    RECEIVE_ACTION_FORMS,
    RECEIVE_NAMES,
    RECEIVE_PRESSED_NAMES,
    RECEIVE_RESIDUAL_FORMS,
    RECEIVE_SPEC,
    check_options,
    check_point,
    check_receive_action_form,
    expand_receive_action,
    receive_features,
    receive_outcome_reward,
    receive_press_active,
    receive_pressed_features,
    receive_residual_action,
    receive_residual_of,
    receive_reward,
    receive_task_action,
)
from .robot_env import Judgement, RobotSkillEnv, SkillDriver, SkillTask, Start

PASSER, RECEIVER = "blue_0", "blue_1"


def positive(name: str, v: float) -> float:
    """``v`` as a float; ValueError naming ``name`` unless it is a positive finite number."""
    if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
        raise ValueError(f"{name} must be a positive finite number, got {v!r}")
    return float(v)


def passing_world(n_blue: int, field: str = "div_b", realism: Any = "none", realtime: bool = False,
                  render_mode: str | None = None, tracker: Any = False, n_yellow: int = 0, **env_kwargs: Any) -> Any:
    """The full-field env under the pass / receive tasks: ``n_blue`` blue robots,
    ``n_yellow`` yellow ones (default none), no referee, no time limit (the task judges its episodes), no teammate or
    opponent slots in the engine's own observations; ``tracker``
    (:func:`~ssl_marl.envs.tracking.resolve_tracker`, default off) puts the vision
    tracker around it."""
    env = SSLParallelEnv(n_blue=n_blue, n_yellow=n_yellow, field=field, realism=realism, realtime=realtime,
                         referee=False, max_time_s=1e9, render_mode=render_mode, obs_max_teammates=0, obs_max_opponents=0,
                         **env_kwargs)
    return with_tracker(env, tracker)


# ------------------------------------------------------------- task plumbing
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
    elif task in ("receive", "receive_pressed"):  # ball xy, ball v, robot v, omega, line offset, gap, closing, on
        high = [d, d, vb, vb, v, v, w, d, d, vb + v, 1]
        low = [-d, -d, -vb, -vb, -v, -v, -w, -d, -d, -(vb + v), 0]
        if task == "receive_pressed":  # opponent xy, v, line offset, gap, present
            high += [d, d, v, v, d, d, 1]
            low += [-d, -d, -v, -v, -d, -d, 0]
    else:
        raise ValueError(f"unknown passing task {task!r}; expected 'pass', 'receive' or 'receive_pressed'")
    return np.array(low, dtype=np.float32), np.array(high, dtype=np.float32)

def robot_travel_time(distance: float, rp: RobotParams) -> float:
    """Shortest time (s) for a robot at rest to cover ``distance`` (m) in a straight line
    (accelerating at ``max_accel`` up to ``max_speed``, no need to stop)."""
    d_acc = rp.max_speed ** 2 / (2.0 * rp.max_accel)
    if distance <= d_acc:
        return math.sqrt(2.0 * distance / rp.max_accel)
    return rp.max_speed / rp.max_accel + (distance - d_acc) / rp.max_speed


def first_reach(robot_xy: np.ndarray, ball_xy: np.ndarray, ball_vel: np.ndarray, rp: RobotParams,
                bp: BallParams, field: FieldGeometry, margin_s: float = 0.3, max_closing: float = 1.5,
                ds: float = 0.05) -> float:
    """Distance (m) along the path of a just-kicked ball (sliding, at ``ball_xy`` with
    ``ball_vel``; team frame, m, m/s) of the first point where a robot at rest at
    ``robot_xy`` can be before the ball, inside the field, while the ball there is slow
    enough to catch moving at most the robot's top speed along it (ball speed <=
    ``max_speed + max_closing``); inf if there is none. The robot's time is
    :func:`robot_travel_time` of the straight-line distance to its receiving position
    plus ``margin_s`` (to turn and settle)."""
    v = float(np.hypot(*ball_vel))
    if v <= 0:
        return math.inf
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
            return float(s)
    return math.inf


def receive_feasible(robot_xy: np.ndarray, ball_xy: np.ndarray, ball_vel: np.ndarray, rp: RobotParams,
                     bp: BallParams, field: FieldGeometry, margin_s: float = 0.3, max_closing: float = 1.5,
                     ds: float = 0.05) -> bool:
    """True if a robot at rest at ``robot_xy`` can be on the path of a just-kicked ball
    before the ball (:func:`first_reach` is finite)."""
    return math.isfinite(first_reach(robot_xy, ball_xy, ball_vel, rp, bp, field, margin_s, max_closing, ds))



# ---------------------------------------------------------------------- receive
class ReceiveTask(SkillTask):
    """receive: intercept a moving ball and hold it on the dribbler for 0.5 s.

    Observation
        ``Box(-inf, inf, (11,), float32)``, spec ``receive/v1``:
        :func:`ssl_marl.skills.passing_features.receive_features`; with
        ``action_form="pressed"`` (spec ``receive/v3``) 18 values,
        :func:`~ssl_marl.skills.passing_features.receive_pressed_features` (the 11 and
        the opponent nearest the ball's path).
    Action
        ``Box(-1, 1, (3,), float32)``, dribbler on; ``action_form``:
        ``"direct"`` (spec ``receive/v1``, default): (vx, vy, omega), robot frame,
        fractions of the robot's limits; ``"residual"`` (spec ``receive/v2``): a
        correction added to the hand-coded receive's (vx, vy, omega) in the state the
        robot sees (:func:`ssl_marl.skills.passing_features.receive_residual_action`;
        0 = the hand-coded receive); ``"pressed"`` (spec ``receive/v3``): the same
        correction on the 18-value state. :meth:`ReceiveEnv.from_direct` converts a direct action.
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
        ``interceptors`` (default 0) yellow robots press the pass, each driven by the
        hand-coded go-to-ball from the first step: one at a point ``U(0.3, 0.9)`` of the
        way from the ball to the robot and ``U(*interceptor_offset)`` m (default 0.3-3.0)
        to a random side of that line (moved inside the field), facing the ball, drawn
        where the receiver meets the ball's path (:func:`first_reach`) at least
        ``interceptor_lead_m`` (default 0 m) before the interceptor can touch it (a pass a
        passer would play; a spawn without such a place is redrawn).
    Termination
        Success (terminated, ``is_success``): the ball has stayed on the dribbler for
        ``hold_s`` (0.5 s). Failure (terminated): "out" when the ball leaves the field;
        "intercepted" when an interceptor has the ball on its dribbler.
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
                 interceptors: int = 0, interceptor_offset: tuple[float, float] = (0.3, 3.0),
                 interceptor_lead_m: float = 0.0) -> None:
        if not (isinstance(interceptors, int) and 0 <= interceptors <= 4):
            raise ValueError(f"interceptors must be an integer in 0..4, got {interceptors!r}")
        lo_hi = tuple(float(v) for v in interceptor_offset)
        if len(lo_hi) != 2 or not (math.isfinite(lo_hi[0]) and math.isfinite(lo_hi[1]) and 0 <= lo_hi[0] <= lo_hi[1]):
            raise ValueError(f"interceptor_offset must be (lo, hi) m with 0 <= lo <= hi, got {interceptor_offset!r}")
        self.interceptors, self.interceptor_offset = interceptors, lo_hi
        if not (isinstance(interceptor_lead_m, (int, float)) and math.isfinite(interceptor_lead_m)):
            raise ValueError(f"interceptor_lead_m must be a finite number (m), got {interceptor_lead_m!r}")
        self.interceptor_lead_m = float(interceptor_lead_m)
        self.action_form = check_receive_action_form(action_form)
        if reward_form not in self.REWARD_FORMS:
            raise ValueError(f"ReceiveEnv reward_form must be one of {self.REWARD_FORMS}, got {reward_form!r}")
        self.reward_form = reward_form
        self.spec_version = RECEIVE_ACTION_FORMS[self.action_form]
        self.max_time_s = positive("max_time_s", max_time_s)
        self.hold_s = positive("hold_s", hold_s)
        self.speed_range = tuple(float(v) for v in speed_range)
        self.distance_range = tuple(float(v) for v in distance_range)
        if not 0 < self.distance_range[0] <= self.distance_range[1]:
            raise ValueError(f"distance_range must satisfy 0 < lo <= hi (m), got {distance_range!r}")
        self.max_side_offset = float(max_side_offset)
        self.heading_noise = float(heading_noise)
        self._state = "receive_pressed" if self.action_form == "pressed" else "receive"
        self._n_obs = len(RECEIVE_PRESSED_NAMES) if self.action_form == "pressed" else len(RECEIVE_NAMES)
        self.observation_space = gymnasium.spaces.Box(-np.inf, np.inf, (self._n_obs,), np.float32)  # bound in bind()
        self.action_space = gymnasium.spaces.Box(-1.0, 1.0, (3,), np.float32)
        self._hold_t0: float | None = None
        self._seen: WorldState | None = None
        self._robot = 0
        self._pressed = True  #: this step's pressed correction applies (receive_press_active)
        self.spawn_draws = 0  #: spawns drawn since construction (rejection-sampling statistics)
        self.spawn_accepted = 0
        self.spawn_off_field = 0  #: draws rejected because the ball would start outside the field

    def bind(self, field: FieldGeometry, robot: RobotParams, ball: BallParams, dt: float) -> None:
        super().bind(field, robot, ball, dt)
        if not 0 < self.speed_range[0] <= self.speed_range[1] <= robot.kick_speed_max:
            raise ValueError(f"speed_range must satisfy 0 < lo <= hi <= {robot.kick_speed_max} m/s, "
                             f"got {self.speed_range!r}")
        self.observation_space = gymnasium.spaces.Box(*passing_observation_bounds(self._state, field, robot),
                                                      (self._n_obs,), np.float32)
        #: the hand-coded receive that a residual action corrects (only its stateless control() is used)
        self._base = ReceiveBaseline(field, robot, ball, hold_s=self.hold_s)

    def _sample_spawn(self, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray, np.ndarray, dict]:
        f, rp, bp = self.field, self.robot_params, self.ball_params
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
            others = self._interceptor_poses(rng, robot, ball, vel)
            if others is None:
                continue
            self.spawn_accepted += 1
            heading = ang + rng.uniform(-self.heading_noise, self.heading_noise)
            return np.array([robot[0], robot[1], heading]), ball, vel, others
        raise RuntimeError("ReceiveEnv: no feasible spawn in 10,000 draws; check the spawn ranges")

    def _interceptor_poses(self, rng: np.random.Generator, robot: np.ndarray, ball: np.ndarray, vel: np.ndarray
                           ) -> dict[str, np.ndarray] | None:
        """Team-frame poses of the interceptors (class docstring), facing the ball; None
        if 20 draws found no place for one from which the receiver still meets the
        ball's path ``interceptor_lead_m`` before it (the spawn is then redrawn)."""
        out: dict[str, np.ndarray] = {}
        if not self.interceptors:
            return out
        rp, bp, f = self.robot_params, self.ball_params, self.field
        mine = first_reach(robot, ball, vel, rp, bp, f)
        d = robot - ball
        n = np.array([-d[1], d[0]]) / max(float(np.hypot(*d)), 1e-9)
        for k in range(self.interceptors):
            for _ in range(20):
                side = rng.choice([-1.0, 1.0])
                along = rng.uniform(0.3, 0.9)
                p = f.clamp_to_field(ball + along * d + side * rng.uniform(*self.interceptor_offset) * n, 0.2)
                if first_reach(p, ball, vel, rp, bp, f, margin_s=0.0, max_closing=math.inf) > \
                        mine + self.interceptor_lead_m:
                    break
            else:
                return None
            to_ball = ball - p
            out[f"yellow_{k}"] = np.array([p[0], p[1], math.atan2(to_ball[1], to_ball[0])])
        return out

    def sample_start(self, rng: np.random.Generator, options: dict) -> Start:
        check_options("ReceiveEnv.reset", options, {"robot_pose", "ball_pos", "ball_vel"})
        pose, ball, vel, others = self._sample_spawn(rng)
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
        if self.interceptors and options:  # place the interceptors for the scene as given
            others = self._interceptor_poses(rng, pose[:2], ball, vel)
            if others is None:
                raise ValueError("ReceiveEnv.reset: no place for an interceptor from which the receiver still "
                                 "meets the ball's path first in this scene (robot_pose / ball_pos / ball_vel)")
        return Start(pose, ball, vel, others=others)

    def begin(self) -> None:
        self._hold_t0 = None

    def begin_step(self, seen: WorldState, robot: int) -> None:
        self._seen, self._robot = seen, robot
        if self.action_form == "pressed":
            self._pressed = receive_press_active(receive_pressed_features(seen, robot, self.robot_params,
                                                                          self.ball_params))

    def base_action(self, seen: WorldState, robot: int = 0) -> np.ndarray:
        """The hand-coded receive's (vx, vy, omega) in the state ``seen``."""
        return receive_task_action(self._base.control(seen, robot))

    def observe(self, seen: WorldState, robot: int) -> np.ndarray:
        if self.action_form == "pressed":
            return receive_pressed_features(seen, robot, self.robot_params, self.ball_params)
        return receive_features(seen, robot, self.robot_params, self.ball_params)

    def env_action(self, action: np.ndarray) -> np.ndarray:
        a = np.clip(action, -1.0, 1.0)
        if self.action_form == "pressed" and not self._pressed:
            a = np.zeros(3, np.float32)  # outside the press the pressed receive is the hand-coded one
        if self.action_form in RECEIVE_RESIDUAL_FORMS:
            a = receive_residual_action(self.base_action(self._seen, self._robot), a)
        return expand_receive_action(a)

    def judge(self, truth: WorldState, robot: int, events: list[dict], t: float) -> Judgement:
        on = bool(truth.team(truth.frame).ball_on_dribbler[robot])
        if on and self._hold_t0 is None:
            self._hold_t0 = t
        elif not on:
            self._hold_t0 = None
        success = on and t - self._hold_t0 >= self.hold_s - 1e-9
        out = (not success) and ball_out(truth, self.field, self.ball_params)
        lost = not (success or out) and bool(np.any(truth.opponents(truth.frame).ball_on_dribbler))
        timeout = not (success or out or lost) and t >= self.max_time_s - 1e-9
        outcome = ("success" if success else "out" if out else "intercepted" if lost else
                   "timeout" if timeout else None)
        if self.reward_form == "outcome":
            terms = receive_outcome_reward(outcome)
        else:
            terms = receive_reward(truth, robot, self.robot_params, self.ball_params, outcome)
        return Judgement(terms, terminated=bool(success or out or lost), truncated=bool(timeout), success=bool(success),
                         failure_reason=None if success else outcome,
                         info={"held_s": 0.0 if self._hold_t0 is None else t - self._hold_t0})


def ball_out(truth: WorldState, field: FieldGeometry, ball: BallParams) -> bool:
    """True once the ball has wholly left the field (crossed a line by its radius)."""
    return not bool(field.in_field(truth.ball_pos, -ball.radius))


class ReceiveEnv(RobotSkillEnv, EzPickle):
    """``ssl_marl/Receive-v0``: :class:`ReceiveTask` for ``blue_0``, the only blue robot of
    a full-field env (:func:`passing_world`; ``field``, ``realism``, ``realtime``,
    ``render_mode``, ``tracker`` and further env options pass through), with
    ``interceptors`` yellow robots running the hand-coded go-to-ball."""

    def __init__(self, max_time_s: float = 6.0, hold_s: float = 0.5, speed_range: tuple[float, float] = (1.5, 6.0),
                 distance_range: tuple[float, float] = (2.0, 8.0), max_side_offset: float = 0.8,
                 heading_noise: float = 0.5, action_form: str = "direct", reward_form: str = "shaped",
                 interceptors: int = 0, interceptor_offset: tuple[float, float] = (0.3, 3.0),
                 interceptor_lead_m: float = 0.0, **kwargs: Any) -> None:
        task = ReceiveTask(max_time_s, hold_s, speed_range, distance_range, max_side_offset, heading_noise,
                           action_form, reward_form, interceptors, interceptor_offset, interceptor_lead_m)
        world = passing_world(n_blue=1, n_yellow=interceptors, **kwargs)
        drivers = []
        if interceptors:
            from .baseline import GoToBallBaseline

            drivers.append(SkillDriver([f"yellow_{k}" for k in range(interceptors)], GoToBallBaseline, world.field,
                                       world.config.robot, world.config.ball))
        super().__init__(world, PASSER, task, drivers)
        EzPickle.__init__(self, max_time_s=max_time_s, hold_s=hold_s, speed_range=speed_range,
                          distance_range=distance_range, max_side_offset=max_side_offset,
                          heading_noise=heading_noise, action_form=action_form, reward_form=reward_form,
                          interceptors=interceptors, interceptor_offset=interceptor_offset,
                          interceptor_lead_m=interceptor_lead_m, **kwargs)

    def base_action(self) -> np.ndarray:
        """The hand-coded receive's (vx, vy, omega) in the state the robot sees now."""
        return self.task.base_action(self.seen(), self.robot)

    def from_direct(self, action3: np.ndarray) -> np.ndarray:
        """This env's action for a direct (vx, vy, omega) action: itself, or the residual
        correction from the hand-coded receive's action (clipped to [-1, 1])."""
        if self.task.action_form not in RECEIVE_RESIDUAL_FORMS:
            return np.asarray(action3, dtype=np.float32)
        return receive_residual_of(self.base_action(), action3)



__all__ = ["PASSER", "RECEIVER", "ReceiveEnv", "ReceiveTask", "passing_observation_bounds", "passing_world",
           "first_reach", "receive_feasible", "robot_travel_time"]
