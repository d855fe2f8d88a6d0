"""Skills: the paper's features and tasks, hand-coded baselines, learned skills.

``make_skill(name, kind, field, robot, ball)`` builds any registered skill (see
:mod:`ssl_marl.skills.registry`) behind the one :class:`~ssl_marl.skills.base.Skill`
protocol, so tactics can swap them by config.
"""

from __future__ import annotations

from pathlib import Path

from ..physics.field import FieldGeometry
from ..physics.params import BallParams, RobotParams
from .base import Skill, SkillStatus, make_action
from .registry import SKILL_KINDS, get_skill, skill_names


def make_skill(name: str, kind: str, field: FieldGeometry, robot: RobotParams | None = None,
               ball: BallParams | None = None, checkpoint: str | Path | None = None, **kwargs) -> Skill:
    """Build registered skill ``name`` of ``kind`` ("baseline" or "learned"; ``checkpoint``
    overrides the shipped actor of a learned skill). Skills without a learned
    implementation (drive_forward, move_to_point) are always hand-coded."""
    if kind not in SKILL_KINDS:
        raise ValueError(f"unknown skill kind {kind!r}; expected one of {SKILL_KINDS}")
    return get_skill(name).build(kind, field, robot, ball, checkpoint=checkpoint, **kwargs)


__all__ = ["Skill", "SkillStatus", "make_action", "make_skill", "SKILL_KINDS", "get_skill", "skill_names"]
