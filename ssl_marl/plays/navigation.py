"""Navigation lives in :mod:`ssl_marl.skills.navigation` (one move-to-point behaviour
for tactics and skills); re-exported here for the tactics' imports."""

from ..skills.navigation import (MoveToPoint, NavigateToPoint, NavParams, defense_corner_waypoint, defense_rect,
                                 detour_waypoint, facing_towards, other_robots, push_out_of_rect, repulsion_velocity,
                                 sanitize_target)

__all__ = ["MoveToPoint", "NavigateToPoint", "NavParams", "defense_corner_waypoint", "defense_rect",
           "detour_waypoint", "facing_towards", "other_robots", "push_out_of_rect", "repulsion_velocity",
           "sanitize_target"]
