"""The training loop: demo burn-in, collection with OU noise, updates, logs, checkpoints, export.

Data handling (Gymnasium 1.x vector envs, ``AutoresetMode.NEXT_STEP``):

* The step on which a sub-env ends returns the true final observation; it is
  stored as ``next_obs`` with ``terminated`` (no bootstrap) -- truncations
  (time limits) are stored with ``terminated = 0`` and so bootstrap.
* The following step of that sub-env is a reset step that ignores the action;
  its transition is never stored (tracked by ``self.autoreset``).

Resume: every ``checkpoint_interval`` env samples the loop cuts all running
episodes (re-seeds and resets the envs; cut episodes are not logged, their
stored transitions stay valid) and saves everything else. A run resumed from a
checkpoint therefore continues exactly as the uninterrupted run does, given
deterministic envs and the same thread count.

Output folder: ``progress.csv`` (one row per episode, demo episodes flagged
``phase=demo``), ``eval.csv``, ``checkpoint.pt`` + ``replay-*.npz``,
``actors/actor-<samples>.pt`` (the actor at each checkpoint, for model selection),
``config.json``, ``actor.pt`` (export), ``eval.json`` (final evaluation),
``learning_curve.png``, and ``tb/`` when TensorBoard is installed.
"""

from __future__ import annotations

import csv
import importlib
import json
import os
import random
import tempfile
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
from ssl_marl.skills.checkpoint import atomic_torch_save, safe_torch_load, save_actor

from .config import DDPGConfig, config_from_dict
from .ddpg import DDPG
from .evaluate import ActionScaler, evaluate_actor, make_env, run_episodes
from .noise import OUNoise
from .replay import ReplayBuffer

CHECKPOINT = "checkpoint.pt"
DemoFn = Callable[..., Iterable[Any]]
BASE_FIELDS = ["phase", "samples", "transitions", "episode", "return", "length", "success", "critic_loss",
               "actor_loss", "updates", "wall_time"]
EVAL_FIELDS = ["samples", "transitions", "updates", "mean_return", "std_return", "mean_length", "success_rate",
               "wall_time"]


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


class CsvLog:
    """Append-only CSV, flushed per row. Columns fixed by the existing header or the first row."""

    def __init__(self, path: Path, fields: list[str] | None = None) -> None:
        self.path, self.fields, self.rows, self._initial_fields = path, fields, 0, fields
        if path.exists() and path.stat().st_size > 0:
            with path.open(newline="") as f:
                reader = csv.reader(f)
                self.fields = next(reader)
                self.rows = sum(1 for _ in reader)
        self._f = None

    def write(self, row: Mapping[str, Any]) -> None:
        if self._f is None:
            new = self.rows == 0
            if self.fields is None:
                self.fields = list(row)
            self._f = self.path.open("a" if not new else "w", newline="")
            self._w = csv.DictWriter(self._f, self.fields, extrasaction="ignore")
            if new:
                self._w.writeheader()
        self._w.writerow({k: ("" if v is None else v) for k, v in row.items()})
        self._f.flush()
        self.rows += 1

    def truncate(self, rows: int) -> None:
        """Keep the header and the first ``rows`` rows (drop what was logged after a checkpoint)."""
        self.close()
        if not self.path.exists():
            return
        lines = self.path.read_text().splitlines(keepends=True)
        _atomic_write_text(self.path, "".join(lines[: rows + 1]))
        self.rows = min(rows, max(len(lines) - 1, 0))

    def clear(self) -> None:
        """Start the file afresh (a new run in a folder left by a run that never checkpointed)."""
        self.close()
        self.path.unlink(missing_ok=True)
        self.fields, self.rows = self._initial_fields, 0

    def close(self) -> None:
        if self._f is not None:
            self._f.close()
            self._f = None


