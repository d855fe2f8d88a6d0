"""The paper's skill evaluation protocol (section 5.1): random spawns, N episodes,
success rate, time to success, failure reasons; JSON + a time histogram.

Each episode ``i`` is seeded with :func:`ssl_marl.io.episode_seed` (seed, i), so the
result does not depend on the number of worker processes or the backend (local pool
or Ray, :mod:`~ssl_marl.runners.pool`).
"""

from __future__ import annotations

import time
from collections import Counter
from pathlib import Path
from typing import Any

import numpy as np

from ..io import episode_seed
from .statistics import time_summary, wilson_interval
from .plots import write_time_histogram
from .pool import chunk_indices, run_pool, validate_backend
from .provenance import build_manifest
from .result import write_result_folder


def _skill_name(task: str) -> str:
    from ..skills.registry import get_skill, get_task

    get_task(task)  # ValueError for a skill without a task
    return get_skill(task).name


def resolve_policy(task: str, policy: str) -> tuple[str, str | None]:
    """("baseline"|"learned", checkpoint path or None); raises clear errors."""
    from ..skills.registry import cli_choices, get_skill

    if task not in cli_choices():
        raise ValueError(f"unknown skill {task!r}; expected one of {cli_choices()}")
    if policy in ("baseline", "learned"):
        if policy == "learned":
            actor = get_skill(task).actor
            if actor is None or not actor.exists():
                raise FileNotFoundError(f"no shipped learned actor for {task} at {actor}")
        return policy, None
    path = Path(policy)
    if not path.exists():
        raise FileNotFoundError(f"checkpoint {policy!r} does not exist (use 'baseline', 'learned' or a path)")
    return "learned", str(path)


def _make_env(task: str, env_kwargs: dict):
    from ..skills.registry import get_task, resolve_ref

    return resolve_ref(get_task(task).entry_point)(**env_kwargs)


def _run_episodes(args: tuple) -> list[dict]:
    task, kind, checkpoint, env_kwargs, seed, indices = args
    from ..skills import make_skill
    from ..skills.registry import get_task

    env = _make_env(task, env_kwargs)  # tracker=True: the skill reads tracked, latency-compensated vision
    task_def = get_task(task)
    skill = make_skill(_skill_name(task), kind, env.field, env.robot_params, env.ball_params, checkpoint=checkpoint)
    out = []
    for i in indices:
        env.reset(seed=episode_seed(seed, i))
        skill.reset()
        ret, steps = 0.0, 0
        while True:
            a = task_def.skill_action(env, skill)
            _, r, term, trunc, info = env.step(a)
            ret += r
            steps += 1
            if term or trunc:
                break
        out.append({"episode": int(i), "success": bool(info["is_success"]), "time_s": float(info["time_s"]),
                    "failure_reason": info["failure_reason"], "return": float(ret), "steps": steps})
    env.close()
    return out


def evaluate_skill(task: str, policy: str = "baseline", episodes: int = 1000, seed: int = 0, workers: int = 1,
                   out: str | Path | None = None, realism: str = "none", field: str = "div_b",
                   progress: bool = True, realtime: bool = False, backend: str = "local",
                   address: str | None = None, tracker: Any = "auto",
                   task_options: dict[str, Any] | None = None) -> dict[str, Any]:
    """Run the protocol; returns the summary dict (and writes ``out/results.json`` and
    ``out/time_hist.png`` when ``out`` is given).

    ``task_options``: keyword arguments of the task's env beyond the protocol's own
    (e.g. receive's ``{"interceptors": 1, "hold_s": 0.1}``: the pass pressed by an
    interceptor); checked by building the env once (ValueError naming the option).

    ``workers`` processes (local) or Ray tasks in flight (``backend="ray"``, None: the
    cluster's CPUs; ``address``: the cluster, None = a local Ray instance). ``tracker``:
    "auto" (on unless realism is "none"), "on" or "off"
    (:class:`~ssl_marl.envs.tracking.TrackedVisionEnv`)."""
    kind, checkpoint = resolve_policy(task, policy)
    if not isinstance(episodes, int) or episodes < 1:
        raise ValueError(f"episodes must be a positive integer, got {episodes!r}")
    validate_backend(backend, workers, address)
    from ..envs.tracking import resolve_tracker

    use_tracker = resolve_tracker(tracker, realism)
    meta: dict[str, Any] = {}
    if kind == "learned":  # a wrong-skill checkpoint fails here, not in every worker
        from ..skills.learned import load_policy

        meta = dict(load_policy(_skill_name(task), checkpoint)[1])
    env_kwargs = {"field": field, "realism": realism, "realtime": realtime, "tracker": use_tracker,
                  **check_task_options(task, task_options)}
    jobs = [(task, kind, checkpoint, env_kwargs, seed, chunk) for chunk in chunk_indices(episodes, workers)]
    t0 = time.perf_counter()
    results = [r for chunk in run_pool(_run_episodes, jobs, workers, f"eval {task} ({policy})", progress, unit="ep",
                                       backend=backend, address=address, size=len, total=episodes)
               for r in chunk]
    wall = time.perf_counter() - t0
    n_succ = sum(r["success"] for r in results)
    times = [r["time_s"] for r in results if r["success"]]
    lo, hi = wilson_interval(n_succ, episodes)
    summary = {
        "skill": task, "policy": policy, "kind": kind, "checkpoint": checkpoint, "episodes": episodes, "seed": seed,
        "success_rate": n_succ / episodes, "success_ci95": [lo, hi], "successes": n_succ,
        "time_to_success_s": time_summary(times),
        "failure_reasons": dict(Counter(r["failure_reason"] for r in results if not r["success"])),
        "mean_return": float(np.mean([r["return"] for r in results])),
        "paper_success_rate": _reference(task, kind),
        "config": env_kwargs, "wall_time_s": wall, "workers": workers, "backend": backend,
        "checkpoint_metadata": _jsonable(meta),
        "episodes_detail": results,
    }
    if out is not None:
        out = Path(out)
        write_result_folder(out, summary, build_manifest(
            rules={"runner": "eval-skill", "skill": task, "policy": policy, **env_kwargs},
            seeds={"seed": seed, "episodes": episodes}, actor_files=[checkpoint]))
        write_time_histogram(times, out / "time_hist.png",
                             title=f"{task}, {policy}: time to success ({n_succ}/{episodes} succeeded)")
    return summary


PROTOCOL_OPTIONS = ("field", "realism", "realtime", "tracker")  #: env options the protocol sets itself


def check_task_options(task: str, options: dict[str, Any] | None) -> dict[str, Any]:
    """``options`` (None: none) if the task's env accepts them, else ValueError naming
    the offending option (one of the protocol's own, or one the env refuses)."""
    options = dict(options or {})
    clash = sorted(set(options) & set(PROTOCOL_OPTIONS))
    if clash:
        raise ValueError(f"task option(s) {clash} are set by the protocol's own flags ({PROTOCOL_OPTIONS})")
    if options:
        try:
            _make_env(task, options).close()
        except TypeError as e:
            raise ValueError(f"task option(s) {sorted(options)} not accepted by the {task} task: {e}") from None
    return options


def _reference(task: str, kind: str) -> float | None:
    from ..skills.registry import get_skill

    return get_skill(task).reference.get(kind)


def _jsonable(d: Any) -> Any:
    if isinstance(d, dict):
        return {str(k): _jsonable(v) for k, v in d.items()}
    if isinstance(d, (list, tuple)):
        return [_jsonable(v) for v in d]
    if isinstance(d, (str, int, float, bool)) or d is None:
        return d
    return str(d)
