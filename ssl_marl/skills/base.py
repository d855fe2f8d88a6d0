"""The skill protocol: one interface for hand-coded and learned skills.

A tactic drives a skill by calling :meth:`Skill.act` once per control tick with
the current world snapshot *in the robot's team frame* (``world.frame`` is the
team name; own goal at -x, opponent goal at +x) and the robot's index inside its
own team. From a field-frame snapshot (``env.world_state()``), pass the team:
``skill.act(env.world_state(), 0, team="yellow")`` converts it with
:func:`~ssl_marl.physics.state.to_team_frame` first (every :class:`SkillBase`
subclass accepts ``team=``); without ``team`` a field-frame snapshot is refused
with an error that says so. The skill returns the robot's action in the env's normalised action
space and updates :attr:`Skill.status`. A tactic cannot tell a learned skill
from a hand-coded one.

Action layout (shared with the env, see :mod:`ssl_marl.envs.actions`):
``[vx, vy, omega, dribble, kick]`` in [-1, 1], body frame (+x forward, +y left),
velocities as fractions of the robot's limits, dribbler on when > 0, kick
strength = value when > 0.
"""

from __future__ import annotations

import enum
import functools
from typing import Callable, Protocol, runtime_checkable

import numpy as np

from ..physics.field import FieldGeometry
from ..physics.params import BallParams, RobotParams
from ..envs.actions import make_action
from ..physics.state import TEAMS, WorldState, to_team_frame
from .features import BALL_LOST_DISTANCE, dribbler_ball_distance


class SkillStatus(enum.Enum):
    RUNNING = "running"
    SUCCEEDED = "succeeded"
    FAILED = "failed"


@runtime_checkable
class Skill(Protocol):
    """A low-level single-robot behaviour."""

    name: str
    status: SkillStatus

    def reset(self) -> None:
        """Start afresh (status RUNNING, internal timers cleared)."""

    def act(self, world: WorldState, robot: int, team: str | None = None) -> np.ndarray:
        """Return a (5,) float32 action for ``robot`` (index in team ``world.frame``, or in
        ``team`` when ``world`` is a field-frame snapshot)."""


def in_team_frame(world: WorldState, team: str | None) -> WorldState:
    """``world`` in the robot's team frame: converted with :func:`to_team_frame` when it
    is a field-frame snapshot and ``team`` is given, returned as is when it already is in
    ``team``'s frame (or ``team`` is None). ValueError saying what to do otherwise."""
    if team is not None and team not in TEAMS:
        raise ValueError(f"team: unknown team {team!r}; expected 'blue' or 'yellow'")
    if world.frame == "field":
        if team is None:
            raise ValueError("a skill acts in its robot's team frame, but this snapshot is in the field frame: "
                             "pass the robot's team, e.g. skill.act(env.world_state(), robot, team='blue'), "
                             "or give a team-frame snapshot (env.vision_state('blue') or "
                             "ssl_marl.physics.state.to_team_frame(world, 'blue'))")
        return to_team_frame(world, team)
    if team is not None and world.frame != team:
        raise ValueError(f"team={team!r} but the snapshot is in {world.frame!r}'s frame; pass a field-frame "
                         f"snapshot (env.world_state()) or the {team!r} frame (env.vision_state({team!r}))")
    return world


def _accepting_team(act: Callable[..., np.ndarray]) -> Callable[..., np.ndarray]:
    """Wrap a skill's ``act(world, robot)`` so it also takes ``team=`` (see :func:`in_team_frame`)."""
    if getattr(act, "_accepts_team", False):
        return act

    @functools.wraps(act)
    def wrapped(self, world: WorldState, robot: int, team: str | None = None) -> np.ndarray:
        return act(self, in_team_frame(world, team), robot)

    wrapped._accepts_team = True
    return wrapped


class SkillBase:
    """Plumbing every skill shares: field, robot and ball parameters, and a status.

    Every subclass's ``act(world, robot)`` also accepts ``team=`` (the robot's team),
    so a field-frame snapshot can be passed directly; see :func:`in_team_frame`.
    """

    name = "skill"

    def __init_subclass__(cls, **kwargs) -> None:
        super().__init_subclass__(**kwargs)
        if "act" in cls.__dict__:
            cls.act = _accepting_team(cls.__dict__["act"])

    def __init__(self, field: FieldGeometry, robot: RobotParams | None = None, ball: BallParams | None = None):
        self.field = field
        self.rp = robot or RobotParams()
        self.bp = ball or BallParams()
        self.status = SkillStatus.RUNNING

    def reset(self) -> None:
        self.status = SkillStatus.RUNNING


class GoToBallSkill(SkillBase):
    """go-to-ball, hand-coded or learned: succeeds when the ball is on the dribbler;
    subclasses say how to approach it (:meth:`approach`)."""

    name = "go_to_ball"

    def act(self, world: WorldState, robot: int) -> np.ndarray:
        if bool(world.team(world.frame).ball_on_dribbler[robot]):
            self.status = SkillStatus.SUCCEEDED
            return make_action(dribble=True)
        self.status = SkillStatus.RUNNING
        return self.approach(world, robot)

    def approach(self, world: WorldState, robot: int) -> np.ndarray:
        raise NotImplementedError


class KickSkill(SkillBase):
    """A skill that holds the ball on the dribbler until it kicks (aim-to-shoot, pass):
    succeeds once it has kicked; fails if the ball leaves the dribbler (d_{d-b} >
    ``BALL_LOST_DISTANCE``) before the kick, or when ``max_time_s`` (None = no limit)
    passes without one. Subclasses implement :meth:`aim`, returning the action and
    whether it fires the kicker; :meth:`fires` may veto or record a kick."""

    def __init__(self, field: FieldGeometry, robot: RobotParams | None = None, ball: BallParams | None = None,
                 max_time_s: float | None = None) -> None:
        super().__init__(field, robot, ball)
        self.max_time_s = max_time_s
        self._kicked = False
        self._t0: float | None = None

    def reset(self) -> None:
        super().reset()
        self._kicked = False
        self._t0 = None

    def act(self, world: WorldState, robot: int) -> np.ndarray:
        if self._kicked:
            self.status = SkillStatus.SUCCEEDED
            return make_action()
        if self._t0 is None:
            self._t0 = world.t
        timed_out = self.max_time_s is not None and world.t - self._t0 > self.max_time_s
        if timed_out or dribbler_ball_distance(world, robot, self.rp, self.bp) > BALL_LOST_DISTANCE:
            self.status = SkillStatus.FAILED
            return make_action(dribble=True)
        action, kicks = self.aim(world, robot)
        kicks = self.fires(world, robot, action, kicks)
        self._kicked = kicks
        self.status = SkillStatus.SUCCEEDED if kicks else SkillStatus.RUNNING
        return action

    def fires(self, world: WorldState, robot: int, action: np.ndarray, kicks: bool) -> bool:
        """Whether the kick :meth:`aim` asked for (``kicks``) counts as fired."""
        return kicks

    def aim(self, world: WorldState, robot: int) -> tuple[np.ndarray, bool]:
        raise NotImplementedError


class AimToShootSkill(KickSkill):
    """aim-to-shoot, hand-coded or learned (see :class:`KickSkill`)."""

    name = "aim_to_shoot"
