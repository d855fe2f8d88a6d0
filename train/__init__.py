"""RLlib-free trainers for ssl_marl, by algorithm family.

* :mod:`train.offpolicy` -- DDPG (the paper's, sections 4.1 and 5.1) and TD3 for the
  single-robot skills: config, agents, replay, n-step returns, exploration noise,
  demonstrations, the training loop, train states and actor export.
* :mod:`train.mappo` -- MAPPO for the multi-agent decision tasks: algorithm, loop,
  tasks, behaviour cloning, evaluation, actor selection and export, reports.
* :mod:`train.tools` -- run-folder tools: model selection, comparison, seed sweeps,
  results tables and learning-curve plots.
* :mod:`train.run_folder` and :mod:`train.logs` -- the output folder both loops share.

Command lines: ``python -m train SKILL ...`` and ``python -m train mappo ...``
(:mod:`train.__main__`), ``python -m train.select`` / ``compare`` / ``sweep`` / ``report`` /
``plots`` / ``export`` and ``python -m train.mappo_bc`` / ``mappo_eval`` / ``mappo_export`` /
``mappo_report`` (entry modules that call the tools' ``main``).

``train`` imports ``ssl_marl``, never the reverse (the one exception: ``ssl-marl train``
forwards to :func:`train.__main__.main`); the actor files it writes are loaded by
:mod:`ssl_marl.skills.checkpoint` without this package.
"""
