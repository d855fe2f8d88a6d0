"""Tactic base: one robot's role as an explicit state machine over skills.

Shape (Thunderbots-style STP, the paper's Fig. 2 for the attacker):

* ``State``: an :class:`enum.Enum` of the tactic's states.
* ``Params``: a frozen dataclass of the parameters a play may set each tick
  (:meth:`Tactic.set_params`); unknown names raise ValueError.
* ``Inputs``: a frozen dataclass of what the transition needs, built from the world
  by :meth:`Tactic.observe` (distances in m, speeds in m/s, the running skill's
  status, whether a kick was commanded on the previous tick...).
* :meth:`Tactic.transition`: a small pure function ``(state, inputs, params) -> state``
  (static, unit-testable without a world).
* :meth:`Tactic.execute`: the action for the current state (runs a skill).
* :attr:`Tactic.status`: a :class:`TacticStatus` report (state, time in state,
  kicks commanded) that plays read.

:meth:`Tactic.act` ties them together once per control tick: observe ->
transition (at most one per tick; entering a state resets its skill) -> execute.
The world is always a *team-frame* snapshot (own goal at -x, ``world.frame`` is the
team) and ``robot`` the index inside that team; the result is the env's normalised
(5,) float32 action ``[vx, vy, omega, dribble, kick]`` (body frame).
"""

from __future__ import annotations

import dataclasses
import enum
import math
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from ..envs.actions import clip_unit
from ..physics.field import FieldGeometry
from ..physics.params import BallParams, RobotParams
from ..physics.state import WorldState
from ..skills.base import SkillStatus, make_action
from .skillset import SkillsSpec, make_tactic_skill, validate_skills

NEAR_BALL_M = 0.035  # the paper's "ball near the dribbler": d_{d-b} <= 35 mm


@dataclass(frozen=True)
class TacticStatus:
    """What a tactic reports to its play.

    Attributes:
        state: current state (member of the tactic's ``State`` enum).
        time_in_state: simulated seconds since the state was entered.
        kicks: kick commands issued since :meth:`Tactic.reset`.
        kicked: a kick was commanded on the last tick.
        transitions: number of state changes since reset.
    """

    state: enum.Enum
    time_in_state: float = 0.0
    kicks: int = 0
    kicked: bool = False
    transitions: int = 0