def _atomic_write_text(path: Path, text: str) -> None:
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    with os.fdopen(fd, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def _tensorboard(out: Path) -> Any:
    try:
        from torch.utils.tensorboard import SummaryWriter
    except Exception:  # tensorboard not installed: optional
        return None
    return SummaryWriter(str(out / "tb"))


class Trainer:
    """One DDPG run writing to ``out``; :meth:`run` trains to ``cfg.total_samples`` env samples."""

    def __init__(self, cfg: DDPGConfig, seed: int, out: str | Path, demo_fn: DemoFn | None = None,
                 progress: bool = True) -> None:
        self.cfg, self.seed, self.out, self.progress = cfg, int(seed), Path(out), progress
        self.out.mkdir(parents=True, exist_ok=True)
        if cfg.torch_threads > 0:
            torch.set_num_threads(cfg.torch_threads)
        random.seed(seed)
        torch.manual_seed(seed)
        ss = np.random.SeedSequence(seed)
        noise_rng, replay_rng, self.rng = (np.random.default_rng(s) for s in ss.spawn(3))

        self.eval_env = make_env(cfg.env_id, cfg.env_kwargs, cfg.max_episode_steps)
        obs_space, act_space = self.eval_env.observation_space, self.eval_env.action_space
        if not isinstance(obs_space, gym.spaces.Box) or len(obs_space.shape) != 1:
            raise ValueError(f"DDPG needs a flat Box observation space, got {obs_space}")
        self.obs_dim, self.act_dim = obs_space.shape[0], int(np.prod(act_space.shape))
        self.scaler = ActionScaler(act_space)
        self.obs_spec = spec_version(self.eval_env, cfg.env_id)
        self.demo_fn = demo_fn if demo_fn is not None else (resolve_callable(cfg.demo_fn) if cfg.demo_fn else None)

        self.agent = DDPG(self.obs_dim, self.act_dim, cfg)
        self.buffer = ReplayBuffer(cfg.buffer_size, self.obs_dim, self.act_dim, cfg.batch_size, replay_rng)
        sigma = cfg.ou_sigma if cfg.ou_sigma_per_dim is None else cfg.ou_sigma_per_dim
        if cfg.ou_sigma_per_dim is not None and len(cfg.ou_sigma_per_dim) != self.act_dim:
            raise ValueError(f"ou_sigma_per_dim has {len(cfg.ou_sigma_per_dim)} values, the action has {self.act_dim}")
        self.noise = OUNoise(cfg.num_envs, self.act_dim, cfg.ou_theta, cfg.ou_mu, sigma, cfg.ou_dt, noise_rng)
        env_fns = [lambda: make_env(cfg.env_id, cfg.env_kwargs, cfg.max_episode_steps)] * cfg.num_envs
        if cfg.vector_mode == "batched":  # the skill tasks' worlds stepped together (ssl_marl.skills.vector)
            from ssl_marl.skills.vector import make_skill_vector_env

            if cfg.max_episode_steps:
                raise ValueError("vector_mode 'batched' does not take max_episode_steps (the tasks time out themselves)")
            self.envs = make_skill_vector_env(cfg.env_id, cfg.num_envs, cfg.env_kwargs)
        else:
            vec_cls = SyncVectorEnv if cfg.vector_mode == "sync" else AsyncVectorEnv
            self.envs = vec_cls(env_fns, autoreset_mode=AutoresetMode.NEXT_STEP)

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
        self.losses: tuple[float, float] | None = None
        self.recent_returns: deque[float] = deque(maxlen=100)
        self.recent_success: deque[float] = deque(maxlen=100)

        self.log = CsvLog(self.out / "progress.csv")
        self.eval_log = CsvLog(self.out / "eval.csv", EVAL_FIELDS)
        self.tb = _tensorboard(self.out)
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
            self.log.fields = BASE_FIELDS + [f"r_{k}" for k in sorted(terms)]
        row = {"phase": phase, "samples": self.samples, "transitions": self.transitions, "episode": self.episodes,
               "return": round(ret, 6), "length": length, "success": None if success is None else int(bool(success)),
               "critic_loss": None if self.losses is None else round(self.losses[0], 6),
               "actor_loss": None if self.losses is None else round(self.losses[1], 6),
               "updates": self.agent.updates, "wall_time": round(self.wall_time(), 3)}
        row.update({f"r_{k}": round(float(v), 6) for k, v in terms.items()})
        self.log.write(row)
        if self.tb is not None:
            self.tb.add_scalar(f"{phase}/return", ret, self.transitions)
            self.tb.add_scalar(f"{phase}/length", length, self.transitions)
            if success is not None:
                self.tb.add_scalar(f"{phase}/success", float(bool(success)), self.transitions)

    # --- demonstration burn-in -------------------------------------------------
    def burn_in(self) -> None:
        """Fill the replay with ``cfg.demo_steps`` demonstration transitions (checked against the spaces)."""
        cfg = self.cfg
        if self.demo_done or self.demo_fn is None or cfg.demo_steps <= 0:
            self.demo_done = True
            return
        chunk: dict[str, list[Any]] = {k: [] for k in ("obs", "act", "rew", "next_obs", "term")}
        ret, length, terms = 0.0, 0, {}  # type: ignore[var-annotated]

        def flush() -> None:
            if chunk["obs"]:
                self.buffer.add(np.stack(chunk["obs"]), np.stack(chunk["act"]),
                                np.asarray(chunk["rew"]) * cfg.reward_scale, np.stack(chunk["next_obs"]),
                                np.asarray(chunk["term"]))
                for v in chunk.values():
                    v.clear()

        bar = tqdm(total=cfg.demo_steps, desc="demo burn-in", unit="step", disable=not self.progress,
                   dynamic_ncols=True)
        n = 0
        for n, tr in enumerate(self.demo_fn(n_steps=cfg.demo_steps, seed=self.seed, **cfg.env_kwargs), 1):
            obs, act, next_obs = self._check_demo(tr, n)
            chunk["obs"].append(obs)
            chunk["act"].append(self.scaler.from_env(act))
            chunk["rew"].append(float(tr.reward))
            chunk["next_obs"].append(next_obs)
            chunk["term"].append(float(bool(tr.terminated)))
            self.transitions += 1
            ret, length = ret + float(tr.reward), length + 1
            info = tr.info if isinstance(tr.info, Mapping) else {}
            for k, v in (info.get("reward_terms") or {}).items():
                terms[k] = terms.get(k, 0.0) + float(v)
            if tr.terminated or tr.truncated:
                self._log_episode("demo", ret, length, info.get("is_success"), terms)
                ret, length, terms = 0.0, 0, {}
            if len(chunk["obs"]) >= 4096:
                flush()
            bar.update(1)
            if n >= cfg.demo_steps:
                break
        flush()
        bar.close()
        if n < cfg.demo_steps:
            raise ValueError(f"demo source produced {n} transitions, expected {cfg.demo_steps}")
        self.demo_done = True

    def _check_demo(self, tr: Any, n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        obs = np.asarray(tr.obs, np.float32)
        next_obs = np.asarray(tr.next_obs, np.float32)
        act = np.asarray(tr.action, np.float64)
        problems = []
        if obs.shape != (self.obs_dim,) or next_obs.shape != (self.obs_dim,):
            problems.append(f"obs shapes {obs.shape}/{next_obs.shape} != ({self.obs_dim},)")
        if act.shape != (self.act_dim,):
            problems.append(f"action shape {act.shape} != ({self.act_dim},)")
        elif np.any(act < self.scaler.low - 1e-5) or np.any(act > self.scaler.high + 1e-5):
            problems.append(f"action {act} outside [{self.scaler.low}, {self.scaler.high}]")
        if not (np.all(np.isfinite(obs)) and np.all(np.isfinite(next_obs)) and np.isfinite(tr.reward)):
            problems.append("non-finite obs or reward")
        if problems:
            raise ValueError(f"demo transition {n} does not fit the env's spaces: " + "; ".join(problems))
        return obs, np.clip(act, self.scaler.low, self.scaler.high), next_obs

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
        self.buffer.add(self.obs[valid], act[valid], rew[valid] * cfg.reward_scale, next_obs[valid], term[valid])
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
        use_bc = cfg.bc_weight > 0 and n_demo > 0 and self.transitions <= self.buffer.capacity  # not overwritten yet
        while self.update_credit >= 1.0:
            demo = self.buffer.sample_rows(0, n_demo, cfg.bc_batch_size) if use_bc else None
            self.agent.update(self.buffer.sample(), demo)
            self.update_credit -= 1.0
            if self.agent.updates % cfg.log_interval == 0:
                self.losses = self.agent.read_losses()
                if self.tb is not None and self.losses is not None:
                    self.tb.add_scalar("loss/critic", self.losses[0], self.transitions)
                    self.tb.add_scalar("loss/actor", self.losses[1], self.transitions)

    def evaluate(self) -> dict[str, Any]:
        """Deterministic evaluation on the fixed eval start states (seed + 1000); logged to eval.csv."""
        res = run_episodes(self.eval_env, lambda o: self.agent.act(o[None])[0], self.cfg.eval_episodes,
                           self.seed + 1000)
        row = {"samples": self.samples, "transitions": self.transitions, "updates": self.agent.updates,
               "wall_time": round(self.wall_time(), 3), **{k: res[k] for k in EVAL_FIELDS if k in res}}
        self.eval_log.write(row)
        if self.tb is not None:
            self.tb.add_scalar("eval/return", res["mean_return"], self.transitions)
        return res

    # --- checkpoints ----------------------------------------------------------
    def save_checkpoint(self) -> Path:
        """Cut running episodes, then save everything needed to resume (atomically)."""
        while self.next_checkpoint <= self.samples:
            self.next_checkpoint += self.cfg.checkpoint_interval
        self.segment += 1
        self._reset_envs()
        replay_name = f"replay-{self.transitions:012d}.npz"
        self.buffer.save(self.out / replay_name)
        state = {
            "format": "ssl_marl.train_state", "version": 1, "config": self.cfg.to_dict(), "seed": self.seed,
            "agent": self.agent.state_dict(), "noise": self.noise.state_dict(),
            "rng": {"action": self.rng.bit_generator.state, "replay": self.buffer.rng.bit_generator.state,
                    "torch": torch.get_rng_state(), "python": random.getstate()},
            "counters": {"samples": self.samples, "transitions": self.transitions, "episodes": self.episodes,
                         "segment": self.segment, "env_seed": self.env_seed, "update_credit": self.update_credit,
                         "demo_done": self.demo_done, "next_eval": self.next_eval,
                         "next_checkpoint": self.next_checkpoint, "wall_time": self.wall_time()},
            "losses": list(self.losses) if self.losses is not None else None,
            "pending_losses": [self.agent._loss_sum.clone(), self.agent._loss_count],
            "recent": {"returns": list(self.recent_returns), "success": list(self.recent_success)},
            "csv_rows": {"progress": self.log.rows, "eval": self.eval_log.rows}, "replay_file": replay_name,
        }
        atomic_torch_save(state, self.out / CHECKPOINT)
        self.export_actor(self.out / "actors" / f"actor-{self.samples:09d}.pt")
        for old in self.out.glob("replay-*.npz"):
            if old.name != replay_name:
                old.unlink(missing_ok=True)
        return self.out / CHECKPOINT

    def load_checkpoint(self) -> None:
        state = safe_torch_load(self.out / CHECKPOINT, "ssl_marl training checkpoint")
        if not isinstance(state, dict) or state.get("format") != "ssl_marl.train_state":
            raise ValueError(f"{self.out / CHECKPOINT} is not a valid ssl_marl training checkpoint")
        if int(state["seed"]) != self.seed:
            raise ValueError(f"checkpoint was made with seed {state['seed']}, not {self.seed}")
        self.agent.load_state_dict(state["agent"])
        self.noise.load_state_dict(state["noise"])
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
        self.losses = tuple(state["losses"]) if state["losses"] is not None else None  # type: ignore[assignment]
        self.agent._loss_sum.copy_(state["pending_losses"][0])
        self.agent._loss_count = int(state["pending_losses"][1])
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
        _atomic_write_text(self.out / "config.json", json.dumps({**cfg.to_dict(), "seed": self.seed}, indent=2))
        if resume:
            self.load_checkpoint()
        else:
            self.log.clear()
            self.eval_log.clear()
            self._reset_envs()
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
            if self.tb is not None:
                self.tb.close()
        return self.finish()

    def postfix(self) -> dict[str, str]:
        d = {"ret": f"{np.mean(self.recent_returns):.1f}" if self.recent_returns else "-"}
        if self.recent_success:
            d["succ"] = f"{np.mean(self.recent_success):.2f}"
        if self.losses is not None:
            d["Lc"], d["La"] = f"{self.losses[0]:.3g}", f"{self.losses[1]:.3g}"
        d["upd"] = str(self.agent.updates)
        return d

    def export_actor(self, path: Path | None = None) -> Path:
        """Write the current actor with its metadata (``OUT/actor.pt`` by default)."""
        meta = {"skill": self.cfg.skill, "obs_spec": self.obs_spec, "env_id": self.cfg.env_id,
                "hyperparameters": self.cfg.to_dict(), "seed": self.seed, "samples": self.samples,
                "demo_transitions": self.transitions - self.samples, "updates": self.agent.updates,
                "action_low": self.scaler.low.tolist(), "action_high": self.scaler.high.tolist()}
        return save_actor(path or self.out / "actor.pt", self.agent.actor, meta)

    def finish(self) -> dict[str, Any]:
        """Export the actor, evaluate it (``eval.json``), draw the learning curve."""
        actor_path = self.export_actor()
        result = evaluate_actor(self.cfg.env_id, actor_path, self.cfg.eval_episodes, self.seed + 1000,
                                self.cfg.env_kwargs, self.cfg.max_episode_steps)
        result["wall_time_s"] = round(self.wall_time(), 1)
        _atomic_write_text(self.out / "eval.json", json.dumps(result, indent=2) + "\n")
        self.eval_env.close()
        try:
            from .plots import plot_run
            plot_run(self.out)
        except Exception as exc:  # a plotting problem must not lose a finished run
            print(f"warning: could not draw the learning curve: {exc}")
        return result


def load_run_config(out: str | Path) -> tuple[DDPGConfig, int]:
    """Config and seed stored in ``OUT/checkpoint.pt`` (for ``--resume``)."""
    state = safe_torch_load(Path(out) / CHECKPOINT, "ssl_marl training checkpoint")
    if not isinstance(state, dict) or "config" not in state:
        raise ValueError(f"{Path(out) / CHECKPOINT} is not a valid ssl_marl training checkpoint")
    return config_from_dict(state["config"]), int(state["seed"])


def train(cfg: DDPGConfig, seed: int, out: str | Path, resume: bool = False, demo_fn: DemoFn | None = None,
          progress: bool = True) -> dict[str, Any]:
    """Train a DDPG actor per ``cfg``; return the final evaluation (also in ``OUT/eval.json``)."""
    out = Path(out)
    if not resume and (out / CHECKPOINT).exists():
        raise FileExistsError(f"{out} already holds a run; pass resume=True (--resume) or another output folder")
    if resume and not (out / CHECKPOINT).exists():
        raise FileNotFoundError(f"checkpoint not found: {out / CHECKPOINT}")
    return Trainer(cfg, seed, out, demo_fn=demo_fn, progress=progress).run(resume=resume)
