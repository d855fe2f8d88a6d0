"""DDPG (Lillicrap et al. 2016; docs/references.md, "Simulators and benchmarks"), the paper's algorithm
(Schwab, Zhu and Veloso 2019, sections 4.1 and 5.1): one update in :meth:`DDPG.update`::

    y        = r + gamma * (1 - terminated) * Q'(s', mu'(s'))      # no grad; truncations bootstrap
    L_critic = mean((Q(s, a) - y)^2)                               # Adam step on the critic
    L_actor  = -mean(Q(s, mu(s))) [+ w_bc * mean((mu(s_d) - a_d)^2)]  # Adam step on the actor only
    theta'   <- theta' + tau * (theta - theta')                    # Polyak, both targets

With n-step returns (``n_step`` > 1, :mod:`train.offpolicy.nstep`) ``r`` is the window's discounted
reward sum and ``gamma`` the row's own ``gamma ** k`` (``Batch.discount``).

Hyperparameters: :class:`train.offpolicy.config.DDPGConfig` (``gamma``, ``tau``, learning rates,
layer sizes, ``bc_weight``); speed options ``autocast_bf16`` and ``compile`` from the run config.

Speed (measured, see benchmarks/bench_ddpg.py and docs/BENCHMARKS.md): fused
Adam stepped through :class:`~train.offpolicy.agent.LeanAdam` (no per-step Python); the critic's parameters frozen during the actor step
(no critic weight gradients); one ``torch._foreach_lerp_`` for the soft update; losses accumulated
as tensors and read out every ``log_interval`` updates (no ``.item()`` sync per
update). Options: ``autocast_bf16`` runs the matrix products in bfloat16 (on CPUs
with AMX, e.g. Sapphire Rapids, a 256x300 @ 300x400 product is ~5x faster than in
float32); ``compile`` hands the two loss functions (forward and backward) to
``torch.compile``, which fuses the layer-norm / ReLU / cast kernels around them
(~30 s of compilation at start-up). Alone, ``compile`` does not pay in float32 here.
"""

from __future__ import annotations

import copy
from typing import Any

import numpy as np
import torch
import torch.nn.functional as F

from ssl_marl.skills.networks import Actor, Critic

from train.offpolicy.agent import LossMeter, actor_act, bf16_autocast, lean_adam, soft_update, step_with_frozen, td_target
from train.offpolicy.config import DDPGConfig
from train.offpolicy.replay import Batch

__all__ = ["DDPG", "soft_update", "td_target"]


class DDPG:
    """Actor, critic, their targets and optimisers; ``update(batch)`` does one gradient step of each."""

    loss_names = ("critic", "actor")

    def __init__(self, obs_dim: int, act_dim: int, cfg: DDPGConfig, autocast_bf16: bool = False,
                 compile: bool = False) -> None:
        """``autocast_bf16``: bfloat16 autocast of the forward passes; ``compile``: torch.compile the
        two loss functions (the run config's speed options)."""
        self.cfg = cfg
        self.actor = Actor(obs_dim, act_dim, cfg.actor_hidden, cfg.layer_norm)
        self.critic = Critic(obs_dim, act_dim, cfg.critic_hidden, cfg.layer_norm)
        self.actor_target = copy.deepcopy(self.actor).requires_grad_(False)
        self.critic_target = copy.deepcopy(self.critic).requires_grad_(False)
        self.actor_opt = lean_adam(self.actor.parameters(), cfg.actor_lr)
        self.critic_opt = lean_adam(self.critic.parameters(), cfg.critic_lr, cfg.critic_weight_decay)
        self._critic_params = list(self.critic.parameters())
        self._online = list(self.actor.parameters()) + self._critic_params
        self._target = list(self.actor_target.parameters()) + list(self.critic_target.parameters())
        self._autocast = bf16_autocast(autocast_bf16)
        self._critic_loss, self._actor_loss = self.critic_loss, self.actor_loss
        if compile:  # shapes are fixed (batch sizes), so no dynamic-shape graphs
            self._critic_loss = torch.compile(self.critic_loss, dynamic=False)
            self._actor_loss = torch.compile(self.actor_loss, dynamic=False)
        self.updates = 0
        self.losses = LossMeter(self.loss_names)

    def critic_loss(self, b: Batch) -> torch.Tensor:
        """mean((Q(s, a) - y)^2) with y from the target networks (no gradient through y)."""
        with torch.no_grad(), self._autocast():
            next_q = self.critic_target(b.next_obs, self.actor_target(b.next_obs)).float().squeeze(-1)
            y = td_target(b.rew, b.terminated, next_q, self.cfg.gamma, b.discount)
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
        ``bc_weight`` > 0 the actor also regresses onto the demonstrated actions
        (behaviour cloning as in DDPGfD / TD3+BC)."""
        critic_loss = self._critic_loss(b)
        self.critic_opt.zero_grad(set_to_none=True)
        critic_loss.backward()
        self.critic_opt.step()

        bc_demo = demo if demo is not None and self.cfg.bc_weight > 0 else None
        actor_loss = step_with_frozen(lambda: self._actor_loss(b, bc_demo), self._critic_params, self.actor_opt)

        soft_update(self._target, self._online, self.cfg.tau)
        self.losses.add(critic=critic_loss, actor=actor_loss)
        self.updates += 1

    def read_losses(self) -> dict[str, float] | None:
        """Mean ``{"critic": ..., "actor": ...}`` since the last call (one sync), or None if no update since."""
        return self.losses.read()

    def act(self, obs: np.ndarray) -> np.ndarray:
        """Deterministic actions in [-1, 1] for a (n, obs_dim) batch of observations."""
        return actor_act(self.actor, obs)

    def state_dict(self) -> dict[str, Any]:
        return {"actor": self.actor.state_dict(), "critic": self.critic.state_dict(),
                "actor_target": self.actor_target.state_dict(), "critic_target": self.critic_target.state_dict(),
                "actor_opt": self.actor_opt.state_dict(), "critic_opt": self.critic_opt.state_dict(),
                "updates": self.updates, "losses": self.losses.state_dict()}

    def load_state_dict(self, state: dict[str, Any]) -> None:
        for name in ("actor", "critic", "actor_target", "critic_target", "actor_opt", "critic_opt"):
            getattr(self, name).load_state_dict(state[name])
        self.updates = int(state["updates"])
        if "losses" in state:  # absent in version-1 train states (the loop migrates those)
            self.losses.load_state_dict(state["losses"])
