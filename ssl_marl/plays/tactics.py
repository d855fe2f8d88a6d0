"""Tactics: one robot's role as a state machine over skills (STP's middle layer).

Everything a play needs, in one import:

* :class:`Tactic` base, :class:`TacticStatus` (see :mod:`ssl_marl.plays.tactic_base`);
* :class:`GoToBallAndShoot` (the paper's Fig. 2) and :class:`Attacker`
  (:mod:`ssl_marl.plays.shoot`);
* :class:`Goalie`, :class:`Defender`, :class:`Mark` and their geometry
  (:mod:`ssl_marl.plays.defense`);
* :class:`Support` (:mod:`ssl_marl.plays.support`);
* navigation around robots and out of defense areas (:mod:`ssl_marl.skills.navigation`).

All tactics take ``(field, robot=None, ball=None, skills="baseline"|"learned"|{...},
dt=1/60, **params)`` and implement ``act(world_team_frame, robot) -> (5,) action``,
``set_params(**params)``, ``status`` and ``reset()``.
"""

from __future__ import annotations

from ..skills.navigation import NavigateToPoint, NavParams
from .clearing import BallClearing, clear_kick_action
from .defense import (Defender, DefenderParams, DefenderState, Goalie, GoalieParams, GoalieState, Mark, MarkParams,
                      MarkState, block_position, goalie_guard_position, mark_position)
from .shoot import Attacker, GoToBallAndShoot, ShootParams, ShootState
from .support import Support, SupportParams, SupportState, open_space_scores
from .tactic_base import NEAR_BALL_M, Tactic, TacticStatus

TACTICS = {"go_to_ball_and_shoot": GoToBallAndShoot, "attacker": Attacker, "goalie": Goalie,
           "defender": Defender, "support": Support, "mark": Mark}

__all__ = ["Tactic", "TacticStatus", "NEAR_BALL_M", "GoToBallAndShoot", "Attacker", "ShootState", "ShootParams",
           "Goalie", "GoalieState", "GoalieParams", "Defender", "DefenderState", "DefenderParams", "Mark",
           "MarkState", "MarkParams", "Support", "SupportState", "SupportParams", "NavigateToPoint", "NavParams",
           "goalie_guard_position", "block_position", "mark_position", "clear_kick_action", "BallClearing",
           "open_space_scores",
           "TACTICS"]
