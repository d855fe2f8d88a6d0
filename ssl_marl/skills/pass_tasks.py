"""The pass skill's Gymnasium task (``ssl_marl/Pass-v0``): :class:`PassTask` on the
per-robot wrapper (:class:`~ssl_marl.skills.robot_env.RobotSkillEnv`) over the passing
tasks' full-field env (:func:`~ssl_marl.skills.receive_task.passing_world`), its
receiver a driver (:class:`PassReceiverDriver`); features from what the robot sees
(``env.vision_state``), rewards and outcomes from the ground truth, ``realism=...`` and
``tracker=...`` passed through. States, actions and rewards:
:mod:`ssl_marl.skills.passing_features`; the receive task: :mod:`.receive_task`.

Also the evaluation hooks of both passing tasks and their demonstration generators (the
hand-coded skills, successful episodes only) for the trainer's replay burn-in and
behaviour-cloning term.
"""

from __future__ import annotations

import math
from typing import Any, Iterator

import gymnasium
import numpy as np
from gymnasium.utils import EzPickle

from ..physics.field import FieldGeometry
from ..physics.params import BallParams, RobotParams
from ..physics.state import WorldState
from .base import make_action
from .demos import Transition, skill_demos
from .features import BALL_LOST_DISTANCE, dribbler_ball_distance
from .motion import velocity_command
from .passing import PassBaseline, ReceiveBaseline
from .passing_features import (
    PASS_SPEC,
    check_options,
    check_point,
    expand_pass_action,
    pass_aim_error,
    pass_features,
    pass_reward,
    pass_task_action,
    receive_task_action,
)
from .receive_task import PASSER, RECEIVER, ReceiveEnv, ball_out, passing_observation_bounds, passing_world, positive
from .robot_env import Judgement, RobotSkillEnv, SkillTask, Start


