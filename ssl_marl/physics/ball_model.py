"""Closed-form ball-deceleration model: the simulator's two-phase ball as pure functions.

The simulator (:mod:`ssl_marl.physics.world`) slows a kicked ball at
``BallParams.slide_decel`` (3.9 m/s^2) until its speed has fallen to
``slide_to_roll_ratio`` (0.69) times the kick speed, then at ``roll_decel``
(0.35 m/s^2) until it stops; a ball that was not kicked (or has finished
sliding) only rolls. The ball moves in a straight line between contacts.

Every function here takes speeds in m/s, times in s, distances in m, and a
:class:`~ssl_marl.physics.params.BallParams`; positions and velocities in
:func:`predict` may be in any consistent frame (field, team or robot frame).
They know nothing of walls, robots or the dribbler: they predict a free ball.

Phases for a kick at speed ``v0 > 0`` (``s = slide_decel``, ``r = roll_decel``,
``k = slide_to_roll_ratio``):

* slide: ``0 <= t < t1 = (1 - k) v0 / s``, covering ``d1 = (v0^2 - (k v0)^2) / (2 s)``;
* roll: from speed ``v1 = k v0`` for ``t2 = v1 / r``, covering ``v1^2 / (2 r)``.

Uses: the pass skill chooses a kick speed that arrives at the receiver at 1-2 m/s
(:func:`kick_speed_for_arrival`); the receive skill and pass-safety costs need
where the ball will be (:func:`predict`, :func:`time_to_distance`).
"""

from __future__ import annotations

import functools
import math
from typing import overload

import numpy as np

from .params import BallParams, RobotParams

#: SSL rule cap on ball speed, also the simulator's kick cap (``RobotParams.kick_speed_max``).
KICK_SPEED_MAX = RobotParams().kick_speed_max
#: The simulator's friction integration step (s): one physics sub-step (control period
#: 1/60 s, 2 sub-steps). The simulator decides slide/roll before each sub-step, so the
#: slide ends up to ``slide_decel * SIM_FRICTION_DT`` (0.03 m/s) below the switch speed;
#: over a 5 m roll that shifts the ball by ~10 cm, so the model reproduces it. ``None``
#: (``friction_dt=None``) gives the continuous-time model.
SIM_FRICTION_DT = 1.0 / 120.0


def _check_speed(name: str, v: float) -> float:
    v = float(v)
    if not (math.isfinite(v) and v >= 0.0):
        raise ValueError(f"{name} must be a finite speed >= 0 m/s, got {v!r}")
    return v


def _phases(v0: float, bp: BallParams, sliding: bool = True, v_kick: float | None = None,
            friction_dt: float | None = SIM_FRICTION_DT) -> tuple[float, float, float, float]:
    """(t1, d1, v1, t2): slide duration, slide distance, speed at the switch, roll duration.

    ``sliding`` False (a rolling ball) gives t1 = d1 = 0, v1 = v0. A ball still sliding
    after a kick at ``v_kick`` (default: ``v0`` is the kick speed) switches at
    ``ratio * v_kick`` (continuous time) or at the first friction step at or below it
    (``friction_dt`` s, the simulator's discretisation).
    """
    if not sliding or v0 <= 0.0:
        return 0.0, 0.0, v0, v0 / bp.roll_decel
    vk = v0 if v_kick is None else _check_speed("v_kick", v_kick)
    v1 = min(bp.slide_to_roll_ratio * vk, v0)
    if friction_dt:
        step = bp.slide_decel * friction_dt
        n = (v0 - v1) / step
        # a switch speed that falls exactly on a friction step (a full 6.5 m/s kick does)
        # goes either way in the simulator's float arithmetic: take the middle
        n_steps = round(n) + 0.5 if abs(n - round(n)) < 1e-6 else math.ceil(n)
        v1 = max(v0 - n_steps * step, 0.0)
    t1 = (v0 - v1) / bp.slide_decel
    d1 = (v0 * v0 - v1 * v1) / (2.0 * bp.slide_decel)
    return t1, d1, v1, v1 / bp.roll_decel


