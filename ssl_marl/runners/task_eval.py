"""Evaluation of a decision policy on a decision-level task (``ssl-marl eval-task``).

Protocol (:func:`evaluate_task`): ``episodes`` episodes of the task
(:data:`ssl_marl.decisions.DECISION_TASKS`), episode ``i`` reset with seed ``seed + i``
(the task draws its scene from it; a random policy draws from it too), one policy for
all agents (:data:`ssl_marl.decisions.DECISION_POLICIES`: learned, handcoded, random,
always-hold). Episodes are independent jobs of the project's pool
(:mod:`ssl_marl.runners.pool`, chunks of at most 25), so the results do not depend on
``workers`` or the backend.

Scores: keepaway -- ``mean_duration_s`` with its 95 % t-interval (Student's t on the
episodes' durations); attack-3v2 and the attack drills -- ``goal_rate`` with its 95 % Wilson interval. Both
also list the outcome counts, a duration summary and every episode (seed, outcome,
duration, decisions, option counts). Throughput (``decisions_per_s``,
``sim_s_per_s``: simulated seconds per wall second, summed over workers' wall time) is
reported but not part of the deterministic results.

Outputs in ``out``: ``results.json``, ``episodes.csv.gz`` and ``manifest.json``
(:func:`~ssl_marl.runners.result.write_result_folder`) and ``duration_hist.png`` (histogram of the
episode durations, :func:`ssl_marl.runners.plots.write_time_histogram`).
"""

from __future__ import annotations

import math
import os
import time
from collections import Counter
from pathlib import Path
from typing import Any

import numpy as np

from .plots import write_time_histogram
from .pool import chunk_indices, run_pool, validate_backend
from .provenance import build_manifest
from .result import write_result_folder
from .statistics import t_interval, time_summary, wilson_interval

TASK_SCORES = {"keepaway": "duration", "attack-3v2": "goal", "attack-drill": "goal", "attack-drill-ssl": "goal",
               "attack-drill-defended": "goal", "attack-drill-mix": "goal"}
DEFAULT_SEEDS = {"keepaway": 40_000, "attack-3v2": 41_000, "attack-drill": 43_000, "attack-drill-ssl": 153_000,
                 "attack-drill-defended": 154_000, "attack-drill-mix": 156_000}

_CACHE: dict[tuple, Any] = {}


def _env_and_policy(task: str, policy: str, actor: str | None, realism: str, field: str, tracker: Any):
    from ..decisions import make_decision_env, make_decision_policy

    key = (task, policy, actor, realism, field, tracker)
    got = _CACHE.get(key)
    if got is None:
        if policy in ("learned", "improved"):
            import torch

            torch.set_num_threads(1)
        env = make_decision_env(task, field=field, realism=realism, tracker=tracker)
        pol = make_decision_policy(policy, task, seed=0, actor=actor)
        got = _CACHE[key] = (env, pol)
    return got


def run_task_episode(index: int, seed: int, task: str, policy: str, actor: str | None = None,
                     realism: str = "none", field: str = "div_b", tracker: Any = "auto") -> dict:
    """Episode ``index`` (reset seed ``seed + index``); returns its summary (deterministic).
    ``tracker``: see :func:`~ssl_marl.envs.tracking.resolve_tracker`."""
    from ..decisions.policies import run_episode

    env, pol = _env_and_policy(task, policy, actor, realism, field, tracker)
    t0 = time.perf_counter()
    r = run_episode(env, pol, seed=seed + index)
    wall = time.perf_counter() - t0
    ep = {"index": index, "seed": seed + index, "outcome": r["outcome"], "duration_s": float(r["t_s"]),
          "decisions": int(r["decisions"]), "steps": int(r["steps"]), "options": r["options"]}
    for k in ("goal", "passes_kicked", "passes_completed"):
        if k in r:
            ep[k] = r[k]
    return {"episode": ep, "wall_s": wall, "ticks": int(env.ticks)}


def _chunk_worker(job: tuple) -> list[dict]:
    indices, rest = job[0], job[1:]
    return [run_task_episode(i, *rest) for i in indices]


