"""The off-policy algorithms behind the :class:`~train.offpolicy.agent.Agent` interface, by ``algo`` name.

Adding one: write ``train/offpolicy/NAME.py`` with a class implementing
:class:`~train.offpolicy.agent.Agent`, give its hyperparameters a section dataclass in
:mod:`train.offpolicy.config` (``SECTIONS``, and ``NAME`` in ``ALGO_NAMES``), and add one
line to :func:`make_agent`. ``--algo NAME`` (or ``--set algo=NAME``) then trains with it.
"""

from __future__ import annotations

from train.offpolicy.agent import Agent
from train.offpolicy.config import ALGO_NAMES, TrainConfig
from train.offpolicy.ddpg import DDPG
from train.offpolicy.td3 import TD3

#: ``algo`` name -> agent class
ALGOS: dict[str, type] = {"ddpg": DDPG, "td3": TD3}
assert tuple(ALGOS) == ALGO_NAMES, "train.offpolicy.config.ALGO_NAMES must list the agents of ALGOS"


def make_agent(obs_dim: int, act_dim: int, cfg: TrainConfig) -> Agent:
    """The agent ``cfg.algo`` names, built for (obs_dim, act_dim) from its config sections."""
    speed = {"autocast_bf16": cfg.autocast_bf16, "compile": cfg.compile}
    if cfg.algo == "ddpg":
        return DDPG(obs_dim, act_dim, cfg.ddpg, **speed)
    if cfg.algo == "td3":
        return TD3(obs_dim, act_dim, cfg.ddpg, cfg.td3, **speed)
    raise ValueError(f"unknown algo {cfg.algo!r}; expected one of {sorted(ALGOS)}")


__all__ = ["ALGOS", "DDPG", "TD3", "make_agent"]
