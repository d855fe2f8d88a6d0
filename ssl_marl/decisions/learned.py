"""Learned decision policies: the MAPPO-trained shared actor as a :class:`~ssl_marl.decisions.policies.DecisionPolicy`.

A decision actor file is an actor file of kind ``"decision"`` (:mod:`ssl_marl.skills.checkpoint`,
read with ``torch.load(weights_only=True)``): its state dict holds the network's ``net.*`` weights
and ``obs_mean`` / ``obs_std`` (obs_dim,); its metadata ``task``, ``obs_dim``, ``n_options``,
``hidden``, ``agent_ids`` ([str, ...] | None), ``option_names`` ([str, ...] | None) and provenance
(seed, decisions, val_score, val_seed, commit).

The network (:class:`DecisionActor`) is the trainer's actor (``train/mappo/algorithm.py``): an MLP
``Linear -> tanh`` per hidden layer, then a linear layer to one logit per option, on the
observation scaled as ``(obs - obs_mean) / obs_std`` (with the agent's one-hot appended when
``agent_ids`` is set). :class:`LearnedDecisionPolicy` plays it greedily: the legal option
(``info["action_mask"]``) with the highest logit.

:class:`ImprovedDecisionPolicy` is the task's hand-coded policy with a *value* actor (the same
network, fitted by ``python -m train.mappo_rollout_pi fit`` to predict each option's return when the
hand-coded policy plays on) consulted at the first decisions of an episode only.

Shipped actors: ``ssl_marl/decisions/pretrained/<task>.pt`` (:func:`pretrained_path`), made by
``python -m train mappo --task TASK ...`` then ``python -m train.mappo_export RUN_DIR ... --out PATH``.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
import torch
from torch import nn

from ..skills.checkpoint import read_actor_file

PRETRAINED_DIR = Path(__file__).resolve().parent / "pretrained"
_TRAIN_CMD = {
    "keepaway": "python -m train mappo --task keepaway --seed 0 --out runs/mappo_keepaway_s0 && "
                "python -m train.mappo_export runs/mappo_keepaway_s0 --out ssl_marl/decisions/pretrained/keepaway.pt",
    "attack-3v2": "python -m train mappo --task attack-3v2 --seed 0 --out runs/mappo_attack_s0 && "
                  "python -m train.mappo_export runs/mappo_attack_s0 --out ssl_marl/decisions/pretrained/attack_3v2.pt",
    "attack-drill": "python -m train mappo --task attack-drill --seed 0 --out runs/mappo_attack_drill_s0 && "
                    "python -m train.mappo_export runs/mappo_attack_drill_s0 --out "
                    "ssl_marl/decisions/pretrained/attack_drill.pt",
}


#: tasks whose agents decide with another task's observation and options (an actor of one
#: plays the other): the full-match task continues the attack drill's decision
SHARED_DECISIONS: dict[str, str] = {"attack-match": "attack-drill", "attack-drill-ssl": "attack-drill",
                                     "attack-drill-defended": "attack-drill", "attack-drill-mix": "attack-drill"}


def decision_family(task: str | None) -> str | None:
    """The task whose observation and options ``task``'s agents use (itself unless listed in
    :data:`SHARED_DECISIONS`): actors of tasks of one family are interchangeable."""
    return SHARED_DECISIONS.get(task, task) if task is not None else None


def pretrained_path(task: str) -> Path:
    """The shipped actor of ``task``'s decision family (:func:`decision_family`;
    ``pretrained/<family with - as _>.pt``: the drill under SSL rules plays the drill's actor);
    FileNotFoundError saying how to train one when it is absent."""
    path = PRETRAINED_DIR / f"{decision_family(task).replace('-', '_')}.pt"
    if not path.is_file():
        cmd = _TRAIN_CMD.get(task, f"python -m train mappo --task {task} --seed 0 --out runs/mappo_{task}")
        raise FileNotFoundError(f"no shipped decision actor for task {task!r} ({path}); train and export one: {cmd}")
    return path


def pretrained_value_path(task: str) -> Path:
    """The shipped value actor of ``task`` for :class:`ImprovedDecisionPolicy`
    (``pretrained/<task with - as _>_value.pt``); FileNotFoundError saying how to make one."""
    path = PRETRAINED_DIR / f"{task.replace('-', '_')}_value.pt"
    if not path.is_file():
        raise FileNotFoundError(f"no shipped value actor for task {task!r} ({path}); label and fit one: "
                                f"python -m train.mappo_rollout_pi collect --task {task} --episodes 250 --seed 121000 "
                                f"--out LABELS && python -m train.mappo_rollout_pi fit --task {task} --labels LABELS "
                                f"--out {path}")
    return path


class DecisionActor(nn.Module):
    """Shared decision actor: scaled obs (..., in_dim) -> option logits (..., n_options)."""

    def __init__(self, obs_dim: int, n_options: int, hidden: Sequence[int], n_agents: int = 0) -> None:
        super().__init__()
        self.obs_dim, self.n_options, self.hidden, self.n_agents = int(obs_dim), int(n_options), tuple(hidden), int(n_agents)
        layers: list[nn.Module] = []
        d = self.obs_dim + self.n_agents
        for h in self.hidden:
            layers += [nn.Linear(d, int(h)), nn.Tanh()]
            d = int(h)
        layers.append(nn.Linear(d, self.n_options))
        self.net = nn.Sequential(*layers)
        self.register_buffer("obs_mean", torch.zeros(self.obs_dim))
        self.register_buffer("obs_std", torch.ones(self.obs_dim))

    def forward(self, obs: torch.Tensor, agent_onehot: torch.Tensor | None = None) -> torch.Tensor:
        x = (obs - self.obs_mean) / self.obs_std
        if self.n_agents:
            if agent_onehot is None:
                raise ValueError("this actor was trained with agent one-hots; pass agent_onehot")
            x = torch.cat([x, agent_onehot], -1)
        return self.net(x)

    @torch.no_grad()
    def logits(self, obs: np.ndarray, agent_index: int | None = None) -> np.ndarray:
        """Logits for one observation (numpy in, numpy out)."""
        o = torch.as_tensor(np.asarray(obs, np.float32))
        hot = None
        if self.n_agents:
            hot = torch.zeros(self.n_agents)
            hot[int(agent_index or 0)] = 1.0
        return self.forward(o, hot).numpy()


def load_decision_actor(path: str | Path) -> tuple[DecisionActor, dict[str, Any]]:
    """Load a decision actor file (``weights_only=True``): the network and the file's metadata."""
    state, meta = read_actor_file(path, "decision")
    for key in ("obs_dim", "n_options", "hidden"):
        if key not in meta:
            raise ValueError(f"{path} is not a valid ssl_marl decision actor: missing {key!r}")
    if meta.get("continuous"):
        raise ValueError(f"{path} holds a continuous-action actor (task {meta.get('task')!r}), not a decision actor")
    agent_ids = meta.get("agent_ids") or None
    actor = DecisionActor(int(meta["obs_dim"]), int(meta["n_options"]), [int(h) for h in meta["hidden"]],
                          len(agent_ids) if agent_ids else 0)
    actor.net.load_state_dict({k[len("net."):]: v for k, v in state.items() if k.startswith("net.")})
    if state.get("obs_mean") is not None:
        actor.obs_mean.copy_(torch.as_tensor(state["obs_mean"], dtype=torch.float32))
        actor.obs_std.copy_(torch.as_tensor(state["obs_std"], dtype=torch.float32))
    actor.eval()
    return actor, meta


