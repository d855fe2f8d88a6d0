"""The paper's skill evaluation protocol (section 5.1): random spawns, N episodes,
success rate, time to success, failure reasons; JSON + a time histogram.

Each episode ``i`` is seeded with :func:`ssl_marl.io.episode_seed` (seed, i), so the
result does not depend on the number of worker processes.
"""

from __future__ import annotations

import multiprocessing as mp
import sys
import time
from collections import Counter
from pathlib import Path
from typing import Any

import numpy as np

from ..io import atomic_savefig, atomic_write_json, episode_seed, time_summary, wilson_interval

TASKS = ("go-to-ball", "aim-to-shoot", "pass", "receive")
PASSING_TASKS = ("pass", "receive")  # issue 11: envs and per-step actions in ssl_marl.skills.pass_tasks
PAPER = {"go-to-ball": {"baseline": 1.0, "learned": 0.999}, "aim-to-shoot": {"baseline": 0.71, "learned": 0.772},
         "pass": {"baseline": None, "learned": None}, "receive": {"baseline": None, "learned": None}}


def _skill_name(task: str) -> str:
    return task.replace("-", "_")


def resolve_policy(task: str, policy: str) -> tuple[str, str | None]:
    """("baseline"|"learned", checkpoint path or None); raises clear errors."""
    if task not in TASKS:
        raise ValueError(f"unknown skill {task!r}; expected one of {TASKS}")
    if policy in ("baseline", "learned"):
        if policy == "learned":
            from .learned import PRETRAINED
            from .passing import PRETRAINED as PASSING_PRETRAINED

            PRETRAINED = {**PRETRAINED, **PASSING_PRETRAINED}

            if not PRETRAINED[_skill_name(task)].exists():
                raise FileNotFoundError(f"no shipped learned actor for {task} at {PRETRAINED[_skill_name(task)]}")
        return policy, None
    path = Path(policy)
    if not path.exists():
        raise FileNotFoundError(f"checkpoint {policy!r} does not exist (use 'baseline', 'learned' or a path)")
    return "learned", str(path)


def _make_env(task: str, env_kwargs: dict):
    from .wrappers import AimToShootEnv, GoToBallEnv

    if task in PASSING_TASKS:
        from .pass_tasks import make_task_env

        return make_task_env(task, env_kwargs)
    return GoToBallEnv(**env_kwargs) if task == "go-to-ball" else AimToShootEnv(**env_kwargs)


def _run_episodes(args: tuple) -> list[dict]:
    task, kind, checkpoint, env_kwargs, seed, indices = args
    from . import make_skill
    from .wrappers import task_action

    env = _make_env(task, env_kwargs)
    skill = make_skill(_skill_name(task), kind, env.field, env.robot_params, env.ball_params, checkpoint=checkpoint)
    out = []
    for i in indices:
        env.reset(seed=episode_seed(seed, i))
        skill.reset()
        ret, steps = 0.0, 0
        while True:
            if task in PASSING_TASKS:
                from .pass_tasks import skill_task_action

                a = skill_task_action(task, env, skill)
            else:
                a = task_action(task, skill.act(env.seen(), 0))
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
                   progress: bool = True, realtime: bool = False) -> dict[str, Any]:
    """Run the protocol; returns the summary dict (and writes ``out/results.json`` and
    ``out/time_hist.png`` when ``out`` is given)."""
    kind, checkpoint = resolve_policy(task, policy)
    if not isinstance(episodes, int) or episodes < 1:
        raise ValueError(f"episodes must be a positive integer, got {episodes!r}")
    if not isinstance(workers, int) or workers < 1:
        raise ValueError(f"workers must be a positive integer, got {workers!r}")
    env_kwargs = {"field": field, "realism": realism, "realtime": realtime}
    chunk = max(1, min(25, episodes // (workers * 4) or 1))
    jobs = [(task, kind, checkpoint, env_kwargs, seed, list(range(s, min(s + chunk, episodes))))
            for s in range(0, episodes, chunk)]
    t0 = time.perf_counter()
    results: list[dict] = []
    from tqdm import tqdm

    bar = tqdm(total=episodes, desc=f"eval {task} ({policy})", disable=not progress, unit="ep", file=sys.stderr)
    if workers == 1:
        for job in jobs:
            res = _run_episodes(job)
            results += res
            bar.update(len(res))
    else:
        # spawn, not fork: forking a process whose torch has started its thread pool (a
        # learned skill loaded earlier in the same process) can deadlock the workers
        ctx = mp.get_context("spawn")
        with ctx.Pool(workers) as pool:
            for res in pool.imap_unordered(_run_episodes, jobs):
                results += res
                bar.update(len(res))
    bar.close()
    results.sort(key=lambda r: r["episode"])
    wall = time.perf_counter() - t0
    n_succ = sum(r["success"] for r in results)
    times = [r["time_s"] for r in results if r["success"]]
    lo, hi = wilson_interval(n_succ, episodes)
    meta: dict[str, Any] = {}
    if kind == "learned":
        from .learned import load_policy
        from .passing import load_passing_policy

        loader = load_passing_policy if task in PASSING_TASKS else load_policy
        meta = dict(loader(_skill_name(task), checkpoint)[1])
    summary = {
        "skill": task, "policy": policy, "kind": kind, "checkpoint": checkpoint, "episodes": episodes, "seed": seed,
        "success_rate": n_succ / episodes, "success_ci95": [lo, hi], "successes": n_succ,
        "time_to_success_s": time_summary(times),
        "failure_reasons": dict(Counter(r["failure_reason"] for r in results if not r["success"])),
        "mean_return": float(np.mean([r["return"] for r in results])),
        "paper_success_rate": PAPER[task][kind],
        "config": env_kwargs, "wall_time_s": wall, "workers": workers, "checkpoint_metadata": _jsonable(meta),
        "episodes_detail": results,
    }
    if out is not None:
        out = Path(out)
        atomic_write_json(out / "results.json", summary)
        plot_time_histogram(times, out / "time_hist.png",
                            title=f"{task}, {policy}: time to success ({n_succ}/{episodes} succeeded)")
    return summary


def _jsonable(d: Any) -> Any:
    if isinstance(d, dict):
        return {str(k): _jsonable(v) for k, v in d.items()}
    if isinstance(d, (list, tuple)):
        return [_jsonable(v) for v in d]
    if isinstance(d, (str, int, float, bool)) or d is None:
        return d
    return str(d)


def plot_time_histogram(times: list[float], path: Path, title: str, bins: int = 30) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 4))
    if times:
        ax.hist(times, bins=bins, color="tab:blue", edgecolor="black")
    ax.set_xlabel("time (s)")
    ax.set_ylabel("episodes")
    ax.set_title(title, fontsize=10)
    fig.tight_layout()
    atomic_savefig(fig, path, dpi=110)
    plt.close(fig)
