"""GoToSpot(spot): stand on a spot the play sets every tick, facing the ball; SpotSupport:
it for the supporter on the spot the play rated best.

Team frame, metres. The play sets ``spot`` every tick (:class:`SpotSupport`: the
attacking plays' rated spots, :mod:`ssl_marl.plays.spot_rating`; the wall,
:mod:`ssl_marl.plays.wall`); the robot navigates there (around robots, out of the
defense areas) and faces the ball, so it is ready to receive. States: SEEK (more than
``arrive_tol`` m from the spot) and HOLD. :class:`SpotSupport`'s actions are the env's
6-entry chip layout (chip entry 0), :class:`GoToSpot`'s the 5-entry one.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

import numpy as np

from ..physics.state import WorldState
from ..skills.navigation import NavigateToPoint, NavParams, facing_towards
from .tactic_base import Tactic, check_field_point


class SpotState(enum.Enum):
    SEEK = "seek"
    HOLD = "hold"


@dataclass(frozen=True)
class GoToSpotParams:
    """Attributes: spot ((x, y) m, or None: stay), arrive_tol (m), tolerance_m (navigation,
    m), arrive_decel (m/s^2: the approach is capped at the speed that stops at the spot
    braking this hard, plus 0.2 m/s; None: the navigation's own profile)."""

    spot: tuple[float, float] | None = None
    arrive_tol: float = 0.15
    tolerance_m: float = 0.05
    arrive_decel: float | None = None


#: :class:`SpotSupport`'s parameters (the same as :class:`GoToSpot`'s)
SpotSupportParams = GoToSpotParams


@dataclass(frozen=True)
class SpotInputs:
    """Attributes: dist_to_spot (m)."""

    dist_to_spot: float


class GoToSpot(Tactic):
    """Go to the spot and face the ball (module docstring)."""

    name = "go_to_spot"
    State = SpotState
    Params = GoToSpotParams
    Inputs = SpotInputs
    initial_state = SpotState.SEEK

    def __init__(self, field, robot=None, ball=None, skills="baseline", dt: float = 1.0 / 60.0, **params) -> None:
        super().__init__(field, robot, ball, skills, dt, **params)
        self.nav = NavigateToPoint(field, self.rp, self.bp, NavParams(), tolerance=self.params.tolerance_m)

    def set_params(self, **changes) -> None:
        if changes.get("spot") is not None:
            changes["spot"] = check_field_point(f"{type(self).__name__}.spot", changes["spot"], self.field)
        super().set_params(**changes)

    def _spot(self, world: WorldState, robot: int) -> np.ndarray:
        s = self.params.spot
        return np.asarray(s, float) if s is not None else world.team(world.frame).pos[robot]

    def observe(self, world: WorldState, robot: int) -> SpotInputs:
        pos = world.team(world.frame).pos[robot]
        return SpotInputs(float(np.hypot(*(self._spot(world, robot) - pos))))

    @staticmethod
    def transition(state: SpotState, inputs: SpotInputs, params: GoToSpotParams) -> SpotState:
        if state is SpotState.SEEK:
            return SpotState.HOLD if inputs.dist_to_spot <= params.arrive_tol else SpotState.SEEK
        return SpotState.SEEK if inputs.dist_to_spot > 2.0 * params.arrive_tol else SpotState.HOLD

    def execute(self, world: WorldState, robot: int, inputs: SpotInputs) -> np.ndarray:
        pos = world.team(world.frame).pos[robot]
        self.nav.target = self._spot(world, robot)
        self.nav.facing = facing_towards(pos, world.ball_pos)
        decel = self.params.arrive_decel
        if decel is not None:
            self.nav.max_speed = float(np.sqrt(0.04 + 2.0 * decel * inputs.dist_to_spot))
        return self.nav.act(world, robot)


class SpotSupport(GoToSpot):
    """Go to the rated spot and face the ball (module docstring); 6-entry actions."""

    name = "spot_support"

    def act(self, world: WorldState, robot: int) -> np.ndarray:
        """:meth:`Tactic.act` with a flat chip entry appended: a (6,) float32 action."""
        return np.append(super().act(world, robot), np.float32(0.0))


__all__ = ["SpotState", "GoToSpotParams", "SpotSupportParams", "SpotInputs", "GoToSpot", "SpotSupport"]
