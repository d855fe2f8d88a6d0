"""Keepaway 3v2 (Stone, Sutton and Kuhlmann 2005) as an engine task: scene and judge.

Three keepers (blue, ``blue_0..2``) keep the ball from two takers (yellow,
``yellow_0..1``) inside a square centred on the field's centre mark. This task only
places the start and judges; who does what is the decision env's business
(:mod:`ssl_marl.decisions.keepaway`).

**Square size: 5 x 5 m** (``KeepawayRules.side_m``). The original uses 20 x 20 m for
simulated players that run ~1 m/s and kick ~2.7 m/s: a player crosses the region in
~20 s, a kick covers it in ~7 s. Our robots run 3 m/s (3 m/s^2) and our passes leave
at 3-5 m/s to arrive at 2 m/s (kick cap 6.5 m/s, ball slide 3.9 m/s^2, roll
0.35 m/s^2): a 5 m side gives passes of 2.5-5 m (corner to corner 7 m), ~0.8-1.5 s of
flight, in which a taker covers 1.5-3.5 m, so a pass across an open lane is safe and
one near a taker is not, as in the original; and a taker needs ~2.2 s to cross the
square (5 m at 3 m/s with 1 s of acceleration), the same order as a pass plus its
handshake, so holding is not free either. Ball to robot speed ratio: 6.5 / 3 = 2.2 (the
original's ~2.7 / 1 = 2.7). The square fits inside Division B's 9 x 6 m field with
0.5 m to the touch lines (the field and its walls never interfere).

**Start** (drawn from ``env.np_random``): the square's corners, 0.5 m inside it; a
random corner is the takers' (both within 0.3 m of it, facing the centre); keepers
``blue_0`` on the diagonally opposite corner with the ball resting on its dribbler,
``blue_1`` / ``blue_2`` on the two other corners (counter-clockwise after ``blue_0``).
Every robot is jittered by U(-0.2, 0.2) m per axis; keepers face the centre.

**End** (judged on the ground truth after every control tick):

* ``taker_control`` (terminated): a taker *controls* the ball: the ball is on its
  dribbler (touching the face, the engine's contact flag) for ``taker_contact_s``
  (0.1 s) in a row, or within ``taker_near_m`` (3 cm) of its dribbler (d_{d-b}, the
  dribbler-centre to ball-surface distance) for ``taker_near_s`` (0.3 s) in a row.
* ``out`` (terminated): the ball is fully outside the square (its centre more than a
  ball radius beyond a side).
* ``time`` (truncated): ``max_time_s`` (60 s) of simulated time.

**Score**: ``duration_s`` = simulated time from the episode start (t = 0) to the end.
**Rewards** per tick: +dt (s) to every keeper, -dt to every taker, so a keeper's
undiscounted return equals the episode's duration.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

import numpy as np

from .base import Task
from .engine import Engine
from .scene import Scene


OUTCOMES = ("taker_control", "out", "time")


@dataclass(frozen=True)
class KeepawayRules:
    """Attributes:
        side_m: side of the square (m), centred on the field centre.
        corner_inset_m: start spots lie this far inside the square's corners (m).
        jitter_m: start positions jittered by U(-jitter, jitter) per axis (m).
        taker_contact_s: ball on a taker's dribbler this long in a row = control (s).
        taker_near_m: ... or within this of its dribbler (d_{d-b}, m) ...
        taker_near_s: ... this long in a row (s).
        max_time_s: truncation (s).
    """

    side_m: float = 5.0
    corner_inset_m: float = 0.5
    jitter_m: float = 0.2
    taker_contact_s: float = 0.1
    taker_near_m: float = 0.03
    taker_near_s: float = 0.3
    max_time_s: float = 60.0

    def __post_init__(self) -> None:
        for f in fields(self):
            v = getattr(self, f.name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v >= 0):
                raise ValueError(f"KeepawayRules.{f.name} must be a non-negative finite number, got {v!r}")
        if self.side_m <= 2 * self.corner_inset_m + 2 * self.jitter_m:
            raise ValueError(f"KeepawayRules.side_m ({self.side_m}) too small for corner_inset_m and jitter_m")
        if self.max_time_s <= 0:
            raise ValueError(f"KeepawayRules.max_time_s must be positive, got {self.max_time_s!r}")

    @property
    def half(self) -> float:
        return 0.5 * self.side_m


class KeepawayTask(Task):
    """Keepaway 3v2 scene and judge (see the module docstring). After the episode,
    :attr:`outcome` is one of :data:`OUTCOMES` and :attr:`duration_s` its length."""

    name = "keepaway"

    def __init__(self, rules: KeepawayRules | None = None) -> None:
        super().__init__()
        self.rules = rules or KeepawayRules()
        self.outcome: str | None = None
        self.duration_s = 0.0
        self.taker_control_by: int | None = None

    def bind(self, env: Engine) -> None:
        super().bind(env)
        cfg = env.config
        if cfg.n_blue != 3 or cfg.n_yellow != 2:
            raise ValueError(f"keepaway needs n_blue=3 keepers and n_yellow=2 takers, got {cfg.n_blue}v{cfg.n_yellow}")
        h = self.rules.half
        if h > env.field.half_length or h > env.field.half_width:
            raise ValueError(f"keepaway square {self.rules.side_m} m does not fit the {env.field.name} field")
        self._reach = cfg.robot.front_distance
        self._ball_r = cfg.ball.radius
        self._dt = cfg.dt

    # ------------------------------------------------------------------- scene
    def start_scene(self, rng: np.random.Generator, taker_corner: int | None = None) -> Scene:
        """The start for a given generator (see the module docstring)."""
        r, env = self.rules, self._env
        c = r.half - r.corner_inset_m
        corners = np.array([[c, c], [-c, c], [-c, -c], [c, -c]])  # counter-clockwise
        k = int(rng.integers(4)) if taker_corner is None else int(taker_corner) % 4
        jit = rng.uniform(-r.jitter_m, r.jitter_m, size=(5, 2))
        pose = np.zeros((5, 3))
        for j, corner in enumerate((k + 2, k + 3, k + 1)):  # blue_0 diagonal, then ccw
            p = corners[corner % 4] + jit[j]
            pose[j] = (p[0], p[1], math.atan2(-p[1], -p[0]))
        tc = corners[k]
        along = np.array([-tc[1], tc[0]]) / np.hypot(*tc)  # tangential: the takers stand side by side
        for j in range(2):
            p = tc + (j - 0.5) * 0.3 * along + 0.25 * jit[3 + j]
            pose[3 + j] = (p[0], p[1], math.atan2(-p[1], -p[0]))
        h0 = pose[0, 2]
        reach = env.config.robot.front_distance + env.config.ball.radius + 0.002
        ball = pose[0, :2] + reach * np.array([math.cos(h0), math.sin(h0)])
        return Scene(pose, ball, np.zeros(2))

    def reset_scene(self, env: Engine, options: dict) -> Scene:
        """The keepaway start; reset options ``{"ball": ..., "robots": ...}`` (field frame)
        override parts of it (constructed scenes in tests), ``{"taker_corner": 0..3}``
        fixes the takers' corner."""
        options = dict(options or {})
        scene = self.start_scene(env.np_random, options.pop("taker_corner", None))
        if not options:
            return scene
        from .scene import scene_from_options

        pose = scene.robot_pose.copy()
        ball_pos, ball_vel = scene.ball_pos, scene.ball_vel
        robots = options.get("robots", {})
        custom = scene_from_options(env, {"robots": robots, "ball": options.get("ball", {"pos": tuple(ball_pos)}),
                                          "formation": "kickoff"}, default_formation="kickoff")
        for name in robots:
            pose[env.agent_index(name)] = custom.robot_pose[env.agent_index(name)]
        if "ball" in options:
            ball_pos, ball_vel = custom.ball_pos, custom.ball_vel
        return Scene(pose, ball_pos, ball_vel)

    # ------------------------------------------------------------------- judge
    def start(self, env: Engine) -> None:
        self.outcome = None
        self.duration_s = 0.0
        self.taker_control_by = None
        self._contact_ticks = np.zeros(2, np.int64)
        self._near_ticks = np.zeros(2, np.int64)
        r = self.rules
        self._need_contact = max(1, int(round(r.taker_contact_s / self._dt)))
        self._need_near = max(1, int(round(r.taker_near_s / self._dt)))

    def taker_ball_distance(self, world) -> np.ndarray:
        """d_{d-b} (m) of each taker (dribbler-centre to ball surface, field frame)."""
        y = world.yellow
        face = y.pos + self._reach * np.column_stack([np.cos(y.heading), np.sin(y.heading)])
        d = np.sqrt(((world.ball_pos - face) ** 2).sum(axis=1)) - self._ball_r
        return np.maximum(d, 0.0)

    def ball_outside(self, ball_pos: np.ndarray) -> bool:
        """The ball is fully outside the square."""
        lim = self.rules.half + self._ball_r
        return abs(float(ball_pos[0])) > lim or abs(float(ball_pos[1])) > lim

    def after_tick(self, env: Engine, events: list[dict]) -> bool:
        if self.outcome is not None:
            return True
        w = env.world_state()
        on = np.asarray(w.yellow.ball_on_dribbler, bool)
        near = self.taker_ball_distance(w) <= self.rules.taker_near_m
        self._contact_ticks = np.where(on, self._contact_ticks + 1, 0)
        self._near_ticks = np.where(near, self._near_ticks + 1, 0)
        ctrl = (self._contact_ticks >= self._need_contact) | (self._near_ticks >= self._need_near)
        if ctrl.any():
            self.outcome = "taker_control"
            self.taker_control_by = int(np.flatnonzero(ctrl)[0])
        elif self.ball_outside(w.ball_pos):
            self.outcome = "out"
        elif w.t >= self.rules.max_time_s - 1e-9:
            self.outcome = "time"
        if self.outcome is not None:
            self.duration_s = float(w.t)
            events.append({"type": "keepaway_end", "outcome": self.outcome, "t": float(w.t)})
            return True
        return False

    def rewards(self, env: Engine):
        dt = self._dt
        return ({a: (dt if a.startswith("blue") else -dt) for a in env.agents},
                {"blue": {"time": dt}, "yellow": {"time": -dt}})

    def end(self, env: Engine) -> tuple[bool, bool]:
        if self.outcome is None:
            return False, False
        return self.outcome != "time", self.outcome == "time"


__all__ = ["KeepawayRules", "KeepawayTask", "OUTCOMES"]
