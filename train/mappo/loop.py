"""The MAPPO training loop: collection over a :class:`~train.mappo.vec.DecisionVector`, SMDP GAE, updates,
logs, validation snapshots and resumable checkpoints.

Collection. A rollout steps every env ``rollout_steps`` times. Where ``infos[agent]["decision"]``
was True, the agent acts (the shared actor samples over its legal options) and a *sample* opens:
(obs, state, agent, action, log-prob, mask, V(state)). Every later step adds the agent's reward
and the step's ``elapsed_s`` to its open sample; the sample closes at the agent's next decision
(linked to the new sample: GAE continues), at the episode's end (termination: no bootstrap;
truncation: bootstrap on the final state) or at the rollout's end (bootstrap on the state
there; rewards the agent gets after that and before its next decision train nothing). Agents
without a decision are sent a placeholder action (0 / zeros) that the env ignores.
Advantages and returns: :func:`train.mappo.algorithm.gae` (the SMDP return is written there).

Observations and states are scaled to about [-1, 1] by their spaces' finite bounds
(``(x - centre) / half_width``; the exported actor stores the same ``obs_mean``/``obs_std``).

Resume. Every ``checkpoint_every`` rollouts the loop saves ``checkpoint.pt`` (networks,
optimisers, value normaliser, the action-sampling generator, counters, CSV row counts) and then
*cuts* every running episode (all envs reset from their seed counters; cut episodes are not
logged). A resumed run repeats that cut, so it continues exactly as the uninterrupted run.

Output folder: ``progress.csv`` (one row per rollout: decisions, agent-steps, episodes,
return and score of the episodes ended in the rollout, losses, throughput), ``val.csv`` and
``actors/actor-<decisions>.pt`` (greedy validation on ``val_seed + i`` and the actor at
that point, a decision actor file of :mod:`ssl_marl.skills.checkpoint`, for model selection),
``config.json``, ``learning_curve.png`` and ``tb/`` when TensorBoard is installed
(:class:`train.run_folder.RunFolder`).
"""

from __future__ import annotations

import random
import time
from dataclasses import asdict, dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np
import torch
from tqdm import tqdm

from ssl_marl.skills.checkpoint import git_commit, save_actor_file

from train.mappo.algorithm import MAPPO, MAPPOConfig, gae, smdp_discount
from train.mappo.tasks import get_task
from train.mappo.vec import DecisionVector
from train.run_folder import CHECKPOINT, RunFolder, read_state

STATE_FORMAT = "ssl_marl.mappo_state"
TICK_HZ = 60.0
PROGRESS_FIELDS = ["rollout", "decisions", "agent_steps", "env_steps", "episodes", "mean_return", "mean_score",
                   "policy_loss", "value_loss", "entropy", "approx_kl", "clipfrac", "decisions_per_s",
                   "agent_steps_per_s", "collect_share", "wall_time"]
VAL_FIELDS = ["rollout", "decisions", "val_score", "val_score_std", "val_return", "val_episodes", "actor"]


@dataclass(frozen=True)
class MAPPORunConfig:
    """One MAPPO run: the task, collection sizes, budget, schedule and the algorithm's hyperparameters."""

    task: str = "toy-signal"
    task_kwargs: dict = field(default_factory=dict)
    num_envs: int = 8                 # envs stepped together
    workers: int = 1                  # env worker processes (1: sequential, in the trainer's process)
    rollout_steps: int = 32           # env steps per env per rollout
    total_decisions: int = 200_000    # training samples (agent decisions) budget
    checkpoint_every: int = 10        # rollouts between checkpoints
    val_every: int = 10               # rollouts between validations (0: only at the end)
    val_episodes: int = 50            # greedy validation episodes (seeds val_seed + i)
    val_seed: int = 5000              # validation seed base (never an evaluation seed)
    torch_threads: int = 1
    init_actor: str | None = None     # decision-actor file whose weights start the actor (train.mappo.bc)
    actor_warmup_rollouts: int = 0    # first rollouts in which only the critic learns
    algo: MAPPOConfig = field(default_factory=MAPPOConfig)

    def to_dict(self) -> dict[str, Any]:
        d = asdict(self)
        d["algo"] = self.algo.to_dict()
        return d

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> MAPPORunConfig:
        d = dict(d)
        d["algo"] = MAPPOConfig.from_dict(d.get("algo", {}))
        return cls(**d)


