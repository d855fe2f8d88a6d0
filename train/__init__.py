"""RLlib-free trainer for the ssl_marl skills (paper sections 4.1 and 5.1): DDPG, and TD3.

Modules: :mod:`train.offpolicy.config` (hyperparameters, one dataclass), :mod:`train.offpolicy.algos` (the
:class:`~train.offpolicy.agent.Agent` interface and its algorithms, ``ddpg`` and ``td3``),
:mod:`train.offpolicy.exploration` (OU and Gaussian action noise), :mod:`train.offpolicy.replay`,
:mod:`train.offpolicy.loop` (collection, demo burn-in, updates, evaluation), :mod:`train.logs`
(CSV and TensorBoard), :mod:`train.offpolicy.checkpoints` (resumable train state, actor metadata),
:mod:`train.offpolicy.export`, :mod:`train.tools.select`, :mod:`train.offpolicy.evaluate`, :mod:`train.tools.plots`,
:mod:`train.offpolicy.toy` (a tiny env for tests and smoke runs). CLI: ``python -m train --help``.

``train`` imports ``ssl_marl``, never the reverse; the exported ``actor.pt`` is
loaded by :func:`ssl_marl.skills.checkpoint.load_actor` without this package.
"""

from train.offpolicy.config import DDPGConfig, TrainConfig, apply_overrides, default_config, load_config

__all__ = ["DDPGConfig", "TrainConfig", "apply_overrides", "default_config", "load_config"]
