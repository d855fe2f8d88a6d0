"""The tracker as an opt-in layer over the SSL env: :class:`TrackedVisionEnv`.

``TrackedVisionEnv(env)`` behaves like the wrapped
:class:`~ssl_marl.envs.ssl_env.SSLParallelEnv` (every attribute and method is the
env's), except that ``vision_state(team)`` returns the team's tracked, predicted
state instead of the raw vision: anything that reads ``env.vision_state(team)``
(team controllers, tactics, the skill task wrappers) reads tracked state unchanged.
The raw frames stay available as :meth:`TrackedVisionEnv.raw_vision_state`.

Per team with robots, a :class:`~.tracker.VisionTracker` gets every vision frame
(after ``reset`` and each ``step``; processed when the team next asks, so that in
real-time mode the work counts against that team's control deadline) and every
command the team sent (from the ``step`` action dict; a missing agent sent the zero
action, as the env reads it). A command passed to ``step`` when the world is at
tick k is executed from tick k + radio-delay steps on; in real-time mode, where one
step can span several ticks, from the last of them (the env repeats the previous
command on the missed ones). ``vision_state(team)`` is the tracker's prediction for
now + the radio delay: the state the next command will start to act on. Goal and
ball-out events (the referee teleports robots or the ball) let a detection outside
the gates restart its filter at once.

The per-agent observation vectors that ``reset``/``step`` return are the env's own
(raw vision): consumers of tracked state read ``vision_state``.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ...physics.state import TEAMS, WorldState, to_team_frame
from .params import TrackerParams
from .tracker import VisionTracker


class TrackedVisionEnv:
    """An SSL env whose ``vision_state(team)`` is tracked and latency-compensated.

    Args:
        env: an :class:`~ssl_marl.envs.ssl_env.SSLParallelEnv` (or anything with its
            ``reset/step/vision_state/world_state/config/possible_agents``).
        params: :class:`TrackerParams`; default :meth:`TrackerParams.for_realism` of
            the env's realism config (measurement noise and radio delay).
    """

    def __init__(self, env: Any, params: TrackerParams | None = None) -> None:
        for name in ("reset", "step", "vision_state", "world_state", "config", "possible_agents"):
            if not hasattr(env, name):
                raise ValueError(f"TrackedVisionEnv: the wrapped env has no {name!r} (expected an SSLParallelEnv)")
        if isinstance(env, TrackedVisionEnv):
            raise ValueError("TrackedVisionEnv: the env is already tracked")
        cfg = env.config
        self.env = env
        self.dt = float(cfg.dt)
        self.params = params if params is not None else TrackerParams.for_realism(cfg.realism, self.dt)
        self.radio_steps = int(round(self.params.radio_delay_s / self.dt))
        vision_steps = int(getattr(cfg.realism, "obs_latency_steps", 0))
        self._jump_frames = vision_steps + 2
        self._agents = {team: [a for a in env.possible_agents if a.startswith(team + "_")] for team in TEAMS}
        self.trackers = {team: VisionTracker(team, cfg.robot, cfg.ball, self.dt, cfg.physics_substeps, self.params)
                         for team in TEAMS if self._agents[team]}
        self._pending: dict[str, list[WorldState]] = {team: [] for team in self.trackers}
        self._cache: dict[str, tuple[float, WorldState]] = {}

    def __getattr__(self, name: str) -> Any:  # everything else is the env's
        if name == "env":
            raise AttributeError(name)
        return getattr(self.env, name)

    # ------------------------------------------------------------------ API
    def reset(self, seed: int | None = None, options: dict | None = None):
        out = self.env.reset(seed=seed, options=options)
        for team, tr in self.trackers.items():
            tr.reset()
            self._pending[team] = [self.env.vision_state(team)]
        self._cache.clear()
        return out

    def step(self, actions: dict):
        out = self.env.step(actions)
        tick = int(round(self.env.world_state().t / self.dt)) - 1 + self.radio_steps
        for team, tr in self.trackers.items():
            cmd = np.zeros((len(self._agents[team]), self.env.action_dim))
            for i, agent in enumerate(self._agents[team]):
                if agent in actions:
                    cmd[i] = np.asarray(actions[agent], dtype=float)
            tr.record_command(tick, cmd)
        infos = out[4]
        events = next(iter(infos.values()))["events"] if infos else []
        if any(e.get("type") in ("goal", "ball_out") for e in events):
            for tr in self.trackers.values():
                tr.expect_jump(self._jump_frames)
        for team in self.trackers:
            pending = self._pending[team]
            pending.append(self.env.vision_state(team))
            if len(pending) > 16:  # a team that never asks: keep its tracker current anyway
                self._flush(team)
        self._cache.clear()
        return out

    def _flush(self, team: str) -> None:
        tr = self.trackers[team]
        for frame in self._pending[team]:
            tr.update(frame)
        self._pending[team] = []

    def vision_state(self, team: str | None = None) -> WorldState:
        """The team's tracked state, predicted to now + the radio delay, in its frame
        (``team=None``: blue's, in the field frame, for symmetry with the env)."""
        if team is None:
            ws = self.vision_state("blue" if "blue" in self.trackers else "yellow")
            return ws if ws.frame == "field" else _to_field(ws)
        if team not in TEAMS:
            raise ValueError(f"team: unknown team {team!r}; expected 'blue' or 'yellow'")
        if team not in self.trackers:
            return self.env.vision_state(team)
        now = float(self.env.world_state().t)
        hit = self._cache.get(team)
        if hit is not None and hit[0] == now:
            return hit[1]
        self._flush(team)
        ws = self.trackers[team].predict(now + self.radio_steps * self.dt)
        self._cache[team] = (now, ws)
        return ws

    def raw_vision_state(self, team: str | None = None) -> WorldState:
        """The env's own vision (noisy, delayed), untouched."""
        return self.env.vision_state(team)


def _to_field(ws: WorldState) -> WorldState:
    """Inverse of :func:`to_team_frame` (the rotation by pi is its own inverse)."""
    from dataclasses import replace

    if ws.frame == "blue":
        return replace(ws, frame="field")
    flipped = to_team_frame(replace(ws, frame="field"), "yellow")
    return replace(flipped, frame="field")