def stop_distance(v0: float, bp: BallParams, sliding: bool = True, v_kick: float | None = None,
                  friction_dt: float | None = SIM_FRICTION_DT) -> float:
    """Distance (m) a ball kicked at ``v0`` (m/s) travels before it stops.

    ``sliding=False``: the ball is already rolling at ``v0``."""
    v0 = _check_speed("v0", v0)
    _, d1, v1, _ = _phases(v0, bp, sliding, v_kick, friction_dt)
    return max(d1 + v1 * v1 / (2.0 * bp.roll_decel) - (v0 * friction_dt / 2.0 if friction_dt else 0.0), 0.0)


def stop_time(v0: float, bp: BallParams, sliding: bool = True, v_kick: float | None = None,
              friction_dt: float | None = SIM_FRICTION_DT) -> float:
    """Time (s) until a ball kicked at ``v0`` (m/s) stops."""
    v0 = _check_speed("v0", v0)
    t1, _, _, t2 = _phases(v0, bp, sliding, v_kick, friction_dt)
    return t1 + t2


@overload
def speed_at(v0: float, t: float, bp: BallParams, sliding: bool = ..., v_kick: float | None = ...,
             friction_dt: float | None = ...) -> float: ...
@overload
def speed_at(v0: float, t: np.ndarray, bp: BallParams, sliding: bool = ..., v_kick: float | None = ...,
             friction_dt: float | None = ...) -> np.ndarray: ...
def speed_at(v0, t, bp, sliding=True, v_kick=None, friction_dt=SIM_FRICTION_DT):
    """Ball speed (m/s) ``t`` seconds after a kick at ``v0`` (m/s); ``t`` a float or an array.

    ``sliding=False`` treats ``v0`` as the speed of a rolling ball."""
    v0 = _check_speed("v0", v0)
    t1, _, v1, _ = _phases(v0, bp, sliding, v_kick, friction_dt)
    ta = np.maximum(np.asarray(t, dtype=float), 0.0)
    v = np.where(ta < t1, v0 - bp.slide_decel * ta, np.maximum(v1 - bp.roll_decel * (ta - t1), 0.0))
    return float(v) if np.ndim(t) == 0 else v


def distance_at(v0, t, bp: BallParams, sliding: bool = True, v_kick: float | None = None,
                friction_dt: float | None = SIM_FRICTION_DT):
    """Distance (m) travelled ``t`` seconds after a kick at ``v0`` (m/s); ``t`` a float or an
    array. Constant once the ball has stopped. With ``friction_dt`` it includes the
    simulator's integration lag (``(v0 - v(t)) * friction_dt / 2``, at most 2.7 cm at
    6.5 m/s), as do the inverse functions."""
    v0 = _check_speed("v0", v0)
    t1, d1, v1, t2 = _phases(v0, bp, sliding, v_kick, friction_dt)
    ta = np.maximum(np.asarray(t, dtype=float), 0.0)
    ts = np.minimum(ta, t1)
    d_slide = v0 * ts - 0.5 * bp.slide_decel * ts * ts
    tr = np.clip(ta - t1, 0.0, t2)
    d_roll = v1 * tr - 0.5 * bp.roll_decel * tr * tr
    d = np.where(ta < t1, d_slide, d1 + d_roll)
    if friction_dt:  # semi-implicit Euler (friction, then move): lags by (v0 - v(t)) dt / 2
        v = np.where(ta < t1, v0 - bp.slide_decel * ta, np.maximum(v1 - bp.roll_decel * (ta - t1), 0.0))
        d = d - (v0 - v) * friction_dt / 2.0
    return float(d) if np.ndim(t) == 0 else d