def task_config(task: str, **overrides: Any) -> MAPPORunConfig:
    """The task's default run config (:data:`train.mappo.tasks.MARL_TASKS`) with ``overrides``
    (``algo`` may be a partial dict of :class:`MAPPOConfig` fields)."""
    d = MAPPORunConfig(task=task).to_dict()
    for src in (get_task(task).defaults, overrides):
        for k, v in src.items():
            if k == "algo":
                d["algo"] = {**d["algo"], **(v.to_dict() if isinstance(v, MAPPOConfig) else v)}
            elif k not in d:
                raise ValueError(f"unknown MAPPO run-config key {k!r}; expected one of {sorted(d)}")
            else:
                d[k] = v
    return MAPPORunConfig.from_dict(d)


def space_scaling(space: Any) -> tuple[np.ndarray, np.ndarray]:
    """``(centre, half_width)`` per dimension of a Box ``space``, float32: the bounds' midpoint and
    half range where both are finite and distinct, else 0 and 1 (``(x - centre) / half_width`` is
    then about [-1, 1] on bounded dimensions and unchanged on the others)."""
    lo, hi = np.asarray(space.low, np.float64), np.asarray(space.high, np.float64)
    finite = np.isfinite(lo) & np.isfinite(hi) & (hi > lo)
    centre = np.where(finite, (lo + hi) / 2, 0.0)
    half = np.where(finite, (hi - lo) / 2, 1.0)
    return centre.astype(np.float32), half.astype(np.float32)


def save_decision_actor(path: str | Path, agent: MAPPO, *, task: str, obs_mean: np.ndarray, obs_std: np.ndarray,
                        option_names: Any, agents: list[str], **meta: Any) -> Path:
    """Write the shared actor as a decision actor file (:mod:`ssl_marl.skills.checkpoint`, kind
    ``"decision"``): its weights and observation scaling, its shape, task and ``meta``."""
    state = {**agent.actor.state_dict(), "obs_mean": torch.as_tensor(obs_mean), "obs_std": torch.as_tensor(obs_std)}
    metadata = {"task": task, "obs_dim": agent.obs_dim, "n_options": agent.n_out, "hidden": list(agent.cfg.hidden),
                "continuous": bool(agent.cfg.continuous), "agent_ids": list(agents) if agent.cfg.agent_onehot else None,
                "option_names": list(option_names) if option_names is not None else None, **meta}
    return save_actor_file(path, "decision", state, metadata)


