"""Receive(expected ball line): stand on the pass line, report ready, take the ball.

The expected ball line runs from ``ball_from`` (the passer's ball, m) to
``receive_point`` (where the play wants the ball taken, m); both team frame, set by the
play every tick. State machine::

    POSITION --(at the point, facing the ball, nearly stopped)--> READY
    POSITION, READY --(ball incoming)--> RECEIVING
    READY --(pushed more than 2 x ready_tol_m off the point)--> POSITION
    RECEIVING --(receive skill SUCCEEDED: ball controlled 0.5 s)--> CONTROLLED
    RECEIVING --(ball nearly stopped, not on the dribbler)--> FETCH
    RECEIVING --(skill FAILED, or give_up_s passed)--> FAILED
    FETCH --(go-to-ball SUCCEEDED: ball on the dribbler)--> CONTROLLED
    FETCH --(give_up_s passed)--> FAILED
    CONTROLLED, FAILED: terminal until reset

"Ball incoming": the ball moves faster than ``incoming_speed`` towards the robot and
its straight path passes within ``line_tol_m`` of the robot centre. RECEIVING runs the
receive skill (learned or baseline), which moves onto the ball's predicted line, faces
it, runs the dribbler and cushions; FETCH covers a pass that stops short (the go-to-ball
skill fetches the resting ball). READY is the handshake the passer waits for; the play
reads it from :attr:`status`.
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass

import numpy as np

from ..physics.state import WorldState, wrap_angle
from ..skills.base import SkillStatus, make_action
from ..skills.navigation import NavigateToPoint, NavParams, facing_towards
from .tactic_base import Tactic, check_field_point, skill_status


class ReceiveState(enum.Enum):
    POSITION = "position"
    READY = "ready"
    RECEIVING = "receiving"
    FETCH = "fetch"
    CONTROLLED = "controlled"
    FAILED = "failed"


@dataclass(frozen=True)
class ReceiveParams:
    """Attributes:
        receive_point: (x, y) where to take the ball (m, team frame), or None (hold still).
        ball_from: (x, y) where the ball will come from (m), or None (the ball's position).
        ready_tol_m: READY within this distance of the receive point (m).
        ready_face_tol: ... and heading within this of the ball direction (rad).
        ready_speed: ... and slower than this (m/s).
        incoming_speed: a ball faster than this (m/s) moving towards us is a pass.
        line_tol_m: ... if its straight path passes within this of the robot (m).
        fetch_speed: in RECEIVING, a ball slower than this (m/s) that is not on the
            dribbler is fetched (FETCH).
        give_up_s: RECEIVING / FETCH longer than this -> FAILED (s).
    """

    receive_point: tuple[float, float] | None = None
    ball_from: tuple[float, float] | None = None
    ready_tol_m: float = 0.15
    ready_face_tol: float = 0.35
    ready_speed: float = 0.4
    incoming_speed: float = 0.5
    line_tol_m: float = 1.0
    fetch_speed: float = 0.3
    give_up_s: float = 3.0


@dataclass(frozen=True)
class ReceiveInputs:
    """Attributes: dist_to_point (m), face_err (rad), speed (own, m/s), ball_incoming,
    ball_speed (m/s), on_dribbler, skill_status (running skill), time_in_state (s)."""

    dist_to_point: float
    face_err: float = 0.0
    speed: float = 0.0
    ball_incoming: bool = False
    ball_speed: float = 0.0
    on_dribbler: bool = False
    skill_status: SkillStatus = SkillStatus.RUNNING
    time_in_state: float = 0.0


def ball_incoming(ball_pos: np.ndarray, ball_vel: np.ndarray, robot_pos: np.ndarray, min_speed: float,
                  line_tol: float) -> bool:
    """The ball moves faster than ``min_speed`` (m/s) towards ``robot_pos`` and its straight
    path passes within ``line_tol`` (m) of it."""
    v = np.asarray(ball_vel, float)
    sp = float(np.hypot(*v))
    if sp < min_speed:
        return False
    rel = np.asarray(robot_pos, float) - np.asarray(ball_pos, float)
    along = float(rel @ v) / sp
    if along <= 0.0:
        return False
    lateral = abs(float(rel[0] * v[1] - rel[1] * v[0])) / sp
    return lateral <= line_tol


class Receive(Tactic):
    """Receive a pass on the expected ball line (see the module docstring)."""

    name = "receive"
    State = ReceiveState
    Params = ReceiveParams
    Inputs = ReceiveInputs
    initial_state = ReceiveState.POSITION
    uses_skills = ("go_to_ball", "receive")

    def __init__(self, field, robot=None, ball=None, skills="baseline", dt: float = 1.0 / 60.0, **params) -> None:
        self.receive_skill = None
        super().__init__(field, robot, ball, skills, dt, **params)
        self.receive_skill = self._skill("receive")
        self.go_to_ball = self._skill("go_to_ball")
        self.nav = NavigateToPoint(field, self.rp, self.bp, NavParams(), tolerance=0.05)
        self.on_enter(self.state)

    def _running_skill(self):
        return {ReceiveState.RECEIVING: self.receive_skill, ReceiveState.FETCH: self.go_to_ball}.get(self.state)

    def set_params(self, **changes) -> None:
        """As :meth:`Tactic.set_params`; ``receive_point`` must be two finite numbers inside
        the field, ``ball_from`` two finite numbers (the ball may lie just outside the lines
        before the referee places it) (ValueError naming the parameter)."""
        if changes.get("receive_point") is not None:
            changes["receive_point"] = check_field_point("Receive.receive_point", changes["receive_point"], self.field)
        if changes.get("ball_from") is not None:
            changes["ball_from"] = check_field_point("Receive.ball_from", changes["ball_from"], None)
        super().set_params(**changes)

    def observe(self, world: WorldState, robot: int) -> ReceiveInputs:
        ts = world.team(world.frame)
        pos, h = ts.pos[robot], float(ts.heading[robot])
        p = self.params
        point = np.asarray(p.receive_point, float) if p.receive_point is not None else pos
        src = np.asarray(p.ball_from, float) if p.ball_from is not None else world.ball_pos
        face = facing_towards(point, src)
        skill = self._running_skill()
        return ReceiveInputs(dist_to_point=float(np.hypot(*(point - pos))), face_err=abs(wrap_angle(face - h)),
                             speed=float(np.hypot(*ts.vel[robot])),
                             ball_incoming=ball_incoming(world.ball_pos, world.ball_vel, pos, p.incoming_speed,
                                                         p.line_tol_m),
                             ball_speed=float(np.hypot(*world.ball_vel)),
                             on_dribbler=bool(ts.ball_on_dribbler[robot]),
                             skill_status=skill_status(skill) if skill is not None else SkillStatus.RUNNING,
                             time_in_state=self._time_in_state)

    @staticmethod
    def transition(state: ReceiveState, inputs: ReceiveInputs, params: ReceiveParams) -> ReceiveState:
        S = ReceiveState
        if state in (S.CONTROLLED, S.FAILED):
            return state
        if state in (S.POSITION, S.READY):
            if inputs.ball_incoming:
                return S.RECEIVING
            ready = (inputs.dist_to_point <= params.ready_tol_m and inputs.face_err <= params.ready_face_tol
                     and inputs.speed <= params.ready_speed)
            if state is S.POSITION:
                return S.READY if ready else S.POSITION
            return S.POSITION if inputs.dist_to_point > 2.0 * params.ready_tol_m else S.READY
        if state is S.RECEIVING:
            if inputs.skill_status is SkillStatus.SUCCEEDED:
                return S.CONTROLLED
            if inputs.skill_status is SkillStatus.FAILED or inputs.time_in_state > params.give_up_s:
                return S.FAILED
            if inputs.ball_speed < params.fetch_speed and not inputs.on_dribbler:
                return S.FETCH
            return S.RECEIVING
        if state is S.FETCH:
            if inputs.skill_status is SkillStatus.SUCCEEDED:
                return S.CONTROLLED
            return S.FAILED if inputs.time_in_state > params.give_up_s else S.FETCH
        raise ValueError(f"unknown state {state!r}")

    def on_enter(self, state: ReceiveState) -> None:
        if self.receive_skill is None:
            return
        skill = self._running_skill()
        if skill is not None:
            skill.reset()

    def execute(self, world: WorldState, robot: int, inputs: ReceiveInputs) -> np.ndarray:
        S, p = ReceiveState, self.params
        if self.state in (S.POSITION, S.READY):
            pos = world.team(world.frame).pos[robot]
            point = np.asarray(p.receive_point, float) if p.receive_point is not None else pos
            src = np.asarray(p.ball_from, float) if p.ball_from is not None else world.ball_pos
            self.nav.target = point
            self.nav.facing = facing_towards(point, src) if math.hypot(*(src - point)) > 1e-6 else None
            self.nav.dribble = self.state is S.READY
            return self.nav.act(world, robot)
        if self.state is S.RECEIVING:
            return self.receive_skill.act(world, robot)
        if self.state is S.FETCH:
            return self.go_to_ball.act(world, robot)
        if self.state is S.CONTROLLED:
            return make_action(dribble=True)
        return make_action()


__all__ = ["ReceiveState", "ReceiveParams", "ReceiveInputs", "Receive", "ball_incoming"]
