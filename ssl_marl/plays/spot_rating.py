"""Support spots rated by pass safety x the spot's value, pure numpy functions.

Team frame (own goal at -x), metres, rad. A grid of candidate spots ahead of the ball
(:func:`candidate_grid`) is rated (:func:`rate_spots`):

    rating(c) = P(ball -> c) x value(c) x lane_penalty(c)
    value(c)  = w_shot * f_open(c) + w_redirect * f_redirect(c) * f_open(c) + w_goal * f_goal(c)

* ``P``: the pass-success estimate of a flat pass from the ball
  (:func:`~ssl_marl.plays.pass_decision.pass_success`: the smallest interception-time
  margin of any opponent along the ball's path; docs/references.md, "Passing and pass
  rating": TIGERs' interception and passability ratings);
* ``f_open``: the spot's own shot angle, the widest open goal interval seen from ``c``
  (opponents shadow it) scaled to [0, 1] at ``good_open_angle``;
* ``f_redirect``: the redirect rating of the deflection at ``c`` between the ball and
  the goal (1 up to 0.9 rad, 0 beyond 1.2 rad;
  :func:`~ssl_marl.plays.attack_decision.redirect_factor`);
* ``f_goal = clip(1 - |c - goal| / far_goal_m, 0, 1)``: near the goal is better;
* ``lane_penalty``: ``lane_block_factor`` where the pass lane ball -> ``c`` passes
  within ``lane_clear_m`` of a teammate that is not the supporter itself (it would
  block the lane), else 1.

With ``edge_spots`` > 0 the grid also holds spots on the opponent defence area's border
(``edge_margin_m`` outside it: ``edge_spots`` along its front line, two on each side line).
A supporter there cannot be marked from the goal side: a marker's goal-side spot lies inside
the defence area, which it may not enter, so the supporter's shot and redirect lines are open
but for the goalie (the defenders' wall stands on the ball's line to the goal).

:func:`assign_spots` picks spots for several supporters greedily: the best spot, then
the best of the rest with spots within ``min_separation_m`` of a chosen one removed and
the lanes that cross a chosen spot penalised; so two supporters never pick the same spot
nor stand in each other's lane. The plays re-rate every few ticks as the ball moves.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..physics.field import FieldGeometry
from ..physics.params import BallParams, RobotParams
from .attack_decision import redirect_factor
from .pass_decision import DecisionParams, open_goal_interval, pass_success


@dataclass(frozen=True)
class SpotParams:
    """Attributes:
        grid: candidate grid size (nx, ny).
        ahead_m: the grid starts this far behind the ball (m; supports also stand level).
        x_min_m: the grid never starts further back than this (m).
        side_margin_m, defense_gap_m: distance kept from the side lines / the opponent
            defense area (m).
        min_ball_dist_m: spots closer to the ball than this are left out (m).
        w_shot, w_redirect, w_goal: value weights; far_goal_m: f_goal's scale (m).
        good_open_angle: open angle (rad) at which f_open is 1.
        lane_clear_m: a teammate this close to the pass lane blocks it (m).
        lane_block_factor: rating factor of a blocked lane.
        min_separation_m: two supporters' spots are at least this far apart (m).
        min_rating: a fallback floor so spots with P = 0 still order by value.
        edge_spots: extra candidates along the front line of the opponent defence area (0:
            none; with any, also two on each of its side lines; module docstring).
        edge_margin_m: the edge spots' distance outside the defence area (m; robots keep
            ``NavParams.defense_margin``, 0.12 m, from it).
    """

    grid: tuple[int, int] = (7, 9)
    ahead_m: float = -0.5
    x_min_m: float = -1.5
    side_margin_m: float = 0.3
    defense_gap_m: float = 0.3
    min_ball_dist_m: float = 1.0
    w_shot: float = 0.5
    w_redirect: float = 0.3
    w_goal: float = 0.2
    far_goal_m: float = 6.0
    good_open_angle: float = 0.2
    lane_clear_m: float = 0.25
    lane_block_factor: float = 0.3
    min_separation_m: float = 1.2
    min_rating: float = 0.02
    edge_spots: int = 0
    edge_margin_m: float = 0.14

    def __post_init__(self) -> None:
        if self.edge_spots < 0 or self.edge_margin_m < 0:
            raise ValueError(f"SpotParams: edge_spots and edge_margin_m must be >= 0, got "
                             f"{self.edge_spots}, {self.edge_margin_m}")


def candidate_grid(field: FieldGeometry, ball: np.ndarray, params: SpotParams = SpotParams()) -> np.ndarray:
    """(G, 2) candidate spots ahead of the ball, inside the field, outside the opponent
    defense area and at least ``min_ball_dist_m`` from the ball."""
    ball = np.asarray(ball, float)
    x_hi = field.half_length - params.defense_gap_m
    x_lo = min(max(float(ball[0]) + params.ahead_m, params.x_min_m), x_hi - 1.0)
    xs = np.linspace(x_lo, x_hi, params.grid[0])
    ys = np.linspace(-field.half_width + params.side_margin_m, field.half_width - params.side_margin_m, params.grid[1])
    gx, gy = np.meshgrid(xs, ys, indexing="ij")
    c = np.column_stack([gx.ravel(), gy.ravel()])
    in_def = (c[:, 0] > field.half_length - field.defense_depth - params.defense_gap_m) & (
        np.abs(c[:, 1]) < 0.5 * field.defense_width + params.defense_gap_m)
    c = c[~in_def]
    if params.edge_spots:
        c = np.concatenate([c, defense_edge_spots(field, params)])
    far = np.hypot(c[:, 0] - ball[0], c[:, 1] - ball[1]) >= params.min_ball_dist_m
    return c[far]


def defense_edge_spots(field: FieldGeometry, params: SpotParams) -> np.ndarray:
    """(edge_spots + 4, 2) spots ``edge_margin_m`` outside the opponent defence area:
    ``edge_spots`` evenly along its front line (its corners included when more than one),
    two on each side line (a third and two thirds of the way to the goal line)."""
    m, n = params.edge_margin_m, params.edge_spots
    x_front = field.half_length - field.defense_depth - m
    hw = 0.5 * field.defense_width
    ys = np.linspace(-hw, hw, n) if n > 1 else np.zeros(1)
    front = np.column_stack([np.full(n, x_front), ys])
    xs = field.half_length - field.defense_depth * np.array([2.0 / 3.0, 1.0 / 3.0])
    sides = np.array([[x, s * (hw + m)] for s in (-1.0, 1.0) for x in xs])
    return np.concatenate([front, sides])


def lane_distances(ball: np.ndarray, spots: np.ndarray, robots: np.ndarray) -> np.ndarray:
    """(G, R) distance (m) of each robot (R, 2) from each lane ball -> spot (G, 2)."""
    a = np.asarray(ball, float)
    b = np.asarray(spots, float).reshape(-1, 2)
    r = np.asarray(robots, float).reshape(-1, 2)
    ab = b - a
    denom = np.maximum((ab * ab).sum(-1), 1e-12)[:, None]
    t = np.clip(((r[None, :, :] - a) * ab[:, None, :]).sum(-1) / denom, 0.0, 1.0)
    closest = a + t[..., None] * ab[:, None, :]
    return np.hypot(*(r[None, :, :] - closest).transpose(2, 0, 1))


def spot_values(spots: np.ndarray, ball: np.ndarray, opponents: np.ndarray, field: FieldGeometry,
                rp: RobotParams, bp: BallParams, params: SpotParams = SpotParams()) -> np.ndarray:
    """(G,) value of receiving at each spot (shot angle, redirect angle, goal distance)."""
    ball = np.asarray(ball, float)
    opp = np.asarray(opponents, float).reshape(-1, 2)
    out = np.empty(len(spots))
    goal = field.goal_center(+1)
    for i, c in enumerate(np.asarray(spots, float).reshape(-1, 2)):
        open_angle, aim = open_goal_interval(c, opp, field, rp, bp)
        f_open = min(open_angle / params.good_open_angle, 1.0)
        back = np.arctan2(ball[1] - c[1], ball[0] - c[0])
        f_red = redirect_factor(float(np.remainder(aim - back + np.pi, 2 * np.pi) - np.pi))
        f_goal = max(1.0 - float(np.hypot(*(c - goal))) / params.far_goal_m, 0.0)
        out[i] = params.w_shot * f_open + params.w_redirect * f_red * f_open + params.w_goal * f_goal
    return out


def rate_spots(spots: np.ndarray, ball: np.ndarray, opponents: np.ndarray, teammates: np.ndarray,
               field: FieldGeometry, rp: RobotParams, bp: BallParams, params: SpotParams = SpotParams(),
               decision: DecisionParams = DecisionParams()) -> np.ndarray:
    """(G,) rating of each spot (module docstring). ``teammates`` (k, 2): robots whose
    lanes must stay clear (the other supporters; not the ball carrier)."""
    spots = np.asarray(spots, float).reshape(-1, 2)
    p = pass_success(np.asarray(ball, float), spots, opponents, rp, bp, decision)
    rating = np.maximum(p, params.min_rating) * spot_values(spots, ball, opponents, field, rp, bp, params)
    mates = np.asarray(teammates, float).reshape(-1, 2)
    if mates.size:
        d = lane_distances(ball, spots, mates)
        at_spot = np.hypot(spots[:, None, 0] - mates[None, :, 0], spots[:, None, 1] - mates[None, :, 1]) < 0.3
        blocked = ((d < params.lane_clear_m) & ~at_spot).any(axis=1)
        rating = np.where(blocked, rating * params.lane_block_factor, rating)
    return rating


def assign_spots(n: int, spots: np.ndarray, ball: np.ndarray, opponents: np.ndarray, field: FieldGeometry,
                 rp: RobotParams, bp: BallParams, params: SpotParams = SpotParams(),
                 decision: DecisionParams = DecisionParams()) -> np.ndarray:
    """(n, 2) spots for ``n`` supporters, best first (greedy; module docstring)."""
    spots = np.asarray(spots, float).reshape(-1, 2)
    base = rate_spots(spots, ball, opponents, np.zeros((0, 2)), field, rp, bp, params, decision)
    chosen: list[np.ndarray] = []
    free = np.ones(len(spots), bool)
    for _ in range(n):
        if not free.any():
            chosen.append(chosen[-1] if chosen else np.asarray(ball, float))
            continue
        rating = base.copy()
        if chosen:
            d = lane_distances(ball, spots, np.array(chosen))
            rating = np.where((d < params.lane_clear_m).any(axis=1), rating * params.lane_block_factor, rating)
        rating = np.where(free, rating, -np.inf)
        best = int(np.argmax(rating))
        chosen.append(spots[best].copy())
        free &= np.hypot(spots[:, 0] - spots[best, 0], spots[:, 1] - spots[best, 1]) >= params.min_separation_m
    return np.array(chosen).reshape(n, 2)


__all__ = ["SpotParams", "candidate_grid", "defense_edge_spots", "lane_distances", "spot_values", "rate_spots",
           "assign_spots"]
