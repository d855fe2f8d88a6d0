"""Deterministic evaluation of an actor (no exploration noise).

``python -m train.offpolicy.evaluate ENV_ID ACTOR.pt --episodes 10 --seed 0 [--out eval.json]``
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
import torch

import ssl_marl  # noqa: F401  (registers the ssl_marl/* Gymnasium ids)
from ssl_marl.skills.checkpoint import load_actor


class ActionScaler:
    """Maps the actor's [-1, 1] output to a bounded Box's [low, high] and back."""

    def __init__(self, space: gym.Space) -> None:
        if not isinstance(space, gym.spaces.Box):
            raise ValueError(f"DDPG needs a Box action space, got {space}")
        self.low = np.asarray(space.low, np.float64)
        self.high = np.asarray(space.high, np.float64)
        if not (np.all(np.isfinite(self.low)) and np.all(np.isfinite(self.high))):
            raise ValueError(f"DDPG needs a bounded action space, got {space}")
        self.dtype = space.dtype

    def to_env(self, a: np.ndarray) -> np.ndarray:
        """[-1, 1] -> [low, high]."""
        return (self.low + (np.asarray(a, np.float64) + 1.0) * 0.5 * (self.high - self.low)).astype(self.dtype)

    def from_env(self, a: np.ndarray) -> np.ndarray:
        """[low, high] -> [-1, 1] (float32)."""
        span = np.where(self.high > self.low, self.high - self.low, 1.0)
        return (2.0 * (np.asarray(a, np.float64) - self.low) / span - 1.0).astype(np.float32)


def make_env(env_id: str, env_kwargs: Mapping[str, Any] | None = None,
             max_episode_steps: int | None = None) -> gym.Env:
    """``gym.make`` with the run's kwargs (``max_episode_steps`` only when set)."""
    kwargs = dict(env_kwargs or {})
    if max_episode_steps:
        kwargs["max_episode_steps"] = int(max_episode_steps)
    return gym.make(env_id, **kwargs)


def run_episodes(env: gym.Env, policy: Callable[[np.ndarray], np.ndarray], episodes: int,
                 seed: int) -> dict[str, Any]:
    """Run ``episodes`` episodes of ``policy`` (obs -> action in [-1, 1]); the env is seeded once with
    ``seed``, so the same seed gives the same start states. Returns mean/std return, mean length,
    success rate (from ``info["is_success"]`` at episode end, None if the env never reports it)."""
    scaler = ActionScaler(env.action_space)
    returns, lengths, successes = [], [], []
    for ep in range(episodes):
        obs, _ = env.reset(seed=seed if ep == 0 else None)
        ret, length, done, info = 0.0, 0, False, {}
        while not done:
            obs, rew, term, trunc, info = env.step(scaler.to_env(policy(obs)))
            ret += float(rew)
            length += 1
            done = bool(term or trunc)
        returns.append(ret)
        lengths.append(length)
        if "is_success" in info:
            successes.append(float(bool(info["is_success"])))
    return {"episodes": episodes, "seed": seed, "mean_return": float(np.mean(returns)),
            "std_return": float(np.std(returns)), "mean_length": float(np.mean(lengths)),
            "success_rate": float(np.mean(successes)) if successes else None, "returns": returns}


def evaluate_actor(env_id: str, actor_path: str | Path, episodes: int = 10, seed: int = 0,
                   env_kwargs: Mapping[str, Any] | None = None,
                   max_episode_steps: int | None = None) -> dict[str, Any]:
    """Evaluate the exported actor at ``actor_path`` deterministically on ``env_id``.

    ``env_kwargs`` / ``max_episode_steps`` default to those the actor was trained with
    (from its metadata's ``hyperparameters``).
    """
    actor, meta = load_actor(actor_path)
    hp = meta.get("hyperparameters") if isinstance(meta.get("hyperparameters"), dict) else {}
    if env_kwargs is None:
        env_kwargs = hp.get("env_kwargs") or {}
    if max_episode_steps is None:
        max_episode_steps = hp.get("max_episode_steps")
    env = make_env(env_id, env_kwargs, max_episode_steps)
    try:
        if env.observation_space.shape != (actor.obs_dim,):
            raise ValueError(f"{actor_path}: actor expects obs ({actor.obs_dim},), "
                             f"{env_id} gives {env.observation_space.shape}")

        @torch.no_grad()
        def policy(obs: np.ndarray) -> np.ndarray:
            return actor(torch.as_tensor(np.asarray(obs, np.float32))).numpy()

        result = run_episodes(env, policy, episodes, seed)
    finally:
        env.close()
    result.update(env_id=env_id, actor=str(actor_path), skill=meta.get("skill"), samples=meta.get("samples"))
    return result


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m train.offpolicy.evaluate", description=__doc__)
    p.add_argument("env_id")
    p.add_argument("actor", type=Path)
    p.add_argument("--episodes", type=int, default=10)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--out", type=Path, default=None, help="write the result as JSON here")
    args = p.parse_args(argv)
    torch.set_num_threads(1)
    result = evaluate_actor(args.env_id, args.actor, args.episodes, args.seed)
    text = json.dumps(result, indent=2)
    if args.out:
        args.out.write_text(text + "\n")
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
