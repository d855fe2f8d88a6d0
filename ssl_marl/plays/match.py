"""Full matches between two controllers, and series of matches in worker processes.

:func:`play_match` runs one match in the full-field env (kickoff after each goal and
out-of-play restarts are the env referee's job) and returns a :class:`MatchResult`.
:func:`play_series` runs K matches (match i seeded ``seed + i``) in a process pool.

Controllers (per team): ``"baseline"`` / ``"learned"``: a
:class:`~ssl_marl.plays.team.TeamController` with those skills and the standard
(no-pass) plays; ``"passing-learned"`` / ``"passing-baseline"``: the same controller
with the passing plays (:mod:`ssl_marl.plays.passing_play`) and those skills
(:func:`~ssl_marl.plays.passing_play.passing_team_skills`); ``"random"``: uniform
random actions (seeded); ``"idle"``: zero actions.

Statistics: a :class:`~ssl_marl.plays.stats.MatchStatsTracker` watches every step
(passes attempted / completed / intercepted, shots, goals per team: ``MatchResult.stats``).

Real-time mode (``realtime=True``, the paper's evaluation mode, section 4.2): each
team's ``act`` is timed; if it takes longer than the control period (1/60 s) that
team's command for this tick is lost and its robots keep executing the previous
command; missed deadlines are counted per team. Each team is held to its own
deadline, as if both ran on their own computers; the simulation itself is not paced
by the wall clock (the env runs in step mode), so a match does not need its
simulated duration in wall time. Results then depend on machine load: only step mode
(``realtime=False``) is reproducible.

Rendering (``render="match.mp4"`` or ``".gif"``): every k-th env frame
(``render_fps``, default 30 frames per simulated second) is drawn with
``env.render()``. GIFs are collected and written with
:func:`ssl_marl.envs.render.write_animation`; MP4 frames are streamed to ffmpeg
(imageio-ffmpeg) as they come, because a 300 s match is ~9000 frames (GBs in memory).
"""

from __future__ import annotations

import math
import os
import tempfile
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any, Callable

import numpy as np

CONTROLLERS = ("learned", "baseline", "random", "idle", "passing-learned", "passing-baseline")


# ------------------------------------------------------------- controllers
class IdleController:
    """Zero actions for every robot of ``team``."""

    def __init__(self, team: str, n_robots: int) -> None:
        self.agents = [f"{team}_{i}" for i in range(n_robots)]

    def reset(self) -> None:
        pass

    def act(self, env_or_world: Any) -> dict[str, np.ndarray]:
        return {a: np.zeros(5, np.float32) for a in self.agents}


class RandomController:
    """Uniform random actions in [-1, 1] (seeded)."""

    def __init__(self, team: str, n_robots: int, seed: int = 0) -> None:
        self.agents = [f"{team}_{i}" for i in range(n_robots)]
        self.seed = seed
        self.reset()

    def reset(self) -> None:
        self.rng = np.random.default_rng(self.seed)

    def act(self, env_or_world: Any) -> dict[str, np.ndarray]:
        a = self.rng.uniform(-1.0, 1.0, (len(self.agents), 5)).astype(np.float32)
        return dict(zip(self.agents, a))


def make_controller(kind: Any, team: str, n_robots: int, field: Any = "div_b", seed: int = 0, **kwargs: Any):
    """Controller ``kind`` (one of :data:`CONTROLLERS`) for ``team``. ``kwargs`` go to
    :class:`~ssl_marl.plays.team.TeamController` (robot, ball, plays, adaptive, ...).
    An object with ``act(env) -> {agent: action}`` and ``agents`` is passed through."""
    if not isinstance(kind, str):
        if not (hasattr(kind, "act") and hasattr(kind, "agents")):
            raise ValueError(f"controller for {team} must be one of {CONTROLLERS} or an object with act() and "
                             f"agents, got {kind!r}")
        return kind
    if kind in ("learned", "baseline"):
        from .team import TeamController

        return TeamController(team, n_robots, field=field, skills=kind, seed=seed, **kwargs)
    if kind in ("passing-learned", "passing-baseline"):
        from .passing_play import passing_plays, passing_team_skills
        from .team import TeamController

        kwargs.setdefault("plays", passing_plays(ball=kwargs.get("ball")))
        return TeamController(team, n_robots, field=field, skills=passing_team_skills(kind.split("-", 1)[1]),
                              seed=seed, **kwargs)
    if kind == "random":
        return RandomController(team, n_robots, seed=seed)
    if kind == "idle":
        return IdleController(team, n_robots)
    raise ValueError(f"unknown controller {kind!r} for {team}; expected one of {CONTROLLERS}")


