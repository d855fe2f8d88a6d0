"""The skill protocol: one interface for hand-coded and learned skills.

A tactic drives a skill by calling :meth:`Skill.act` once per control tick with
the current world snapshot *in the robot's team frame* (``world.frame`` is the
team name; own goal at -x, opponent goal at +x) and the robot's index inside its
own team. The skill returns the robot's action in the env's normalised action
space and updates :attr:`Skill.status`. A tactic cannot tell a learned skill
from a hand-coded one.

Action layout (shared with the env, see :mod:`ssl_marl.envs.actions`):
``[vx, vy, omega, dribble, kick]`` in [-1, 1], body frame (+x forward, +y left),
velocities as fractions of the robot's limits, dribbler on when > 0, kick
strength = value when > 0.
"""

from __future__ import annotations

import enum
from typing import Protocol, runtime_checkable

import numpy as np

from ..physics.state import WorldState


class SkillStatus(enum.Enum):
    RUNNING = "running"
    SUCCEEDED = "succeeded"
    FAILED = "failed"


@runtime_checkable
class Skill(Protocol):
    """A low-level single-robot behaviour."""

    name: str
    status: SkillStatus

    def reset(self) -> None:
        """Start afresh (status RUNNING, internal timers cleared)."""

    def act(self, world: WorldState, robot: int) -> np.ndarray:
        """Return a (5,) float32 action for ``robot`` (index in team ``world.frame``)."""


def make_action(vx: float = 0.0, vy: float = 0.0, omega: float = 0.0, dribble: bool = False,
                kick: float = 0.0) -> np.ndarray:
    """Build a normalised (5,) action, clipping each entry to [-1, 1]."""
    a = np.array([vx, vy, omega, 1.0 if dribble else -1.0, kick if kick > 0 else -1.0], dtype=np.float32)
    return np.clip(a, -1.0, 1.0)
