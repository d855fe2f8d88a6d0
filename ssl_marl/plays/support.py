"""Support tactic: take open space ahead of the ball in the opponent half.

Team frame (own goal at -x), metres. Each tick the tactic scores a grid of candidate
spots (:func:`open_space_scores`, pure and vectorised) and keeps its current spot
unless another one is better by ``switch_margin`` (hysteresis, so it does not
dither between near-equal spots). It then drives there (navigation around robots,
out of both defense areas), facing the ball.

Score terms (unitless, higher is better):
* ``-2 * sum_o exp(-|c - o|^2 / (2 * 0.6^2))``: away from opponents;
* ``-1.5 * max_o clip(1 - d(o, ball->c) / 0.4, 0, 1)``: a free pass lane from the ball;
* ``+1.5 * view``: the angle (rad) the opponent goal mouth subtends from the spot;
* ``-0.4 * |x_c - x_pref|``: ``ahead`` metres in front of the ball (clipped to the x range);
* ``-2 * clip(1 - |c - ball| / min_ball_dist, 0, 1)``: not on top of the ball;
* ``-1.5 * sum_m exp(-|c - m|^2 / (2 * 0.5^2))``: away from teammates;
* ``+pass_lane_weight * P(ball -> c)`` (default weight 0: off): how safely the ball can
  be passed to the spot, the pass-success estimate of
  :func:`~ssl_marl.plays.pass_decision.pass_success` (the smallest interception-time
  margin of any opponent along the ball's path, from the ball model). The passing plays
  turn it on, so supports look for pass lanes, not only space. With it on, spots are
  re-scored every ``rescore_every`` ticks (it costs ~1 ms per scoring).
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

import numpy as np

from ..physics.field import FieldGeometry
from ..physics.state import WorldState
from ..skills.navigation import NavigateToPoint, NavParams, facing_towards
from .pass_decision import DecisionParams, pass_success
from .tactic_base import Tactic


def _seg_dist(points: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distances (k, m) from points (m, 2) to the k segments a -> b[k] (a: (2,), b: (k, 2))."""
    ab = b - a  # (k, 2)
    ap = points[None, :, :] - a  # (1, m, 2)
    denom = np.maximum((ab * ab).sum(-1), 1e-12)[:, None]
    t = np.clip((ap * ab[:, None, :]).sum(-1) / denom, 0.0, 1.0)  # (k, m)
    closest = a + t[..., None] * ab[:, None, :]
    d = points[None, :, :] - closest
    return np.hypot(d[..., 0], d[..., 1])


def open_space_scores(cands: np.ndarray, ball: np.ndarray, opponents: np.ndarray, teammates: np.ndarray,
                      field: FieldGeometry, ahead: float = 1.0, min_ball_dist: float = 1.0,
                      x_range: tuple[float, float] | None = None) -> np.ndarray:
    """Score candidate spots (k, 2) (see the module docstring); returns (k,)."""
    c = np.asarray(cands, float)
    ball = np.asarray(ball, float)
    score = np.zeros(len(c))
    if opponents.size:
        d2 = ((c[:, None, :] - opponents[None, :, :]) ** 2).sum(-1)
        score -= 2.0 * np.exp(-d2 / (2 * 0.6 ** 2)).sum(1)
        score -= 1.5 * np.clip(1.0 - _seg_dist(opponents, ball, c) / 0.4, 0.0, 1.0).max(1)
    left, right = field.goal_posts(+1)
    a1 = np.arctan2(left[1] - c[:, 1], left[0] - c[:, 0])
    a2 = np.arctan2(right[1] - c[:, 1], right[0] - c[:, 0])
    score += 1.5 * np.abs(np.angle(np.exp(1j * (a1 - a2))))
    lo, hi = x_range if x_range is not None else (-field.half_length, field.half_length)
    x_pref = float(np.clip(ball[0] + ahead, lo, hi))
    score -= 0.4 * np.abs(c[:, 0] - x_pref)
    db = np.hypot(c[:, 0] - ball[0], c[:, 1] - ball[1])
    score -= 2.0 * np.clip(1.0 - db / max(min_ball_dist, 1e-9), 0.0, 1.0)
    if teammates.size:
        d2 = ((c[:, None, :] - teammates[None, :, :]) ** 2).sum(-1)
        score -= 1.5 * np.exp(-d2 / (2 * 0.5 ** 2)).sum(1)
    return score


class SupportState(enum.Enum):
    SEEK = "seek"
    HOLD = "hold"


