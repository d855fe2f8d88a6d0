"""One full match between two team controllers: :func:`play_match`.

The match runs in the full-field env (kickoff after each goal and out-of-play
restarts are the env referee's job) and returns a
:class:`~ssl_marl.runners.result.MatchResult`. Teams are named as in
:mod:`~ssl_marl.runners.controllers` (``"learned"``, ``"baseline"``, ``"random"``,
``"idle"``, with optional per-skill sources for STP teams); series of matches are
:func:`ssl_marl.runners.series.play_series`.

Real-time mode (``realtime=True``, the paper's evaluation mode, section 4.2): each
team's ``act`` is timed against the control period by its own
:class:`~ssl_marl.envs.deadline.ControlDeadline`; a command computed too late is lost
and that team's robots keep executing the previous command. Each team is held to
its own deadline, as if both ran on their own computers; the simulation itself is
not paced by the wall clock (the env runs in step mode), so a match does not need
its simulated duration in wall time. Results then depend on machine load: only step
mode (``realtime=False``) is reproducible.

Formats (:func:`format_options`): "plain" (one period; play restarts at once after the
ball leaves the field) or "ssl" (two halves with ends changed at half-time, referee
commands, free kicks and fouls of :mod:`ssl_marl.envs.game_control`, the match clock
stopped during STOP as SSL's rules stop it, so a match simulates more than its
``seconds``: ``MatchResult.played_s`` is its clock, ``sim_time_s`` all of it); the referee's
calls are counted in ``MatchResult.stats["referee"]``. In both, every restart's robot
placement is drawn from the match seed (``restart_jitter_m``).

Rendering (``render="match.mp4"`` or ``".gif"``): every k-th env frame
(``render_fps`` frames per simulated second) is drawn with ``env.render()`` and
streamed to disk by :class:`~ssl_marl.envs.animation.VideoSink` (constant memory).
"""

from __future__ import annotations

import math
import os
import time
from typing import Any

import numpy as np

from ..envs.actions import fit_action
from ..envs.referee import match_start_options
from ..envs.deadline import ControlDeadline
from ..envs.game_control import SSL_GAME_CONTROL
from .controllers import (CHIP_KINDS, STP_KINDS, TEAM_KINDS, controller_label, decision_label, decision_spec,
                          make_controller)
from .result import MatchResult
from .team_process import TeamProcess, team_view
from ..envs.animation import VideoSink


#: env events counted in ``MatchResult.stats["referee"]`` when SSL game control is on
REFEREE_CALLS = ("ball_out", "no_progress", "foul", "referee", "half_time")


#: the :class:`~ssl_marl.envs.config.MatchRules` fields of SSL game control, recorded in a
#: match's config when any is on
GAME_RULES = ("ssl_restarts", "fouls", "restart_jitter_m", "stop_s", "free_kick_timeout_s", "half_time_s",
              "clock_stops")
#: env options of the SSL format (``--format ssl``): two halves of ``seconds / 2`` of playing
#: time (the clock stops during STOP), SSL restarts and fouls, restart placement jittered by 0.1 m
SSL_FORMAT = {**SSL_GAME_CONTROL, "restart_jitter_m": 0.1, "clock_stops": True}


def format_options(fmt: str, seconds: float) -> dict:
    """Env options of a match format: "plain" (one period, restarts without referee
    commands; none) or "ssl" (:data:`SSL_FORMAT` and half-time at ``seconds / 2``)."""
    if fmt == "plain":
        return {}
    if fmt == "ssl":
        return {**SSL_FORMAT, "half_time_s": float(seconds) / 2}
    raise ValueError(f"format must be 'plain' or 'ssl', got {fmt!r}")


