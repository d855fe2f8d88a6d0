"""The paper's tactic evaluation (section 5.2): go-to-ball-and-shoot from random scenes.

Protocol (:func:`evaluate_tactic`): per episode, one blue robot (random position,
random heading) and the ball (random position) are placed on an otherwise empty
field; the env referee is on with ``after_goal="terminate"``. The
:class:`~ssl_marl.plays.shoot.GoToBallAndShoot` tactic runs until a goal or
``max_time_s`` (15 s). A goal by blue is a success (its time is the goal event's
simulated time); an own goal or the time limit is a failure. The paper reports
75.5 % success, 7.49 s mean, 3.87 s std with learned skills (2018 Division A field).

Scenes: episode i uses ``episode_seed(seed, i)`` (numpy ``SeedSequence([seed, i])``)
for both the scene RNG and the env reset, so results depend only on ``seed`` and the
episode count, never on the number of worker processes or the backend (local pool
or Ray, :mod:`~ssl_marl.runners.pool`). Positions are uniform over
the playing area shrunk by 0.1 m; the robot starts at least 0.3 m from the ball.

Outputs in ``out``: ``results.json``, ``episodes.csv.gz`` and ``manifest.json``
(:func:`~ssl_marl.runners.result.write_result_folder`) and ``time_hist.png`` (histogram of the successful episodes' times, like the paper's Figs. 4-5).
"""

from __future__ import annotations

import math
import os
import time
from pathlib import Path
from typing import Any

import numpy as np

from ..envs.deadline import ControlDeadline
from ..io import episode_seed
from .statistics import time_summary, wilson_interval
from .plots import write_time_histogram
from .pool import chunk_indices, run_pool, validate_backend
from .provenance import build_manifest
from .result import write_result_folder

PAPER_RESULT = {"success_rate": 0.755, "time_mean_s": 7.49, "time_std_s": 3.87, "episodes": 500}
SCENE_MARGIN_M = 0.1
MIN_ROBOT_BALL_DIST_M = 0.3


def sample_scene(rng: np.random.Generator, field) -> tuple[np.ndarray, np.ndarray]:
    """(ball (2,), robot pose (3,): x, y, heading) in the field frame (m, rad)."""
    lo = np.array([-field.half_length + SCENE_MARGIN_M, -field.half_width + SCENE_MARGIN_M])
    hi = -lo
    ball = rng.uniform(lo, hi)
    for _ in range(1000):
        xy = rng.uniform(lo, hi)
        if float(np.hypot(*(xy - ball))) >= MIN_ROBOT_BALL_DIST_M:
            break
    return ball, np.array([xy[0], xy[1], rng.uniform(-math.pi, math.pi)])


_ENV_CACHE: dict[tuple, Any] = {}

#: tactics ``evaluate_tactic(tactic=...)`` can run (CLI spelling -> class path); the
#: default is the paper's. Both take the same (field, robot, ball, skills, dt) arguments.
TACTIC_CHOICES = {"go-to-ball-and-shoot": "ssl_marl.plays.shoot:GoToBallAndShoot",
                  "dribble-and-shoot": "ssl_marl.plays.dribble_shoot:DribbleAndShoot"}


def tactic_class(name: str):
    """The tactic class for a name in :data:`TACTIC_CHOICES` (``_`` may replace ``-``)."""
    import importlib

    key = str(name).replace("_", "-")
    if key not in TACTIC_CHOICES:
        raise ValueError(f"tactic: unknown tactic {name!r}; expected one of {sorted(TACTIC_CHOICES)}")
    module, cls = TACTIC_CHOICES[key].split(":")
    return getattr(importlib.import_module(module), cls)


