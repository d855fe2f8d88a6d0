"""PettingZoo API of the full-field SSL simulator.

``parallel_env(**config)`` returns the :class:`~ssl_marl.envs.ssl_env.SSLParallelEnv`
(ParallelEnv); ``env(**config)`` its AEC form. Options: :func:`~ssl_marl.envs.config.make_config`.

Versions: v0 (the default) has a (5,) action and a 168-entry observation.
``parallel_env(chip_kicks=True)`` (or ``env(chip_kicks=True)``) is v1, with the ball in
the air: a sixth action entry, the chip (kick elevation), and the ball's height and
vertical velocity appended to the observation (see
:class:`~ssl_marl.envs.config.EnvConfig`).
"""

from __future__ import annotations

from typing import Any

from pettingzoo.utils.conversions import parallel_to_aec

from .config import EnvConfig, MatchRules, RealismConfig, make_config
from .ssl_env import SSLParallelEnv


def parallel_env(**config: Any) -> SSLParallelEnv:
    """Full-field SSL env, PettingZoo Parallel API."""
    return SSLParallelEnv(**config)


def env(**config: Any):
    """Full-field SSL env, PettingZoo AEC API (``parallel_to_aec`` of :func:`parallel_env`)."""
    return parallel_to_aec(parallel_env(**config))


__all__ = ["parallel_env", "env", "EnvConfig", "MatchRules", "RealismConfig", "make_config", "SSLParallelEnv"]
