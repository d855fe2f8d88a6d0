"""Evaluate a MAPPO actor file (greedy) or a uniform-random policy on any MAPPO task.

``python -m train.mappo_eval --task pass-and-score --actor RUN/actors/actor-N.pt --episodes 200 --seed 48000
[--random] [--out results.json]``

For the decision tasks (keepaway, attack-3v2, attack-drill) the project's evaluation is ``ssl-marl eval-task``;
this one serves the toy tasks and the continuous drill (whose actor has a Gaussian head: the
greedy action is its mean). Episode i uses seed ``seed + i``. Prints (and writes) the mean score
with a 95 % interval (Wilson for 0/1 scores, else t) and the outcome counts.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import Any

import numpy as np
import torch

from ssl_marl.io import atomic_write_json
from ssl_marl.runners.statistics import wilson_interval
from ssl_marl.skills.checkpoint import read_actor_file

from train.mappo.algorithm import ActorNet
from train.mappo.tasks import get_task


def load_actor_net(path: str | Path) -> tuple[ActorNet, dict[str, Any]]:
    """The trainer's actor network from a decision actor file (discrete or continuous) and the
    file's metadata with its observation scaling ``obs_mean`` / ``obs_std``."""
    state, d = read_actor_file(path, "decision")
    n_agents = len(d["agent_ids"]) if d.get("agent_ids") else 0
    net = ActorNet(int(d["obs_dim"]) + n_agents, int(d["n_options"]), [int(h) for h in d["hidden"]],
                   bool(d.get("continuous")))
    net.load_state_dict({k: v for k, v in state.items() if k not in ("obs_mean", "obs_std")})
    net.eval()
    return net, {**d, "obs_mean": state["obs_mean"], "obs_std": state["obs_std"]}


def evaluate(task: str, episodes: int, seed: int, actor: str | Path | None = None,
             task_kwargs: dict | None = None) -> dict[str, Any]:
    """Greedy ``actor`` (or uniform random actions when None) over ``episodes`` episodes."""
    spec = get_task(task)
    env = spec.factory(**(task_kwargs or {}))
    agents = list(env.possible_agents)
    net, meta = load_actor_net(actor) if actor is not None else (None, {})
    rng = np.random.default_rng(seed)
    scores, outcomes, passed = [], {}, []
    for i in range(episodes):
        obs, infos = env.reset(seed=seed + i)
        while env.agents:
            act = {}
            for k, a in enumerate(agents):
                space = env.action_space(a)
                if net is None:
                    if hasattr(space, "n"):
                        legal = np.flatnonzero(np.asarray(infos[a].get("action_mask", np.ones(space.n))))
                        act[a] = int(rng.choice(legal))
                    else:
                        act[a] = rng.uniform(space.low, space.high).astype(np.float32)
                    continue
                x = (torch.as_tensor(np.asarray(obs[a], np.float32)) - meta["obs_mean"]) / meta["obs_std"]
                if meta.get("agent_ids"):
                    x = torch.cat([x, torch.nn.functional.one_hot(torch.tensor(k), len(agents)).float()])
                with torch.no_grad():
                    out = net(x).numpy()
                if net.continuous:
                    act[a] = (space.low + (np.clip(out, -1, 1) + 1) * 0.5 * (space.high - space.low)).astype(np.float32)
                else:
                    mask = np.asarray(infos[a].get("action_mask", np.ones_like(out)), bool)
                    act[a] = int(np.argmax(np.where(mask, out, -np.inf)))
            obs, _, _, _, infos = env.step(act)
        fi = infos[agents[0]]
        scores.append(float(fi.get(spec.score_key, np.nan)))
        if "passed" in fi:
            passed.append(float(fi["passed"]))
        o = str(fi.get("outcome", ""))
        outcomes[o] = outcomes.get(o, 0) + 1
    env.close()
    s = np.asarray(scores)
    out: dict[str, Any] = {"task": task, "policy": str(actor) if actor else "random", "episodes": episodes,
                           "seed": seed, "mean_score": float(s.mean()), "score_key": spec.score_key,
                           "outcomes": outcomes}
    if passed:
        out["pass_rate"] = float(np.mean(passed))
    if set(np.unique(s)) <= {0.0, 1.0}:
        out["ci95"] = list(wilson_interval(int(s.sum()), len(s)))
    else:
        half = 1.96 * float(s.std(ddof=1)) / np.sqrt(len(s)) if len(s) > 1 else float("nan")
        out["ci95"] = [float(s.mean()) - half, float(s.mean()) + half]
    return out


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m train.mappo_eval", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--task", required=True, help="MAPPO task name (train/mappo/tasks.py)")
    p.add_argument("--actor", type=Path, default=None, help="MAPPO actor file (default: uniform random policy)")
    p.add_argument("--episodes", type=int, default=100, help="episodes (seed + i)")
    p.add_argument("--seed", type=int, default=48000, help="first episode seed (never a training/validation seed)")
    p.add_argument("--out", type=Path, default=None, help="write the result JSON here")
    args = p.parse_args(argv)
    res = evaluate(args.task, args.episodes, args.seed, args.actor)
    if args.out:
        atomic_write_json(args.out, res)
    print(json.dumps(res))
    return 0
