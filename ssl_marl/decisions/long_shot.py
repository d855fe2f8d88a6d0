"""The long-shot rule on a learned attacking decision's legal options.

The attack drill (:mod:`ssl_marl.decisions.attack_drill`) is played on half a Division B field,
so its actors never learned what a shot from farther out is worth. With the ball farther than
:data:`LONG_SHOT_MASK_M` (default None: off) from the opponent goal centre, the match's learned decider
(:class:`~ssl_marl.decisions.match_decider.PolicyAttackDecider`) and the full-match task
(:class:`~ssl_marl.decisions.attack_match.AttackMatchEnv`) offer the shot only when no other
option is legal: one rule for both, so what is trained is what plays.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..physics.field import FieldGeometry
from .dribble_limit import check_distance_m

#: m: with the ball farther than this from the opponent goal centre, a learned attacking
#: decider offers the shot only when no other option is legal (:func:`limit_long_shots`).
#: The drill's half of a Division B field lies within 5.4 m of the goal centre. None (the
#: default): the shot always offered; with 6 m, matches on the same new seeds scored exactly as
#: many goals on both divisions and conceded a few more (docs/RESULTS.md, "Division A: long
#: shots"). Read when a decider or the full-match task is built
#: (:func:`~ssl_marl.decisions.match_decider.make_match_decider`).
LONG_SHOT_MASK_M: float | None = None


def check_long_shot_m(value: Any, where: str) -> float | None:
    """``value`` as a long-shot distance (m): None or finite and > 0; ValueError naming ``where`` otherwise."""
    return check_distance_m(value, where, "long_shot_m", allow_zero=False)


def limit_long_shots(mask: np.ndarray, ball: np.ndarray, field: FieldGeometry, shoot_option: int,
                     max_m: float | None) -> tuple[np.ndarray, bool]:
    """The long-shot rule on a learned decision's legal options: with the ball (team frame, m)
    farther than ``max_m`` from the opponent goal centre ``(field.half_length, 0)`` the
    ``shoot_option`` is masked, unless it is the only legal option. Returns (mask, whether it
    masked); ``mask`` is not modified. ``max_m`` None: unchanged."""
    if max_m is None or not mask[shoot_option] or int(np.count_nonzero(mask)) <= 1:
        return mask, False
    if math.hypot(float(ball[0]) - field.half_length, float(ball[1])) <= max_m:
        return mask, False
    mask = mask.copy()
    mask[shoot_option] = 0
    return mask, True


__all__ = ["LONG_SHOT_MASK_M", "check_long_shot_m", "limit_long_shots"]
