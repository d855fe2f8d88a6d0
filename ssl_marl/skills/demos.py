"""Demonstration generators for replay burn-in (paper, section 5.1).

* go-to-ball: the robot spawns at a random position *facing the ball* and drives
  straight forward at full speed until it touches it (:func:`go_to_ball_demos`); for a
  task whose ball may be rolling, the hand-coded skill's successful episodes, which lead
  the ball by its velocity (:func:`go_to_ball_baseline_demos`).
* aim-to-shoot: the robot spawns near the opponent goal (1-2.5 m in front of it),
  facing a point between the posts, and kicks at full strength at once.

Both yield :class:`Transition` tuples in the task wrapper's exact spaces, episode
after episode, until ``n_steps`` transitions have been produced.
"""

from __future__ import annotations

import math
from typing import Any, Callable, Iterator, NamedTuple

import numpy as np

from .wrappers import AimToShootEnv, GoToBallEnv


class Transition(NamedTuple):
    obs: np.ndarray
    action: np.ndarray
    reward: float
    next_obs: np.ndarray
    terminated: bool
    truncated: bool
    info: dict


def _run(env, n_steps: int, seed: int, reset_options, policy) -> Iterator[Transition]:
    rng = np.random.default_rng(seed)
    produced, episode = 0, 0
    while produced < n_steps:
        obs, _ = env.reset(seed=int(rng.integers(2 ** 31)), options=reset_options(env, rng))
        done = False
        while not done and produced < n_steps:
            action = policy(obs)
            next_obs, reward, terminated, truncated, info = env.step(action)
            yield Transition(obs, action, float(reward), next_obs, bool(terminated), bool(truncated), info)
            produced += 1
            obs, done = next_obs, terminated or truncated
        episode += 1


def go_to_ball_demos(n_steps: int, seed: int = 0, **env_kwargs: Any) -> Iterator[Transition]:
    """``n_steps`` go-to-ball demonstration transitions (obs (14,), action (3,))."""
    env = GoToBallEnv(**env_kwargs)
    forward = np.array([1.0, 0.0, 0.0], dtype=np.float32)
    return _run(env, n_steps, seed, lambda e, rng: {"face_ball": True}, lambda obs: forward)


def go_to_ball_baseline_demos(n_steps: int, seed: int = 0, **env_kwargs: Any) -> Iterator[Transition]:
    """``n_steps`` go-to-ball transitions of the hand-coded skill
    (:class:`~ssl_marl.skills.baseline.GoToBallBaseline`, which leads a rolling ball by its
    velocity) from the task's own spawns (``env_kwargs``: e.g. ``rolling``, ``state``);
    successful episodes only."""
    from .baseline import GoToBallBaseline
    from .features import go_to_ball_task_action

    env = GoToBallEnv(**env_kwargs)
    skill = GoToBallBaseline(env.field, env.robot_params, env.ball_params)
    return skill_demos(env, skill, lambda e, sk: go_to_ball_task_action(sk.act(e.seen(), 0)), n_steps, seed)


def aim_to_shoot_demos(n_steps: int, seed: int = 0, **env_kwargs: Any) -> Iterator[Transition]:
    """``n_steps`` aim-to-shoot demonstration transitions (obs (10,), action (3,))."""
    env = AimToShootEnv(**env_kwargs)
    f = env.field
    kick = np.array([0.0, 1.0, 1.0], dtype=np.float32)

    def options(e, rng):
        x = rng.uniform(f.half_length - 2.5, f.half_length - 1.0)
        y = rng.uniform(-f.goal_width, f.goal_width)
        aim_y = rng.uniform(-0.3, 0.3) * f.goal_width
        return {"robot_pose": (x, y, math.atan2(aim_y - y, f.half_length - x))}

    return _run(env, n_steps, seed, options, lambda obs: kick)


def aim_to_shoot_baseline_demos(n_steps: int, seed: int = 0, post_margin: float = 0.05,
                                **env_kwargs: Any) -> Iterator[Transition]:
    """``n_steps`` aim-to-shoot transitions from the hand-coded skill (turn towards the
    goal with the dribbler on, kick once the heading is ``post_margin`` rad inside the
    posts) from the task's own random spawns; only successful episodes are kept. These
    show turning with the ball, which the paper's facing-the-goal demos do not."""
    from .baseline import AimToShootBaseline
    from .wrappers import task_action

    env = AimToShootEnv(**env_kwargs)
    skill = AimToShootBaseline(env.field, env.robot_params, env.ball_params, post_margin=post_margin)
    yield from skill_demos(env, skill, lambda e, sk: task_action("aim-to-shoot", sk.act(e.seen(), 0)),
                                      n_steps, seed)


def skill_demos(env: Any, skill: Any, act: Callable[[Any, Any], np.ndarray], n_steps: int, seed: int,
                successful_only: bool = True) -> Iterator[Transition]:
    """``n_steps`` transitions of ``skill`` (a :class:`~ssl_marl.skills.base.Skill`) acting
    in task env ``env`` through ``act(env, skill) -> task action``, from the task's own
    random spawns (episode seeds drawn from ``seed``); only successful episodes are kept
    unless ``successful_only`` is False (then failures too, e.g. for a critic to see what
    the hand-coded choices lead to)."""
    rng = np.random.default_rng(seed)
    produced = 0
    while produced < n_steps:
        obs, _ = env.reset(seed=int(rng.integers(2 ** 31)))
        skill.reset()
        episode: list[Transition] = []
        while True:
            action = act(env, skill)
            next_obs, reward, terminated, truncated, info = env.step(action)
            episode.append(Transition(obs, action, float(reward), next_obs, bool(terminated), bool(truncated), info))
            obs = next_obs
            if terminated or truncated:
                break
        if successful_only and not info["is_success"]:
            continue
        for tr in episode[: n_steps - produced]:
            yield tr
        produced += min(len(episode), n_steps - produced)


def aim_to_shoot_mixed_demos(n_steps: int, seed: int = 0, **env_kwargs: Any) -> Iterator[Transition]:
    """Half :func:`aim_to_shoot_demos` (the paper's), half :func:`aim_to_shoot_baseline_demos`."""
    half = n_steps // 2
    yield from aim_to_shoot_demos(half, seed, **env_kwargs)
    yield from aim_to_shoot_baseline_demos(n_steps - half, seed + 1, **env_kwargs)
