"""Keepaway 3v2: the keepers' observations and the global state (:class:`KeepawayObservation`,
mixed into :class:`~ssl_marl.decisions.keepaway.env.KeepawayEnv`).

Observation (per keeper, float32, field/team frame, metres, m/s, radians; D = 39)::

    [0:2]   own position relative to the square centre
    [2]     own distance to the centre           [3] own distance to the nearest side
    [4:6]   own velocity                         [6] 1 if this keeper controls the ball
    [7:9]   ball position relative to self       [9] ball distance
    [10:12] ball velocity
    [12:24] teammates (i+1)%3, (i+2)%3, 6 each: relative position (2), distance,
            its distance to the centre, its distance to its nearest taker,
            min angle at self between it and a taker closer than it (pi if none)
    [24:36] takers sorted by distance to self, 6 each: relative position (2),
            distance, its distance to the centre, its velocity (2)
    [36:39] phase one-hot: a keeper holds the ball / a pass is under way / ball loose

State (global, D = 41): ball position and velocity (4); per keeper 0..2 then taker
0..1: position (2), velocity (2), cos/sin heading (2) (30); phase one-hot (3); the
option holder's one-hot over keepers (3, zeros when none); t / max_time_s (1).

Observations read what the keepers see (``engine.vision_state("blue")``: the tracker's
estimate when the env runs it); the global state reads the ground truth.
"""

from __future__ import annotations

import math

import numpy as np

OBS_DIM = 39
STATE_DIM = 41


def lane_angles(src: np.ndarray, dst: np.ndarray, takers: np.ndarray) -> float:
    """Smallest angle (rad) at ``src`` between the lane to ``dst`` and a taker that is
    not farther from ``src`` than ``dst`` (+0.3 m); pi when no taker qualifies."""
    lane = dst - src
    dl = math.hypot(lane[0], lane[1])
    best = math.pi
    for t in takers:
        v = t - src
        dt_ = math.hypot(v[0], v[1])
        if dt_ > dl + 0.3:
            continue
        if dt_ < 1e-6 or dl < 1e-6:
            return 0.0
        c = (v[0] * lane[0] + v[1] * lane[1]) / (dt_ * dl)
        best = min(best, math.acos(max(-1.0, min(1.0, c))))
    return best


class KeepawayObservation:
    """Observation and state hooks of :class:`~ssl_marl.decisions.keepaway.env.KeepawayEnv`
    (module docstring); reads the env's ``engine``, ``field``, ``rules``, ``holder``,
    ``phase``, ``controller()`` and ``_truth``."""

    def observation_bounds(self) -> tuple[np.ndarray, np.ndarray]:
        L = 2.0 * math.hypot(self.field.half_length, self.field.half_width) + 1.0
        V = 10.0
        lo, hi = np.zeros(OBS_DIM, np.float32), np.zeros(OBS_DIM, np.float32)

        def put(sl, a, b):
            lo[sl], hi[sl] = a, b

        put(slice(0, 2), -L, L); put(2, 0, L); put(3, -L, L); put(slice(4, 6), -V, V); put(6, 0, 1)
        put(slice(7, 9), -L, L); put(9, 0, L); put(slice(10, 12), -V, V)
        for j in range(2):
            b = 12 + 6 * j
            put(slice(b, b + 2), -L, L); put(slice(b + 2, b + 5), 0, L); put(b + 5, 0, math.pi)
        for j in range(2):
            b = 24 + 6 * j
            put(slice(b, b + 2), -L, L); put(slice(b + 2, b + 4), 0, L); put(slice(b + 4, b + 6), -V, V)
        put(slice(36, 39), 0, 1)
        return lo, hi

    def observe(self) -> dict[str, np.ndarray]:
        w = self.engine.vision_state("blue")
        kp, kv = w.blue.pos, w.blue.vel
        tk, tv = w.yellow.pos, w.yellow.vel
        ball, bv = w.ball_pos, w.ball_vel
        half = self._half
        kc = np.sqrt((kp ** 2).sum(axis=1))
        tc = np.sqrt((tk ** 2).sum(axis=1))
        kt = np.sqrt(((kp[:, None, :] - tk[None, :, :]) ** 2).sum(axis=2)).min(axis=1)
        ctrl = self.holder if self.holder is not None else self.controller()
        ph = self.phase
        out = {}
        for i, a in enumerate(self.possible_agents):
            o = np.empty(OBS_DIM, np.float32)
            pos = kp[i]
            o[0:2] = pos
            o[2] = kc[i]
            o[3] = half - max(abs(pos[0]), abs(pos[1]))
            o[4:6] = kv[i]
            o[6] = 1.0 if ctrl == i else 0.0
            rb = ball - pos
            o[7:9] = rb
            o[9] = math.hypot(rb[0], rb[1])
            o[10:12] = bv
            for j in range(2):
                k = (i + 1 + j) % 3
                b = 12 + 6 * j
                r = kp[k] - pos
                o[b:b + 2] = r
                o[b + 2] = math.hypot(r[0], r[1])
                o[b + 3] = kc[k]
                o[b + 4] = kt[k]
                o[b + 5] = lane_angles(pos, kp[k], tk)
            dts = np.sqrt(((tk - pos) ** 2).sum(axis=1))
            for j, k in enumerate(np.argsort(dts, kind="stable")):
                b = 24 + 6 * j
                o[b:b + 2] = tk[k] - pos
                o[b + 2] = dts[k]
                o[b + 3] = tc[k]
                o[b + 4:b + 6] = tv[k]
            o[36:39] = (ph == "hold", ph == "pass", ph == "loose")
            out[a] = o
        return out

    def state_bounds(self) -> tuple[np.ndarray, np.ndarray]:
        L = math.hypot(self.field.half_length, self.field.half_width) + 1.0
        V = 10.0
        lo, hi = np.full(STATE_DIM, -1.0, np.float32), np.full(STATE_DIM, 1.0, np.float32)
        lo[0:2], hi[0:2] = -L, L
        lo[2:4], hi[2:4] = -V, V
        for j in range(5):
            b = 4 + 6 * j
            lo[b:b + 2], hi[b:b + 2] = -L, L
            lo[b + 2:b + 4], hi[b + 2:b + 4] = -V, V
        lo[34:41] = 0.0
        return lo, hi

    def global_state(self) -> np.ndarray:
        w = self._truth
        s = np.zeros(STATE_DIM, np.float32)
        s[0:2], s[2:4] = w.ball_pos, w.ball_vel
        for j, (team, k) in enumerate([("blue", 0), ("blue", 1), ("blue", 2), ("yellow", 0), ("yellow", 1)]):
            ts = w.team(team)
            b = 4 + 6 * j
            s[b:b + 2], s[b + 2:b + 4] = ts.pos[k], ts.vel[k]
            s[b + 4], s[b + 5] = math.cos(ts.heading[k]), math.sin(ts.heading[k])
        ph = self.phase
        s[34:37] = (ph == "hold", ph == "pass", ph == "loose")
        if self.holder is not None:
            s[37 + self.holder] = 1.0
        s[40] = min(self.t / self.rules.max_time_s, 1.0)
        return s


__all__ = ["KeepawayObservation", "OBS_DIM", "STATE_DIM", "lane_angles"]
