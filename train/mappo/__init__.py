"""MAPPO for the multi-agent decision tasks (keepaway, attack-3v2, attack-drill, pass-and-score, toy tasks).

* :mod:`~train.mappo.algorithm` -- the networks, SMDP advantages and the PPO update, with
  :class:`~train.mappo.algorithm.MAPPOConfig` (the hyperparameters);
* :mod:`~train.mappo.loop` -- collection over :mod:`~train.mappo.vec`, validation snapshots,
  checkpoints, with :class:`~train.mappo.loop.MAPPORunConfig` (the run);
* :mod:`~train.mappo.tasks` and :mod:`~train.mappo.toy_marl` -- the tasks it trains on;
* :mod:`~train.mappo.cli` (``python -m train mappo``), :mod:`~train.mappo.bc` (behaviour
  cloning of a benchmark policy), :mod:`~train.mappo.eval`, :mod:`~train.mappo.export`
  (actor selection by validation score), :mod:`~train.mappo.report` (learning curves).
"""
