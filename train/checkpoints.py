"""The resumable training state (``OUT/checkpoint.pt``) and the metadata of exported actors.

A train state is a ``torch.save``-d plain dict read back with ``weights_only=True``::

    {"format": "ssl_marl.train_state", "version": 2, "algo": "ddpg" | "td3", "config": {...},
     "seed": int, "agent": Agent.state_dict(), "exploration": {...}, "rng": {...},
     "counters": {...}, "losses": {name: float} | None, "recent": {...},
     "csv_rows": {...}, "replay_file": "replay-<transitions>.npz"}

Version 1 (written before the algorithm interface, DDPG only) is read by
:func:`read_train_state`, which migrates it to version 2 in memory: its ``noise``
becomes ``exploration``, its ``pending_losses`` move into the agent's ``losses``
meter and its ``losses`` list becomes a dict. A run started by the old trainer
therefore resumes with this one.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from ssl_marl.skills.checkpoint import safe_torch_load

from .config import TrainConfig, config_from_dict

CHECKPOINT = "checkpoint.pt"
FORMAT = "ssl_marl.train_state"
VERSION = 2
_V1_LOSSES = ("critic", "actor")  # DDPG's, the only algorithm of version 1


def read_train_state(path: str | Path) -> dict[str, Any]:
    """Load a train state (any known version, migrated to :data:`VERSION`); clear errors otherwise."""
    path = Path(path)
    what = "ssl_marl training checkpoint"
    state = safe_torch_load(path, what)
    if not isinstance(state, dict) or state.get("format") != FORMAT:
        raise ValueError(f"{path} is not a valid {what} (no {FORMAT!r} format tag)")
    version = state.get("version")
    if version == 1:
        state = _migrate_v1(state)
    elif version != VERSION:
        raise ValueError(f"{path} is a {what} of unsupported version {version!r} (this trainer reads 1 and {VERSION})")
    return state


def _migrate_v1(state: dict[str, Any]) -> dict[str, Any]:
    state = dict(state)
    sums, count = state.pop("pending_losses")
    state["agent"] = {**state["agent"], "losses": {"names": list(_V1_LOSSES), "sums": sums,
                                                   "counts": [int(count)] * len(_V1_LOSSES)}}
    state["exploration"] = state.pop("noise")
    state["losses"] = dict(zip(_V1_LOSSES, state["losses"])) if state["losses"] is not None else None
    state["algo"] = "ddpg"
    state["version"] = VERSION
    return state


def load_run_config(out: str | Path) -> tuple[TrainConfig, int]:
    """Config and seed stored in ``OUT/checkpoint.pt`` (for ``--resume``)."""
    state = read_train_state(Path(out) / CHECKPOINT)
    return config_from_dict(state["config"]), int(state["seed"])


def actor_metadata(cfg: TrainConfig, *, obs_spec: str, seed: int, samples: int, transitions: int, updates: int,
                   action_low: list[float], action_high: list[float], **extra: Any) -> dict[str, Any]:
    """Metadata of an exported actor (:func:`ssl_marl.skills.checkpoint.save_actor` adds the network shape,
    git commit and date): the skill, algorithm and observation spec it was trained on, its
    hyperparameters, seed, env samples, demonstration transitions, updates and the env's action bounds."""
    return {"skill": cfg.skill, "algo": cfg.algo, "obs_spec": obs_spec, "env_id": cfg.env_id,
            "hyperparameters": cfg.to_dict(), "seed": int(seed), "samples": int(samples),
            "demo_transitions": int(transitions) - int(samples), "updates": int(updates),
            "action_low": list(action_low), "action_high": list(action_high), **extra}
