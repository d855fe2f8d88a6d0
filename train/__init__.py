"""RLlib-free DDPG trainer for the ssl_marl skills (paper sections 4.1 and 5.1).

Modules: :mod:`train.config` (hyperparameters), :mod:`train.ddpg` (the update),
:mod:`train.replay`, :mod:`train.noise`, :mod:`train.loop` (collection, burn-in,
logs, checkpoints), :mod:`train.evaluate`, :mod:`train.plots`, :mod:`train.toy`
(a tiny env for tests and smoke runs). CLI: ``python -m train --help``.

``train`` imports ``ssl_marl``, never the reverse; the exported ``actor.pt`` is
loaded by :func:`ssl_marl.skills.checkpoint.load_actor` without this package.
"""

from .config import DDPGConfig, apply_overrides, default_config, load_config

__all__ = ["DDPGConfig", "apply_overrides", "default_config", "load_config"]
