"""K full-field SSL worlds stepped together: a batched multi-agent API.

:class:`BatchedSSLEnv` runs K independent copies of
:class:`~ssl_marl.envs.ssl_env.SSLParallelEnv` (same options) in one process.
Everything per robot and per world is numpy over all worlds at once (velocity
controller, kicker, ball friction and contact checks in
:class:`~ssl_marl.physics.batched.BatchedPhysics`; referee checks, rewards,
truncation and observations here); Box2D's step stays one C++ call per world.
Rare per-world events (resets, ball placement after the ball leaves the field,
kickoff after a goal) go through the same code as the single env. With realism
switched on, radio and vision (noise, latency, dropout) run per world with each
world's own generator, exactly as in the single env.

World k behaves exactly as an ``SSLParallelEnv`` with the same options reset with
seed ``seed + k`` and given the same actions (positions, observations, rewards,
terminations; tested).

Arrays (K worlds, n = n_blue + n_yellow agents in ``possible_agents`` order):

* ``reset(seed=None, options=None) -> obs (K, n, D) float32, info``
* ``step(actions (K, n, A)) -> obs, rewards (K, n) float64, terminated (K,) bool,
  truncated (K,) bool, info`` (a dict of arrays: ``goal`` (K,) +1 blue scored /
  -1 yellow scored / 0, ``ball_out`` (K,), ``no_progress`` (K,) (the referee's
  no-progress restart), ``kicker`` (K,) index of the robot whose kick fired (-1 none), ``kick_speed`` (K,) m/s, ``score`` (K, 2) blue/yellow,
  ``t`` (K,) s, ``reward_terms`` {term: (K, n)}, ``autoreset`` (K,)).

A = 5, or 6 with chip kicks (``chip_kicks=True``, the env's v1 layout: the chip entry
appended to the action, the ball's height and vertical velocity to the observation,
D + 2; see :class:`~ssl_marl.envs.config.EnvConfig`). A goal counts only if the ball
was never higher than 0.15 m since the last touch, as in the single env.

Autoreset: Gymnasium's "next step" mode. A world whose episode ended in the last
``step`` is reset at the start of the next one (its actions are ignored; it
returns its first observation with reward 0 and ``info["autoreset"]`` True).
Bad actions (wrong shape, NaN or inf) raise ``ValueError`` naming the world and
the agent, as the single env names the agent.

:meth:`BatchedSSLEnv.world_view` gives a PettingZoo ``ParallelEnv`` of one world
(stepping only that world).
"""

from __future__ import annotations

import math
from typing import Any, Sequence

import gymnasium
import numpy as np
from pettingzoo import ParallelEnv

from ..physics.batched import BatchedPhysics
from ..physics.state import WorldState, to_team_frame
from .actions import chip_angles, scale_actions
from .batched_obs import batched_observations
from .config import EnvConfig, MatchRules, make_config
from .observation import all_observations, state_vector
from .referee import GOAL_MAX_HEIGHT_M, NoProgressWatch, clear_robots_from, kickoff_poses, placement_point
from .ssl_env import SSLParallelEnv
from .tasks import FreePlayTask, MatchTask

TEAMS = ("blue", "yellow")



def _batched_rules(env: SSLParallelEnv) -> MatchRules:
    """The rules the batched env vectorises, from the single env's task: a
    :class:`MatchTask`'s own rules, or for :class:`FreePlayTask` no referee, no rewards
    and no end. Other tasks are refused (their logic is not vectorised)."""
    task = env.task
    if isinstance(task, MatchTask):
        game = [k for k in ("ssl_restarts", "fouls", "restart_jitter_m", "half_time_s")
                if getattr(task.rules, k) not in (False, 0.0, None)]
        if game:
            raise ValueError(f"the batched env does not run SSL game control ({', '.join(game)}): use the single env")
        return task.rules
    if isinstance(task, FreePlayTask):
        return MatchRules(referee=False, after_goal="kickoff", max_time_s=math.inf,
                          reward_scales={"goal": 0.0, "ball_progress": 0.0, "possession": 0.0})
    raise ValueError(f"task: the batched env runs the 'match' and 'free_play' tasks, got {type(task).__name__}")