# ------------------------------------------------------------------ result
@dataclass
class MatchResult:
    """Outcome of one match.

    Attributes:
        score: goals per team.
        goals: [{"team": scorer, "t": simulated time (s)}] in order.
        shots: kick events per team (every kick, not only shots on goal).
        stats: per team, from :class:`~ssl_marl.plays.stats.MatchStatsTracker`: kicks,
            shots (kicks aimed at the goal), goals, passes attempted / completed /
            intercepted / lost, interceptions, pass_completion; ``"events"``: the
            tracker's log of passes (with outcomes) and shots, in time order.
        possession: fraction of control steps in which a robot of the team held the
            ball on its dribbler (ground truth; the two may sum to less than 1).
        steps: control steps simulated. sim_time_s: simulated seconds.
        wall_time_s: wall-clock seconds for the whole match (env + controllers).
        act_time_ms: mean wall time of each team's ``act`` (ms).
        missed_deadlines: real-time mode: ticks whose command was lost, per team.
        seed: env seed. config: the match options.
    """

    score: dict[str, int]
    goals: list[dict] = field(default_factory=list)
    shots: dict[str, int] = field(default_factory=dict)
    possession: dict[str, float] = field(default_factory=dict)
    steps: int = 0
    sim_time_s: float = 0.0
    wall_time_s: float = 0.0
    act_time_ms: dict[str, float] = field(default_factory=dict)
    missed_deadlines: dict[str, int] = field(default_factory=dict)
    seed: int = 0
    config: dict = field(default_factory=dict)
    stats: dict = field(default_factory=dict)

    @property
    def winner(self) -> str | None:
        """"blue", "yellow" or None for a draw."""
        b, y = self.score.get("blue", 0), self.score.get("yellow", 0)
        return None if b == y else ("blue" if b > y else "yellow")

    def to_dict(self) -> dict:
        d = asdict(self)
        d["winner"] = self.winner
        return d


# ------------------------------------------------------------------- video
class _VideoSink:
    """Collects frames for a GIF (written by ``write_animation``) or streams an MP4."""

    def __init__(self, path: str | os.PathLike, fps: float) -> None:
        self.path = Path(path)
        self.fps = fps
        self.suffix = self.path.suffix.lower()
        if self.suffix not in (".gif", ".mp4"):
            raise ValueError(f"render: unsupported suffix {self.path.suffix!r} for {self.path}; use .gif or .mp4")
        self.frames: list[np.ndarray] = []
        self._writer = None
        self._tmp: str | None = None
        self._shape: tuple[int, ...] | None = None

    def add(self, frame: np.ndarray) -> None:
        frame = np.ascontiguousarray(frame, dtype=np.uint8)
        if self.suffix == ".gif":
            self.frames.append(frame)
            return
        h, w = frame.shape[:2]
        if h % 2 or w % 2:  # yuv420p needs even sizes
            frame = np.ascontiguousarray(np.pad(frame, ((0, h % 2), (0, w % 2), (0, 0)), mode="edge"))
        if self._writer is None:
            import imageio_ffmpeg

            self._shape = frame.shape
            directory = self.path.parent if str(self.path.parent) else Path(".")
            fd, self._tmp = tempfile.mkstemp(prefix=f".{self.path.stem}.", suffix=".tmp.mp4", dir=directory)
            os.close(fd)
            self._writer = imageio_ffmpeg.write_frames(self._tmp, (frame.shape[1], frame.shape[0]), fps=self.fps,
                                                       codec="libx264", macro_block_size=1, quality=6)
            self._writer.send(None)
        self._writer.send(frame.tobytes())

    def close(self, ok: bool = True) -> None:
        if self.suffix == ".gif":
            if ok and self.frames:
                from ..envs.render import write_animation

                write_animation(self.frames, self.path, fps=int(round(self.fps)))
            self.frames = []
            return
        if self._writer is not None:
            self._writer.close()
            self._writer = None
            if ok:
                mask = os.umask(0)
                os.umask(mask)
                os.chmod(self._tmp, 0o666 & ~mask)
                os.replace(self._tmp, self.path)
            else:
                try:
                    os.unlink(self._tmp)
                except OSError:
                    pass


