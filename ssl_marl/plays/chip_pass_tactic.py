"""ChipPass(target robot): the passer of the attacking plays, flat or chipped.

The state machine, handshake and flat kick are :class:`~ssl_marl.plays.pass_tactic.Pass`'s
(GET_BALL -> HOLD -> KICK -> DONE / FAILED; module :mod:`~ssl_marl.plays.pass_tactic`).
With ``chip_angle`` > 0 the KICK state kicks the ball itself instead of running the
pass skill: it keeps the ball on the dribbler and turns until its heading points at
``target_point`` within ``chip_align_tol`` (a chip flies along the heading), then kicks
with the 3-D speed ``chip_speed`` (m/s, the kick entry ``chip_speed / kick_speed_max``)
and the elevation ``chip_angle`` (rad, the chip entry ``chip_angle / chip_angle_max``).
The play chooses both from the flight model so that the first bounce lands short of
the receiver (:func:`~ssl_marl.plays.attack_decision.chip_kick`).

Actions are the env's 6-entry chip layout (``parallel_env(chip_kicks=True)``; index 5
the chip, 0 for a flat kick): the tactic runs only in a chip env.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..physics.state import WorldState, wrap_angle
from ..skills.motion import velocity_command
from ..skills.navigation import facing_towards
from .pass_tactic import Pass, PassParams, PassState


@dataclass(frozen=True)
class ChipPassParams(PassParams):
    """:class:`~ssl_marl.plays.pass_tactic.PassParams` and:

    Attributes:
        chip_angle: kick elevation (rad; 0: a flat pass by the pass skill).
        chip_speed: 3-D kick speed of the chip (m/s).
        chip_align_tol: the chip is kicked with the heading this close to the target (rad).
        chip_turn_rate: turn rate while aiming the chip (rad/s).
    """

    chip_angle: float = 0.0
    chip_speed: float = 0.0
    chip_align_tol: float = 0.04
    chip_turn_rate: float = 3.0


class ChipPass(Pass):
    """Pass the ball flat or chipped (module docstring); 6-entry actions."""

    name = "chip_pass"
    Params = ChipPassParams

    def __init__(self, *args, **kwargs) -> None:
        self._chip = 0.0
        super().__init__(*args, **kwargs)

    def execute(self, world: WorldState, robot: int, inputs) -> np.ndarray:
        p = self.params
        self._chip = 0.0
        if self.state is not PassState.KICK or p.chip_angle <= 0.0 or p.target_point is None:
            return super().execute(world, robot, inputs)
        ts = world.team(world.frame)
        err = wrap_angle(facing_towards(ts.pos[robot], np.asarray(p.target_point, float)) - float(ts.heading[robot]))
        if abs(err) > p.chip_align_tol:
            omega = float(np.clip(p.hold_turn_gain * err, -p.chip_turn_rate, p.chip_turn_rate))
            return velocity_command(world, robot, np.zeros(2), omega, self.rp, dribble=True)
        self._chip = min(p.chip_angle / self.rp.chip_angle_max, 1.0)
        kick = min(p.chip_speed / self.rp.kick_speed_max, 1.0)
        return velocity_command(world, robot, np.zeros(2), 0.0, self.rp, dribble=False, kick=kick)

    def act(self, world: WorldState, robot: int) -> np.ndarray:
        """:meth:`Pass.act` with the chip entry appended: a (6,) float32 action."""
        a = super().act(world, robot)
        return np.append(a, np.float32(self._chip if a[4] > 0.0 else 0.0))


__all__ = ["ChipPassParams", "ChipPass"]
