"""Shoot, pass or keep: the ball carrier's decision as documented, pure value functions.

Team frame (own goal at -x, opponent goal at +x), metres, seconds, m/s. Everything
here is a pure function of positions (no world object, no state), so the decision can
be tested on hand-built scenes and reused by plays, supports and future learners.

**Interception time** (:func:`opponent_reach_time`): an opponent at ``o`` reaches a
point ``q`` after ``reaction_s + T(max(|q - o| - reach, 0))``, where ``T(d)`` is the
time to cover ``d`` from rest with acceleration ``a`` up to top speed ``v``
(``sqrt(2 d / a)`` while accelerating, then ``d / v + v / (2 a)``) and ``reach`` the
robot radius plus the ball radius. This is TIGERs' "reachable disc growing with time",
fast model (docs/references.md, "Passing and pass rating"), with a reaction time.

**Ball time** along a path: the two-phase slide/roll model of
:mod:`ssl_marl.physics.ball_model` (``times_to_distances``), the same model the
simulator integrates.

**Path margin** (:func:`path_margin`): sample the ball's straight path from the kick
point to its end point; at each sample ``q_i`` reached at ``t_i`` by the ball, each
opponent's margin is ``t_opp(q_i) - t_i``; the path margin is the smallest over samples
and opponents (s; negative = an opponent gets there first). Samples closer than
``skip_near_m`` to the kick point are left out (the kicker's own robot shields them).
With a receiver (a pass) and ``receiver_guard_m`` > 0, a sample within that distance of
the receiver counts as the receiver's once the receiver gets there first: its margin is
``t_opp(q_i) - min(t_i, t_recv(q_i))``, with ``t_recv`` the receiver's reach time (the
opponents' model without the reaction time: the receiver knows the pass). A marker
standing beside the receiver then no longer intercepts every pass to it (TIGERs' pass
rating compares the receiver's and the opponents' times to the ball; docs/references.md,
"Passing and pass rating").

**Shot value** (:func:`shot_value`, in [0, 1]): from a point ``p``, the goal mouth (posts
at ``x = L/2, y = +-goal_width/2``) minus the angular shadows of all robots other than
the shooter (discs of robot radius + ball radius) gives open intervals; the widest one
has width ``open_angle`` (rad) and centre ``aim``. Then, with a shot kicked at
``shot_speed`` at the aim point on the goal line,

    shot_value = f_angle * f_margin * f_dist
    f_angle  = clip((open_angle - min_open_angle) / (good_open_angle - min_open_angle), 0, 1)
    f_margin = clip((margin - shot_margin_lo) / (shot_margin_hi - shot_margin_lo), 0, 1)
    f_dist   = 1 for d <= near_shot_m, falling linearly to far_shot_floor at far_shot_m (clipped)

where ``margin`` is the path margin of the shot (the goalie's and defenders'
interception times) and ``d`` the distance to the goal centre.

**Pass value** (:func:`evaluate_passes`, per teammate ``k`` at its receive point ``q_k``):

    P_k        = clip((margin_k - pass_margin_lo) / (pass_margin_hi - pass_margin_lo), 0, 1)
    value_k    = P_k * (w_receiver_shot * shot_value(q_k) + w_progress * progress_k + w_possession)
    progress_k = clip((x_qk - x_p) / progress_scale_m, -1, 1)

``margin_k`` (less the time the carrier needs to turn towards ``q_k`` at ``turn_rate``
when its heading is known) is the path margin of a pass kicked so that it arrives at
``pass_arrive_speed`` (:func:`~ssl_marl.physics.ball_model.kick_speed_for_arrival`,
clipped to the kicker's cap), the smallest interception-time margin of any opponent
along the ball's path. ``w_possession`` is the value of simply keeping the ball in the
team (keepaway's reason to pass). Passes shorter than ``min_pass_m``, longer than
``max_pass_m``, or to a point outside the field or inside a defense area are not
candidates.

**Keep value**: ``w_keep * pressure``, ``pressure = clip((t_press - press_lo) /
(press_hi - press_lo), 0, 1)`` with ``t_press`` the nearest opponent's reach time to
the carrier: holding is worth little when an opponent is about to arrive.

**Decision** (:func:`decide`):

1. ``shot_value(p) >= shoot_threshold`` -> SHOOT;
2. else the best pass ``k`` with ``P_k >= min_pass_success`` and
   ``value_k >= max(shot_value(p), keep_value) + pass_gain`` -> PASS to ``k``;
3. else KEEP (dribble: hold the ball, turn and creep toward the goal) while the keep
   value is at least ``min_keep`` (no opponent about to arrive); otherwise, or when the
   shot value is at least ``shoot_fallback``, SHOOT (a pressed carrier without a pass
   gets rid of the ball towards the goal rather than lose it standing).

All thresholds and weights are :class:`DecisionParams` fields with the reason for
their defaults.
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..physics import ball_model
from ..physics.field import FieldGeometry
from ..physics.params import BallParams, RobotParams


#: m: a pass's receive point lies at least this far inside the field lines in open play
#: (:attr:`DecisionParams.receive_margin_m`'s default)
RECEIVE_MARGIN_M = 0.15


@dataclass(frozen=True)
class DecisionParams:
    """Parameters of the value functions (see the module docstring).

    Attributes:
        opp_reaction_s: opponent reaction time (s); Thunderbots assume 0.4 s for enemy
            reaction, TIGERs' fast model 0 s; 0.3 s: a robot must first see the kick and
            turn its plan around (our own tactics re-plan every tick, but move to
            positional targets, not to the ball's path).
        opp_speed, opp_accel: opponent top speed (m/s) and acceleration (m/s^2); None =
            the robot parameters (3 m/s, 3 m/s^2).
        shot_speed: kick speed of a shot (m/s; the kicker cap).
        pass_arrive_speed: pass arrival speed (m/s); TIGERs aim <= 3.2 and rate 1 from 2,
            a receivable pass arrives at 1-2; the Pass tactic asks its skill for the same.
        min_pass_speed: passes are kicked at least this fast (m/s).
        path_samples: samples along a ball path for the margin.
        skip_near_m: path samples closer than this to the kick point are ignored (m).
        receiver_guard_m: path samples within this of the receiver are the receiver's
            once it gets there first (m; 0: off, every sample is the ball's alone).
        min_open_angle, good_open_angle: open goal angle (rad) at which the angle term
            is 0 / 1 (Thunderbots shoot from >= 6 deg = 0.10 rad).
        shot_margin_lo, shot_margin_hi: shot path margin (s) at which f_margin is 0 / 1.
        near_shot_m, far_shot_m, far_shot_floor: distance term of the shot value.
        pass_margin_lo, pass_margin_hi: pass path margin (s) at which P is 0 / 1.
        min_pass_m, max_pass_m: pass length range (m).
        receive_margin_m: a pass's receive point lies at least this far inside the field
            lines (m; :func:`valid_receive_point`).
        w_receiver_shot, w_progress, w_possession: pass value weights.
        progress_scale_m: forward gain (m) that counts as full progress.
        w_keep, press_lo, press_hi: keep value (see the module docstring).
        shoot_threshold: shoot at once at or above this shot value. 0.25: with a goalie
            and a defender on the ball-goal line the value rarely reaches 0.5, so at 0.5
            the carrier almost never shoots (docs/RESULTS.md, "Passing game"); among
            0.5 / 0.25 / 0.12, 0.25 gives the highest hand-coded Attack 3v2 goal rate on
            60 validation episodes (seeds 46000-46059: 0.15 / 0.32 / 0.25).
        min_pass_success: passes with a lower P are not considered.
        pass_gain: a pass must beat both the shot and the keep value by this much.
        shoot_fallback: without a good pass, shoot anyway at or above this shot value.
        min_keep: without a good pass, keep only at or above this keep value, else shoot.
        turn_rate: the passer's turn rate with the ball (rad/s; the Pass tactic's hold rate).
    """

    opp_reaction_s: float = 0.3
    opp_speed: float | None = None
    opp_accel: float | None = None
    shot_speed: float = 6.5
    pass_arrive_speed: float = 2.0
    min_pass_speed: float = 2.0
    path_samples: int = 10
    skip_near_m: float = 0.15
    receiver_guard_m: float = 0.0
    min_open_angle: float = 0.05
    good_open_angle: float = 0.20
    shot_margin_lo: float = -0.05
    shot_margin_hi: float = 0.20
    near_shot_m: float = 2.0
    far_shot_m: float = 6.0
    far_shot_floor: float = 0.2
    pass_margin_lo: float = 0.0
    pass_margin_hi: float = 0.4
    min_pass_m: float = 1.0
    max_pass_m: float = 6.0
    receive_margin_m: float = RECEIVE_MARGIN_M
    w_receiver_shot: float = 0.6
    w_progress: float = 0.2
    w_possession: float = 0.25
    progress_scale_m: float = 3.0
    w_keep: float = 0.3
    press_lo: float = 0.25
    press_hi: float = 1.0
    shoot_threshold: float = 0.25
    min_pass_success: float = 0.35
    pass_gain: float = 0.05
    shoot_fallback: float = 0.25
    min_keep: float = 0.1
    turn_rate: float = 4.0

    def __post_init__(self) -> None:
        for name in ("shot_speed", "pass_arrive_speed", "min_pass_speed", "good_open_angle", "far_shot_m",
                     "max_pass_m", "progress_scale_m", "press_hi"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise ValueError(f"DecisionParams.{name} must be a positive finite number, got {v!r}")
        pairs = (("min_open_angle", "good_open_angle"), ("shot_margin_lo", "shot_margin_hi"),
                 ("pass_margin_lo", "pass_margin_hi"), ("min_pass_m", "max_pass_m"), ("press_lo", "press_hi"),
                 ("near_shot_m", "far_shot_m"))
        for lo, hi in pairs:
            if not getattr(self, lo) < getattr(self, hi):
                raise ValueError(f"DecisionParams.{lo} must be smaller than DecisionParams.{hi}")
        for name in ("receiver_guard_m", "receive_margin_m"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v >= 0):
                raise ValueError(f"DecisionParams.{name} must be a finite number >= 0, got {v!r}")
        if not (isinstance(self.path_samples, int) and self.path_samples >= 2):
            raise ValueError(f"DecisionParams.path_samples must be an integer >= 2, got {self.path_samples!r}")


class Choice(enum.Enum):
    SHOOT = "shoot"
    PASS = "pass"
    KEEP = "keep"


@dataclass(frozen=True)
class PassOption:
    """One evaluated pass: teammate index, receive point (m), kick speed (m/s), path
    margin (s), success estimate P, the receiver's shot value there, and the value."""

    teammate: int
    point: np.ndarray
    kick_speed: float
    margin: float
    success: float
    receiver_shot: float
    value: float


@dataclass(frozen=True)
class Decision:
    """The carrier's choice with its evidence (values as in the module docstring).

    Three optional fields let a decider other than :func:`decide` (a learned one,
    :mod:`ssl_marl.plays.passing_play`'s ``CarrierDecider`` hook) say more than the cost
    decision does; their defaults are the cost decision's behaviour:

    * ``dribble_to``: with KEEP, the point (m, team frame) the carrier turns to and
      dribbles towards (None: the opponent goal centre, the attacker's KEEP);
    * ``dribble_speed``: KEEP's forward speed (m/s; None: the attacker's ``keep_speed``);
    * ``commit_s``: the play asks for no new decision for this long (s) while the
      carrier keeps the ball (0: re-decide every ``decide_every`` ticks). A committed
      KEEP is not turned into a shot after ``max_keep_s``.
    """

    choice: Choice
    shot: float
    keep: float
    passes: tuple[PassOption, ...] = ()
    best_pass: PassOption | None = None
    dribble_to: np.ndarray | None = None
    dribble_speed: float | None = None
    commit_s: float = 0.0

    @property
    def target(self) -> int | None:
        """The pass receiver (teammate index) when the choice is PASS."""
        return self.best_pass.teammate if self.choice is Choice.PASS and self.best_pass else None


# ------------------------------------------------------------- primitives
def motion_time(d: np.ndarray, v_max: float, accel: float) -> np.ndarray:
    """Time (s) to cover distance(s) ``d`` (m) from rest, accelerating at ``accel`` up to ``v_max``."""
    d = np.maximum(np.asarray(d, float), 0.0)
    d_acc = v_max * v_max / (2.0 * accel)
    return np.where(d <= d_acc, np.sqrt(2.0 * d / accel), d / v_max + v_max / (2.0 * accel))


def body_reach_time(d: np.ndarray, rp: RobotParams, bp: BallParams, v_max: float, accel: float) -> np.ndarray:
    """Time (s) for a robot whose centre is ``d`` m from a point to put its body on the ball
    there (the distance less robot + ball radius, from rest; no reaction time)."""
    return motion_time(np.asarray(d, float) - (rp.radius + bp.radius), v_max, accel)


def opponent_reach_time(opponents: np.ndarray, points: np.ndarray, rp: RobotParams, bp: BallParams,
                        params: DecisionParams) -> np.ndarray:
    """(O, P) time (s) for each opponent (O, 2) to put its body on each point (P, 2)."""
    o = np.asarray(opponents, float).reshape(-1, 2)
    q = np.asarray(points, float).reshape(-1, 2)
    d = np.hypot(o[:, None, 0] - q[None, :, 0], o[:, None, 1] - q[None, :, 1])
    return params.opp_reaction_s + body_reach_time(d, rp, bp, params.opp_speed or rp.max_speed,
                                                   params.opp_accel or rp.max_accel)


def path_margins(start: np.ndarray, ends: np.ndarray, kick_speeds: np.ndarray, opponents: np.ndarray,
                 rp: RobotParams, bp: BallParams, params: DecisionParams,
                 receivers: np.ndarray | None = None) -> np.ndarray:
    """(K,) smallest interception-time margin (s) of any opponent along each straight ball
    path ``start -> ends[k]`` kicked at ``kick_speeds[k]`` (m/s); inf without opponents,
    -inf where the ball stops short of the end. ``receivers`` (K, 2): the robot each path
    goes to, for ``receiver_guard_m`` (see the module docstring)."""
    start = np.asarray(start, float).reshape(2)
    ends = np.asarray(ends, float).reshape(-1, 2)
    v0 = np.asarray(kick_speeds, float).reshape(-1, 1)
    opp = np.asarray(opponents, float).reshape(-1, 2)
    rel = ends - start
    length = np.hypot(rel[:, 0], rel[:, 1])[:, None]  # (K, 1)
    frac = np.linspace(0.0, 1.0, params.path_samples)[None, :]
    s = np.maximum(frac * length, np.minimum(params.skip_near_m, length))  # (K, P)
    t_ball = ball_model.times_to_distances(v0, s, bp)  # (K, P)
    stops_short = ~np.isfinite(t_ball[:, -1])
    if opp.shape[0] == 0:
        return np.where(stops_short, -np.inf, np.inf)
    u = rel / np.maximum(length, 1e-9)
    pts = start[None, None, :] + s[..., None] * u[:, None, :]  # (K, P, 2)
    t_opp = opponent_reach_time(opp, pts.reshape(-1, 2), rp, bp, params).reshape(opp.shape[0], *s.shape)
    t_own = t_ball
    if receivers is not None and params.receiver_guard_m > 0:
        r = np.asarray(receivers, float).reshape(-1, 2)
        d = np.linalg.norm(pts - r[:, None, :], axis=-1)  # (K, P)
        t_recv = body_reach_time(d, rp, bp, rp.max_speed, rp.max_accel)
        t_own = np.where(d <= params.receiver_guard_m, np.minimum(t_ball, t_recv), t_ball)
    margin = (t_opp - t_own[None]).min(axis=(0, 2))
    return np.where(stops_short, -np.inf, margin)


def path_margin(start: np.ndarray, end: np.ndarray, kick_speed: float, opponents: np.ndarray, rp: RobotParams,
                bp: BallParams, params: DecisionParams, receiver: np.ndarray | None = None) -> float:
    """Smallest interception-time margin (s) of any opponent along the straight ball path
    ``start -> end`` kicked at ``kick_speed`` (m/s); inf without opponents; -inf if the
    ball stops short of ``end``; ``receiver``: the robot the ball goes to (a pass)."""
    return float(path_margins(start, np.asarray(end, float)[None, :], np.array([kick_speed]), opponents, rp, bp,
                              params, None if receiver is None else np.asarray(receiver, float)[None, :])[0])


def pass_success(start: np.ndarray, points: np.ndarray, opponents: np.ndarray, rp: RobotParams, bp: BallParams,
                 params: DecisionParams) -> np.ndarray:
    """(K,) pass success estimate P in [0, 1] from ``start`` to each point (K, 2): the
    path margin of a pass kicked at :func:`pass_kick_speeds`, mapped as in
    :func:`evaluate_passes` (no length limits)."""
    pts = np.asarray(points, float).reshape(-1, 2)
    length = np.hypot(pts[:, 0] - start[0], pts[:, 1] - start[1])
    m = path_margins(start, pts, pass_kick_speeds(length, bp, rp, params), opponents, rp, bp, params)
    return np.clip((m - params.pass_margin_lo) / (params.pass_margin_hi - params.pass_margin_lo), 0.0, 1.0)


def open_goal_interval(p: np.ndarray, obstacles: np.ndarray, field: FieldGeometry, rp: RobotParams,
                       bp: BallParams) -> tuple[float, float]:
    """(open_angle, aim_angle) in rad: the widest part of the +x goal mouth seen from ``p``
    not shadowed by any robot in ``obstacles`` (k, 2); (0, angle to the goal centre) if
    none is open."""
    p = np.asarray(p, float)
    px, py = p.tolist()
    (lx, ly), (rx, ry) = (q.tolist() for q in field.goal_posts(+1))
    a_hi = math.atan2(ly - py, lx - px)
    a_lo = math.atan2(ry - py, rx - px)
    half_length = field.half_length
    centre = math.atan2(-py, half_length - px)
    if px >= half_length or a_hi <= a_lo:
        return 0.0, centre
    intervals = [(a_lo, a_hi)]
    goal_dist = half_length - px
    R = rp.radius + bp.radius
    d_all = np.asarray(obstacles, float).reshape(-1, 2) - p
    for (dx, dy), dist in zip(d_all.tolist(), np.hypot(d_all[:, 0], d_all[:, 1]).tolist()):
        if dist < 1e-6 or dx <= -R or dx > goal_dist + R:
            continue
        half = math.asin(min(R / dist, 1.0))
        c = math.atan2(dy, dx)
        lo, hi = c - half, c + half
        new = []
        for a, b in intervals:
            if hi <= a or lo >= b:
                new.append((a, b))
                continue
            if lo > a:
                new.append((a, lo))
            if hi < b:
                new.append((hi, b))
        intervals = new
        if not intervals:
            return 0.0, centre
    a, b = max(intervals, key=lambda ab: ab[1] - ab[0])
    return b - a, 0.5 * (a + b)


def shot_value(p: np.ndarray, opponents: np.ndarray, others: np.ndarray, field: FieldGeometry, rp: RobotParams,
               bp: BallParams, params: DecisionParams) -> float:
    """Shot value in [0, 1] from point ``p`` (see the module docstring). ``opponents``
    (O, 2) can intercept; ``others`` (k, 2) are further robots that only shadow the goal
    (teammates)."""
    p = np.asarray(p, float)
    opp = np.asarray(opponents, float).reshape(-1, 2)
    obstacles = np.concatenate([opp, np.asarray(others, float).reshape(-1, 2)], axis=0)
    open_angle, aim = open_goal_interval(p, obstacles, field, rp, bp)
    f_angle = min(max((open_angle - params.min_open_angle) / (params.good_open_angle - params.min_open_angle),
                      0.0), 1.0)
    if f_angle <= 0.0:
        return 0.0
    dx = field.half_length - float(p[0])
    end = p + np.array([dx, dx * math.tan(aim)])
    margin = path_margin(p, end, params.shot_speed, opp, rp, bp, params)
    f_margin = min(max((margin - params.shot_margin_lo) / (params.shot_margin_hi - params.shot_margin_lo), 0.0),
                   1.0)
    d = float(np.hypot(*(field.goal_center(+1) - p)))
    f_dist = 1.0 - (1.0 - params.far_shot_floor) * (d - params.near_shot_m) / (params.far_shot_m - params.near_shot_m)
    f_dist = min(max(f_dist, params.far_shot_floor), 1.0)
    return float(f_angle * f_margin * f_dist)


def pass_kick_speeds(lengths, bp: BallParams, rp: RobotParams, params: DecisionParams) -> np.ndarray:
    """Kick speeds (m/s) of passes of ``lengths`` m: arriving at ``pass_arrive_speed``
    (the ball model, tabulated every 5 cm and interpolated), at least ``min_pass_speed``,
    at most the kicker cap."""
    v = ball_model.kick_speeds_for_arrival(lengths, float(params.pass_arrive_speed), bp, float(rp.kick_speed_max))
    return np.clip(v, params.min_pass_speed, rp.kick_speed_max)


def pass_kick_speed(length: float, bp: BallParams, rp: RobotParams, params: DecisionParams) -> float:
    """Scalar :func:`pass_kick_speeds`."""
    return float(pass_kick_speeds(length, bp, rp, params))


def keep_value(p: np.ndarray, opponents: np.ndarray, rp: RobotParams, bp: BallParams,
               params: DecisionParams) -> float:
    """Value of holding the ball at ``p`` (falls to 0 as an opponent closes in)."""
    opp = np.asarray(opponents, float).reshape(-1, 2)
    if opp.shape[0] == 0:
        return params.w_keep
    t_press = float(opponent_reach_time(opp, np.asarray(p, float)[None, :], rp, bp, params).min())
    pressure = min(max((t_press - params.press_lo) / (params.press_hi - params.press_lo), 0.0), 1.0)
    return params.w_keep * pressure


def valid_receive_point(q: np.ndarray, field: FieldGeometry, margin: float = RECEIVE_MARGIN_M) -> bool:
    """A pass may go to ``q``: inside the field (by ``margin``) and outside both defense areas."""
    q = np.asarray(q, float)
    return bool(field.in_field(q, margin) and not field.in_defense_area(q, -1, 0.1)
                and not field.in_defense_area(q, +1, 0.1))


def pass_candidates(p: np.ndarray, receive_points: dict[int, np.ndarray], min_m: float, max_m: float,
                    field: FieldGeometry, margin: float) -> list[tuple[int, np.ndarray, float]]:
    """``(teammate, receive point, length)`` of each ``{teammate: point}`` a pass from ``p``
    may go to: ``min_m`` to ``max_m`` metres long, at a :func:`valid_receive_point` (at least
    ``margin`` m inside the field lines)."""
    out = []
    for k, q in receive_points.items():
        q = np.asarray(q, float)
        length = float(np.hypot(*(q - p)))
        if min_m <= length <= max_m and valid_receive_point(q, field, margin):
            out.append((k, q, length))
    return out


def margin_success(margin: float, params: DecisionParams) -> float:
    """Pass success P in [0, 1] of a path margin (s): 0 at ``pass_margin_lo``, 1 at ``pass_margin_hi``."""
    return min(max((margin - params.pass_margin_lo) / (params.pass_margin_hi - params.pass_margin_lo), 0.0), 1.0)


def receive_value(p: np.ndarray, q: np.ndarray, receiver_shot: float, params: DecisionParams) -> float:
    """Value of the ball controlled at ``q`` after a pass from ``p`` (a pass's result term):
    ``w_receiver_shot * receiver_shot + w_progress * progress + w_possession``."""
    progress = min(max((float(q[0]) - float(p[0])) / params.progress_scale_m, -1.0), 1.0)
    return params.w_receiver_shot * receiver_shot + params.w_progress * progress + params.w_possession


def teammates_except(mates: np.ndarray, k: int) -> np.ndarray:
    """``mates`` (n, 2) without row ``k`` (all of them when ``k`` is not a row)."""
    return np.delete(mates, k, axis=0) if 0 <= k < len(mates) else mates


def evaluate_passes(p: np.ndarray, receive_points: dict[int, np.ndarray], teammates: np.ndarray,
                    opponents: np.ndarray, field: FieldGeometry, rp: RobotParams, bp: BallParams,
                    params: DecisionParams, heading: float | None = None) -> tuple[PassOption, ...]:
    """Evaluate a pass from ``p`` to each ``{teammate index: receive point}``.
    ``teammates`` (n, 2) are all own robot positions (they shadow the receivers' shots).
    With the carrier's ``heading`` (rad), the time to turn towards each receiver at
    ``turn_rate`` is taken off its margin (the opponents move while the passer turns)."""
    p = np.asarray(p, float)
    opp = np.asarray(opponents, float).reshape(-1, 2)
    mates = np.asarray(teammates, float).reshape(-1, 2)
    out = []
    for k, q, length in pass_candidates(p, receive_points, params.min_pass_m, params.max_pass_m, field,
                                        params.receive_margin_m):
        v0 = pass_kick_speed(length, bp, rp, params)
        margin = path_margin(p, q, v0, opp, rp, bp, params, receiver=mates[k])
        if heading is not None:
            turn = abs(math.remainder(math.atan2(q[1] - p[1], q[0] - p[0]) - heading, 2.0 * math.pi))
            margin -= turn / params.turn_rate
        success = margin_success(margin, params)
        recv_shot = shot_value(q, opp, teammates_except(mates, k), field, rp, bp, params)
        value = success * receive_value(p, q, recv_shot, params)
        out.append(PassOption(int(k), q, v0, margin, success, recv_shot, float(value)))
    return tuple(out)


def decide(p: np.ndarray, carrier: int, teammates: np.ndarray, opponents: np.ndarray, field: FieldGeometry,
           rp: RobotParams | None = None, bp: BallParams | None = None, params: DecisionParams | None = None,
           receive_points: dict[int, np.ndarray] | None = None, candidates: tuple[int, ...] | None = None,
           heading: float | None = None) -> Decision:
    """The carrier's choice (module docstring).

    Args:
        p: ball (carrier) position (2,), team frame.
        carrier: the carrier's index in ``teammates``.
        teammates: (n, 2) own robot positions; opponents: (O, 2).
        receive_points: ``{k: point}`` where teammate ``k`` would receive (default: its position).
        candidates: teammates that may be passed to (default: all but the carrier).
        heading: the carrier's heading (rad); passes that need a long turn lose margin.
    """
    rp, bp, params = rp or RobotParams(), bp or BallParams(), params or DecisionParams()
    p = np.asarray(p, float)
    mates = np.asarray(teammates, float).reshape(-1, 2)
    opp = np.asarray(opponents, float).reshape(-1, 2)
    if not 0 <= carrier < len(mates):
        raise ValueError(f"decide: carrier index {carrier} outside the {len(mates)} teammates")
    others = np.delete(mates, carrier, axis=0)
    shot = shot_value(p, opp, others, field, rp, bp, params)
    keep = keep_value(p, opp, rp, bp, params)
    if shot >= params.shoot_threshold:
        return Decision(Choice.SHOOT, shot, keep)
    cands = candidates if candidates is not None else tuple(k for k in range(len(mates)) if k != carrier)
    points = {k: (receive_points or {}).get(k, mates[k]) for k in cands if k != carrier}
    passes = evaluate_passes(p, points, mates, opp, field, rp, bp, params, heading)
    choice, best = choose(shot, keep, passes, params)
    return Decision(choice, shot, keep, passes, best)


def choose(shot: float, keep: float, options: tuple, params: DecisionParams) -> tuple[Choice, Any]:
    """The carrier's rule once its options are valued: the best option whose success is at
    least ``min_pass_success`` if it beats both shot and keep by ``pass_gain`` (returned as
    ``Choice.PASS``: the caller names its kind), else a shot when the shot is worth
    ``shoot_fallback`` or keeping is hopeless (< ``min_keep``), else keep. Returns
    (choice, the best eligible option or None)."""
    ok = [o for o in options if o.success >= params.min_pass_success]
    best = max(ok, key=lambda o: o.value) if ok else None
    if best is not None and best.value >= max(shot, keep) + params.pass_gain:
        return Choice.PASS, best
    if shot >= params.shoot_fallback or keep < params.min_keep:
        return Choice.SHOOT, best
    return Choice.KEEP, best


__all__ = ["RECEIVE_MARGIN_M", "DecisionParams", "Choice", "PassOption", "Decision", "motion_time", "body_reach_time", "opponent_reach_time",
           "path_margins", "path_margin", "pass_success", "pass_kick_speeds", "open_goal_interval", "shot_value",
           "pass_kick_speed", "keep_value", "valid_receive_point", "pass_candidates", "margin_success",
           "receive_value", "teammates_except", "evaluate_passes", "choose", "decide"]
