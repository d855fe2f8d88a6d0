"""The DDPG learner: networks, optimisers and the update step (Lillicrap et al. 2016).

One update, all of it in :meth:`DDPG.update`::

    y        = r + gamma * (1 - terminated) * Q'(s', mu'(s'))      # no grad; truncations bootstrap
    L_critic = mean((Q(s, a) - y)^2)                               # Adam step on the critic
    L_actor  = -mean(Q(s, mu(s))) [+ w_bc * mean((mu(s_d) - a_d)^2)]  # Adam step on the actor only
    theta'   <- theta' + tau * (theta - theta')                    # Polyak, both targets

Speed (measured, see benchmarks/bench_ddpg.py and docs/BENCHMARKS.md): fused
Adam; the critic's parameters frozen during the actor step (no critic weight
gradients); one ``torch._foreach_lerp_`` for the soft update; losses accumulated
as tensors and read out every ``log_interval`` updates (no ``.item()`` sync per
update). Options: ``autocast_bf16`` runs the matrix products in bfloat16 (on CPUs
with AMX, e.g. Sapphire Rapids, a 256x300 @ 300x400 product is ~5x faster than in
float32); ``compile`` hands the two loss functions (forward and backward) to
``torch.compile``, which fuses the layer-norm / ReLU / cast kernels around them
(~30 s of compilation at start-up). Alone, ``compile`` does not pay in float32 here.
"""

from __future__ import annotations

import contextlib
import copy
from collections.abc import Sequence
from typing import Any

import numpy as np
import torch
import torch.nn.functional as F

from ssl_marl.skills.networks import Actor, Critic

from .config import DDPGConfig
from .replay import Batch


def td_target(rew: torch.Tensor, terminated: torch.Tensor, next_q: torch.Tensor, gamma: float) -> torch.Tensor:
    """Bellman target r + gamma (1 - terminated) Q'(s', mu'(s')). Truncated (time-limit) steps have
    terminated = 0 and so bootstrap; shapes (B,)."""
    return rew + gamma * (1.0 - terminated) * next_q


@torch.no_grad()
def soft_update(target: Sequence[torch.Tensor], online: Sequence[torch.Tensor], tau: float) -> None:
    """In place: target <- target + tau * (online - target), one fused foreach op."""
    torch._foreach_lerp_(list(target), list(online), tau)


def _adam(params: Any, lr: float, weight_decay: float = 0.0) -> torch.optim.Adam:
    try:  # fused CPU Adam (torch >= 2.4) measured ~7% faster than foreach here
        return torch.optim.Adam(params, lr=lr, weight_decay=weight_decay, fused=True)
    except (RuntimeError, TypeError):
        return torch.optim.Adam(params, lr=lr, weight_decay=weight_decay, foreach=True)


