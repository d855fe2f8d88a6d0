"""RLlib-free trainer for the ssl_marl skills (paper sections 4.1 and 5.1): DDPG, and TD3.

Modules: :mod:`train.config` (hyperparameters, one dataclass), :mod:`train.algos` (the
:class:`~train.algos.base.Agent` interface and its algorithms, ``ddpg`` and ``td3``),
:mod:`train.exploration` (OU and Gaussian action noise), :mod:`train.replay`,
:mod:`train.loop` (collection, demo burn-in, updates, evaluation), :mod:`train.logs`
(CSV and TensorBoard), :mod:`train.checkpoints` (resumable train state, actor metadata),
:mod:`train.export`, :mod:`train.select`, :mod:`train.evaluate`, :mod:`train.plots`,
:mod:`train.toy` (a tiny env for tests and smoke runs). CLI: ``python -m train --help``.

``train`` imports ``ssl_marl``, never the reverse; the exported ``actor.pt`` is
loaded by :func:`ssl_marl.skills.checkpoint.load_actor` without this package.
"""

from .config import DDPGConfig, TrainConfig, apply_overrides, default_config, load_config

__all__ = ["DDPGConfig", "TrainConfig", "apply_overrides", "default_config", "load_config"]
