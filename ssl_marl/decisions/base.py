"""Decision-level multi-agent tasks: the generic PettingZoo ParallelEnv over the engine.

A :class:`DecisionEnv` wraps the full-field engine
(:class:`~ssl_marl.envs.ssl_env.SSLParallelEnv`) with a task (``ssl_marl/envs/tasks``:
scene, judge, per-tick rewards, end) and turns it into an *option-level* game: the
learning team's robots (``possible_agents``, e.g. ``keeper_0..2``) choose among a few
discrete options (``option_names``) at explicit decision points, and everything in
between (running the chosen option's tactics, the teammates' fixed behaviours, the
opponents' hand-coded policy) is simulated at the engine's 60 Hz control rate.

Step semantics:

* ``reset(seed, options) -> (obs, infos)``; ``step(actions) -> (obs, rewards,
  terminations, truncations, infos)``. All agents live for the whole episode.
* A step first starts the options of the agents whose ``infos[agent]["decision"]`` was
  True (their actions are read; other agents' actions are validated and ignored), then
  advances the simulator tick by tick (1/60 s) until (a) at least one agent has a
  decision to make, (b) the episode ends (the task terminates or truncates it), or
  (c) ``max_interval_s`` of simulated time has passed in this step.
* ``infos[agent]``: ``"decision"`` (bool: this agent's action is read at the NEXT
  step), ``"action_mask"`` (int8 ``(n_options,)``, legal options; all ones when
  ``decision`` is False), ``"elapsed_s"`` (simulated seconds the step spanned; 0.0
  after reset), ``"t"`` (simulated time since reset, s); at the end of the episode
  also ``"outcome"`` (str) and the task's score (e.g. ``"duration_s"``).
* Rewards: per agent, the sum of the task's per-tick rewards over the step's ticks,
  *undiscounted*. A step in which an agent made no decision (its flag was False)
  still returns that agent's reward: it belongs to the agent's last decision.

SMDP return (what the MAPPO trainer computes; ``tau`` is its time constant in s):
for an agent's decisions k = 0, 1, ... made at simulated times t_k, with R_k the sum
of the step rewards from decision k up to (not including) decision k+1 and
Delta_k = t_{k+1} - t_k (the sum of the steps' ``elapsed_s`` over that span)::

    G_k = R_k + gamma ** (Delta_k / tau) * G_{k+1}      (G after the last decision: 0
                                                        on termination, V(s) on truncation)

Illegal options: an option whose ``action_mask`` entry is 0, chosen by an agent that
decides, raises ``ValueError`` (``illegal_option="raise"``, the default), or is
replaced by the env's documented ``default_option`` (``illegal_option="default"``).
An action that is not an integer in ``[0, n_options)`` (NaN, out of range, wrong
type) or an unknown agent name always raises ``ValueError`` naming the agent.

Vision: the options' tactics, the fixed behaviours and the observations read
``self.engine.vision_state(team)``; with ``tracker`` on (default "auto": on unless
realism is "none", :func:`~ssl_marl.envs.tracking.resolve_tracker`) that is the vision
tracker's estimate (:class:`~ssl_marl.envs.tracking.TrackedVisionEnv` around the
engine), as in matches. Judges and global states read the ground truth.

Seeding: ``reset(seed=s)`` seeds the engine (scene draws, realism noise) and the
env's own generator ``self.np_random`` (for subclasses' random choices); equal seeds
and actions give equal episodes.

Subclass hooks (see :class:`DecisionEnv`): ``make_task``, ``engine_kwargs``,
``agent_robot``, ``on_reset``, ``decision_agents``, ``action_mask``,
``start_options``, ``tick_actions``, ``after_tick``, ``observe``,
``observation_bounds``, ``global_state``, ``state_bounds``, ``episode_info``.
"""

from __future__ import annotations

import math
from typing import Any, ClassVar, Mapping

import gymnasium
import numpy as np
from pettingzoo import ParallelEnv

from ..envs.ssl_env import SSLParallelEnv
from ..envs.tasks import Task
from ..envs.tracking import with_tracker