# ------------------------------------------------------------------- match
def start_options(env: Any, seed: int, jitter_m: float) -> dict | None:
    """Reset options: the kickoff formation (field frame) with seeded jitter, or None."""
    if not jitter_m:
        return None
    from ..envs.referee import kickoff_poses

    rng = np.random.default_rng([int(seed), 0x5EED])
    cfg = env.config
    poses = kickoff_poses(env.field, cfg.n_blue, cfg.n_yellow)
    robots = {}
    for name, (x0, y0, h0) in zip(env.possible_agents, poses.tolist()):
        dxy = np.clip(rng.normal(0.0, jitter_m, 2), -2 * jitter_m, 2 * jitter_m)
        x, y = x0 + dxy[0], y0 + dxy[1]
        x = min(x, -0.05) if name.startswith("blue") else max(x, 0.05)  # stay in the own half
        h = h0 + float(np.clip(rng.normal(0.0, jitter_m), -0.2, 0.2))
        robots[name] = (float(x), float(y), h)
    return {"formation": "kickoff", "robots": robots}


def play_match(blue: str = "baseline", yellow: str = "baseline", robots: int = 6, field: Any = "div_b",
               seconds: float = 300.0, seed: int = 0, realism: Any = "none", realtime: bool = False,
               render: str | os.PathLike | None = None, progress: bool = True, render_fps: float = 30.0,
               render_width_px: int = 640, start_jitter_m: float = 0.05, controller_kwargs: dict | None = None,
               env_kwargs: dict | None = None) -> MatchResult:
    """Play one match and return its :class:`MatchResult`.

    Args:
        blue, yellow: controller kinds ("learned", "baseline", "random", "idle").
        robots: robots per team (1-11).
        field: "div_a", "div_b" or a FieldGeometry.
        seconds: simulated match length (s).
        seed: env seed (step mode is deterministic for a given seed).
        realism: "none", "realistic" or a RealismConfig / dict.
        realtime: hold each team to the 1/60 s control deadline (see the module docstring).
        render: output path (.mp4 or .gif) or None.
        progress: show a tqdm bar (simulated seconds).
        render_fps: frames per simulated second in the video.
        render_width_px: video frame width.
        start_jitter_m: the match starts from the kickoff formation with each robot
            moved by Gaussian noise of this sigma (m, clipped at 2 sigma; headings by
            sigma / 0.1 m x 0.1 rad), drawn from ``seed``. Without noise (realism
            "none") the simulation is deterministic, so this is what makes matches
            with different seeds differ; 0 = the exact formation.
        controller_kwargs: extra TeamController options for both teams.
        env_kwargs: extra env options.
    """
    from ..envs import parallel_env

    for name, kind in (("blue", blue), ("yellow", yellow)):
        if isinstance(kind, str) and kind not in CONTROLLERS:
            raise ValueError(f"{name} must be one of {CONTROLLERS} or a controller object, got {kind!r}")
    if not (isinstance(seconds, (int, float)) and math.isfinite(seconds) and seconds > 0):
        raise ValueError(f"seconds must be a positive number, got {seconds!r}")
    env_opts = dict(n_blue=robots, n_yellow=robots, field=field, max_time_s=float(seconds), realism=realism,
                    after_goal="kickoff", realtime=False)
    if render is not None:
        env_opts.update(render_mode="rgb_array", render_width_px=int(render_width_px))
    env_opts.update(env_kwargs or {})
    env = parallel_env(**env_opts)
    geom = env.field
    ck = dict(controller_kwargs or {})
    ck.setdefault("robot", env.config.robot)
    ck.setdefault("ball", env.config.ball)
    ck.setdefault("dt", env.config.dt)
    ctrls = {team: make_controller(kind, team, robots, geom, seed=seed + k,
                                   **(ck if kind in ("learned", "baseline", "passing-learned", "passing-baseline")
                                      else {}))
             for k, (team, kind) in enumerate((("blue", blue), ("yellow", yellow)))}
    for team, c in ctrls.items():
        if hasattr(c, "reset"):
            c.reset()
    dt = env.config.dt
    total_steps = int(round(seconds / dt))
    every = max(int(round(env.config.control_hz / render_fps)), 1)
    sink = _VideoSink(render, env.config.control_hz / every) if render is not None else None

    from .stats import MatchStatsTracker

    tracker = MatchStatsTracker(geom, env.config.ball)
    t_start = time.perf_counter()
    env.reset(seed=seed, options=start_options(env, seed, start_jitter_m))
    prev = {team: {a: np.zeros(5, np.float32) for a in c.agents} for team, c in ctrls.items()}
    missed = {"blue": 0, "yellow": 0}
    act_time = {"blue": 0.0, "yellow": 0.0}
    shots = {"blue": 0, "yellow": 0}
    held = {"blue": 0, "yellow": 0}
    goals: list[dict] = []
    steps = 0
    bar = None
    if progress:
        from tqdm.auto import tqdm

        bar = tqdm(total=total_steps, desc=f"match (seed {seed})", unit="step", leave=False)
    ok = False
    try:
        if sink is not None:
            sink.add(env.render())
        while env.agents:
            actions: dict[str, np.ndarray] = {}
            for team, ctrl in ctrls.items():
                t0 = time.perf_counter()
                a = ctrl.act(env)
                el = time.perf_counter() - t0
                act_time[team] += el
                if realtime and el > dt:
                    missed[team] += 1
                    a = prev[team]
                prev[team] = a
                actions.update(a)
            _, _, _, _, infos = env.step(actions)
            steps += 1
            events = next(iter(infos.values()))["events"] if infos else []
            for e in events:
                if e["type"] == "kick":
                    shots[e["agent"].split("_")[0]] += 1
                elif e["type"] == "goal":
                    goals.append({"team": e["team"], "t": float(e["t"])})
            truth = env.world_state()
            tracker.observe(truth, events)
            held["blue"] += bool(truth.blue.ball_on_dribbler.any())
            held["yellow"] += bool(truth.yellow.ball_on_dribbler.any())
            if sink is not None and steps % every == 0:
                sink.add(env.render())
            if bar is not None:
                bar.update(1)
                if goals and steps % 60 == 0:
                    bar.set_postfix(score=f"{env.score['blue']}-{env.score['yellow']}")
        ok = True
    finally:
        if bar is not None:
            bar.close()
        if sink is not None:
            sink.close(ok)
        env.close()
    wall = time.perf_counter() - t_start
    label = {t: k if isinstance(k, str) else type(k).__name__ for t, k in (("blue", blue), ("yellow", yellow))}
    config = dict(blue=label["blue"], yellow=label["yellow"], robots=robots, field=geom.name,
                  seconds=float(seconds), seed=seed, realism=realism if isinstance(realism, str) else repr(realism),
                  realtime=realtime, start_jitter_m=start_jitter_m,
                  render=str(render) if render is not None else None,
                  skills={t: _json_safe(getattr(c, "skills", None)) for t, c in ctrls.items()})
    return MatchResult(score=dict(env.score), goals=goals, shots=shots,
                       possession={k: v / max(steps, 1) for k, v in held.items()}, steps=steps,
                       sim_time_s=steps * dt, wall_time_s=wall,
                       act_time_ms={k: 1000.0 * v / max(steps, 1) for k, v in act_time.items()},
                       missed_deadlines=missed, seed=seed, config=config,
                       stats={**tracker.summary(), "events": tracker.log})


