"""Which skill implementation a tactic uses: the one switch between learned and baseline.

Tactics never import a skill class directly. They ask :func:`make_tactic_skill` for a
registered skill (``"go_to_ball"``, ``"aim_to_shoot"``, ...) and get an object with the
:class:`ssl_marl.skills.base.Skill` protocol. ``skills`` selects the kind:

* ``"baseline"`` or ``"learned"`` for every skill, or
* a mapping ``{"go_to_ball": "learned", "aim_to_shoot": "baseline"}`` to mix kinds
  (skills not named default to ``"baseline"``).

The swappable skills (those with a learned implementation) come from the skill
registry (:func:`ssl_marl.skills.registry.learned_skills`).

Construction goes through the skills package factory
``ssl_marl.skills.make_skill(name, kind, field, robot, ball)`` (which reads the
registry record).

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
from ..skills.registry import SKILL_KINDS, learned_skills

SkillsSpec = Union[str, Mapping[str, str]]


def swappable_skills() -> tuple[str, ...]:
    """Skills a skill set can switch between learned and baseline (registry order)."""
    return tuple(s.name for s in learned_skills())


def __getattr__(name: str):
    if name == "SWAPPABLE":  # kept for old imports; computed from the registry
        return swappable_skills()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def validate_skills(skills: SkillsSpec) -> None:
    """Raise ValueError if ``skills`` is not a kind name or a {skill: kind} mapping."""
    if isinstance(skills, str):
        if skills not in SKILL_KINDS:
            raise ValueError(f"skills must be one of {SKILL_KINDS} or a mapping, got {skills!r}")
        return
    if not isinstance(skills, Mapping):
        raise ValueError(f"skills must be one of {SKILL_KINDS} or a mapping, got {skills!r}")
    for name, kind in skills.items():
        if name not in swappable_skills():
            raise ValueError(f"skills: unknown skill {name!r}; expected some of {swappable_skills()}")
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
    """Build swappable skill ``name`` ("go_to_ball", "aim_to_shoot", ...) of the kind ``skills`` selects."""
    if name not in swappable_skills():
        raise ValueError(f"make_tactic_skill: unknown skill {name!r}; expected one of {swappable_skills()}")
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
    from .. import skills  # looked up at call time: the factory is the one construction path

    return skills.make_skill(name, kind, field, robot, ball)
