"""Observations of every robot of K worlds in one numpy pass.

:func:`batched_observations` is :func:`ssl_marl.envs.observation.all_observations`
with a leading world axis: the same layout (see that module's table), the same
operations in the same order, so world k's rows equal ``all_observations`` of
world k's snapshot (tested).
"""

from __future__ import annotations

import numpy as np

from ..physics.field import FieldGeometry
from .observation import BALL_AIR_DIM, SELF_DIM, SLOT_DIM, _category_offset, obs_dim


def batched_observations(pos: np.ndarray, heading: np.ndarray, vel: np.ndarray, omega: np.ndarray,
                         ball_pos: np.ndarray, ball_vel: np.ndarray, on_dribbler: np.ndarray, kick_ready: np.ndarray,
                         ball_visible: np.ndarray | bool, field: FieldGeometry, n_blue: int, n_yellow: int,
                         max_teammates: int, max_opponents: int,
                         ball_air: tuple[np.ndarray, np.ndarray] | None = None) -> np.ndarray:
    """(K, n, obs_dim) float32 observations, blue robots first, each in its team frame.

    Args (field frame, SI units): pos (K, n, 2), heading (K, n), vel (K, n, 2),
    omega (K, n), ball_pos (K, 2), ball_vel (K, 2), on_dribbler (K, n) bool,
    kick_ready (K, n) bool, ball_visible (K,) bool or one bool for all worlds;
    ball_air (chip kicks): (ball height (K,) m, vertical velocity (K,) m/s), appended
    as the last two entries (None: the layout without them).
    """
    K, n = pos.shape[0], n_blue + n_yellow
    nb, ny = n_blue, n_yellow
    # float32 output written directly: every value is computed in float64 and rounded
    # once on assignment, as all_observations' final astype does
    out = np.zeros((K, n, obs_dim(max_teammates, max_opponents, ball_air is not None)), dtype=np.float32)
    if ball_air is not None:
        out[..., -BALL_AIR_DIM] = np.asarray(ball_air[0], np.float64)[:, None]
        out[..., -1] = np.asarray(ball_air[1], np.float64)[:, None]
    sgn = np.concatenate([np.ones(nb), -np.ones(ny)])
    s2 = sgn[:, None]
    cos_h, sin_h = np.cos(heading), np.sin(heading)
    p = pos * s2
    out[..., 0:2] = p
    out[..., 2] = cos_h * sgn
    out[..., 3] = sin_h * sgn
    out[..., 4:6] = vel * s2
    out[..., 6] = omega
    out[..., 7:9] = ball_pos[:, None, :] * s2 - p
    out[..., 9:11] = ball_vel[:, None, :] * s2
    out[..., 11] = on_dribbler
    out[..., 12] = kick_ready
    out[..., 13] = np.asarray(ball_visible, dtype=np.float64).reshape(-1, 1) if np.ndim(ball_visible) else \
        (1.0 if ball_visible else 0.0)
    out[..., 14] = field.half_length - p[..., 0]
    out[..., 15] = -p[..., 1]
    out[..., 16] = -field.half_length - p[..., 0]
    out[..., 17] = -p[..., 1]
    out[..., 18] = field.half_length
    out[..., 19] = field.half_width
    out[..., 20] = field.goal_width / 2
    if n > 1 and (max_teammates or max_opponents):
        rel = (pos[:, None, :, :] - pos[:, :, None, :]) * s2[None, :, :, None]  # (k, i, j): j seen from i
        d2 = rel[..., 0] * rel[..., 0] + rel[..., 1] * rel[..., 1]
        order = np.argsort(d2 + _category_offset(nb, ny), axis=2, kind="stable")  # mates, opponents, self
        # per-robot values gathered in each observer's order (one row-take over all worlds),
        # then made relative to the observer and turned into its team frame. The sign
        # flip is exact (x * -1.0 == -x), so the values equal all_observations'.
        q = np.concatenate([pos, vel, cos_h[..., None], sin_h[..., None]], axis=2).reshape(K * n, 6)
        g = np.take(q, order + (np.arange(K) * n)[:, None, None], axis=0)  # (K, i, rank, 6)
        g[..., 0:2] -= pos[:, :, None, :]
        if ny:
            g[:, nb:] *= -1.0
        n_slots = max_teammates + max_opponents
        blk = np.zeros((K, n, n_slots, SLOT_DIM))
        for lo, hi, n_mates, n_opp in ((0, nb, nb - 1, ny), (nb, n, ny - 1, nb)):
            if hi == lo:
                continue
            km, ko = min(max(n_mates, 0), max_teammates), min(n_opp, max_opponents)
            om = max(n_mates, 0)
            for s0, r0, cnt in ((0, 0, km), (max_teammates, om, ko)):  # (slot start, rank start, count)
                if cnt > 0:
                    blk[:, lo:hi, s0:s0 + cnt, 0] = 1.0
                    blk[:, lo:hi, s0:s0 + cnt, 1:] = g[:, lo:hi, r0:r0 + cnt]
        out[..., SELF_DIM:SELF_DIM + n_slots * SLOT_DIM] = blk.reshape(K, n, n_slots * SLOT_DIM)
    return out
