"""Realism effects: vision noise, ball dropout, observation latency, radio latency and
command loss, as composable effect objects.

Off by default (all parameters zero), as the paper's simulator allows. Noise is drawn
from the env's seeded generator, so runs stay reproducible.

Two pipelines, each a list of effects applied in order:

* :class:`Vision` turns the ground truth into what the teams see. With realism on, the
  cameras first report a ball in the air as SSL-Vision does: projected onto the
  ground-ball plane, no height (:class:`~ssl_marl.envs.camera.CameraRig`; the
  observation's ball height is then 0). Its *measurement effects*
  (:class:`BallDropout`, :class:`VisionNoise`, ...) transform that frame (``apply``);
  the finished measurement is then delayed by ``latency_steps``
  (:class:`ObservationDelay`).
* :class:`Radio` turns commanded actions into executed ones through *command
  effects* (:class:`CommandDelay`, :class:`CommandLoss`, ...).

:func:`vision_effects` / :func:`command_effects` build the lists a
:class:`~ssl_marl.envs.config.RealismConfig` asks for (only the effects that are on).
A new effect is a class with the same methods, added to those lists (or to a
``Vision``/``Radio`` built by hand). The order in the lists is the order random
numbers are drawn in; changing it changes every noisy run.
"""

from __future__ import annotations

from collections import deque
from dataclasses import replace

import numpy as np

from ..physics.state import TeamState, WorldState, make_team_state, wrap_angle
from .camera import CameraRig
from .config import RealismConfig


def _read_only(a: np.ndarray) -> np.ndarray:
    out = np.array(a, dtype=float)
    out.setflags(write=False)
    return out


# ------------------------------------------------------------------ vision
class VisionEffect:
    """One transformation of a measured frame (field frame). ``first`` is True for the
    frame measured at reset."""

    def reset(self, truth: WorldState) -> None:
        """A new episode starts from ``truth``."""

    def apply(self, seen: WorldState, truth: WorldState, rng: np.random.Generator, first: bool) -> WorldState:
        raise NotImplementedError

    def observed(self, seen: WorldState) -> None:
        """The finished measurement of this frame (after every effect)."""


class BallDropout(VisionEffect):
    """The ball is not detected with probability ``p`` per frame (never in the reset
    frame): the frame then holds the last seen (measured) ball position, the true ball
    velocity and ``ball_visible = False``."""

    def __init__(self, p: float) -> None:
        self.p = p
        self._last: np.ndarray | None = None

    def reset(self, truth: WorldState) -> None:
        self._last = truth.ball_pos

    def apply(self, seen: WorldState, truth: WorldState, rng: np.random.Generator, first: bool) -> WorldState:
        if not first and rng.random() < self.p:
            return replace(seen, ball_pos=_read_only(self._last), ball_vel=_read_only(truth.ball_vel),
                           ball_visible=False)
        return seen

    def observed(self, seen: WorldState) -> None:
        if seen.ball_visible:
            self._last = seen.ball_pos


class VisionNoise(VisionEffect):
    """Gaussian noise on robot positions (m), headings (rad), velocities (m/s) and on the
    ball's position and velocity (the ball only when it is visible in this frame).
    A sigma of 0 draws nothing."""

    def __init__(self, robot_pos_sigma: float = 0.0, robot_angle_sigma: float = 0.0, ball_pos_sigma: float = 0.0,
                 vel_sigma: float = 0.0) -> None:
        self.robot_pos_sigma, self.robot_angle_sigma = robot_pos_sigma, robot_angle_sigma
        self.ball_pos_sigma, self.vel_sigma = ball_pos_sigma, vel_sigma

    def _team(self, ts: TeamState, rng: np.random.Generator) -> TeamState:
        if ts.n == 0:
            return ts
        pos = ts.pos + rng.normal(0.0, self.robot_pos_sigma, ts.pos.shape) if self.robot_pos_sigma else ts.pos
        hd = (wrap_angle(ts.heading + rng.normal(0.0, self.robot_angle_sigma, ts.n)) if self.robot_angle_sigma
              else ts.heading)
        vel = ts.vel + rng.normal(0.0, self.vel_sigma, ts.vel.shape) if self.vel_sigma else ts.vel
        return make_team_state(pos, hd, vel, ts.omega, ts.ball_on_dribbler, ts.kick_ready)

    def apply(self, seen: WorldState, truth: WorldState, rng: np.random.Generator, first: bool) -> WorldState:
        bpos, bvel = seen.ball_pos, seen.ball_vel
        if seen.ball_visible:
            bpos = bpos + rng.normal(0.0, self.ball_pos_sigma, 2) if self.ball_pos_sigma else bpos
            bvel = bvel + rng.normal(0.0, self.vel_sigma, 2) if self.vel_sigma else bvel
        return replace(seen, ball_pos=_read_only(bpos), ball_vel=_read_only(bvel),
                       blue=self._team(seen.blue, rng), yellow=self._team(seen.yellow, rng))


