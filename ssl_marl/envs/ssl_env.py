"""The full-field SSL env as a PettingZoo ParallelEnv.

Agents: ``blue_0 .. blue_{n_blue-1}``, ``yellow_0 .. yellow_{n_yellow-1}``.

Observation
    Per agent, ``Box(low, high, (D,), float32)`` in the agent's team frame (own
    goal at -x). Index by index layout and the finite bounds (field walls + margin,
    speed caps x safety factor; observations are clipped into them) in
    :mod:`ssl_marl.envs.observation` (D = 21 + 7 * (obs_max_teammates +
    obs_max_opponents) = 168 by default; 170 with chip kicks: the ball's height (m)
    and vertical velocity (m/s) appended).
    ``state()`` / ``state_space``: the whole world in the field frame (see
    :func:`ssl_marl.envs.observation.state_vector`).

Action
    Per agent, ``Box(-1, 1, (5,), float32)``: body-frame vx, vy, omega (fractions of
    the robot limits), dribbler (on when > 0), kick strength (kick when > 0). See
    :mod:`ssl_marl.envs.actions`. Agents missing from the action dict do nothing
    this step (zero action). NaN/inf, a wrong shape or an unknown agent raise
    ``ValueError`` naming the agent; finite values outside [-1, 1] are clipped.

Versions
    v0 (the default): the layouts above. v1, ``chip_kicks=True``
    (``ssl_marl.envs.parallel_env(chip_kicks=True)``, metadata name ``ssl_marl_v1``):
    the ball can fly. The action gains a sixth entry, the chip (kick elevation =
    value x ``chip_angle_max`` when > 0, else flat), the observation the ball's height
    and vertical velocity at its end, and the robots kick on contact (see
    :class:`~ssl_marl.envs.config.EnvConfig`). A goal then counts only if the ball was
    never higher than 0.15 m since the last touch (:mod:`ssl_marl.envs.referee`).

Task
    What an episode is about (start, rules, rewards, end) is the env's task
    (``task=``, :mod:`ssl_marl.envs.tasks`): by default the full-field match
    (:class:`~ssl_marl.envs.tasks.match.MatchTask`):

    Reward: shared by a team: sum over named terms x ``reward_scales``. ``goal``: +1
    when the team scores, -1 when it concedes (default scale 1). ``ball_progress``:
    ball displacement towards the opponent goal / (L/2) (default scale 0).
    ``possession``: +dt while a robot of the team holds the ball on its dribbler
    (default 0). Scaled per-term values are in ``infos[agent]["reward_terms"]``.

    Termination / truncation: truncation for every agent when simulated time reaches
    ``max_time_s``. Termination after a goal if ``after_goal == "terminate"``;
    otherwise the kickoff formation is placed and play goes on. Ball out of play ->
    ball placed inside the field. Events ("goal", "ball_out", "kick") are listed in
    ``infos[agent]["events"]``; the score in ``infos[agent]["score"]``.

Reset options
    ``{"ball": {"pos": (x, y), "vel": (vx, vy)}, "robots": {"blue_0": (x, y, heading), ...},
    "formation": "kickoff" | "random"}`` (field frame, metres, radians). Robots not
    named are placed by the formation (``randomize_reset`` picks the default).
"""

from __future__ import annotations

from typing import Any

import gymnasium
import numpy as np
from gymnasium.utils import EzPickle
from pettingzoo import ParallelEnv

from ..physics.state import WorldState, to_team_frame
from ..physics.world import PhysicsWorld
from .actions import action_dim, chip_angles, scale_actions, validate_actions
from .camera import CameraRig
from .config import EnvConfig, RealismConfig, make_config
from .deadline import ControlDeadline
from .observation import (
    all_observations,
    clip_to_bounds,
    obs_dim,
    observation_bounds,
    state_bounds,
    state_dim,
    state_vector,
)
from .randomization import DomainRandomization, resolve_randomization
from .realism import Radio, Vision
from .tasks import Task, make_task