def _env(field: str, realism: Any, max_time_s: float, tracker: Any = "auto"):
    from ..envs import parallel_env
    from ..envs.tracking import with_tracker

    key = (field if isinstance(field, str) else repr(field), repr(realism), float(max_time_s), repr(tracker))
    env = _ENV_CACHE.get(key)
    if env is None:
        env = _ENV_CACHE[key] = with_tracker(parallel_env(n_blue=1, n_yellow=0, field=field, realism=realism,
                                                          referee=True, after_goal="terminate",
                                                          max_time_s=float(max_time_s)), tracker)
    return env


def run_episode(index: int, seed: int, skills: Any = "baseline", realism: Any = "none", field: Any = "div_b",
                max_time_s: float = 15.0, realtime: bool = False, tracker: Any = "auto",
                tactic: str = "go-to-ball-and-shoot") -> dict:
    """One evaluation episode; returns a dict (index, seed, success, outcome, time_s,
    kicks, ball, robot, missed_deadlines)."""
    tactic_cls = tactic_class(tactic)
    env = _env(field, realism, max_time_s, tracker)
    es = episode_seed(seed, index)
    rng = np.random.default_rng(es)
    ball, pose = sample_scene(rng, env.field)
    env.reset(seed=es, options={"ball": {"pos": ball.tolist()}, "robots": {"blue_0": pose.tolist()}})
    tactic = tactic_cls(env.field, env.config.robot, env.config.ball, skills=skills, dt=env.config.dt)
    outcome, t_end = "timeout", max_time_s
    deadline = ControlDeadline(env.config.dt)
    a = np.zeros(5, np.float32)
    while env.agents:
        if realtime:
            a, _ = deadline.command(lambda: tactic.act(env.vision_state("blue"), 0), a)
        else:
            a = tactic.act(env.vision_state("blue"), 0)
        _, _, _, _, infos = env.step({"blue_0": a})
        for e in infos["blue_0"]["events"]:
            if e["type"] == "goal":
                outcome = "goal" if e["team"] == "blue" else "own_goal"
                t_end = float(e["t"])
        if not env.agents and outcome == "timeout":
            t_end = float(env.world_state().t)
    return {"index": index, "seed": es, "success": outcome == "goal", "outcome": outcome, "time_s": t_end,
            "kicks": tactic.status.kicks, "ball": [float(v) for v in ball], "robot": [float(v) for v in pose],
            "missed_deadlines": deadline.missed,
            **({"stalls": int(tactic.stalls)} if hasattr(tactic, "stalls") else {})}


def _episodes_worker(job: tuple) -> list[dict]:
    indices, rest = job[0], job[1:]
    return [run_episode(i, *rest) for i in indices]


