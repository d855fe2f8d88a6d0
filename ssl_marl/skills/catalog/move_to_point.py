"""move-to-point: go to a point (team frame) facing a heading, around robots and out of
forbidden defense areas (:class:`~ssl_marl.skills.navigation.MoveToPoint`); hand-coded only, no task."""

from __future__ import annotations

from ..navigation import MoveToPoint
from ..registry import SkillDef, register

SKILL = register(SkillDef(name="move_to_point", summary="go to a point facing a given heading",
                          baseline=MoveToPoint))