def _json_safe(skills: Any) -> Any:
    return dict(skills) if hasattr(skills, "items") else skills


# ------------------------------------------------------------------ series
def _series_worker(job: tuple[int, dict]) -> tuple[int, MatchResult]:
    i, kwargs = job
    return i, play_match(**kwargs)


def summarize(results: list[MatchResult]) -> dict:
    """Table summary from blue's side: wins / draws / losses, goals for / against, ...;
    ``stats``: per-team totals of the match statistics (:func:`~ssl_marl.plays.stats.summarize_stats`)."""
    from .stats import summarize_stats

    n = len(results)
    wins = sum(r.winner == "blue" for r in results)
    losses = sum(r.winner == "yellow" for r in results)
    gf = sum(r.score["blue"] for r in results)
    ga = sum(r.score["yellow"] for r in results)
    mean = (lambda xs: float(np.mean(xs)) if xs else 0.0)
    return {"matches": n, "blue": results[0].config.get("blue") if n else None,
            "yellow": results[0].config.get("yellow") if n else None,
            "wins": wins, "draws": n - wins - losses, "losses": losses, "goals_for": gf, "goals_against": ga,
            "goal_diff_mean": (gf - ga) / n if n else 0.0,
            "shots_blue_mean": mean([r.shots["blue"] for r in results]),
            "shots_yellow_mean": mean([r.shots["yellow"] for r in results]),
            "possession_blue_mean": mean([r.possession["blue"] for r in results]),
            "possession_yellow_mean": mean([r.possession["yellow"] for r in results]),
            "missed_deadlines_blue": sum(r.missed_deadlines["blue"] for r in results),
            "missed_deadlines_yellow": sum(r.missed_deadlines["yellow"] for r in results),
            "wall_time_s_total": float(sum(r.wall_time_s for r in results)),
            "stats": summarize_stats([r.stats for r in results if r.stats])}