class DDPG:
    """Actor, critic, their targets and optimisers; ``update(batch)`` does one gradient step of each."""

    def __init__(self, obs_dim: int, act_dim: int, cfg: DDPGConfig) -> None:
        self.cfg = cfg
        self.actor = Actor(obs_dim, act_dim, cfg.actor_hidden, cfg.layer_norm)
        self.critic = Critic(obs_dim, act_dim, cfg.critic_hidden, cfg.layer_norm)
        self.actor_target = copy.deepcopy(self.actor).requires_grad_(False)
        self.critic_target = copy.deepcopy(self.critic).requires_grad_(False)
        self.actor_opt = _adam(self.actor.parameters(), cfg.actor_lr)
        self.critic_opt = _adam(self.critic.parameters(), cfg.critic_lr, cfg.critic_weight_decay)
        self._critic_params = list(self.critic.parameters())
        self._online = list(self.actor.parameters()) + self._critic_params
        self._target = list(self.actor_target.parameters()) + list(self.critic_target.parameters())
        self._autocast = (lambda: torch.autocast("cpu", dtype=torch.bfloat16)) if cfg.autocast_bf16 \
            else contextlib.nullcontext
        self._critic_loss, self._actor_loss = self.critic_loss, self.actor_loss
        if cfg.compile:  # shapes are fixed (batch sizes), so no dynamic-shape graphs
            self._critic_loss = torch.compile(self.critic_loss, dynamic=False)
            self._actor_loss = torch.compile(self.actor_loss, dynamic=False)
        self.updates = 0
        self._loss_sum = torch.zeros(2)  # (critic, actor) summed since the last read-out
        self._loss_count = 0

    def critic_loss(self, b: Batch) -> torch.Tensor:
        """mean((Q(s, a) - y)^2) with y from the target networks (no gradient through y)."""
        with torch.no_grad(), self._autocast():
            next_q = self.critic_target(b.next_obs, self.actor_target(b.next_obs)).float().squeeze(-1)
            y = td_target(b.rew, b.terminated, next_q, self.cfg.gamma)
        with self._autocast():
            q = self.critic(b.obs, b.act).float().squeeze(-1)
        return F.mse_loss(q, y)

    def actor_loss(self, b: Batch, demo: Batch | None = None) -> torch.Tensor:
        """-mean(Q(s, mu(s))) [+ bc_weight * mean((mu(s_d) - a_d)^2) on demonstration rows]."""
        with self._autocast():
            loss = -self.critic(b.obs, self.actor(b.obs)).float().mean()
            if demo is not None:
                loss = loss + self.cfg.bc_weight * F.mse_loss(self.actor(demo.obs).float(), demo.act)
        return loss

    def update(self, b: Batch, demo: Batch | None = None) -> None:
        """One DDPG update from batch ``b`` (see the module docstring); with ``demo`` and
        ``cfg.bc_weight`` > 0 the actor also regresses onto the demonstrated actions
        (behaviour cloning as in DDPGfD / TD3+BC)."""
        critic_loss = self._critic_loss(b)
        self.critic_opt.zero_grad(set_to_none=True)
        critic_loss.backward()
        self.critic_opt.step()

        for p in self._critic_params:  # the actor step needs dQ/da only, not the critic's weight gradients
            p.requires_grad_(False)
        try:
            actor_loss = self._actor_loss(b, demo if demo is not None and self.cfg.bc_weight > 0 else None)
            self.actor_opt.zero_grad(set_to_none=True)
            actor_loss.backward()
        finally:
            for p in self._critic_params:
                p.requires_grad_(True)
        self.actor_opt.step()

        soft_update(self._target, self._online, self.cfg.tau)
        self._loss_sum += torch.stack((critic_loss.detach(), actor_loss.detach()))
        self._loss_count += 1
        self.updates += 1

    def read_losses(self) -> tuple[float, float] | None:
        """Mean (critic, actor) loss since the last call (one sync), or None if no update since."""
        if self._loss_count == 0:
            return None
        c, a = (self._loss_sum / self._loss_count).tolist()
        self._loss_sum.zero_()
        self._loss_count = 0
        return c, a

    @torch.no_grad()
    def act(self, obs: np.ndarray) -> np.ndarray:
        """Deterministic actions in [-1, 1] for a (n, obs_dim) batch of observations."""
        return self.actor(torch.from_numpy(np.asarray(obs, np.float32))).numpy()

    def state_dict(self) -> dict[str, Any]:
        return {"actor": self.actor.state_dict(), "critic": self.critic.state_dict(),
                "actor_target": self.actor_target.state_dict(), "critic_target": self.critic_target.state_dict(),
                "actor_opt": self.actor_opt.state_dict(), "critic_opt": self.critic_opt.state_dict(),
                "updates": self.updates}

    def load_state_dict(self, state: dict[str, Any]) -> None:
        for name in ("actor", "critic", "actor_target", "critic_target", "actor_opt", "critic_opt"):
            getattr(self, name).load_state_dict(state[name])
        self.updates = int(state["updates"])
