"""Decision-level multi-agent tasks: option-level PettingZoo ParallelEnvs over
the engine (:mod:`.base`), their benchmark policies (:mod:`.policies`) and registries.

Layer: beside the runners. It uses envs, skills and plays; plays never import it.

Registries (names used by ``ssl-marl eval-task`` and the trainers):

* :data:`DECISION_TASKS`: task name -> factory ``(**kwargs) -> DecisionEnv``
  ("keepaway": :class:`~ssl_marl.decisions.keepaway.env.KeepawayEnv`; "attack-3v2":
  ``ssl_marl.decisions.attack:Attack3v2Env``, the passing play's options; "attack-drill":
  ``ssl_marl.decisions.attack_drill:AttackDrillEnv``, the attacking plays' options;
  "attack-drill-ssl": ``AttackDrillSSLEnv``, the same drill under SSL rules;
  "attack-drill-defended": ``AttackDrillDefendedEnv``, under SSL rules against the match's defence;
  "attack-drill-mix": ``ssl_marl.decisions.attack_drill_mix:AttackDrillMixEnv``, one of the last two
  drawn per episode).
* :data:`HANDCODED_POLICIES`: task name -> the task's hand-coded benchmark policy class
  ("keepaway": ``HandcodedKeepawayPolicy``; "attack-3v2":
  ``ssl_marl.decisions.attack:HandcodedAttackPolicy``; "attack-drill":
  ``ssl_marl.decisions.attack_drill:HandcodedAttackDrillPolicy``, for all four drills).
* :data:`DECISION_POLICIES`: policy name -> factory ``(task, seed=0, actor=None) ->
  DecisionPolicy`` ("random", "always-hold" (keepaway only), "handcoded", "learned"
  (``ssl_marl.decisions.learned``, the shipped actor or ``actor``), "improved" (the hand-coded
  policy with a value actor at an episode's first decision, ``ImprovedDecisionPolicy``; the shipped
  value actor ``pretrained/<task>_value.pt`` or ``actor``)).

Entries are ``"module:attribute"`` strings imported on first use, so a task whose
module is not in this checkout fails with a clear message when it is asked for, and
importing this package stays cheap. To add a task: one entry in each of the first two
dictionaries (``_TASK_SPECS``, ``_HANDCODED_SPECS``).
"""

from __future__ import annotations

import importlib
from typing import Any, Callable

#: task name -> "module:DecisionEnv subclass"
_TASK_SPECS: dict[str, str] = {
    "keepaway": "ssl_marl.decisions.keepaway.env:KeepawayEnv",
    "attack-3v2": "ssl_marl.decisions.attack:Attack3v2Env",
    "attack-drill": "ssl_marl.decisions.attack_drill:AttackDrillEnv",
    "attack-drill-ssl": "ssl_marl.decisions.attack_drill:AttackDrillSSLEnv",
    "attack-drill-defended": "ssl_marl.decisions.attack_drill:AttackDrillDefendedEnv",
    "attack-drill-mix": "ssl_marl.decisions.attack_drill_mix:AttackDrillMixEnv",
}
#: task name -> "module:hand-coded benchmark policy class" (constructor takes no required arguments)
_HANDCODED_SPECS: dict[str, str] = {
    "keepaway": "ssl_marl.decisions.keepaway.policies:HandcodedKeepawayPolicy",
    "attack-3v2": "ssl_marl.decisions.attack:HandcodedAttackPolicy",
    "attack-drill": "ssl_marl.decisions.attack_drill:HandcodedAttackDrillPolicy",
    "attack-drill-ssl": "ssl_marl.decisions.attack_drill:HandcodedAttackDrillPolicy",
    "attack-drill-defended": "ssl_marl.decisions.attack_drill:HandcodedAttackDrillPolicy",
    "attack-drill-mix": "ssl_marl.decisions.attack_drill:HandcodedAttackDrillPolicy",
}


def load_spec(spec: str, what: str) -> Any:
    """Import ``"module:attribute"``; ValueError saying which module is missing."""
    module, attr = spec.split(":")
    try:
        mod = importlib.import_module(module)
    except ModuleNotFoundError as e:
        if e.name is not None and module.startswith(e.name):
            raise ValueError(f"{what} needs module {module}, which is not in this checkout") from None
        raise
    try:
        return getattr(mod, attr)
    except AttributeError:
        raise ValueError(f"{what}: module {module} has no {attr!r}") from None


