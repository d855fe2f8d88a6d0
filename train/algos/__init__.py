"""Learning algorithms behind the :class:`~train.algos.base.Agent` interface, by config name.

Adding one: write ``train/algos/NAME.py`` with a class implementing
:class:`~train.algos.base.Agent` (constructor ``(obs_dim, act_dim, cfg)``, any new
hyperparameters as ``NAME_*`` fields of :class:`train.config.TrainConfig`), and add one
line to :data:`ALGOS`. ``--set algo=NAME`` (or ``--algo NAME``) then trains with it.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from .base import Agent, LossMeter
from .ddpg import DDPG
from .mappo import MAPPO
from .td3 import TD3

if TYPE_CHECKING:
    from ..config import TrainConfig

#: on-policy multi-agent algorithms (own loop, :mod:`train.mappo_loop`; ``python -m train mappo``):
#: name -> class; they do not implement the replay-based :class:`Agent` interface
ON_POLICY_ALGOS: dict[str, type] = {
    "mappo": MAPPO,
}

#: config ``algo`` name -> agent class
ALGOS: dict[str, type] = {
    "ddpg": DDPG,
    "td3": TD3,
}


def make_agent(obs_dim: int, act_dim: int, cfg: TrainConfig) -> Agent:
    """The agent ``cfg.algo`` names, built for (obs_dim, act_dim)."""
    try:
        cls = ALGOS[cfg.algo]
    except KeyError:
        raise ValueError(f"unknown algo {cfg.algo!r}; expected one of {sorted(ALGOS)}") from None
    return cls(obs_dim, act_dim, cfg)


__all__ = ["ALGOS", "DDPG", "MAPPO", "ON_POLICY_ALGOS", "TD3", "Agent", "LossMeter", "make_agent"]
