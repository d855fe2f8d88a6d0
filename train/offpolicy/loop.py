"""The training loop: demo burn-in, collection with exploration noise, updates, logs, checkpoints, export.

Algorithm-free: the agent (:mod:`train.offpolicy.algos`, chosen by ``cfg.algo``) does the
updates, the exploration process (:mod:`train.offpolicy.exploration`, ``cfg.exploration.kind``)
perturbs its actions; this module collects, logs, evaluates, checkpoints and
exports.

Data handling (Gymnasium 1.x vector envs, ``AutoresetMode.NEXT_STEP``):

* The step on which a sub-env ends returns the true final observation; it is
  stored as ``next_obs`` with ``terminated`` (no bootstrap) -- truncations
  (time limits) are stored with ``terminated = 0`` and so bootstrap.
* The following step of that sub-env is a reset step that ignores the action;
  its transition is never stored (tracked by ``self.autoreset``).
* With ``n_step`` > 1 each sub-env's steps go through :class:`train.offpolicy.nstep.NStepBuffer`
  first: a row is stored once its n-step window is complete or its episode ended;
  a checkpoint cut ends the open windows as truncations. ``samples`` counts env steps.

Resume: every ``checkpoint_interval`` env samples the loop cuts all running
episodes (re-seeds and resets the envs; cut episodes are not logged, their
stored transitions stay valid) and saves everything else. A run resumed from a
checkpoint therefore continues exactly as the uninterrupted run does, given
deterministic envs and the same thread count.

Output folder: ``progress.csv`` (one row per episode, demo episodes flagged
``phase=demo``), ``eval.csv``, ``checkpoint.pt`` + ``replay-*.npz``,
``actors/actor-<samples>.pt`` (the actor at each checkpoint, for model selection),
``config.json``, ``actor.pt`` (export), ``eval.json`` (final evaluation),
``learning_curve.png``, and ``tb/`` when TensorBoard is installed (:class:`train.run_folder.RunFolder`).
"""

from __future__ import annotations

import dataclasses
import importlib
import itertools
import random
import time
from collections import deque
from collections.abc import Callable, Iterable, Mapping
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
import torch
from gymnasium.vector import AsyncVectorEnv, AutoresetMode, SyncVectorEnv
from tqdm import tqdm

import ssl_marl  # noqa: F401  (registers the ssl_marl/* Gymnasium ids)
from ssl_marl.io import atomic_write_json
from ssl_marl.skills.checkpoint import save_actor

from train.logs import EVAL_FIELDS, TensorBoardLog, progress_fields
from train.offpolicy.algos import make_agent
from train.offpolicy.checkpoints import FORMAT, VERSION, actor_metadata, load_run_config, read_train_state
from train.offpolicy.config import TrainConfig
from train.offpolicy.demos import fill_replay
from train.offpolicy.evaluate import ActionScaler, evaluate_actor, make_env, run_episodes
from train.offpolicy.exploration import make_exploration
from train.offpolicy.nstep import NStepBuffer
from train.offpolicy.replay import ReplayBuffer
from train.run_folder import CHECKPOINT, RunFolder

__all__ = ["CHECKPOINT", "Trainer", "load_run_config", "train"]
DemoFn = Callable[..., Iterable[Any]]


def resolve_callable(path: str) -> Callable[..., Any]:
    """``"package.module:function"`` -> the function."""
    module, sep, name = path.partition(":")
    if not sep or not module or not name:
        raise ValueError(f"expected 'module:function', got {path!r}")
    obj: Any = importlib.import_module(module)
    for part in name.split("."):
        obj = getattr(obj, part)
    if not callable(obj):
        raise ValueError(f"{path} is not callable")
    return obj


def spec_version(env: gym.Env, env_id: str) -> str:
    """The env's observation-spec string (``env.unwrapped.spec_version``), else its id."""
    v = getattr(env.unwrapped, "spec_version", None)
    return v if isinstance(v, str) and v else env_id


def _masked(info: Mapping[str, Any], key: str, i: int) -> Any:
    """Sub-env ``i``'s value of vector-env info ``key`` (None when absent for that sub-env)."""
    if key not in info or not bool(info.get("_" + key, np.ones(i + 1, bool))[i]):
        return None
    return info[key][i]


