"""drive-forward: the paper's fixed skill (dribbler on, drive forward for 1 s); hand-coded only, no task."""

from __future__ import annotations

from ..baseline import DriveForward
from ..registry import SkillDef, register

SKILL = register(SkillDef(name="drive_forward", summary="dribbler on, drive forward for a fixed time",
                          baseline=DriveForward))
