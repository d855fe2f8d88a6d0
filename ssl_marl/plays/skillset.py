"""Which skill implementation a tactic uses: the one switch between learned and baseline.

Tactics never import a skill class directly. They ask :func:`make_tactic_skill` for a
registered skill (``"go_to_ball"``, ``"aim_to_shoot"``, ...) and get an object with the
:class:`ssl_marl.skills.base.Skill` protocol. ``skills`` selects the kind:

* ``"baseline"`` or ``"learned"`` for every skill, or
* a mapping ``{"go_to_ball": "learned", "aim_to_shoot": "baseline"}`` to mix kinds
  (skills not named default to ``"baseline"``). A value may also be the path of an
  actor checkpoint (a freshly trained ``runs/NAME/actor.pt``): that skill is then
  the learned skill running that actor. Keys may be spelled ``go_to_ball`` or
  ``go-to-ball``.

The swappable skills (those with a learned implementation) come from the skill
registry (:func:`ssl_marl.skills.registry.learned_skills`).

Construction goes through the registry record's ``build`` (what
``ssl_marl.skills.make_skill`` calls).

Learned skills load their actor from disk when built. Tactics are built often (a
robot that changes role gets a fresh tactic), so a learned skill is built through
the factory once per (name, field, robot, ball) and later instances are shallow
copies of that prototype, reset (the actor weights are shared and read-only; the
per-run state lives in attributes that ``reset()`` rebinds).
"""

from __future__ import annotations

import copy
import os
from pathlib import Path
from typing import Any, Mapping, Union

from ..physics.field import FieldGeometry
from ..physics.params import BallParams, RobotParams
from ..skills.registry import SKILL_KINDS, learned_skills

SkillsSpec = Union[str, Mapping[str, Union[str, os.PathLike]]]


#: the skills every STP team builds (the go-to-ball-and-shoot tactics; checked when a team is built)
CORE_SKILLS = ("go_to_ball", "aim_to_shoot")
#: used only by the passing plays' Pass / Receive tactics
PASSING_SKILLS = ("pass", "receive")
#: every skill a passing team's tactics build (core and passing)
TEAM_SKILLS = CORE_SKILLS + PASSING_SKILLS
#: every skill the attacking plays' tactics build: the passing team's and the ChipPass /
#: Redirect tactics' chip pass and one-touch redirect
ATTACK_SKILLS = TEAM_SKILLS + ("chip_pass", "redirect")


def swappable_skills() -> tuple[str, ...]:
    """Skills a skill set can switch between learned and baseline (registry order)."""
    return tuple(s.name for s in learned_skills())


def _canonical(name: Any) -> Any:
    return name.replace("-", "_") if isinstance(name, str) else name


def _source(name: str, value: Any) -> tuple[str, str | None]:
    """(kind, checkpoint path or None) for one skill's source; clear errors."""
    if isinstance(value, str) and value in SKILL_KINDS:
        return _shipped_or_baseline(name, value), None
    if isinstance(value, (str, os.PathLike)):
        path = Path(value)
        if path.is_file():
            return "learned", str(path)
        if isinstance(value, os.PathLike) or os.sep in str(value) or "/" in str(value) or path.suffix:
            raise FileNotFoundError(f"skills[{name!r}]: checkpoint {str(value)!r} does not exist")
    raise ValueError(f"skills[{name!r}] must be one of {SKILL_KINDS} or the path of an actor checkpoint, "
                     f"got {value!r}")


def _shipped_or_baseline(name: str, kind: str) -> str:
    """``kind``, except that "learned" for a skill with no shipped actor (the registry
    record's ``actor`` missing, e.g. a skill whose learned actor did not beat its
    hand-coded baseline) means the hand-coded skill: a "learned" team uses every shipped
    learned skill. A checkpoint path always selects the learned skill."""
    if kind != "learned":
        return kind
    from ..skills.registry import get_skill

    actor = get_skill(name).actor
    return kind if actor is not None and actor.exists() else "baseline"


