"""A trivially learnable 1-D task and its demonstrations, for tests and smoke runs of the trainer.

``train_toy/MoveToTarget-v0`` (registered on import; use the id
``"train.offpolicy.toy:train_toy/MoveToTarget-v0"`` to import this module from ``gym.make``):
a point at position x in [-1, 1] must reach the target x = 0.

* obs: ``[x]`` (float32, shape (1,))
* action: velocity in Box(-2, 2, (1,)) (deliberately not [-1, 1], to exercise
  action rescaling); ``x <- clip(x + 0.05 * v, -1, 1)``
* reward: ``-|x|`` per step (term "distance") plus +1 on reaching |x| < 0.05
  (term "bonus"), which terminates the episode with ``info["is_success"] = True``
* truncation after ``max_steps`` (default 40) steps.

An idle policy (v = 0) scores about -0.5 * 40 = -20 on average; a good one about -2.
"""

from __future__ import annotations

from typing import Any, Iterator

import gymnasium as gym
import numpy as np

from ssl_marl.skills.demos import Transition

ENV_ID = "train_toy/MoveToTarget-v0"


class MoveToTarget(gym.Env):
    metadata = {"render_modes": []}
    spec_version = "toy_move_to_target/v1"

    def __init__(self, max_steps: int = 40, speed: float = 0.05, goal_radius: float = 0.05) -> None:
        self.observation_space = gym.spaces.Box(-1.0, 1.0, (1,), np.float32)
        self.action_space = gym.spaces.Box(-2.0, 2.0, (1,), np.float32)
        self.max_steps, self.speed, self.goal_radius = max_steps, speed, goal_radius
        self.x, self.t = 0.0, 0

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None):
        super().reset(seed=seed)
        self.x = float(self.np_random.choice([-1.0, 1.0]) * self.np_random.uniform(0.3, 1.0))
        self.t = 0
        return np.array([self.x], np.float32), {}

    def step(self, action: np.ndarray):
        v = float(np.clip(np.asarray(action, np.float64).reshape(-1)[0], -2.0, 2.0))
        self.x = float(np.clip(self.x + self.speed * v, -1.0, 1.0))
        self.t += 1
        success = abs(self.x) < self.goal_radius
        terms = {"distance": -abs(self.x), "bonus": 1.0 if success else 0.0}
        truncated = (not success) and self.t >= self.max_steps
        info: dict[str, Any] = {"reward_terms": terms}
        if success or truncated:
            info["is_success"] = success
        return np.array([self.x], np.float32), float(sum(terms.values())), success, truncated, info


def toy_demos(n_steps: int, seed: int = 0, **env_kwargs: Any) -> Iterator[Transition]:
    """``n_steps`` transitions of the expert (full speed towards the target), episode after episode."""
    env = MoveToTarget(**env_kwargs)
    rng = np.random.default_rng(seed)
    produced = 0
    while produced < n_steps:
        obs, _ = env.reset(seed=int(rng.integers(2**31)))
        done = False
        while not done and produced < n_steps:
            action = np.array([-2.0 * np.sign(obs[0])], np.float32)
            next_obs, rew, term, trunc, info = env.step(action)
            yield Transition(obs, action, rew, next_obs, term, trunc, info)
            produced += 1
            obs, done = next_obs, term or trunc


if ENV_ID not in gym.registry:
    gym.register(id=ENV_ID, entry_point=MoveToTarget)
