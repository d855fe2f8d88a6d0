"""Keepaway 3v2 benchmark policies: :class:`AlwaysHoldPolicy` and the hand-coded keeper
(:class:`HandcodedKeepawayPolicy`), read from the keepers' observations
(:mod:`.observation`)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from .params import HOLD


class AlwaysHoldPolicy:
    """Keepaway benchmark: always ``hold``."""

    name = "always-hold"

    def reset(self, env: Any) -> None:
        pass

    def act(self, env: Any, agent: str, obs: np.ndarray, info: dict) -> int:
        return HOLD


@dataclass(frozen=True)
class HandcodedKeepawayParams:
    """The hand-coded keeper: hold while no taker is near, else pass to the most open
    teammate, scored as in Stone, Sutton and Kuhlmann's hand-coded keeper (4 x the
    teammate's distance to its nearest taker in metres + its lane angle in degrees, in
    their 20 m square), with distances scaled to our 5 m square (x 4).

    Attributes:
        hold_dist_m: hold while the nearest taker is farther than this from the ball
            holder (m). 2.0 m: a taker at 3 m/s covers ~1.5 m during the ~0.5 s a pass
            needs before the kick (turn, settle, the receiver's READY); picked among
            1.25 (the original 5 m / 4), 2.0, 2.5 and 3.0 m on 12 validation episodes
            (seeds 45000-45011; the differences were within their noise).
        dist_weight: per-teammate score = dist_weight x (its distance to its nearest
            taker, m) + (the smallest angle at the holder between it and a taker, deg).
        hold_score: None (default): when pressed always pass; a number:
            the original's score of holding (90), kept when no teammate scores higher.
    """

    hold_dist_m: float = 2.0
    dist_weight: float = 16.0
    hold_score: float | None = None


class HandcodedKeepawayPolicy:
    """Keepaway benchmark (see :class:`HandcodedKeepawayParams`): hold while the nearest
    taker is farther than ``hold_dist_m``; otherwise pass to the teammate with the best
    ``dist_weight * d + angle_deg`` (the observation's values; ties: the lower teammate),
    or hold if ``hold_score`` is set and higher."""

    name = "handcoded"

    def __init__(self, params: HandcodedKeepawayParams | None = None) -> None:
        self.params = params or HandcodedKeepawayParams()

    def reset(self, env: Any) -> None:
        pass

    def act(self, env: Any, agent: str, obs: np.ndarray, info: dict) -> int:
        p = self.params
        o = np.asarray(obs, float)
        if min(o[26], o[32]) > p.hold_dist_m:
            return HOLD
        best, best_score = HOLD, (-math.inf if p.hold_score is None else p.hold_score)
        for j in range(2):
            b = 12 + 6 * j
            s = p.dist_weight * o[b + 4] + math.degrees(o[b + 5])
            if s > best_score:
                best, best_score = 1 + j, s
        mask = np.asarray(info.get("action_mask", np.ones(3)))
        return best if mask[best] else HOLD


__all__ = ["AlwaysHoldPolicy", "HandcodedKeepawayParams", "HandcodedKeepawayPolicy"]
