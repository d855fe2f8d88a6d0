"""Normalised actions -> SI robot commands: the one place where actions are scaled.

Action per agent: ``Box(-1, 1, (5,), float32)``; with chip kicks on
(``EnvConfig.chip_kicks``, the env's v1 layout) ``Box(-1, 1, (6,), float32)``.

====  ==========  ===========================================================
idx   name        meaning
====  ==========  ===========================================================
0     vx          body-frame forward velocity, fraction of ``max_speed`` (m/s)
1     vy          body-frame leftward velocity, fraction of ``max_speed`` (m/s)
2     omega       angular velocity, fraction of ``max_omega`` (rad/s, CCW +)
3     dribble     dribbler on when > 0
4     kick        kick strength k = value when > 0 (3-D ball speed k * kick_speed_max)
5     chip        (chip kicks only) kick elevation = value * ``chip_angle_max`` (rad)
                  when > 0, else a flat kick
====  ==========  ===========================================================

The resulting velocity is capped at ``max_speed`` in norm by the physics. Finite
values outside [-1, 1] are clipped; NaN or inf is refused (:func:`validate_actions`).
"""

from __future__ import annotations

import numpy as np

from ..physics.params import RobotParams

ACTION_DIM = 5
#: action length with chip kicks on (the chip entry appended)
CHIP_ACTION_DIM = 6


def action_dim(chip_kicks: bool) -> int:
    """Action length per agent: :data:`ACTION_DIM`, or :data:`CHIP_ACTION_DIM` with chip kicks."""
    return CHIP_ACTION_DIM if chip_kicks else ACTION_DIM


def fit_action(action: np.ndarray, dim: int) -> np.ndarray:
    """``action`` with ``dim`` entries: a 5-entry action in a chip env (``dim`` 6) gets a
    flat chip entry (0); an action of ``dim`` entries is returned as it is."""
    a = np.asarray(action, np.float32)
    if a.shape[-1] == dim:
        return a
    out = np.zeros(a.shape[:-1] + (dim,), np.float32)
    out[..., :a.shape[-1]] = a
    return out


def make_action(vx: float = 0.0, vy: float = 0.0, omega: float = 0.0, dribble: bool = False,
                kick: float = 0.0, chip: float | None = None) -> np.ndarray:
    """Build a normalised (5,) action, clipping each entry to [-1, 1]; with ``chip`` (the
    chip entry: elevation fraction of ``chip_angle_max``, <= 0 flat) a (6,) action."""
    entries = [vx, vy, omega, 1.0 if dribble else -1.0, kick if kick > 0 else -1.0]
    if chip is not None:
        entries.append(chip)
    return clip_unit(np.array(entries, dtype=np.float32).tolist())


def clip_unit(values: list[float]) -> np.ndarray:
    """``np.clip(np.float32(values), -1, 1)`` without numpy's per-call overhead (the same
    float32 values, NaN kept): the hot path of every action a tactic or skill builds."""
    return np.array([min(max(v, -1.0), 1.0) for v in values], dtype=np.float32)


def validate_actions(actions: np.ndarray, names: list[str]) -> None:
    """Raise ValueError naming the agent whose action row is not finite."""
    bad = ~np.isfinite(actions).all(axis=1)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise ValueError(f"action for agent {names[i]!r} contains NaN or inf: {actions[i].tolist()}")


def scale_actions(actions: np.ndarray, robot: RobotParams) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(n, 5) or (n, 6) normalised actions -> (v_body (n, 2) m/s, omega (n,) rad/s,
    dribble (n,) bool, kick (n,) in [0, 1]); a chip entry is read by :func:`chip_angles`.

    Values are clipped to [-1, 1] first (finite values only: validate before).
    """
    a = np.clip(actions[:, :ACTION_DIM], -1.0, 1.0)
    return (a[:, 0:2] * robot.max_speed, a[:, 2] * robot.max_omega, a[:, 3] > 0.0, np.maximum(a[:, 4], 0.0))


def chip_angles(actions: np.ndarray, robot: RobotParams) -> np.ndarray:
    """(n, 6) normalised actions -> (n,) kick elevations (rad): the chip entry (index 5),
    clipped to [-1, 1], times ``robot.chip_angle_max`` where it is > 0, else 0 (a flat
    kick). Finite values only: validate before."""
    return np.maximum(np.clip(actions[:, ACTION_DIM], -1.0, 1.0), 0.0) * robot.chip_angle_max
