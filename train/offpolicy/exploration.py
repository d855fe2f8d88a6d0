"""Exploration noise added to the actor's actions during collection, one process per sub-env.

The :class:`Exploration` interface: ``noise()`` advances every sub-env's process one
step and returns the ``(num_envs, act_dim)`` noise (float32, in the actor's normalised
action units); ``reset(mask)`` restarts the processes of sub-envs whose episode ended;
``state_dict()`` / ``load_state_dict()`` for exact resume. Two kinds, by
``exploration.kind`` (:class:`train.offpolicy.config.ExplorationConfig`, :func:`make_exploration`):

* ``"ou"`` -- :class:`OUNoise`, the Ornstein-Uhlenbeck process of DDPG (Lillicrap et
  al. 2016) and of the paper (Tables 1 and 2: theta 0.15, mu 0, sigma 0.3);
* ``"gaussian"`` -- :class:`GaussianNoise`, independent N(0, sigma) per step, as
  TD3 (Fujimoto et al. 2018: sigma 0.1) and most later work use.

Ornstein-Uhlenbeck: Euler-Maruyama step of dx = theta (mu - x) dt + sigma dW::

    x <- x + theta * (mu - x) * dt + sigma * sqrt(dt) * N(0, 1)

For dt = 1 this is the textbook discrete process, an AR(1) with stationary mean
mu and stationary std sigma / sqrt(2 theta - theta^2) (~= sigma / sqrt(2 theta)
for small theta: 0.569 vs 0.548 at theta 0.15, sigma 0.3). Values are in the
actor's normalised action units.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, Protocol, runtime_checkable

import numpy as np

from train.offpolicy.config import ExplorationConfig


@runtime_checkable
class Exploration(Protocol):
    """Per-sub-env action noise (see the module docstring)."""

    def __call__(self) -> np.ndarray: ...

    def reset(self, mask: np.ndarray | None = None) -> None: ...

    def state_dict(self) -> dict[str, Any]: ...

    def load_state_dict(self, state: dict[str, Any]) -> None: ...


def _sigma(sigma: float | Sequence[float], act_dim: int) -> float | np.ndarray:
    """One sigma for every dimension (float) or one per dimension (array of act_dim)."""
    if np.ndim(sigma):
        return np.broadcast_to(np.asarray(sigma, dtype=np.float64), (act_dim,)).copy()
    return float(sigma)  # type: ignore[arg-type]


class OUNoise:
    """Vectorised OU process of shape ``(num_envs, act_dim)``; reset per sub-env at episode end."""

    def __init__(self, num_envs: int, act_dim: int, theta: float = 0.15, mu: float = 0.0,
                 sigma: float | Sequence[float] = 0.3, dt: float = 1.0,
                 rng: np.random.Generator | None = None) -> None:
        """``sigma`` is one value for every action dimension or one per dimension."""
        sig = _sigma(sigma, act_dim)
        if theta < 0 or np.any(np.asarray(sig) < 0) or dt <= 0:
            raise ValueError(f"need theta >= 0, sigma >= 0, dt > 0 (got {theta}, {sigma}, {dt})")
        self.theta, self.mu, self.sigma, self.dt = float(theta), float(mu), sig, float(dt)
        self.rng = rng if rng is not None else np.random.default_rng()
        self.x = np.full((num_envs, act_dim), self.mu, dtype=np.float64)

    def __call__(self) -> np.ndarray:
        """Advance every process one step; return the new state (float32 copy)."""
        self.x += self.theta * (self.mu - self.x) * self.dt \
            + self.sigma * np.sqrt(self.dt) * self.rng.standard_normal(self.x.shape)
        return self.x.astype(np.float32)

    def reset(self, mask: np.ndarray | None = None) -> None:
        """Set the processes of sub-envs where ``mask`` is True (all if None) back to mu."""
        if mask is None:
            self.x[:] = self.mu
        else:
            self.x[np.asarray(mask, bool)] = self.mu

    def state_dict(self) -> dict[str, Any]:
        return {"x": self.x.tolist(), "rng": self.rng.bit_generator.state}

    def load_state_dict(self, state: dict[str, Any]) -> None:
        x = np.asarray(state["x"], dtype=np.float64)
        if x.shape != self.x.shape:
            raise ValueError(f"OU state shape {x.shape} does not match {self.x.shape}")
        self.x[:] = x
        self.rng.bit_generator.state = state["rng"]


class GaussianNoise:
    """Independent N(0, sigma^2) noise of shape ``(num_envs, act_dim)`` each step (no state to reset)."""

    def __init__(self, num_envs: int, act_dim: int, sigma: float | Sequence[float] = 0.1,
                 rng: np.random.Generator | None = None) -> None:
        """``sigma`` is one value for every action dimension or one per dimension."""
        self.sigma = _sigma(sigma, act_dim)
        if np.any(np.asarray(self.sigma) < 0):
            raise ValueError(f"need sigma >= 0 (got {sigma})")
        self.shape = (num_envs, act_dim)
        self.rng = rng if rng is not None else np.random.default_rng()

    def __call__(self) -> np.ndarray:
        return (self.sigma * self.rng.standard_normal(self.shape)).astype(np.float32)

    def reset(self, mask: np.ndarray | None = None) -> None:
        """Nothing to reset: steps are independent."""

    def state_dict(self) -> dict[str, Any]:
        return {"rng": self.rng.bit_generator.state}

    def load_state_dict(self, state: dict[str, Any]) -> None:
        self.rng.bit_generator.state = state["rng"]


def make_exploration(cfg: ExplorationConfig, num_envs: int, act_dim: int, rng: np.random.Generator) -> Exploration:
    """The exploration process ``cfg.kind`` names, for ``num_envs`` sub-envs."""
    if cfg.ou_sigma_per_dim is not None and len(cfg.ou_sigma_per_dim) != act_dim:
        raise ValueError(f"ou_sigma_per_dim has {len(cfg.ou_sigma_per_dim)} values, the action has {act_dim}")
    if cfg.kind == "ou":
        sigma = cfg.ou_sigma if cfg.ou_sigma_per_dim is None else cfg.ou_sigma_per_dim
        return OUNoise(num_envs, act_dim, cfg.ou_theta, cfg.ou_mu, sigma, cfg.ou_dt, rng)
    if cfg.kind == "gaussian":
        return GaussianNoise(num_envs, act_dim, cfg.gaussian_sigma, rng)
    raise ValueError(f"unknown exploration.kind {cfg.kind!r}; expected 'ou' or 'gaussian'")
