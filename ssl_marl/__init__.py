"""ssl_marl: RoboCup Small Size League full-field simulator (Box2D, PettingZoo),
the paper's skills as Gymnasium tasks, learned and hand-coded skills, and STP.

Importing the package registers ``ssl_marl/GoToBall-v0``, ``ssl_marl/AimToShoot-v0``,
``ssl_marl/Pass-v0`` and ``ssl_marl/Receive-v0`` with Gymnasium.
"""

from __future__ import annotations

import gymnasium

__version__ = "0.1.0"


def _register() -> None:
    ids = {"ssl_marl/GoToBall-v0": "ssl_marl.skills.wrappers:GoToBallEnv",
           "ssl_marl/AimToShoot-v0": "ssl_marl.skills.wrappers:AimToShootEnv",
           "ssl_marl/Pass-v0": "ssl_marl.skills.pass_tasks:PassEnv",
           "ssl_marl/Receive-v0": "ssl_marl.skills.pass_tasks:ReceiveEnv"}
    for env_id, entry in ids.items():
        if env_id not in gymnasium.registry:
            gymnasium.register(id=env_id, entry_point=entry, disable_env_checker=True)


_register()
