"""Redirect(receive point, target): meet the pass and kick it on toward the goal in one touch.

:class:`~ssl_marl.plays.receive_tactic.Receive` with a ``redirect_target`` (m, team
frame, a point inside the open goal interval; None: an ordinary reception). With a
target the states mean:

* POSITION / READY: the robot stands so that its kicker face (``front_distance`` +
  ball radius ahead of its centre) is on the receive point, its heading pointing at the
  target (a kick leaves along the heading); READY as in Receive, the heading measured
  against the target direction;
* RECEIVING (ball incoming): the redirect skill runs (learned or baseline,
  :mod:`ssl_marl.plays.skillset`; :mod:`ssl_marl.skills.redirect`): it chooses its
  aim point in the open part of the goal mouth and the contact point on the ball's
  path, puts the face there turned towards the aim and keeps the kicker armed (in a
  chip env the robots kick on contact, so the kicker fires when the ball reaches the
  face). POSITION / READY do not run it: its contact planner needs a ball moving
  towards the robot, and before the pass the robot only has to stand ready;
* CONTROLLED: the ball left the robot faster than ``redirected_speed`` towards the
  target half-plane (the redirect is done; the play ends the pass); FETCH / FAILED as
  in Receive (a ball that stops short is fetched).

The deflection (angle at the receive point between the passer and the target) should
stay under 0.9 rad (TIGERs' redirect rating; docs/references.md, "Passing and pass
rating"); the play only chooses redirects that do
(:mod:`~ssl_marl.plays.attack_decision`). Actions are the env's 6-entry chip layout
(chip entry 0).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..physics.state import WorldState, wrap_angle
from ..skills.navigation import facing_towards
from .receive_tactic import Receive, ReceiveInputs, ReceiveParams, ReceiveState
from .tactic_base import check_field_point


@dataclass(frozen=True)
class RedirectParams(ReceiveParams):
    """:class:`~ssl_marl.plays.receive_tactic.ReceiveParams` and:

    Attributes:
        redirect_target: (x, y) the play's aim point of the one-touch shot (m), or None
            (receive); the robot faces it while it waits, and a ball leaving towards
            its half-plane is redirected (the skill picks the exact aim at contact).
        redirected_speed: the ball moving away faster than this (m/s) ends the redirect.
    """

    redirect_target: tuple[float, float] | None = None
    redirected_speed: float = 2.0


@dataclass(frozen=True)
class RedirectInputs(ReceiveInputs):
    """:class:`~ssl_marl.plays.receive_tactic.ReceiveInputs` and ``redirected`` (the ball
    leaves the robot towards the target, faster than ``redirected_speed``)."""

    redirected: bool = False


class Redirect(Receive):
    """Receive a pass, or with a ``redirect_target`` kick it on in one touch (module docstring)."""

    name = "redirect"
    Params = RedirectParams
    Inputs = RedirectInputs
    uses_skills = ("go_to_ball", "receive", "redirect")

    def __init__(self, *args, **kwargs) -> None:
        self.redirect_skill = None
        super().__init__(*args, **kwargs)
        self.redirect_skill = self._skill("redirect")

    def _running_skill(self):
        if self.params.redirect_target is not None and self.state is ReceiveState.RECEIVING:
            return self.redirect_skill
        return super()._running_skill()

    def set_params(self, **changes) -> None:
        """As :meth:`Receive.set_params`; ``redirect_target`` must be two finite numbers."""
        if changes.get("redirect_target") is not None:
            changes["redirect_target"] = check_field_point("Redirect.redirect_target", changes["redirect_target"],
                                                           None)
        super().set_params(**changes)

    def _heading(self, pos: np.ndarray) -> float:
        return facing_towards(pos, np.asarray(self.params.redirect_target, float))

    def _face_offset(self) -> float:
        return self.rp.front_distance + self.bp.radius

    def observe(self, world: WorldState, robot: int) -> RedirectInputs:
        base = super().observe(world, robot)
        p = self.params
        if p.redirect_target is None:
            return RedirectInputs(**vars(base))
        ts = world.team(world.frame)
        pos, h = ts.pos[robot], float(ts.heading[robot])
        point = np.asarray(p.receive_point, float) if p.receive_point is not None else pos
        want = self._heading(point)
        centre = point - self._face_offset() * np.array([math.cos(want), math.sin(want)])
        rel = np.asarray(world.ball_pos, float) - pos
        vel = np.asarray(world.ball_vel, float)
        sp = float(np.hypot(*vel))
        away = sp > p.redirected_speed and float(rel @ vel) > 0.0 and float(np.hypot(*rel)) < 1.0 and \
            math.cos(math.atan2(vel[1], vel[0]) - want) > 0.5
        values = dict(vars(base))
        values.update(dist_to_point=float(np.hypot(*(centre - pos))), face_err=abs(wrap_angle(want - h)),
                      redirected=bool(away))
        return RedirectInputs(**values)

    @staticmethod
    def transition(state: ReceiveState, inputs: RedirectInputs, params: RedirectParams) -> ReceiveState:
        if params.redirect_target is not None and state in (ReceiveState.RECEIVING, ReceiveState.READY,
                                                            ReceiveState.POSITION) and inputs.redirected:
            return ReceiveState.CONTROLLED
        if params.redirect_target is not None and state is ReceiveState.RECEIVING:
            if inputs.ball_speed < params.fetch_speed and not inputs.on_dribbler:
                return ReceiveState.FETCH
            return ReceiveState.FAILED if inputs.time_in_state > params.give_up_s else state
        return Receive.transition(state, inputs, params)

    def execute(self, world: WorldState, robot: int, inputs: RedirectInputs) -> np.ndarray:
        p, S = self.params, ReceiveState
        if p.redirect_target is None or self.state not in (S.POSITION, S.READY, S.RECEIVING):
            return super().execute(world, robot, inputs)
        if self.state is S.RECEIVING:
            return self.redirect_skill.act(world, robot)
        point = np.asarray(p.receive_point, float) if p.receive_point is not None \
            else world.team(world.frame).pos[robot]
        want = self._heading(point)
        self.nav.target = point - self._face_offset() * np.array([math.cos(want), math.sin(want)])
        self.nav.facing = want
        self.nav.dribble = False
        return self.nav.act(world, robot)

    def act(self, world: WorldState, robot: int) -> np.ndarray:
        """:meth:`Receive.act` with a flat chip entry appended: a (6,) float32 action."""
        return np.append(super().act(world, robot), np.float32(0.0))


__all__ = ["RedirectParams", "RedirectInputs", "Redirect"]
