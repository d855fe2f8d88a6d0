"""The start of an episode (:class:`Scene`) and the scene that reset options ask for.

Reset options, shared by the tasks (:func:`scene_from_options`; field frame, metres, radians)::

    {"ball": {"pos": (x, y), "vel": (vx, vy)},
     "robots": {"blue_0": (x, y, heading), ...},
     "formation": "kickoff" | "random"}

Robots not named are placed by the formation: the kickoff formation, or uniformly at
random (0.1 m inside the lines, 0.25 m from every robot and the ball, random heading).
Without a ball position the ball goes to the centre mark (kickoff) or to a random free
spot 0.15 m from the named robots. Random draws come from ``env.np_random``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import gymnasium
import numpy as np

from ..referee import kickoff_poses
from .engine import Engine

KNOWN_OPTIONS = ("ball", "robots", "formation")
FORMATIONS = ("kickoff", "random")


@dataclass(frozen=True)
class Scene:
    """Start of an episode in the field frame: robot poses ``(n, 3)`` (x, y m; heading
    rad; blue rows first), ball position and velocity (m, m/s)."""

    robot_pose: np.ndarray
    ball_pos: np.ndarray
    ball_vel: np.ndarray


def option_vector(v: Any, n: int, name: str) -> np.ndarray | None:
    """``v`` as n finite floats (None stays None); ValueError names the option."""
    if v is None:
        return None
    a = np.asarray(v, dtype=float)
    if a.shape != (n,) or not np.isfinite(a).all():
        raise ValueError(f"reset options: {name} must be {n} finite numbers, got {v!r}")
    return a


def scene_from_options(env: Engine, options: dict, default_formation: str) -> Scene:
    """The scene the reset options ask for (see the module docstring)."""
    cfg, f = env.config, env.field
    unknown = set(options) - set(KNOWN_OPTIONS)
    if unknown:  # tolerated (PettingZoo's API test passes arbitrary options), but said
        gymnasium.logger.warn(f"reset options: ignoring unknown key(s) {sorted(unknown)}; "
                              f"known: {sorted(KNOWN_OPTIONS)}")
    formation = options.get("formation", default_formation)
    if formation not in FORMATIONS:
        raise ValueError(f"reset options: formation must be 'kickoff' or 'random', got {formation!r}")
    ball = options.get("ball", {})
    if not isinstance(ball, dict):
        raise ValueError("reset options: 'ball' must be a dict with 'pos' and/or 'vel'")
    robots = options.get("robots", {})
    for name in robots:
        env.agent_index(name)
    ball_pos = option_vector(ball.get("pos"), 2, "ball.pos")
    ball_vel = option_vector(ball.get("vel", (0.0, 0.0)), 2, "ball.vel")
    fixed = {name: option_vector(p, 3, f"robots.{name}") for name, p in robots.items()}
    pose = np.zeros((len(env.possible_agents), 3))
    if formation == "kickoff":
        if ball_pos is None:
            ball_pos = np.zeros(2)
        pose = kickoff_poses(f, cfg.n_blue, cfg.n_yellow)
    placed: list[np.ndarray] = [p[:2] for p in fixed.values()]
    rng = env.np_random
    if ball_pos is None:
        ball_pos = f.random_free_point(rng, 0.1, placed, 0.15)
    for i, name in enumerate(env.possible_agents):
        if name in fixed:
            pose[i] = fixed[name]
        elif formation == "random":
            xy = f.random_free_point(rng, 0.1, placed + [ball_pos], 0.25)
            placed.append(xy)
            pose[i] = (xy[0], xy[1], rng.uniform(-np.pi, np.pi))
    return Scene(pose, ball_pos, ball_vel)


__all__ = ["Scene", "scene_from_options", "option_vector", "KNOWN_OPTIONS", "FORMATIONS"]