def validate_skills(skills: SkillsSpec) -> None:
    """Raise ValueError if ``skills`` is not a kind name or a {skill: kind or
    checkpoint path} mapping (FileNotFoundError for a checkpoint path that does not
    exist; whether the file holds the right skill is checked when it is loaded)."""
    if isinstance(skills, str):
        if skills not in SKILL_KINDS:
            raise ValueError(f"skills must be one of {SKILL_KINDS} or a mapping, got {skills!r}")
        return
    if not isinstance(skills, Mapping):
        raise ValueError(f"skills must be one of {SKILL_KINDS} or a mapping, got {skills!r}")
    for name, value in skills.items():
        if _canonical(name) not in swappable_skills():
            raise ValueError(f"skills: unknown skill {name!r}; expected some of {swappable_skills()}")
        _source(_canonical(name), value)


def skill_source(skills: SkillsSpec, name: str) -> tuple[str, str | None]:
    """(kind, checkpoint) that ``skills`` selects for skill ``name``: kind is
    "baseline" or "learned"; checkpoint is a path, or None for the shipped actor."""
    validate_skills(skills)
    if isinstance(skills, str):
        return _shipped_or_baseline(name, skills), None
    for key, value in skills.items():
        if _canonical(key) == name:
            return _source(name, value)
    return "baseline", None


def skill_kind(skills: SkillsSpec, name: str) -> str:
    """The kind ("baseline"/"learned") that ``skills`` selects for skill ``name``."""
    return skill_source(skills, name)[0]


def team_skill_set(kind: str, names: tuple[str, ...] = TEAM_SKILLS, where: str = "team") -> dict[str, str]:
    """The skill set ``{skill: "baseline" | "learned"}`` of a team whose skills ``names``
    are all of ``kind``: ``"baseline"``: every skill hand-coded; ``"learned"``: every
    skill learned where its actor is shipped, else hand-coded (:func:`skill_kind`). A
    match result's ``config["skills"]`` records this mapping. ValueError (naming
    ``where``) for another kind."""
    if kind not in SKILL_KINDS:
        raise ValueError(f"{where}: skills must be one of {SKILL_KINDS}, got {kind!r}")
    return {name: skill_kind(kind, name) for name in names}


def check_skills(skills: SkillsSpec, field: FieldGeometry, robot: RobotParams | None = None,
                 ball: BallParams | None = None, names: tuple[str, ...] | None = None) -> None:
    """Build every learned skill ``skills`` selects among ``names`` (default: every
    swappable skill) once, so that a missing or wrong-skill checkpoint fails now (one
    clear error) rather than mid-run."""
    for name in (swappable_skills() if names is None else names):
        if skill_kind(skills, name) == "learned":
            make_tactic_skill(name, skills, field, robot, ball)


def make_tactic_skill(name: str, skills: SkillsSpec, field: FieldGeometry, robot: RobotParams | None = None,
                      ball: BallParams | None = None):
    """Build swappable skill ``name`` ("go_to_ball", "aim_to_shoot", ...) of the kind ``skills`` selects."""
    if name not in swappable_skills():
        raise ValueError(f"make_tactic_skill: unknown skill {name!r}; expected one of {swappable_skills()}")
    kind, checkpoint = skill_source(skills, name)
    if kind == "learned":
        key = (name, checkpoint, field, robot or RobotParams(), ball or BallParams())
        proto = _LEARNED_PROTOTYPES.get(key)
        if proto is None:
            proto = _LEARNED_PROTOTYPES[key] = _build(name, kind, field, robot, ball, checkpoint)
        skill = copy.copy(proto)
        skill.reset()
        return skill
    return _build(name, kind, field, robot, ball)


_LEARNED_PROTOTYPES: dict[tuple, Any] = {}


def clear_skill_cache() -> None:
    """Forget the learned-skill prototypes (e.g. after a new checkpoint was written)."""
    _LEARNED_PROTOTYPES.clear()


def _build(name: str, kind: str, field: FieldGeometry, robot: RobotParams | None, ball: BallParams | None,
           checkpoint: str | None = None):
    from .. import skills  # the skills package factory (make_skill -> the registry record's build)

    if checkpoint is None:
        return skills.make_skill(name, kind, field, robot, ball)
    return skills.make_skill(name, kind, field, robot, ball, checkpoint=checkpoint)
