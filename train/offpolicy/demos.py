"""Demonstration burn-in: checked demonstration transitions into the replay before training.

A demonstration source is a ``"module:function"`` (config ``demo_fn``) called as
``fn(n_steps=..., seed=..., **env_kwargs)`` that yields
:class:`ssl_marl.skills.demos.Transition` tuples in the env's own spaces (actions in
the env's units); :func:`fill_replay` checks each against the spaces, rescales the
action to the actor's [-1, 1] and stores it.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from typing import Any

import numpy as np
from tqdm import tqdm

from train.offpolicy.evaluate import ActionScaler
from train.offpolicy.replay import ReplayBuffer

#: on_episode(transitions stored so far, return, length, is_success or None, summed reward terms)
EpisodeCallback = Callable[[int, float, int, Any, Mapping[str, float]], None]


def check_demo(tr: Any, n: int, obs_dim: int, scaler: ActionScaler) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Demonstration transition ``n`` as (obs, action in [-1, 1], next_obs); ValueError naming what
    does not fit the env's spaces."""
    obs = np.asarray(tr.obs, np.float32)
    next_obs = np.asarray(tr.next_obs, np.float32)
    act = np.asarray(tr.action, np.float64)
    problems = []
    if obs.shape != (obs_dim,) or next_obs.shape != (obs_dim,):
        problems.append(f"obs shapes {obs.shape}/{next_obs.shape} != ({obs_dim},)")
    if act.shape != scaler.low.shape:
        problems.append(f"action shape {act.shape} != {scaler.low.shape}")
    elif np.any(act < scaler.low - 1e-5) or np.any(act > scaler.high + 1e-5):
        problems.append(f"action {act} outside [{scaler.low}, {scaler.high}]")
    if not (np.all(np.isfinite(obs)) and np.all(np.isfinite(next_obs)) and np.isfinite(tr.reward)):
        problems.append("non-finite obs or reward")
    if problems:
        raise ValueError(f"demo transition {n} does not fit the env's spaces: " + "; ".join(problems))
    return obs, scaler.from_env(np.clip(act, scaler.low, scaler.high)), next_obs


def fill_replay(demos: Iterable[Any], n_steps: int, buffer: ReplayBuffer, scaler: ActionScaler, obs_dim: int,
                reward_scale: float, on_episode: EpisodeCallback, progress: bool = True) -> int:
    """Store the first ``n_steps`` transitions of ``demos`` (rewards times ``reward_scale``); call
    ``on_episode`` at each episode end; return ``n_steps``. ValueError if a transition does not fit
    the spaces or the source runs dry."""
    chunk: dict[str, list[Any]] = {k: [] for k in ("obs", "act", "rew", "next_obs", "term")}
    ret, length, terms = 0.0, 0, {}  # type: ignore[var-annotated]

    def flush() -> None:
        if chunk["obs"]:
            buffer.add(np.stack(chunk["obs"]), np.stack(chunk["act"]), np.asarray(chunk["rew"]) * reward_scale,
                       np.stack(chunk["next_obs"]), np.asarray(chunk["term"]))
            for v in chunk.values():
                v.clear()

    bar = tqdm(total=n_steps, desc="demo burn-in", unit="step", disable=not progress, dynamic_ncols=True)
    n = 0
    for n, tr in enumerate(demos, 1):
        obs, act, next_obs = check_demo(tr, n, obs_dim, scaler)
        chunk["obs"].append(obs)
        chunk["act"].append(act)
        chunk["rew"].append(float(tr.reward))
        chunk["next_obs"].append(next_obs)
        chunk["term"].append(float(bool(tr.terminated)))
        ret, length = ret + float(tr.reward), length + 1
        info = tr.info if isinstance(tr.info, Mapping) else {}
        for k, v in (info.get("reward_terms") or {}).items():
            terms[k] = terms.get(k, 0.0) + float(v)
        if tr.terminated or tr.truncated:
            on_episode(n, ret, length, info.get("is_success"), terms)
            ret, length, terms = 0.0, 0, {}
        if len(chunk["obs"]) >= 4096:
            flush()
        bar.update(1)
        if n >= n_steps:
            break
    flush()
    bar.close()
    if n < n_steps:
        raise ValueError(f"demo source produced {n} transitions, expected {n_steps}")
    return n_steps