class MAPPOTrainer:
    """One run writing to ``out``; :meth:`run` trains to ``cfg.total_decisions`` samples."""

    def __init__(self, cfg: MAPPORunConfig, seed: int, out: str | Path, progress: bool = True,
                 resume: bool = False) -> None:
        self.cfg, self.seed, self.progress = cfg, int(seed), progress
        self.folder = RunFolder(out)
        self.out = self.folder.path
        torch.set_num_threads(max(1, cfg.torch_threads))
        random.seed(seed)
        np.random.seed(seed % 2**32)
        torch.manual_seed(seed)
        self.gen = torch.Generator().manual_seed(seed)
        self.task = get_task(cfg.task)
        self.vec = DecisionVector(cfg.task, cfg.task_kwargs, cfg.num_envs, seed, cfg.workers)
        env = self.vec.probe
        self.agents = self.vec.agents
        self.n_agents = len(self.agents)
        obs_space, act_space = env.observation_space(self.agents[0]), env.action_space(self.agents[0])
        self.obs_c, self.obs_s = space_scaling(obs_space)
        self.state_c, self.state_s = space_scaling(env.state_space)
        self.continuous = cfg.algo.continuous
        if self.continuous:
            self.act_low, self.act_high = np.asarray(act_space.low, np.float32), np.asarray(act_space.high, np.float32)
            n_out = int(np.prod(act_space.shape))
        else:
            if not hasattr(act_space, "n"):
                raise ValueError(f"task {cfg.task!r} has a {type(act_space).__name__} action space; "
                                 "set algo.continuous=true for Box actions")
            n_out = int(act_space.n)
        self.option_names = getattr(env, "option_names", None)
        self.agent = MAPPO(int(obs_space.shape[0]), int(env.state_space.shape[0]), self.n_agents, n_out, cfg.algo)
        self.counters = {"rollout": 0, "decisions": 0, "agent_steps": 0, "env_steps": 0, "episodes": 0}
        self.wall = 0.0
        self.progress_log = self.folder.csv_log("progress.csv", PROGRESS_FIELDS)
        self.val_log = self.folder.csv_log("val.csv", VAL_FIELDS)
        if resume:
            self._load()
        else:
            if cfg.init_actor:
                self.load_init_actor(cfg.init_actor)
            self.progress_log.clear()
            self.val_log.clear()
            self.folder.write_config({"seed": self.seed, **cfg.to_dict()})
        self.tb = self.folder.tensorboard(purge_step=self.counters["decisions"] if resume else None)
        self._cut()

    def load_init_actor(self, path: str | Path) -> None:
        """Start the shared actor from a decision-actor file (e.g. behaviour cloning of a
        benchmark policy, :mod:`train.mappo.bc`, or an actor of a task with the same decision,
        :func:`ssl_marl.decisions.learned.decision_family`), read by the one loader of that format
        (:func:`ssl_marl.decisions.learned.load_decision_actor`, ``weights_only=True``); its
        task family, sizes, hidden layers and observation scaling must be this run's."""
        from ssl_marl.decisions.learned import decision_family, load_decision_actor

        actor, meta = load_decision_actor(path)
        want = {"task": decision_family(self.cfg.task), "obs_dim": self.agent.obs_dim, "n_options": self.agent.n_out,
                "hidden": list(self.cfg.algo.hidden)}
        got = {"task": decision_family(meta.get("task")), "obs_dim": actor.obs_dim, "n_options": actor.n_options,
               "hidden": list(actor.hidden)}
        for k, v in want.items():
            if got[k] != v:
                raise ValueError(f"init_actor {path}: {k} is {got[k]!r}, this run needs {v!r}")
        if not (np.allclose(actor.obs_mean.numpy(), self.obs_c) and np.allclose(actor.obs_std.numpy(), self.obs_s)):
            raise ValueError(f"init_actor {path}: its observation scaling differs from this run's")
        self.agent.actor.net.load_state_dict(actor.net.state_dict())

    # --- scaling and acting ----------------------------------------------------------------------
    def _obs(self, x: np.ndarray) -> np.ndarray:
        return (x - self.obs_c) / self.obs_s

    def _state(self, x: np.ndarray) -> np.ndarray:
        return (x - self.state_c) / self.state_s

    def _env_action(self, a: np.ndarray) -> Any:
        if self.continuous:
            return self.act_low + (np.clip(a, -1.0, 1.0) + 1.0) * 0.5 * (self.act_high - self.act_low)
        return int(a)

    def _placeholder(self) -> Any:
        return np.zeros_like(self.act_low) + (self.act_low + self.act_high) / 2 if self.continuous else 0

    def _cut(self) -> None:
        """Reset every env (start of a run, and after each checkpoint)."""
        self.cur = self.vec.reset_all()
        self.ep_ret = np.zeros((self.vec.num_envs, self.n_agents))

    # --- one rollout -----------------------------------------------------------------------------
    def collect(self) -> tuple[dict[str, np.ndarray], dict[str, float]]:
        E, A = self.vec.num_envs, self.n_agents
        S: dict[str, list] = {k: [] for k in ("obs", "state", "agent", "act", "logp", "mask", "value")}
        rew, elapsed, next_value, terminal, next_index = [], [], [], [], []
        open_ = -np.ones((E, A), int)  # open sample index per (env, agent)
        ep_returns, ep_scores = [], []
        ticks = 0.0

        def close(k: int, v_next: float, term: bool, nxt: int) -> None:
            next_value[k], terminal[k], next_index[k] = v_next, float(term), nxt

        for _ in range(self.cfg.rollout_steps):
            rows = [(e, a) for e in range(E) for a in range(A) if self.cur[e]["decision"][a]]
            actions = [{ag: self._placeholder() for ag in self.agents} for _ in range(E)]
            if rows:
                obs = self._obs(np.stack([self.cur[e]["obs"][a] for e, a in rows]))
                state = self._state(np.stack([self.cur[e]["state"] for e, a in rows]))
                aidx = np.array([a for _, a in rows])
                mask = None
                if not self.continuous:
                    mask = np.stack([self.cur[e]["mask"][a] if self.cur[e]["mask"] is not None
                                     else np.ones(self.agent.n_out, np.int8) for e, a in rows])
                    if (mask.sum(-1) == 0).any():
                        raise ValueError("an agent has a decision but no legal option (action_mask all zero)")
                act, logp = self.agent.act(obs, aidx, mask, self.gen)
                val = self.agent.value(state, aidx)
                for j, (e, a) in enumerate(rows):
                    k = len(rew)
                    if open_[e, a] >= 0:
                        close(open_[e, a], val[j], False, k)
                    open_[e, a] = k
                    for key, v in (("obs", obs[j]), ("state", state[j]), ("agent", a), ("act", act[j]),
                                   ("logp", logp[j]), ("mask", None if mask is None else mask[j]), ("value", val[j])):
                        S[key].append(v)
                    rew.append(0.0), elapsed.append(0.0), next_value.append(0.0), terminal.append(0.0)
                    next_index.append(-1)
                    actions[e][self.agents[a]] = self._env_action(act[j])
            results = self.vec.step(actions)
            boot: list[tuple[int, int, np.ndarray]] = []  # (sample, agent, final state) for truncations
            for e, r in enumerate(results):
                ticks += r["elapsed"] * TICK_HZ
                self.ep_ret[e] += r["rew"]
                for a in range(A):
                    k = open_[e, a]
                    if k >= 0:
                        rew[k] += r["rew"][a]
                        elapsed[k] += r["elapsed"]
                if r["done"]:
                    for a in range(A):
                        k = open_[e, a]
                        if k >= 0:
                            if r["term"][a]:
                                close(k, 0.0, True, -1)
                            else:
                                boot.append((k, a, r["state"]))
                            open_[e, a] = -1
                    ep_returns.append(float(self.ep_ret[e].mean()))
                    fi = r["final_infos"][self.agents[0]]
                    ep_scores.append(float(fi.get(self.task.score_key, np.nan)))
                    self.ep_ret[e] = 0.0
                    self.cur[e] = r["reset"]
                else:
                    self.cur[e] = r
            if boot:
                self._bootstrap(boot, close)
            self.counters["env_steps"] += E
        rest = [(open_[e, a], a, self.cur[e]["state"]) for e in range(E) for a in range(A) if open_[e, a] >= 0]
        if rest:
            self._bootstrap(rest, close)
        n = len(rew)
        adv, ret = gae(np.array(rew), np.array(S["value"]), np.array(next_value),
                       smdp_discount(np.array(elapsed), self.cfg.algo.gamma, self.cfg.algo.tau_s),
                       np.array(terminal), np.array(next_index, int), self.cfg.algo.lam)
        batch = {"obs": np.asarray(S["obs"], np.float32).reshape(n, -1),
                 "state": np.asarray(S["state"], np.float32).reshape(n, -1),
                 "agent": np.asarray(S["agent"], np.int64), "act": np.asarray(S["act"]),
                 "logp": np.asarray(S["logp"], np.float32), "adv": adv, "ret": ret}
        if not self.continuous:
            batch["mask"] = np.asarray(S["mask"], np.int8).reshape(n, -1)
            batch["act"] = batch["act"].astype(np.int64)
        else:
            batch["act"] = batch["act"].astype(np.float32).reshape(n, -1)
        self.counters["decisions"] += n
        self.counters["agent_steps"] += int(round(ticks * A))
        self.counters["episodes"] += len(ep_returns)
        stats = {"mean_return": float(np.mean(ep_returns)) if ep_returns else None,
                 "mean_score": float(np.nanmean(ep_scores)) if ep_scores and not np.all(np.isnan(ep_scores)) else None,
                 "episodes_in_rollout": len(ep_returns), "ticks": ticks}
        return batch, stats

    def _bootstrap(self, items: list, close: Any) -> None:
        states = self._state(np.stack([s for _, _, s in items]))
        v = self.agent.value(states, np.array([a for _, a, _ in items]))
        for (k, _, _), vk in zip(items, v):
            close(k, float(vk), False, -1)

    # --- validation ------------------------------------------------------------------------------
    def validate(self) -> dict[str, float]:
        """Greedy episodes on seeds ``val_seed + i``; mean and std of the task score and team return."""
        env = get_task(self.cfg.task).factory(**self.cfg.task_kwargs)
        scores, returns = [], []
        for i in range(self.cfg.val_episodes):
            obs, infos = env.reset(seed=self.cfg.val_seed + i)
            total, done = 0.0, False
            while not done:
                act = {}
                for a_i, ag in enumerate(self.agents):
                    if infos[ag].get("decision", True):
                        m = None if self.continuous else np.asarray(infos[ag].get("action_mask",
                                                                    np.ones(self.agent.n_out)), np.int8)[None]
                        a, _ = self.agent.act(self._obs(np.asarray(obs[ag], np.float32))[None], np.array([a_i]),
                                              m, greedy=True)
                        act[ag] = self._env_action(a[0])
                    else:
                        act[ag] = self._placeholder()
                obs, rew, term, trunc, infos = env.step(act)
                total += float(np.mean([rew[ag] for ag in self.agents]))
                done = any(term.values()) or any(trunc.values())
            scores.append(float(infos[self.agents[0]].get(self.task.score_key, np.nan)))
            returns.append(total)
        env.close()
        return {"val_score": float(np.mean(scores)), "val_score_std": float(np.std(scores)),
                "val_return": float(np.mean(returns)), "val_episodes": len(scores)}

    def save_actor(self, path: Path, **meta: Any) -> Path:
        return save_decision_actor(path, self.agent, task=self.cfg.task, obs_mean=self.obs_c, obs_std=self.obs_s,
                                   option_names=self.option_names, agents=self.agents, seed=self.seed,
                                   decisions=self.counters["decisions"], commit=git_commit(), **meta)

    def _validate_and_snapshot(self) -> dict[str, float]:
        v = self.validate()
        d = self.counters["decisions"]
        path = self.save_actor(self.folder.actor_snapshot(d), val_score=v["val_score"],
                               val_seed=self.cfg.val_seed, val_episodes=v["val_episodes"])
        self.val_log.write({"rollout": self.counters["rollout"], "decisions": d, **v,
                            "actor": str(path.relative_to(self.out))})
        self.tb.scalars("val", v, d)
        return v

    # --- checkpoints -----------------------------------------------------------------------------
    def checkpoint(self) -> None:
        self.folder.save_checkpoint({"format": STATE_FORMAT, "version": 1, "config": self.cfg.to_dict(),
                                     "seed": self.seed, "agent": self.agent.state_dict(), "gen": self.gen.get_state(),
                                     "torch_rng": torch.get_rng_state(), "counters": dict(self.counters),
                                     "env_counters": list(self.vec.counters), "wall": self.wall,
                                     "csv_rows": {"progress": self.progress_log.rows, "val": self.val_log.rows}})

    def _load(self) -> None:
        st = read_mappo_state(self.folder.checkpoint)
        saved = MAPPORunConfig.from_dict(st["config"])
        if replace(saved, total_decisions=self.cfg.total_decisions) != self.cfg or int(st["seed"]) != self.seed:
            raise ValueError(f"{self.out / CHECKPOINT} was written by another config or seed; "
                             "resume with the checkpoint's own (see load_mappo_run)")
        self.agent.load_state_dict(st["agent"])
        self.gen.set_state(st["gen"])
        torch.set_rng_state(st["torch_rng"])
        self.counters = {k: int(v) for k, v in st["counters"].items()}
        self.vec.counters = [int(c) for c in st["env_counters"]]
        self.wall = float(st["wall"])
        self.progress_log.truncate(int(st["csv_rows"]["progress"]))
        self.val_log.truncate(int(st["csv_rows"]["val"]))

    # --- the run ---------------------------------------------------------------------------------
    def run(self, stop_after_rollouts: int | None = None) -> dict[str, Any]:
        """Train to the budget (or ``stop_after_rollouts`` more rollouts, for tests); returns the last row."""
        cfg = self.cfg
        bar = tqdm(total=cfg.total_decisions, initial=min(self.counters["decisions"], cfg.total_decisions),
                   disable=not self.progress, unit="dec", desc=f"mappo {cfg.task} s{self.seed}", dynamic_ncols=True)
        row: dict[str, Any] = {}
        done_rollouts = 0
        try:
            while self.counters["decisions"] < cfg.total_decisions:
                if stop_after_rollouts is not None and done_rollouts >= stop_after_rollouts:
                    break
                t0 = time.perf_counter()
                before = self.counters["decisions"]
                batch, st = self.collect()
                t_collect = time.perf_counter() - t0
                losses = self.agent.update(batch, self.gen,
                                           train_actor=self.counters["rollout"] >= cfg.actor_warmup_rollouts)
                dt = time.perf_counter() - t0
                self.wall += dt
                self.counters["rollout"] += 1
                done_rollouts += 1
                n = self.counters["decisions"] - before
                row = {"rollout": self.counters["rollout"], **{k: self.counters[k] for k in
                       ("decisions", "agent_steps", "env_steps", "episodes")},
                       "mean_return": st["mean_return"], "mean_score": st["mean_score"],
                       "policy_loss": losses["policy"], "value_loss": losses["value"], "entropy": losses["entropy"],
                       "approx_kl": losses["approx_kl"], "clipfrac": losses["clipfrac"],
                       "decisions_per_s": n / dt, "agent_steps_per_s": st["ticks"] * self.n_agents / dt,
                       "collect_share": t_collect / dt, "wall_time": round(self.wall, 3)}
                self.progress_log.write(row)
                self.tb.scalars("train", row, self.counters["decisions"])
                bar.update(n)
                bar.set_postfix(score=st["mean_score"], ent=round(losses["entropy"], 3),
                                dps=round(n / dt), refresh=False)
                r = self.counters["rollout"]
                last = self.counters["decisions"] >= cfg.total_decisions
                if (cfg.val_every and r % cfg.val_every == 0) or last:
                    self._validate_and_snapshot()
                if r % cfg.checkpoint_every == 0 or last:
                    self.checkpoint()
                    if not last:
                        self._cut()
        finally:
            bar.close()
        return row

    def close(self) -> None:
        self.vec.close()
        self.progress_log.close()
        self.val_log.close()
        self.tb.close()


