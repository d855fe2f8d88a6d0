"""Physics layer: field geometry, robot/ball parameters, world-state snapshot and the Box2D world."""

from .field import FieldGeometry
from .params import BallParams, RobotParams
from .state import TeamState, WorldState, to_team_frame, wrap_angle
from .world import PhysicsWorld

__all__ = ["FieldGeometry", "BallParams", "RobotParams", "TeamState", "WorldState", "to_team_frame",
           "wrap_angle", "PhysicsWorld"]
