"""ssl_marl: RoboCup Small Size League full-field simulator (Box2D, PettingZoo),
the skills of *Learning Skills for Small Size League RoboCup* (D. Schwab, Y. Zhu and
M. Veloso, RoboCup 2018; "the paper") as Gymnasium tasks, learned and hand-coded
skills, STP plays and learned team decisions. Sources: docs/references.md.

Importing the package registers the task of every registered skill with Gymnasium
(``ssl_marl/GoToBall-v0``, ``ssl_marl/AimToShoot-v0``; see :mod:`ssl_marl.skills.registry`).
"""

from __future__ import annotations

__version__ = "0.1.0"


def _register() -> None:
    from .skills.registry import register_gym, task_skills

    for skill in task_skills():
        register_gym(skill.task)


_register()