def _continuous_distance(v0: float, d: float, bp: BallParams, sliding: bool, v_kick: float | None,
                         friction_dt: float | None) -> float:
    """The continuous-time distance at which the simulated ball (lagging by
    ``(v0 - v) dt / 2``) has covered ``d``: a fixed point, 3 iterations (< 0.1 mm)."""
    if not friction_dt:
        return d
    dc = d
    for _ in range(3):
        dc = d + (v0 - _speed_at_continuous_distance(v0, dc, bp, sliding, v_kick, friction_dt)) * friction_dt / 2.0
    return dc


def _speed_at_continuous_distance(v0: float, d: float, bp: BallParams, sliding: bool, v_kick: float | None,
                                  friction_dt: float | None) -> float:
    _, d1, v1, _ = _phases(v0, bp, sliding, v_kick, friction_dt)
    if d <= d1:
        return math.sqrt(max(v0 * v0 - 2.0 * bp.slide_decel * d, 0.0))
    return math.sqrt(max(v1 * v1 - 2.0 * bp.roll_decel * (d - d1), 0.0))


def time_to_distance(v0: float, d: float, bp: BallParams, sliding: bool = True,
                     v_kick: float | None = None, friction_dt: float | None = SIM_FRICTION_DT) -> float:
    """Time (s) for a ball kicked at ``v0`` (m/s) to cover ``d`` (m); ``inf`` if it stops short."""
    v0 = _check_speed("v0", v0)
    d = float(d)
    if not math.isfinite(d):
        raise ValueError(f"d must be a finite distance (m), got {d!r}")
    if d <= 0.0:
        return 0.0
    d = _continuous_distance(v0, d, bp, sliding, v_kick, friction_dt)
    t1, d1, v1, _ = _phases(v0, bp, sliding, v_kick, friction_dt)
    if d <= d1:  # during the slide: d = v0 t - s t^2 / 2
        disc = v0 * v0 - 2.0 * bp.slide_decel * d
        return (v0 - math.sqrt(max(disc, 0.0))) / bp.slide_decel
    rest = d - d1
    disc = v1 * v1 - 2.0 * bp.roll_decel * rest
    if disc < 0.0:
        return math.inf
    return t1 + (v1 - math.sqrt(disc)) / bp.roll_decel


def speed_at_distance(v0: float, d: float, bp: BallParams, sliding: bool = True,
                      v_kick: float | None = None, friction_dt: float | None = SIM_FRICTION_DT) -> float:
    """Speed (m/s) of a ball kicked at ``v0`` (m/s) when it has covered ``d`` (m); 0 if it
    stops short."""
    v0 = _check_speed("v0", v0)
    d = _continuous_distance(v0, max(float(d), 0.0), bp, sliding, v_kick, friction_dt)
    return _speed_at_continuous_distance(v0, d, bp, sliding, v_kick, friction_dt)


def kick_speed_for_arrival(d: float, v_arrive: float, bp: BallParams, v_max: float = KICK_SPEED_MAX,
                           friction_dt: float | None = SIM_FRICTION_DT) -> float:
    """Kick speed (m/s) at which the ball still moves at ``v_arrive`` (m/s) after ``d`` (m),
    clipped to ``v_max`` (the kicker cap, 6.5 m/s).

    Closed form in continuous time: with ``s``, ``r``, ``k`` as in the module docstring,
    the slide covers ``v0^2 (1 - k^2) / (2 s)``; if the arrival lies in the roll phase
    (``v_arrive <= k v0``), ``v0^2 ((1 - k^2)/s + k^2/r) = 2 d + v_arrive^2 / r``;
    otherwise the ball is still sliding and ``v0^2 = v_arrive^2 + 2 s d``. With the
    simulator's discretisation (``friction_dt``) a bisection on :func:`speed_at_distance`
    refines it (the smallest kick speed that arrives at >= ``v_arrive``, to 1e-8 m/s).
    """
    d = float(d)
    if not (math.isfinite(d) and d >= 0.0):
        raise ValueError(f"d must be a finite distance >= 0 m, got {d!r}")
    v_arrive = _check_speed("v_arrive", v_arrive)
    s, r, k = bp.slide_decel, bp.roll_decel, bp.slide_to_roll_ratio
    v0 = math.sqrt((2.0 * d + v_arrive * v_arrive / r) / ((1.0 - k * k) / s + k * k / r))
    if v_arrive > k * v0:  # arrives while still sliding
        v0 = math.sqrt(v_arrive * v_arrive + 2.0 * s * d)
    if friction_dt and d > 0.0:  # bisection on the discretised model, bracketing the estimate
        lo, hi = max(v0 - 0.3, v_arrive), v0 + 0.3
        while speed_at_distance(hi, d, bp, True, None, friction_dt) < v_arrive:
            lo, hi = hi, hi + 0.5
        for _ in range(30):
            mid = 0.5 * (lo + hi)
            if speed_at_distance(mid, d, bp, True, None, friction_dt) >= v_arrive:
                hi = mid
            else:
                lo = mid
        v0 = hi
    return min(v0, float(v_max))


