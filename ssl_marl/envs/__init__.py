"""PettingZoo API of the full-field SSL simulator.

``parallel_env(**config)`` returns the :class:`~ssl_marl.envs.ssl_env.SSLParallelEnv`
(ParallelEnv); ``env(**config)`` its AEC form. Options: :func:`~ssl_marl.envs.config.make_config`.
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