def split_evenly(total: int, parts: int) -> list[int]:
    """``total`` split into ``parts`` counts differing by at most one (the first ones larger)."""
    return [total // parts + (j < total % parts) for j in range(parts)]


def pool_results(parts: list[dict[str, Any]]) -> dict[str, Any]:
    """Pool :func:`~train.offpolicy.evaluate.run_episodes` results of the env variants (one: unchanged);
    the per-variant figures (without their returns) are kept under ``"variants"``."""
    if len(parts) == 1:
        return parts[0]
    episodes = sum(p["episodes"] for p in parts)
    returns = [r for p in parts for r in p["returns"]]
    rates = [p["success_rate"] for p in parts]
    return {**{k: v for k, v in parts[0].items() if k not in ("returns", "success_rate")},
            "episodes": episodes, "mean_return": float(np.mean(returns)), "std_return": float(np.std(returns)),
            "mean_length": float(sum(p["mean_length"] * p["episodes"] for p in parts) / episodes),
            "success_rate": None if None in rates else float(sum(r * p["episodes"] for r, p in zip(rates, parts))
                                                              / episodes),
            "returns": returns, "variants": [{k: v for k, v in p.items() if k != "returns"} for p in parts]}


class Trainer:
    """One training run writing to ``out``; :meth:`run` trains to ``cfg.total_samples`` env samples."""

    def __init__(self, cfg: TrainConfig, seed: int, out: str | Path, demo_fn: DemoFn | None = None,
                 progress: bool = True) -> None:
        self.cfg, self.seed, self.progress = cfg, int(seed), progress
        self.folder = RunFolder(out)
        self.out = self.folder.path
        if cfg.torch_threads > 0:
            torch.set_num_threads(cfg.torch_threads)
        random.seed(seed)
        torch.manual_seed(seed)
        ss = np.random.SeedSequence(seed)
        noise_rng, replay_rng, self.rng = (np.random.default_rng(s) for s in ss.spawn(3))

        variants = cfg.variant_kwargs()  # one dict per block of sub-envs (config.env_variants)
        self.eval_envs = [make_env(cfg.env_id, kw, cfg.max_episode_steps) for kw in variants]
        self.eval_env = self.eval_envs[0]
        obs_space, act_space = self.eval_env.observation_space, self.eval_env.action_space
        for e in self.eval_envs[1:]:
            if e.observation_space.shape != obs_space.shape or e.action_space != act_space:
                raise ValueError(f"invalid training config: env_variants give different spaces ({e.observation_space}, "
                                 f"{e.action_space} vs {obs_space}, {act_space})")
        if not isinstance(obs_space, gym.spaces.Box) or len(obs_space.shape) != 1:
            raise ValueError(f"{cfg.algo} needs a flat Box observation space, got {obs_space}")
        self.obs_dim, self.act_dim = obs_space.shape[0], int(np.prod(act_space.shape))
        self.scaler = ActionScaler(act_space)
        self.obs_spec = spec_version(self.eval_env, cfg.env_id)
        self.demo_fn = demo_fn if demo_fn is not None else (resolve_callable(cfg.demo_fn) if cfg.demo_fn else None)

        self.agent = make_agent(self.obs_dim, self.act_dim, cfg)
        # n_step > 1: windows per sub-env (train.offpolicy.nstep), rows carry their own discount; 1: the one-step path
        self.nstep = NStepBuffer(cfg.num_envs, cfg.n_step, cfg.ddpg.gamma, self.obs_dim, self.act_dim) \
            if cfg.n_step > 1 else None
        self.buffer = ReplayBuffer(cfg.buffer_size, self.obs_dim, self.act_dim, cfg.batch_size, replay_rng,
                                   discount=self.nstep is not None, default_discount=cfg.ddpg.gamma)
        self.noise = make_exploration(cfg.exploration, cfg.num_envs, self.act_dim, noise_rng)
        per_block = cfg.num_envs // len(variants)  # sub-envs [j * per_block, (j + 1) * per_block) use variants[j]
        env_fns = [lambda kw=kw: make_env(cfg.env_id, kw, cfg.max_episode_steps) for kw in variants
                   for _ in range(per_block)]
        if cfg.vector_mode == "batched":  # the skill tasks' worlds stepped together (ssl_marl.skills.vector)
            from ssl_marl.skills.vector import make_skill_vector_env

            if cfg.max_episode_steps:
                raise ValueError("vector_mode 'batched' does not take max_episode_steps (the tasks time out themselves)")
            blocks = [make_skill_vector_env(cfg.env_id, per_block, kw) for kw in variants]
            if len(blocks) == 1:
                self.envs = blocks[0]
            else:  # one batched world set per configuration (a field each), side by side
                from ssl_marl.skills.concat_vector import ConcatVectorEnv

                self.envs = ConcatVectorEnv(blocks)
        else:
            vec_cls = SyncVectorEnv if cfg.vector_mode == "sync" else AsyncVectorEnv
            self.envs = vec_cls(env_fns, autoreset_mode=AutoresetMode.NEXT_STEP,  # variants: bounds differ per field
                                observation_mode="different" if len(variants) > 1 else "same")

        # counters (all saved in the checkpoint)
        self.samples = 0  # env samples stored by the learner (excludes demos)
        self.transitions = 0  # all transitions stored, demos included
        self.episodes = 0
        self.segment = 0  # checkpoint cuts so far; seeds the env resets
        self.update_credit = 0.0
        self.demo_done = False
        self.next_eval = cfg.eval_interval if cfg.eval_interval > 0 else None
        self.next_checkpoint = cfg.checkpoint_interval
        self.wall_offset = 0.0
        self.losses: dict[str, float] | None = None  # the last read-out of the agent's named losses
        self.recent_returns: deque[float] = deque(maxlen=100)
        self.recent_success: deque[float] = deque(maxlen=100)

        self.log = self.folder.csv_log("progress.csv")
        self.eval_log = self.folder.csv_log("eval.csv", EVAL_FIELDS)
        self.tb: TensorBoardLog | None = None  # opened by run() (it knows whether this is a resume)
        self._t0 = time.perf_counter()

    # --- helpers --------------------------------------------------------------
    def wall_time(self) -> float:
        return self.wall_offset + time.perf_counter() - self._t0

    def _reset_envs(self) -> None:
        """(Re)start every sub-env from a seed fixed by (seed, segment): part of the resume contract."""
        self.env_seed = int(np.random.SeedSequence([self.seed, self.segment]).generate_state(1)[0] % 2**31)
        self.obs, _ = self.envs.reset(seed=self.env_seed)  # sub-env i gets env_seed + i
        self.autoreset = np.zeros(self.cfg.num_envs, bool)
        self.noise.reset()
        self.ep_return = np.zeros(self.cfg.num_envs)
        self.ep_length = np.zeros(self.cfg.num_envs, np.int64)
        self.ep_terms: dict[str, np.ndarray] = {}

    def _log_episode(self, phase: str, ret: float, length: int, success: Any, terms: Mapping[str, float]) -> None:
        self.episodes += 1
        self.recent_returns.append(ret)
        if success is not None:
            self.recent_success.append(float(bool(success)))
        if self.log.fields is None:  # first row fixes the columns: base + reward terms seen now
            self.log.fields = progress_fields(self.agent.loss_names, list(terms))
        losses = self.losses or {}
        row = {"phase": phase, "samples": self.samples, "transitions": self.transitions, "episode": self.episodes,
               "return": round(ret, 6), "length": length, "success": None if success is None else int(bool(success)),
               **{f"{k}_loss": None if k not in losses else round(losses[k], 6) for k in self.agent.loss_names},
               "updates": self.agent.updates, "wall_time": round(self.wall_time(), 3)}
        row.update({f"r_{k}": round(float(v), 6) for k, v in terms.items()})
        self.log.write(row)
        if self.tb is not None:
            self.tb.scalars(phase, {"return": ret, "length": length, "success": row["success"],
                                    **{f"r_{k}": v for k, v in terms.items()}},
                            self.transitions)

    # --- demonstration burn-in -------------------------------------------------
    def burn_in(self) -> None:
        """Fill the replay with ``cfg.demo_steps`` demonstration transitions (checked against the spaces)."""
        cfg = self.cfg
        if self.demo_done or self.demo_fn is None or cfg.demo_steps <= 0:
            self.demo_done = True
            return
        start = self.transitions

        def on_episode(stored: int, ret: float, length: int, success: Any, terms: Mapping[str, float]) -> None:
            self.transitions = start + stored
            self._log_episode("demo", ret, length, success, terms)

        variants = cfg.variant_kwargs()
        shares = split_evenly(cfg.demo_steps, len(variants))
        demos = itertools.chain.from_iterable(
            itertools.islice(self.demo_fn(n_steps=n, seed=self.seed + j, **kw), n)
            for j, (n, kw) in enumerate(zip(shares, variants)))
        self.transitions = start + fill_replay(demos, cfg.demo_steps, self.buffer, self.scaler, self.obs_dim,
                                               cfg.reward_scale, on_episode, self.progress)
        self.demo_done = True

    # --- collection -----------------------------------------------------------
    def collect_step(self) -> int:
        """One vector-env step; store the real transitions; return how many were stored."""
        cfg = self.cfg
        noise = self.noise()  # advance every process (sub-envs in autoreset discard theirs)
        if cfg.random_warmup and self.samples < cfg.warmup_samples:
            act = self.rng.uniform(-1.0, 1.0, (cfg.num_envs, self.act_dim)).astype(np.float32)
        else:
            act = np.clip(self.agent.act(self.obs) + noise, -1.0, 1.0)
        next_obs, rew, term, trunc, info = self.envs.step(self.scaler.to_env(act))
        valid = ~self.autoreset  # False: this step was an autoreset step (action ignored, obs = reset obs)
        if self.nstep is None:
            self.buffer.add(self.obs[valid], act[valid], rew[valid] * cfg.reward_scale, next_obs[valid], term[valid])
        else:
            ready = self.nstep.step(np.flatnonzero(valid), self.obs[valid], act[valid],
                                    rew[valid] * cfg.reward_scale, next_obs[valid], term[valid], trunc[valid])
            self.buffer.add(*ready)
        n_valid = int(valid.sum())
        self.samples += n_valid
        self.transitions += n_valid

        self.ep_return[valid] += rew[valid]
        self.ep_length[valid] += 1
        terms = info.get("reward_terms")
        if isinstance(terms, Mapping):
            for k, v in terms.items():
                if not k.startswith("_"):
                    mask = valid & np.asarray(terms.get("_" + k, valid), bool)
                    self.ep_terms.setdefault(k, np.zeros(cfg.num_envs))[mask] += np.asarray(v, np.float64)[mask]
        done = (term | trunc) & valid
        for i in np.flatnonzero(done):
            ep_terms = {k: float(v[i]) for k, v in self.ep_terms.items()}
            self._log_episode("train", float(self.ep_return[i]), int(self.ep_length[i]),
                              _masked(info, "is_success", i), ep_terms)
            self.ep_return[i], self.ep_length[i] = 0.0, 0
            for v in self.ep_terms.values():
                v[i] = 0.0
        self.noise.reset(~valid)  # sub-envs that just reset start their new episode with fresh noise
        self.autoreset = done
        self.obs = next_obs
        return n_valid

    def train_step(self, n_new: int) -> None:
        """Do the updates earned by ``n_new`` new samples (``updates_per_sample`` each) after warm-up."""
        cfg = self.cfg
        if self.samples < cfg.warmup_samples or len(self.buffer) < cfg.batch_size:
            return
        self.update_credit += n_new * cfg.updates_per_sample
        n_demo = self.transitions - self.samples  # burn-in wrote the demos to rows [0, n_demo)
        use_bc = cfg.ddpg.bc_weight > 0 and n_demo > 0 and self.transitions <= self.buffer.capacity  # not overwritten yet
        if use_bc and cfg.bc_anneal_samples > 0:
            use_bc = self.anneal_bc()
        while self.update_credit >= 1.0:
            demo = self.buffer.sample_rows(0, n_demo, cfg.bc_batch_size) if use_bc else None
            self.agent.update(self.buffer.sample(), demo)
            self.update_credit -= 1.0
            if self.agent.updates % cfg.log_interval == 0:
                losses = self.agent.read_losses()
                if losses is not None:
                    self.losses = {**(self.losses or {}), **losses}
                    if self.tb is not None:
                        self.tb.scalars("loss", losses, self.transitions)

    def anneal_bc(self) -> bool:
        """Set the agent's behaviour-cloning weight to ``ddpg.bc_weight`` x max(0, 1 - (samples -
        warmup_samples) / bc_anneal_samples) (a function of the sample count, so a resumed
        run anneals as the uninterrupted one); False once it is 0 (no demo rows needed).
        The agent gets a changed copy of its section; the run config keeps ``bc_weight``."""
        cfg = self.cfg
        w = cfg.ddpg.bc_weight * max(0.0, 1.0 - (self.samples - cfg.warmup_samples) / cfg.bc_anneal_samples)
        self.agent.cfg = dataclasses.replace(self.agent.cfg, bc_weight=w)
        return w > 0

    def evaluate(self) -> dict[str, Any]:
        """Deterministic evaluation on the fixed eval start states (seed + 1000); logged to eval.csv."""
        policy = lambda o: self.agent.act(o[None])[0]  # noqa: E731
        shares = split_evenly(self.cfg.eval_episodes, len(self.eval_envs))  # per env variant
        res = pool_results([run_episodes(e, policy, n, self.seed + 1000)
                            for e, n in zip(self.eval_envs, shares) if n > 0])
        row = {"samples": self.samples, "transitions": self.transitions, "updates": self.agent.updates,
               "wall_time": round(self.wall_time(), 3), **{k: res[k] for k in EVAL_FIELDS if k in res}}
        self.eval_log.write(row)
        if self.tb is not None:
            self.tb.scalars("eval", {k: res[k] for k in ("mean_return", "std_return", "mean_length", "success_rate")},
                            self.transitions)
        return res

    # --- checkpoints ----------------------------------------------------------
    def save_checkpoint(self) -> Path:
        """Cut running episodes, then save everything needed to resume (atomically)."""
        while self.next_checkpoint <= self.samples:
            self.next_checkpoint += self.cfg.checkpoint_interval
        self.segment += 1
        if self.nstep is not None:  # the cut ends every running window as a truncation (bootstraps)
            self.buffer.add(*self.nstep.flush(self.obs))
        self._reset_envs()
        replay_name = f"replay-{self.transitions:012d}.npz"
        self.buffer.save(self.out / replay_name)
        state = {
            "format": FORMAT, "version": VERSION, "algo": self.cfg.algo, "config": self.cfg.to_dict(),
            "seed": self.seed, "agent": self.agent.state_dict(), "exploration": self.noise.state_dict(),
            "rng": {"action": self.rng.bit_generator.state, "replay": self.buffer.rng.bit_generator.state,
                    "torch": torch.get_rng_state(), "python": random.getstate()},
            "counters": {"samples": self.samples, "transitions": self.transitions, "episodes": self.episodes,
                         "segment": self.segment, "env_seed": self.env_seed, "update_credit": self.update_credit,
                         "demo_done": self.demo_done, "next_eval": self.next_eval,
                         "next_checkpoint": self.next_checkpoint, "wall_time": self.wall_time()},
            "losses": self.losses,
            "recent": {"returns": list(self.recent_returns), "success": list(self.recent_success)},
            "csv_rows": {"progress": self.log.rows, "eval": self.eval_log.rows}, "replay_file": replay_name,
        }
        self.folder.save_checkpoint(state)
        self.export_actor(self.folder.actor_snapshot(self.samples, digits=9))
        for old in self.out.glob("replay-*.npz"):
            if old.name != replay_name:
                old.unlink(missing_ok=True)
        return self.folder.checkpoint

    def load_checkpoint(self) -> None:
        state = read_train_state(self.folder.checkpoint)
        if int(state["seed"]) != self.seed:
            raise ValueError(f"checkpoint was made with seed {state['seed']}, not {self.seed}")
        if state["algo"] != self.cfg.algo:
            raise ValueError(f"checkpoint was trained with algo {state['algo']!r}, not {self.cfg.algo!r}")
        self.agent.load_state_dict(state["agent"])
        self.noise.load_state_dict(state["exploration"])
        self.buffer.load(self.out / state["replay_file"])
        self.rng.bit_generator.state = state["rng"]["action"]
        self.buffer.rng.bit_generator.state = state["rng"]["replay"]
        torch.set_rng_state(state["rng"]["torch"])
        random.setstate(state["rng"]["python"])
        c = state["counters"]
        self.samples, self.transitions, self.episodes = int(c["samples"]), int(c["transitions"]), int(c["episodes"])
        self.segment, self.update_credit, self.demo_done = int(c["segment"]), float(c["update_credit"]), c["demo_done"]
        self.next_eval, self.next_checkpoint = c["next_eval"], int(c["next_checkpoint"])
        self.wall_offset = float(c["wall_time"])
        self._t0 = time.perf_counter()
        self.losses = dict(state["losses"]) if state["losses"] is not None else None
        self.recent_returns.extend(state["recent"]["returns"])
        self.recent_success.extend(state["recent"]["success"])
        self.log.truncate(int(state["csv_rows"]["progress"]))
        self.eval_log.truncate(int(state["csv_rows"]["eval"]))
        noise_state = self.noise.state_dict()
        self._reset_envs()  # same seed as the uninterrupted run used right after this checkpoint
        self.noise.load_state_dict(noise_state)

    # --- main ------------------------------------------------------------------
    def run(self, resume: bool = False) -> dict[str, Any]:
        """Train (or resume) to ``cfg.total_samples``; export ``actor.pt``; return a summary."""
        cfg = self.cfg
        self.folder.write_config({**cfg.to_dict(), "seed": self.seed})
        if resume:
            self.load_checkpoint()
        else:
            self.log.clear()
            self.eval_log.clear()
            self._reset_envs()
        self.tb = self.folder.tensorboard(purge_step=self.transitions if resume else None)
        if not resume:
            self.burn_in()
        bar = tqdm(total=cfg.total_samples, initial=min(self.samples, cfg.total_samples), desc=cfg.skill,
                   unit="sample", disable=not self.progress, dynamic_ncols=True, smoothing=0.05)
        last_postfix = 0.0
        try:
            while self.samples < cfg.total_samples:
                n_new = self.collect_step()
                self.train_step(n_new)
                bar.update(n_new)
                if self.next_eval is not None and self.samples >= self.next_eval:
                    self.evaluate()
                    while self.next_eval <= self.samples:
                        self.next_eval += cfg.eval_interval
                if self.samples >= self.next_checkpoint or self.samples >= cfg.total_samples:
                    self.save_checkpoint()
                if self.progress and time.perf_counter() - last_postfix > 1.0:
                    last_postfix = time.perf_counter()
                    bar.set_postfix(self.postfix(), refresh=False)
        finally:
            bar.close()
            self.envs.close()
            self.log.close()
            self.eval_log.close()
            self.tb.close()
        return self.finish()

    def postfix(self) -> dict[str, str]:
        d = {"ret": f"{np.mean(self.recent_returns):.1f}" if self.recent_returns else "-"}
        if self.recent_success:
            d["succ"] = f"{np.mean(self.recent_success):.2f}"
        for k, v in (self.losses or {}).items():
            d[f"L{k[0]}"] = f"{v:.3g}"
        d["upd"] = str(self.agent.updates)
        return d

    def export_actor(self, path: Path | None = None) -> Path:
        """Write the current actor with its metadata (``OUT/actor.pt`` by default)."""
        meta = actor_metadata(self.cfg, obs_spec=self.obs_spec, seed=self.seed, samples=self.samples,
                              transitions=self.transitions, updates=self.agent.updates,
                              action_low=self.scaler.low.tolist(), action_high=self.scaler.high.tolist())
        return save_actor(path or self.out / "actor.pt", self.agent.actor, meta)

    def finish(self) -> dict[str, Any]:
        """Export the actor, evaluate it (``eval.json``), draw the learning curve."""
        actor_path = self.export_actor()
        shares = split_evenly(self.cfg.eval_episodes, len(self.eval_envs))  # per env variant
        result = pool_results([evaluate_actor(self.cfg.env_id, actor_path, n, self.seed + 1000, kw,
                                              self.cfg.max_episode_steps)
                               for kw, n in zip(self.cfg.variant_kwargs(), shares) if n > 0])
        result["wall_time_s"] = round(self.wall_time(), 1)
        atomic_write_json(self.out / "eval.json", result)
        for e in self.eval_envs:
            e.close()
        try:
            from train.tools.plots import plot_run
            plot_run(self.out)
        except Exception as exc:  # a plotting problem must not lose a finished run
            print(f"warning: could not draw the learning curve: {exc}")
        return result


def train(cfg: TrainConfig, seed: int, out: str | Path, resume: bool = False, demo_fn: DemoFn | None = None,
          progress: bool = True) -> dict[str, Any]:
    """Train an actor per ``cfg`` (algorithm ``cfg.algo``); return the final evaluation (also in ``OUT/eval.json``)."""
    out = Path(out)
    if not resume and (out / CHECKPOINT).exists():
        raise FileExistsError(f"{out} already holds a run; pass resume=True (--resume) or another output folder")
    if resume and not (out / CHECKPOINT).exists():
        raise FileNotFoundError(f"checkpoint not found: {out / CHECKPOINT}")
    return Trainer(cfg, seed, out, demo_fn=demo_fn, progress=progress).run(resume=resume)