class MatchStats:
    """Per-step bookkeeping of a match: kicks, goals and ball possession per team."""

    def __init__(self) -> None:
        self.shots = {"blue": 0, "yellow": 0}
        self.held = {"blue": 0, "yellow": 0}
        self.goals: list[dict] = []
        self.steps = 0
        self.referee: dict[str, int] = {}  #: counts of the referee's calls (game control on)
        #: fouls by the offending team: {"blue": {foul: count}, "yellow": {...}}
        self.fouls: dict[str, dict[str, int]] = {"blue": {}, "yellow": {}}

    def record(self, events: list[dict], truth: Any) -> None:
        """Count one control step's env events and who holds the ball (ground truth)."""
        self.steps += 1
        for e in events:
            if e["type"] == "kick":
                self.shots[e["agent"].split("_")[0]] += 1
            elif e["type"] == "goal":
                self.goals.append({"team": e["team"], "t": float(e["t"])})
            if e["type"] in REFEREE_CALLS:
                key = {"foul": lambda: f"foul_{e['foul']}", "referee": lambda: f"command_{e['command']}"}.get(
                    e["type"], lambda: e["type"])()
                self.referee[key] = self.referee.get(key, 0) + 1
            if e["type"] == "foul" and e.get("team") in self.fouls:
                by = self.fouls[e["team"]]
                by[e["foul"]] = by.get(e["foul"], 0) + 1
        self.held["blue"] += bool(truth.blue.ball_on_dribbler.any())
        self.held["yellow"] += bool(truth.yellow.ball_on_dribbler.any())

    def possession(self) -> dict[str, float]:
        return {k: v / max(self.steps, 1) for k, v in self.held.items()}


def validate_match_args(blue: Any, yellow: Any, seconds: Any) -> None:
    """Clear errors for bad team names and match lengths (before anything is built)."""
    for name, kind in (("blue", blue), ("yellow", yellow)):
        if isinstance(kind, str) and kind not in TEAM_KINDS:
            raise ValueError(f"{name} must be one of {TEAM_KINDS} or a controller object, got {kind!r}")
    if not (isinstance(seconds, (int, float)) and math.isfinite(seconds) and seconds > 0):
        raise ValueError(f"seconds must be a positive number, got {seconds!r}")


TEAM_PROCESSES = ("off", "on", "auto")


def use_team_processes(mode: str, realtime: bool, kind: Any, skills: Any, decision: Any, controller_kwargs: dict
                       ) -> bool:
    """Whether :func:`play_match` runs yellow in a
    :class:`~ssl_marl.runners.team_process.TeamProcess` (``team_processes`` = ``mode``):
    "on" raises ValueError where it cannot (real-time mode, a controller object, a
    spec that does not pickle); "auto" is on where "on" would work and the machine
    has two or more CPUs."""
    import pickle

    if mode not in TEAM_PROCESSES:
        raise ValueError(f"team_processes must be one of {TEAM_PROCESSES}, got {mode!r}")
    if mode == "off":
        return False
    why = None
    if realtime:
        why = "real-time mode times each team in this process"
    elif not isinstance(kind, str):
        why = "yellow is a controller object, not a team kind"
    else:
        try:
            pickle.dumps((skills, decision, controller_kwargs))
        except Exception as exc:  # noqa: BLE001 - any pickling failure
            why = f"yellow's skills or decision do not pickle ({type(exc).__name__})"
    if why is not None:
        if mode == "on":
            raise ValueError(f"team_processes='on': {why}")
        return False
    return mode == "on" or (os.cpu_count() or 1) >= 2


