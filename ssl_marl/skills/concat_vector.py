"""Several Gymnasium vector envs of one task side by side, as one vector env.

:class:`ConcatVectorEnv` steps ``[v_0, v_1, ...]`` together: sub-env ``i`` of the result
is sub-env ``i - offset_j`` of ``v_j`` (consecutive blocks). It exists so that one
learner can collect from differently configured copies of a task at once (for
example go-to-ball worlds on the Division A and on the Division B field, whose
batched physics cannot share one :class:`~ssl_marl.envs.batched_env.BatchedSSLEnv`).

* Observations, rewards, terminations and truncations are concatenated.
* Infos (dicts of arrays with ``_key`` masks, Gymnasium's vector convention) are
  merged key by key, recursively for dict values; a block that lacks a key gets a
  zero / ``None`` entry with its mask False.
* ``reset(seed=s)`` seeds sub-env ``i`` with ``s + i`` (as one vector env would).
* The single observation space is the elementwise union of the blocks' Boxes (the
  bounds differ with the field); actions and observation shapes must agree.
"""

from __future__ import annotations

from typing import Any, Sequence

import numpy as np
from gymnasium import spaces
from gymnasium.vector import VectorEnv
from gymnasium.vector.utils import batch_space


def _merge_infos(infos: Sequence[dict], sizes: Sequence[int]) -> dict:
    """Concatenate vector infos (dicts of per-sub-env arrays + ``_key`` masks)."""
    keys: list[str] = []
    for info in infos:
        keys += [k for k in info if not k.startswith("_") and k not in keys]
    out: dict[str, Any] = {}
    for k in keys:
        present = [info.get(k) for info in infos]
        if any(isinstance(v, dict) for v in present):
            out[k] = _merge_infos([v if isinstance(v, dict) else {} for v in present], sizes)
        else:
            proto = np.asarray(next(v for v in present if v is not None))
            parts = [np.asarray(v) if v is not None else
                     (np.full(n, None, object) if proto.dtype == object else np.zeros(n, proto.dtype))
                     for v, n in zip(present, sizes)]
            out[k] = np.concatenate(parts)
        out["_" + k] = np.concatenate([np.asarray(info.get("_" + k, np.full(n, k in info)), bool)
                                       for info, n in zip(infos, sizes)])
    return out


class ConcatVectorEnv(VectorEnv):
    """The vector envs ``envs`` (one task, any configurations) as one vector env (module docstring)."""

    def __init__(self, envs: Sequence[VectorEnv]) -> None:
        if not envs:
            raise ValueError("ConcatVectorEnv needs at least one vector env")
        self.envs = list(envs)
        first = self.envs[0]
        obs_spaces = [e.single_observation_space for e in self.envs]
        if not all(isinstance(s, spaces.Box) and s.shape == obs_spaces[0].shape for s in obs_spaces):
            raise ValueError(f"ConcatVectorEnv: observation spaces must be Boxes of one shape, got {obs_spaces}")
        for e in self.envs[1:]:
            if e.single_action_space != first.single_action_space:
                raise ValueError(f"ConcatVectorEnv: action spaces differ ({e.single_action_space} vs "
                                 f"{first.single_action_space})")
            if e.metadata.get("autoreset_mode") != first.metadata.get("autoreset_mode"):
                raise ValueError("ConcatVectorEnv: the vector envs' autoreset modes differ")
        low = np.minimum.reduce([s.low for s in obs_spaces])
        high = np.maximum.reduce([s.high for s in obs_spaces])
        self.sizes = [e.num_envs for e in self.envs]
        self.offsets = np.concatenate([[0], np.cumsum(self.sizes)]).astype(int)
        self.num_envs = int(self.offsets[-1])
        self.metadata = dict(first.metadata)
        self.single_observation_space = spaces.Box(low, high, obs_spaces[0].shape, obs_spaces[0].dtype)
        self.single_action_space = first.single_action_space
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)
        self.render_mode = None

    def _split(self, x: Any) -> list[Any]:
        return [x[a:b] for a, b in zip(self.offsets[:-1], self.offsets[1:])]

    def reset(self, *, seed: int | list[int | None] | None = None, options: dict | None = None):
        if seed is None or isinstance(seed, (int, np.integer)):
            seeds = [None if seed is None else int(seed) + int(o) for o in self.offsets[:-1]]
        else:
            if len(seed) != self.num_envs:
                raise ValueError(f"reset: {len(seed)} seeds for {self.num_envs} sub-envs")
            seeds = self._split(list(seed))
        res = [e.reset(seed=s, options=options) for e, s in zip(self.envs, seeds)]
        return np.concatenate([r[0] for r in res]), _merge_infos([r[1] for r in res], self.sizes)

    def step(self, actions: Any):
        actions = np.asarray(actions)
        if actions.shape[:1] != (self.num_envs,):
            raise ValueError(f"actions: expected {self.num_envs} rows (one per sub-env), got shape {actions.shape}")
        res = [e.step(a) for e, a in zip(self.envs, self._split(actions))]
        obs, rew, term, trunc = (np.concatenate([r[i] for r in res]) for i in range(4))
        return obs, rew, term, trunc, _merge_infos([r[4] for r in res], self.sizes)

    def close_extras(self, **kwargs: Any) -> None:
        for e in self.envs:
            e.close()


__all__ = ["ConcatVectorEnv"]