class ObservationDelay:
    """Vision latency: what is seen is ``steps`` control steps old (the reset frame
    fills the delay line)."""

    def __init__(self, steps: int) -> None:
        self._queue: deque[WorldState] = deque(maxlen=steps + 1)

    def reset(self, first: WorldState) -> WorldState:
        self._queue.clear()
        for _ in range(self._queue.maxlen):
            self._queue.append(first)
        return self._queue[0]

    def push(self, frame: WorldState) -> WorldState:
        self._queue.append(frame)
        return self._queue[0]


def vision_effects(cfg: RealismConfig) -> list[VisionEffect]:
    """The measurement effects ``cfg`` switches on, in drawing order (dropout, noise)."""
    effects: list[VisionEffect] = []
    if cfg.ball_dropout:
        effects.append(BallDropout(cfg.ball_dropout))
    if cfg.robot_pos_sigma or cfg.robot_angle_sigma or cfg.ball_pos_sigma or cfg.vel_sigma:
        effects.append(VisionNoise(cfg.robot_pos_sigma, cfg.robot_angle_sigma, cfg.ball_pos_sigma, cfg.vel_sigma))
    return effects


class Vision:
    """Turns ground-truth snapshots into what the teams see: the ``camera`` model (a
    ball in the air reported as SSL-Vision does; None: seen where it is, with its
    height), then ``effects`` applied to each frame in order, then ``latency_steps`` of
    delay. With no camera and no effects a frame is the truth itself."""

    def __init__(self, cfg: RealismConfig | None = None, effects: list[VisionEffect] | None = None,
                 latency_steps: int | None = None, camera: CameraRig | None = None) -> None:
        cfg = cfg or RealismConfig()
        self.effects = vision_effects(cfg) if effects is None else list(effects)
        self.delay = ObservationDelay(cfg.obs_latency_steps if latency_steps is None else latency_steps)
        self.camera = camera

    def reset(self, truth: WorldState, rng: np.random.Generator) -> WorldState:
        for e in self.effects:
            e.reset(truth)
        return self.delay.reset(self._measure(truth, rng, first=True))

    def observe(self, truth: WorldState, rng: np.random.Generator) -> WorldState:
        return self.delay.push(self._measure(truth, rng, first=False))

    def _measure(self, truth: WorldState, rng: np.random.Generator, first: bool) -> WorldState:
        seen = truth if self.camera is None else self.camera.observe(truth)
        for e in self.effects:
            seen = e.apply(seen, truth, rng, first)
        for e in self.effects:
            e.observed(seen)
        return seen


# ------------------------------------------------------------------- radio
class CommandEffect:
    """One transformation of the (n, dim) commands on their way to the robots."""

    def reset(self, n: int, dim: int) -> None:
        """A new episode: ``n`` robots, ``dim`` action entries."""

    def apply(self, actions: np.ndarray, rng: np.random.Generator) -> np.ndarray:
        raise NotImplementedError


class CommandDelay(CommandEffect):
    """Radio latency: commands act ``steps`` control steps late (zeros at first)."""

    def __init__(self, steps: int) -> None:
        self.steps = steps
        self._queue: deque[np.ndarray] = deque()

    def reset(self, n: int, dim: int) -> None:
        self._queue = deque(np.zeros((n, dim)) for _ in range(self.steps))

    def apply(self, actions: np.ndarray, rng: np.random.Generator) -> np.ndarray:
        self._queue.append(actions)
        return self._queue.popleft()


class CommandLoss(CommandEffect):
    """Each robot's command is lost with probability ``p``; the robot keeps executing
    its previous command."""

    def __init__(self, p: float) -> None:
        self.p = p
        self._applied = np.zeros((0, 0))

    def reset(self, n: int, dim: int) -> None:
        self._applied = np.zeros((n, dim))

    def apply(self, actions: np.ndarray, rng: np.random.Generator) -> np.ndarray:
        lost = rng.random(actions.shape[0]) < self.p
        self._applied = np.where(lost[:, None], self._applied, actions)
        return self._applied


def command_effects(cfg: RealismConfig) -> list[CommandEffect]:
    """The command effects ``cfg`` switches on, in order (delay, then loss)."""
    effects: list[CommandEffect] = []
    if cfg.cmd_latency_steps:
        effects.append(CommandDelay(cfg.cmd_latency_steps))
    if cfg.cmd_loss:
        effects.append(CommandLoss(cfg.cmd_loss))
    return effects


class Radio:
    """Sends commands through ``effects`` in order (none: commands act at once, unchanged)."""

    def __init__(self, cfg: RealismConfig | None, n: int, action_dim: int,
                 effects: list[CommandEffect] | None = None) -> None:
        self.effects = command_effects(cfg or RealismConfig()) if effects is None else list(effects)
        self.n, self.dim = n, action_dim

    def reset(self) -> None:
        for e in self.effects:
            e.reset(self.n, self.dim)

    def transmit(self, actions: np.ndarray, rng: np.random.Generator) -> np.ndarray:
        """Send this step's (n, dim) actions; return what the robots execute now."""
        if not self.effects:
            return actions
        executed = np.array(actions, dtype=float, copy=True)
        for e in self.effects:
            executed = e.apply(executed, rng)
        return executed


__all__ = ["VisionEffect", "BallDropout", "VisionNoise", "ObservationDelay", "vision_effects", "Vision",
           "CommandEffect", "CommandDelay", "CommandLoss", "command_effects", "Radio"]