def task_results(task: str, policy: str, eps: list[dict], *, seed: int, actor: str | None,
                 config: dict, throughput: dict) -> dict:
    """eval-task's results dict from per-episode records (``duration_s``, ``outcome``,
    ``decisions``, ``options``; attack: ``goal``; keepaway: ``passes_*``): the score with its
    95 % interval (t-interval of the mean duration, or Wilson of the goal rate), outcome and
    option counts, and every episode."""
    n = len(eps)
    durations = [e["duration_s"] for e in eps]
    results: dict[str, Any] = {
        "task": task, "policy": policy, "actor": actor, "episodes": n, "seed": seed,
        "seeds": f"episode i uses seed {seed} + i",
        "config": config,
        "outcomes": dict(sorted(Counter(e["outcome"] for e in eps).items())),
        "duration_s": time_summary(durations),
    }
    if TASK_SCORES[task] == "duration":
        lo, hi = t_interval(durations)
        results["mean_duration_s"] = float(np.mean(durations))
        results["mean_duration_ci95"] = [lo, hi]
    else:
        goals = sum(int(bool(e.get("goal", e["outcome"] == "goal"))) for e in eps)
        lo, hi = wilson_interval(goals, n)
        results["goals"] = goals
        results["goal_rate"] = goals / n
        results["goal_rate_ci95"] = [lo, hi]
    opt_tot: Counter = Counter()
    for e in eps:
        opt_tot.update(e["options"])
    results["options"] = dict(opt_tot)
    results["decisions"] = sum(e["decisions"] for e in eps)
    if "passes_kicked" in eps[0]:
        results["passes_kicked"] = int(sum(e.get("passes_kicked", 0) for e in eps))
        results["passes_completed"] = int(sum(e.get("passes_completed", 0) for e in eps))
    results["throughput"] = throughput
    results["episodes_detail"] = eps
    return results


def write_task_results(results: dict, out: str | os.PathLike) -> None:
    """The result folder (:func:`~ssl_marl.runners.result.write_result_folder`) and
    ``out/duration_hist.png`` for :func:`task_results`."""
    d = Path(out)
    d.mkdir(parents=True, exist_ok=True)
    write_result_folder(d, results, build_manifest(
        rules={"runner": "eval-task", "task": results["task"], "policy": results["policy"], **results["config"]},
        seeds={"seed": results["seed"], "episodes": results["episodes"]}, actor_files=[results["actor"]]))
    task, policy, n = results["task"], results["policy"], results["episodes"]
    realism = results["config"].get("realism", "none")
    if TASK_SCORES[task] == "duration":
        lo, hi = results["mean_duration_ci95"]
        title = (f"{task} ({policy}, realism {realism}): mean {results['mean_duration_s']:.2f} s "
                 f"[{lo:.2f}, {hi:.2f}], n={n}")
    else:
        lo, hi = results["goal_rate_ci95"]
        title = f"{task} ({policy}, realism {realism}): goal rate {results['goal_rate']:.3f} [{lo:.3f}, {hi:.3f}], n={n}"
    durations = [e["duration_s"] for e in results["episodes_detail"]]
    hi_t = max(durations) if durations else 1.0
    write_time_histogram(durations, d / "duration_hist.png", title, max_time_s=math.ceil(hi_t),
                         xlabel="episode duration (s)", bin_s=max(0.25, math.ceil(hi_t) / 60))