ILLEGAL_OPTION_MODES = ("raise", "default")


class DecisionEnv(ParallelEnv):
    """Option-level PettingZoo ParallelEnv over the engine and a task (module docstring).

    Args:
        field: "div_b" (default), "div_a" or a FieldGeometry (robot parameters are the
            same on both; the field only bounds the world around the task's area).
        realism: engine realism preset ("none", "realistic") or a RealismConfig.
        max_interval_s: longest simulated time one step may span (s) without a decision.
        illegal_option: "raise" or "default" (see the module docstring).
        render_mode: None or "rgb_array" (the engine's renderer).
        tracker: "auto" (default; on unless realism is "none"), "on" / True or
            "off" / False: the vision tracker between the engine's vision and everything
            that reads ``self.engine.vision_state`` (module docstring).

    Class attributes a subclass sets: ``task_name`` (registry name),
    ``option_names``, ``agent_prefix`` (agents are ``f"{agent_prefix}_{i}"``),
    ``n_agents``, ``team`` (the learning team's colour), ``default_option``;
    ``engine_observations`` False when the subclass builds its observations from
    ``vision_state`` alone (the engine then skips its per-robot observation vectors).
    """

    metadata = {"name": "ssl_marl_decision_v0", "render_modes": ["rgb_array"], "is_parallelizable": True}

    task_name: ClassVar[str] = "decision"
    option_names: ClassVar[tuple[str, ...]] = ()
    agent_prefix: ClassVar[str] = "agent"
    n_agents: ClassVar[int] = 1
    team: ClassVar[str] = "blue"
    default_option: ClassVar[int] = 0
    engine_observations: ClassVar[bool] = True

    def __init__(self, field: Any = "div_b", realism: Any = "none", max_interval_s: float = 4.0,
                 illegal_option: str = "raise", render_mode: str | None = None, tracker: Any = "auto") -> None:
        if not (isinstance(max_interval_s, (int, float)) and math.isfinite(max_interval_s) and max_interval_s > 0):
            raise ValueError(f"max_interval_s must be a positive number of seconds, got {max_interval_s!r}")
        if illegal_option not in ILLEGAL_OPTION_MODES:
            raise ValueError(f"illegal_option must be one of {ILLEGAL_OPTION_MODES}, got {illegal_option!r}")
        if render_mode not in (None, "rgb_array"):
            raise ValueError(f"render_mode must be None or 'rgb_array', got {render_mode!r}")
        self.max_interval_s = float(max_interval_s)
        self.illegal_option = illegal_option
        self.render_mode = render_mode
        self.task: Task = self.make_task()
        kwargs = dict(field=field, realism=realism, referee=False, task=self.task, render_mode=render_mode,
                      obs_max_teammates=0, obs_max_opponents=0, max_time_s=1e9)
        kwargs.update(self.engine_kwargs())
        sim = SSLParallelEnv(**kwargs)
        if not self.engine_observations:
            sim._observations = dict  # ~10 % of a tick spared
        self.engine = with_tracker(sim, tracker)
        self.field = self.engine.field
        self.dt = float(self.engine.config.dt)
        self.possible_agents = [f"{self.agent_prefix}_{i}" for i in range(self.n_agents)]
        self.agents: list[str] = []
        self._robot_of = {a: self.agent_robot(a) for a in self.possible_agents}
        self.n_options = len(self.option_names)
        if self.n_options < 1:
            raise ValueError(f"{type(self).__name__}.option_names is empty")
        lo, hi = self.observation_bounds()
        self._obs_low, self._obs_high = np.asarray(lo, np.float32), np.asarray(hi, np.float32)
        self._obs_space = gymnasium.spaces.Box(self._obs_low, self._obs_high, self._obs_low.shape, np.float32)
        slo, shi = self.state_bounds()
        self._state_low, self._state_high = np.asarray(slo, np.float32), np.asarray(shi, np.float32)
        self.state_space = gymnasium.spaces.Box(self._state_low, self._state_high, self._state_low.shape, np.float32)
        self._act_space = gymnasium.spaces.Discrete(self.n_options)
        self.observation_spaces = {a: self._obs_space for a in self.possible_agents}
        self.action_spaces = {a: self._act_space for a in self.possible_agents}
        self.np_random = np.random.default_rng()
        self._deciding: frozenset[str] = frozenset()
        self._masks: dict[str, np.ndarray] = {}
        self._ones = np.ones(self.n_options, np.int8)
        self.t = 0.0
        self.episode_seed: int | None = None  # the seed of the last reset (None: unseeded)
        self.decisions = 0  # decisions taken this episode (all agents)
        self.ticks = 0  # control ticks simulated this episode

    # ------------------------------------------------------------ subclass hooks
    def make_task(self) -> Task:
        """The engine task (scene, judge, per-tick rewards, end); one per env."""
        raise NotImplementedError

    def engine_kwargs(self) -> dict:
        """Extra SSLParallelEnv keyword arguments (n_blue, n_yellow, ...)."""
        return {}

    def agent_robot(self, agent: str) -> str:
        """The engine agent (``blue_i`` / ``yellow_i``) a decision agent drives."""
        return f"{self.team}_{int(agent.rsplit('_', 1)[1])}"

    def on_reset(self) -> None:
        """The engine was reset (``self.engine.world_state()`` is the start): build the
        episode's controllers. ``self.np_random`` is seeded."""

    def decision_agents(self) -> frozenset[str]:
        """Agents that have a decision to make now (called after reset and every tick)."""
        raise NotImplementedError

    def action_mask(self, agent: str) -> np.ndarray:
        """Legal options (int8, ``(n_options,)``) of a deciding agent (default: all)."""
        return self._ones

    def start_options(self, chosen: Mapping[str, int]) -> None:
        """Start the options chosen by the deciding agents (agent -> option index)."""
        raise NotImplementedError

    def tick_actions(self) -> dict[str, np.ndarray]:
        """Engine actions (engine agent -> (5,) array) for the next tick, all robots."""
        raise NotImplementedError

    def after_tick(self) -> None:
        """Bookkeeping after each tick (e.g. option timers), before the decision test."""

    def observe(self) -> dict[str, np.ndarray]:
        """Observations of all agents (float32, inside ``observation_bounds``)."""
        raise NotImplementedError

    def observation_bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """(low, high) finite float32 bounds of one agent's observation."""
        raise NotImplementedError

    def global_state(self) -> np.ndarray:
        """The global state vector (float32, inside ``state_bounds``)."""
        raise NotImplementedError

    def state_bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """(low, high) finite float32 bounds of :meth:`state`."""
        raise NotImplementedError

    def episode_info(self) -> dict:
        """Score and outcome added to every agent's info when the episode ends
        (must contain ``"outcome"``)."""
        return {"outcome": getattr(self.task, "outcome", None)}

    # ------------------------------------------------------------- spaces / API
    def observation_space(self, agent: str) -> gymnasium.spaces.Box:
        self._check_agent(agent)
        return self._obs_space

    def action_space(self, agent: str) -> gymnasium.spaces.Discrete:
        self._check_agent(agent)
        return self._act_space

    def _check_agent(self, agent: Any) -> str:
        if agent not in self._robot_of:
            raise ValueError(f"unknown agent {agent!r}; agents are {self.possible_agents}")
        return agent

    def state(self) -> np.ndarray:
        s = np.asarray(self.global_state(), np.float32)
        return np.clip(s, self._state_low, self._state_high)

    def _obs(self) -> dict[str, np.ndarray]:
        obs = self.observe()
        return {a: np.clip(np.asarray(obs[a], np.float32), self._obs_low, self._obs_high) for a in self.possible_agents}

    def _infos(self, elapsed: float) -> dict[str, dict]:
        infos = {}
        for a in self.possible_agents:
            dec = a in self._deciding
            infos[a] = {"decision": dec, "action_mask": self._masks[a] if dec else self._ones.copy(),
                        "elapsed_s": float(elapsed), "t": float(self.t)}
        return infos

    def _update_decisions(self) -> None:
        self._deciding = frozenset(self.decision_agents())
        self._masks = {a: np.asarray(self.action_mask(a), np.int8).copy() for a in self._deciding}

    # ------------------------------------------------------------------- reset
    def reset(self, seed: int | None = None, options: dict | None = None):
        if seed is not None:
            self.np_random = np.random.default_rng(np.random.SeedSequence([int(seed), 1]))
            eng_seed: int | None = int(seed)
        else:
            eng_seed = int(self.np_random.integers(2 ** 31))
        self.episode_seed = seed
        self.engine.reset(seed=eng_seed, options=options)
        self.agents = list(self.possible_agents)
        self.t = 0.0
        self.decisions = 0
        self.ticks = 0
        self.on_reset()
        self._update_decisions()
        return self._obs(), self._infos(0.0)

    # -------------------------------------------------------------------- step
    def _read_actions(self, actions: Any) -> dict[str, int]:
        if not isinstance(actions, Mapping):
            raise ValueError(f"actions must be a dict agent -> option index, got {type(actions).__name__}")
        chosen: dict[str, int] = {}
        for agent, act in actions.items():
            self._check_agent(agent)
            a = np.asarray(act)
            if a.ndim != 0 and a.shape != (1,):
                raise ValueError(f"action for agent {agent!r} must be one option index, got shape {a.shape}")
            v = a.reshape(()).item()
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v != int(v):
                raise ValueError(f"action for agent {agent!r} must be an integer option index, got {act!r}")
            v = int(v)
            if not 0 <= v < self.n_options:
                raise ValueError(f"action for agent {agent!r} is option {v}, outside [0, {self.n_options}) "
                                 f"(options: {self.option_names})")
            chosen[agent] = v
        for agent in self._deciding:
            if agent not in chosen:
                raise ValueError(f"agent {agent!r} has a decision to make (infos[{agent!r}]['decision']) "
                                 f"but no action was given")
            if not self._masks[agent][chosen[agent]]:
                if self.illegal_option == "raise":
                    raise ValueError(f"action for agent {agent!r}: option {chosen[agent]} "
                                     f"({self.option_names[chosen[agent]]}) is illegal now (action_mask "
                                     f"{self._masks[agent].tolist()})")
                chosen[agent] = self.default_option
        return {a: chosen[a] for a in sorted(self._deciding)}

    def step(self, actions: Mapping[str, Any]):
        if not self.agents:
            raise RuntimeError("step() called on a finished episode: call reset() first")
        chosen = self._read_actions(actions)
        self.decisions += len(chosen)
        if chosen:
            self.start_options(chosen)
        rewards = {a: 0.0 for a in self.possible_agents}
        robot_of = self._robot_of
        elapsed = 0.0
        terminated = truncated = False
        n_max = max(1, int(round(self.max_interval_s / self.dt)))
        for _ in range(n_max):
            _, r, term, trunc, _ = self.engine.step(self.tick_actions())
            self.ticks += 1
            elapsed += self.dt
            self.t += self.dt
            for a in self.possible_agents:
                rewards[a] += float(r.get(robot_of[a], 0.0))
            self.after_tick()
            terminated = any(term.values())
            truncated = any(trunc.values()) and not terminated
            if terminated or truncated:
                break
            self._update_decisions()
            if self._deciding:
                break
        if terminated or truncated:
            self._deciding = frozenset()
            self._masks = {}
        infos = self._infos(elapsed)
        if terminated or truncated:
            extra = self.episode_info()
            for a in self.possible_agents:
                infos[a].update(extra)
        obs = self._obs()
        terms = {a: bool(terminated) for a in self.possible_agents}
        truncs = {a: bool(truncated) for a in self.possible_agents}
        if terminated or truncated:
            self.agents = []
        return obs, rewards, terms, truncs, infos

    # ------------------------------------------------------------------ render
    def render(self):
        if self.render_mode is None:
            gymnasium.logger.warn("render() called without a render_mode; pass render_mode='rgb_array'")
            return None
        return self.engine.render()

    def close(self) -> None:
        self.engine.close()


__all__ = ["DecisionEnv", "ILLEGAL_OPTION_MODES"]
