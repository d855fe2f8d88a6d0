"""Shot lines rated by who reaches them first: where in the goal mouth to shoot.

Team frame (opponent goal at +x), metres, seconds, m/s. Pure functions of positions.

A shot kicked from the ball at ``p`` towards a point ``g_j`` on the opponent goal line
(``x = L/2``, ``|y| <= goal_width / 2 - inset``) is rated by its **path margin**
(:func:`~ssl_marl.plays.pass_decision.path_margins`, the passes' interception model): the
smallest, over the opponents and over samples along the straight path, of the time an
opponent needs to put its body on the sample (``reaction_s`` plus the motion from rest at
the robot's acceleration and top speed) less the time the ball needs to get there (the
two-phase ball model at ``shot_speed``). A line that passes within robot + ball radius of
a teammate is blocked (margin ``-inf``). The best line is the one with the largest margin:
the goalie and the defenders standing on the ball-goal line cover the centre and must move
to reach a corner, and a shot at the line they reach last is the one they save least
(TIGERs rate goal-kick targets by the keeper's and defenders' reach times, Sumatra's
"best goal kick rater"; docs/references.md, "Passing and pass rating").

The geometric alternative (:func:`~ssl_marl.plays.pass_decision.open_goal_interval`) only
knows shadows: with two defenders and a goalie on the ball-goal line the mouth is shut
from almost everywhere (docs/RESULTS.md, section 12: 57 of 62 shots left with < 0.05 rad
open), and a shut mouth gives no direction at all.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from ..physics.field import FieldGeometry
from ..physics.params import BallParams, RobotParams
from .pass_decision import DecisionParams, path_margins

#: reaction time (s) of the goalie and defenders in the shot-line rating: our own defence
#: follows the ball's path every tick (``goalie_guard_position``), so less than the
#: passes' 0.3 s (a robot must first turn its plan around); one tenth of a second for the
#: motors to respond and the ball to leave the dribbler
SHOT_REACTION_S = 0.1


def goal_line_targets(field: FieldGeometry, n: int = 21, inset_m: float = 0.05) -> np.ndarray:
    """(n, 2) points on the +x goal line from the right post to the left, ``inset_m`` (m)
    inside each post (the ball's radius and a little more)."""
    if n < 2:
        raise ValueError(f"goal_line_targets: n must be >= 2, got {n!r}")
    hw = field.goal_width / 2.0 - inset_m
    if hw <= 0:
        raise ValueError(f"goal_line_targets: inset_m {inset_m!r} leaves no goal mouth")
    y = np.linspace(-hw, hw, n)
    return np.stack([np.full(n, field.half_length), y], axis=1)


def blocked_by(start: np.ndarray, ends: np.ndarray, blockers: np.ndarray, reach: float) -> np.ndarray:
    """(K,) True where the segment ``start -> ends[k]`` passes within ``reach`` (m) of any
    blocker (B, 2) ahead of the start."""
    e = np.asarray(ends, float).reshape(-1, 2)
    b = np.asarray(blockers, float).reshape(-1, 2)
    if b.shape[0] == 0:
        return np.zeros(e.shape[0], bool)
    s = np.asarray(start, float).reshape(1, 2)
    d = e - s  # (K, 2)
    L2 = np.maximum((d * d).sum(axis=1), 1e-12)[:, None]  # (K, 1)
    rel = b[None, :, :] - s[:, None, :]  # (1, B, 2)
    t = (rel * d[:, None, :]).sum(axis=2) / L2  # (K, B)
    ahead = t > 0.0
    t = np.clip(t, 0.0, 1.0)
    closest = s[:, None, :] + t[..., None] * d[:, None, :]
    dist = np.hypot(*(b[None, :, :] - closest).transpose(2, 0, 1))
    return ((dist < reach) & ahead).any(axis=1)


def shot_line_margins(p: np.ndarray, targets: np.ndarray, opponents: np.ndarray, teammates: np.ndarray,
                      rp: RobotParams, bp: BallParams, params: DecisionParams, reaction_s: float) -> np.ndarray:
    """(K,) path margin (s) of a shot from ``p`` to each target (K, 2) at
    ``params.shot_speed``, the opponents (O, 2) reacting after ``reaction_s``; ``-inf``
    where a teammate (T, 2) stands in the line (module docstring)."""
    tg = np.asarray(targets, float).reshape(-1, 2)
    rated = dataclasses.replace(params, opp_reaction_s=float(reaction_s))
    speeds = np.full(tg.shape[0], min(float(params.shot_speed), float(rp.kick_speed_max)))
    m = path_margins(p, tg, speeds, opponents, rp, bp, rated)
    return np.where(blocked_by(p, tg, teammates, rp.radius + bp.radius), -np.inf, m)


def best_shot_line(p: np.ndarray, opponents: np.ndarray, teammates: np.ndarray, field: FieldGeometry,
                   rp: RobotParams, bp: BallParams, params: DecisionParams, reaction_s: float = SHOT_REACTION_S,
                   n: int = 21) -> tuple[np.ndarray, float]:
    """(target (2,), margin (s)) of the best of ``n`` shot lines from ``p`` (module docstring)."""
    t = goal_line_targets(field, n)
    m = shot_line_margins(p, t, opponents, teammates, rp, bp, params, reaction_s)
    k = int(np.argmax(m))
    return t[k], float(m[k])


def heading_goal_point(p: np.ndarray, heading: float, field: FieldGeometry, inset_m: float = 0.02) -> np.ndarray | None:
    """Where a kick from ``p`` along ``heading`` (rad) crosses the +x goal line, or None
    when it does not cross it inside the mouth (``inset_m`` inside the posts) or points
    away from the goal."""
    c = math.cos(heading)
    dx = field.half_length - float(p[0])
    if c <= 1e-6 or dx <= 0:
        return None
    y = float(p[1]) + dx * math.tan(heading)
    if abs(y) > field.goal_width / 2.0 - inset_m:
        return None
    return np.array([field.half_length, y])


__all__ = ["SHOT_REACTION_S", "goal_line_targets", "blocked_by", "shot_line_margins", "best_shot_line",
           "heading_goal_point"]
