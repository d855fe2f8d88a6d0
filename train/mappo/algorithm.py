"""MAPPO: PPO with one actor shared by all teammates and a centralised critic on the global state
(Yu et al. 2022; docs/references.md, "Keepaway and MAPPO").

On-policy, so it does not implement the off-policy :class:`~train.offpolicy.agent.Agent`
interface (no replay batches); :mod:`train.mappo.loop` drives it. Everything the update needs is here:

* :class:`ActorNet` -- the shared policy: obs (+ agent one-hot, optional) -> option logits
  (discrete; illegal options get ``-inf`` logits from the action mask) or a Gaussian mean
  with a state-independent log-std (continuous; actions sampled unclipped, the env clips).
* :class:`CriticNet` -- V(state, agent one-hot) on the env's ``state()`` (centralised critic).
* :class:`ValueNorm` -- running mean/std of the value targets; the critic predicts
  normalised values (the MAPPO paper's "value normalisation").
* :func:`smdp_discount` and :func:`gae` -- the semi-Markov advantage (below).
* :class:`MAPPO` -- the networks, one Adam per network, and :meth:`MAPPO.update`
  (clipped surrogate, value loss on normalised targets, entropy bonus, grad clipping).

SMDP return (variable-duration decisions). A training sample k of agent i spans from its
decision k to its next decision (or the episode's end, or the rollout's end). Over that
interval the env reported rewards r_1..r_m over steps of elapsed_s e_1..e_m; the trainer
stores ``R_k = r_1 + ... + r_m`` (undiscounted inside the interval, as the env reports it)
and ``d_k = gamma ** ((e_1 + ... + e_m) / tau_s)``. Then, with V the critic's (de-normalised) value::

    delta_k = R_k + d_k * (1 - terminal_k) * V(s_{k+1}) - V(s_k)
    A_k     = delta_k + d_k * lam * A_{k+1}      (A_{k+1} := 0 where the sample's chain ends)
    G_k     = A_k + V(s_k)                       (the critic's target)

``s_{k+1}`` is the state at the agent's next decision; at a time-limit truncation or a
rollout cut it is the state there (bootstrapped, the chain ends); at a termination the
value is 0. ``lam`` is applied per decision, ``gamma`` per ``tau_s`` seconds of simulated time.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np
import torch
from torch import nn

from train.offpolicy.agent import adam

__all__ = ["ActorNet", "CriticNet", "MAPPO", "MAPPOConfig", "ValueNorm", "gae", "smdp_discount"]


@dataclass(frozen=True)
class MAPPOConfig:
    """MAPPO hyperparameters (times in simulated seconds)."""

    hidden: tuple[int, ...] = (128, 128)   # actor and critic hidden layers (tanh)
    lr: float = 5e-4                       # Adam step size, actor and critic
    gamma: float = 0.99                    # discount per tau_s seconds
    tau_s: float = 0.1                     # time unit of gamma: discount gamma ** (elapsed_s / tau_s)
    lam: float = 0.95                      # GAE lambda, per decision
    clip: float = 0.2                      # PPO ratio clip
    epochs: int = 5                        # passes over a rollout
    minibatches: int = 4                   # minibatches per pass
    ent_coef: float = 0.01                 # entropy bonus weight
    vf_coef: float = 1.0                   # value-loss weight (critic has its own optimiser; scales its loss)
    max_grad_norm: float = 0.5             # per-network gradient-norm clip
    value_norm: bool = True                # running mean/std normalisation of value targets
    agent_onehot: bool = False             # append the agent's one-hot to the actor input (critic always gets it)
    continuous: bool = False               # Gaussian head for Box action spaces
    log_std_init: float = -0.5             # initial log-std of the Gaussian head
    target_kl: float | None = None         # stop the epochs early when the approx. KL exceeds it

    def to_dict(self) -> dict[str, Any]:
        d = asdict(self)
        d["hidden"] = list(self.hidden)
        return d

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> MAPPOConfig:
        d = dict(d)
        if "hidden" in d:
            d["hidden"] = tuple(int(h) for h in d["hidden"])
        return cls(**d)


def smdp_discount(elapsed_s: np.ndarray | float, gamma: float, tau_s: float) -> np.ndarray:
    """``gamma ** (elapsed_s / tau_s)``: the discount over an interval of ``elapsed_s`` simulated seconds."""
    if tau_s <= 0:
        raise ValueError(f"tau_s must be positive, got {tau_s}")
    return np.power(gamma, np.asarray(elapsed_s, np.float64) / tau_s)


def gae(rewards: np.ndarray, values: np.ndarray, next_values: np.ndarray, discounts: np.ndarray,
        terminal: np.ndarray, next_index: np.ndarray, lam: float) -> tuple[np.ndarray, np.ndarray]:
    """SMDP GAE over samples stored in creation order (see the module docstring).

    ``next_index[k]``: index of the same agent's next sample in the same episode (always > k),
    or -1 where the chain ends. Returns (advantages, returns), float32, shape (n,)."""
    n = len(rewards)
    adv = np.zeros(n, np.float64)
    delta = rewards + discounts * (1.0 - terminal) * next_values - values
    for k in range(n - 1, -1, -1):
        j = next_index[k]
        adv[k] = delta[k] + (discounts[k] * lam * adv[j] if j >= 0 else 0.0)
    return adv.astype(np.float32), (adv + values).astype(np.float32)


class ValueNorm(nn.Module):
    """Running mean and variance of value targets (Chan et al. parallel update, float64 buffers)."""

    def __init__(self, eps: float = 1e-5) -> None:
        super().__init__()
        self.eps = eps
        self.register_buffer("mean", torch.zeros((), dtype=torch.float64))
        self.register_buffer("var", torch.ones((), dtype=torch.float64))
        self.register_buffer("count", torch.zeros((), dtype=torch.float64))

    @torch.no_grad()
    def update(self, x: torch.Tensor) -> None:
        x = x.detach().double().flatten()
        n, m, v = x.numel(), x.mean(), x.var(unbiased=False)
        tot = self.count + n
        d = m - self.mean
        self.mean += d * n / tot
        self.var.copy_((self.var * self.count + v * n + d * d * self.count * n / tot) / tot)
        self.count.copy_(tot)

    def normalize(self, x: torch.Tensor) -> torch.Tensor:
        return ((x - self.mean) / torch.sqrt(self.var + self.eps)).to(x.dtype)

    def denormalize(self, x: torch.Tensor) -> torch.Tensor:
        return (x * torch.sqrt(self.var + self.eps) + self.mean).to(x.dtype)


def _mlp(in_dim: int, hidden: Sequence[int], out_dim: int, out_gain: float) -> nn.Sequential:
    layers: list[nn.Module] = []
    for h in hidden:
        lin = nn.Linear(in_dim, h)
        nn.init.orthogonal_(lin.weight, np.sqrt(2))
        nn.init.zeros_(lin.bias)
        layers += [lin, nn.Tanh()]
        in_dim = h
    out = nn.Linear(in_dim, out_dim)
    nn.init.orthogonal_(out.weight, out_gain)
    nn.init.zeros_(out.bias)
    return nn.Sequential(*layers, out)


class ActorNet(nn.Module):
    """Shared policy: (..., in_dim) -> logits (..., n_out) [discrete] or mean (..., n_out) [continuous]."""

    def __init__(self, in_dim: int, n_out: int, hidden: Sequence[int], continuous: bool = False,
                 log_std_init: float = -0.5) -> None:
        super().__init__()
        self.in_dim, self.n_out, self.hidden, self.continuous = int(in_dim), int(n_out), tuple(hidden), continuous
        self.net = _mlp(self.in_dim, self.hidden, self.n_out, 0.01)
        self.log_std = nn.Parameter(torch.full((self.n_out,), float(log_std_init))) if continuous else None

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        return self.net(x)

    def dist(self, x: torch.Tensor, mask: torch.Tensor | None = None) -> torch.distributions.Distribution:
        out = self.net(x)
        if self.continuous:
            return torch.distributions.Normal(out, self.log_std.exp().expand_as(out))
        if mask is not None:
            out = out.masked_fill(mask == 0, float("-inf"))
        return torch.distributions.Categorical(logits=out)


class CriticNet(nn.Module):
    """Centralised critic: (..., state_dim + n_agents) -> normalised value (...,)."""

    def __init__(self, in_dim: int, hidden: Sequence[int]) -> None:
        super().__init__()
        self.net = _mlp(int(in_dim), tuple(hidden), 1, 1.0)

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        return self.net(x).squeeze(-1)


def _log_prob(d: torch.distributions.Distribution, act: torch.Tensor, continuous: bool) -> torch.Tensor:
    lp = d.log_prob(act)
    return lp.sum(-1) if continuous else lp


def _entropy(d: torch.distributions.Distribution, continuous: bool) -> torch.Tensor:
    e = d.entropy()
    return e.sum(-1) if continuous else e


@dataclass
class MAPPO:
    """The shared actor, the centralised critic, their optimisers and the value normaliser.

    ``obs_dim``/``state_dim``: the env's per-agent observation and global state sizes (already
    scaled by the loop); ``n_agents``: team size (one-hot width); ``n_out``: options or action dims."""

    obs_dim: int
    state_dim: int
    n_agents: int
    n_out: int
    cfg: MAPPOConfig = field(default_factory=MAPPOConfig)

    def __post_init__(self) -> None:
        c = self.cfg
        self.actor_in = self.obs_dim + (self.n_agents if c.agent_onehot else 0)
        self.actor = ActorNet(self.actor_in, self.n_out, c.hidden, c.continuous, c.log_std_init)
        self.critic = CriticNet(self.state_dim + self.n_agents, c.hidden)
        self.value_norm = ValueNorm()
        self.actor_opt = adam(self.actor.parameters(), c.lr)
        self.critic_opt = adam(self.critic.parameters(), c.lr)
        self.updates = 0

    # --- inputs -------------------------------------------------------------------------------
    def actor_input(self, obs: np.ndarray, agent_idx: np.ndarray) -> torch.Tensor:
        x = torch.as_tensor(np.asarray(obs, np.float32))
        if self.cfg.agent_onehot:
            x = torch.cat([x, torch.nn.functional.one_hot(torch.as_tensor(agent_idx), self.n_agents).float()], -1)
        return x

    def critic_input(self, state: np.ndarray, agent_idx: np.ndarray) -> torch.Tensor:
        s = torch.as_tensor(np.asarray(state, np.float32))
        return torch.cat([s, torch.nn.functional.one_hot(torch.as_tensor(agent_idx), self.n_agents).float()], -1)

    # --- acting -------------------------------------------------------------------------------
    @torch.no_grad()
    def act(self, obs: np.ndarray, agent_idx: np.ndarray, mask: np.ndarray | None,
            gen: torch.Generator | None = None, greedy: bool = False) -> tuple[np.ndarray, np.ndarray]:
        """Sampled (or greedy) actions and their log-probabilities for a batch of agents."""
        m = None if mask is None or self.cfg.continuous else torch.as_tensor(np.asarray(mask))
        d = self.actor.dist(self.actor_input(obs, agent_idx), m)
        if self.cfg.continuous:
            a = d.mean if greedy else d.mean + d.stddev * torch.randn(d.mean.shape, generator=gen)
        else:
            a = d.probs.argmax(-1) if greedy else torch.multinomial(d.probs, 1, generator=gen).squeeze(-1)
        return a.numpy(), _log_prob(d, a, self.cfg.continuous).numpy()

    @torch.no_grad()
    def value(self, state: np.ndarray, agent_idx: np.ndarray) -> np.ndarray:
        """De-normalised V(state) for each (state, agent) row."""
        v = self.critic(self.critic_input(state, agent_idx))
        return (self.value_norm.denormalize(v) if self.cfg.value_norm else v).numpy().astype(np.float64)

    # --- learning -----------------------------------------------------------------------------
    def update(self, batch: dict[str, np.ndarray], gen: torch.Generator | None = None,
               train_actor: bool = True) -> dict[str, float]:
        """PPO epochs over one rollout's samples: ``obs, state, agent, act, logp, mask, adv, ret``.
        ``train_actor=False``: only the critic learns (a warm-started actor's warm-up)."""
        c = self.cfg
        t = {k: torch.as_tensor(v) for k, v in batch.items()}
        x_actor, x_critic = self.actor_input(batch["obs"], batch["agent"]), self.critic_input(batch["state"], batch["agent"])
        ret = t["ret"].float()
        if c.value_norm:
            self.value_norm.update(ret)
            ret = self.value_norm.normalize(ret)
        n = len(ret)
        mb = max(1, n // c.minibatches)
        stats: dict[str, list[float]] = {k: [] for k in ("policy", "value", "entropy", "approx_kl", "clipfrac")}
        for _ in range(c.epochs):
            perm = torch.randperm(n, generator=gen)
            kls = []
            for start in range(0, n, mb):
                i = perm[start:start + mb]
                adv = t["adv"][i].float()
                adv = (adv - adv.mean()) / (adv.std(unbiased=False) + 1e-8) if len(i) > 1 else adv
                d = self.actor.dist(x_actor[i], None if c.continuous else t["mask"][i])
                logp = _log_prob(d, t["act"][i], c.continuous)
                log_ratio = logp - t["logp"][i].float()
                ratio = log_ratio.exp()
                pg = -torch.min(ratio * adv, ratio.clamp(1 - c.clip, 1 + c.clip) * adv).mean()
                ent = _entropy(d, c.continuous).mean()
                if train_actor:
                    self.actor_opt.zero_grad(set_to_none=True)
                    (pg - c.ent_coef * ent).backward()
                    nn.utils.clip_grad_norm_(self.actor.parameters(), c.max_grad_norm)
                    self.actor_opt.step()
                v_loss = 0.5 * ((self.critic(x_critic[i]) - ret[i]) ** 2).mean()
                self.critic_opt.zero_grad(set_to_none=True)
                (c.vf_coef * v_loss).backward()
                nn.utils.clip_grad_norm_(self.critic.parameters(), c.max_grad_norm)
                self.critic_opt.step()
                with torch.no_grad():
                    kl = ((ratio - 1) - log_ratio).mean().item()
                    kls.append(kl)
                    for k, v in (("policy", pg.item()), ("value", v_loss.item()), ("entropy", ent.item()),
                                 ("approx_kl", kl), ("clipfrac", ((ratio - 1).abs() > c.clip).float().mean().item())):
                        stats[k].append(v)
            if c.target_kl is not None and np.mean(kls) > c.target_kl:
                break
        self.updates += 1
        return {k: float(np.mean(v)) for k, v in stats.items()}

    def state_dict(self) -> dict[str, Any]:
        return {"actor": self.actor.state_dict(), "critic": self.critic.state_dict(),
                "value_norm": self.value_norm.state_dict(), "actor_opt": self.actor_opt.state_dict(),
                "critic_opt": self.critic_opt.state_dict(), "updates": self.updates}

    def load_state_dict(self, state: dict[str, Any]) -> None:
        self.actor.load_state_dict(state["actor"])
        self.critic.load_state_dict(state["critic"])
        self.value_norm.load_state_dict(state["value_norm"])
        self.actor_opt.load_state_dict(state["actor_opt"])
        self.critic_opt.load_state_dict(state["critic_opt"])
        self.updates = int(state["updates"])
