"""What a task may use of the engine that runs it: the :class:`Engine` protocol.

:class:`~ssl_marl.envs.ssl_env.SSLParallelEnv` implements it; tasks are typed against
this protocol only, so the task modules do not import the env.
"""

from __future__ import annotations

from typing import Protocol

import numpy as np

from ...physics.field import FieldGeometry
from ...physics.state import WorldState
from ..config import EnvConfig


class Engine(Protocol):
    """The engine's side of the task API: read the world, move robots and ball, count goals.

    Attributes:
        config: the engine's options.
        field: the field geometry (m, field frame).
        np_random: the episode's generator (seeded by ``reset(seed=...)``).
        possible_agents: every agent, blue first (``blue_0 .. yellow_{n-1}``).
        agents: the live agents of this episode.
    """

    config: EnvConfig
    field: FieldGeometry
    np_random: np.random.Generator
    possible_agents: list[str]
    agents: list[str]

    def agent_index(self, agent: str) -> int:
        """Row of ``agent`` in pose arrays (blue first); ValueError for an unknown agent."""
        ...

    def team_of(self, agent: str) -> str:
        """"blue" or "yellow"."""
        ...

    def world_state(self) -> WorldState:
        """Ground-truth snapshot in the field frame."""
        ...

    def robot_poses(self) -> np.ndarray:
        """(n, 3) field-frame poses (x, y m; heading rad), blue rows first (a copy)."""
        ...

    def place_robots(self, pose: np.ndarray, only: np.ndarray | None = None) -> None:
        """Teleport robots (all, or the rows ``only``) to field-frame ``pose`` (n, 3), at rest."""
        ...

    def place_ball(self, pos: np.ndarray, vel: np.ndarray | None = None) -> None:
        """Teleport the ball to field-frame ``pos`` (m) with velocity ``vel`` (m/s, default at rest)."""
        ...

    def award_goal(self, team: str, events: list[dict]) -> None:
        """Count a goal for ``team`` and record the ``goal`` event."""
        ...


__all__ = ["Engine"]