def predict(pos, vel, t, bp: BallParams, sliding: bool = False, v_kick: float | None = None,
            friction_dt: float | None = SIM_FRICTION_DT) -> tuple[np.ndarray, np.ndarray]:
    """Position (m) and velocity (m/s) of a free ball ``t`` s from now.

    Args:
        pos: (2,) current position (m), any frame.  vel: (2,) current velocity (m/s).
        t: float or (T,) array of times (s); with an array the results are (T, 2).
        sliding: the ball is still sliding (just kicked); by default it is assumed to
            be rolling, the safe assumption when the kick is not known.
        v_kick: the kick speed (m/s) when ``sliding``; default: the current speed.
    Returns:
        ``(pos, vel)``: (2,) each, or (T, 2) each for an array ``t``.
    """
    p = np.asarray(pos, dtype=float).reshape(2)
    v = np.asarray(vel, dtype=float).reshape(2)
    sp = float(np.hypot(v[0], v[1]))
    scalar = np.ndim(t) == 0
    if sp <= 0.0:
        if scalar:
            return p.copy(), np.zeros(2)
        n = np.shape(t)[0]
        return np.tile(p, (n, 1)), np.zeros((n, 2))
    u = v / sp
    d = distance_at(sp, t, bp, sliding, v_kick, friction_dt)
    s = speed_at(sp, t, bp, sliding, v_kick, friction_dt)
    if scalar:
        return p + u * d, u * s
    d, s = np.asarray(d), np.asarray(s)
    return p[None, :] + d[:, None] * u[None, :], s[:, None] * u[None, :]


def stop_point(pos, vel, bp: BallParams, sliding: bool = False, v_kick: float | None = None,
               friction_dt: float | None = SIM_FRICTION_DT) -> np.ndarray:
    """(2,) point (m) where a free ball at ``pos`` moving at ``vel`` comes to rest."""
    p = np.asarray(pos, dtype=float).reshape(2)
    v = np.asarray(vel, dtype=float).reshape(2)
    sp = float(np.hypot(v[0], v[1]))
    if sp <= 0.0:
        return p.copy()
    return p + v / sp * stop_distance(sp, bp, sliding, v_kick, friction_dt)


#: kick speeds (m/s) of the ball-time table of :func:`times_to_distances`
TIME_TABLE_V = np.arange(0.25, 6.5 + 1e-9, 0.05)
#: distances (m) of the ball-time table of :func:`times_to_distances`
TIME_TABLE_S = np.arange(0.0, 12.0 + 1e-9, 0.025)


