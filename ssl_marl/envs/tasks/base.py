"""The task API: what an episode of the engine is about.

:class:`~ssl_marl.envs.ssl_env.SSLParallelEnv` is the *engine*: physics, realism
effects, actions, observations, rendering. A :class:`Task` says everything else:
where an episode starts (:meth:`Task.reset_scene`), which rules apply after each
control tick (:meth:`Task.after_tick`: a referee, a drill's own judge, nothing),
what each agent is rewarded (:meth:`Task.rewards`), when the episode ends
(:meth:`Task.end`) and what happens between steps (:meth:`Task.after_step`, e.g. a
kickoff after a goal). The engine calls these hooks in a fixed order every step::

    reset:  scene = task.reset_scene(env, options)   # env.np_random is seeded
            (world built from the scene)
            task.start(env)
    step:   task.begin_step(env)
            for each control tick in the step (several in real-time mode when late):
                physics tick; kick events
                if task.after_tick(env, events): break     # e.g. a goal
            rewards, terms = task.rewards(env)
            terminated, truncated = task.end(env)
            task.after_step(env, terminated, truncated)

A task reads the world through the engine's public methods (``world_state()``,
``robot_poses()``, ``config``, ``field``, ``np_random``) and changes it only through
``place_robots``, ``place_ball`` and ``award_goal``: the :class:`~.engine.Engine`
protocol, which the hooks are typed against. One task object belongs to one
env (it may keep per-episode state). Multi-agent drills (keepaway, attack drills)
are tasks too: their own scene, judge, per-agent rewards and end.
"""

from __future__ import annotations

from .engine import Engine
from .scene import Scene, scene_from_options


class Task:
    """Base task: no rules, no rewards, never ends (override what a task needs)."""

    name = "task"

    def __init__(self) -> None:
        self._env: Engine | None = None

    def bind(self, env: Engine) -> None:
        """Called once by the engine that owns this task."""
        if self._env is not None and self._env is not env:
            raise ValueError(f"task {self.name!r} already belongs to another env; build one task per env")
        self._env = env

    def reset_scene(self, env: Engine, options: dict) -> Scene:
        """The episode's start (default: the reset options, see :func:`~.scene.scene_from_options`)."""
        return scene_from_options(env, options, default_formation="kickoff")

    def start(self, env: Engine) -> None:
        """The world exists (``env.world_state()``): initialise per-episode state."""

    def begin_step(self, env: Engine) -> None:
        """A step begins (before its first physics tick)."""

    def after_tick(self, env: Engine, events: list[dict]) -> bool:
        """Judge the world after one physics tick; append events; True stops the step's
        remaining ticks (real-time catch-up)."""
        return False

    def rewards(self, env: Engine) -> tuple[dict[str, float], dict[str, dict[str, float]]]:
        """(reward per live agent, named reward terms per team) for this step."""
        return {a: 0.0 for a in env.agents}, {"blue": {}, "yellow": {}}

    def end(self, env: Engine) -> tuple[bool, bool]:
        """(terminated, truncated) for every agent after this step."""
        return False, False

    def after_step(self, env: Engine, terminated: bool, truncated: bool) -> None:
        """Between steps (after rewards and the end test): e.g. place a kickoff."""


class FreePlayTask(Task):
    """No referee, no rewards, no end: the world only, for wrappers that judge episodes
    themselves (the single-robot skill tasks) and for scripted scenes. Reset options
    place robots and ball; robots not named take the kickoff formation."""

    name = "free_play"


__all__ = ["Task", "FreePlayTask"]
