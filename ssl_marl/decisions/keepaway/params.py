"""Keepaway 3v2: the keepers' options and the behaviour parameters of keepers and takers.

Options (indices of ``KeepawayEnv.option_names``): :data:`HOLD`, :data:`PASS1`
(pass to teammate ``(i + 1) % 3``), :data:`PASS2` (to ``(i + 2) % 3``); the phases of
the observation's one-hot: :data:`PHASES`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

HOLD, PASS1, PASS2 = 0, 1, 2
PHASES = ("hold", "pass", "loose")


@dataclass(frozen=True)
class KeepawayParams:
    """Behaviour parameters of the keepers' options and fixed behaviours, and the takers.

    Attributes:
        hold_s: duration of one hold option (s).
        hold_turn_rate: max turn rate while holding (rad/s).
        hold_alpha: max change of the turn rate while holding (rad/s^2).
        hold_speed: drift speed while holding (m/s).
        control_m: keeper control: d_{d-b} at most this (m) ...
        control_rel_speed: ... ball speed relative to the robot at most this (m/s) ...
        control_ticks: ... for this many ticks in a row.
        receive_inset_m: receive points are clamped this far inside the square (m).
        getopen_inset_m: the get-open grid lies this far inside the square (m).
        getopen_grid: grid points per side.
        getopen_replan_s: get-open spots are re-planned this often (s).
        fetch_touch_speed: keepers' go-to-ball governor speed at contact (m/s).
        takers: the takers' policy: "press" (both go for the ball, the default) or
            "block" (the second taker blocks a pass lane; see :mod:`.takers`).
        press_m: the presser's spot, this far beyond a holding keeper's centre on the far
            side from the chaser (m; robot diameter 0.18 m + 2 cm: the ball, on the
            keeper's dribbler when it faces that way, is then pressed against the presser).
        block_fraction: ("block") the blocking taker stands this far along the lane (fraction).
        block_min_m: ... at least this far from the ball (m).
        pass_arrival_speed: the Pass tactic's ``arrival_speed`` (m/s): the pass skill
            picks the kick speed from the ball model so the ball reaches the receiver
            at this speed (TIGERs cap arrivals at 3.2 m/s; the tactic's default 2 m/s
            lets a 3 m/s taker catch a 4 m pass, see docs/DESIGN.md).
        positioning_every: the positioning commands (get-open keepers, the blocking
            taker: navigation without the ball) are recomputed every this many ticks and
            repeated in between (2: at 30 Hz; a third of the per-tick Python time).
        skills: the tactics' skill source ("baseline" or "learned", see plays/skillset).
    """

    hold_s: float = 0.2
    hold_turn_rate: float = 2.0
    hold_alpha: float = 20.0
    hold_speed: float = 0.5
    control_m: float = 0.035
    control_rel_speed: float = 0.5
    control_ticks: int = 3
    receive_inset_m: float = 0.4
    getopen_inset_m: float = 0.6
    getopen_grid: int = 5
    getopen_replan_s: float = 0.2
    fetch_touch_speed: float = 0.8
    takers: str = "press"
    press_m: float = 0.2
    block_fraction: float = 0.4
    block_min_m: float = 0.6
    pass_arrival_speed: float = 3.0
    positioning_every: int = 2
    skills: str = "baseline"

    def __post_init__(self) -> None:
        for f in fields(self):
            v = getattr(self, f.name)
            if f.name == "skills":
                if v not in ("baseline", "learned"):
                    raise ValueError(f"KeepawayParams.skills must be 'baseline' or 'learned', got {v!r}")
            elif f.name == "takers":
                if v not in ("press", "block"):
                    raise ValueError(f"KeepawayParams.takers must be 'press' or 'block', got {v!r}")
            elif f.name in ("control_ticks", "getopen_grid", "positioning_every"):
                if not isinstance(v, int) or isinstance(v, bool) or v < 1:
                    raise ValueError(f"KeepawayParams.{f.name} must be a positive integer, got {v!r}")
            elif not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise ValueError(f"KeepawayParams.{f.name} must be a positive finite number, got {v!r}")


__all__ = ["HOLD", "PASS1", "PASS2", "PHASES", "KeepawayParams"]
