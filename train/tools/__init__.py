"""Tools over run folders: :mod:`~train.tools.select` (model selection on validation episodes),
:mod:`~train.tools.compare` (runs side by side), :mod:`~train.tools.sweep` (one config over
several seeds), :mod:`~train.tools.report` (results tables) and :mod:`~train.tools.plots`
(learning curves)."""
