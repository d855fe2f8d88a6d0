"""DDPG update throughput at the paper's go-to-ball sizes; prints JSON.

    python benchmarks/bench_ddpg.py [--batch 256] [--seconds 3] [--rounds 3] [--threads 1,2]

Measures updates/s (replay sampling included) of:

* ``ours``: :meth:`train.offpolicy.ddpg.DDPG.update` (fused Adam, actor loss back-propagated
  into the actor only, foreach soft update, no per-update ``.item()``);
* ``naive``: the same maths written the common way (default Adam, full
  ``backward()``, per-parameter soft-update loop, ``.item()`` every update),
  to show what the choices buy;
* ``ours_bf16`` (with ``--bf16``): ours with bfloat16 autocast;
* ``ours_compile`` and ``ours_bf16_compile`` (with ``--compile``): the same with the
  loss functions compiled by ``torch.compile`` (compilation time reported apart);
* ``sb3``: Stable-Baselines3 ``DDPG.train(gradient_steps, batch_size)`` when
  ``stable_baselines3`` is importable (not a dependency). SB3's MLP has no
  layer norm, so it does a little less work per update.

Actor and critic are 300-400 (obs 14, action 3) with layer norm, as in Table 1.
Each configuration runs ``rounds`` x ``seconds`` interleaved with the others;
the median round is reported (the machine may be shared: see ``load_avg``).
"""

from __future__ import annotations

import argparse
import copy
import json
import os
import platform
import statistics
import sys
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np
import torch
import torch.nn.functional as F

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from ssl_marl.skills.networks import Actor, Critic  # noqa: E402
from train.offpolicy.agent import adam  # noqa: E402
from train.offpolicy.config import DDPGConfig, TrainConfig  # noqa: E402
from train.offpolicy.ddpg import DDPG  # noqa: E402
from train.offpolicy.replay import ReplayBuffer  # noqa: E402

OBS_DIM, ACT_DIM, HIDDEN, N_FILL = 14, 3, (300, 400), 100_000


def filled_buffer(batch: int) -> ReplayBuffer:
    rng = np.random.default_rng(0)
    buf = ReplayBuffer(N_FILL, OBS_DIM, ACT_DIM, batch, rng)
    buf.add(rng.standard_normal((N_FILL, OBS_DIM)), rng.uniform(-1, 1, (N_FILL, ACT_DIM)), rng.standard_normal(N_FILL),
            rng.standard_normal((N_FILL, OBS_DIM)), rng.random(N_FILL) < 0.01)
    return buf


def ours(batch: int, bf16: bool = False, compiled: bool = False, torch_adam: bool = False) -> Callable[[], None]:
    torch.manual_seed(0)
    cfg = DDPGConfig(actor_hidden=HIDDEN, critic_hidden=HIDDEN)
    agent, buf = DDPG(OBS_DIM, ACT_DIM, cfg, autocast_bf16=bf16, compile=compiled), filled_buffer(batch)
    log_interval = TrainConfig().log_interval
    if torch_adam:  # the optimiser step of torch.optim.Adam(fused=True).step() instead of the lean Adam
        agent.actor_opt = adam(agent.actor.parameters(), cfg.actor_lr)
        agent.critic_opt = adam(agent.critic.parameters(), cfg.critic_lr, cfg.critic_weight_decay)

    def step() -> None:
        agent.update(buf.sample())
        if agent.updates % log_interval == 0:
            agent.read_losses()
    return step


def naive(batch: int) -> Callable[[], None]:
    torch.manual_seed(0)
    actor, critic = Actor(OBS_DIM, ACT_DIM, HIDDEN), Critic(OBS_DIM, ACT_DIM, HIDDEN)
    actor_t, critic_t = copy.deepcopy(actor), copy.deepcopy(critic)
    a_opt, c_opt = torch.optim.Adam(actor.parameters(), 1e-4), torch.optim.Adam(critic.parameters(), 1e-3)
    buf = filled_buffer(batch)

    def step() -> None:
        b = buf.sample()
        with torch.no_grad():
            y = b.rew + 0.99 * (1 - b.terminated) * critic_t(b.next_obs, actor_t(b.next_obs)).squeeze(-1)
        c_loss = F.mse_loss(critic(b.obs, b.act).squeeze(-1), y)
        c_opt.zero_grad()
        c_loss.backward()
        c_opt.step()
        a_loss = -critic(b.obs, actor(b.obs)).mean()
        a_opt.zero_grad()
        a_loss.backward()
        a_opt.step()
        for net, tgt in ((actor, actor_t), (critic, critic_t)):
            for p, tp in zip(net.parameters(), tgt.parameters()):
                tp.data.mul_(0.995).add_(0.005 * p.data)
        c_loss.item(), a_loss.item()
    return step


