"""Which skill implementation a tactic uses: the one switch between learned and baseline.

Tactics never import a skill class directly. They ask :func:`make_tactic_skill` for
``"go_to_ball"``, ``"aim_to_shoot"``, ``"pass"`` or ``"receive"`` and get an object with the
:class:`ssl_marl.skills.base.Skill` protocol. ``skills`` selects the kind:

* ``"baseline"`` or ``"learned"`` for every skill, or
* a mapping ``{"go_to_ball": "learned", "aim_to_shoot": "baseline"}`` to mix kinds
  (skills not named default to ``"baseline"``).

Construction goes through the skills package factory
``ssl_marl.skills.make_skill(name, kind, field, robot, ball)``, imported lazily so
that this module (and the baseline path) keeps working if the learned runtime is
missing or broken. For ``"baseline"`` the hand-coded classes are used directly when
the factory cannot be imported.

Learned skills load their actor from disk when built. Tactics are built often (a
robot that changes role gets a fresh tactic), so a learned skill is built through
the factory once per (name, field, robot, ball) and later instances are shallow
copies of that prototype, reset (the actor weights are shared and read-only; the
per-run state lives in attributes that ``reset()`` rebinds).
"""

from __future__ import annotations

import copy
from typing import Any, Mapping, Union

from ..physics.field import FieldGeometry
from ..physics.params import BallParams, RobotParams

SkillsSpec = Union[str, Mapping[str, str]]
SKILL_KINDS = ("baseline", "learned")
SWAPPABLE = ("go_to_ball", "aim_to_shoot")  #: the skills every team uses (checked when a team is built)
PASSING_SKILLS = ("pass", "receive")  #: used only by the passing plays' Pass / Receive tactics
TACTIC_SKILLS = SWAPPABLE + PASSING_SKILLS


def validate_skills(skills: SkillsSpec) -> None:
    """Raise ValueError if ``skills`` is not a kind name or a {skill: kind} mapping."""
    if isinstance(skills, str):
        if skills not in SKILL_KINDS:
            raise ValueError(f"skills must be one of {SKILL_KINDS} or a mapping, got {skills!r}")
        return
    if not isinstance(skills, Mapping):
        raise ValueError(f"skills must be one of {SKILL_KINDS} or a mapping, got {skills!r}")
    for name, kind in skills.items():
        if name not in TACTIC_SKILLS:
            raise ValueError(f"skills: unknown skill {name!r}; expected some of {TACTIC_SKILLS}")
        if kind not in SKILL_KINDS:
            raise ValueError(f"skills[{name!r}] must be one of {SKILL_KINDS}, got {kind!r}")


def skill_kind(skills: SkillsSpec, name: str) -> str:
    """The kind ("baseline"/"learned") that ``skills`` selects for skill ``name``."""
    validate_skills(skills)
    if isinstance(skills, str):
        return skills
    return skills.get(name, "baseline")


def make_tactic_skill(name: str, skills: SkillsSpec, field: FieldGeometry, robot: RobotParams | None = None,
                      ball: BallParams | None = None):
    """Build skill ``name`` (one of :data:`TACTIC_SKILLS`) of the kind ``skills`` selects."""
    if name not in TACTIC_SKILLS:
        raise ValueError(f"make_tactic_skill: unknown skill {name!r}; expected one of {TACTIC_SKILLS}")
    kind = skill_kind(skills, name)
    if kind == "learned":
        key = (name, field, robot or RobotParams(), ball or BallParams())
        proto = _LEARNED_PROTOTYPES.get(key)
        if proto is None:
            proto = _LEARNED_PROTOTYPES[key] = _build(name, kind, field, robot, ball)
        skill = copy.copy(proto)
        skill.reset()
        return skill
    return _build(name, kind, field, robot, ball)


_LEARNED_PROTOTYPES: dict[tuple, Any] = {}


def clear_skill_cache() -> None:
    """Forget the learned-skill prototypes (e.g. after a new checkpoint was written)."""
    _LEARNED_PROTOTYPES.clear()


def _build(name: str, kind: str, field: FieldGeometry, robot: RobotParams | None, ball: BallParams | None):
    try:
        from ..skills import make_skill  # lazy: the learned runtime may pull in torch
    except ImportError as exc:  # pragma: no cover - only without the factory
        if kind != "baseline" or name not in SWAPPABLE:
            raise RuntimeError("learned skills need ssl_marl.skills.make_skill, which could not be "
                               f"imported ({exc}); use skills='baseline'") from exc
        from ..skills.baseline import AimToShootBaseline, GoToBallBaseline

        cls = GoToBallBaseline if name == "go_to_ball" else AimToShootBaseline
        return cls(field, robot, ball)
    return make_skill(name, kind, field, robot, ball)