class Tactic:
    """Base class; subclasses define ``State``, ``Params``, ``initial_state``,
    :meth:`observe`, :meth:`transition` and :meth:`execute`.

    Args:
        field: field geometry.
        robot, ball: physical parameters (defaults when None).
        skills: "baseline", "learned" or {skill_name: kind}: which go-to-ball /
            aim-to-shoot implementation this tactic's states run (see
            :mod:`ssl_marl.plays.skillset`).
        dt: control period (s), for fixed-duration skills.
        **params: initial values for ``Params`` fields.
    """

    name: ClassVar[str] = "tactic"
    #: skills (names in :func:`~ssl_marl.plays.skillset.swappable_skills`) the tactic builds;
    #: a team checks that they can be built (e.g. a learned actor exists) before kickoff.
    uses_skills: ClassVar[tuple[str, ...]] = ()
    #: the tactic goes for the ball (attacker, passer): the team controller keeps the robot
    #: that took our set piece off such roles until another robot has touched the ball
    #: (but lets it keep one whose tactic is done with the ball: :attr:`wants_ball`)
    takes_ball: ClassVar[bool] = False
    State: ClassVar[type[enum.Enum]]
    Params: ClassVar[type]
    initial_state: ClassVar[enum.Enum]

    def __init__(self, field: FieldGeometry, robot: RobotParams | None = None, ball: BallParams | None = None,
                 skills: SkillsSpec = "baseline", dt: float = 1.0 / 60.0, **params: Any) -> None:
        validate_skills(skills)
        self.field = field
        self.rp = robot or RobotParams()
        self.bp = ball or BallParams()
        self.skills = skills
        self.dt = float(dt)
        self.params = self.Params()
        if params:
            self.set_params(**params)
        self.state = self.initial_state
        self._since = None  # world time at state entry
        self._time_in_state = 0.0
        self._kicks = 0
        self._kicked = False
        self._transitions = 0

    # ---------------------------------------------------------------- params
    def set_params(self, **changes: Any) -> None:
        """Set parameters (names of ``Params`` fields); plays call this every tick."""
        names = _field_names(self.Params)
        unknown = [] if names.issuperset(changes) else sorted(set(changes) - names)
        if unknown:
            raise ValueError(f"{type(self).__name__}.set_params: unknown parameter(s) {unknown}; "
                             f"known: {sorted(names)}")
        try:
            same = all(getattr(self.params, k) == v for k, v in changes.items())
        except (TypeError, ValueError):  # e.g. numpy arrays: always replace
            same = False
        if not same:
            self.params = dataclasses.replace(self.params, **changes)

    # ---------------------------------------------------------------- status
    @property
    def status(self) -> TacticStatus:
        return TacticStatus(self.state, self._time_in_state, self._kicks, self._kicked, self._transitions)

    @property
    def wants_ball(self) -> bool:
        """Whether the tactic will still go for the ball (default: :attr:`takes_ball`)."""
        return self.takes_ball

    def reset(self) -> None:
        """Back to ``initial_state``, counters cleared, skills reset (params kept)."""
        self.state = self.initial_state
        self._since = None
        self._time_in_state = 0.0
        self._kicks = 0
        self._kicked = False
        self._transitions = 0
        self.on_enter(self.state)

    # ------------------------------------------------------------- the tick
    def act(self, world: WorldState, robot: int) -> np.ndarray:
        """One control tick: observe, transition, execute. Returns a (5,) float32 action."""
        if world.frame not in ("blue", "yellow"):
            raise ValueError(f"{type(self).__name__}.act needs a team-frame snapshot, got frame={world.frame!r}")
        if self._since is None:
            self._since = world.t
        self._time_in_state = max(world.t - self._since, 0.0)
        inputs = self.observe(world, robot)
        new = self.transition(self.state, inputs, self.params)
        if new is not self.state:
            self.state = new
            self._since = world.t
            self._time_in_state = 0.0
            self._transitions += 1
            self.on_enter(new)
        a = np.asarray(self.execute(world, robot, inputs), dtype=np.float32)
        entries = a.tolist() if a.shape == (5,) else None
        if entries is None or not all(map(math.isfinite, entries)):
            raise ValueError(f"{type(self).__name__} in state {self.state.name} produced an invalid action "
                             f"for robot {robot}: {a!r}")
        a = clip_unit(entries)
        self._kicked = bool(a[4] > 0.0)
        self._kicks += int(self._kicked)
        return a

    # ------------------------------------------------------ subclass hooks
    def observe(self, world: WorldState, robot: int) -> Any:
        raise NotImplementedError

    @staticmethod
    def transition(state: enum.Enum, inputs: Any, params: Any) -> enum.Enum:
        raise NotImplementedError

    def on_enter(self, state: enum.Enum) -> None:
        """Called when ``state`` is entered (reset its skill here)."""

    def execute(self, world: WorldState, robot: int, inputs: Any) -> np.ndarray:
        raise NotImplementedError

    # ------------------------------------------------------------ helpers
    def _skill(self, name: str):
        """A fresh go-to-ball / aim-to-shoot skill of the configured kind."""
        return make_tactic_skill(name, self.skills, self.field, self.rp, self.bp)

    @staticmethod
    def stop() -> np.ndarray:
        return make_action()


_FIELD_NAMES: dict[type, frozenset[str]] = {}


def _field_names(cls: type) -> frozenset[str]:
    names = _FIELD_NAMES.get(cls)
    if names is None:
        names = _FIELD_NAMES[cls] = frozenset(f.name for f in dataclasses.fields(cls))
    return names


def check_field_point(name: str, point: Any, field: FieldGeometry | None) -> tuple[float, float]:
    """``point`` as an (x, y) tuple of floats (m) if it is two finite numbers inside the
    playing area (anywhere when ``field`` is None); ValueError naming ``name`` otherwise."""
    try:
        p = np.asarray(point, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be two numbers (x, y) in metres, got {point!r}") from None
    if p.shape != (2,) or not np.isfinite(p).all():
        raise ValueError(f"{name} must be two finite numbers (x, y) in metres, got {point!r}")
    if field is not None and not bool(field.in_field(p)):
        raise ValueError(f"{name} {p.tolist()} lies outside the {field.name} field "
                         f"(|x| <= {field.half_length}, |y| <= {field.half_width} m)")
    return float(p[0]), float(p[1])


def skill_status(skill: Any) -> SkillStatus:
    """The status of a skill object (RUNNING if it has none)."""
    return getattr(skill, "status", SkillStatus.RUNNING)
