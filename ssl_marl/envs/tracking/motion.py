"""Motion models the tracker predicts with: pure functions, the simulator's own models.

* :func:`robot_response`: one control step of an omni robot following a command,
  the controller of :meth:`ssl_marl.physics.world.PhysicsWorld.step` (commanded
  body-frame velocity rotated by the heading, capped at ``max_speed``, reached with
  at most ``max_accel`` (speeding up) or ``max_brake`` (slowing down) per second;
  omega with at most ``max_alpha``). Returned as the acceleration the command
  implies: ER-Force's control input (docs/references.md, "Vision and tracking").
* :func:`ball_deceleration`: the two-phase (slide, then roll) deceleration of
  :class:`ssl_marl.physics.params.BallParams`.
* :func:`face_geometry`: where a ball lies relative to robots' dribbler faces.

Frames: positions and velocities in one world frame (field or team frame, m, m/s),
headings in rad; commands in the robot's body frame (m/s, rad/s).
"""

from __future__ import annotations

import math

import numpy as np

from ...physics.params import BallParams, RobotParams


def robot_response(heading: np.ndarray, vel: np.ndarray, omega: np.ndarray, v_body: np.ndarray,
                   w_cmd: np.ndarray, rp: RobotParams, dt: float) -> tuple[np.ndarray, np.ndarray]:
    """Acceleration (n, 2) m/s^2 and angular acceleration (n,) rad/s^2 that the
    simulator's velocity controller applies over one control step ``dt`` (s) to robots
    with ``heading`` (n,), ``vel`` (n, 2), ``omega`` (n,) commanded ``v_body`` (n, 2)
    (body frame) and ``w_cmd`` (n,)."""
    c, s = np.cos(heading), np.sin(heading)
    des = np.stack([c * v_body[:, 0] - s * v_body[:, 1], s * v_body[:, 0] + c * v_body[:, 1]], axis=1)
    sp = np.hypot(des[:, 0], des[:, 1])
    over = sp > rp.max_speed
    if over.any():
        des[over] *= (rp.max_speed / sp[over])[:, None]
        sp = np.minimum(sp, rp.max_speed)
    err = des - vel
    en = np.hypot(err[:, 0], err[:, 1])
    cur = np.hypot(vel[:, 0], vel[:, 1])
    lim = np.where(sp < cur, rp.max_brake, rp.max_accel) * dt
    scale = np.where(en > lim, lim / np.maximum(en, 1e-12), 1.0)
    dv = err * scale[:, None]
    w_des = np.clip(w_cmd, -rp.max_omega, rp.max_omega)
    dw = np.clip(w_des - omega, -rp.max_alpha * dt, rp.max_alpha * dt)
    return dv / dt, dw / dt


def ball_deceleration(vel: np.ndarray, slide_until: float, bp: BallParams, dt: float) -> tuple[np.ndarray, float]:
    """(acceleration (2,) m/s^2 over the next ``dt`` s, updated slide threshold).

    The ball slides (``slide_decel``) while its speed exceeds ``slide_until`` (m/s;
    ``inf`` = rolling), then rolls (``roll_decel``); it never reverses: a ball that
    would stop within ``dt`` gets exactly the deceleration that stops it."""
    sp = float(math.hypot(vel[0], vel[1]))
    if sp <= 0.0:
        return np.zeros(2), slide_until
    if sp > slide_until:
        dec = bp.slide_decel
    else:
        dec, slide_until = bp.roll_decel, math.inf
    dec = min(dec, sp / dt)
    return -dec * np.asarray(vel, float) / sp, slide_until


def ball_position_factor(substeps: int) -> float:
    """Position gain of a constant acceleration over one control step in the
    simulator's integration (velocity changed before each of ``substeps`` equal
    sub-steps): dp = v dt + factor * a dt^2, factor = (m + 1) / (2 m)."""
    return (substeps + 1) / (2.0 * substeps)


def face_geometry(pos: np.ndarray, heading: np.ndarray, ball: np.ndarray, rp: RobotParams,
                  bp: BallParams) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """For robots at ``pos`` (n, 2) with ``heading`` (n,) and a ball at ``ball`` (2,):
    (gap (n,) m between the ball surface and the front face along the heading, lateral
    offset (n,) m of the ball along the face, d_db (n,) m = distance from the face
    midpoint to the ball surface, as :func:`ssl_marl.skills.features.dribbler_ball_distance`)."""
    d = np.asarray(ball, float)[None, :] - pos
    c, s = np.cos(heading), np.sin(heading)
    lx = c * d[:, 0] + s * d[:, 1]
    ly = -s * d[:, 0] + c * d[:, 1]
    gap = lx - rp.front_distance - bp.radius
    d_db = np.maximum(np.hypot(lx - rp.front_distance, ly) - bp.radius, 0.0)
    return gap, ly, d_db


def pinned_ball(pos: np.ndarray, heading: float, vel: np.ndarray, omega: float,
                offset: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Position (2,) and velocity (2,) of a ball held at ``offset`` (2,) (robot frame,
    m) by a robot at ``pos`` with ``heading``, ``vel`` (2,) and ``omega``."""
    c, s = math.cos(heading), math.sin(heading)
    r = np.array([c * offset[0] - s * offset[1], s * offset[0] + c * offset[1]])
    return pos + r, vel + omega * np.array([-r[1], r[0]])