@functools.lru_cache(maxsize=8)
def _ball_time_table(bp: BallParams) -> np.ndarray:
    """(V, S) time (s) a ball kicked at ``TIME_TABLE_V[i]`` needs to cover ``TIME_TABLE_S[j]``
    (inf where it stops short), from :func:`distance_at` on a fine time grid."""
    table = np.full((len(TIME_TABLE_V), len(TIME_TABLE_S)), np.inf)
    for i, v0 in enumerate(TIME_TABLE_V):
        tg = np.linspace(0.0, stop_time(float(v0), bp), 600)
        dg = np.maximum.accumulate(np.asarray(distance_at(float(v0), tg, bp), float))
        reach = TIME_TABLE_S <= dg[-1] - 1e-6
        table[i, reach] = np.interp(TIME_TABLE_S[reach], dg, tg)
    return table


def times_to_distances(kick_speed, s, bp: BallParams) -> np.ndarray:
    """Times (s) at which balls kicked at ``kick_speed`` (m/s; scalar or (K, 1)) have
    covered the distances ``s`` (m; broadcastable, e.g. (K, P)); inf where the ball
    stops short. :func:`distance_at`, tabulated once per :class:`BallParams` (every
    0.05 m/s and 2.5 cm, up to 12 m) and interpolated bilinearly, so that many paths
    cost a few array operations; within 0.05 s of :func:`time_to_distance` while the ball is faster than 0.8 m/s
    (tested; the model's slide ends on the simulator's 1/120 s friction steps, which
    makes time a slightly kinked function of the kick speed)."""
    table = _ball_time_table(bp)
    v = np.clip(np.asarray(kick_speed, float), TIME_TABLE_V[0], TIME_TABLE_V[-1])
    d = np.clip(np.asarray(s, float), 0.0, TIME_TABLE_S[-1])
    v, d = np.broadcast_arrays(v, d)
    fi = (v - TIME_TABLE_V[0]) / (TIME_TABLE_V[1] - TIME_TABLE_V[0])
    fj = d / (TIME_TABLE_S[1] - TIME_TABLE_S[0])
    i0 = np.minimum(np.floor(fi).astype(int), len(TIME_TABLE_V) - 2)
    j0 = np.minimum(np.floor(fj).astype(int), len(TIME_TABLE_S) - 2)
    a, b = fi - i0, fj - j0
    with np.errstate(invalid="ignore"):
        t = ((1 - a) * (1 - b) * table[i0, j0] + a * (1 - b) * table[i0 + 1, j0]
             + (1 - a) * b * table[i0, j0 + 1] + a * b * table[i0 + 1, j0 + 1])
    return np.where(np.isnan(t), np.inf, t)


#: m between the distances of the kick-speed table of :func:`kick_speeds_for_arrival`
KICK_TABLE_STEP_M = 0.05


@functools.lru_cache(maxsize=32)
def _kick_speed_table(bp: BallParams, v_arrive: float, v_max: float) -> tuple[np.ndarray, np.ndarray]:
    """(distances, kick speeds) of :func:`kick_speed_for_arrival` on a 5 cm grid
    up to 12 m (the model's solve is exact but slow to call per candidate and tick)."""
    d = np.arange(0.0, 12.0 + KICK_TABLE_STEP_M, KICK_TABLE_STEP_M)
    v = np.array([kick_speed_for_arrival(float(x), v_arrive, bp, v_max=v_max) for x in d])
    return d, v


def kick_speeds_for_arrival(lengths, v_arrive: float, bp: BallParams, v_max: float) -> np.ndarray:
    """Kick speeds (m/s) at which balls still move at ``v_arrive`` (m/s) after ``lengths``
    (m; any shape): :func:`kick_speed_for_arrival` capped at ``v_max`` (m/s), tabulated
    every 5 cm up to 12 m and interpolated linearly."""
    d, v = _kick_speed_table(bp, v_arrive, v_max)
    return np.interp(np.asarray(lengths, float), d, v)


__all__ = ["KICK_SPEED_MAX", "distance_at", "kick_speed_for_arrival", "kick_speeds_for_arrival", "predict",
           "speed_at", "speed_at_distance", "stop_distance", "stop_point", "stop_time", "time_to_distance",
           "times_to_distances"]