@dataclass(frozen=True)
class SupportParams:
    """Attributes:
        y_range: (y_min, y_max) band of the field this support covers (m), or None
            for the whole width; plays split the width between several supports.
        x_range: (x_min, x_max) (m), or None for the opponent half from ``x_min_m``
            up to ``defense_gap_m`` before the opponent defense area.
        x_min_m, defense_gap_m: the default x range's ends (m); hand-tuned: 0.3 m past
            the halfway line (out of the centre circle's restart area), 0.35 m short
            of the opponent defense area (room for a robot outside it).
        side_margin_m: candidate spots stay this far inside the touch lines (m);
            hand-tuned (a robot radius plus room to receive).
        tolerance_m: navigation position tolerance (m); hand-tuned.
        ahead: preferred distance in front of the ball along +x (m).
        min_ball_dist: keep at least about this far from the ball (m).
        switch_margin: a new spot must score this much better to be taken.
        grid: (nx, ny) candidate grid size.
        arrive_tol: SEEK -> HOLD within this distance of the spot (m).
        pass_lane_weight: weight of the pass-success term (0 = off; module docstring).
        rescore_every: with the pass-lane term on, re-score spots every this many ticks.
    """

    y_range: tuple[float, float] | None = None
    x_range: tuple[float, float] | None = None
    ahead: float = 1.0
    min_ball_dist: float = 1.0
    switch_margin: float = 0.15
    grid: tuple[int, int] = (7, 7)
    arrive_tol: float = 0.1
    x_min_m: float = 0.3
    defense_gap_m: float = 0.35
    side_margin_m: float = 0.3
    tolerance_m: float = 0.05
    pass_lane_weight: float = 0.0
    rescore_every: int = 6


@dataclass(frozen=True)
class SupportInputs:
    """Attributes: dist_to_target (m), target_changed (a new spot was chosen this tick)."""

    dist_to_target: float
    target_changed: bool


class Support(Tactic):
    """Takes open space ahead of the ball in the opponent half, away from opponents."""

    name = "support"
    State = SupportState
    Params = SupportParams
    Inputs = SupportInputs
    initial_state = SupportState.SEEK

    def __init__(self, field, robot=None, ball=None, skills="baseline", dt: float = 1.0 / 60.0, **params) -> None:
        super().__init__(field, robot, ball, skills, dt, **params)
        self.nav = NavigateToPoint(field, self.rp, self.bp, NavParams(), tolerance=self.params.tolerance_m)
        self.target: np.ndarray | None = None
        self._ticks_since_score = 0

    def reset(self) -> None:
        super().reset()
        self.target = None
        self._ticks_since_score = 0

    def candidates(self) -> tuple[np.ndarray, tuple[float, float]]:
        """Candidate grid (k, 2) and the x range used (cached per parameter set)."""
        key = (self.params.x_range, self.params.y_range, self.params.grid)
        cached = getattr(self, "_grid_cache", None)
        if cached is None or cached[0] != key:
            self._grid_cache = (key, *self._candidates())
        return self._grid_cache[1], self._grid_cache[2]

    def _candidates(self) -> tuple[np.ndarray, tuple[float, float]]:
        f, p = self.field, self.params
        x_range = p.x_range or (p.x_min_m, f.half_length - f.defense_depth - p.defense_gap_m)
        y_lo, y_hi = p.y_range or (-f.half_width, f.half_width)
        y_lo, y_hi = max(y_lo, -f.half_width + p.side_margin_m), min(y_hi, f.half_width - p.side_margin_m)
        if y_lo > y_hi:
            y_lo = y_hi = 0.5 * (y_lo + y_hi)
        xs = np.linspace(x_range[0], x_range[1], p.grid[0])
        ys = np.linspace(y_lo, y_hi, p.grid[1])
        gx, gy = np.meshgrid(xs, ys, indexing="ij")
        return np.column_stack([gx.ravel(), gy.ravel()]), x_range

    def choose_spot(self, world: WorldState, robot: int) -> tuple[np.ndarray, bool]:
        """Best spot with hysteresis against the current one; (spot, changed)."""
        ts = world.team(world.frame)
        mates = np.delete(ts.pos, robot, axis=0)
        p = self.params
        if p.pass_lane_weight > 0 and self.target is not None:
            self._ticks_since_score += 1
            if self._ticks_since_score < p.rescore_every:
                return self.target, False
        self._ticks_since_score = 0
        cands, x_range = self.candidates()
        if self.target is not None:
            cands = np.vstack([cands, self.target[None, :]])
        opp = world.opponents(world.frame).pos
        s = open_space_scores(cands, world.ball_pos, opp, mates, self.field,
                              self.params.ahead, self.params.min_ball_dist, x_range)
        if p.pass_lane_weight > 0:
            s = s + p.pass_lane_weight * pass_success(world.ball_pos, cands, opp, self.rp, self.bp, DecisionParams())
        best = int(np.argmax(s))
        if self.target is None:
            return cands[best].copy(), True
        if s[best] > s[-1] + self.params.switch_margin:
            return cands[best].copy(), True
        return self.target, False

    def observe(self, world: WorldState, robot: int) -> SupportInputs:
        spot, changed = self.choose_spot(world, robot)
        self.target = spot
        pos = world.team(world.frame).pos[robot]
        return SupportInputs(dist_to_target=float(np.hypot(*(spot - pos))), target_changed=changed)

    @staticmethod
    def transition(state: SupportState, inputs: SupportInputs, params: SupportParams) -> SupportState:
        S = SupportState
        if state is S.SEEK:
            return S.HOLD if inputs.dist_to_target <= params.arrive_tol and not inputs.target_changed else S.SEEK
        if inputs.target_changed or inputs.dist_to_target > 2.0 * params.arrive_tol:
            return S.SEEK
        return S.HOLD

    def execute(self, world: WorldState, robot: int, inputs: SupportInputs) -> np.ndarray:
        pos = world.team(world.frame).pos[robot]
        self.nav.target = self.target
        self.nav.facing = facing_towards(pos, world.ball_pos)
        return self.nav.act(world, robot)
