"""Off-policy actor-critic training of the single-robot skills: DDPG and TD3.

* :mod:`~train.offpolicy.config` -- :class:`~train.offpolicy.config.TrainConfig`, its sections
  (``ddpg``, ``td3``, ``exploration``), JSON files and ``--set`` overrides;
* :mod:`~train.offpolicy.agent` -- the :class:`~train.offpolicy.agent.Agent` interface and
  shared update helpers; :mod:`~train.offpolicy.ddpg`, :mod:`~train.offpolicy.td3` -- the
  algorithms, each readable on one screen; :mod:`~train.offpolicy.algos` -- the registry;
* :mod:`~train.offpolicy.replay`, :mod:`~train.offpolicy.nstep`, :mod:`~train.offpolicy.exploration`,
  :mod:`~train.offpolicy.demos` -- experience: replay buffer, n-step returns, action noise,
  demonstration burn-in;
* :mod:`~train.offpolicy.loop` -- collection, updates, evaluation, checkpoints, export;
  :mod:`~train.offpolicy.checkpoints` -- the resumable train state;
* :mod:`~train.offpolicy.evaluate`, :mod:`~train.offpolicy.export`, :mod:`~train.offpolicy.cli`,
  :mod:`~train.offpolicy.toy` (a tiny env for tests and smoke runs).
"""
