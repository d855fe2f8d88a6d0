"""End-to-end DDPG training throughput on the real go-to-ball env; prints JSON.

    python benchmarks/bench_training.py [--steps 2000] [--warmup 1000] [--rounds 1] [--threads 1] [--seed 0]
                                        [--no-sb3] [--fast]

Three configurations on ``ssl_marl/GoToBall-v0`` (obs 14, action Box(-1, 1, (3,))),
one env, run one after the other in each round (``--rounds`` rounds; the median
over rounds of each figure is reported, with every round's samples/s):

* ``env_only``: the bare env (``gym.make``) stepped with uniform-random actions,
  no learning -- the ceiling that collection alone allows;
* ``ours``: :class:`train.offpolicy.loop.Trainer` (subclassed only to time it and to skip
  the end-of-run export/evaluation/plot) with the paper's go-to-ball config,
  demo_steps 0, no evaluations, no intermediate checkpoints, output in a temp dir;
* ``sb3``: ``stable_baselines3.DDPG("MlpPolicy", ...)`` with ``learn()`` (when
  ``stable_baselines3`` is importable; it is not a project dependency).

Both learners: actor and critic 300-400, batch 256, replay 100,000, one gradient
update per env step, ``--warmup`` env steps before the first update (ours:
``warmup_samples``, SB3: ``learning_starts``), OU noise theta 0.15, sigma 0.3,
dt 1. Ours has layer norm after each hidden layer (paper), SB3's MLP has none, so
SB3 does a little less work per update. Ours warms up with actor + noise, SB3
with uniform-random actions; the warm-up is not timed.

Timed window: from the end of the ``--warmup``-th env step (ours: after its
update step; SB3: the callback at ``num_timesteps == warmup``) to the end of the
``warmup + steps``-th env step (SB3: ``learn()`` returning), so ``steps`` env
steps and ``steps`` updates (ours does its first update on the warm-up's last
step, before the window; SB3 on the step after, inside it). Reported per
configuration: ``samples_per_s`` (env samples collected per wall second, updates
included), ``updates_per_s``, ``seconds`` and ``updates`` in the window. The
machine may be shared: see ``load_avg`` (before and after).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
import torch

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import ssl_marl  # noqa: E402,F401  (registers ssl_marl/GoToBall-v0)
from train.offpolicy.config import TrainConfig, config_from_dict, default_config  # noqa: E402
from train.offpolicy.loop import Trainer  # noqa: E402

ENV_ID = "ssl_marl/GoToBall-v0"
BUFFER = 100_000


def bench_config(steps: int, warmup: int, threads: int, fast: bool = False) -> TrainConfig:
    """The shipped go-to-ball config, without demos, evaluations or intermediate checkpoints
    (``fast``: with ``autocast_bf16`` and ``compile``)."""
    return config_from_dict({"autocast_bf16": fast, "compile": fast, "demo_steps": 0, "eval_interval": 0,
                             "eval_episodes": 1, "checkpoint_interval": 10**12, "buffer_size": BUFFER,
                             "warmup_samples": warmup, "total_samples": warmup + steps, "num_envs": 1,
                             "batch_size": 256, "updates_per_sample": 1.0, "torch_threads": threads},
                            base=default_config("go-to-ball"))


class TimedTrainer(Trainer):
    """Trainer that timestamps the window [warmup_samples, total_samples] and skips the final export."""

    t0: float | None = None
    t1: float | None = None
    u0 = u1 = 0

    def train_step(self, n_new: int) -> None:
        super().train_step(n_new)
        if self.t0 is None and self.samples >= self.cfg.warmup_samples:
            self.t0, self.s0, self.u0 = time.perf_counter(), self.samples, self.agent.updates
        if self.t1 is None and self.samples >= self.cfg.total_samples:
            self.t1, self.s1, self.u1 = time.perf_counter(), self.samples, self.agent.updates

    def finish(self) -> dict[str, Any]:  # no actor export, final evaluation or plot
        self.eval_env.close()
        return {}


def _rates(samples: int, updates: int, seconds: float) -> dict[str, float]:
    return {"samples_per_s": round(samples / seconds, 1), "updates_per_s": round(updates / seconds, 1),
            "seconds": round(seconds, 3), "samples": samples, "updates": updates}


def run_ours(steps: int, warmup: int, threads: int, seed: int, fast: bool = False) -> dict[str, float]:
    cfg = bench_config(steps, warmup, threads, fast)
    with tempfile.TemporaryDirectory(prefix="bench_training_") as out:
        tr = TimedTrainer(cfg, seed, out, progress=False)
        tr.run()
    assert tr.t0 is not None and tr.t1 is not None
    return _rates(tr.s1 - tr.s0, tr.u1 - tr.u0, tr.t1 - tr.t0)


def sb3_available() -> bool:
    try:
        import stable_baselines3  # noqa: F401
    except ImportError:
        return False
    return True


def run_sb3(steps: int, warmup: int, threads: int, seed: int) -> dict[str, float]:
    from stable_baselines3 import DDPG as SB3DDPG
    from stable_baselines3.common.callbacks import BaseCallback
    from stable_baselines3.common.noise import OrnsteinUhlenbeckActionNoise

    torch.set_num_threads(threads)
    cfg = bench_config(steps, warmup, threads)

    class Mark(BaseCallback):
        t0: float | None = None
        u0 = 0

        def _on_step(self) -> bool:
            if self.t0 is None and self.num_timesteps >= warmup:
                self.t0, self.s0, self.u0 = time.perf_counter(), self.num_timesteps, self.model._n_updates
            return True

    env = gym.make(ENV_ID)
    ou, hp = cfg.exploration, cfg.ddpg
    noise = OrnsteinUhlenbeckActionNoise(mean=np.full(3, ou.ou_mu), sigma=np.full(3, ou.ou_sigma),
                                         theta=ou.ou_theta, dt=ou.ou_dt)
    model = SB3DDPG("MlpPolicy", env, learning_rate=hp.critic_lr, buffer_size=BUFFER, learning_starts=warmup,
                    batch_size=256, tau=hp.tau, gamma=hp.gamma, train_freq=1, gradient_steps=1,
                    policy_kwargs={"net_arch": {"pi": list(hp.actor_hidden), "qf": list(hp.critic_hidden)}},
                    action_noise=noise, device="cpu", seed=seed, verbose=0)
    mark = Mark()
    model.learn(total_timesteps=warmup + steps, callback=mark)
    t1 = time.perf_counter()
    s1, u1 = model.num_timesteps, model._n_updates
    env.close()
    assert mark.t0 is not None
    return _rates(s1 - mark.s0, u1 - mark.u0, t1 - mark.t0)


def run_env_only(steps: int, warmup: int, threads: int, seed: int) -> dict[str, float]:
    env = gym.make(ENV_ID)
    rng = np.random.default_rng(seed)
    env.reset(seed=seed)
    for i in range(warmup + steps):
        if i == warmup:
            t0 = time.perf_counter()
        _, _, term, trunc, _ = env.step(rng.uniform(-1.0, 1.0, 3).astype(np.float32))
        if term or trunc:
            env.reset()
    seconds = time.perf_counter() - t0
    env.close()
    return _rates(steps, 0, seconds)


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--steps", type=int, default=2000, help="timed env steps after the warm-up")
    p.add_argument("--warmup", type=int, default=1000, help="env steps before the first update (not timed)")
    p.add_argument("--rounds", type=int, default=1, help="rounds of all configurations; the median is reported")
    p.add_argument("--threads", type=int, default=1, help="torch.set_num_threads")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--no-sb3", action="store_true", help="skip stable-baselines3 even when installed")
    p.add_argument("--fast", action="store_true",
                   help="also run ours with autocast_bf16 + compile (compilation happens in the untimed warm-up)")
    args = p.parse_args(argv)
    if args.steps <= 0 or args.warmup < 256 or args.rounds <= 0 or args.threads <= 0:
        p.error("need --steps > 0, --warmup >= 256 (batch size), --rounds > 0, --threads > 0")

    torch.set_num_threads(args.threads)
    runners: dict[str, Any] = {"env_only": run_env_only, "ours": run_ours}
    if args.fast:
        runners["ours_fast"] = lambda *a: run_ours(*a, fast=True)
    have_sb3 = not args.no_sb3 and sb3_available()
    if have_sb3:
        runners["sb3"] = run_sb3
    load_before = [round(x, 2) for x in os.getloadavg()]
    per_round: dict[str, list[dict[str, float]]] = {k: [] for k in runners}
    t_start = time.perf_counter()
    for r in range(args.rounds):
        for name, fn in runners.items():
            per_round[name].append(fn(args.steps, args.warmup, args.threads, args.seed + r))

    def summary(rows: list[dict[str, float]]) -> dict[str, Any]:
        med = {k: round(statistics.median(d[k] for d in rows), 3 if k == "seconds" else 1)
               for k in ("samples_per_s", "updates_per_s", "seconds")}
        return {**med, "samples": rows[0]["samples"], "updates": rows[0]["updates"],
                "samples_per_s_rounds": [d["samples_per_s"] for d in rows]}

    results: dict[str, Any] = {k: summary(v) for k, v in per_round.items()}
    if "sb3" in results:
        results["ours_over_sb3_samples_per_s"] = round(
            results["ours"]["samples_per_s"] / results["sb3"]["samples_per_s"], 2)
        if "ours_fast" in results:
            results["ours_fast_over_sb3_samples_per_s"] = round(
                results["ours_fast"]["samples_per_s"] / results["sb3"]["samples_per_s"], 2)
    cpu = next((ln.split(":", 1)[1].strip() for ln in Path("/proc/cpuinfo").read_text().splitlines()
                if ln.startswith("model name")), platform.processor()) if Path("/proc/cpuinfo").exists() else ""
    versions = {"torch": torch.__version__, "gymnasium": gym.__version__, "numpy": np.__version__}
    if have_sb3:
        import stable_baselines3
        versions["stable_baselines3"] = stable_baselines3.__version__
    out = {
        "benchmark": "end-to-end DDPG training throughput (env samples/s with 1 update per sample)",
        "env": ENV_ID,
        "setup": {"num_envs": 1, "warmup_steps_untimed": args.warmup, "timed_steps": args.steps,
                  "batch": 256, "updates_per_step": 1, "replay": BUFFER, "actor": [300, 400], "critic": [300, 400],
                  "layer_norm": {"ours": True, "sb3": False},
                  "threads": args.threads, "rounds": args.rounds, "seed": args.seed},
        "results": results,
        "notes": [
            ("samples_per_s: env steps in the timed window per wall second, updates included; "
             "samples_per_s, updates_per_s, seconds: medians over rounds"),
            "env_only: bare gym.make env with uniform-random actions, no learning (reference ceiling)",
            ("ours: train.offpolicy.loop.Trainer (progress.csv logging included; demos, evaluations, checkpoints off), "
             "layer norm after each hidden layer (paper)"),
            "ours_fast (--fast): ours with autocast_bf16 and compile (bf16 matrix products, compiled losses)",
            ("sb3: stable_baselines3 DDPG learn(), MlpPolicy WITHOUT layer norm (a little less work per update), "
             "single learning rate, Monitor + DummyVecEnv wrappers; not a project dependency")
            if have_sb3 else "sb3: not measured (stable_baselines3 not importable or --no-sb3)",
        ],
        "versions": versions, "cpu": cpu, "cores": os.cpu_count(),
        "load_avg_before": load_before, "load_avg_after": [round(x, 2) for x in os.getloadavg()],
        "total_wall_s": round(time.perf_counter() - t_start, 1),
    }
    print(json.dumps(out, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