def evaluate_tactic(skills: Any = "learned", episodes: int = 500, seed: int = 0, workers: int = 1,
                    realism: Any = "none", out: str | os.PathLike | None = None, field: Any = "div_b",
                    max_time_s: float = 15.0, realtime: bool = False, progress: bool = True,
                    backend: str = "local", address: str | None = None, tracker: Any = "auto",
                    tactic: str = "go-to-ball-and-shoot") -> dict:
    """Evaluate go-to-ball-and-shoot as in the paper's section 5.2 (see the module docstring).

    Args:
        skills: "learned", "baseline" or {skill: kind or actor checkpoint path}
            (:mod:`~ssl_marl.plays.skillset`).
        episodes: number of random scenes (paper: 500).
        seed: evaluation seed; episode i uses ``episode_seed(seed, i)``.
        workers: worker processes, or Ray tasks in flight (None with Ray: the
            cluster's CPUs); results do not depend on it.
        realism: env realism preset / config.
        out: output directory for results.json and time_hist.png (None: no files).
        field: "div_b" (default), "div_a" or a FieldGeometry.
        max_time_s: per-episode limit (paper: 15 s).
        realtime: drop a command whose computation exceeds the 1/60 s deadline.
        progress: tqdm bar.
        backend: "local" (process pool) or "ray"; ``address``: Ray cluster address
            (None: a local Ray instance). See :mod:`~ssl_marl.runners.pool`.
        tracker: "auto" (on unless realism is "none"), "on" or "off": the tactic reads
            :class:`~ssl_marl.envs.tracking.TrackedVisionEnv`'s tracked state.
        tactic: a name in :data:`TACTIC_CHOICES`: "go-to-ball-and-shoot" (the paper's,
            default) or "dribble-and-shoot" (:mod:`~ssl_marl.plays.dribble_shoot`).

    Returns: the results dict (also written to ``out/results.json``).
    """
    if not isinstance(episodes, int) or episodes < 1:
        raise ValueError(f"episodes must be a positive integer, got {episodes!r}")
    validate_backend(backend, workers, address)
    from ..physics.field import FieldGeometry
    from ..plays.skillset import check_skills

    tactic = str(tactic).replace("_", "-")
    tactic_class(tactic)  # a bad name fails here
    check_skills(skills, FieldGeometry.from_name(field))  # fail here (e.g. a bad checkpoint), not in every worker
    t0 = time.perf_counter()
    from ..envs.tracking import resolve_tracker

    use_tracker = resolve_tracker(tracker, realism)
    jobs = [(chunk, seed, skills, realism, field, max_time_s, realtime, use_tracker, tactic)
            for chunk in chunk_indices(episodes, workers)]
    eps = [e for chunk in run_pool(_episodes_worker, jobs, workers, f"eval {tactic} ({skills})",
                                   progress, unit="ep", backend=backend, address=address, size=len, total=episodes)
           for e in chunk]
    succ_times = [e["time_s"] for e in eps if e["success"]]
    k = len(succ_times)
    lo, hi = wilson_interval(k, episodes)
    failures = {"timeout": sum(e["outcome"] == "timeout" for e in eps),
                "own_goal": sum(e["outcome"] == "own_goal" for e in eps)}
    field_name = field if isinstance(field, str) else getattr(field, "name", repr(field))
    results = {
        "protocol": f"paper section 5.2: one robot and the ball at random, {tactic} until a goal "
                    f"or {max_time_s:g} s",
        "tactic": tactic,
        "skills": skills if isinstance(skills, str) else dict(skills),
        "episodes": episodes, "seed": seed,
        "config": {"field": field_name, "realism": realism if isinstance(realism, str) else repr(realism),
                   "max_time_s": max_time_s, "realtime": realtime, "workers": workers, "backend": backend,
                   "tracker": use_tracker,
                   "scene_margin_m": SCENE_MARGIN_M, "min_robot_ball_dist_m": MIN_ROBOT_BALL_DIST_M},
        "success_rate": k / episodes, "successes": k, "success_ci95": [lo, hi],
        "time_s": time_summary(succ_times), "failures": failures,
        "kicks_mean": float(np.mean([e["kicks"] for e in eps])),
        "missed_deadlines": int(sum(e["missed_deadlines"] for e in eps)),
        **({"go_to_ball_stalls": int(sum(e["stalls"] for e in eps)),
            "episodes_with_stall": int(sum(e["stalls"] > 0 for e in eps))} if eps and "stalls" in eps[0] else {}),
        "paper": PAPER_RESULT, "wall_time_s": time.perf_counter() - t0, "episodes_detail": eps,
    }
    if out is not None:
        d = Path(out)
        d.mkdir(parents=True, exist_ok=True)
        write_result_folder(d, results, build_manifest(
            rules={"runner": "eval-tactic", "tactic": tactic, "skills": results["skills"], **results["config"]},
            seeds={"seed": seed, "episodes": episodes}))
        ts = results["time_s"]
        title = (f"{tactic} ({results['skills']}), {field_name}: success {k}/{episodes} "
                 f"= {100 * k / episodes:.1f} %" + (f", {ts['mean']:.2f} \u00b1 {ts['std']:.2f} s" if k else ""))
        write_time_histogram(succ_times, d / "time_hist.png", title, max_time_s, xlabel="time to score (s)")
    return results
