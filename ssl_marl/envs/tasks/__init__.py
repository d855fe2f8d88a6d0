"""Tasks for the full-field engine: what an episode is about (see :mod:`.base`).

``SSLParallelEnv(task=...)`` takes a task name from :data:`TASKS` or a
:class:`Task` object. Built in: ``"match"`` (the default: SSL referee, kickoffs,
team rewards) and ``"free_play"`` (no rules, rewards or end: the world only).
To add a task: subclass :class:`Task` in a new module here (or anywhere, and pass
the object), and add its name to :data:`TASKS` if it should be selectable by name.
Tasks see the env through the :class:`Engine` protocol; the match task's parameters
are :class:`ssl_marl.envs.config.MatchRules`.
"""

from __future__ import annotations

from typing import Any, Callable

from .base import FreePlayTask, Task
from .engine import Engine
from .keepaway import KeepawayRules, KeepawayTask
from .match import MatchTask
from .scene import Scene

#: task name -> factory (no arguments; parameters come from the env config at bind time)
TASKS: dict[str, Callable[[], Task]] = {"match": MatchTask, "free_play": FreePlayTask, "keepaway": KeepawayTask}


def make_task(task: Any) -> Task:
    """A task object from a name in :data:`TASKS` or a :class:`Task` (returned as is);
    ValueError for anything else (the env calls it when it is built)."""
    if isinstance(task, Task):
        return task
    if isinstance(task, str) and task in TASKS:
        return TASKS[task]()
    raise ValueError(f"task must be one of {tuple(TASKS)} or a Task object, got {task!r}")


__all__ = ["Task", "Engine", "Scene", "FreePlayTask", "MatchTask", "KeepawayTask", "KeepawayRules", "TASKS",
           "make_task"]