class BatchedSSLEnv:
    """K SSL worlds with one set of options (see :class:`~ssl_marl.envs.config.EnvConfig`).

    Args:
        n_worlds: K >= 1.
        envs: optional K existing single envs to drive (the skill vector envs pass
            theirs); built from ``config`` otherwise.
        **config: env options; ``realtime`` and ``render_mode`` are not supported
            (use :meth:`world_view` with a single env for those).
    """

    def __init__(self, n_worlds: int, envs: Sequence[SSLParallelEnv] | None = None, **config: Any) -> None:
        if not isinstance(n_worlds, int) or isinstance(n_worlds, bool) or n_worlds < 1:
            raise ValueError(f"n_worlds must be a positive integer, got {n_worlds!r}")
        if envs is None:
            cfg = make_config(**config)
            if cfg.realtime:
                raise ValueError("realtime: not supported by the batched env (use SSLParallelEnv)")
            if cfg.render_mode is not None:
                raise ValueError("render_mode: not supported by the batched env (use SSLParallelEnv)")
            if cfg.randomization is not None:
                raise ValueError("randomization: per-episode domain randomisation (realism='randomized') is not "
                                 "supported by the batched env: its worlds share one set of physics parameters "
                                 "and one realism pipeline; use SSLParallelEnv")
            envs = [SSLParallelEnv(**config) for _ in range(n_worlds)]
        elif config:
            raise ValueError(f"pass either envs or env options, not both (got options {sorted(config)})")
        elif len(envs) != n_worlds:
            raise ValueError(f"got {len(envs)} envs for n_worlds={n_worlds}")
        self.envs = list(envs)
        self.config: EnvConfig = self.envs[0].config
        cfg = self.config
        if any(e.config.randomization is not None for e in self.envs):
            raise ValueError("randomization: per-episode domain randomisation (realism='randomized') is not "
                             "supported by the batched env; use SSLParallelEnv")
        self.K = n_worlds
        self.field = cfg.field
        self.robot_radius = cfg.robot.radius  #: m, for the restarts' placements
        self.possible_agents = list(self.envs[0].possible_agents)
        self.n = len(self.possible_agents)
        self.n_blue, self.n_yellow = cfg.n_blue, cfg.n_yellow
        self.single_observation_space = self.envs[0].observation_space(self.possible_agents[0])
        self.single_action_space = self.envs[0].action_space(self.possible_agents[0])
        self.obs_dim = int(self.single_observation_space.shape[0])
        #: action length per agent (5; 6 with chip kicks)
        self.action_dim = int(self.single_action_space.shape[0])
        self.physics = BatchedPhysics(cfg.field, cfg.robot, cfg.ball, cfg.n_blue, cfg.n_yellow, n_worlds, cfg.dt,
                                      cfg.physics_substeps, worlds=[e.physics for e in self.envs])
        K = n_worlds
        self.score = np.zeros((K, 2), np.int64)
        self.prev_ball_x = np.zeros(K)
        self.needs_reset = np.zeros(K, bool)
        self._was_reset = np.zeros(K, bool)
        self.obs = np.zeros((K, self.n, self.obs_dim), np.float32)
        self._realism = cfg.realism.enabled
        self._seen: list[WorldState | None] = [None] * K
        self._is_blue = np.arange(self.n) < cfg.n_blue
        self.rules = _batched_rules(self.envs[0])
        scales = self.rules.reward_scales
        self._scales = (float(scales["goal"]), float(scales["ball_progress"]), float(scales["possession"]))
        self._watch = NoProgressWatch(K, self.rules.no_progress_s if self.rules.referee else None)

    # ------------------------------------------------------------------ reset
    def reset(self, seed: int | Sequence[int | None] | None = None, options: dict | Sequence[dict | None] | None = None):
        """Reset every world: world k with seed ``seed + k`` (or ``seed[k]``) and
        ``options`` (one dict for all worlds or one per world; the single env's reset options)."""
        K = self.K
        seeds = self._per_world(seed, "seed", lambda s, k: None if s is None else int(s) + k)
        opts = self._per_world(options, "options", lambda o, k: o)
        for k in range(K):
            self.reset_world(k, seeds[k], opts[k])
        return self.obs.copy(), {"t": self.physics.t.copy()}

    def _per_world(self, value: Any, name: str, spread) -> list:
        """A list/tuple gives one value per world; anything else is spread over the worlds."""
        if isinstance(value, (list, tuple)):
            if len(value) != self.K:
                raise ValueError(f"{name}: expected one value per world ({self.K}), got {len(value)}")
            return list(value)
        return [spread(value, k) for k in range(self.K)]

    def reset_world(self, k: int, seed: int | None = None, options: dict | None = None) -> np.ndarray:
        """Reset world k alone (the single env's ``reset``); return its (n, D) observation."""
        self.envs[k].reset(seed=seed, options=options)
        self.adopt_world(k)
        return self.obs[k]

    def adopt_world(self, k: int) -> None:
        """Take over world k after its single env was reset directly (the skill vector
        envs reset through their task envs)."""
        env = self.envs[k]
        self.physics.pull(k)
        self.score[k] = 0
        self.prev_ball_x[k] = self.physics.ball_pos[k, 0]
        self._watch.restart(np.array([k]), self.physics.ball_pos[k][None, :], self.physics.t[k:k + 1])
        self.needs_reset[k] = False
        self._was_reset[k] = True
        self._seen[k] = env._seen
        cfg = self.config
        self.obs[k] = all_observations(env._seen, self.field, cfg.obs_max_teammates, cfg.obs_max_opponents,
                                       cfg.chip_kicks)

    # ------------------------------------------------------------------- step
    def check_actions(self, actions: Any, n_worlds: int | None = None) -> np.ndarray:
        """(K, n, A) float64 actions (A = :attr:`action_dim`), or ValueError naming the world and agent."""
        K, dim = self.K if n_worlds is None else n_worlds, self.action_dim
        a = np.asarray(actions, dtype=np.float64)
        if a.shape != (K, self.n, dim):
            raise ValueError(f"actions must have shape (worlds, agents, {dim}) = {(K, self.n, dim)}, "
                             f"got {a.shape}")
        bad = ~np.isfinite(a).all(axis=2)
        if bad.any():
            k, i = (int(x) for x in np.argwhere(bad)[0])
            raise ValueError(f"world {k}: action for agent {self.possible_agents[i]!r} contains NaN or inf: "
                             f"{a[k, i].tolist()}")
        return a

    def step(self, actions: Any):
        """Step all worlds (autoresetting those whose episode ended last step)."""
        if not self._was_reset.all():
            raise RuntimeError(f"step() called before reset() (worlds never reset: "
                               f"{np.flatnonzero(~self._was_reset).tolist()})")
        a = self.check_actions(actions)
        resetting = np.flatnonzero(self.needs_reset)
        live = np.flatnonzero(~self.needs_reset) if resetting.size else None
        for k in resetting:
            self.reset_world(int(k))
        obs, rew, term, trunc, info = self._step_worlds(a, live)
        info["autoreset"] = np.zeros(self.K, bool)
        info["autoreset"][resetting] = True
        self.needs_reset = term | trunc
        return obs, rew, term, trunc, info

    def _step_worlds(self, a: np.ndarray, worlds: np.ndarray | None):
        """Step worlds ``worlds`` (None: all) with actions a (K, n, A); others keep their
        state and report zeros. Returns full-size (K, ...) arrays."""
        cfg, ph, K, n = self.config, self.physics, self.K, self.n
        idx = np.arange(K) if worlds is None else np.asarray(worlds, np.int64)
        if idx.size == 0:
            return self.obs.copy(), np.zeros((K, n)), np.zeros(K, bool), np.zeros(K, bool), self._empty_info()
        cmd = a if worlds is None else a[idx]
        if self._realism:
            cmd = np.stack([self.envs[k].radio.transmit(cmd[j], self.envs[k]._noise_rng) for j, k in enumerate(idx)])
        flat = cmd.reshape(-1, self.action_dim)
        v, w, drib, kick = scale_actions(flat, cfg.robot)
        m = idx.size
        chip = chip_angles(flat, cfg.robot).reshape(m, n) if cfg.chip_kicks else None
        ph.step(v.reshape(m, n, 2), w.reshape(m, n), drib.reshape(m, n), kick.reshape(m, n), worlds=worlds,
                chip=chip)
        goal = np.zeros(K, np.int64)
        ball_out = np.zeros(K, bool)
        no_progress = np.zeros(K, bool)
        if self.rules.referee:
            self._referee(idx, goal, ball_out, no_progress)
        # rewards (SSLParallelEnv._rewards)
        bx = ph.ball_pos[idx, 0]
        progress = (bx - self.prev_ball_x[idx]) / self.field.half_length
        self.prev_ball_x[idx] = bx
        on = ph.on_dribbler[idx]
        poss = np.stack([on[:, self._is_blue].any(axis=1), on[:, ~self._is_blue].any(axis=1)], axis=1)  # (m, 2)
        g_s, p_s, q_s = self._scales
        sgn = np.array([1.0, -1.0])
        g = goal[idx]
        goal_term = g_s * np.where(g[:, None] == 0, 0.0, np.where(g[:, None] == sgn[None, :], 1.0, -1.0))
        prog_term = p_s * sgn[None, :] * progress[:, None]
        poss_term = q_s * np.where(poss, cfg.dt, 0.0)
        team_reward = goal_term + prog_term + poss_term  # (m, 2), summed in the single env's order
        team_of = np.where(self._is_blue, 0, 1)
        rewards = np.zeros((K, n))
        rewards[idx] = team_reward[:, team_of]
        terms = {name: np.zeros((K, n)) for name in ("goal", "ball_progress", "possession")}
        for name, t in (("goal", goal_term), ("ball_progress", prog_term), ("possession", poss_term)):
            terms[name][idx] = t[:, team_of]
        t_now = ph.t[idx]
        terminated = np.zeros(K, bool)
        truncated = np.zeros(K, bool)
        term_now = (g != 0) & (self.rules.after_goal == "terminate")
        terminated[idx] = term_now
        truncated[idx] = (t_now >= self.rules.max_time_s - 1e-9) & ~term_now
        if self.rules.after_goal == "kickoff":
            for j in np.flatnonzero(g != 0):
                self._kickoff(int(idx[j]))
        self._observe(idx)
        info = {"goal": goal, "ball_out": ball_out, "no_progress": no_progress, "kicker": np.full(K, -1),
                "kick_speed": np.zeros(K), "score": self.score.copy(), "t": ph.t.copy(), "reward_terms": terms}
        info["kicker"][idx] = ph.kicker if worlds is None else ph.kicker[idx]
        info["kick_speed"][idx] = ph.kick_speed if worlds is None else ph.kick_speed[idx]
        return self.obs.copy(), rewards, terminated, truncated, info

    def _empty_info(self) -> dict:
        K, n = self.K, self.n
        return {"goal": np.zeros(K, np.int64), "ball_out": np.zeros(K, bool), "no_progress": np.zeros(K, bool),
                "kicker": np.full(K, -1),
                "kick_speed": np.zeros(K), "score": self.score.copy(), "t": self.physics.t.copy(),
                "reward_terms": {k: np.zeros((K, n)) for k in ("goal", "ball_progress", "possession")}}

    def _referee(self, idx: np.ndarray, goal: np.ndarray, ball_out: np.ndarray, no_progress: np.ndarray) -> None:
        """Vectorised :func:`ssl_marl.envs.referee.judge` and the no-progress call; the
        rare calls handled per world."""
        f, br, ph = self.field, self.config.ball.radius, self.physics
        bp = ph.ball_pos[idx]
        x, y = bp[:, 0], bp[:, 1]
        in_goal = (np.abs(y) <= f.goal_width / 2.0) & (np.abs(x) >= f.half_length + br)
        out = ~in_goal & ((np.abs(x) >= f.half_length + br) | (np.abs(y) >= f.half_width + br))
        stalled = np.zeros(idx.size, bool)
        rest = ~(in_goal | out)
        stalled[rest] = self._watch.update(idx[rest], bp[rest], ph.t[idx[rest]])
        for j in np.flatnonzero(in_goal | out | stalled):
            k = int(idx[j])
            if in_goal[j] and ph.worlds[k].ball_max_height <= GOAL_MAX_HEIGHT_M:
                side = 1 if x[j] > 0 else -1
                goal[k] = side
                self.score[k, 0 if side > 0 else 1] += 1
                continue
            ball_out[k], no_progress[k] = bool(out[j] or in_goal[j]), bool(stalled[j])
            place = placement_point(ph.ball_pos[k], f)
            new_pos = clear_robots_from(place, ph.pos[k], f, robot_radius=self.robot_radius)
            moved = np.flatnonzero(np.any(new_pos != ph.pos[k], axis=1))
            if moved.size:
                pose = np.column_stack([ph.pos[k], ph.heading[k]])
                pose[moved, 0:2] = new_pos[moved]
                ph.set_robots(k, pose, only=moved)
            ph.set_ball(k, place)
            self.prev_ball_x[k] = ph.ball_pos[k, 0]
            self._watch.restart(np.array([k]), ph.ball_pos[k][None, :], ph.t[k:k + 1])

    def _kickoff(self, k: int) -> None:
        cfg = self.config
        self.physics.set_robots(k, kickoff_poses(self.field, cfg.n_blue, cfg.n_yellow))
        self.physics.set_ball(k, np.zeros(2))
        self.prev_ball_x[k] = 0.0
        self._watch.restart(np.array([k]), np.zeros((1, 2)), self.physics.t[k:k + 1])

    def _observe(self, idx: np.ndarray) -> None:
        cfg, ph = self.config, self.physics
        if self._realism:
            for k in idx.tolist():
                env = self.envs[k]
                seen = env.vision.observe(ph.snapshot(k), env._noise_rng)
                self._seen[k] = seen
                self.obs[k] = all_observations(seen, self.field, cfg.obs_max_teammates, cfg.obs_max_opponents,
                                               cfg.chip_kicks)
            return
        full = idx.size == self.K

        def get(x):
            return x if full else x[idx]

        air = None
        if cfg.chip_kicks:
            air = (np.array([ph.worlds[k].ball_z for k in idx.tolist()]),
                   np.array([ph.worlds[k].ball_vz for k in idx.tolist()]))
        ob = batched_observations(get(ph.pos), get(ph.heading), get(ph.vel), get(ph.omega), get(ph.ball_pos),
                                  get(ph.ball_vel), get(ph.on_dribbler), get(ph.kick_cooldown) <= 0, True, self.field,
                                  self.n_blue, self.n_yellow, cfg.obs_max_teammates, cfg.obs_max_opponents, air)
        if full:
            self.obs = ob
        else:
            self.obs[idx] = ob

    # ------------------------------------------------------------- accessors
    def world_state(self, k: int) -> WorldState:
        """Ground truth of world k (field frame)."""
        return self.physics.snapshot(k)

    def vision_state(self, k: int, team: str | None = None) -> WorldState:
        """What the teams of world k see (equals the truth without realism)."""
        ws = self._seen[k] if self._realism and self._seen[k] is not None else self.physics.snapshot(k)
        return ws if team is None else to_team_frame(ws, team)

    def state(self) -> np.ndarray:
        """(K, state_dim) whole-world vectors (see :func:`ssl_marl.envs.observation.state_vector`)."""
        return np.stack([state_vector(self.physics.snapshot(k)) for k in range(self.K)])

    def world_view(self, k: int) -> "BatchedWorldView":
        """A PettingZoo ``ParallelEnv`` of world k."""
        if not 0 <= k < self.K:
            raise ValueError(f"world index must be in 0..{self.K - 1}, got {k}")
        return BatchedWorldView(self, k)

    def close(self) -> None:
        for e in self.envs:
            e.close()


