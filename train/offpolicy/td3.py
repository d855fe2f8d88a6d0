"""TD3 (Fujimoto et al. 2018, "Addressing Function Approximation Error in Actor-Critic Methods";
docs/references.md, "Simulators and benchmarks").

DDPG plus three fixes of its value over-estimation; one update in :meth:`TD3.update`::

    a'       = clip(mu'(s') + clip(N(0, sigma_s), -c, c), -1, 1)    # target policy smoothing
    y        = r + gamma * (1 - terminated) * min(Q1'(s', a'), Q2'(s', a'))   # clipped double Q
    L_critic = mean((Q1(s, a) - y)^2) + mean((Q2(s, a) - y)^2)     # one Adam step, both critics
    every d-th update (delayed policy update):
        L_actor = -mean(Q1(s, mu(s))) [+ w_bc * mean((mu(s_d) - a_d)^2)]  # Adam step on the actor
        theta'  <- theta' + tau * (theta - theta')                 # Polyak, all three targets

With n-step returns (``n_step`` > 1) ``r`` and ``gamma`` are the row's window sum and
``gamma ** k`` (:mod:`train.offpolicy.nstep`), as in DDPG.

Hyperparameters: :class:`train.offpolicy.config.DDPGConfig` (shared with DDPG) and
:class:`train.offpolicy.config.TD3Config`: ``policy_noise`` (sigma_s, 0.2), ``noise_clip``
(c, 0.5) and ``policy_delay`` (d, 2), the paper's
values, in the actor's normalised action units ([-1, 1]). Exploration is the loop's
(:mod:`train.offpolicy.exploration`; the paper uses Gaussian noise, ``exploration.kind=gaussian``).
The actor is the same :class:`~ssl_marl.skills.networks.Actor` as DDPG's, so a TD3
actor ships and loads exactly like a DDPG one. Same speed options as :mod:`train.offpolicy.ddpg`
(bf16 autocast, compiled loss functions); the smoothing noise is drawn outside the
compiled function, from torch's global generator (saved with the checkpoint).
The logged "critic" loss is the mean of the two critics' losses.
"""

from __future__ import annotations

import copy
from typing import Any

import numpy as np
import torch
import torch.nn.functional as F

from ssl_marl.skills.networks import Actor, Critic

from train.offpolicy.agent import LossMeter, actor_act, bf16_autocast, lean_adam, soft_update, step_with_frozen, td_target
from train.offpolicy.config import DDPGConfig, TD3Config
from train.offpolicy.replay import Batch


