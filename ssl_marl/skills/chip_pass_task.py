"""The chip pass skill's Gymnasium task (``ssl_marl/ChipPass-v0``): :class:`ChipPassTask`
on the per-robot wrapper (:class:`~ssl_marl.skills.robot_env.RobotSkillEnv`) over a
full-field env in the chip layout (``chip_kicks=True``) with the passer ``blue_0``, the
receiver ``blue_1`` (the pass task's :class:`~ssl_marl.skills.pass_tasks.PassReceiverDriver`:
the hand-coded receive once the ball is kicked) and a blocker ``yellow_0`` standing in
the lane. ``realism=...`` and ``tracker=...`` pass through; features from what the
robot sees, outcomes from the ground truth.
"""

from __future__ import annotations

import math
from typing import Any, Iterator

import gymnasium
import numpy as np
from gymnasium.utils import EzPickle

from ..envs.actions import fit_action, make_action
from ..envs.ssl_env import SSLParallelEnv
from ..envs.tracking import with_tracker
from ..physics.field import FieldGeometry
from ..physics.params import BallParams, RobotParams
from ..physics.state import WorldState
from .chip_pass import (CHIP_PASS_SPEC, ChipPassBaseline, chip_pass_features, chip_pass_task_action,
                        expand_chip_pass_action)
from .demos import Transition, skill_demos
from .pass_tasks import PassReceiverDriver, PassTask
from .passing_features import check_options, check_point
from .receive_task import PASSER, RECEIVER, passing_observation_bounds
from .robot_env import Judgement, RobotDriver, RobotSkillEnv, Start

BLOCKER = "yellow_0"


class ChipLayoutDriver:
    """A driver of 5-entry actions in a chip-layout env: each action gets the chip entry
    0 (a flat kick)."""

    def __init__(self, driver: RobotDriver) -> None:
        self.driver = driver

    def reset(self) -> None:
        self.driver.reset()

    def act(self, env: Any) -> dict[str, np.ndarray]:
        return {k: fit_action(a, 6) for k, a in self.driver.act(env).items()}


