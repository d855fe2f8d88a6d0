"""Motion primitives shared by the hand-coded skills, navigation and tactics.

Frame: the team frame of the snapshot (own goal at -x); metres, seconds, radians.
Actions are the normalised (5,) env actions of :func:`ssl_marl.skills.base.make_action`.
"""

from __future__ import annotations

import math

import numpy as np

from ..physics.params import RobotParams
from ..physics.state import WorldState
from .base import make_action
from .features import rotate_to_robot


def robot_motion(world: WorldState, robot: int) -> tuple[np.ndarray, float, np.ndarray]:
    """(position (m), heading (rad), velocity (m/s)) of own robot ``robot`` in the
    snapshot's frame."""
    ts = world.team(world.frame)
    return ts.pos[robot], float(ts.heading[robot]), ts.vel[robot]


def velocity_command(world: WorldState, robot: int, v_field: np.ndarray, omega: float, rp: RobotParams,
                     dribble: bool = False, kick: float = 0.0) -> np.ndarray:
    """Normalised action for a desired team-frame velocity (m/s) and omega (rad/s)."""
    _, h, _ = robot_motion(world, robot)
    vb = rotate_to_robot(np.asarray(v_field, float), h) / rp.max_speed
    return make_action(vb[0], vb[1], omega / rp.max_omega, dribble=dribble, kick=kick)


def approach_speed(distance: float, rp: RobotParams, decel: float | None = None, v_end: float = 0.0) -> float:
    """Speed (m/s) from which the robot can still stop (down to ``v_end``, m/s) within
    ``distance`` (m), braking at ``decel`` (m/s^2; default 0.8 x ``rp.max_brake``)."""
    a = decel if decel is not None else 0.8 * rp.max_brake
    return min(rp.max_speed, math.sqrt(max(v_end * v_end + 2.0 * a * max(distance, 0.0), 0.0)))


__all__ = ["robot_motion", "velocity_command", "approach_speed"]
