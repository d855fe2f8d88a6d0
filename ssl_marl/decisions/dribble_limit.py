"""SSL's dribbling limit on a learned carrier decision's legal options.

The SSL rules call a dribble of more than 1 m (``excessive_dribbling``,
:mod:`ssl_marl.envs.game_control`). A learned decision of the attacking plays is not offered
its dribble options once the carrier has dribbled :data:`DRIBBLE_MASK_M` in its current
dribble (:attr:`~ssl_marl.plays.play.PlayContext.dribbled_m`, as the referee measures it):
the match's policy deciders (:mod:`.match_decider`) and the attack drill under SSL rules
(``attack-drill-ssl``, :mod:`.attack_drill`) apply the same rule, so what is trained is what
plays.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..plays.pass_coordinator import CarrierRequest

#: m: a learned attacking decider stops offering dribbles from this dribble distance on
#: (a dribble option carries the ball about 0.3 m; SSL's limit is 1 m)
DRIBBLE_MASK_M = 0.5


def check_distance_m(value: Any, where: str, name: str, allow_zero: bool = True) -> float | None:
    """``value`` as an optional distance (m): None, or finite and >= 0 (> 0 unless
    ``allow_zero``); ValueError naming ``where`` and the parameter ``name`` otherwise."""
    if value is not None and not (isinstance(value, (int, float)) and not isinstance(value, bool)
                                  and math.isfinite(value) and (value >= 0 if allow_zero else value > 0)):
        raise ValueError(f"{where}: {name} must be None or a finite distance {'>=' if allow_zero else '>'} 0 (m), "
                         f"got {value!r}")
    return value


def check_dribble_mask_m(value: Any, where: str) -> float | None:
    """``value`` as a dribble-mask distance (m): None or finite and >= 0; ValueError naming ``where`` otherwise."""
    return check_distance_m(value, where, "dribble_mask_m")


def limit_dribbles(mask: np.ndarray, request: CarrierRequest, dribble_options: tuple[int, ...],
                   mask_m: float | None) -> tuple[np.ndarray, bool]:
    """SSL's dribbling limit on a learned decision's legal options: once the carrier has
    dribbled the ball ``mask_m`` or more in its current dribble
    (:attr:`~ssl_marl.plays.play.PlayContext.dribbled_m`, as the referee measures it), the
    ``dribble_options`` are masked (shoot stays legal). Returns (mask, whether it masked);
    ``mask`` is not modified."""
    dribbled = request.ctx.dribbled_m
    if mask_m is None or dribbled is None or float(dribbled[request.carrier]) < mask_m:
        return mask, False
    mask = mask.copy()
    mask[list(dribble_options)] = 0
    return mask, True


__all__ = ["DRIBBLE_MASK_M", "check_distance_m", "check_dribble_mask_m", "limit_dribbles"]