# ------------------------------------------------------------------------- pass
class PassTask(SkillTask):
    """pass: with the ball on the dribbler, turn and kick so that a teammate can receive it.

    Observation
        ``Box(-inf, inf, (10,), float32)``, spec ``pass/v1``:
        :func:`ssl_marl.skills.passing_features.pass_features`, with the target = the
        receiver's seen position and velocity.
    Action
        ``Box(-1, 1, (3,), float32)``: (omega, kick, speed), see
        :func:`ssl_marl.skills.passing_features.expand_pass_action`.
    Reward
        aim + kick + outcome (:func:`ssl_marl.skills.passing_features.pass_reward`); the
        aim error is the one seen as the step starts.
    Spawn
        The passer uniformly in the field 0.5 m inside the lines with a uniformly random
        heading, the ball resting on its dribbler. The receiver (``blue_1``) ``U(1, 6)`` m
        away in a uniformly random direction, 0.3 m inside the lines, facing the passer;
        standing (probability 1/2) or moving slowly (``U(0.1, 0.5)`` m/s in a uniformly
        random direction that keeps it 0.3 m inside the field for 4 s) until the kick
        (:class:`PassReceiverDriver`).
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
                 resolve_after_kick: bool = True) -> None:
        self.max_time_s = positive("max_time_s", max_time_s)
        self.post_kick_time_s = positive("post_kick_time_s", post_kick_time_s)
        self.hold_s = positive("hold_s", hold_s)
        self.distance_range = tuple(float(v) for v in distance_range)
        if not 0 < self.distance_range[0] <= self.distance_range[1]:
            raise ValueError(f"distance_range must satisfy 0 < lo <= hi (m), got {distance_range!r}")
        self.max_receiver_speed = float(max_receiver_speed)
        self.resolve_after_kick = bool(resolve_after_kick)
        self.observation_space = gymnasium.spaces.Box(-np.inf, np.inf, (10,), np.float32)  # bounded in bind()
        self.action_space = gymnasium.spaces.Box(-1.0, 1.0, (3,), np.float32)
        self.kick_t: float | None = None  #: episode time of the kick (s), None before it
        self.kick_speed: float | None = None  #: m/s of the kick, once kicked
        self.receiver_vel = np.zeros(2)  #: the receiver's walking velocity until the kick (m/s, team frame)
        self._hold_t0: float | None = None
        self._aim_err = 0.0
        self._kicked_now = False

    def bind(self, field: FieldGeometry, robot: RobotParams, ball: BallParams, dt: float) -> None:
        super().bind(field, robot, ball, dt)
        self.observation_space = gymnasium.spaces.Box(*passing_observation_bounds("pass", field, robot),
                                                      (10,), np.float32)

    # --- spawn ------------------------------------------------------------------
    def _sample_spawn(self, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        f = self.field
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

    def sample_start(self, rng: np.random.Generator, options: dict) -> Start:
        check_options("PassEnv.reset", options, {"passer_pose", "target", "receiver_vel"})
        pose, recv, vel = self._sample_spawn(rng)
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
        self.receiver_vel = vel
        return Start(pose, ball, others={RECEIVER: np.array([recv[0], recv[1], face])})

    def begin(self) -> None:
        self.kick_t = None
        self.kick_speed = None
        self._hold_t0 = None
        self._kicked_now = False

    # --- helpers ----------------------------------------------------------------
    def target(self, world: WorldState) -> tuple[np.ndarray, np.ndarray]:
        """The pass target (the receiver's position, m) and its velocity (m/s) as seen."""
        return world.blue.pos[1].copy(), world.blue.vel[1].copy()

    def observe(self, seen: WorldState, robot: int) -> np.ndarray:
        tgt, tv = self.target(seen)
        return pass_features(seen, robot, tgt, tv)

    def begin_step(self, seen: WorldState, robot: int) -> None:
        self._aim_err = pass_aim_error(seen, robot, self.target(seen)[0])
        self._kicked_now = False

    def env_action(self, action: np.ndarray) -> np.ndarray:
        if self.kick_t is not None:
            return make_action()
        return expand_pass_action(np.clip(action, -1.0, 1.0), self.robot_params)

    def _post_kick_outcome(self, truth: WorldState, t: float) -> str | None:
        on = bool(truth.blue.ball_on_dribbler[1])
        if on and self._hold_t0 is None:
            self._hold_t0 = t
        elif not on:
            self._hold_t0 = None
        if on and t - self._hold_t0 >= self.hold_s - 1e-9:
            return "success"
        if ball_out(truth, self.field, self.ball_params):
            return "out"
        if not on and float(np.hypot(*truth.ball_vel)) < 0.02:
            return "stopped_short"
        if t - self.kick_t >= self.post_kick_time_s - 1e-9:
            return "not_received"
        return None

    def judge(self, truth: WorldState, robot: int, events: list[dict], t: float) -> Judgement:
        agent = f"{truth.frame}_{robot}"
        if self.kick_t is None:
            for ev in events:
                if ev["type"] == "kick" and ev["agent"] == agent:
                    self.kick_t, self.kick_speed, self._kicked_now = t, float(ev["speed"]), True
        outcome, truncated = None, False
        if self.kick_t is None:
            if dribbler_ball_distance(truth, robot, self.robot_params, self.ball_params) > BALL_LOST_DISTANCE:
                outcome = "ball_lost"
            elif t >= self.max_time_s - 1e-9:
                outcome, truncated = "timeout", True
        else:
            outcome = self._post_kick_outcome(truth, t)
        terms = pass_reward(self._aim_err, self._kicked_now, outcome)
        success = outcome == "success"
        return Judgement(terms, terminated=bool(outcome) and not truncated, truncated=truncated, success=success,
                         failure_reason=None if success else outcome,
                         info={"kicked": self.kick_t is not None, "kick_speed": self.kick_speed},
                         run_on=outcome is None and self.kick_t is not None and self.resolve_after_kick)


class PassReceiverDriver:
    """The pass task's receiver (``blue_1``), from what blue sees: until the kick it walks
    at the task's ``receiver_vel`` facing the ball, dribbler on; from the kick on it runs
    :class:`~ssl_marl.skills.passing.ReceiveBaseline` (rebuilt state every episode)."""

    def __init__(self, task: PassTask, field: FieldGeometry, robot: RobotParams, ball: BallParams) -> None:
        self.task, self.robot_params = task, robot
        self.receiver = ReceiveBaseline(field, robot, ball, hold_s=task.hold_s)

    def reset(self) -> None:
        self.receiver.reset()

    def act(self, env: Any) -> dict[str, np.ndarray]:
        seen = env.vision_state("blue")
        if self.task.kick_t is not None:
            return {RECEIVER: self.receiver.act(seen, 1)}
        to_ball = seen.ball_pos - seen.blue.pos[1]
        err = math.atan2(to_ball[1], to_ball[0]) - float(seen.blue.heading[1])
        err = math.atan2(math.sin(err), math.cos(err))
        return {RECEIVER: velocity_command(seen, 1, self.task.receiver_vel, 6.0 * err, self.robot_params,
                                           dribble=True)}


class PassEnv(RobotSkillEnv, EzPickle):
    """``ssl_marl/Pass-v0``: :class:`PassTask` for ``blue_0`` in a full-field env with a
    second blue robot, the receiver (:class:`PassReceiverDriver`) (:func:`passing_world`;
    ``field``, ``realism``, ``realtime``, ``render_mode``, ``tracker`` and further env
    options pass through)."""

    def __init__(self, max_time_s: float = 2.0, post_kick_time_s: float = 4.0, hold_s: float = 0.1,
                 distance_range: tuple[float, float] = (1.0, 6.0), max_receiver_speed: float = 0.5,
                 resolve_after_kick: bool = True, **kwargs: Any) -> None:
        task = PassTask(max_time_s, post_kick_time_s, hold_s, distance_range, max_receiver_speed, resolve_after_kick)
        env = passing_world(n_blue=2, **kwargs)
        driver = PassReceiverDriver(task, env.field, env.config.robot, env.config.ball)
        super().__init__(env, PASSER, task, drivers=[driver])
        EzPickle.__init__(self, max_time_s=max_time_s, post_kick_time_s=post_kick_time_s, hold_s=hold_s,
                          distance_range=distance_range, max_receiver_speed=max_receiver_speed,
                          resolve_after_kick=resolve_after_kick, **kwargs)


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
    return skill_demos(env, skill, lambda e, sk: skill_task_action("pass", e, sk), n_steps, seed)


def receive_baseline_demos(n_steps: int, seed: int = 0, **env_kwargs: Any) -> Iterator[Transition]:
    """``n_steps`` receive transitions (obs (11,), action (3,)) from :class:`ReceiveBaseline`
    on the task's own spawns; successful episodes only. With ``action_form="residual"``
    the actions are the (zero) corrections of the env's own hand-coded receive."""
    env = ReceiveEnv(**env_kwargs)
    skill = ReceiveBaseline(env.field, env.robot_params, env.ball_params)
    return skill_demos(env, skill, lambda e, sk: skill_task_action("receive", e, sk), n_steps, seed)


__all__ = ["PassEnv", "PassReceiverDriver", "PassTask", "make_task_env", "pass_baseline_demos",
           "receive_baseline_demos", "skill_task_action"]
