"""n-step returns for the replay: per-env windows of the last ``n`` steps, folded into one transition.

For a start step t of sub-env i the stored transition is::

    obs      = s_t,   act = a_t
    rew      = r_t + gamma r_{t+1} + ... + gamma^(k-1) r_{t+k-1}
    next_obs = s_{t+k}
    terminated = 1 if the episode truly ended at step t+k-1 (no bootstrap), else 0
    discount = gamma^k

with k = n while the episode runs on, and k < n for the last n-1 starts of an episode
(the window is truncated at the episode's end). The critic's target is then
``rew + discount * (1 - terminated) * Q'(next_obs, mu'(next_obs))``
(:func:`train.offpolicy.agent.td_target`), so:

* a termination inside the window ends the sum there and never bootstraps;
* a truncation (time limit, or the trainer cutting episodes at a checkpoint) ends the sum
  there and bootstraps from the last true observation with ``gamma^k``;
* ``n = 1`` gives exactly the one-step transitions (``discount = gamma``).

Rewards are summed in float64 and stored as float32; units are the env's reward units
(times the trainer's ``reward_scale``, applied by the caller before :meth:`NStepBuffer.step`).
"""

from __future__ import annotations

from collections import deque
from typing import NamedTuple

import numpy as np


class NStepTransitions(NamedTuple):
    """Transitions ready for the replay (leading axis m, m may be 0); float32."""

    obs: np.ndarray  #: (m, obs_dim)
    act: np.ndarray  #: (m, act_dim)
    rew: np.ndarray  #: (m,) discounted sum of the window's rewards
    next_obs: np.ndarray  #: (m, obs_dim) observation after the window's last step
    terminated: np.ndarray  #: (m,) 1.0 where the window ends in a true termination
    discount: np.ndarray  #: (m,) gamma ** (steps in the window)


class NStepBuffer:
    """Pending windows of ``num_envs`` sub-envs (``n`` >= 1 steps, discount ``gamma`` in [0, 1])."""

    def __init__(self, num_envs: int, n: int, gamma: float, obs_dim: int, act_dim: int) -> None:
        if not isinstance(n, int) or isinstance(n, bool) or n < 1:
            raise ValueError(f"n_step must be an integer >= 1 (got {n!r})")
        if not 0.0 <= gamma <= 1.0:
            raise ValueError(f"gamma must be in [0, 1] (got {gamma!r})")
        if num_envs < 1:
            raise ValueError(f"num_envs must be >= 1 (got {num_envs!r})")
        self.num_envs, self.n, self.gamma, self.obs_dim, self.act_dim = num_envs, n, float(gamma), obs_dim, act_dim
        self.pending: list[deque[tuple[np.ndarray, np.ndarray, float]]] = [deque() for _ in range(num_envs)]
        self._powers = self.gamma ** np.arange(n + 1, dtype=np.float64)

    def __len__(self) -> int:
        """Steps waiting for their window to fill (over all sub-envs)."""
        return sum(len(p) for p in self.pending)

    def _emit(self, i: int, next_obs: np.ndarray, terminated: bool, out: list) -> None:
        """Emit the oldest pending step of sub-env ``i`` with its window up to now, and drop it."""
        window = self.pending[i]
        k = len(window)
        rews = np.fromiter((w[2] for w in window), np.float64, k)
        obs, act, _ = window.popleft()
        out.append((obs, act, float(rews @ self._powers[:k]), next_obs, float(terminated), float(self._powers[k])))

    def step(self, env_ids: np.ndarray, obs: np.ndarray, act: np.ndarray, rew: np.ndarray, next_obs: np.ndarray,
             terminated: np.ndarray, truncated: np.ndarray) -> NStepTransitions:
        """Add one step for each sub-env in ``env_ids`` (rows of the other arrays, in that order);
        return the transitions whose windows are complete: the oldest step of every full window,
        and every pending step of a sub-env whose episode ended here (terminated or truncated)."""
        out: list = []
        for row, i in enumerate(np.asarray(env_ids, np.int64)):
            self.pending[i].append((np.array(obs[row], np.float32), np.array(act[row], np.float32), float(rew[row])))
            nxt = np.array(next_obs[row], np.float32)
            if bool(terminated[row]) or bool(truncated[row]):
                while self.pending[i]:
                    self._emit(i, nxt, bool(terminated[row]), out)
            elif len(self.pending[i]) == self.n:
                self._emit(i, nxt, False, out)
        return self._pack(out)

    def flush(self, last_obs: np.ndarray) -> NStepTransitions:
        """End every running window as a truncation at ``last_obs`` (num_envs, obs_dim), the current
        observation of each sub-env: used when the trainer cuts the running episodes."""
        out: list = []
        for i in range(self.num_envs):
            while self.pending[i]:
                self._emit(i, np.array(last_obs[i], np.float32), False, out)
        return self._pack(out)

    def _pack(self, out: list) -> NStepTransitions:
        if not out:
            return NStepTransitions(np.zeros((0, self.obs_dim), np.float32), np.zeros((0, self.act_dim), np.float32),
                                    np.zeros(0, np.float32), np.zeros((0, self.obs_dim), np.float32),
                                    np.zeros(0, np.float32), np.zeros(0, np.float32))
        obs, act, rew, nxt, term, disc = zip(*out)
        return NStepTransitions(np.stack(obs), np.stack(act), np.asarray(rew, np.float32), np.stack(nxt),
                                np.asarray(term, np.float32), np.asarray(disc, np.float32))