def _task_factory(name: str) -> Callable[..., Any]:
    def factory(**kwargs: Any) -> Any:
        return load_spec(_TASK_SPECS[name], f"decision task {name!r}")(**kwargs)

    factory.__name__ = f"make_{name.replace('-', '_')}"
    factory.__doc__ = f"Build the {name!r} DecisionEnv ({_TASK_SPECS[name]}) with keyword arguments."
    return factory


#: task name -> factory(**kwargs) -> DecisionEnv
DECISION_TASKS: dict[str, Callable[..., Any]] = {name: _task_factory(name) for name in _TASK_SPECS}
#: task name -> "module:Class" of its hand-coded benchmark policy
HANDCODED_POLICIES: dict[str, str] = _HANDCODED_SPECS


def _check_task(task: str) -> None:
    if task not in DECISION_TASKS:
        raise ValueError(f"unknown decision task {task!r}; expected one of {tuple(DECISION_TASKS)}")


def _random(task: str, seed: int = 0, actor: str | None = None) -> Any:
    from .policies import RandomPolicy

    _check_task(task)
    return RandomPolicy(seed)


def _always_hold(task: str, seed: int = 0, actor: str | None = None) -> Any:
    _check_task(task)
    if task != "keepaway":
        raise ValueError(f"policy 'always-hold' is a keepaway benchmark; task {task!r} has no hold option")
    from .keepaway.policies import AlwaysHoldPolicy

    return AlwaysHoldPolicy()


def _handcoded(task: str, seed: int = 0, actor: str | None = None) -> Any:
    _check_task(task)
    return load_spec(HANDCODED_POLICIES[task], f"the hand-coded policy of {task!r}")()


def _learned(task: str, seed: int = 0, actor: str | None = None) -> Any:
    _check_task(task)
    learned = load_spec("ssl_marl.decisions.learned:LearnedDecisionPolicy", "policy 'learned'")
    if actor is None:
        actor = load_spec("ssl_marl.decisions.learned:pretrained_path", "policy 'learned'")(task)
    return learned(actor, task=task)


def _improved(task: str, seed: int = 0, actor: str | None = None) -> Any:
    _check_task(task)
    improved = load_spec("ssl_marl.decisions.learned:ImprovedDecisionPolicy", "policy 'improved'")
    if actor is None:
        actor = load_spec("ssl_marl.decisions.learned:pretrained_value_path", "policy 'improved'")(task)
    return improved(_handcoded(task), actor, task=task)


#: policy name -> factory(task, seed=0, actor=None) -> DecisionPolicy
DECISION_POLICIES: dict[str, Callable[..., Any]] = {
    "learned": _learned,
    "handcoded": _handcoded,
    "random": _random,
    "always-hold": _always_hold,
    "improved": _improved,
}


def make_decision_env(task: str, **kwargs: Any) -> Any:
    """``DECISION_TASKS[task](**kwargs)`` with a clear error for an unknown name."""
    _check_task(task)
    return DECISION_TASKS[task](**kwargs)


def make_decision_policy(name: str, task: str, seed: int = 0, actor: str | None = None) -> Any:
    """``DECISION_POLICIES[name](task, seed, actor)`` with a clear error for an unknown name."""
    if name not in DECISION_POLICIES:
        raise ValueError(f"unknown decision policy {name!r}; expected one of {tuple(DECISION_POLICIES)}")
    return DECISION_POLICIES[name](task, seed=seed, actor=actor)


def __getattr__(name: str):
    if name == "DecisionEnv":
        from .base import DecisionEnv

        return DecisionEnv
    if name in ("DecisionPolicy", "RandomPolicy", "run_episode"):
        from . import policies

        return getattr(policies, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = ["DECISION_TASKS", "DECISION_POLICIES", "HANDCODED_POLICIES", "make_decision_env",
           "make_decision_policy", "load_spec", "DecisionEnv", "DecisionPolicy", "RandomPolicy", "run_episode"]
