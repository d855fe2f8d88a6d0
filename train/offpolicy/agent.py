"""What the training loop needs from a learning algorithm: the :class:`Agent` interface.

The loop (:mod:`train.offpolicy.loop`) collects experience, keeps the replay, logs, evaluates and
checkpoints; an agent owns its networks and optimisers and does the gradient steps.
An agent is built by :func:`train.offpolicy.algos.make_agent` from the sections of a
:class:`train.offpolicy.config.TrainConfig` and offers:

* ``actor`` -- the deterministic policy :class:`ssl_marl.skills.networks.Actor`
  (normalised actions in [-1, 1]); it is what the loop exports and what
  :func:`ssl_marl.skills.checkpoint.load_actor` loads, whatever the algorithm;
* ``act(obs)`` -- actions for a batch of observations, no exploration (the loop adds
  the exploration noise of :mod:`train.offpolicy.exploration`);
* ``update(batch, demo=None)`` -- one gradient update from a replay batch (``demo``:
  demonstration rows for a behaviour-cloning term, when the config asks for one);
* ``updates`` -- number of updates done;
* ``loss_names`` and ``read_losses()`` -- the named losses, averaged since the last read;
* ``state_dict()`` / ``load_state_dict()`` -- everything needed to resume exactly.

:class:`LossMeter` accumulates named losses as tensors, so an update never waits
for a ``.item()``; the loop reads them every ``log_interval`` updates.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, Protocol, runtime_checkable

import numpy as np
import torch

from ssl_marl.skills.networks import Actor

from train.offpolicy.replay import Batch


@runtime_checkable
class Agent(Protocol):
    """The interface every algorithm in :data:`train.offpolicy.algos.ALGOS` implements (see the module docstring)."""

    actor: Actor
    updates: int
    loss_names: tuple[str, ...]

    def act(self, obs: np.ndarray) -> np.ndarray: ...

    def update(self, batch: Batch, demo: Batch | None = None) -> None: ...

    def read_losses(self) -> dict[str, float] | None: ...

    def state_dict(self) -> dict[str, Any]: ...

    def load_state_dict(self, state: dict[str, Any]) -> None: ...


class LossMeter:
    """Sums of named scalar losses (tensors, no sync) and how many values each sum holds."""

    def __init__(self, names: Sequence[str]) -> None:
        self.names = tuple(names)
        self.sums = torch.zeros(len(self.names))
        self.counts = [0] * len(self.names)

    def add(self, **losses: torch.Tensor) -> None:
        """Add one value per given loss (a loss may be left out, e.g. a delayed actor loss)."""
        idx = [self.names.index(k) for k in losses]
        if len(idx) == len(self.names):
            self.sums += torch.stack([losses[k].detach().float() for k in self.names])
        else:
            for i, k in zip(idx, losses):
                self.sums[i] += losses[k].detach().float()
        for i in idx:
            self.counts[i] += 1

    def read(self) -> dict[str, float] | None:
        """Mean of each loss since the last read (one sync), or None when nothing was added."""
        if not any(self.counts):
            return None
        values = self.sums.tolist()
        out = {k: values[i] / self.counts[i] for i, k in enumerate(self.names) if self.counts[i]}
        self.sums.zero_()
        self.counts = [0] * len(self.names)
        return out

    def state_dict(self) -> dict[str, Any]:
        return {"names": list(self.names), "sums": self.sums.clone(), "counts": list(self.counts)}

    def load_state_dict(self, state: dict[str, Any]) -> None:
        if list(state["names"]) != list(self.names):
            raise ValueError(f"loss names {state['names']} do not match {list(self.names)}")
        self.sums.copy_(state["sums"])
        self.counts = [int(c) for c in state["counts"]]


@torch.no_grad()
def soft_update(target: Sequence[torch.Tensor], online: Sequence[torch.Tensor], tau: float) -> None:
    """In place: target <- target + tau * (online - target), one fused foreach op."""
    torch._foreach_lerp_(list(target), list(online), tau)


def step_with_frozen(loss_fn: Any, frozen: Sequence[torch.Tensor], opt: Any) -> torch.Tensor:
    """One optimiser step on ``loss_fn()`` with ``frozen`` parameters excluded from the
    backward pass (the actor step needs dQ/da, not the critic's weight gradients);
    returns the loss."""
    for p in frozen:
        p.requires_grad_(False)
    try:
        loss = loss_fn()
        opt.zero_grad(set_to_none=True)
        loss.backward()
    finally:
        for p in frozen:
            p.requires_grad_(True)
    opt.step()
    return loss


def td_target(rew: torch.Tensor, terminated: torch.Tensor, next_q: torch.Tensor, gamma: float,
              discount: torch.Tensor | None = None) -> torch.Tensor:
    """Bellman target r + gamma (1 - terminated) Q'(s', a'). Truncated (time-limit) steps have
    terminated = 0 and so bootstrap; shapes (B,). With ``discount`` (B,) (n-step rows,
    :mod:`train.offpolicy.nstep`: ``gamma ** k`` for the k steps summed into ``rew``) it replaces
    ``gamma``: r + discount (1 - terminated) Q'(s', a')."""
    if discount is None:
        return rew + gamma * (1.0 - terminated) * next_q
    return rew + discount * (1.0 - terminated) * next_q


def adam(params: Any, lr: float, weight_decay: float = 0.0) -> torch.optim.Adam:
    """Adam, fused on CPU where torch has it (>= 2.4: measured ~7 % faster than foreach here)."""
    try:
        return torch.optim.Adam(params, lr=lr, weight_decay=weight_decay, fused=True)
    except (RuntimeError, TypeError):
        return torch.optim.Adam(params, lr=lr, weight_decay=weight_decay, foreach=True)


class LeanAdam:
    """``torch.optim.Adam(fused=True)`` with a lean :meth:`step`: after the first step (which the
    wrapped optimiser does, creating its state) every step is one ``torch._foreach_add_`` on the
    step counters and one ``torch._fused_adam_`` call on cached lists of parameters and moments,
    the two kernels ``Adam.step`` ends in; what is skipped is its per-step Python (hooks,
    profiler scope, grouping tensors by device and dtype, state look-ups). Bit-identical to
    ``torch.optim.Adam(fused=True)`` (tested); the state dict is the wrapped optimiser's, so
    checkpoints are interchangeable. Parameters without a gradient, or a torch without the
    fused CPU kernel, fall back to the wrapped optimiser's own step."""

    def __init__(self, params: Any, lr: float, weight_decay: float = 0.0) -> None:
        self.opt = torch.optim.Adam(params, lr=lr, weight_decay=weight_decay, fused=True)
        if len(self.opt.param_groups) != 1:
            raise ValueError("LeanAdam takes one parameter group")
        self.params: list[torch.Tensor] = list(self.opt.param_groups[0]["params"])
        self._lists: tuple[list[torch.Tensor], list[torch.Tensor], list[torch.Tensor]] | None = None

    @property
    def param_groups(self) -> list[dict[str, Any]]:
        return self.opt.param_groups

    @property
    def state(self) -> Any:
        return self.opt.state

    def zero_grad(self, set_to_none: bool = True) -> None:
        for p in self.params:
            if set_to_none:
                p.grad = None
            elif p.grad is not None:
                p.grad.zero_()

    def _cache(self) -> None:
        st = self.opt.state
        if all(p in st and "exp_avg" in st[p] for p in self.params):
            self._lists = ([st[p]["exp_avg"] for p in self.params], [st[p]["exp_avg_sq"] for p in self.params],
                           [st[p]["step"] for p in self.params])

    def step(self) -> None:
        grads = [p.grad for p in self.params]
        if self._lists is None or any(g is None for g in grads):
            self.opt.step()
            if self._lists is None:
                self._cache()
            return
        g = self.opt.param_groups[0]
        exp_avgs, exp_avg_sqs, steps = self._lists
        beta1, beta2 = g["betas"]
        torch._foreach_add_(steps, 1)
        torch._fused_adam_(self.params, grads, exp_avgs, exp_avg_sqs, [], steps, amsgrad=False, lr=g["lr"],
                           beta1=beta1, beta2=beta2, weight_decay=g["weight_decay"], eps=g["eps"],
                           maximize=False, grad_scale=None, found_inf=None)

    def state_dict(self) -> dict[str, Any]:
        return self.opt.state_dict()

    def load_state_dict(self, state: dict[str, Any]) -> None:
        self.opt.load_state_dict(state)  # replaces the state tensors: rebuild the cached lists
        self._lists = None
        self._cache()


def lean_adam(params: Any, lr: float, weight_decay: float = 0.0) -> LeanAdam | torch.optim.Adam:
    """:class:`LeanAdam` where this torch has fused CPU Adam, else :func:`adam`."""
    try:
        return LeanAdam(params, lr, weight_decay)
    except (RuntimeError, TypeError):
        return adam(params, lr, weight_decay)


def bf16_autocast(enabled: bool) -> Any:
    """A context-manager factory: bfloat16 CPU autocast when ``enabled``, else a no-op."""
    import contextlib

    if enabled:
        return lambda: torch.autocast("cpu", dtype=torch.bfloat16)
    return contextlib.nullcontext


@torch.no_grad()
def actor_act(actor: Actor, obs: np.ndarray) -> np.ndarray:
    """Deterministic actions in [-1, 1] for a (n, obs_dim) batch of observations."""
    return actor(torch.from_numpy(np.asarray(obs, np.float32))).numpy()