class BatchedWorldView(ParallelEnv):
    """PettingZoo Parallel API over world k of a :class:`BatchedSSLEnv`: ``step``
    advances that world only; episodes end as in the single env (no autoreset)."""

    metadata = {"name": "ssl_marl_batched_world_v0", "render_modes": [], "is_parallelizable": True}

    def __init__(self, batched: BatchedSSLEnv, k: int) -> None:
        self.batched, self.k = batched, k
        self.possible_agents = list(batched.possible_agents)
        self.agents: list[str] = []
        self.observation_spaces = {a: batched.single_observation_space for a in self.possible_agents}
        self.action_spaces = {a: batched.single_action_space for a in self.possible_agents}
        self.state_space = batched.envs[k].state_space
        self.render_mode = None
        self._index = {a: i for i, a in enumerate(self.possible_agents)}

    def observation_space(self, agent: str) -> gymnasium.spaces.Box:
        self._check_agent(agent)
        return self.batched.single_observation_space

    def action_space(self, agent: str) -> gymnasium.spaces.Box:
        self._check_agent(agent)
        return self.batched.single_action_space

    def _check_agent(self, agent: str) -> int:
        try:
            return self._index[agent]
        except KeyError:
            raise ValueError(f"unknown agent {agent!r}; agents are {self.possible_agents}") from None

    def reset(self, seed: int | None = None, options: dict | None = None):
        ob = self.batched.reset_world(self.k, seed, options)
        self.agents = list(self.possible_agents)
        return dict(zip(self.possible_agents, ob.copy())), {a: {"events": [], "score": self._score()} for a in self.agents}

    def _score(self) -> dict:
        s = self.batched.score[self.k]
        return {"blue": int(s[0]), "yellow": int(s[1])}

    def step(self, actions: dict):
        if not self.agents:
            raise RuntimeError("step() called on a finished episode: call reset() first")
        b = self.batched
        if not isinstance(actions, dict):
            raise ValueError(f"actions must be a dict agent -> action, got {type(actions).__name__}")
        dim = b.action_dim
        arr = np.zeros((b.K, b.n, dim))
        for agent, act in actions.items():
            i = self._check_agent(agent)
            x = np.asarray(act, dtype=float)
            if x.shape != (dim,):
                raise ValueError(f"action for agent {agent!r} must have shape ({dim},), got {x.shape}")
            if not np.isfinite(x).all():
                raise ValueError(f"action for agent {agent!r} contains NaN or inf: {x.tolist()}")
            arr[self.k, i] = x
        obs, rew, term, trunc, info = b._step_worlds(arr, np.array([self.k]))
        k = self.k
        events: list[dict] = []
        if info["kicker"][k] >= 0:
            events.append({"type": "kick", "agent": self.possible_agents[int(info["kicker"][k])],
                           "speed": float(info["kick_speed"][k])})
        if info["goal"][k]:
            events.append({"type": "goal", "team": "blue" if info["goal"][k] > 0 else "yellow", "t": float(info["t"][k])})
        if info["ball_out"][k]:
            events.append({"type": "ball_out", "t": float(info["t"][k])})
        if info["no_progress"][k]:
            events.append({"type": "no_progress", "t": float(info["t"][k])})
        o = {a: obs[k, i] for i, a in enumerate(self.agents)}
        r = {a: float(rew[k, i]) for i, a in enumerate(self.agents)}
        te = {a: bool(term[k]) for a in self.agents}
        tr = {a: bool(trunc[k]) for a in self.agents}
        infos = {a: {"events": events, "score": self._score(),
                     "reward_terms": {t: float(v[k, i]) for t, v in info["reward_terms"].items()}}
                 for i, a in enumerate(self.agents)}
        if term[k] or trunc[k]:
            self.agents = []
        return o, r, te, tr, infos

    def state(self) -> np.ndarray:
        return state_vector(self.batched.physics.snapshot(self.k))

    def close(self) -> None:
        pass
