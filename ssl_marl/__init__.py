"""ssl_marl: RoboCup Small Size League full-field simulator (Box2D, PettingZoo),
the paper's skills as Gymnasium tasks, learned and hand-coded skills, and STP.

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
