"""A vectorised Kalman filter for position-velocity pairs.

Each object (robot or ball) has ``k`` independent axes (x, y; or the heading), each
with the state [p, v]: position (m or rad) and velocity (m/s or rad/s). Axes are
decoupled in the process and measurement models, so the filter keeps one 2x2
covariance per object and axis. Process: a known acceleration ``a`` (the control
input: commanded motion, ball deceleration, 0 for constant velocity) plus white-noise
acceleration of standard deviation ``q``::

    v' = v + a dt,   p' = p + v dt + c a dt^2   (c = 1 for the simulator's robots)
    Q  = q^2 [[dt^4/4, dt^3/2], [dt^3/2, dt^2]]

Measurements: position (noise ``r_p``) and, optionally, velocity (``r_v``). Angle
axes wrap the position innovation to (-pi, pi].
"""

from __future__ import annotations

import numpy as np

from ...physics.state import wrap_angle


class PVFilter:
    """Kalman filters for ``n`` objects with ``k`` axes each.

    Attributes:
        p: (n, k) positions.  v: (n, k) velocities.  P: (n, k, 2, 2) covariances.
        angular: True if the axes are angles (wrapped).
    """

    def __init__(self, n: int, k: int, angular: bool = False) -> None:
        self.n, self.k, self.angular = int(n), int(k), bool(angular)
        self.p = np.zeros((n, k))
        self.v = np.zeros((n, k))
        self.P = np.zeros((n, k, 2, 2))

    def copy(self) -> PVFilter:
        out = PVFilter.__new__(PVFilter)
        out.n, out.k, out.angular = self.n, self.k, self.angular
        out.p, out.v, out.P = self.p.copy(), self.v.copy(), self.P.copy()
        return out

    def set(self, idx, p: np.ndarray, v: np.ndarray, p_var: float, v_var: float) -> None:
        """Restart objects ``idx`` at (p, v) with diagonal covariance."""
        self.p[idx] = p
        self.v[idx] = v
        P = np.zeros((2, 2))
        P[0, 0], P[1, 1] = p_var, v_var
        self.P[idx] = P
        if self.angular:
            self.p[idx] = wrap_angle(self.p[idx])

    def predict(self, dt: float, accel: np.ndarray | float = 0.0, q: float = 0.0, pos_factor: float = 1.0,
                covariance: bool = True) -> None:
        """Advance ``dt`` s with acceleration ``accel`` ((n, k) or scalar) and white-noise
        acceleration of standard deviation ``q`` (scalar). ``covariance=False`` skips
        the covariance (prediction-only copies)."""
        if self.n == 0:
            return
        self.v = self.v + accel * dt
        self.p = self.p + self.v * dt + (pos_factor - 1.0) * accel * dt * dt
        if self.angular:
            self.p = wrap_angle(self.p)
        if not covariance:
            return
        P = self.P
        p00, p01, p11 = P[..., 0, 0], P[..., 0, 1], P[..., 1, 1]
        q2 = float(q) ** 2
        out = np.empty_like(P)
        out[..., 0, 0] = p00 + 2 * dt * p01 + dt * dt * p11 + q2 * dt ** 4 / 4
        out[..., 0, 1] = out[..., 1, 0] = p01 + dt * p11 + q2 * dt ** 3 / 2
        out[..., 1, 1] = p11 + q2 * dt * dt
        self.P = out

    def innovation(self, zp: np.ndarray) -> np.ndarray:
        """Measured minus predicted position (n, k), wrapped for angles."""
        d = np.asarray(zp, float) - self.p
        return wrap_angle(d) if self.angular else d

    def update(self, mask: np.ndarray, zp: np.ndarray, r_p: float, zv: np.ndarray | None = None,
               r_v: float | None = None) -> None:
        """Measurement update of the objects where ``mask`` (n,) is True with positions
        ``zp`` (n, k) (noise sigma ``r_p``) and, if given, velocities ``zv`` (n, k)
        (sigma ``r_v``)."""
        idx = np.flatnonzero(mask)
        if idx.size == 0:
            return
        P = self.P[idx]  # (m, k, 2, 2)
        y_p = self.innovation(zp)[idx]
        if zv is None:
            s = P[..., 0, 0] + r_p * r_p
            K = P[..., :, 0] / s[..., None]  # (m, k, 2)
            dp, dv = K[..., 0] * y_p, K[..., 1] * y_p
            newP = P - K[..., :, None] * P[..., 0, None, :]
        else:
            y_v = np.asarray(zv, float)[idx] - self.v[idx]
            R = np.zeros(P.shape)
            R[..., 0, 0], R[..., 1, 1] = r_p * r_p, r_v * r_v
            S = P + R
            K = P @ np.linalg.inv(S)
            y = np.stack([y_p, y_v], axis=-1)
            dx = np.einsum("mkij,mkj->mki", K, y)
            dp, dv = dx[..., 0], dx[..., 1]
            newP = P - K @ P
        self.p[idx] += dp
        self.v[idx] += dv
        if self.angular:
            self.p[idx] = wrap_angle(self.p[idx])
        self.P[idx] = 0.5 * (newP + np.swapaxes(newP, -1, -2))
