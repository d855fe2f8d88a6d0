"""Skills: the paper's features and tasks, hand-coded baselines, learned skills.

``make_skill(name, kind, field, robot, ball)`` builds any skill behind the one
:class:`~ssl_marl.skills.base.Skill` protocol, so tactics can swap them by config.
"""

from __future__ import annotations

from pathlib import Path

from ..physics.field import FieldGeometry
from ..physics.params import BallParams, RobotParams
from .base import Skill, SkillStatus, make_action

SKILL_NAMES = ("go_to_ball", "aim_to_shoot", "drive_forward", "move_to_point", "pass", "receive")
SKILL_KINDS = ("baseline", "learned")


def make_skill(name: str, kind: str, field: FieldGeometry, robot: RobotParams | None = None,
               ball: BallParams | None = None, checkpoint: str | Path | None = None, **kwargs) -> Skill:
    """Build skill ``name`` of ``kind`` ("baseline" or "learned"; ``checkpoint`` overrides
    the shipped actor of a learned skill). drive_forward and move_to_point are always
    hand-coded."""
    from . import baseline

    if kind not in SKILL_KINDS:
        raise ValueError(f"unknown skill kind {kind!r}; expected one of {SKILL_KINDS}")
    if name not in SKILL_NAMES:
        raise ValueError(f"unknown skill {name!r}; expected one of {SKILL_NAMES}")
    if name == "drive_forward":
        return baseline.DriveForward(field, robot, ball, **kwargs)
    if name == "move_to_point":
        return baseline.MoveToPoint(field, robot, ball, **kwargs)
    if name in ("pass", "receive"):  # issue 11: the passing skills (ssl_marl.skills.passing)
        from . import passing

        if kind == "baseline" and checkpoint is None:
            cls = passing.PassBaseline if name == "pass" else passing.ReceiveBaseline
            return cls(field, robot, ball, **kwargs)
        cls = passing.LearnedPass if name == "pass" else passing.LearnedReceive
        return cls(field, robot, ball, checkpoint=checkpoint, **kwargs)
    if kind == "baseline" and checkpoint is None:
        cls = baseline.GoToBallBaseline if name == "go_to_ball" else baseline.AimToShootBaseline
        return cls(field, robot, ball, **kwargs)
    from . import learned

    cls = learned.LearnedGoToBall if name == "go_to_ball" else learned.LearnedAimToShoot
    return cls(field, robot, ball, checkpoint=checkpoint, **kwargs)


__all__ = ["Skill", "SkillStatus", "make_action", "make_skill", "SKILL_NAMES", "SKILL_KINDS"]
