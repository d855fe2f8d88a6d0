"""The passing game's plays: the ball carrier chooses shoot, pass or keep each tick.

:func:`passing_plays` builds one :class:`~ssl_marl.plays.pass_coordinator.PassCoordinator`
(the team's pass plan and the carrier's decision, with the handshake between passer and
receiver) and the plays that share it through their roles
(:mod:`ssl_marl.plays.passing_roles`):

* ``restart`` (priority 1: the ball rests at the centre mark or at a free-kick spot near
  a line; the carrier is biased towards passing:
  :data:`~ssl_marl.plays.pass_coordinator.RESTART_DECISION`);
* ``offense_passing`` (applicable like ``offense``, and while a plan is running so that a
  pass in flight is not dropped);
* the standard ``defense``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..physics.params import BallParams
from .pass_coordinator import CarrierDecider, PassCoordinator, PassingParams
from .passing_roles import passing_roles
from .play import HAS_BALL_MARGIN_S, Play, PlayContext, defense_play, offense_applicable

RESTART_LINE_BAND_M = 0.35  # a resting ball this close to a field line is at a free-kick spot (placed 0.2 m in)


def restart_applicable(ctx: PlayContext) -> bool:
    """A restart we can take: the ball rests (< 0.1 m/s) and nobody holds it, and either
    the referee gave us the kickoff / free kick (``ctx.set_piece``) or, without referee
    commands, the ball lies at the centre mark (kickoff) or within
    ``RESTART_LINE_BAND_M`` of a field line (the placement after an out), nobody is
    within 0.3 m of it, and we are at least as close as they are (+0.25 s)."""
    w, f = ctx.world, ctx.field
    if float(np.hypot(*w.ball_vel)) >= 0.1 or ctx.we_have_ball or ctx.they_have_ball:
        return False
    if ctx.set_piece:
        return True
    b = ctx.ball
    at_mark = float(np.hypot(*b)) < 0.15
    near_line = (f.half_length - abs(float(b[0])) < RESTART_LINE_BAND_M
                 or f.half_width - abs(float(b[1])) < RESTART_LINE_BAND_M)
    near = min(ctx.our_time, ctx.their_time) * ctx.robot.max_speed
    return (at_mark or near_line) and near > 0.3 and ctx.our_time <= ctx.their_time + HAS_BALL_MARGIN_S


def passing_plays(params: PassingParams | None = None, ball: BallParams | None = None,
                  decider: CarrierDecider | None = None) -> tuple[Play, ...]:
    """(restart, offense_passing, defense) sharing one new
    :class:`~ssl_marl.plays.pass_coordinator.PassCoordinator` (:func:`coordinator_of`
    finds it) whose carrier decision is ``decider`` (default
    :class:`~ssl_marl.plays.pass_coordinator.CostDecider`)."""
    coord = PassCoordinator(params, ball, decider)
    roles = passing_roles(coord)

    def offense_passing_applicable(ctx: PlayContext) -> bool:
        return coord.active or offense_applicable(ctx)

    restart = Play("restart", restart_applicable, roles, priority=1, prepare=PrepareHook(coord, restart=True))
    offense = Play("offense_passing", offense_passing_applicable, roles, prepare=PrepareHook(coord))
    return (restart, offense, defense_play())


@dataclass(frozen=True)
class PrepareHook:
    """``Play.prepare`` of the passing plays: runs the shared coordinator's tick."""

    coordinator: PassCoordinator
    restart: bool = False

    def reset(self) -> None:
        """A new episode: the coordinator's plan is forgotten."""
        self.coordinator.reset()

    def __call__(self, ctx: PlayContext) -> None:
        self.coordinator.prepare(ctx, restart=self.restart)


def coordinator_of(plays) -> PassCoordinator | None:
    """The coordinator of a :func:`passing_plays` tuple (None for other plays)."""
    for p in plays:
        c = getattr(p.prepare, "coordinator", None)
        if c is not None:
            return c
    return None


__all__ = ["passing_plays", "coordinator_of", "restart_applicable", "PrepareHook", "RESTART_LINE_BAND_M"]
