"""The ball in the air: chip kicks, flight under gravity and damped bounces.

The field simulation is top-down (Box2D moves the ball in x, y); the height is a
separate coordinate integrated here, one physics sub-step at a time, for one world
or many at once (numpy arrays of any shape; the single world passes shape (1,)
arrays, so single and batched worlds run the same float operations).

Frame and units: ``z`` is the height of the ball's lowest point above the field (m,
0 = on the ground), ``vz`` its vertical velocity (m/s, up positive), times in s.

Model (parameters in :class:`~ssl_marl.physics.params.BallParams`):

* Flight: drag-free projectile, ``z(t) = z0 + vz t - g t^2 / 2``; integrated in
  closed form, so the apex and the landing point are exact (no step error).
* Bounce: TIGERs' analytic chip model (Sumatra, ``BallParameters``: chip damping
  z 0.47, xy 0.8 on the first hop, 0.85 on later hops; docs/references.md,
  "Ball motion models"): at touchdown the vertical speed is reversed and multiplied
  by ``bounce_damping_z`` and the horizontal velocity by ``bounce_damping_xy_first``
  (first bounce) or ``bounce_damping_xy_later``. A hop lower than
  ``min_hop_height`` ends the flight: the ball lies on the ground and rolls (the
  rolling phase of the two-phase ground model). grSim's figures (z 0.42, xy 0.6
  then 0.96) are one ``dataclasses.replace`` away.
* Robots: a ball higher than ``robot_height`` (0.15 m; robots fit under 0.15 m,
  SSL rules "Robot shape") passes over them; lower, it collides with them.

A flight step crosses at most one bounce: the shortest hop that is not the last
(``min_hop_height`` = 0.01 m) lasts 2 sqrt(2 h / g) = 90 ms, ten sub-steps.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class FlightStep:
    """The result of :func:`advance` over one sub-step (arrays of the input's shape).

    z, vz: height (m) and vertical velocity (m/s) at the end of the sub-step.
    bounced: the ball touched the ground during the sub-step.
    t_touch: time from the start of the sub-step to that touchdown (s; dt where none).
    xy_factor: the horizontal velocity factor of that bounce (1 where none).
    landed: the flight ended (the hop after the bounce is lower than min_hop_height).
    apex: the highest point reached during the sub-step (m).
    """

    z: np.ndarray
    vz: np.ndarray
    bounced: np.ndarray
    t_touch: np.ndarray
    xy_factor: np.ndarray
    landed: np.ndarray
    apex: np.ndarray


def launch(speed: np.ndarray, angle: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Split a kick's 3-D ball speed (m/s) at elevation ``angle`` (rad) into its
    horizontal and vertical parts."""
    speed, angle = np.asarray(speed, float), np.asarray(angle, float)
    return speed * np.cos(angle), speed * np.sin(angle)


def airborne(z: np.ndarray, vz: np.ndarray) -> np.ndarray:
    """True where the ball is in flight (above the ground or rising from it)."""
    return (np.asarray(z) > 0.0) | (np.asarray(vz) > 0.0)


def advance(z: np.ndarray, vz: np.ndarray, bounces: np.ndarray, dt: float, gravity: float, damping_z: float,
            damping_xy_first: float, damping_xy_later: float, min_hop_height: float) -> FlightStep:
    """Advance balls in flight by ``dt`` seconds (closed-form projectile, one bounce at most).

    Args:
        z, vz: height (m) and vertical velocity (m/s) at the start of the sub-step.
        bounces: bounces so far in this flight (selects the first-hop xy damping).
        dt: sub-step (s). gravity: m/s^2. The damping and hop figures as in the module
            docstring.
    """
    z = np.asarray(z, float)
    vz = np.asarray(vz, float)
    g = gravity
    z_free = z + vz * dt - 0.5 * g * dt * dt
    vz_free = vz - g * dt
    # apex inside the sub-step where the vertical velocity changes sign in it
    t_up = np.clip(vz / g, 0.0, dt)
    apex = np.maximum(z, z + vz * t_up - 0.5 * g * t_up * t_up)
    bounced = z_free <= 0.0
    if not bounced.any():
        one = np.ones_like(z)
        return FlightStep(z_free, vz_free, bounced, np.full_like(z, dt), one, np.zeros_like(bounced), apex)
    # touchdown: z + vz t - g t^2 / 2 = 0, the later root
    t_touch = np.where(bounced, (vz + np.sqrt(np.maximum(vz * vz + 2.0 * g * z, 0.0))) / g, dt)
    t_touch = np.clip(t_touch, 0.0, dt)
    v_in = vz - g * t_touch  # negative: falling
    v_out = -v_in * damping_z
    landed = bounced & (v_out * v_out < 2.0 * g * min_hop_height)
    rest = dt - t_touch
    z_hop = v_out * rest - 0.5 * g * rest * rest
    vz_hop = v_out - g * rest
    factor = np.where(np.asarray(bounces) > 0, damping_xy_later, damping_xy_first)
    return FlightStep(
        z=np.where(bounced, np.where(landed, 0.0, np.maximum(z_hop, 0.0)), z_free),
        vz=np.where(bounced, np.where(landed, 0.0, vz_hop), vz_free),
        bounced=bounced,
        t_touch=t_touch,
        xy_factor=np.where(bounced, factor, 1.0),
        landed=landed,
        apex=apex,
    )


def effective_xy_scale(step: FlightStep, dt: float) -> np.ndarray:
    """Factor for the horizontal velocity during a sub-step with a bounce, so that the
    distance covered equals v t_touch + v f (dt - t_touch) (full speed until the
    touchdown, damped after it); 1 where there is no bounce."""
    return np.where(step.bounced, (step.t_touch + step.xy_factor * (dt - step.t_touch)) / dt, 1.0)


def flight_height(x: float | np.ndarray, speed: float, angle: float, gravity: float) -> float | np.ndarray:
    """Height (m) of a drag-free ball launched from the ground at ``speed`` (m/s, 3-D)
    and elevation ``angle`` (rad), at horizontal distance ``x`` (m) from the launch."""
    vh, vv = speed * math.cos(angle), speed * math.sin(angle)
    t = np.asarray(x, float) / vh
    return vv * t - 0.5 * gravity * t * t


def speed_for_range(distance: float, angle: float, gravity: float) -> float:
    """3-D launch speed (m/s) at elevation ``angle`` (rad) whose first touchdown is
    ``distance`` m away (drag-free: d = v^2 sin(2a) / g)."""
    return math.sqrt(gravity * distance / math.sin(2.0 * angle))


def projectile_reference(speed: float, angle: float, gravity: float) -> tuple[float, float]:
    """Drag-free projectile from the ground: (distance to the first touchdown (m), apex (m))."""
    vh, vv = float(np.cos(angle)) * speed, float(np.sin(angle)) * speed
    return 2.0 * vv * vh / gravity, vv * vv / (2.0 * gravity)
