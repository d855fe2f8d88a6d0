"""The skill tasks as one Gymnasium ``VectorEnv`` over batched worlds.

:class:`SkillVectorEnv` runs ``num_envs`` copies of
:class:`~ssl_marl.skills.wrappers.GoToBallEnv` or
:class:`~ssl_marl.skills.wrappers.AimToShootEnv` with their worlds stepped together
by :class:`~ssl_marl.envs.batched_env.BatchedSSLEnv`, and the paper's features,
rewards and outcomes computed over all worlds at once
(:mod:`ssl_marl.skills.batched_features`). Resets (the task's spawn distribution)
go through each copy's own ``reset``, so sub-env i behaves as the single task env
reset with seed ``seed + i`` (tested against Gymnasium's ``SyncVectorEnv`` of the
single env: same observations, terminations and, to the last bit of ``arctan2``
and ``exp``, rewards).

Spaces, autoreset and infos follow Gymnasium's vector API: ``metadata
["autoreset_mode"]`` is ``NEXT_STEP`` (as the trainer's ``SyncVectorEnv``); infos
are dicts of arrays with ``_key`` masks (``reward_terms`` every step that steps a world, absent when every world autoresets; ``is_success``,
``failure_reason``, ``time_s`` where an episode ended; ``kicked`` for aim-to-shoot).
Bad actions (wrong shape, NaN or inf) raise ``ValueError`` naming the sub-env.

Not supported (``ValueError``): ``realtime``, ``render_mode``, ``opponent_policy=
"chase"``. With realism on, features are computed per world from what the robot
sees (exactly as the single env), the rest stays vectorised.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space

from ..envs.batched_env import BatchedSSLEnv
from ..envs.tracking import resolve_tracker
from .batched_features import (aim_to_shoot_features_batch, aim_to_shoot_reward_batch, dribbler_ball_distance_batch,
                               go_to_ball_features_batch, go_to_ball_reward_batch)
from .wrappers import AimToShootEnv, GoToBallEnv

TASKS = {"go-to-ball": GoToBallEnv, "aim-to-shoot": AimToShootEnv}
ENV_IDS = {"ssl_marl/GoToBall-v0": "go-to-ball", "ssl_marl/AimToShoot-v0": "aim-to-shoot"}


class SkillVectorEnv(VectorEnv):
    """``num_envs`` copies of a skill task ("go-to-ball" or "aim-to-shoot"; the
    registered ids are accepted too), keyword options as the task env's."""

    metadata = {"autoreset_mode": AutoresetMode.NEXT_STEP}

    def __init__(self, task: str, num_envs: int, **task_kwargs: Any) -> None:
        task = ENV_IDS.get(task, task)
        if task not in TASKS:
            raise ValueError(f"task must be one of {sorted(TASKS)} (or {sorted(ENV_IDS)}), got {task!r}")
        if not isinstance(num_envs, int) or isinstance(num_envs, bool) or num_envs < 1:
            raise ValueError(f"num_envs must be a positive integer, got {num_envs!r}")
        for name in ("realtime", "render_mode"):
            if task_kwargs.get(name):
                raise ValueError(f"{name}: not supported by the vector env (use the single task env)")
        if resolve_tracker(task_kwargs.get("tracker", False), task_kwargs.get("realism", "none")):
            raise ValueError("tracker: not supported by the vector env (use the single task env)")
        if task_kwargs.get("opponent_policy", "static") != "static":
            raise ValueError("opponent_policy: only 'static' opponents are supported by the vector env")
        self.task = task
        self.envs = [TASKS[task](**task_kwargs) for _ in range(num_envs)]
        first = self.envs[0]
        self.num_envs = num_envs
        self.batched = BatchedSSLEnv(num_envs, envs=[e.env for e in self.envs])
        self.single_observation_space = first.observation_space
        self.single_action_space = first.action_space
        self.observation_space = batch_space(first.observation_space, num_envs)
        self.action_space = batch_space(first.action_space, num_envs)
        self.field, self.robot_params, self.ball_params = first.field, first.robot_params, first.ball_params
        self.spec_version = first.spec_version
        self.render_mode = None
        self._realism = self.batched._realism
        self._autoreset = np.zeros(num_envs, bool)
        self._kick_t = np.full(num_envs, np.nan)  # aim-to-shoot: time of the kick (nan: not yet)
        self._n_robots = self.batched.n
        self._obs = np.zeros((num_envs,) + first.observation_space.shape, np.float32)

    # ------------------------------------------------------------------ reset
    def reset(self, *, seed: int | list[int | None] | None = None, options: dict | None = None):
        n = self.num_envs
        if isinstance(seed, int):
            super().reset(seed=seed)  # the VectorEnv's own generator, as Gymnasium's vector envs do
        if seed is None or isinstance(seed, int):
            seeds = [None if seed is None else seed + i for i in range(n)]
        else:
            if len(seed) != n:
                raise ValueError(f"seed: expected one seed per sub-env ({n}), got {len(seed)}")
            seeds = list(seed)
        for i in range(n):
            self._reset_one(i, seeds[i], options)
        self._autoreset[:] = False
        return self._obs.copy(), {}

    def _reset_one(self, i: int, seed: int | None = None, options: dict | None = None) -> None:
        obs, _ = self.envs[i].reset(seed=seed, options=options)
        self.batched.adopt_world(i)
        self._obs[i] = obs
        self._kick_t[i] = np.nan

    # ------------------------------------------------------------------- step
    def _check(self, actions: Any) -> np.ndarray:
        a = np.asarray(actions, dtype=np.float64)
        shape = (self.num_envs,) + self.single_action_space.shape
        if a.shape != shape:
            raise ValueError(f"actions must have shape {shape}, got {a.shape}")
        bad = ~np.isfinite(a).all(axis=1)
        if bad.any():
            i = int(np.flatnonzero(bad)[0])
            raise ValueError(f"sub-env {i}: action contains NaN or inf: {a[i].tolist()}")
        return np.clip(a, -1.0, 1.0)

    def _full_actions(self, a: np.ndarray) -> np.ndarray:
        """(K, n, 5) env actions: the task's mapping (expand_task_action), float32 as make_action builds it."""
        a32 = a.astype(np.float32).astype(np.float64)
        full = np.zeros((self.num_envs, self._n_robots, 5))
        if self.task == "go-to-ball":
            full[:, 0, 0:3] = a32
            full[:, 0, 3], full[:, 0, 4] = 1.0, -1.0
            return full
        full[:, 0, 2] = a32[:, 0]
        full[:, 0, 3] = np.where(a[:, 1] > 0, 1.0, -1.0)
        strength = a32[:, 2] if self.envs[0].kick_action == "strength" else np.ones(self.num_envs)
        full[:, 0, 4] = np.where(a[:, 2] > 0, strength, -1.0)
        kicked = ~np.isnan(self._kick_t)  # after the kick the robot's actions no longer matter
        full[kicked, 0] = (0.0, 0.0, 0.0, -1.0, -1.0)
        return full

    def step(self, actions: Any):
        a = self._check(actions)
        K = self.num_envs
        resetting = np.flatnonzero(self._autoreset)
        live = np.flatnonzero(~self._autoreset)
        for i in resetting:
            self._reset_one(int(i))
        rewards = np.zeros(K)
        terminated = np.zeros(K, bool)
        truncated = np.zeros(K, bool)
        info: dict[str, Any] = {}
        if live.size:
            _, _, _, _, binfo = self.batched._step_worlds(self._full_actions(a), live if resetting.size else None)
            self._task_step(live, binfo, rewards, terminated, truncated, info)
        self._autoreset = terminated | truncated
        return self._obs.copy(), rewards, terminated, truncated, info

    def _task_step(self, live: np.ndarray, binfo: dict, rewards: np.ndarray, terminated: np.ndarray,
                   truncated: np.ndarray, info: dict) -> None:
        ph, K = self.batched.physics, self.num_envs
        pos, hd, on = ph.pos[live, 0], ph.heading[live, 0], ph.on_dribbler[live, 0]
        t = ph.t[live]
        mask = np.zeros(K, bool)
        mask[live] = True
        ended = np.zeros(live.size, bool)
        success = np.zeros(live.size, bool)
        reason = np.full(live.size, None, dtype=object)
        env0 = self.envs[0]
        if self.task == "go-to-ball":
            terms = go_to_ball_reward_batch(pos, hd, ph.ball_pos[live], on, env0.orientation_form)
            success = on.copy()
            timeout = ~success & (t >= env0.max_time_s - 1e-9)
            terminated[live], truncated[live] = success, timeout
            ended = success | timeout
            reason[timeout] = "timeout"
        else:
            kicked_now = (binfo["kicker"][live] == 0) & np.isnan(self._kick_t[live])
            self._kick_t[live[kicked_now]] = t[kicked_now]
            kick_t = self._kick_t[live]
            has_kicked = ~np.isnan(kick_t)
            terms = aim_to_shoot_reward_batch(pos, hd, ph.ball_vel[live], self.field)
            if env0.reward_form == "kick_only":
                terms["aim"] = np.where(has_kicked, terms["aim"], 0.0)
            term_, trunc_, success, reason = self._aim_outcome(live, has_kicked, kick_t, t)
            if env0.success_bonus:
                terms["success_bonus"] = np.where(success, env0.success_bonus, 0.0)
            terminated[live], truncated[live] = term_, trunc_
            ended = term_ | trunc_
        total = np.zeros(live.size)
        for v in terms.values():
            total = total + v
        rewards[live] = total
        rt: dict[str, Any] = {}
        for k, v in terms.items():
            full = np.zeros(K)
            full[live] = v
            rt[k], rt["_" + k] = full, mask.copy()
        info["reward_terms"], info["_reward_terms"] = rt, mask.copy()
        info["t"], info["_t"] = ph.t.copy(), mask.copy()
        if self.task == "aim-to-shoot":
            kk = np.zeros(K, bool)
            kk[live] = ~np.isnan(self._kick_t[live])
            info["kicked"], info["_kicked"] = kk, mask.copy()
        done = np.zeros(K, bool)
        done[live] = ended
        if done.any():
            s = np.zeros(K, bool)
            s[live] = success
            r = np.full(K, None, dtype=object)
            r[live] = reason
            info["is_success"], info["_is_success"] = s, done.copy()
            info["failure_reason"], info["_failure_reason"] = r, done.copy()
            info["time_s"], info["_time_s"] = np.where(done, ph.t, 0.0), done.copy()
        self._features(live)

    def _aim_outcome(self, live, has_kicked, kick_t, t):
        """Vectorised AimToShootEnv._outcome: terminated, truncated, success, failure reason."""
        ph, f, env0 = self.batched.physics, self.field, self.envs[0]
        br = self.ball_params.radius
        pos, hd = ph.pos[live, 0], ph.heading[live, 0]
        bp, bv = ph.ball_pos[live], ph.ball_vel[live]
        m = live.size
        term, trunc, success = np.zeros(m, bool), np.zeros(m, bool), np.zeros(m, bool)
        reason = np.full(m, None, dtype=object)
        # before the kick
        lost = dribbler_ball_distance_batch(pos, hd, bp, self.robot_params, self.ball_params) > env0.lost_distance
        timeout = ~lost & (t >= env0.max_time_s - 1e-9)
        pre = ~has_kicked
        term |= pre & lost
        reason[pre & lost] = "ball_lost"
        trunc |= pre & timeout
        reason[pre & timeout] = "timeout"
        # after the kick
        bx, by = bp[:, 0], bp[:, 1]
        in_goal = (np.abs(by) <= f.goal_width / 2.0) & (np.abs(bx) >= f.half_length + br)
        side = np.where(in_goal, np.where(bx > 0, 1, -1), 0)
        goal = has_kicked & (side == 1)
        out = (np.abs(by) >= f.half_width + br) | ((np.abs(bx) >= f.half_length + br) & (side == 0))
        stopped = np.hypot(bv[:, 0], bv[:, 1]) < 0.05
        with np.errstate(invalid="ignore"):
            late = (t - kick_t) >= env0.post_kick_time_s
        missed = has_kicked & ~goal & (out | (side == -1) | stopped | (bv[:, 0] <= 0) | late)
        term |= goal | missed
        success |= goal
        reason[missed] = "missed"
        return term, trunc, success, reason

    def _features(self, live: np.ndarray) -> None:
        ph = self.batched.physics
        if self._realism:  # what the robot sees: per world, the single env's pure functions
            for i in live.tolist():
                self._obs[i] = self.envs[i].task.observe(self.batched.vision_state(i, "blue"), 0)
            return
        pos, hd = ph.pos[live, 0], ph.heading[live, 0]
        if self.task == "go-to-ball":
            ball_vel = ph.ball_vel[live] if self.envs[0].task.state == "ball_velocity" else None
            self._obs[live] = go_to_ball_features_batch(pos, hd, ph.vel[live, 0], ph.omega[live, 0], ph.ball_pos[live],
                                                        self.field, ball_vel)
        else:
            self._obs[live] = aim_to_shoot_features_batch(pos, hd, ph.omega[live, 0], ph.ball_pos[live],
                                                          ph.ball_vel[live], self.field)

    def close_extras(self, **kwargs: Any) -> None:
        for e in self.envs:
            e.close()


def make_skill_vector_env(env_id: str, num_envs: int, env_kwargs: dict | None = None) -> SkillVectorEnv:
    """The trainer's hook: a :class:`SkillVectorEnv` for a registered skill env id."""
    if env_id not in ENV_IDS:
        raise ValueError(f"vector_mode 'batched' supports {sorted(ENV_IDS)}, got env_id {env_id!r}")
    return SkillVectorEnv(env_id, num_envs, **(env_kwargs or {}))


__all__ = ["SkillVectorEnv", "make_skill_vector_env", "TASKS", "ENV_IDS"]
