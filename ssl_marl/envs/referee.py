"""Referee rules as pure functions of a field-frame snapshot.

* Goal: the ball has *fully* crossed the goal line between the posts
  (|x| >= L/2 + r and |y| <= goal_width/2). The ball can only be there inside
  the goal, since the goal walls close it. It counts only if the ball was never
  higher than :data:`GOAL_MAX_HEIGHT_M` since a robot last touched it (SSL rules,
  "Scoring": 150 mm; ``WorldState.ball_max_height``); a higher ball left the field
  over the goal line: the ball-out restart. A ball that never leaves the ground
  (no chip kicks) always scores.
* Ball out: the ball has fully crossed a touch line (|y| >= W/2 + r) or a goal line
  outside the goal. The restart places the ball 0.2 m inside the field at the
  crossing point (out of the defense area), stopped, and moves robots that stand
  within 0.5 m of it outwards to 0.5 m (SSL: robots keep 0.5 m at restarts).
* No progress (SSL rules, Force Start: the referee restarts play after "a clear lack
  of progress for at least 10 seconds"): the ball has stayed within
  ``NO_PROGRESS_RADIUS_M`` of one spot for ``no_progress_s`` (MatchRules); the restart
  is the ball-out one at the ball's own position (:func:`placement_point`,
  :func:`clear_robots_from`), so two robots pinning the ball between them are parted.
* After a goal: kickoff formation (both teams in their own halves, ball at the
  centre mark) or termination, per ``MatchRules.after_goal``.

SSL's referee commands (STOP, kickoff, free kicks to the team that did not touch the
ball last), its fouls and the seeded placement of restarts are
:mod:`ssl_marl.envs.game_control`, switched on by :class:`~ssl_marl.envs.config.MatchRules`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..physics.field import FieldGeometry
from ..physics.params import RobotParams
from ..physics.state import WorldState

PLACEMENT_INSET = 0.2  # m inside the lines
RESTART_CLEARANCE = 0.5  # m between the placed ball and any robot centre
#: m: a ball that stays within this of one spot makes no progress (the SSL rules leave
#: "clear lack of progress" to the referee; two robots pinning the ball move it a few cm)
NO_PROGRESS_RADIUS_M = 0.25
#: m: a goal counts only if the ball stayed at most this high after the last touch (SSL rules)
GOAL_MAX_HEIGHT_M = 0.15


@dataclass(frozen=True)
class RefereeCall:
    """What the referee saw this step: ``goal_for`` is the scoring team or None;
    ``ball_out`` is True for out of play; ``placement`` the ball restart point."""

    goal_for: str | None = None
    ball_out: bool = False
    placement: np.ndarray | None = None


def judge(ws: WorldState, field: FieldGeometry, ball_radius: float) -> RefereeCall:
    side = field.in_goal(ws.ball_pos, ball_radius)
    if side and ws.ball_max_height <= GOAL_MAX_HEIGHT_M:
        return RefereeCall(goal_for="blue" if side > 0 else "yellow")
    x, y = float(ws.ball_pos[0]), float(ws.ball_pos[1])
    out_x = abs(x) >= field.half_length + ball_radius
    out_y = abs(y) >= field.half_width + ball_radius
    if not (out_x or out_y):
        return RefereeCall()
    return RefereeCall(ball_out=True, placement=placement_point(ws.ball_pos, field))


def placement_point(ball_pos: np.ndarray, field: FieldGeometry) -> np.ndarray:
    """Restart spot for a ball that left the field at ball_pos (0.2 m inside the lines,
    outside both defense areas)."""
    p = field.clamp_to_field(ball_pos, margin=PLACEMENT_INSET)
    for side in (1, -1):
        if field.in_defense_area(p, side, margin=PLACEMENT_INSET):
            p[0] = side * (field.half_length - field.defense_depth - PLACEMENT_INSET)
    return p


#: m: an SSL free kick is placed at least this far outside both defense areas
#: (ssl-game-controller's ``placement-offset-defense-area``, Divisions A and B)
FREE_KICK_DEFENSE_OFFSET_M = 1.0
#: m: an SSL goal kick is placed this far inside the goal line
#: (ssl-game-controller's ``placement-offset-goal-line-goal-kick``)
GOAL_KICK_OFFSET_M = 1.0


def free_kick_spot(ball_pos: np.ndarray, field: FieldGeometry, goal_line: int = 0,
                   goal_kick: bool = False) -> np.ndarray:
    """The spot of an SSL free kick for a ball at ``ball_pos`` (field frame, m), as the
    SSL game controller places it (docs/references.md, "SSL rules"):

    * a ball out over the goal line at x = ``goal_line`` * L/2 (+1 / -1; 0: not over a
      goal line): the corner spot on the ball's side, :data:`PLACEMENT_INSET` inside the
      touch line and :data:`PLACEMENT_INSET` inside the goal line (a corner kick for the
      attackers) or :data:`GOAL_KICK_OFFSET_M` inside it (``goal_kick``: the kick goes to
      the team defending that goal);
    * else the ball's spot, at least :data:`PLACEMENT_INSET` inside the lines;
    * then, inside a defense area grown by :data:`FREE_KICK_DEFENSE_OFFSET_M`, moved to
      the nearer of that grown area's front or side line.

    :func:`placement_point` is the simpler spot of matches without SSL restarts."""
    if goal_line not in (-1, 0, 1):
        raise ValueError(f"free_kick_spot: goal_line must be -1, 0 or +1, got {goal_line!r}")
    p = field.clamp_to_field(np.asarray(ball_pos, float), margin=PLACEMENT_INSET)
    if goal_line:
        inset = GOAL_KICK_OFFSET_M if goal_kick else PLACEMENT_INSET
        p = np.array([goal_line * (field.half_length - inset), math.copysign(field.half_width - PLACEMENT_INSET,
                                                                              float(p[1]))])
    max_x = field.half_length - field.defense_depth - FREE_KICK_DEFENSE_OFFSET_M
    min_y = field.defense_width / 2.0 + FREE_KICK_DEFENSE_OFFSET_M
    if abs(p[0]) > max_x and abs(p[1]) < min_y:
        if max_x - abs(p[0]) > abs(p[1]) - min_y:  # nearer the front line than the side line
            p[0] = math.copysign(max_x, float(p[0]))
        else:
            p[1] = math.copysign(min_y, float(p[1]))
    return p


#: m of free space kept between the bodies of two robots a restart places
PLACEMENT_GAP_M = 0.02
#: the angles (rad) a restart tries, in this order, to turn a robot's way out of the ball
#: until the spot is inside the walled area and clear of every other robot
_PLACEMENT_TURNS = (0.0, np.pi, np.pi / 2, -np.pi / 2) + tuple(s * k * 0.35 for k in range(1, 9) for s in (1, -1))
_PLACEMENT_RINGS_M = (0.0, 0.25, 0.5)  #: extra distance (m) beyond the clearance, tried after the turns


def placement_spot(point: np.ndarray, angle: float, radius: float, pos: np.ndarray, i: int,
                   field: FieldGeometry, robot_radius: float) -> np.ndarray:
    """Where a restart puts robot ``i`` that stands too near the ball at ``point`` (m, field
    frame): ``radius`` m from it in direction ``angle`` (rad), else the first of
    :data:`_PLACEMENT_TURNS` x :data:`_PLACEMENT_RINGS_M` that lies inside the walled area
    (0.1 m from the wall) and at least 2 ``robot_radius`` + :data:`PLACEMENT_GAP_M` from every
    other robot in ``pos`` ((n, 2), the placements so far), so that no two robots are put one
    on top of the other; if none is, the first spot inside the walled area."""
    others = np.delete(pos, i, axis=0)
    need = 2.0 * robot_radius + PLACEMENT_GAP_M
    first = None
    for ring in _PLACEMENT_RINGS_M:
        for turn in _PLACEMENT_TURNS:
            cand = point + (radius + ring) * np.array([np.cos(angle + turn), np.sin(angle + turn)])
            if not field.in_field(cand, margin=-field.boundary_width + 0.1):
                continue
            if first is None:
                first = cand
            if others.size == 0 or float(np.min(np.hypot(*(others - cand).T))) >= need:
                return cand
    return first if first is not None else point + radius * np.array([np.cos(angle), np.sin(angle)])


def clear_robots_from(point: np.ndarray, robot_pos: np.ndarray, field: FieldGeometry,
                      clearance: float = RESTART_CLEARANCE, robot_radius: float | None = None) -> np.ndarray:
    """Move robots closer than ``clearance`` to ``point`` radially out to ``clearance``
    (kept inside the walled area, clear of the other robots of radius ``robot_radius``, m,
    default :class:`~ssl_marl.physics.params.RobotParams`'s: :func:`placement_spot`).
    Returns new (n, 2) positions."""
    robot_radius = RobotParams().radius if robot_radius is None else robot_radius
    pos = np.array(robot_pos, dtype=float, copy=True)
    d = pos - point[None, :]
    dist = np.hypot(d[:, 0], d[:, 1])
    for i in np.flatnonzero(dist < clearance):
        u = d[i] / dist[i] if dist[i] > 1e-9 else np.array([-np.sign(point[0]) or -1.0, 0.0])
        pos[i] = placement_spot(point, float(np.arctan2(u[1], u[0])), clearance, pos, int(i), field, robot_radius)
    return pos


class NoProgressWatch:
    """The no-progress call for K worlds (module docstring): per world, the spot the ball
    was at when it last moved more than ``radius`` m away from the previous spot, and
    when. ``limit_s`` None switches the call off."""

    def __init__(self, n_worlds: int, limit_s: float | None, radius: float = NO_PROGRESS_RADIUS_M) -> None:
        self.limit_s, self.radius = limit_s, float(radius)
        self.anchor = np.zeros((n_worlds, 2))
        self.since = np.zeros(n_worlds)

    def restart(self, idx: np.ndarray, ball_pos: np.ndarray, t: np.ndarray) -> None:
        """Worlds ``idx`` start a new watch at ball positions (m, 2) and times (m,) s."""
        self.anchor[idx] = ball_pos
        self.since[idx] = t

    def update(self, idx: np.ndarray, ball_pos: np.ndarray, t: np.ndarray) -> np.ndarray:
        """(m,) True where world ``idx[j]``'s ball has stayed within ``radius`` for
        ``limit_s`` (the caller restarts play and then calls :meth:`restart`)."""
        if self.limit_s is None:
            return np.zeros(len(idx), bool)
        d = ball_pos - self.anchor[idx]
        moved = d[:, 0] ** 2 + d[:, 1] ** 2 > self.radius ** 2
        if moved.any():
            self.restart(idx[moved], ball_pos[moved], t[moved])
        return ~moved & (t - self.since[idx] >= self.limit_s - 1e-9)


def kickoff_formation(field: FieldGeometry, n: int) -> np.ndarray:
    """(n, 3) poses in the *team frame* (own half, x < 0), all facing +x: a keeper on
    its goal line, then rows of three field players at x = -0.8, -1.6, ... m
    (outside the centre circle and the defense area), centre first."""
    L2, W2 = field.half_length, field.half_width
    poses = [(-L2 + 0.25, 0.0, 0.0)]
    x_min = -L2 + field.defense_depth + 0.25
    ys = (0.0, W2 / 2, -W2 / 2)
    row = 0
    while len(poses) < n:
        x = max(-0.8 * (row + 1), x_min)
        y_shift = 0.0 if row % 2 == 0 else W2 / 4
        for y in ys:
            if len(poses) < n:
                poses.append((x, float(np.clip(y + y_shift, -W2 + 0.3, W2 - 0.3)), 0.0))
        row += 1
    return np.array(poses[:n], dtype=float).reshape(n, 3)


def kickoff_poses(field: FieldGeometry, n_blue: int, n_yellow: int) -> np.ndarray:
    """(n_blue + n_yellow, 3) kickoff poses in the *field* frame: blue in the -x half
    facing +x, yellow mirrored in the +x half facing -x (blue rows first)."""
    blue = kickoff_formation(field, n_blue)
    yellow = kickoff_formation(field, n_yellow)
    yellow[:, 0:2] *= -1.0
    yellow[:, 2] = np.pi
    return np.concatenate([blue, yellow]).reshape(n_blue + n_yellow, 3)


def match_start_options(env: Any, seed: int, jitter_m: float) -> dict | None:
    """A match's reset options: the kickoff formation (field frame) with each robot moved
    by a seeded normal jitter of ``jitter_m`` (m; clipped at 2x, kept in its own half)
    and turned by up to 0.2 rad; None for ``jitter_m`` 0."""
    if not jitter_m:
        return None
    rng = np.random.default_rng([int(seed), 0x5EED])
    cfg = env.config
    poses = kickoff_poses(env.field, cfg.n_blue, cfg.n_yellow)
    robots = {}
    for name, (x0, y0, h0) in zip(env.possible_agents, poses.tolist()):
        dxy = np.clip(rng.normal(0.0, jitter_m, 2), -2 * jitter_m, 2 * jitter_m)
        x, y = x0 + dxy[0], y0 + dxy[1]
        x = min(x, -0.05) if name.startswith("blue") else max(x, 0.05)  # stay in the own half
        h = h0 + float(np.clip(rng.normal(0.0, jitter_m), -0.2, 0.2))
        robots[name] = (float(x), float(y), h)
    return {"formation": "kickoff", "robots": robots}
