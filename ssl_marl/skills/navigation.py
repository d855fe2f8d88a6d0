"""Navigation: move to a point without running into robots, and keep field players
out of their own defense area. :class:`NavigateToPoint` is the one move-to-point
behaviour: positioning tactics use it, and the registered ``move_to_point`` skill is
it with a heading check on success (:class:`MoveToPoint`).

Frame: the team frame (own goal at -x), metres, seconds, radians.

Method (documented choice: a *one-waypoint detour plus short-range repulsion*; no
global planner. Cheap (tens of microseconds), deterministic, and good enough for
positioning roles that re-plan every tick; the ball-handling skills do not use it):

1. **Target sanitising** (:func:`sanitize_target`): the target is clamped into the
   playing area and, for a field player, pushed out of its own defense area grown by
   ``defense_margin`` (robot radius + a little), and optionally out of the opponent's.
2. **Defense-area routing**: if the straight segment to the target crosses the grown
   own defense area, the robot first heads for the nearer of its two front corners.
3. **Detour** (:func:`detour_waypoint`): the first robot (either team) whose centre
   lies within ``clearance`` of the segment, ahead of us and before the target, is
   passed on the side nearer to our path: the waypoint sits beside it at
   ``clearance + detour_margin`` along the segment's normal.
4. **Speed profile**: a stopping-distance profile (``approach_speed`` with 0.6 x
   the braking limit) on the distance
   still to go to the *final* target (so a detour waypoint is passed at speed).
5. **Repulsion** (:func:`repulsion_velocity`): robots closer than
   ``repulsion_radius`` add a velocity away from them, growing linearly to
   ``repulsion_gain`` at contact, and the commanded velocity loses its component
   towards any robot nearer than ``clearance`` (a velocity-obstacle-lite brake).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..physics.field import FieldGeometry
from ..physics.params import BallParams, RobotParams
from ..physics.state import WorldState, wrap_angle
from .base import SkillBase, SkillStatus
from .motion import approach_speed, velocity_command


@dataclass(frozen=True)
class NavParams:
    """Navigation tuning (metres, m/s).

    Attributes:
        clearance: centre-to-centre distance to keep from other robots (2 x 0.09 m
            radius + 7 cm).
        detour_margin: extra sideways room at a detour waypoint.
        repulsion_radius: robots closer than this push us away.
        repulsion_gain: push speed at contact (m/s).
        defense_margin: robot centres stay this far outside the defense area.
        avoid_own_defense: keep out of the own defense area (False for the goalie).
        avoid_opp_defense: keep out of the opponent's defense area (SSL rule for
            positioning; the attacker's ball skills ignore it).
        run_off: targets may lie this far beyond the field lines, in the run-off area
            between the lines and the wall (m; 0: inside the lines). A set piece's kicker
            stands behind a ball placed 0.2 m inside them.
    """

    clearance: float = 0.25
    detour_margin: float = 0.08
    repulsion_radius: float = 0.35
    repulsion_gain: float = 1.0
    defense_margin: float = 0.12
    avoid_own_defense: bool = True
    avoid_opp_defense: bool = True
    run_off: float = 0.0


def defense_rect(field: FieldGeometry, side: int, margin: float) -> tuple[float, float, float, float]:
    """(x_min, x_max, y_min, y_max) of the defense area at x = side * L/2, grown by
    ``margin`` towards the field (and sideways); it extends behind the goal line so
    that nothing is routed around its back."""
    L2 = field.half_length
    hw = field.defense_width / 2.0 + margin
    inner = L2 - field.defense_depth - margin
    outer = L2 + field.boundary_width + 1.0
    if side < 0:
        return (-outer, -inner, -hw, hw)
    return (inner, outer, -hw, hw)


def _in_rect(p: np.ndarray, rect: tuple[float, float, float, float]) -> bool:
    x, y = p.tolist() if isinstance(p, np.ndarray) else p
    return rect[0] < x < rect[1] and rect[2] < y < rect[3]


def _push_out_xy(x: float, y: float, rect: tuple[float, float, float, float]) -> tuple[float, float]:
    """(x, y) moved to the nearest point on the boundary of ``rect`` if inside it."""
    x0, x1, y0, y1 = rect
    if not (x0 < x < x1 and y0 < y < y1):
        return x, y
    d = (x - x0, x1 - x, y - y0, y1 - y)
    k = d.index(min(d))
    if k == 0:
        return x0, y
    if k == 1:
        return x1, y
    return x, (y0 if k == 2 else y1)


def push_out_of_rect(p: np.ndarray, rect: tuple[float, float, float, float]) -> np.ndarray:
    """Nearest point on the boundary of ``rect`` if p is inside it, else p."""
    return np.array(_push_out_xy(float(p[0]), float(p[1]), rect))


def sanitize_target(target: np.ndarray, field: FieldGeometry, params: NavParams) -> np.ndarray:
    """Clamp ``target`` into the playing area (grown by ``params.run_off``) and out of the
    defense areas ``params`` forbids."""
    # the numbers of clamp_to_field / push_out_of_rect / clamp_to_field, on Python floats
    x, y = np.asarray(target, dtype=float).tolist()
    hx, hy = field.half_length + params.run_off, field.half_width + params.run_off
    x, y = min(max(x, -hx), hx), min(max(y, -hy), hy)
    for side, avoid in ((-1, params.avoid_own_defense), (1, params.avoid_opp_defense)):
        if avoid:
            x, y = _push_out_xy(x, y, defense_rect(field, side, params.defense_margin))
    return np.array([min(max(x, -hx), hx), min(max(y, -hy), hy)])


def _segment_hits_rect(a: np.ndarray, b: np.ndarray, rect: tuple[float, float, float, float]) -> bool:
    """True if segment a-b passes through the interior of rect (Liang-Barsky clip)."""
    ax, ay = a.tolist() if isinstance(a, np.ndarray) else a
    bx, by = b.tolist() if isinstance(b, np.ndarray) else b
    dx, dy = bx - ax, by - ay
    t0, t1 = 0.0, 1.0
    for p, q in ((-dx, ax - rect[0]), (dx, rect[1] - ax), (-dy, ay - rect[2]), (dy, rect[3] - ay)):
        if abs(p) < 1e-12:
            if q < 0:
                return False
            continue
        r = q / p
        if p < 0:
            t0 = max(t0, r)
        else:
            t1 = min(t1, r)
        if t0 > t1:
            return False
    return t1 - t0 > 1e-6


def defense_corner_waypoint(pos: np.ndarray, target: np.ndarray, field: FieldGeometry,
                            margin: float) -> np.ndarray | None:
    """If segment pos-target crosses the own (-x) defense area grown by ``margin``, the
    front corner (slightly further out) that gives the shorter path; else None."""
    rect = defense_rect(field, -1, margin)
    if _in_rect(pos, rect) or not _segment_hits_rect(pos, target, rect):
        return None
    out = 0.05
    corners = [np.array([rect[1] + out, rect[3] + out]), np.array([rect[1] + out, rect[2] - out])]
    lengths = [np.hypot(*(c - pos)) + np.hypot(*(target - c)) for c in corners]
    return corners[int(np.argmin(lengths))]


def line_frame(origin: np.ndarray, target: np.ndarray, points: np.ndarray
               ) -> tuple[np.ndarray, float, np.ndarray, np.ndarray] | None:
    """Coordinates of ``points`` ((k, 2) or (2,), m) along the line ``origin -> target``:
    (unit direction, line length (m), along-track distance from ``origin`` (m),
    left-positive cross-track offset (m)); None when the line is shorter than 1 um."""
    d = np.asarray(target, float) - np.asarray(origin, float)
    length = float(np.hypot(*d))
    if length < 1e-6:
        return None
    u = d / length
    rel = np.asarray(points, float) - origin
    return u, length, rel @ u, rel[..., 0] * (-u[1]) + rel[..., 1] * u[0]


def detour_waypoint(pos: np.ndarray, target: np.ndarray, obstacles: np.ndarray, clearance: float,
                    margin: float) -> np.ndarray | None:
    """Waypoint around the first obstacle blocking segment pos-target, or None.

    An obstacle blocks if its centre is within ``clearance`` of the segment, its
    projection lies ahead of ``pos`` and before the target, and it is not already
    touching us (then repulsion handles it). The waypoint lies beside the obstacle at
    ``clearance + margin`` on the side of the segment away from the obstacle centre.
    """
    if obstacles.size == 0:
        return None
    frame = line_frame(pos, target, obstacles)
    if frame is None:
        return None
    u, length, s, lat = frame
    blocking = (s > 0.0) & (s < length + clearance * 0.5) & (np.abs(lat) < clearance)
    if not blocking.any():
        return None
    k = int(np.flatnonzero(blocking)[np.argmin(s[blocking])])
    n = np.array([-u[1], u[0]])
    side = -1.0 if lat[k] > 0 else 1.0  # pass on the side away from its centre
    return obstacles[k] + side * n * (clearance + margin)


def repulsion_velocity(pos: np.ndarray, v_des: np.ndarray, obstacles: np.ndarray, params: NavParams) -> np.ndarray:
    """``v_des`` (m/s) with the component towards robots nearer than ``clearance``
    removed, plus a push away from robots nearer than ``repulsion_radius``."""
    v = np.asarray(v_des, float).copy()
    if obstacles.size == 0:
        return v
    rel = pos - obstacles
    dist = np.hypot(rel[:, 0], rel[:, 1])
    for i in np.flatnonzero(dist < params.repulsion_radius):
        away = rel[i] / max(dist[i], 1e-6)
        if dist[i] < params.clearance:
            towards = -float(v @ away)
            if towards > 0:
                v += towards * away
        v += away * params.repulsion_gain * (1.0 - dist[i] / params.repulsion_radius)
    return v


def other_robots(world: WorldState, robot: int) -> np.ndarray:
    """(k, 2) centres of every robot except ``robot`` of the frame's team."""
    own = world.team(world.frame).pos
    opp = world.opponents(world.frame).pos
    return np.concatenate([own[:robot], own[robot + 1:], opp], axis=0)