class SSLParallelEnv(ParallelEnv, EzPickle):
    """Full-field SSL simulator (Box2D) with the PettingZoo Parallel API. Options: see
    :func:`ssl_marl.envs.config.make_config` (all keyword arguments: the
    :class:`~ssl_marl.envs.config.EnvConfig` fields and the match task's
    :class:`~ssl_marl.envs.config.MatchRules` fields). It implements the tasks'
    :class:`~ssl_marl.envs.tasks.engine.Engine` protocol."""

    metadata = {"name": "ssl_marl_v0", "render_modes": ["human", "rgb_array"], "render_fps": 60,
                "is_parallelizable": True}

    def __init__(self, **config: Any) -> None:
        EzPickle.__init__(self, **config)
        self.config: EnvConfig = make_config(**config)
        cfg = self.config
        #: per-episode domain randomisation (None: off), resolved from ``config.randomization``
        self.randomization: DomainRandomization | None = resolve_randomization(cfg.randomization)
        self.task: Task = make_task(cfg.task)
        self.field = cfg.field
        self.render_mode = cfg.render_mode
        self.possible_agents = [f"blue_{i}" for i in range(cfg.n_blue)] + [f"yellow_{i}" for i in range(cfg.n_yellow)]
        self.agents: list[str] = []
        self._index = {a: i for i, a in enumerate(self.possible_agents)}
        self.n = len(self.possible_agents)
        if cfg.chip_kicks:
            self.metadata = {**self.metadata, "name": "ssl_marl_v1"}
        #: action length per agent (5; 6 with chip kicks)
        self.action_dim = action_dim(cfg.chip_kicks)
        d = obs_dim(cfg.obs_max_teammates, cfg.obs_max_opponents, cfg.chip_kicks)
        self._obs_low, self._obs_high = observation_bounds(cfg.field, cfg.robot, cfg.obs_max_teammates,
                                                           cfg.obs_max_opponents,
                                                           cfg.ball if cfg.chip_kicks else None)
        self._obs_space = gymnasium.spaces.Box(self._obs_low, self._obs_high, (d,), np.float32)
        self._act_space = gymnasium.spaces.Box(-1.0, 1.0, (self.action_dim,), np.float32)
        self.observation_spaces = {a: self._obs_space for a in self.possible_agents}
        self.action_spaces = {a: self._act_space for a in self.possible_agents}
        self._state_low, self._state_high = state_bounds(cfg.field, cfg.robot, self.n)
        self.state_space = gymnasium.spaces.Box(self._state_low, self._state_high, (state_dim(self.n),), np.float32)
        self.physics = PhysicsWorld(cfg.field, cfg.robot, cfg.ball, cfg.n_blue, cfg.n_yellow, cfg.dt,
                                    cfg.physics_substeps)
        self.vision = self._vision(cfg.realism)
        self.radio = Radio(cfg.realism, self.n, self.action_dim)
        #: this episode's domain-randomised conditions (None without randomisation)
        self.conditions = None
        self._truth: WorldState | None = None
        self._seen: WorldState | None = None
        self._noise_rng = np.random.default_rng(0)
        self.np_random = np.random.default_rng()
        self.score = {"blue": 0, "yellow": 0}
        self._prev_cmd = np.zeros((self.n, self.action_dim))
        self._deadline = ControlDeadline(self.config.dt)
        self._renderer = None
        self._team_of = {a: a.split("_")[0] for a in self.possible_agents}
        self.task.bind(self)

    # ------------------------------------------------------------------ spaces
    def observation_space(self, agent: str) -> gymnasium.spaces.Box:
        self._check_agent(agent)
        return self._obs_space

    def action_space(self, agent: str) -> gymnasium.spaces.Box:
        self._check_agent(agent)
        return self._act_space

    def _check_agent(self, agent: str) -> int:
        try:
            return self._index[agent]
        except KeyError:
            raise ValueError(f"unknown agent {agent!r}; agents are {self.possible_agents}") from None

    # ------------------------------------------------------------------- reset
    def reset(self, seed: int | None = None, options: dict | None = None):
        if seed is not None:
            self.np_random = np.random.default_rng(seed)
        self._noise_rng = np.random.default_rng(self.np_random.integers(2 ** 63))
        if self.randomization is not None:
            self._apply_conditions(np.random.default_rng(self.np_random.integers(2 ** 63)))
        options = dict(options or {})
        scene = self.task.reset_scene(self, options)
        self.physics.reset(scene.robot_pose, scene.ball_pos, scene.ball_vel)
        self.agents = list(self.possible_agents)
        self.score = {"blue": 0, "yellow": 0}
        self._prev_cmd = np.zeros((self.n, self.action_dim))
        self.radio.reset()
        self._truth = self.physics.snapshot()
        self._seen = self.vision.reset(self._truth, self._noise_rng)
        self.task.start(self)
        if self._renderer is not None:
            self._renderer.reset_trails()
        self._deadline.start()
        obs = self._observations()
        infos = {a: {"events": [], "score": dict(self.score)} for a in self.agents}
        if self.conditions is not None:
            cond = self.conditions.as_dict()
            for a in self.agents:
                infos[a]["conditions"] = cond
        if self.render_mode == "human":
            self.render()
        return obs, infos

    def _apply_conditions(self, rng: np.random.Generator) -> None:
        """Domain randomisation (:attr:`randomization`): draw this episode's conditions
        and rebuild vision, radio and the physics parameters from them. Actions stay
        scaled by the nominal ``config.robot`` (a command is a velocity in m/s; a slower
        robot simply cannot follow a fast one)."""
        cfg = self.config
        self.conditions = self.randomization.draw(rng, cfg.robot, cfg.ball)
        self.vision = self._vision(self.conditions.realism)
        self.radio = Radio(self.conditions.realism, self.n, self.action_dim)
        self.physics.set_params(robot=self.conditions.robot, ball=self.conditions.ball)

    def _vision(self, realism: RealismConfig) -> Vision:
        """The vision pipeline of ``realism``: with realism on, the cameras report a ball
        in the air as SSL-Vision does (:mod:`ssl_marl.envs.camera`)."""
        camera = CameraRig(self.field, self.config.ball.radius) if realism.enabled else None
        return Vision(realism, camera=camera)

    # -------------------------------------------------------------------- step
    def _action_array(self, actions: dict) -> np.ndarray:
        if not isinstance(actions, dict):
            raise ValueError(f"actions must be a dict agent -> action, got {type(actions).__name__}")
        dim = self.action_dim
        arr = np.zeros((self.n, dim))
        for agent, act in actions.items():
            i = self._check_agent(agent)
            if agent not in self.agents:
                raise ValueError(f"agent {agent!r} is not live (episode over: call reset())")
            a = np.asarray(act, dtype=float)
            if a.shape != (dim,):
                raise ValueError(f"action for agent {agent!r} must have shape ({dim},), got {a.shape}")
            arr[i] = a
        validate_actions(arr, self.possible_agents)
        return arr

    def step(self, actions: dict):
        if not self.agents:
            raise RuntimeError("step() called on a finished episode: call reset() first")
        cmd = self._action_array(actions)
        events: list[dict] = []
        n_ticks = 1
        if self.config.realtime:
            n_ticks = self._deadline.wait_for_tick()
            if n_ticks > 1:
                events.append({"type": "missed_deadline", "steps": n_ticks - 1})
        self.task.begin_step(self)
        for tick in range(n_ticks):
            sent = self._prev_cmd if tick < n_ticks - 1 else cmd
            self._physics_tick(sent, events)
            if self.task.after_tick(self, events):
                break
        self._prev_cmd = cmd
        rewards, terms = self.task.rewards(self)
        terminated, truncated = self.task.end(self)
        self.task.after_step(self, terminated, truncated)
        self._seen = self.vision.observe(self._truth, self._noise_rng)
        obs = self._observations()
        term = {a: bool(terminated) for a in self.agents}
        trunc = {a: bool(truncated) for a in self.agents}
        infos = {}
        for a in self.agents:
            infos[a] = {"events": events, "score": dict(self.score), "reward_terms": terms.get(self._team_of[a], {})}
        if terminated or truncated:
            self.agents = []
        if self.render_mode == "human":
            self.render()
        return obs, rewards, term, trunc, infos

    def _physics_tick(self, cmd: np.ndarray, events: list[dict]) -> None:
        executed = self.radio.transmit(cmd, self._noise_rng)
        v, w, drib, kick = scale_actions(executed, self.config.robot)
        if self.config.chip_kicks:
            self.physics.step(v, w, drib, kick, chip=chip_angles(executed, self.config.robot))
        else:
            self.physics.step(v, w, drib, kick)
        for i, speed in self.physics.kicks_this_step:
            events.append({"type": "kick", "agent": self.possible_agents[i], "speed": speed})
        self._truth = self.physics.snapshot()

    # ------------------------------------------------- services for the task
    def agent_index(self, agent: str) -> int:
        """Row of ``agent`` in pose arrays (blue first); ValueError for an unknown agent."""
        return self._check_agent(agent)

    def team_of(self, agent: str) -> str:
        """"blue" or "yellow"."""
        return self._team_of[agent]

    def robot_poses(self) -> np.ndarray:
        """(n, 3) field-frame poses (x, y m; heading rad), blue rows first (a copy)."""
        return np.column_stack([self.physics.pos, self.physics.heading])

    def place_robots(self, pose: np.ndarray, only: np.ndarray | None = None) -> None:
        """Teleport robots (all, or the rows ``only``) to field-frame ``pose`` (n, 3), at rest."""
        self.physics.set_robots(pose, only=only)
        self._truth = self.physics.snapshot()

    def place_ball(self, pos: np.ndarray, vel: np.ndarray | None = None) -> None:
        """Teleport the ball to field-frame ``pos`` (m) with velocity ``vel`` (m/s, default at rest)."""
        self.physics.set_ball(pos, vel)
        self._truth = self.physics.snapshot()

    def award_goal(self, team: str, events: list[dict]) -> None:
        """Count a goal for ``team`` and record the ``goal`` event."""
        self.score[team] += 1
        events.append({"type": "goal", "team": team, "t": self._truth.t})


    # ------------------------------------------------------------ observations
    def _observations(self) -> dict[str, np.ndarray]:
        cfg = self.config
        if not cfg.observations:  # the runner's controllers read vision_state()
            return {}
        ob = all_observations(self._seen, self.field, cfg.obs_max_teammates, cfg.obs_max_opponents, cfg.chip_kicks)
        return dict(zip(self.possible_agents, clip_to_bounds(ob, self._obs_low, self._obs_high)))

    def world_state(self) -> WorldState:
        """Ground-truth snapshot in the field frame (what the referee and rewards read)."""
        return self._truth

    def vision_state(self, team: str | None = None) -> WorldState:
        """What the teams see (noise, dropout, latency applied when realism is on), in
        the field frame, or in ``team``'s frame (own goal at -x) if given."""
        return self._seen if team is None else to_team_frame(self._seen, team)

    def state(self) -> np.ndarray:
        return clip_to_bounds(state_vector(self._truth), self._state_low, self._state_high)

    # ---------------------------------------------------------------- render
    def render(self):
        if self.render_mode is None:
            gymnasium.logger.warn("render() called without a render_mode; pass render_mode='rgb_array' or 'human'")
            return None
        if self._renderer is None:
            from .render import FieldRenderer

            self._renderer = FieldRenderer(self.field, self.config.robot, self.config.ball,
                                           width_px=self.config.render_width_px, trails=self.config.render_trails,
                                           team_labels=self.config.render_team_labels)
        text = f"t={self._truth.t:5.1f} s   blue {self.score['blue']} - {self.score['yellow']} yellow"
        frame = self._renderer.draw(self._truth, info_text=text)
        if self.render_mode == "human":
            self._renderer.show(frame)
            return None
        return frame

    def close(self) -> None:
        if self._renderer is not None:
            self._renderer.close()
            self._renderer = None