def run_pool(worker: Callable, jobs: list, workers: int, desc: str, progress: bool = True,
             start_method: str = "spawn", unit: str = "job") -> list:
    """Run ``worker(job)`` over ``jobs`` (in-process if workers <= 1, else a process pool
    of the given start method), with a tqdm bar; results in completion order."""
    from tqdm.auto import tqdm

    out = []
    with tqdm(total=len(jobs), desc=desc, unit=unit, disable=not progress) as bar:
        if workers <= 1 or len(jobs) <= 1:
            for job in jobs:
                out.append(worker(job))
                bar.update(1)
            return out
        import multiprocessing as mp

        ctx = mp.get_context(start_method)
        with ctx.Pool(processes=min(workers, len(jobs))) as pool:
            for res in pool.imap_unordered(worker, jobs):
                out.append(res)
                bar.update(1)
    return out


def play_series(blue: str = "baseline", yellow: str = "baseline", matches: int = 10, workers: int = 1,
                seed: int = 0, progress: bool = True, start_method: str = "spawn",
                **match_kwargs: Any) -> tuple[list[MatchResult], dict]:
    """Play ``matches`` matches (match i with seed ``seed + i``) in ``workers`` processes.

    ``match_kwargs`` go to :func:`play_match` (robots, field, seconds, realism,
    realtime, ...; ``render`` is not allowed: render single matches). Returns
    ``(results in match order, summary)`` with the summary of :func:`summarize`.
    Start method "spawn" (default; safe with torch and threads) or "fork"/"forkserver".
    """
    if not isinstance(matches, int) or matches < 1:
        raise ValueError(f"matches must be a positive integer, got {matches!r}")
    if not isinstance(workers, int) or workers < 1:
        raise ValueError(f"workers must be a positive integer, got {workers!r}")
    if match_kwargs.get("render") is not None:
        raise ValueError("play_series does not render; use play_match(render=...) for a video")
    match_kwargs.pop("render", None)
    jobs = [(i, dict(blue=blue, yellow=yellow, seed=seed + i, progress=False, **match_kwargs))
            for i in range(matches)]
    done = run_pool(_series_worker, jobs, workers, f"{blue} vs {yellow}", progress, start_method, unit="match")
    results = [r for _, r in sorted(done, key=lambda x: x[0])]
    return results, summarize(results)