def evaluate_task(task: str, policy: str, episodes: int = 1000, seed: int | None = None, workers: int | None = 1,
                  realism: str = "none", field: str = "div_b", actor: str | None = None,
                  out: str | os.PathLike | None = None, progress: bool = True, backend: str = "local",
                  address: str | None = None, tracker: Any = "auto") -> dict:
    """Evaluate ``policy`` on ``task`` (module docstring); returns the results dict (also
    written to ``out/results.json`` with ``out/duration_hist.png`` when ``out`` is given).

    Args:
        task: "keepaway", "attack-3v2", "attack-drill", "attack-drill-ssl", "attack-drill-defended" or
            "attack-drill-mix".
        policy: "learned", "handcoded", "random", "always-hold" (keepaway only) or "improved".
        episodes: number of episodes.
        seed: episode i uses seed + i (default: 40000 keepaway, 41000 attack-3v2, 43000 attack-drill,
            153000 attack-drill-ssl, 154000 attack-drill-defended, 156000 attack-drill-mix).
        workers: worker processes (or Ray tasks in flight); results do not depend on it.
        realism: "none" or "realistic".
        field: "div_b" or "div_a".
        actor: a learned decision actor file (policy "learned"; default the shipped one) or a
            value actor file (policy "improved"; default the shipped one).
        backend, address: see :mod:`ssl_marl.runners.pool`.
        tracker: "auto" (on unless realism is "none"), "on" or "off": the options'
            tactics, the fixed behaviours and the observations read
            :class:`~ssl_marl.envs.tracking.TrackedVisionEnv`'s tracked state.
    """
    from ..decisions import DECISION_POLICIES, DECISION_TASKS, make_decision_policy

    if task not in DECISION_TASKS or task not in TASK_SCORES:
        raise ValueError(f"unknown decision task {task!r}; expected one of {tuple(TASK_SCORES)}")
    if policy not in DECISION_POLICIES:
        raise ValueError(f"unknown policy {policy!r}; expected one of {tuple(DECISION_POLICIES)}")
    if actor is not None and policy not in ("learned", "improved"):
        raise ValueError(f"--actor is only used with --policy learned or improved, not {policy!r}")
    if actor is not None and not Path(actor).is_file():
        raise FileNotFoundError(f"actor file {actor} does not exist")
    if not isinstance(episodes, int) or isinstance(episodes, bool) or episodes < 1:
        raise ValueError(f"episodes must be a positive integer, got {episodes!r}")
    if realism not in ("none", "realistic"):
        raise ValueError(f"realism must be 'none' or 'realistic', got {realism!r}")
    if field not in ("div_a", "div_b"):
        raise ValueError(f"field must be 'div_a' or 'div_b', got {field!r}")
    seed = DEFAULT_SEEDS[task] if seed is None else int(seed)
    validate_backend(backend, workers, address)
    from ..envs.tracking import resolve_tracker

    use_tracker = resolve_tracker(tracker, realism)
    make_decision_policy(policy, task, seed=0, actor=actor)  # fail here (missing module / actor), not in workers
    t0 = time.perf_counter()
    jobs = [(chunk, seed, task, policy, actor, realism, field, use_tracker)
            for chunk in chunk_indices(episodes, workers)]
    res = [r for chunk in run_pool(_chunk_worker, jobs, workers, f"eval-task {task} ({policy})", progress,
                                   unit="ep", backend=backend, address=address, size=len, total=episodes)
           for r in chunk]
    wall = time.perf_counter() - t0
    eps = [r["episode"] for r in res]
    worker_wall = sum(r["wall_s"] for r in res)
    durations = [e["duration_s"] for e in eps]
    decisions = sum(e["decisions"] for e in eps)
    throughput = {"wall_time_s": wall, "episode_wall_s_sum": worker_wall,
                  "decisions_per_s": decisions / worker_wall if worker_wall > 0 else None,
                  "sim_s_per_s": sum(durations) / worker_wall if worker_wall > 0 else None,
                  "ticks_per_s": sum(r["ticks"] for r in res) / worker_wall if worker_wall > 0 else None,
                  "note": "per worker process (episode wall time summed over workers); not deterministic"}
    results = task_results(task, policy, eps, seed=seed, actor=actor, throughput=throughput,
                           config={"realism": realism, "tracker": use_tracker, "field": field, "workers": workers,
                                   "backend": backend})
    if out is not None:
        write_task_results(results, out)
    return results


__all__ = ["evaluate_task", "run_task_episode", "task_results", "write_task_results", "TASK_SCORES", "DEFAULT_SEEDS"]