class LearnedDecisionPolicy:
    """Greedy policy of a decision actor: argmax of the logits over the legal options.

    ``path_or_actor``: an actor file or a :class:`DecisionActor`; ``task``: the task the env
    plays (checked against the file's). :meth:`reset` refuses an env whose observation size or
    option count differ from the actor's, naming both."""

    name = "learned"

    def __init__(self, path_or_actor: str | Path | DecisionActor, task: str | None = None) -> None:
        if isinstance(path_or_actor, DecisionActor):
            self.actor, self.meta = path_or_actor, {"task": task}
        else:
            self.actor, self.meta = load_decision_actor(path_or_actor)
            got = self.meta.get("task")
            if task is not None and got is not None and decision_family(got) != decision_family(task):
                raise ValueError(f"{path_or_actor} is an actor for task {got!r}, not {task!r}")
        self.task = task or self.meta.get("task")
        self.agent_ids: list[str] | None = self.meta.get("agent_ids") or None

    def reset(self, env: Any) -> None:
        agent = env.possible_agents[0]
        obs_dim = int(np.prod(env.observation_space(agent).shape))
        n_opt = int(env.action_space(agent).n)
        if obs_dim != self.actor.obs_dim:
            raise ValueError(f"learned decision actor expects observations of size {self.actor.obs_dim}, "
                             f"the env gives {obs_dim} (observation_space of {agent!r}); retrain or export "
                             f"an actor for this env version")
        if n_opt != self.actor.n_options:
            raise ValueError(f"learned decision actor has {self.actor.n_options} options, the env has {n_opt} "
                             f"(action_space of {agent!r}: {getattr(env, 'option_names', None)})")
        names = self.meta.get("option_names")
        if names is not None and getattr(env, "option_names", None) is not None \
                and list(names) != list(env.option_names):
            raise ValueError(f"learned decision actor's options {list(names)} differ from the env's "
                             f"{list(env.option_names)}")

    def act(self, env: Any, agent: str, obs: np.ndarray, info: dict) -> int:
        idx = self.agent_ids.index(agent) if self.agent_ids else None
        logits = self.actor.logits(obs, idx)
        mask = np.asarray(info.get("action_mask", np.ones_like(logits)), bool)
        if not mask.any():
            raise ValueError(f"learned policy: agent {agent!r} has no legal option (action_mask all zero)")
        return int(np.argmax(np.where(mask, logits, -np.inf)))


