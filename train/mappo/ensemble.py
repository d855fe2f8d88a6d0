"""Merge decision actors of one shape into one actor that outputs their mean logits.

An ensemble of K MLPs ``Linear -> tanh -> ... -> Linear`` with the same input, hidden sizes
and observation scaling is itself such an MLP, K times as wide: the first layer stacks the
members' first layers (every member reads the same input), each hidden layer is block
diagonal (member k's units feed only member k's), and the last layer concatenates the
members' last layers scaled by 1/K with the mean of their biases. The merged file is an
ordinary decision actor file (:mod:`ssl_marl.decisions.learned`), so every policy that
plays an actor (``ImprovedDecisionPolicy`` included) plays the ensemble unchanged; its
metadata names the members and their sha256 (``ensemble``).

``python -m train.mappo_rollout_pi merge --actor A B C --out PATH`` writes one.
"""

from __future__ import annotations

import hashlib
from pathlib import Path
from typing import Any, Sequence

import torch

from ssl_marl.skills.checkpoint import read_actor_file, save_actor_file

#: metadata that must agree between members (the network's shape and what it reads)
SAME_META = ("task", "obs_dim", "n_options", "hidden", "agent_ids", "option_names")


def merge_decision_actors(paths: Sequence[str | Path], **meta: Any) -> tuple[dict[str, torch.Tensor], dict[str, Any]]:
    """The merged actor's state dict and metadata (module docstring); ``meta`` is added to the
    metadata. ValueError naming the first difference when the members do not share a shape,
    an observation scaling or a task."""
    if len(paths) < 2:
        raise ValueError(f"an ensemble needs at least two actors, got {len(paths)}")
    members = [read_actor_file(p, "decision") for p in paths]
    state0, meta0 = members[0]
    for p, (state, m) in zip(paths[1:], members[1:]):
        for key in SAME_META:
            if m.get(key) != meta0.get(key):
                raise ValueError(f"{p}: {key} {m.get(key)!r} differs from {paths[0]}'s {meta0.get(key)!r}")
        for key in ("obs_mean", "obs_std"):
            if not torch.equal(torch.as_tensor(state[key]), torch.as_tensor(state0[key])):
                raise ValueError(f"{p}: {key} differs from {paths[0]}'s; members must scale observations alike")
    n_linear = len(meta0["hidden"]) + 1
    k = len(members)
    out: dict[str, torch.Tensor] = {"obs_mean": torch.as_tensor(state0["obs_mean"]),
                                    "obs_std": torch.as_tensor(state0["obs_std"])}
    for i in range(n_linear):
        w = [torch.as_tensor(s[f"net.{2 * i}.weight"]) for s, _ in members]
        b = [torch.as_tensor(s[f"net.{2 * i}.bias"]) for s, _ in members]
        if i == 0:
            out[f"net.{2 * i}.weight"], out[f"net.{2 * i}.bias"] = torch.cat(w, 0), torch.cat(b)
        elif i < n_linear - 1:
            out[f"net.{2 * i}.weight"], out[f"net.{2 * i}.bias"] = torch.block_diag(*w), torch.cat(b)
        else:
            out[f"net.{2 * i}.weight"] = torch.cat(w, 1) / k
            out[f"net.{2 * i}.bias"] = torch.stack(b).mean(0)
    if n_linear == 1:  # no hidden layer: the mean of the members' single layers
        out["net.0.weight"] = torch.stack([torch.as_tensor(s["net.0.weight"]) for s, _ in members]).mean(0)
        out["net.0.bias"] = torch.stack([torch.as_tensor(s["net.0.bias"]) for s, _ in members]).mean(0)
    merged = {key: meta0.get(key) for key in SAME_META}
    merged.update(continuous=False, hidden=[int(h) * k for h in meta0["hidden"]],
                  ensemble={"mean": "logits", "members": [{"file": Path(p).name, "sha256": _sha256(p)} for p in paths]},
                  **meta)
    return out, merged


def write_merged(paths: Sequence[str | Path], out: str | Path, **meta: Any) -> Path:
    """Merge ``paths`` (:func:`merge_decision_actors`) and write the actor file ``out`` atomically."""
    state, merged = merge_decision_actors(paths, **meta)
    return save_actor_file(out, "decision", state, merged)


def _sha256(path: str | Path) -> str:
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


__all__ = ["merge_decision_actors", "write_merged", "SAME_META"]
