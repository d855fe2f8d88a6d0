"""SSL field geometry: one frozen dataclass, Division A/B presets, named queries.

Frame: the *field frame* has its origin at the centre mark, +x towards the
goal that the blue team attacks (yellow's goal is at +x, blue's own goal at -x),
+y to the left when looking along +x. All lengths in metres.

Sources: SSL rules, "Playing Environment" > "Field Setup" (playing area, goal, defense
area, boundary); docs/references.md, "SSL rules".
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np


@dataclass(frozen=True)
class FieldGeometry:
    """Geometry of an SSL field (metres).

    Attributes:
        name: preset name ("div_a", "div_b" or "custom").
        length: playing-area length, goal line to goal line (x extent).
        width: playing-area width, touch line to touch line (y extent).
        goal_width: inner width of the goal mouth.
        goal_depth: inner depth of the goal behind the goal line.
        goal_wall_thickness: thickness of goal side and back walls.
        defense_width: defense-area extent along y.
        defense_depth: defense-area extent along x (from the goal line).
        boundary_width: run-off area between field lines and the outer wall.
        center_circle_radius: radius of the centre circle.
        penalty_mark_distance: distance of the penalty mark from the goal centre.
        max_robots_per_team: rule limit for the division.
    """

    name: str
    length: float
    width: float
    goal_width: float
    goal_depth: float = 0.18
    goal_wall_thickness: float = 0.02
    defense_width: float = 2.0
    defense_depth: float = 1.0
    boundary_width: float = 0.3
    center_circle_radius: float = 0.5
    penalty_mark_distance: float = 6.0
    max_robots_per_team: int = 11

    def __post_init__(self) -> None:
        for fname in ("length", "width", "goal_width", "goal_depth", "goal_wall_thickness",
                      "defense_width", "defense_depth", "boundary_width", "center_circle_radius"):
            v = getattr(self, fname)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise ValueError(f"FieldGeometry.{fname} must be a positive finite number, got {v!r}")
        if self.goal_width >= self.width:
            raise ValueError("FieldGeometry.goal_width must be smaller than the field width")
        if self.defense_width >= self.width or self.defense_depth * 2 >= self.length:
            raise ValueError("FieldGeometry.defense_width/defense_depth do not fit inside the field")
        if self.goal_depth + self.goal_wall_thickness > self.boundary_width:
            raise ValueError("FieldGeometry.goal_depth must fit inside boundary_width (goal behind the goal line)")

    # ------------------------------------------------------------------ presets
    @staticmethod
    def div_a() -> "FieldGeometry":
        """Division A (rules 2025): 12 x 9 m, 1.8 m goal, 3.6 x 1.8 m defense area."""
        return FieldGeometry(name="div_a", length=12.0, width=9.0, goal_width=1.8,
                             defense_width=3.6, defense_depth=1.8, penalty_mark_distance=8.0,
                             max_robots_per_team=11)

    @staticmethod
    def div_b() -> "FieldGeometry":
        """Division B (rules 2025): 9 x 6 m, 1.0 m goal, 2.0 x 1.0 m defense area."""
        return FieldGeometry(name="div_b", length=9.0, width=6.0, goal_width=1.0,
                             defense_width=2.0, defense_depth=1.0, penalty_mark_distance=6.0,
                             max_robots_per_team=6)

    @staticmethod
    def from_name(name: "str | FieldGeometry") -> "FieldGeometry":
        """Return a preset by name, or pass a FieldGeometry through."""
        if isinstance(name, FieldGeometry):
            return name
        presets = {"div_a": FieldGeometry.div_a, "div_b": FieldGeometry.div_b}
        if name not in presets:
            raise ValueError(f"field: unknown field {name!r}; expected one of {sorted(presets)} "
                             "or a FieldGeometry")
        return presets[name]()

    # ------------------------------------------------------------ named queries
    @cached_property
    def half_length(self) -> float:
        return self.length / 2.0

    @cached_property
    def half_width(self) -> float:
        return self.width / 2.0

    @property
    def wall_half_length(self) -> float:
        """x of the outer boundary wall (inner face)."""
        return self.half_length + self.boundary_width

    @property
    def wall_half_width(self) -> float:
        """y of the outer boundary wall (inner face)."""
        return self.half_width + self.boundary_width

    def goal_center(self, side: int) -> np.ndarray:
        """Centre of the goal mouth on the goal line; side=+1 for +x goal, -1 for -x goal."""
        return np.array([side * self.half_length, 0.0])

    def goal_posts(self, side: int) -> tuple[np.ndarray, np.ndarray]:
        """(left, right) inner goal posts of the goal at x = side * L/2, as seen by a
        robot attacking that goal (left = +y for side=+1, -y for side=-1)."""
        x = side * self.half_length
        hw = self.goal_width / 2.0
        return np.array([x, side * hw]), np.array([x, -side * hw])

    def in_field(self, p: np.ndarray, margin: float = 0.0) -> bool | np.ndarray:
        """True where point(s) p (..., 2) lie inside the playing area shrunk by margin."""
        p = np.asarray(p)
        return (np.abs(p[..., 0]) <= self.half_length - margin) & (np.abs(p[..., 1]) <= self.half_width - margin)

    def in_defense_area(self, p: np.ndarray, side: int, margin: float = 0.0) -> bool | np.ndarray:
        """True where p lies inside the defense area of the goal at x = side * L/2 (grown by margin)."""
        p = np.asarray(p)
        x = side * p[..., 0]
        return ((x >= self.half_length - self.defense_depth - margin) & (x <= self.half_length + margin)
                & (np.abs(p[..., 1]) <= self.defense_width / 2.0 + margin))

    def in_goal(self, p: np.ndarray, radius: float = 0.0) -> int:
        """+1 / -1 if a disc of ``radius`` at p has fully crossed the goal line inside the
        +x / -x goal, else 0."""
        x, y = float(p[0]), float(p[1])
        if abs(y) <= self.goal_width / 2.0 and abs(x) >= self.half_length + radius:
            return 1 if x > 0 else -1
        return 0

    def clamp_to_field(self, p: np.ndarray, margin: float = 0.0) -> np.ndarray:
        """Project p (a point (2,) or points (..., 2), m) onto the playing area shrunk by margin."""
        a = np.asarray(p, dtype=float)
        hx, hy = self.half_length - margin, self.half_width - margin
        if a.shape == (2,):  # one point, the hot path: the same numbers as np.clip, without its overhead
            x, y = a.tolist()
            return np.array([min(max(x, -hx), hx), min(max(y, -hy), hy)])
        return np.clip(a, [-hx, -hy], [hx, hy])

    def random_free_point(self, rng: np.random.Generator, margin: float = 0.0, taken: list | tuple = (),
                          min_dist: float = 0.0, tries: int = 1000) -> np.ndarray:
        """Uniform point in the playing area shrunk by ``margin``, at least ``min_dist`` from
        every point in ``taken`` (rejection sampling; RuntimeError if none is found)."""
        lo = [-self.half_length + margin, -self.half_width + margin]
        hi = [self.half_length - margin, self.half_width - margin]
        for _ in range(tries):
            p = rng.uniform(lo, hi)
            if all(np.hypot(*(p - np.asarray(q))) >= min_dist for q in taken):
                return p
        raise RuntimeError(f"no free point on the {self.name} field {min_dist} m from {len(taken)} others")

    def edge_closest_points(self, p: np.ndarray) -> np.ndarray:
        """Closest points on the top (+y), bottom (-y), left (-x) and right (+x) field
        lines to point p, as a (4, 2) array in the field frame (the paper's go-to-ball
        features, before conversion to the robot frame)."""
        x = float(np.clip(p[0], -self.half_length, self.half_length))
        y = float(np.clip(p[1], -self.half_width, self.half_width))
        return np.array([[x, self.half_width], [x, -self.half_width],
                         [-self.half_length, y], [self.half_length, y]])