class ImprovedDecisionPolicy:
    """The task's hand-coded policy, improved at its first decisions by a value actor.

    At each of the first ``first_k`` decisions of an episode the value actor (``path_or_actor``:
    outputs are predicted returns per option, as ``python -m train.mappo_rollout_pi fit`` trains
    them) rates the legal options; where the best of them is predicted to beat the hand-coded
    policy's choice by more than ``margin``, it is played instead; the comparison is of the actor's
    outputs, the logits of a goal (log-odds: a margin of 0.1 is about 0.025 goals near even odds). Every
    other decision is the hand-coded policy's. This is one step of policy iteration kept where
    its labels hold: each label is an option's return with the hand-coded policy playing on, so
    the improvement is sound for a deviation followed by the hand-coded policy; played at every
    decision the actor keeps choosing the passes it rates above shots and the drill runs out of
    time (docs/RESULTS.md, section 9, "Where the cost decision loses").

    Args:
        base: the hand-coded policy (its :meth:`act` runs at every decision, so its own state,
            e.g. the keep clock, stays as if it played alone).
        path_or_actor: value actor file or :class:`DecisionActor`; ``task``: checked as in
            :class:`LearnedDecisionPolicy`.
        first_k: decisions per episode, counted over all agents, at which the actor may deviate;
            None: the value actor file's ``improve["first_k"]`` (``fit --first-k``), else 1.
        margin: logit (log-odds) gain a deviation needs; None: the file's
            ``improve["margin"]`` (``fit --margin``), else 0.1.
    """

    name = "improved"

    def __init__(self, base: Any, path_or_actor: str | Path | DecisionActor, task: str | None = None,
                 first_k: int | None = None, margin: float | None = None) -> None:
        self.base, self.value = base, LearnedDecisionPolicy(path_or_actor, task=task)
        recorded_k, recorded_margin = improve_settings(self.value.meta)
        first_k = recorded_k if first_k is None else first_k
        margin = recorded_margin if margin is None else margin
        if first_k < 0 or not np.isfinite(margin):
            raise ValueError(f"ImprovedDecisionPolicy: first_k must be >= 0 and margin finite, got {first_k}, {margin}")
        self.first_k, self.margin = int(first_k), float(margin)
        self.decisions = 0
        self.deviations = 0

    def reset(self, env: Any) -> None:
        self.base.reset(env)
        self.value.reset(env)
        self.decisions = 0

    def act(self, env: Any, agent: str, obs: np.ndarray, info: dict) -> int:
        choice = int(self.base.act(env, agent, obs, info))
        i, self.decisions = self.decisions, self.decisions + 1
        if i >= self.first_k:
            return choice
        idx = self.value.agent_ids.index(agent) if self.value.agent_ids else None
        v = self.value.actor.logits(obs, idx)
        best = better_option(v, np.asarray(info.get("action_mask", np.ones_like(v)), bool), choice, self.margin)
        if best is None:
            return choice
        self.deviations += 1
        return best


#: how :class:`ImprovedDecisionPolicy` plays a value actor file that records nothing else: the
#: episode's first decision only, where the actor's logit exceeds the hand-coded option's by more than 0.1
DEFAULT_FIRST_K, DEFAULT_MARGIN = 1, 0.1


def improve_settings(meta: dict) -> tuple[int, float]:
    """(first_k, margin) a value actor file records for :class:`ImprovedDecisionPolicy`
    (its ``improve`` entry, ``python -m train.mappo_rollout_pi fit --first-k --margin``),
    else (:data:`DEFAULT_FIRST_K`, :data:`DEFAULT_MARGIN`)."""
    improve = meta.get("improve") or {}
    return int(improve.get("first_k", DEFAULT_FIRST_K)), float(improve.get("margin", DEFAULT_MARGIN))


def better_option(values: np.ndarray, mask: np.ndarray, choice: int, margin: float) -> int | None:
    """The legal option (``mask``) of the highest predicted value (``values``, one per option)
    if it beats option ``choice`` by more than ``margin``, else None."""
    v = np.where(np.asarray(mask, bool), values, -np.inf)
    best = int(np.argmax(v))
    return best if v[best] > v[choice] + margin else None


__all__ = ["DecisionActor", "ImprovedDecisionPolicy", "better_option", "improve_settings", "LearnedDecisionPolicy", "load_decision_actor", "pretrained_path",
           "pretrained_value_path"]
