"""Ball clearing: the sub-behaviour the Goalie and the Defender share (team frame).

The go-to-ball skill (learned or baseline) fetches the ball; once it is within
``near_ball_m`` (the paper's 35 mm) of the dribbler the robot turns with the dribbler
on, at most ``turn_rate``, until its heading lies within ``kick_cone`` of +x (towards
the opponent half), then kicks (:func:`clear_kick_action`). A ball that drifts
further than ``BALL_LOST_DISTANCE`` (:mod:`ssl_marl.skills.features`, the skills' own
"ball lost" distance, a hysteresis over 35 mm) from the dribbler while turning is lost and
fetched again.

:func:`clear_phase` is the shared part of both tactics' state machines; each tactic
adds its own abort rules (the goalie gives up when the ball leaves its area, the
defender when the ball enters it or a teammate has it). :class:`BallClearing` holds
the go-to-ball skill and produces the action of each phase.
"""

from __future__ import annotations

import enum
from typing import Any, Protocol

import numpy as np

from ..physics.params import RobotParams
from ..physics.state import WorldState, wrap_angle
from ..skills.base import make_action
from ..skills.features import BALL_LOST_DISTANCE

CLEAR_TURN_GAIN = 6.0  # 1/s: omega = gain x heading error, then capped at turn_rate (hand-tuned, no overshoot)


class ClearParams(Protocol):
    """The clearing parameters a tactic's Params carry (GoalieParams, DefenderParams).

    near_ball_m: d_{d-b} (m) at which the ball counts as taken; kick_cone (rad);
    kick_strength (0..1]; turn_rate: turning rate with the ball (rad/s)."""

    near_ball_m: float
    kick_cone: float
    kick_strength: float
    turn_rate: float


class ClearPhase(enum.Enum):
    APPROACH = "approach"  # fetching the ball
    KICK = "kick"  # ball on the dribbler: turning to +x, then kicking
    DONE = "done"  # kicked last tick
    LOST = "lost"  # the ball got away while turning


def clear_phase(kicking: bool, d_db: float, kicked: bool, params: ClearParams) -> ClearPhase:
    """Next clearing phase from APPROACH (``kicking=False``) or KICK, given the
    dribbler-ball distance ``d_db`` (m) and whether the robot kicked last tick."""
    if not kicking:
        return ClearPhase.KICK if d_db <= params.near_ball_m else ClearPhase.APPROACH
    if kicked:
        return ClearPhase.DONE
    return ClearPhase.LOST if d_db > BALL_LOST_DISTANCE else ClearPhase.KICK


def clear_kick_action(world: WorldState, robot: int, rp: RobotParams, cone: float, strength: float,
                      turn_rate: float) -> np.ndarray:
    """Ball on the dribbler: kick at ``strength`` if the heading is within ``cone`` (rad)
    of +x and the kicker is ready, else turn towards +x at most ``turn_rate`` (rad/s)
    with the dribbler on."""
    ts = world.team(world.frame)
    h = float(ts.heading[robot])
    err = float(wrap_angle(-h))
    if abs(err) <= cone and bool(ts.kick_ready[robot]):
        return make_action(dribble=True, kick=strength)
    omega = min(max(CLEAR_TURN_GAIN * err, -turn_rate), turn_rate)
    return make_action(omega=omega / rp.max_omega, dribble=True)


class BallClearing:
    """Fetch-turn-kick actions over a go-to-ball skill (any object with ``act`` and
    ``reset``). ``reset()`` when a new approach starts."""

    def __init__(self, go_to_ball: Any, rp: RobotParams) -> None:
        self.go_to_ball = go_to_ball
        self.rp = rp

    def reset(self) -> None:
        self.go_to_ball.reset()

    def act(self, kicking: bool, world: WorldState, robot: int, params: ClearParams) -> np.ndarray:
        """The action of the APPROACH (``kicking=False``) or KICK phase."""
        if not kicking:
            return self.go_to_ball.act(world, robot)
        return clear_kick_action(world, robot, self.rp, params.kick_cone, params.kick_strength, params.turn_rate)
