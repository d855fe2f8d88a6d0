"""Normalised actions -> SI robot commands: the one place where actions are scaled.

Action per agent: ``Box(-1, 1, (5,), float32)``

====  ==========  ===========================================================
idx   name        meaning
====  ==========  ===========================================================
0     vx          body-frame forward velocity, fraction of ``max_speed`` (m/s)
1     vy          body-frame leftward velocity, fraction of ``max_speed`` (m/s)
2     omega       angular velocity, fraction of ``max_omega`` (rad/s, CCW +)
3     dribble     dribbler on when > 0
4     kick        kick strength k = value when > 0 (ball speed k * kick_speed_max)
====  ==========  ===========================================================

The resulting velocity is capped at ``max_speed`` in norm by the physics.
"""

from __future__ import annotations

import numpy as np

from ..physics.params import RobotParams

ACTION_DIM = 5


def make_action(vx: float = 0.0, vy: float = 0.0, omega: float = 0.0, dribble: bool = False,
                kick: float = 0.0) -> np.ndarray:
    """Build a normalised (5,) action, clipping each entry to [-1, 1]."""
    a = np.array([vx, vy, omega, 1.0 if dribble else -1.0, kick if kick > 0 else -1.0], dtype=np.float32)
    return np.clip(a, -1.0, 1.0)


def validate_actions(actions: np.ndarray, names: list[str]) -> None:
    """Raise ValueError naming the agent whose action row is not finite."""
    bad = ~np.isfinite(actions).all(axis=1)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise ValueError(f"action for agent {names[i]!r} contains NaN or inf: {actions[i].tolist()}")


def scale_actions(actions: np.ndarray, robot: RobotParams) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(n, 5) normalised actions -> (v_body (n, 2) m/s, omega (n,) rad/s, dribble (n,) bool, kick (n,) in [0, 1]).

    Values are clipped to [-1, 1] first (finite values only: validate before).
    """
    a = np.clip(actions, -1.0, 1.0)
    return (a[:, 0:2] * robot.max_speed, a[:, 2] * robot.max_omega, a[:, 3] > 0.0, np.maximum(a[:, 4], 0.0))