class NavigateToPoint(SkillBase):
    """Skill-protocol mover: go to ``target`` facing ``facing`` (rad, None = keep),
    around robots and out of forbidden defense areas (see the module docstring).

    Tactics set ``target`` / ``facing`` / ``params`` every tick. Succeeds when within
    ``tolerance`` (m) of the sanitised target and nearly stopped (and, with
    ``facing_tolerance`` set, within that many rad of ``facing``); ``waypoint`` holds
    the point it is heading for this tick (for plots and tests).
    """

    name = "navigate_to_point"

    def __init__(self, field: FieldGeometry, robot: RobotParams | None = None, ball: BallParams | None = None,
                 params: NavParams | None = None, tolerance: float = 0.03, turn_gain: float = 6.0,
                 max_speed: float | None = None, dribble: bool = False, target=(0.0, 0.0),
                 facing: float | None = None, facing_tolerance: float | None = None) -> None:
        super().__init__(field, robot, ball)
        self.params = params or NavParams()
        self.tolerance, self.turn_gain, self.max_speed, self.dribble = tolerance, turn_gain, max_speed, dribble
        self.facing_tolerance = facing_tolerance
        self.target = np.asarray(target, float)
        self.facing: float | None = facing
        self.waypoint = np.zeros(2)

    def act(self, world: WorldState, robot: int) -> np.ndarray:
        ts = world.team(world.frame)
        pos, h, vel = ts.pos[robot], float(ts.heading[robot]), ts.vel[robot]
        p, rp = self.params, self.rp
        goal = sanitize_target(self.target, self.field, p)
        obstacles = other_robots(world, robot)
        way = None
        if p.avoid_own_defense:
            way = defense_corner_waypoint(pos, goal, self.field, p.defense_margin)
        if way is None:
            way = detour_waypoint(pos, goal, obstacles, p.clearance, p.detour_margin)
        way = goal if way is None else way
        self.waypoint = way
        d_way = way - pos
        dist_way = math.hypot(d_way[0], d_way[1])
        remaining = dist_way + (math.hypot(goal[0] - way[0], goal[1] - way[1]) if way is not goal else 0.0)
        vmax = rp.max_speed if self.max_speed is None else min(self.max_speed, rp.max_speed)
        speed = min(approach_speed(remaining, rp, decel=0.6 * rp.max_brake), vmax)
        v = d_way * (speed / dist_way) if dist_way > 1e-3 else np.zeros(2)
        v = repulsion_velocity(pos, v, obstacles, p)
        sp = math.hypot(v[0], v[1])
        if sp > vmax:
            v *= vmax / sp
        face_err = 0.0 if self.facing is None else float(wrap_angle(self.facing - h))
        omega = min(max(self.turn_gain * face_err, -rp.max_omega), rp.max_omega)
        done = (math.hypot(goal[0] - pos[0], goal[1] - pos[1]) <= self.tolerance
                and math.hypot(vel[0], vel[1]) < 0.2
                and (self.facing_tolerance is None or abs(face_err) <= self.facing_tolerance))
        self.status = SkillStatus.SUCCEEDED if done else SkillStatus.RUNNING
        return velocity_command(world, robot, v, omega, rp, dribble=self.dribble)


class MoveToPoint(NavigateToPoint):
    """The registered ``move_to_point`` skill: :class:`NavigateToPoint` that also
    requires the heading to be within ``facing_tolerance`` (0.05 rad) of ``facing`` to
    succeed."""

    name = "move_to_point"

    def __init__(self, field: FieldGeometry, robot: RobotParams | None = None, ball: BallParams | None = None,
                 target=(0.0, 0.0), facing: float | None = None, tolerance: float = 0.03, turn_gain: float = 6.0,
                 max_speed: float | None = None, dribble: bool = False, params: NavParams | None = None,
                 facing_tolerance: float | None = 0.05) -> None:
        super().__init__(field, robot, ball, params, tolerance, turn_gain, max_speed, dribble, target, facing,
                         facing_tolerance)


def facing_towards(src: np.ndarray, dst: np.ndarray) -> float:
    """Heading (rad) that points from ``src`` to ``dst``."""
    return math.atan2(float(dst[1]) - float(src[1]), float(dst[0]) - float(src[0]))
