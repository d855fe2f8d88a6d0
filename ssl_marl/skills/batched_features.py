"""The paper's skill features and rewards over many worlds at once (numpy).

Each function is the vectorised twin of the per-robot pure function of
:mod:`ssl_marl.skills.features` with the same name minus ``_batch``; the tests
compare them world by world. Inputs are one robot per world in the robot's team
frame (blue's team frame is the field frame): ``pos`` (K, 2) m, ``heading`` (K,)
rad, ``vel`` (K, 2) m/s, ``omega`` (K,) rad/s, ``ball_pos``/``ball_vel`` (K, 2).
Positions, distances and the success / failure tests are bit-equal to the
per-robot functions; angles from ``arctan2`` and the ``exp`` of the rewards may
differ in the last bit (numpy's vectorised ``arctan2``/``exp`` are not libm's).
"""

from __future__ import annotations

import numpy as np

from ..physics.field import FieldGeometry
from ..physics.params import BallParams, RobotParams
from ..physics.state import wrap_angle

_SQRT_2PI = float(np.sqrt(2 * np.pi))


def _to_robot(px: np.ndarray, py: np.ndarray, pos: np.ndarray, c: np.ndarray, s: np.ndarray) -> tuple:
    dx, dy = px - pos[:, 0], py - pos[:, 1]
    return c * dx + s * dy, -s * dx + c * dy


def go_to_ball_features_batch(pos, heading, vel, omega, ball_pos, field: FieldGeometry,
                              ball_vel: np.ndarray | None = None) -> np.ndarray:
    """(K, 14) float32: :func:`ssl_marl.skills.features.go_to_ball_features` per world;
    with ``ball_vel`` (K, 2) given, (K, 16): its ``"ball_velocity"`` state."""
    c, s = np.cos(heading), np.sin(heading)
    out = np.empty((pos.shape[0], 14 if ball_vel is None else 16))
    out[:, 0], out[:, 1] = _to_robot(ball_pos[:, 0], ball_pos[:, 1], pos, c, s)
    out[:, 2] = c * vel[:, 0] + s * vel[:, 1]
    out[:, 3] = -s * vel[:, 0] + c * vel[:, 1]
    out[:, 4] = omega
    out[:, 5] = np.hypot(ball_pos[:, 0] - pos[:, 0], ball_pos[:, 1] - pos[:, 1])
    L2, W2 = field.half_length, field.half_width
    x, y = np.clip(pos[:, 0], -L2, L2), np.clip(pos[:, 1], -W2, W2)
    for j, (px, py) in enumerate(((x, W2), (x, -W2), (-L2, y), (L2, y))):
        out[:, 6 + 2 * j], out[:, 7 + 2 * j] = _to_robot(px, py, pos, c, s)
    if ball_vel is not None:
        out[:, 14] = c * ball_vel[:, 0] + s * ball_vel[:, 1]
        out[:, 15] = -s * ball_vel[:, 0] + c * ball_vel[:, 1]
    return out.astype(np.float32)


def goal_post_angles_batch(pos, heading, field: FieldGeometry) -> tuple[np.ndarray, np.ndarray]:
    """(K,), (K,): left / right post angles of the opponent goal relative to the heading."""
    left, right = field.goal_posts(+1)
    al = np.arctan2(left[1] - pos[:, 1], left[0] - pos[:, 0]) - heading
    ar = np.arctan2(right[1] - pos[:, 1], right[0] - pos[:, 0]) - heading
    return wrap_angle(al), wrap_angle(ar)


def aim_to_shoot_features_batch(pos, heading, omega, ball_pos, ball_vel, field: FieldGeometry) -> np.ndarray:
    """(K, 10) float32: :func:`ssl_marl.skills.features.aim_to_shoot_features` per world."""
    c, s = np.cos(heading), np.sin(heading)
    out = np.empty((pos.shape[0], 10))
    out[:, 0], out[:, 1] = _to_robot(ball_pos[:, 0], ball_pos[:, 1], pos, c, s)
    out[:, 2] = c * ball_vel[:, 0] + s * ball_vel[:, 1]
    out[:, 3] = -s * ball_vel[:, 0] + c * ball_vel[:, 1]
    out[:, 4] = omega
    g = field.goal_center(+1)
    out[:, 5] = np.hypot(g[0] - pos[:, 0], g[1] - pos[:, 1])
    al, ar = goal_post_angles_batch(pos, heading, field)
    out[:, 6], out[:, 7], out[:, 8], out[:, 9] = np.sin(al), np.cos(al), np.sin(ar), np.cos(ar)
    return out.astype(np.float32)


def go_to_ball_reward_batch(pos, heading, ball_pos, on_dribbler, orientation_form: str = "gaussian") -> dict:
    """{term: (K,)}: :func:`ssl_marl.skills.features.go_to_ball_reward` per world."""
    dx, dy = ball_pos[:, 0] - pos[:, 0], ball_pos[:, 1] - pos[:, 1]
    d = np.hypot(dx, dy)
    theta = np.abs(wrap_angle(np.arctan2(dy, dx) - heading))
    if orientation_form == "gaussian":
        r_or = np.exp(-2.0 * theta ** 2 / np.pi ** 2) / _SQRT_2PI
    elif orientation_form == "printed":
        r_or = np.exp(-2.0 * theta / np.pi ** 2) / _SQRT_2PI
    else:
        raise ValueError(f"orientation_form must be 'gaussian' or 'printed', got {orientation_form!r}")
    return {"contact": np.where(on_dribbler, 100.0, 0.0), "distance": 5.0 / _SQRT_2PI * np.exp(-d * d / 2.0) - 2.0,
            "orientation": r_or}


def aim_to_shoot_reward_batch(pos, heading, ball_vel, field: FieldGeometry) -> dict:
    """{"aim": (K,)}: :func:`ssl_marl.skills.features.aim_to_shoot_reward` per world."""
    al, ar = goal_post_angles_batch(pos, heading, field)
    alpha = np.abs(wrap_angle(al - ar))
    beta = np.maximum(np.abs(al), np.abs(ar))
    speed = np.hypot(ball_vel[:, 0], ball_vel[:, 1])
    diff = alpha - beta
    return {"aim": np.where(diff > 0, 0.05 * diff, diff) * speed}


def dribbler_ball_distance_batch(pos, heading, ball_pos, robot: RobotParams, ball: BallParams) -> np.ndarray:
    """(K,) m: :func:`ssl_marl.skills.features.dribbler_ball_distance` per world."""
    fx = pos[:, 0] + robot.front_distance * np.cos(heading)
    fy = pos[:, 1] + robot.front_distance * np.sin(heading)
    return np.maximum(np.hypot(ball_pos[:, 0] - fx, ball_pos[:, 1] - fy) - ball.radius, 0.0)