def read_mappo_state(path: str | Path) -> dict[str, Any]:
    """A MAPPO train state (``OUT/checkpoint.pt``), read with ``weights_only=True``."""
    return read_state(path, STATE_FORMAT, "ssl_marl MAPPO training checkpoint")


def load_mappo_run(out: str | Path) -> tuple[MAPPORunConfig, int]:
    """Config and seed stored in ``OUT/checkpoint.pt`` (for ``--resume``)."""
    st = read_mappo_state(Path(out) / CHECKPOINT)
    return MAPPORunConfig.from_dict(st["config"]), int(st["seed"])


def train_mappo(cfg: MAPPORunConfig, seed: int, out: str | Path, resume: bool = False,
                progress: bool = True) -> dict[str, Any]:
    """Train (or resume) one run to its budget; draw its learning curve; return the final row and validation."""
    trainer = MAPPOTrainer(cfg, seed, out, progress=progress, resume=resume)
    try:
        row = trainer.run()
    finally:
        trainer.close()
    try:
        from train.mappo.report import plot_mappo_run

        plot_mappo_run(out)
    except Exception as exc:  # the plot is a convenience; the CSVs are the record
        print(f"note: learning curve not drawn ({type(exc).__name__}: {exc})")
    return row


__all__ = ["MAPPORunConfig", "MAPPOTrainer", "load_mappo_run", "save_decision_actor", "space_scaling", "task_config",
           "train_mappo"]