class TD3:
    """Actor, twin critics, their targets and optimisers (see the module docstring)."""

    loss_names = ("critic", "actor")

    def __init__(self, obs_dim: int, act_dim: int, cfg: DDPGConfig, td3: TD3Config, autocast_bf16: bool = False,
                 compile: bool = False) -> None:
        """``cfg``: the actor-critic hyperparameters shared with DDPG; ``td3``: the TD3 ones;
        ``autocast_bf16`` and ``compile``: the run config's speed options (as :class:`~train.offpolicy.ddpg.DDPG`)."""
        self.cfg, self.td3 = cfg, td3
        self.actor = Actor(obs_dim, act_dim, cfg.actor_hidden, cfg.layer_norm)
        self.critic1 = Critic(obs_dim, act_dim, cfg.critic_hidden, cfg.layer_norm)
        self.critic2 = Critic(obs_dim, act_dim, cfg.critic_hidden, cfg.layer_norm)
        self.actor_target = copy.deepcopy(self.actor).requires_grad_(False)
        self.critic1_target = copy.deepcopy(self.critic1).requires_grad_(False)
        self.critic2_target = copy.deepcopy(self.critic2).requires_grad_(False)
        self.actor_opt = lean_adam(self.actor.parameters(), cfg.actor_lr)
        self.critic_opt = lean_adam(list(self.critic1.parameters()) + list(self.critic2.parameters()), cfg.critic_lr,
                               cfg.critic_weight_decay)
        self._q1_params = list(self.critic1.parameters())
        self._online = [*self.actor.parameters(), *self.critic1.parameters(), *self.critic2.parameters()]
        self._target = [*self.actor_target.parameters(), *self.critic1_target.parameters(),
                        *self.critic2_target.parameters()]
        self._autocast = bf16_autocast(autocast_bf16)
        self._critic_loss, self._actor_loss = self.critic_loss, self.actor_loss
        if compile:  # fixed batch shapes: no dynamic-shape graphs
            self._critic_loss = torch.compile(self.critic_loss, dynamic=False)
            self._actor_loss = torch.compile(self.actor_loss, dynamic=False)
        self.updates = 0
        self.losses = LossMeter(self.loss_names)

    def smoothing_noise(self, b: Batch) -> torch.Tensor:
        """clip(N(0, policy_noise), -noise_clip, noise_clip), shape of ``b.act``."""
        eps = torch.randn(b.act.shape) * self.td3.policy_noise
        return eps.clamp_(-self.td3.noise_clip, self.td3.noise_clip)

    def critic_loss(self, b: Batch, eps: torch.Tensor) -> torch.Tensor:
        """Sum of both critics' MSE to the clipped double-Q target (no gradient through the target)."""
        with torch.no_grad(), self._autocast():
            next_act = (self.actor_target(b.next_obs).float() + eps).clamp(-1.0, 1.0)
            next_q = torch.minimum(self.critic1_target(b.next_obs, next_act).float(),
                                   self.critic2_target(b.next_obs, next_act).float()).squeeze(-1)
            y = td_target(b.rew, b.terminated, next_q, self.cfg.gamma, b.discount)
        with self._autocast():
            q1 = self.critic1(b.obs, b.act).float().squeeze(-1)
            q2 = self.critic2(b.obs, b.act).float().squeeze(-1)
        return F.mse_loss(q1, y) + F.mse_loss(q2, y)

    def actor_loss(self, b: Batch, demo: Batch | None = None) -> torch.Tensor:
        """-mean(Q1(s, mu(s))) [+ bc_weight * mean((mu(s_d) - a_d)^2) on demonstration rows]."""
        with self._autocast():
            loss = -self.critic1(b.obs, self.actor(b.obs)).float().mean()
            if demo is not None:
                loss = loss + self.cfg.bc_weight * F.mse_loss(self.actor(demo.obs).float(), demo.act)
        return loss

    def update(self, b: Batch, demo: Batch | None = None) -> None:
        """One TD3 update (see the module docstring): a critic step always, an actor step and the
        target updates every ``policy_delay``-th call."""
        critic_loss = self._critic_loss(b, self.smoothing_noise(b))
        self.critic_opt.zero_grad(set_to_none=True)
        critic_loss.backward()
        self.critic_opt.step()
        losses = {"critic": critic_loss.detach() * 0.5}

        if self.updates % self.td3.policy_delay == 0:
            bc_demo = demo if demo is not None and self.cfg.bc_weight > 0 else None  # the actor step needs dQ1/da only
            actor_loss = step_with_frozen(lambda: self._actor_loss(b, bc_demo), self._q1_params, self.actor_opt)
            soft_update(self._target, self._online, self.cfg.tau)
            losses["actor"] = actor_loss
        self.losses.add(**losses)
        self.updates += 1

    def read_losses(self) -> dict[str, float] | None:
        """Mean ``{"critic": ..., "actor": ...}`` since the last call (one sync), or None if no update since."""
        return self.losses.read()

    def act(self, obs: np.ndarray) -> np.ndarray:
        """Deterministic actions in [-1, 1] for a (n, obs_dim) batch of observations."""
        return actor_act(self.actor, obs)

    _MODULES = ("actor", "critic1", "critic2", "actor_target", "critic1_target", "critic2_target", "actor_opt",
                "critic_opt")

    def state_dict(self) -> dict[str, Any]:
        return {**{k: getattr(self, k).state_dict() for k in self._MODULES}, "updates": self.updates,
                "losses": self.losses.state_dict()}

    def load_state_dict(self, state: dict[str, Any]) -> None:
        for name in self._MODULES:
            getattr(self, name).load_state_dict(state[name])
        self.updates = int(state["updates"])
        self.losses.load_state_dict(state["losses"])
