"""STP: tactics, role assignment, plays, the team controller, matches and evaluation.

Layers (the paper's vocabulary): skills (``ssl_marl.skills``) -> tactics (one robot's
state machine over skills, :mod:`.tactics`) -> plays (team coordination: which
tactics, and which robot gets which by cost, :mod:`.play`, :mod:`.assignment`) ->
:class:`TeamController` -> :func:`play_match` / :func:`evaluate_tactic`.

Everything works in the team frame (own goal at -x), so one controller serves both
colours. Heavier modules (match runner, evaluation) are imported lazily.
"""

from __future__ import annotations

from typing import Any

from .assignment import Assignment, RoleSlot, assign
from .play import Play, PlayContext, PlaySelector, RoleDef, standard_plays
from .tactics import (TACTICS, Attacker, Defender, Goalie, GoToBallAndShoot, Mark, NavigateToPoint, NavParams,
                      Support, Tactic, TacticStatus)
from .team import TeamController

_LAZY = {"play_match": "match", "play_series": "match", "MatchResult": "match", "summarize": "match",
         "evaluate_tactic": "evaluate", "run_episode": "evaluate", "wilson_interval": "evaluate"}


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        import importlib

        return getattr(importlib.import_module(f".{_LAZY[name]}", __name__), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = ["assign", "Assignment", "RoleSlot", "Play", "PlayContext", "PlaySelector", "RoleDef", "standard_plays",
           "Tactic", "TacticStatus", "GoToBallAndShoot", "Attacker", "Goalie", "Defender", "Support", "Mark",
           "NavigateToPoint", "NavParams", "TACTICS", "TeamController", *_LAZY]