def play_match(blue: Any = "baseline", yellow: Any = "baseline", robots: int = 6, field: Any = "div_b",
               seconds: float = 300.0, seed: int = 0, realism: Any = "none", realtime: bool = False,
               render: str | os.PathLike | None = None, progress: bool = True, render_fps: float = 30.0,
               render_width_px: int = 640, start_jitter_m: float = 0.05, restart_jitter_m: float = 0.1,
               controller_kwargs: dict | None = None,
               env_kwargs: dict | None = None, blue_skills: Any = None, yellow_skills: Any = None,
               tracker: Any = "auto", blue_decision: Any = None, yellow_decision: Any = None,
               team_processes: str = "off") -> MatchResult:
    """Play one match and return its :class:`MatchResult`.

    Args:
        blue, yellow: team kinds ("learned", "baseline", "random", "idle") or
            controller objects.
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
        restart_jitter_m: every restart (kickoff after a goal, ball placement after an
            out or a no-progress call) places its robots at poses drawn from the match's
            seeded RNG within this many metres of the fixed placement
            (:class:`~ssl_marl.envs.config.MatchRules`, ``restart_jitter_m``): the same
            seed gives the same match, but no restart repeats an earlier one, so a
            deterministic kickoff cannot replay itself goal after goal. 0 = the fixed
            placements. ``env_kwargs["restart_jitter_m"]`` takes precedence.
        controller_kwargs: extra :func:`~ssl_marl.runners.controllers.make_controller`
            options for both STP teams (robot, ball, dt, TeamSpec fields).
        env_kwargs: extra env options.
        tracker: "auto" (on unless realism is "none"), "on" or "off": both teams read
            :class:`~ssl_marl.envs.tracking.TrackedVisionEnv`'s tracked state.
        blue_skills, yellow_skills: an STP team's skills as a
            :mod:`~ssl_marl.plays.skillset` spec (e.g. from
            :func:`~ssl_marl.runners.controllers.team_skills`: a trained actor for one
            skill); None = the kind's own skills.
        blue_decision, yellow_decision: a passing team's ball-carrier decision:
            "handcoded" (the cost decision), "learned" (the shipped Attack 3v2 actor), an
            actor checkpoint path, or a decider / decision-policy object; None = the
            kind's own (learned for "passing-learned-decision", else handcoded).
        team_processes: "on": yellow's controller decides in its own process
            (:class:`~ssl_marl.runners.team_process.TeamProcess`) while blue's decides
            in this one, the same match bit for bit in about 60 % of the wall time on
            two cores; needs step mode and a named yellow team whose skills and
            decision pickle. "auto": on when those hold and the machine has two or
            more CPUs. "off" (default): one process.
    """
    from ..envs import parallel_env

    validate_match_args(blue, yellow, seconds)
    decision_spec(blue, blue_decision, "blue")  # a decision for a non-passing team fails before the env is built
    decision_spec(yellow, yellow_decision, "yellow")
    env_opts = dict(n_blue=robots, n_yellow=robots, field=field, max_time_s=float(seconds), realism=realism,
                    after_goal="kickoff", realtime=False, observations=False)  # teams read vision_state()
    if render is not None:
        env_opts.update(render_mode="rgb_array", render_width_px=int(render_width_px),  # caption: who is who
                        render_team_labels={t: f"{k} skills" if k in ("learned", "baseline") else str(k)
                                            for t, k in (("blue", blue), ("yellow", yellow)) if isinstance(k, str)})
    if any(isinstance(k, str) and k in CHIP_KINDS for k in (blue, yellow)):
        env_opts["chip_kicks"] = True  # a team that chips; the other team's 5-entry actions get a flat chip entry
    env_opts["restart_jitter_m"] = float(restart_jitter_m)
    env_opts.update(env_kwargs or {})
    from ..envs.tracking import with_tracker

    env = with_tracker(parallel_env(**env_opts), tracker)
    geom = env.field
    ck = dict(controller_kwargs or {})
    ck.setdefault("robot", env.config.robot)
    ck.setdefault("ball", env.config.ball)
    ck.setdefault("dt", env.config.dt)
    teams = (("blue", blue, blue_skills, blue_decision), ("yellow", yellow, yellow_skills, yellow_decision))
    remote = {"yellow"} if use_team_processes(team_processes, realtime, yellow, yellow_skills, yellow_decision,
                                               ck) else set()
    ctrls: dict[str, Any] = {}
    for k, (team, kind, skills, decision) in enumerate(teams):
        kw = dict(seed=seed + k, skills=skills, decision=decision, **(ck if kind in STP_KINDS else {}))
        ctrls[team] = (TeamProcess(make_controller, kind, team, robots, geom, **kw) if team in remote
                       else make_controller(kind, team, robots, geom, **kw))
    for c in ctrls.values():
        if hasattr(c, "reset"):
            c.reset()
    dt = env.config.dt
    total_steps = int(round(seconds / dt))
    clock = env.task.clock_s  # s on the match clock (MatchTask)
    every = max(int(round(env.config.control_hz / render_fps)), 1)
    sink = VideoSink(render, env.config.control_hz / every) if render is not None else None
    deadlines = {team: ControlDeadline(dt) for team in ctrls}

    t_start = time.perf_counter()
    env.reset(seed=seed, options=match_start_options(env, seed, start_jitter_m))
    prev = {team: {a: np.zeros(5, np.float32) for a in c.agents} for team, c in ctrls.items()}
    chip_dim = 6 if env_opts.get("chip_kicks") else 5
    act_time = {"blue": 0.0, "yellow": 0.0}
    stats = MatchStats()
    from ..plays.stats import MatchStatsTracker

    pass_stats = MatchStatsTracker(geom, env.config.ball)  # passes, interceptions, shots
    bar = None
    if progress:
        from tqdm.auto import tqdm

        bar = tqdm(total=total_steps, desc=f"match (seed {seed})", unit="step", leave=False)
    ok = False
    try:
        for team in remote if env.agents else ():  # these decide in their own processes while this one
            ctrls[team].submit(team_view(env, team))  # draws, keeps statistics and decides for the others
        if sink is not None:
            sink.add(env.render())
        while env.agents:
            actions: dict[str, np.ndarray] = {}
            for team, ctrl in ctrls.items():
                if team in remote:
                    a, elapsed = ctrl.result()
                elif realtime:
                    a, elapsed = deadlines[team].command(lambda c=ctrl: c.act(env), prev[team])
                else:
                    t0 = time.perf_counter()
                    a = ctrl.act(env)
                    elapsed = time.perf_counter() - t0
                act_time[team] += elapsed
                prev[team] = a
                actions.update(a if chip_dim == 5 else {k: fit_action(v, chip_dim) for k, v in a.items()})
            _, _, _, _, infos = env.step(actions)
            for team in remote if env.agents else ():  # the next frame, sent before the bookkeeping below
                ctrls[team].submit(team_view(env, team))
            events = next(iter(infos.values()))["events"] if infos else []
            truth = env.world_state()
            stats.record(events, truth)
            pass_stats.observe(truth, events)
            if sink is not None and stats.steps % every == 0:
                sink.add(env.render())
            if bar is not None:
                bar.update(min(int(round(clock(env) / dt)), total_steps) - bar.n)
                if stats.goals and stats.steps % 60 == 0:
                    bar.set_postfix(score=f"{env.score['blue']}-{env.score['yellow']}")
        played = clock(env)
        ok = True
    finally:
        if bar is not None:
            bar.close()
        if sink is not None:
            sink.close(ok)
        for team in remote:
            ctrls[team].close()
        env.close()
    wall = time.perf_counter() - t_start
    steps = stats.steps
    rules = env.config.match
    game_on = rules.ssl_restarts or rules.fouls or rules.half_time_s is not None or rules.restart_jitter_m > 0
    config = dict(blue=controller_label(blue, blue_skills), yellow=controller_label(yellow, yellow_skills),
                  robots=robots, field=geom.name, seconds=float(seconds), seed=seed,
                  realism=realism if isinstance(realism, str) else repr(realism), realtime=realtime,
                  no_progress_s=env.config.match.no_progress_s,
                  tracker=hasattr(env, "raw_vision_state"),
                  start_jitter_m=start_jitter_m, restart_jitter_m=rules.restart_jitter_m,
                  render=str(render) if render is not None else None,
                  skills={t: _json_safe(getattr(c, "skills", None)) for t, c in ctrls.items()})
    decisions = {t: decision_label(k, d) for t, k, _, d in teams}
    if any(v not in (None, "handcoded") for v in decisions.values()):
        config["decision"] = decisions
    if game_on:
        config["rules"] = {k: getattr(rules, k) for k in GAME_RULES}
    return MatchResult(score=dict(env.score), goals=stats.goals, shots=stats.shots, possession=stats.possession(),
                       steps=steps, sim_time_s=steps * dt, played_s=played, wall_time_s=wall,
                       act_time_ms={k: 1000.0 * v / max(steps, 1) for k, v in act_time.items()},
                       missed_deadlines={team: d.missed for team, d in deadlines.items()}, seed=seed, config=config,
                       stats={**pass_stats.summary(), "events": pass_stats.log,
                              **({"referee": stats.referee, "fouls": stats.fouls} if game_on else {})})


def _json_safe(skills: Any) -> Any:
    return dict(skills) if hasattr(skills, "items") else skills
