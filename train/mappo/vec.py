"""Many decision envs stepped together for MAPPO: in this process (``workers=1``) or in worker processes.

Each env's step result is packed into arrays ordered by ``env.possible_agents``
(:func:`pack`). An env whose episode ended is reset at once with the next seed of its own
sequence, ``episode_seed(run_seed, env_index, counter)``, so the experience depends only on
the run seed and the env count, never on the worker count. Workers run envs only (numpy);
they set ``torch.set_num_threads(1)`` in case a task touches torch.
"""

from __future__ import annotations

import multiprocessing as mp
from collections.abc import Sequence
from typing import Any

import numpy as np

from train.mappo.tasks import get_task


def episode_seed(run_seed: int, env_index: int, counter: int) -> int:
    """Reset seed of env ``env_index``'s ``counter``-th episode (a 31-bit int)."""
    return int(np.random.SeedSequence([int(run_seed), int(env_index), int(counter)]).generate_state(1)[0] >> 1)


def pack(env: Any, obs: dict, infos: dict, rewards: dict | None = None, term: dict | None = None,
         trunc: dict | None = None) -> dict[str, Any]:
    """One env's step (or reset) as arrays over ``possible_agents``."""
    agents = env.possible_agents
    out = {
        "obs": np.stack([np.asarray(obs[a], np.float32) for a in agents]),
        "state": np.asarray(env.state(), np.float32),
        "decision": np.array([bool(infos[a].get("decision", True)) for a in agents]),
        "mask": np.stack([np.asarray(infos[a].get("action_mask", 1), np.int8) * np.ones(1, np.int8)
                          for a in agents]) if "action_mask" in infos[agents[0]] else None,
        "elapsed": float(max(float(infos[a].get("elapsed_s", 0.0)) for a in agents)),
        "rew": np.array([float(rewards[a]) for a in agents]) if rewards is not None else np.zeros(len(agents)),
        "term": np.array([bool(term[a]) for a in agents]) if term is not None else np.zeros(len(agents), bool),
        "trunc": np.array([bool(trunc[a]) for a in agents]) if trunc is not None else np.zeros(len(agents), bool),
    }
    out["done"] = bool(out["term"].any() or out["trunc"].any())
    if out["done"]:
        out["final_infos"] = {a: {k: v for k, v in infos[a].items() if isinstance(v, (int, float, str, bool))}
                              for a in agents}
    return out


class _EnvSlice:
    """The envs of one worker (or of the sequential vector)."""

    def __init__(self, task: str, task_kwargs: dict, indices: Sequence[int], run_seed: int) -> None:
        factory = get_task(task).factory
        self.envs = {i: factory(**task_kwargs) for i in indices}
        self.run_seed = run_seed

    def reset(self, counters: dict[int, int]) -> dict[int, dict]:
        out = {}
        for i, c in counters.items():
            env = self.envs[i]
            obs, infos = env.reset(seed=episode_seed(self.run_seed, i, c))
            out[i] = pack(env, obs, infos)
        return out

    def step(self, actions: dict[int, dict], counters: dict[int, int]) -> dict[int, dict]:
        """Step each env; an env that ends is reset with seed counter ``counters[i]`` and
        its result gets ``reset`` (the packed reset) beside the final step."""
        out = {}
        for i, act in actions.items():
            env = self.envs[i]
            res = pack(env, *_reorder(env.step(act)))
            if res["done"]:
                obs, infos = env.reset(seed=episode_seed(self.run_seed, i, counters[i]))
                res["reset"] = pack(env, obs, infos)
            out[i] = res
        return out

    def close(self) -> None:
        for env in self.envs.values():
            env.close()


def _reorder(step: tuple) -> tuple:
    obs, rew, term, trunc, infos = step
    return obs, infos, rew, term, trunc


def _worker(conn: Any, task: str, task_kwargs: dict, indices: list[int], run_seed: int) -> None:
    import torch

    torch.set_num_threads(1)
    sl = _EnvSlice(task, task_kwargs, indices, run_seed)
    try:
        while True:
            cmd, arg = conn.recv()
            if cmd == "reset":
                conn.send(sl.reset(arg))
            elif cmd == "step":
                conn.send(sl.step(*arg))
            elif cmd == "close":
                break
    finally:
        sl.close()
        conn.close()


class DecisionVector:
    """``num_envs`` envs of ``task``, in ``workers`` processes (1: in this process).

    ``counters[i]`` is how many episodes env i has started; resets use and advance it."""

    def __init__(self, task: str, task_kwargs: dict, num_envs: int, run_seed: int, workers: int = 1) -> None:
        self.num_envs, self.workers = int(num_envs), max(1, min(int(workers), int(num_envs)))
        self.counters = [0] * self.num_envs
        self.probe = get_task(task).factory(**task_kwargs)  # spaces and agent names
        self.agents = list(self.probe.possible_agents)
        if self.workers == 1:
            self._local = _EnvSlice(task, task_kwargs, range(self.num_envs), run_seed)
            self._conns: list[Any] = []
        else:
            ctx = mp.get_context("fork")
            self._parts = [list(range(self.num_envs))[w::self.workers] for w in range(self.workers)]
            self._conns, self._procs = [], []
            for part in self._parts:
                a, b = ctx.Pipe()
                p = ctx.Process(target=_worker, args=(b, task, task_kwargs, part, run_seed), daemon=True)
                p.start()
                b.close()
                self._conns.append(a)
                self._procs.append(p)

    def _dispatch(self, cmd: str, per_env: dict[int, Any], extra: dict[int, int] | None = None) -> list[dict]:
        if not self._conns:
            res = self._local.reset(per_env) if cmd == "reset" else self._local.step(per_env, extra or {})
        else:
            res = {}
            for conn, part in zip(self._conns, self._parts):
                sub = {i: per_env[i] for i in part if i in per_env}
                conn.send((cmd, sub if cmd == "reset" else (sub, {i: extra[i] for i in sub})))
            for conn in self._conns:
                res.update(conn.recv())
        return [res[i] for i in sorted(res)]

    def reset_all(self) -> list[dict]:
        """Reset every env (a new episode each, from its counter)."""
        out = self._dispatch("reset", {i: self.counters[i] for i in range(self.num_envs)})
        self.counters = [c + 1 for c in self.counters]
        return out

    def step(self, actions: list[dict]) -> list[dict]:
        out = self._dispatch("step", dict(enumerate(actions)), {i: self.counters[i] for i in range(self.num_envs)})
        for i, r in enumerate(out):
            if r["done"]:
                self.counters[i] += 1
        return out

    def close(self) -> None:
        for conn in self._conns:
            try:
                conn.send(("close", None))
            except (BrokenPipeError, OSError):
                pass
        for p in getattr(self, "_procs", []):
            p.join(timeout=5)
        if not self._conns:
            self._local.close()
        self.probe.close()
