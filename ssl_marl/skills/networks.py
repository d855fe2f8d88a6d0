"""Actor and critic networks for the learned skills (paper section 5.1).

Each hidden layer is ``Linear -> LayerNorm -> ReLU`` (layer norm optional); the
actor ends in ``tanh`` so its output is a normalised action in [-1, 1]^act_dim,
the critic ends in a linear unit (a Q-value in the reward's units).

This module is inference-safe: shipped learned skills import :class:`Actor`
from here without pulling in the ``train`` package.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import torch
from torch import nn

#: Final-layer weights and biases are drawn from U(-FINAL_INIT, FINAL_INIT)
#: (Lillicrap et al. 2016, sec. 7) so initial actions and Q-values are near 0.
FINAL_INIT = 3e-3


def mlp(in_dim: int, hidden: Sequence[int], layer_norm: bool = True) -> nn.Sequential:
    """Hidden trunk: ``Linear -> [LayerNorm] -> ReLU`` for each size in ``hidden``."""
    if in_dim <= 0 or any(int(h) <= 0 for h in hidden):
        raise ValueError(f"layer sizes must be positive, got in_dim={in_dim}, hidden={tuple(hidden)}")
    layers: list[nn.Module] = []
    prev = in_dim
    for size in hidden:
        layers.append(nn.Linear(prev, int(size)))
        if layer_norm:
            layers.append(nn.LayerNorm(int(size)))
        layers.append(nn.ReLU())
        prev = int(size)
    return nn.Sequential(*layers)


def _final_layer(in_dim: int, out_dim: int) -> nn.Linear:
    layer = nn.Linear(in_dim, out_dim)
    nn.init.uniform_(layer.weight, -FINAL_INIT, FINAL_INIT)
    nn.init.uniform_(layer.bias, -FINAL_INIT, FINAL_INIT)
    return layer


class Actor(nn.Module):
    """Deterministic policy ``mu(s)``: obs (..., obs_dim) -> action (..., act_dim) in [-1, 1]."""

    def __init__(self, obs_dim: int, act_dim: int, hidden: Sequence[int] = (300, 400),
                 layer_norm: bool = True) -> None:
        super().__init__()
        self.obs_dim = int(obs_dim)
        self.act_dim = int(act_dim)
        self.hidden = tuple(int(h) for h in hidden)
        self.layer_norm = bool(layer_norm)
        self.trunk = mlp(self.obs_dim, self.hidden, self.layer_norm)
        self.head = _final_layer(self.hidden[-1] if self.hidden else self.obs_dim, self.act_dim)

    def forward(self, obs: torch.Tensor) -> torch.Tensor:
        return torch.tanh(self.head(self.trunk(obs)))

    @torch.no_grad()
    def act(self, obs: np.ndarray) -> np.ndarray:
        """Numpy convenience for deployment: (obs_dim,) or (n, obs_dim) -> float32 action(s) in [-1, 1]."""
        x = torch.as_tensor(np.asarray(obs, dtype=np.float32))
        return self.forward(x).numpy()


class Critic(nn.Module):
    """Action-value ``Q(s, a)``: concat(obs, act) (..., obs_dim + act_dim) -> (..., 1)."""

    def __init__(self, obs_dim: int, act_dim: int, hidden: Sequence[int] = (300, 400),
                 layer_norm: bool = True) -> None:
        super().__init__()
        self.obs_dim = int(obs_dim)
        self.act_dim = int(act_dim)
        self.hidden = tuple(int(h) for h in hidden)
        self.layer_norm = bool(layer_norm)
        self.trunk = mlp(self.obs_dim + self.act_dim, self.hidden, self.layer_norm)
        self.head = _final_layer(self.hidden[-1] if self.hidden else self.obs_dim + self.act_dim, 1)

    def forward(self, obs: torch.Tensor, act: torch.Tensor) -> torch.Tensor:
        return self.head(self.trunk(torch.cat((obs, act), dim=-1)))