class ChipPassTask(PassTask):
    """chip pass: with the ball on the dribbler, turn and chip it over the robot standing
    in the lane so that a teammate receives it.

    Observation
        ``Box(-inf, inf, (12,), float32)`` (bounded in ``bind``), spec ``chip_pass/v1``:
        :func:`ssl_marl.skills.chip_pass.chip_pass_features`, the target = the
        receiver's seen position and velocity.
    Action
        ``Box(-1, 1, (4,), float32)``: (omega, kick, speed, elevation), see
        :func:`ssl_marl.skills.chip_pass.expand_chip_pass_action`.
    Reward
        As the pass task's (:func:`ssl_marl.skills.passing_features.pass_reward`: aim,
        kick, outcome +10 / -5).
    Spawn
        The passer uniformly in the field 0.5 m inside the lines with a uniformly random
        heading, the ball resting on its dribbler; the receiver (``blue_1``) ``U(3, 5)`` m
        from the ball in a uniformly random direction, 0.5 m inside the lines, at rest,
        facing the ball; the blocker (``yellow_0``) on the midpoint of the ball ->
        receiver segment, ``U(-0.05, 0.05)`` m to its side, facing the ball, standing
        still throughout.
    Episode
        As the pass task's (before the kick "ball_lost" / "timeout" after 2 s; the kick
        step resolves the pass with the receiver on the hand-coded receive), with the
        failure "blocked" (terminated): after the kick the ball, at most
        ``RobotParams.height`` high, comes within the blocker's radius + the ball's
        radius + 1 cm of its centre (in a game, an interception). Success: the ball
        stays ``hold_s`` (0.5 s: a chipped ball arrives hopping) on the receiver's
        dribbler. ``info["max_height"]``: the highest the ball flew after the kick (m).
    Reset options
        ``passer_pose`` (x, y, heading), ``target`` (the receiver's position, x, y),
        ``blocker`` (x, y). Points outside the field are errors.
    """

    spec_version = CHIP_PASS_SPEC

    def __init__(self, max_time_s: float = 2.0, post_kick_time_s: float = 4.0, hold_s: float = 0.5,
                 distance_range: tuple[float, float] = (3.0, 5.0), blocker_side: float = 0.05,
                 resolve_after_kick: bool = True) -> None:
        super().__init__(max_time_s, post_kick_time_s, hold_s, distance_range, 0.0, resolve_after_kick)
        if not (math.isfinite(blocker_side) and blocker_side >= 0):
            raise ValueError(f"blocker_side must be a finite distance >= 0 (m), got {blocker_side!r}")
        self.blocker_side = float(blocker_side)
        self.observation_space = gymnasium.spaces.Box(-np.inf, np.inf, (12,), np.float32)
        self.action_space = gymnasium.spaces.Box(-1.0, 1.0, (4,), np.float32)
        self.max_height = 0.0  #: the highest the ball has flown since the kick (m)

    def bind(self, field: FieldGeometry, robot: RobotParams, ball: BallParams, dt: float) -> None:
        super().bind(field, robot, ball, dt)
        low, high = passing_observation_bounds("pass", field, robot)
        d = float(high[0])
        self.observation_space = gymnasium.spaces.Box(np.append(low, [-d, -d]).astype(np.float32),
                                                      np.append(high, [d, d]).astype(np.float32), (12,), np.float32)

    def _sample_chip_spawn(self, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        f, reach = self.field, self.robot_params.front_distance + self.ball_params.radius
        for _ in range(10_000):
            passer = f.random_free_point(rng, margin=0.5)
            heading = rng.uniform(-math.pi, math.pi)
            ball = passer + reach * np.array([math.cos(heading), math.sin(heading)])
            ang = rng.uniform(-math.pi, math.pi)
            u = np.array([math.cos(ang), math.sin(ang)])
            recv = ball + rng.uniform(*self.distance_range) * u
            if not bool(f.in_field(recv, 0.5)) or float(np.hypot(*(recv - passer))) < 1.0:
                continue
            blocker = 0.5 * (ball + recv) + rng.uniform(-self.blocker_side, self.blocker_side) * np.array([-u[1], u[0]])
            return np.array([passer[0], passer[1], heading]), ball, recv, blocker
        raise RuntimeError("ChipPassEnv: no spawn found in 10,000 draws; check distance_range")

    def sample_start(self, rng: np.random.Generator, options: dict) -> Start:
        check_options("ChipPassEnv.reset", options, {"passer_pose", "target", "blocker"})
        pose, ball, recv, blocker = self._sample_chip_spawn(rng)
        if "passer_pose" in options:
            pose = np.asarray(options["passer_pose"], float).reshape(3)
            reach = self.robot_params.front_distance + self.ball_params.radius
            ball = pose[:2] + reach * np.array([math.cos(pose[2]), math.sin(pose[2])])
        if "target" in options:
            recv = check_point("target", options["target"])
        if "blocker" in options:
            blocker = check_point("blocker", options["blocker"])
        for name, p in (("passer_pose", pose[:2]), ("target", recv), ("blocker", blocker)):
            if not bool(self.field.in_field(p)):
                raise ValueError(f"ChipPassEnv.reset: {name} {np.asarray(p).tolist()} lies outside the "
                                 f"{self.field.name} field")
        self.receiver_vel = np.zeros(2)

        def facing(p: np.ndarray) -> float:
            return math.atan2(ball[1] - p[1], ball[0] - p[0])

        return Start(pose, ball, others={RECEIVER: np.array([recv[0], recv[1], facing(recv)]),
                                         BLOCKER: np.array([blocker[0], blocker[1], facing(blocker)])})

    def begin(self) -> None:
        super().begin()
        self.max_height = 0.0

    def observe(self, seen: WorldState, robot: int) -> np.ndarray:
        tgt, tv = self.target(seen)
        return chip_pass_features(seen, robot, tgt, tv)

    def env_action(self, action: np.ndarray) -> np.ndarray:
        if self.kick_t is not None:
            return make_action(chip=0.0)
        return expand_chip_pass_action(np.clip(action, -1.0, 1.0), self.robot_params)

    def judge(self, truth: WorldState, robot: int, events: list[dict], t: float) -> Judgement:
        j = super().judge(truth, robot, events, t)
        j.info["max_height"] = self.max_height
        return j

    def _post_kick_outcome(self, truth: WorldState, t: float) -> str | None:
        self.max_height = max(self.max_height, float(truth.ball_height))
        opp = truth.opponents(truth.frame)
        near = float(np.min(np.hypot(*(opp.pos - truth.ball_pos).T))) if len(opp.pos) else math.inf
        if (float(truth.ball_height) <= self.robot_params.height
                and near <= self.robot_params.radius + self.ball_params.radius + 0.01) or bool(opp.ball_on_dribbler.any()):
            return "blocked"
        return super()._post_kick_outcome(truth, t)


class ChipPassEnv(RobotSkillEnv, EzPickle):
    """``ssl_marl/ChipPass-v0``: :class:`ChipPassTask` for ``blue_0`` in a full-field
    chip-layout env with the receiver ``blue_1`` and the blocker ``yellow_0``; ``field``,
    ``realism``, ``realtime``, ``render_mode``, ``tracker`` and further env options pass
    through."""

    def __init__(self, max_time_s: float = 2.0, post_kick_time_s: float = 4.0, hold_s: float = 0.5,
                 distance_range: tuple[float, float] = (3.0, 5.0), blocker_side: float = 0.05,
                 resolve_after_kick: bool = True, field: str = "div_b", realism: Any = "none",
                 realtime: bool = False, render_mode: str | None = None, tracker: Any = False,
                 **env_kwargs: Any) -> None:
        task = ChipPassTask(max_time_s, post_kick_time_s, hold_s, distance_range, blocker_side, resolve_after_kick)
        env = SSLParallelEnv(n_blue=2, n_yellow=1, field=field, realism=realism, realtime=realtime, referee=False,
                             max_time_s=1e9, render_mode=render_mode, obs_max_teammates=0, obs_max_opponents=0,
                             chip_kicks=True, **env_kwargs)
        env = with_tracker(env, tracker)
        driver = ChipLayoutDriver(PassReceiverDriver(task, env.field, env.config.robot, env.config.ball))
        super().__init__(env, PASSER, task, drivers=[driver])
        EzPickle.__init__(self, max_time_s=max_time_s, post_kick_time_s=post_kick_time_s, hold_s=hold_s,
                          distance_range=distance_range, blocker_side=blocker_side,
                          resolve_after_kick=resolve_after_kick, field=field, realism=realism, realtime=realtime,
                          render_mode=render_mode, tracker=tracker, **env_kwargs)


def chip_pass_skill_action(env: ChipPassEnv, skill: Any) -> np.ndarray:
    """One step of a chip-pass skill (hand-coded or learned) in its task env: the
    skill's task action (:attr:`~ssl_marl.skills.chip_pass.ChipPassSkill.task_action`;
    a skill of another kind: its (6,) action projected onto the task's); the skill's
    target is the receiver's seen position and velocity, updated every step."""
    seen = env.seen()
    tgt, tv = env.target(seen)
    skill.set_target(env.field.clamp_to_field(tgt), tv)
    action = skill.act(seen, 0)
    task_action = getattr(skill, "task_action", None)
    return task_action if task_action is not None else chip_pass_task_action(action, env.robot_params)


def chip_pass_baseline_demos(n_steps: int, seed: int = 0, **env_kwargs: Any) -> Iterator[Transition]:
    """``n_steps`` chip-pass transitions (obs (12,), action (4,)) from
    :class:`~ssl_marl.skills.chip_pass.ChipPassBaseline` on the task's own spawns;
    successful episodes only."""
    env = ChipPassEnv(**env_kwargs)
    skill = ChipPassBaseline(env.field, env.robot_params, env.ball_params)
    return skill_demos(env, skill, chip_pass_skill_action, n_steps, seed)


__all__ = ["BLOCKER", "ChipLayoutDriver", "ChipPassEnv", "ChipPassTask", "chip_pass_baseline_demos",
           "chip_pass_skill_action"]
