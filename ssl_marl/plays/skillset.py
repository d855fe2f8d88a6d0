"""Which skill implementation a tactic uses: the one switch between learned and baseline.

Tactics never import a skill class directly. They ask :func:`make_tactic_skill` for
``"go_to_ball"`` or ``"aim_to_shoot"`` and get an object with the
:class:`ssl_marl.skills.base.Skill` protocol. ``skills`` selects the kind:

* ``"baseline"`` or ``"learned"`` for every skill, or
* a mapping ``{"go_to_ball": "learned", "aim_to_shoot": "baseline"}`` to mix kinds
  (skills not named default to ``"baseline"``). A value may also be the path of an
  actor checkpoint (a freshly trained ``runs/NAME/actor.pt``): that skill is then
  the learned skill running that actor. Keys may be spelled ``go_to_ball`` or
  ``go-to-ball``.

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
import os
from pathlib import Path
from typing import Any, Mapping, Union

from ..physics.field import FieldGeometry
from ..physics.params import BallParams, RobotParams

SkillsSpec = Union[str, Mapping[str, Union[str, os.PathLike]]]
SKILL_KINDS = ("baseline", "learned")
SWAPPABLE = ("go_to_ball", "aim_to_shoot")


def _canonical(name: Any) -> Any:
    return name.replace("-", "_") if isinstance(name, str) else name


def _source(name: str, value: Any) -> tuple[str, str | None]:
    """(kind, checkpoint path or None) for one skill's source; clear errors."""
    if isinstance(value, str) and value in SKILL_KINDS:
        return value, None
    if isinstance(value, (str, os.PathLike)):
        path = Path(value)
        if path.is_file():
            return "learned", str(path)
        if isinstance(value, os.PathLike) or os.sep in str(value) or "/" in str(value) or path.suffix:
            raise FileNotFoundError(f"skills[{name!r}]: checkpoint {str(value)!r} does not exist")
    raise ValueError(f"skills[{name!r}] must be one of {SKILL_KINDS} or the path of an actor checkpoint, "
                     f"got {value!r}")


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
        if _canonical(name) not in SWAPPABLE:
            raise ValueError(f"skills: unknown skill {name!r}; expected some of {SWAPPABLE}")
        _source(_canonical(name), value)


def skill_source(skills: SkillsSpec, name: str) -> tuple[str, str | None]:
    """(kind, checkpoint) that ``skills`` selects for skill ``name``: kind is
    "baseline" or "learned"; checkpoint is a path, or None for the shipped actor."""
    validate_skills(skills)
    if isinstance(skills, str):
        return skills, None
    for key, value in skills.items():
        if _canonical(key) == name:
            return _source(name, value)
    return "baseline", None


def skill_kind(skills: SkillsSpec, name: str) -> str:
    """The kind ("baseline"/"learned") that ``skills`` selects for skill ``name``."""
    return skill_source(skills, name)[0]


def check_skills(skills: SkillsSpec, field: FieldGeometry, robot: RobotParams | None = None,
                 ball: BallParams | None = None) -> None:
    """Build every learned skill ``skills`` names once, so that a missing or
    wrong-skill checkpoint fails now (one clear error) rather than mid-run."""
    for name in SWAPPABLE:
        if skill_kind(skills, name) == "learned":
            make_tactic_skill(name, skills, field, robot, ball)


def make_tactic_skill(name: str, skills: SkillsSpec, field: FieldGeometry, robot: RobotParams | None = None,
                      ball: BallParams | None = None):
    """Build skill ``name`` ("go_to_ball" or "aim_to_shoot") of the kind ``skills`` selects."""
    if name not in SWAPPABLE:
        raise ValueError(f"make_tactic_skill: unknown skill {name!r}; expected one of {SWAPPABLE}")
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
    try:
        from ..skills import make_skill  # lazy: the learned runtime may pull in torch
    except ImportError as exc:  # pragma: no cover - only without the factory
        if kind != "baseline":
            raise RuntimeError("learned skills need ssl_marl.skills.make_skill, which could not be "
                               f"imported ({exc}); use skills='baseline'") from exc
        from ..skills.baseline import AimToShootBaseline, GoToBallBaseline

        cls = GoToBallBaseline if name == "go_to_ball" else AimToShootBaseline
        return cls(field, robot, ball)
    if checkpoint is None:
        return make_skill(name, kind, field, robot, ball)
    return make_skill(name, kind, field, robot, ball, checkpoint=checkpoint)
