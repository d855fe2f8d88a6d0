"""ChipPass(target robot): the passer of the attacking plays, flat or chipped.

The state machine, handshake and flat kick are :class:`~ssl_marl.plays.pass_tactic.Pass`'s
(GET_BALL -> HOLD -> KICK -> DONE / FAILED; module :mod:`~ssl_marl.plays.pass_tactic`).
With ``chip`` set (the play's decision chose a chip pass) the KICK state runs the
chip-pass skill instead of the pass skill (learned or baseline,
:mod:`ssl_marl.plays.skillset`; :mod:`ssl_marl.skills.chip_pass`), told the same target
point: the skill turns with the ball and chooses the chip's speed and elevation over
the robot standing in the lane itself (the hand-coded skill passes flat where no chip
fits). The skill's status ends KICK as the pass skill's does. A set piece's chip
(``strike``) is the hand-coded chip of :func:`~ssl_marl.skills.chip_pass.lane_chip`,
kicked from behind the ball without the dribbler (:meth:`ChipPass.strike_kick`).

Actions are the env's 6-entry chip layout (``parallel_env(chip_kicks=True)``; index 5
the chip, 0 for a flat kick): the tactic runs only in a chip env.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..physics.state import WorldState
from ..skills.chip_pass import lane_chip
from .pass_tactic import Pass, PassParams, PassState


@dataclass(frozen=True)
class ChipPassParams(PassParams):
    """:class:`~ssl_marl.plays.pass_tactic.PassParams` and:

    Attributes:
        chip: KICK runs the chip-pass skill (False: a flat pass by the pass skill).
        chip_arrive_speed: the STRIKE's chip is one the receiver can take on its dribbler,
            no faster than this (m/s) at its face (:func:`~ssl_marl.skills.chip_pass.lane_chip`'s
            ``arrive_speed_max``); None: the shortest-flight chip.
    """

    chip: bool = False
    chip_arrive_speed: float | None = None


class ChipPass(Pass):
    """Pass the ball flat or chipped (module docstring); 6-entry actions."""

    name = "chip_pass"
    Params = ChipPassParams
    uses_skills = ("go_to_ball", "pass", "chip_pass")

    def __init__(self, *args, **kwargs) -> None:
        self._chip = 0.0
        super().__init__(*args, **kwargs)
        self.chip_skill = self._skill("chip_pass")

    def kick_skill(self):
        """The skill the KICK state runs: the chip-pass skill with ``chip`` set, else the pass skill."""
        return self.chip_skill if self.params.chip else self.pass_skill

    def strike_kick(self, world: WorldState) -> tuple[float, float]:
        """The set piece's STRIKE (:meth:`Pass.strike_kick`): with ``chip`` set, the
        hand-coded chip over the lane's blocker (:func:`~ssl_marl.skills.chip_pass.lane_chip`:
        speed and elevation; ``chip_arrive_speed``), flat where no chip fits."""
        if self.params.chip:
            c = lane_chip(world.ball_pos, np.asarray(self.params.target_point, float),
                          world.opponents(world.frame).pos, self.rp, self.bp,
                          arrive_speed_max=self.params.chip_arrive_speed)
            if c is not None:
                return min(c.speed / self.rp.kick_speed_max, 1.0), c.angle / self.rp.chip_angle_max
        return super().strike_kick(world)

    def execute(self, world: WorldState, robot: int, inputs) -> np.ndarray:
        a = np.asarray(super().execute(world, robot, inputs), dtype=np.float32)
        if self.state is PassState.STRIKE:
            self._chip = self.strike_chip
        else:
            self._chip = float(a[5]) if a.shape == (6,) else 0.0
        return a[:5]

    def act(self, world: WorldState, robot: int) -> np.ndarray:
        """:meth:`Pass.act` with the chip entry appended: a (6,) float32 action."""
        a = super().act(world, robot)
        return np.append(a, np.float32(self._chip if a[4] > 0.0 else 0.0))


__all__ = ["ChipPassParams", "ChipPass"]
