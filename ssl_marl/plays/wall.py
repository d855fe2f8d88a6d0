"""Wall: stand on the line from the opponents' set-piece ball to our goal, just outside
the distance the rules keep us from the ball, and block the direct shot.

A wall, as in human football: the kicking team may approach the ball, the defending team
keeps 0.5 m (SSL rules), so the robot stands where the direct shot has to pass. At
:data:`WALL_DISTANCE_M` from the ball a robot 0.18 m across shadows 0.34 rad of the goal
mouth seen from the ball: all of the Division B goal (1 m wide) from 3.5 m out, with the
goalie covering the rest nearer in. Team frame (own goal at -x), metres. States: SEEK
(more than ``arrive_tol`` m from the wall spot) and HOLD; the robot navigates there (round
robots, out of the own defense area) and faces the ball.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

import numpy as np

from ..physics.field import FieldGeometry
from ..physics.state import WorldState
from ..skills.navigation import NavigateToPoint, NavParams, facing_towards
from .tactic_base import Tactic

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


class WallState(enum.Enum):
    SEEK = "seek"
    HOLD = "hold"


@dataclass(frozen=True)
class WallParams:
    """Attributes: lane_offset (m sideways from the ball-goal line, set by the play for a
    wall of several robots), arrive_tol (m), tolerance_m (navigation, m)."""

    lane_offset: float = 0.0
    arrive_tol: float = 0.1
    tolerance_m: float = 0.03


@dataclass(frozen=True)
class WallInputs:
    """Attributes: dist_to_spot (m)."""

    dist_to_spot: float


class Wall(Tactic):
    """Block the direct shot of an opponent's set piece (module docstring)."""

    name = "wall"
    State = WallState
    Params = WallParams
    Inputs = WallInputs
    initial_state = WallState.SEEK

    def __init__(self, field, robot=None, ball=None, skills="baseline", dt: float = 1.0 / 60.0, **params) -> None:
        super().__init__(field, robot, ball, skills, dt, **params)
        self.nav = NavigateToPoint(field, self.rp, self.bp, NavParams(), tolerance=self.params.tolerance_m)

    def spot(self, world: WorldState) -> np.ndarray:
        """The wall spot for the world's ball (team frame, m)."""
        return wall_spot(world.ball_pos, self.field, self.params.lane_offset)

    def observe(self, world: WorldState, robot: int) -> WallInputs:
        pos = world.team(world.frame).pos[robot]
        return WallInputs(float(np.hypot(*(self.spot(world) - pos))))

    @staticmethod
    def transition(state: WallState, inputs: WallInputs, params: WallParams) -> WallState:
        if state is WallState.SEEK:
            return WallState.HOLD if inputs.dist_to_spot <= params.arrive_tol else WallState.SEEK
        return WallState.SEEK if inputs.dist_to_spot > 2.0 * params.arrive_tol else WallState.HOLD

    def execute(self, world: WorldState, robot: int, inputs: WallInputs) -> np.ndarray:
        pos = world.team(world.frame).pos[robot]
        self.nav.target = self.spot(world)
        self.nav.facing = facing_towards(pos, world.ball_pos)
        # arrive braking at WALL_DECEL: gentler than keep_clear's 2 m/s^2, so that it never has to
        # take over (it keeps a braking robot's sideways speed, and the robot would overshoot the spot)
        self.nav.max_speed = float(np.sqrt(0.04 + 2.0 * WALL_DECEL * inputs.dist_to_spot))
        return self.nav.act(world, robot)


__all__ = ["WALL_DISTANCE_M", "WALL_DECEL", "wall_spot", "WallState", "WallParams", "WallInputs", "Wall"]
