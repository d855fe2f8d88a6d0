"""STP: tactics, role assignment, plays and the team controller.

Layers (the paper's vocabulary): skills (``ssl_marl.skills``) -> tactics (one robot's
state machine over skills, :mod:`.tactics`) -> plays (team coordination: which
tactics, and which robot gets which by cost, :mod:`.play`, :mod:`.assignment`) ->
:class:`TeamController`, built from a :class:`TeamSpec` (plays, skill set, carrier
decision) by :func:`build_team`. Matches and evaluations run them from
:mod:`ssl_marl.runners` (this package imports nothing from there).

Everything works in the team frame (own goal at -x), so one controller serves both
colours.
"""

from __future__ import annotations

from .assignment import Assignment, RoleSlot, assign
from .play import Play, PlayContext, PlaySelector, RoleDef, standard_plays
from .tactics import (TACTICS, Attacker, Defender, Goalie, GoToBallAndShoot, Mark, NavigateToPoint, NavParams,
                      Support, Tactic, TacticStatus)
from .team import TeamController, TeamSpec, build_team

__all__ = ["assign", "Assignment", "RoleSlot", "Play", "PlayContext", "PlaySelector", "RoleDef", "standard_plays",
           "Tactic", "TacticStatus", "GoToBallAndShoot", "Attacker", "Goalie", "Defender", "Support", "Mark",
           "NavigateToPoint", "NavParams", "TACTICS", "TeamController", "TeamSpec", "build_team"]
