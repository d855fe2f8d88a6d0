"""Wall: stand on the line from the opponents' set-piece ball to our goal, just outside
the distance the rules keep us from the ball, and block the direct shot.

A wall, as in human football: the kicking team may approach the ball, the defending team
keeps 0.5 m (SSL rules), so the robot stands where the direct shot has to pass. At
:data:`WALL_DISTANCE_M` from the ball a robot 0.18 m across shadows 0.34 rad of the goal
mouth seen from the ball: all of the Division B goal (1 m wide) from 3.5 m out, with the
goalie covering the rest nearer in. Team frame (own goal at -x), metres. :class:`Wall` is
:class:`~ssl_marl.plays.spot_support_tactic.GoToSpot` (SEEK, HOLD; round robots, out of
the own defense area, facing the ball) on the spot the play sets, braking at
:data:`WALL_DECEL` as it arrives.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..physics.field import FieldGeometry
from .spot_support_tactic import GoToSpot, GoToSpotParams

#: m from the ball to a wall robot's centre: the 0.6 m the team keeps at an opponent's
#: set piece (``plays.team.KEEP_CLEAR_M``) and a little more
WALL_DISTANCE_M = 0.65


#: m/s^2: a wall robot's braking towards its spot (below ``plays.team.keep_clear``'s 2 m/s^2)
WALL_DECEL = 1.6


def wall_spot(ball: np.ndarray, field: FieldGeometry, lane_offset: float = 0.0,
              distance: float = WALL_DISTANCE_M) -> np.ndarray:
    """The wall spot (team frame, m): ``distance`` from ``ball`` towards the centre of our
    goal (at -x), moved ``lane_offset`` m sideways (to the left of the ball-goal line,
    looking from the ball)."""
    ball = np.asarray(ball, float)
    d = field.goal_center(-1) - ball
    u = d / max(float(np.hypot(*d)), 1e-9)
    return ball + distance * u + lane_offset * np.array([-u[1], u[0]])


@dataclass(frozen=True)
class WallParams(GoToSpotParams):
    """:class:`~ssl_marl.plays.spot_support_tactic.GoToSpotParams` with the wall's
    defaults: the spot (the play sets it to :func:`wall_spot` every tick), arrive_tol
    0.1 m, tolerance_m 0.03 m and the approach braking at :data:`WALL_DECEL`."""

    arrive_tol: float = 0.1
    tolerance_m: float = 0.03
    arrive_decel: float | None = WALL_DECEL


class Wall(GoToSpot):
    """Block the direct shot of an opponent's set piece (module docstring)."""

    name = "wall"
    Params = WallParams


__all__ = ["WALL_DISTANCE_M", "WALL_DECEL", "wall_spot", "WallParams", "Wall"]
