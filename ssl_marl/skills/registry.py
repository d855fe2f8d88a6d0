"""The skill registry: one frozen record per skill, read by every consumer.

A skill is defined once, in its own module under :mod:`ssl_marl.skills.catalog`
(``catalog/go_to_ball.py`` ...), which builds a :class:`SkillDef` and calls
:func:`register`. The catalog's ``MODULES`` tuple lists those modules; adding a
skill is one new module plus one entry there. Everything that used to switch on a
skill-name string reads the registry instead: :func:`ssl_marl.skills.make_skill`,
the Gymnasium registration in :mod:`ssl_marl`, the learned-actor loader, the task
wrappers, the evaluation runner, the STP skill sets, the trainer's default configs
(``train/`` resolves :attr:`SkillTaskDef.train_config`; ``ssl_marl`` never imports
``train``) and the CLI's choices.

Names: the canonical name is snake_case (``go_to_ball``); the CLI spelling is the
same with dashes (``go-to-ball``). :func:`get_skill` accepts either.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType
from typing import Any, Callable, Mapping

import numpy as np

#: the kinds of implementation a skill can have (a skill without a learned class is
#: built hand-coded whatever kind is asked for)
SKILL_KINDS = ("baseline", "learned")
#: where shipped actors live
PRETRAINED_DIR = Path(__file__).resolve().parent / "pretrained"


def resolve_ref(ref: str) -> Any:
    """Import ``"package.module:attribute"`` and return the attribute."""
    module, _, attr = ref.partition(":")
    if not module or not attr:
        raise ValueError(f"reference {ref!r} must look like 'package.module:attribute'")
    return getattr(importlib.import_module(module), attr)


@dataclass(frozen=True)
class SkillTaskDef:
    """The single-robot learning task of a skill (what a trainer and the skill
    evaluation run).

    Attributes:
        env_id: Gymnasium id (``ssl_marl/GoToBall-v0``), registered on ``import ssl_marl``.
        entry_point: ``"module:Class"`` of the Gymnasium env (a
            :class:`~ssl_marl.skills.robot_env.RobotSkillEnv` over a one-robot env).
        features: pure feature function ``(team-frame WorldState, robot, field) -> (obs_dim,)``.
        feature_names: one name per feature.
        action_names: one name per task action dimension.
        to_task_action: a skill's full (5,) env action -> the task's action.
        to_env_action: the task's action (and an action-mapping name) -> the full (5,) env action.
        spec_versions: action-mapping name -> observation/action spec string stored in a
            learned actor's metadata (``{"default": "pass/v1"}``; aim-to-shoot has two kick
            mappings, v1 and v2, go-to-ball two state forms). The first entry is the default
            mapping.
        demo_fn: ``"module:function"`` yielding demonstration transitions for replay burn-in.
        train_config: name of the default trainer config (``train/configs/<name>.json``);
            resolved by ``train``, never imported here.
        drive: how the evaluation protocol drives a :class:`Skill` object in the task env,
            ``(env, skill) -> task action``; None: ``to_task_action(skill.act(env.seen(), 0))``.
            Tasks whose skill needs per-step inputs from the task (the pass's target) set it.
        form_names: action-mapping name -> (feature names, action names) for a mapping
            whose state or action differs from ``feature_names`` / ``action_names`` (the
            redirect's ``aim`` form); the others use those two.
    """

    env_id: str
    entry_point: str
    features: Callable[..., np.ndarray]
    feature_names: tuple[str, ...]
    action_names: tuple[str, ...]
    to_task_action: Callable[[np.ndarray], np.ndarray]
    to_env_action: Callable[..., np.ndarray]
    spec_versions: Mapping[str, str]
    demo_fn: str | None = None
    train_config: str | None = None
    drive: Callable[[Any, Any], np.ndarray] | None = None
    form_names: Mapping[str, tuple[tuple[str, ...], tuple[str, ...]]] = field(default_factory=dict)

    def __post_init__(self) -> None:
        if not self.spec_versions:
            raise ValueError(f"{self.env_id}: spec_versions needs at least one action mapping")
        unknown = set(self.form_names) - set(self.spec_versions)
        if unknown:
            raise ValueError(f"{self.env_id}: form_names names unknown action mappings {sorted(unknown)}")
        object.__setattr__(self, "spec_versions", MappingProxyType(dict(self.spec_versions)))
        object.__setattr__(self, "form_names", MappingProxyType(dict(self.form_names)))

    def names_of(self, mapping: str | None = None) -> tuple[tuple[str, ...], tuple[str, ...]]:
        """(feature names, action names) of an action mapping (default: the first)."""
        mapping = self.mapping_of(self.spec_of(mapping))
        return self.form_names.get(mapping, (tuple(self.feature_names), tuple(self.action_names)))

    def skill_action(self, env: Any, skill: Any) -> np.ndarray:
        """The task action of ``skill`` (a :class:`Skill` object) acting for the task's
        robot in ``env`` this step (see ``drive``)."""
        if self.drive is not None:
            return self.drive(env, skill)
        return self.to_task_action(skill.act(env.seen(), 0))

    @property
    def obs_dim(self) -> int:
        return len(self.feature_names)

    @property
    def act_dim(self) -> int:
        return len(self.action_names)

    @property
    def default_mapping(self) -> str:
        return next(iter(self.spec_versions))

    @property
    def specs(self) -> tuple[str, ...]:
        """Every spec string a learned actor of this task may carry."""
        return tuple(self.spec_versions.values())

    def spec_of(self, mapping: str | None = None) -> str:
        """The spec string of an action mapping (default: the first); ValueError names the bad one."""
        mapping = self.default_mapping if mapping is None else mapping
        try:
            return self.spec_versions[mapping]
        except (KeyError, TypeError):
            raise ValueError(f"action mapping must be one of {tuple(self.spec_versions)}, got {mapping!r}") from None

    def mapping_of(self, spec: str) -> str:
        """Inverse of :meth:`spec_of`."""
        for mapping, s in self.spec_versions.items():
            if s == spec:
                return mapping
        raise ValueError(f"unknown spec {spec!r}; expected one of {self.specs}")


@dataclass(frozen=True)
class SkillDef:
    """Everything the code base knows about one skill.

    Attributes:
        name: canonical snake_case name (``go_to_ball``).
        summary: one line for ``--help`` and docs.
        baseline: the hand-coded class (``Skill`` protocol; constructor
            ``(field, robot, ball, **kwargs)``).
        learned: ``"module:Class"`` of the learned skill (constructor adds
            ``checkpoint=``), or None for a skill that is always hand-coded.
        actor: shipped actor file of the learned skill (None: none shipped).
        task: the single-robot learning task, or None (utility skills).
        reference: figures it is compared with, e.g. the paper's success rates per kind
            (``{"baseline": 1.0, "learned": 0.999}``); evaluation reports them.
        reference_source: where ``reference`` comes from.
    """

    name: str
    summary: str
    baseline: type
    learned: str | None = None
    actor: Path | None = None
    task: SkillTaskDef | None = None
    reference: Mapping[str, float] = field(default_factory=dict)
    reference_source: str = ""

    def __post_init__(self) -> None:
        if not self.name.isidentifier() or self.name != self.name.lower():
            raise ValueError(f"skill name must be a snake_case identifier, got {self.name!r}")
        object.__setattr__(self, "reference", MappingProxyType(dict(self.reference)))

    @property
    def cli_name(self) -> str:
        """The command-line spelling (``go-to-ball``)."""
        return self.name.replace("_", "-")

    @property
    def has_learned(self) -> bool:
        return self.learned is not None

    def learned_class(self) -> type:
        if self.learned is None:
            raise ValueError(f"skill {self.name!r} has no learned implementation")
        return resolve_ref(self.learned)

    def build(self, kind: str, field, robot=None, ball=None, checkpoint: str | Path | None = None, **kwargs):
        """A fresh skill object of ``kind`` ("baseline" or "learned"; ``checkpoint``
        overrides the shipped actor and implies learned). A skill without a learned
        implementation is hand-coded whatever the kind."""
        if kind not in SKILL_KINDS:
            raise ValueError(f"unknown skill kind {kind!r}; expected one of {SKILL_KINDS}")
        if self.learned is None:
            return self.baseline(field, robot, ball, **kwargs)
        if kind == "baseline" and checkpoint is None:
            return self.baseline(field, robot, ball, **kwargs)
        return self.learned_class()(field, robot, ball, checkpoint=checkpoint, **kwargs)


def direct_env_action(expand: Callable[[Any], np.ndarray], skill: str, residual_specs: Mapping[str, str],
                      learned: str, env: str, action3: Any, mapping: str | None = None) -> np.ndarray:
    """``to_env_action`` of a skill task with a ``direct`` action form and residual ones
    (``residual_specs``: action-mapping name -> spec; bind the first five arguments with
    :func:`functools.partial`): ``expand(action3)`` for a direct action; a residual action
    is a correction of the hand-coded skill's action and needs the world state, so it is
    refused (ValueError naming ``learned`` and ``env``, which apply it)."""
    if mapping in residual_specs:
        raise ValueError(f"a residual {skill} action ({residual_specs[mapping]}) is a correction of the hand-coded "
                         f"{skill}'s action and needs the world state: use {learned} or {env}(action_form={mapping!r})")
    return expand(action3)


_REGISTRY: dict[str, SkillDef] = {}
_LOADED = False


def register(skill: SkillDef) -> SkillDef:
    """Add ``skill`` to the registry (a second record under the same name is an error,
    unless it is the same object: re-importing a catalog module is harmless)."""
    old = _REGISTRY.get(skill.name)
    if old is not None and old is not skill:
        raise ValueError(f"skill {skill.name!r} is already registered")
    _REGISTRY[skill.name] = skill
    if skill.task is not None:
        register_gym(skill.task)
    return skill


def register_gym(task: SkillTaskDef) -> None:
    """Register ``task``'s Gymnasium id (no-op if it is registered already)."""
    import gymnasium

    if task.env_id not in gymnasium.registry:
        gymnasium.register(id=task.env_id, entry_point=task.entry_point, disable_env_checker=True)


def _ensure_loaded() -> None:
    global _LOADED
    if not _LOADED:
        _LOADED = True
        importlib.import_module("ssl_marl.skills.catalog")


def all_skills() -> tuple[SkillDef, ...]:
    """Every registered skill, in catalog order."""
    _ensure_loaded()
    return tuple(_REGISTRY.values())


def skill_names() -> tuple[str, ...]:
    """Canonical names of every registered skill."""
    return tuple(s.name for s in all_skills())


def task_skills() -> tuple[SkillDef, ...]:
    """The skills that have a single-robot learning task (evaluated, trained)."""
    return tuple(s for s in all_skills() if s.task is not None)


def learned_skills() -> tuple[SkillDef, ...]:
    """The skills that have a learned implementation (swappable in STP)."""
    return tuple(s for s in all_skills() if s.has_learned)


def cli_choices() -> tuple[str, ...]:
    """CLI spellings of the skills with a task (``eval-skill``'s choices)."""
    return tuple(s.cli_name for s in task_skills())


def get_skill(name: str) -> SkillDef:
    """The record of skill ``name`` (canonical or CLI spelling); ValueError lists the known ones."""
    _ensure_loaded()
    key = name.replace("-", "_") if isinstance(name, str) else name
    try:
        return _REGISTRY[key]
    except (KeyError, TypeError):
        raise ValueError(f"unknown skill {name!r}; expected one of {tuple(_REGISTRY)}") from None


def get_task(name: str) -> SkillTaskDef:
    """The learning task of skill ``name``; ValueError if it has none."""
    skill = get_skill(name)
    if skill.task is None:
        with_task = tuple(s.cli_name for s in task_skills())
        raise ValueError(f"skill {name!r} has no learning task; skills with one: {with_task}")
    return skill.task


__all__ = ["SKILL_KINDS", "PRETRAINED_DIR", "SkillDef", "SkillTaskDef", "register", "all_skills", "skill_names",
           "task_skills", "learned_skills", "cli_choices", "get_skill", "get_task", "resolve_ref", "direct_env_action"]
