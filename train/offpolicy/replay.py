"""Replay memory: a numpy ring buffer of (obs, act, rew, next_obs, terminated[, discount]).

With ``discount=True`` (n-step returns, :mod:`train.offpolicy.nstep`) every row also stores its own
bootstrap discount (``gamma ** k`` for a k-step window); rows added without one get
``default_discount`` (e.g. the one-step demonstrations). Without it the buffer and its
files are exactly the one-step ones (``Batch.discount`` is None).

Sampling is uniform with replacement. Indices are drawn once per batch and
gathered with ``np.take(..., out=...)`` into preallocated arrays that share
memory with the returned torch tensors (no per-sample Python, no allocation):
the tensors of a batch are overwritten by the next :meth:`ReplayBuffer.sample`.
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path
from typing import NamedTuple

import numpy as np
import torch


class Batch(NamedTuple):
    """A sampled batch; shapes (B, obs_dim), (B, act_dim), (B,), (B, obs_dim), (B,); float32."""

    obs: torch.Tensor
    act: torch.Tensor
    rew: torch.Tensor
    next_obs: torch.Tensor
    terminated: torch.Tensor  # 1.0 where the episode truly ended (no bootstrap), else 0.0
    discount: torch.Tensor | None = None  # (B,) per-row bootstrap discount (n-step); None: the config's gamma


class ReplayBuffer:
    """Fixed-capacity FIFO of transitions; the oldest are overwritten once full."""

    _FIELDS = ("obs", "act", "rew", "next_obs", "terminated")

    def __init__(self, capacity: int, obs_dim: int, act_dim: int, batch_size: int,
                 rng: np.random.Generator | None = None, discount: bool = False,
                 default_discount: float = 1.0) -> None:
        if capacity <= 0 or batch_size <= 0:
            raise ValueError(f"capacity and batch_size must be > 0 (got {capacity}, {batch_size})")
        self._FIELDS = ReplayBuffer._FIELDS + (("discount",) if discount else ())
        self.default_discount = float(default_discount)
        if discount:
            self.discount = np.zeros(capacity, np.float32)
        self.capacity, self.obs_dim, self.act_dim, self.batch_size = int(capacity), obs_dim, act_dim, batch_size
        self.rng = rng if rng is not None else np.random.default_rng()
        self.obs = np.zeros((capacity, obs_dim), np.float32)
        self.act = np.zeros((capacity, act_dim), np.float32)
        self.rew = np.zeros(capacity, np.float32)
        self.next_obs = np.zeros((capacity, obs_dim), np.float32)
        self.terminated = np.zeros(capacity, np.float32)
        self.ptr = 0  # next row to write
        self.size = 0  # rows holding data
        self._out = {k: np.zeros((batch_size, *getattr(self, k).shape[1:]), np.float32) for k in self._FIELDS}
        self._batch = Batch(*(torch.from_numpy(self._out[k]) for k in self._FIELDS))

    def __len__(self) -> int:
        return self.size

    def add(self, obs: np.ndarray, act: np.ndarray, rew: np.ndarray, next_obs: np.ndarray,
            terminated: np.ndarray, discount: np.ndarray | None = None) -> None:
        """Append n transitions (leading axis n; n may be 0), wrapping around when full.
        ``discount`` (n,): per-row bootstrap discounts, only for a buffer made with
        ``discount=True`` (default there: ``default_discount``)."""
        obs = np.asarray(obs, np.float32).reshape(-1, self.obs_dim)
        n = obs.shape[0]
        if n == 0:
            return
        data: tuple[np.ndarray, ...] = (
            obs, np.asarray(act, np.float32).reshape(n, self.act_dim),
            np.asarray(rew, np.float32).reshape(n), np.asarray(next_obs, np.float32).reshape(n, self.obs_dim),
            np.asarray(terminated, np.float32).reshape(n))
        if "discount" in self._FIELDS:
            disc = np.full(n, self.default_discount, np.float32) if discount is None \
                else np.asarray(discount, np.float32).reshape(n)
            data = data + (disc,)
        elif discount is not None:
            raise ValueError("this replay buffer stores no per-row discount (make it with discount=True)")
        if n > self.capacity:  # only the newest `capacity` rows survive anyway
            data = tuple(d[-self.capacity:] for d in data)
            self.ptr = (self.ptr + n - self.capacity) % self.capacity
            n = self.capacity
        idx = (self.ptr + np.arange(n)) % self.capacity
        for name, d in zip(self._FIELDS, data):
            getattr(self, name)[idx] = d
        self.ptr = (self.ptr + n) % self.capacity
        self.size = min(self.size + n, self.capacity)

    def sample(self) -> Batch:
        """A uniform batch of ``batch_size`` transitions (tensors reused by the next call)."""
        if self.size == 0:
            raise ValueError("cannot sample from an empty replay buffer")
        idx = self.rng.integers(0, self.size, self.batch_size)
        for name in self._FIELDS:
            np.take(getattr(self, name), idx, axis=0, out=self._out[name])
        return self._batch

    # --- persistence ------------------------------------------------------
    def sample_rows(self, lo: int, hi: int, n: int) -> Batch:
        """A fresh batch of ``n`` rows drawn uniformly from rows [lo, hi) (e.g. the demonstrations,
        which burn-in writes first)."""
        idx = self.rng.integers(lo, hi, n)
        return Batch(*(torch.from_numpy(getattr(self, k)[idx]) for k in self._FIELDS))

    def save(self, path: str | os.PathLike[str]) -> Path:
        """Write the contents to an ``.npz`` atomically (the sampling RNG is saved by the caller)."""
        path = Path(path)
        arrays = {k: getattr(self, k)[: self.size] for k in self._FIELDS}
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
        try:
            with os.fdopen(fd, "wb") as f:
                np.savez(f, ptr=self.ptr, size=self.size, capacity=self.capacity, **arrays)
                f.flush()
                os.fsync(f.fileno())
            os.replace(tmp, path)
        except BaseException:
            Path(tmp).unlink(missing_ok=True)
            raise
        return path

    def load(self, path: str | os.PathLike[str]) -> None:
        """Restore contents saved by :meth:`save` into this (same-shaped) buffer."""
        try:
            with np.load(path, allow_pickle=False) as z:
                capacity, size, ptr = int(z["capacity"]), int(z["size"]), int(z["ptr"])
                arrays = {k: z[k] for k in self._FIELDS}
        except FileNotFoundError:
            raise FileNotFoundError(f"replay file not found: {path}") from None
        except Exception as exc:
            raise ValueError(f"{path} is not a valid replay buffer file: {exc}") from exc
        if capacity != self.capacity or arrays["obs"].shape[1:] != (self.obs_dim,) \
                or arrays["act"].shape[1:] != (self.act_dim,):
            raise ValueError(f"{path}: replay shape (capacity {capacity}, obs {arrays['obs'].shape[1:]}, "
                             f"act {arrays['act'].shape[1:]}) does not match this buffer "
                             f"({self.capacity}, ({self.obs_dim},), ({self.act_dim},))")
        for k in self._FIELDS:
            getattr(self, k)[:size] = arrays[k]
        self.size, self.ptr = size, ptr