def sb3(batch: int) -> Callable[[], None] | None:
    try:
        import gymnasium as gym
        from stable_baselines3 import DDPG as SB3DDPG
        from stable_baselines3.common.logger import configure
    except Exception:
        return None
    env = gym.make("train.offpolicy.toy:train_toy/MoveToTarget-v0")  # any env; spaces replaced below
    env.observation_space = gym.spaces.Box(-np.inf, np.inf, (OBS_DIM,), np.float32)
    env.action_space = gym.spaces.Box(-1.0, 1.0, (ACT_DIM,), np.float32)
    model = SB3DDPG("MlpPolicy", env, buffer_size=N_FILL, learning_starts=0, batch_size=batch, device="cpu", seed=0,
                    policy_kwargs=dict(net_arch=dict(pi=list(HIDDEN), qf=list(HIDDEN))))
    model.set_logger(configure(None, []))
    rb, rng = model.replay_buffer, np.random.default_rng(0)
    rb.observations[:] = rng.standard_normal(rb.observations.shape)
    rb.next_observations[:] = rng.standard_normal(rb.next_observations.shape)
    rb.actions[:] = rng.uniform(-1, 1, rb.actions.shape)
    rb.rewards[:] = rng.standard_normal(rb.rewards.shape)
    rb.dones[:] = rng.random(rb.dones.shape) < 0.01
    rb.full, rb.pos = True, 0

    def step() -> None:
        model.train(gradient_steps=10, batch_size=batch)
    step.per_call = 10  # type: ignore[attr-defined]
    return step


def measure(fns: dict[str, Callable[[], None]], threads: int, seconds: float, rounds: int,
            clock: str = "wall") -> dict[str, float]:
    """Median updates/s per configuration over ``rounds`` interleaved rounds of ``seconds`` each;
    ``clock`` "cpu" divides by this process's CPU time instead of wall time (updates per CPU
    second: on a shared machine, close to the idle machine's 1-thread rate)."""
    torch.set_num_threads(threads)
    for fn in fns.values():  # warm-up
        for _ in range(5):
            fn()
    timer = time.process_time if clock == "cpu" else time.perf_counter
    rates: dict[str, list[float]] = {k: [] for k in fns}
    for _ in range(rounds):
        for name, fn in fns.items():
            per_call = getattr(fn, "per_call", 1)
            n, t0 = 0, timer()
            while timer() - t0 < seconds:
                fn()
                n += per_call
            rates[name].append(n / (timer() - t0))
    return {k: round(statistics.median(v), 1) for k, v in rates.items()}


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--batch", type=int, default=256)
    p.add_argument("--seconds", type=float, default=3.0, help="per round and configuration")
    p.add_argument("--rounds", type=int, default=3)
    p.add_argument("--threads", default="1,2", help="comma-separated torch thread counts")
    p.add_argument("--bf16", action="store_true", help="also measure ours with bfloat16 autocast")
    p.add_argument("--compile", action="store_true",
                   help="also measure ours with torch.compile (fp32 and, with --bf16, bf16)")
    p.add_argument("--no-naive", action="store_true")
    p.add_argument("--clock", choices=("wall", "cpu"), default="wall",
                   help="rate per wall second (default) or per CPU second of this process (shared machines)")
    p.add_argument("--torch-adam", action="store_true",
                   help="also measure ours with torch.optim.Adam(fused=True).step() instead of the lean Adam step")
    args = p.parse_args(argv)

    fns: dict[str, Callable[[], None]] = {"ours": ours(args.batch)}
    if args.torch_adam:
        fns["ours_torch_adam"] = ours(args.batch, torch_adam=True)
    if args.bf16:
        fns["ours_bf16"] = ours(args.batch, bf16=True)
    compile_s: dict[str, float] = {}
    if args.compile:
        variants = [("ours_compile", False)] + ([("ours_bf16_compile", True)] if args.bf16 else [])
        for name, bf16 in variants:
            t0 = time.perf_counter()
            fns[name] = ours(args.batch, bf16=bf16, compiled=True)
            fns[name]()  # first call compiles
            compile_s[name] = round(time.perf_counter() - t0, 1)
    if not args.no_naive:
        fns["naive"] = naive(args.batch)
    sb = sb3(args.batch)
    if sb is not None:
        fns["sb3"] = sb
    results = {f"threads_{t}": measure(fns, int(t), args.seconds, args.rounds, args.clock)
               for t in args.threads.split(",")}
    cpu = next((ln.split(":", 1)[1].strip() for ln in Path("/proc/cpuinfo").read_text().splitlines()
                if ln.startswith("model name")), platform.processor()) if Path("/proc/cpuinfo").exists() else ""
    out = {
        "benchmark": "DDPG updates/s (actor+critic step incl. replay sampling)",
        "sizes": {"obs": OBS_DIM, "act": ACT_DIM, "actor": list(HIDDEN), "critic": list(HIDDEN), "batch": args.batch},
        "updates_per_s": results,
        "clock": args.clock,
        "compile_seconds": compile_s,
        "notes": ["ours and naive use layer norm after each hidden layer (paper)",
                  "sb3: stable_baselines3 DDPG has no layer norm" if sb is not None else
                  "sb3: stable_baselines3 not importable, not measured"],
        "torch": torch.__version__, "cpu": cpu, "cores": os.cpu_count(),
        "load_avg": [round(x, 2) for x in os.getloadavg()],
    }
    print(json.dumps(out, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
