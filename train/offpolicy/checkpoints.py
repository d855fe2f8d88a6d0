"""The resumable training state (``OUT/checkpoint.pt``) and the metadata of exported actors.

A train state is a ``torch.save``-d plain dict read back with ``weights_only=True``::

    {"format": "ssl_marl.train_state", "version": 3, "algo": "ddpg" | "td3", "config": {...},
     "seed": int, "agent": Agent.state_dict(), "exploration": {...}, "rng": {...},
     "counters": {...}, "losses": {name: float} | None, "recent": {...},
     "csv_rows": {...}, "replay_file": "replay-<transitions>.npz"}

``config`` is :meth:`TrainConfig.to_dict` (sections nested). :func:`read_train_state`
reads the earlier versions too and converts them in memory, so every stored run resumes:
version 2 stores the config flat (section keys at the top level, TD3's as ``td3_*``,
the noise kind as ``exploration``); version 1 (DDPG only) also keeps ``noise`` for
``exploration``, ``pending_losses`` outside the agent's ``losses`` meter and ``losses``
as a list.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any


from train.offpolicy.config import SECTIONS, TrainConfig, config_from_dict, section_of
from train.run_folder import CHECKPOINT, read_state

FORMAT = "ssl_marl.train_state"
VERSION = 3
_V1_LOSSES = ("critic", "actor")  # DDPG's, the only algorithm of version 1


def read_train_state(path: str | Path) -> dict[str, Any]:
    """Load a train state (any known version, migrated to :data:`VERSION`); clear errors otherwise."""
    path = Path(path)
    what = "ssl_marl training checkpoint"
    state = read_state(path, FORMAT, what)
    version = state.get("version")
    if version == 1:
        state = _migrate_v1(state)
    elif version == 2:
        state = {**state, "config": nest_flat_config(state["config"]), "version": VERSION}
    elif version != VERSION:
        raise ValueError(f"{path} is a {what} of unsupported version {version!r} (this trainer reads 1 to {VERSION})")
    return state


def nest_flat_config(flat: dict[str, Any]) -> dict[str, Any]:
    """A version-1/2 stored config (every key at the top level) in the nested layout of
    :meth:`TrainConfig.to_dict`: section keys move into their section (``actor_lr`` ->
    ``ddpg.actor_lr``, ``td3_policy_delay`` -> ``td3.policy_delay``, ``exploration`` ->
    ``exploration.kind``)."""
    out: dict[str, Any] = {name: {} for name in SECTIONS}
    for key, value in flat.items():
        if key == "exploration":
            out["exploration"]["kind"] = value
        elif (section := section_of(key)) is not None:
            out[section][key[4:] if key.startswith("td3_") else key] = value
        else:
            out[key] = value
    return out


def _migrate_v1(state: dict[str, Any]) -> dict[str, Any]:
    state = dict(state)
    sums, count = state.pop("pending_losses")
    state["agent"] = {**state["agent"], "losses": {"names": list(_V1_LOSSES), "sums": sums,
                                                   "counts": [int(count)] * len(_V1_LOSSES)}}
    state["exploration"] = state.pop("noise")
    state["losses"] = dict(zip(_V1_LOSSES, state["losses"])) if state["losses"] is not None else None
    state["algo"] = "ddpg"
    state["config"] = nest_flat_config(state["config"])
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
