"""Vision noise, ball dropout, observation latency, radio latency and command loss.

Off by default (all parameters zero), as the paper's simulator allows. Noise is drawn
from the env's seeded generator, so runs stay reproducible.
"""

from __future__ import annotations

from collections import deque
from dataclasses import replace

import numpy as np

from ..physics.state import TeamState, WorldState, make_team_state, wrap_angle
from .config import RealismConfig


def _noisy_team(ts: TeamState, cfg: RealismConfig, rng: np.random.Generator) -> TeamState:
    if ts.n == 0:
        return ts
    pos = ts.pos + rng.normal(0.0, cfg.robot_pos_sigma, ts.pos.shape) if cfg.robot_pos_sigma else ts.pos
    hd = wrap_angle(ts.heading + rng.normal(0.0, cfg.robot_angle_sigma, ts.n)) if cfg.robot_angle_sigma else ts.heading
    vel = ts.vel + rng.normal(0.0, cfg.vel_sigma, ts.vel.shape) if cfg.vel_sigma else ts.vel
    return make_team_state(pos, hd, vel, ts.omega, ts.ball_on_dribbler, ts.kick_ready)


class Vision:
    """Turns ground-truth snapshots into what the teams see: noisy, with dropped ball
    detections, ``obs_latency_steps`` old."""

    def __init__(self, cfg: RealismConfig) -> None:
        self.cfg = cfg
        self._queue: deque[WorldState] = deque(maxlen=cfg.obs_latency_steps + 1)
        self._last_ball: np.ndarray | None = None

    def reset(self, truth: WorldState, rng: np.random.Generator) -> WorldState:
        self._queue.clear()
        self._last_ball = truth.ball_pos
        first = self._measure(truth, rng, allow_dropout=False)
        for _ in range(self._queue.maxlen):
            self._queue.append(first)
        return self._queue[0]

    def observe(self, truth: WorldState, rng: np.random.Generator) -> WorldState:
        self._queue.append(self._measure(truth, rng))
        return self._queue[0]

    def _measure(self, truth: WorldState, rng: np.random.Generator, allow_dropout: bool = True) -> WorldState:
        cfg = self.cfg
        if not cfg.enabled:
            return truth
        visible = not (allow_dropout and cfg.ball_dropout and rng.random() < cfg.ball_dropout)
        if visible:
            bpos = truth.ball_pos + rng.normal(0.0, cfg.ball_pos_sigma, 2) if cfg.ball_pos_sigma else truth.ball_pos
            bvel = truth.ball_vel + rng.normal(0.0, cfg.vel_sigma, 2) if cfg.vel_sigma else truth.ball_vel
            self._last_ball = bpos
        else:
            bpos, bvel = self._last_ball, truth.ball_vel
        bpos = np.array(bpos, dtype=float)
        bvel = np.array(bvel, dtype=float)
        bpos.setflags(write=False)
        bvel.setflags(write=False)
        return replace(truth, ball_pos=bpos, ball_vel=bvel, ball_visible=visible,
                       blue=_noisy_team(truth.blue, cfg, rng), yellow=_noisy_team(truth.yellow, cfg, rng))


class Radio:
    """Delays commands by ``cmd_latency_steps`` and loses each robot's command with
    probability ``cmd_loss`` (the robot then keeps executing its previous command)."""

    def __init__(self, cfg: RealismConfig, n: int, action_dim: int) -> None:
        self.cfg = cfg
        self.n, self.dim = n, action_dim
        self._queue: deque[np.ndarray] = deque()
        self._applied = np.zeros((n, action_dim))

    def reset(self) -> None:
        self._queue = deque(np.zeros((self.n, self.dim)) for _ in range(self.cfg.cmd_latency_steps))
        self._applied = np.zeros((self.n, self.dim))

    def transmit(self, actions: np.ndarray, rng: np.random.Generator) -> np.ndarray:
        """Send this step's (n, dim) actions; return what the robots execute now."""
        if not self.cfg.enabled:
            return actions
        self._queue.append(np.array(actions, dtype=float, copy=True))
        arriving = self._queue.popleft()
        if self.cfg.cmd_loss:
            lost = rng.random(self.n) < self.cfg.cmd_loss
            arriving = np.where(lost[:, None], self._applied, arriving)
        self._applied = arriving
        return arriving
