"""Pass-endurance drill (after rSoccer's PassEndurance): two robots 2-5 m apart pass the
ball back and forth for 60 s of simulated time with the pass and receive skills.

One drill run, on an empty field with the referee off:

1. **setup**: the robot with the ball (the holder) dribbles back to its home spot
   (at most 0.8 m/s, facing its partner); the partner returns to its own home spot,
   facing the ball. Both set (within 0.1 m of home, slower than 0.2 m/s), or 3 s
   passed -> pass.
2. **pass**: the holder runs the pass skill with its partner's seen position and
   velocity as the target; the partner stands, facing the ball. The kick starts an
   attempt; losing the ball before the kick is a loss ("lost_before_kick").
3. **receive**: the partner runs the receive skill, the passer stands still. The pass
   is *completed* when the receive skill SUCCEEDS (ball held 0.5 s on the dribbler)
   within ``pass_timeout_s`` (4 s) of the kick without the ball having come to rest
   first; otherwise a loss: "out" (ball left the field), "stopped_short", "timeout".
   On completion the roles swap.
4. A pass still in flight when the time is up is not counted.
5. After a loss the drill re-places the robots at their homes and the ball on the
   dribbler of the robot that should have received it, and goes on (the clock keeps
   running across the re-placement: it counts simulated control steps).

Home spots: a random centre in the field and direction, the two homes ``U(2, 5)`` m
apart (0.5 m inside the lines), drawn per run from its seed.
"""

from __future__ import annotations

import math
import sys
import time
from collections import Counter
from pathlib import Path
from typing import Any

import numpy as np

from ..envs.ssl_env import SSLParallelEnv
from ..io import episode_seed
from .statistics import wilson_interval
from ..physics.state import WorldState
from ..skills.base import SkillStatus, make_action
from ..skills.navigation import MoveToPoint
from .provenance import build_manifest
from .result import write_result_folder

DRILLS = ("pass-endurance",)
AGENTS = ("blue_0", "blue_1")


def _home_spots(rng: np.random.Generator, field, distance_range=(2.0, 5.0)) -> np.ndarray:
    for _ in range(10_000):
        d = rng.uniform(*distance_range)
        c = field.random_free_point(rng, margin=0.5)
        a = rng.uniform(-math.pi, math.pi)
        u = np.array([math.cos(a), math.sin(a)]) * d / 2
        homes = np.array([c - u, c + u])
        if bool(np.all(field.in_field(homes, 0.5))):
            return homes
    raise RuntimeError("pass-endurance: no home spots found")


def run_pass_endurance(policy: str = "baseline", seed: int = 0, duration_s: float = 60.0, realism: str = "none",
                       field: str = "div_b", pass_timeout_s: float = 4.0, setup_timeout_s: float = 3.0,
                       pass_checkpoint: str | None = None, receive_checkpoint: str | None = None,
                       receive_policy: str | None = None) -> dict[str, Any]:
    """One drill run; returns its counts (passes attempted / completed, losses by reason,
    pass lengths and flight times). ``policy`` ("baseline" or "learned") picks the pass
    skill and, unless ``receive_policy`` is given, the receive skill."""
    from ..skills import make_skill

    receive_policy = policy if receive_policy is None else receive_policy
    for name, value in (("policy", policy), ("receive_policy", receive_policy)):
        if value not in ("baseline", "learned"):
            raise ValueError(f"{name} must be 'baseline' or 'learned', got {value!r}")
    if not (math.isfinite(duration_s) and duration_s > 0):
        raise ValueError(f"duration_s must be a positive number of seconds, got {duration_s!r}")
    env = SSLParallelEnv(n_blue=2, n_yellow=0, field=field, realism=realism, referee=False, max_time_s=1e9,
                         obs_max_teammates=1, obs_max_opponents=0)
    f, rp, bp, dt = env.field, env.config.robot, env.config.ball, env.config.dt
    rng = np.random.default_rng(seed)
    homes = _home_spots(rng, f)
    passer = make_skill("pass", policy, f, rp, bp, checkpoint=pass_checkpoint)
    receiver = make_skill("receive", receive_policy, f, rp, bp, checkpoint=receive_checkpoint)
    movers = [MoveToPoint(f, rp, bp, target=homes[i], tolerance=0.1, max_speed=0.8) for i in range(2)]
    reach = rp.front_distance + bp.radius

    def place(holder: int) -> None:
        other = 1 - holder
        face = [math.atan2(*(homes[1 - i] - homes[i])[::-1]) for i in range(2)]
        pose = {AGENTS[i]: (homes[i][0], homes[i][1], face[i]) for i in range(2)}
        ball = homes[holder] + reach * np.array([math.cos(face[holder]), math.sin(face[holder])])
        env.reset(seed=int(rng.integers(2 ** 31)), options={"robots": pose, "ball": {"pos": tuple(ball)}})
        del other

    holder, phase, phase_t = 0, "setup", 0.0
    place(holder)
    steps, n_steps = 0, int(round(duration_s / dt))
    attempts, completed = 0, 0
    losses: Counter = Counter()
    lengths, flight_times = [], []
    kick_pos: np.ndarray | None = None
    ball_stopped = False

    def face_ball(seen: WorldState, i: int) -> float:
        d = seen.ball_pos - seen.blue.pos[i]
        return math.atan2(d[1], d[0])

    def start(new_phase: str) -> None:
        nonlocal phase, phase_t
        phase, phase_t = new_phase, 0.0

    while steps < n_steps:
        seen = env.vision_state("blue")
        truth = env.world_state()  # blue's frame is the field frame
        other = 1 - holder
        acts: dict[str, np.ndarray] = {}
        if phase == "setup":
            for i in range(2):
                mv = movers[i]
                mv.dribble = i == holder
                mv.facing = math.atan2(*(seen.blue.pos[1 - i] - seen.blue.pos[i])[::-1]) if i == holder \
                    else face_ball(seen, i)
                acts[AGENTS[i]] = mv.act(seen, i)
            set_ = all(float(np.hypot(*(seen.blue.pos[i] - homes[i]))) < 0.1 and
                       float(np.hypot(*seen.blue.vel[i])) < 0.2 for i in range(2))
            if set_ or phase_t >= setup_timeout_s:
                passer.reset()
                start("pass")
        if phase == "pass":
            passer.set_target(f.clamp_to_field(seen.blue.pos[other]), seen.blue.vel[other])
            acts[AGENTS[holder]] = passer.act(seen, holder)
            movers[other].dribble, movers[other].facing = False, face_ball(seen, other)
            acts[AGENTS[other]] = movers[other].act(seen, other)
            if passer.status == SkillStatus.FAILED:
                losses["lost_before_kick"] += 1
                attempts += 1
                place(other)
                holder = other
                start("setup")
                steps += 1
                continue
        elif phase == "receive":
            acts[AGENTS[holder]] = make_action()
            acts[AGENTS[other]] = receiver.act(seen, other)
        env.step(acts)
        steps += 1
        phase_t += dt
        if phase == "pass" and passer.status == SkillStatus.SUCCEEDED:
            attempts += 1
            kick_pos = np.asarray(truth.ball_pos, float).copy()
            ball_stopped = False
            receiver.reset()
            start("receive")
        elif phase == "receive":
            truth = env.world_state()
            if float(np.hypot(*truth.ball_vel)) < 0.02 and not bool(truth.blue.ball_on_dribbler[other]):
                ball_stopped = True
            reason = None
            if receiver.status == SkillStatus.SUCCEEDED:
                if ball_stopped:
                    reason = "stopped_short"
                else:
                    completed += 1
                    lengths.append(float(np.hypot(*(truth.ball_pos - kick_pos))))
                    flight_times.append(phase_t - receiver.hold_s)
                    holder = other
                    start("setup")
            elif not bool(f.in_field(truth.ball_pos, -bp.radius)):
                reason = "out"
            elif phase_t >= pass_timeout_s:
                reason = "stopped_short" if ball_stopped else "timeout"
            if reason:
                losses[reason] += 1
                place(other)
                holder = other
                start("setup")
    env.close()
    in_flight = phase == "receive"  # a pass still travelling when the time is up: not counted
    attempts -= int(in_flight)
    return {"seed": seed, "unresolved_at_end": int(in_flight), "homes": homes.tolist(), "home_distance_m": float(np.hypot(*(homes[1] - homes[0]))),
            "attempts": attempts, "completed": completed, "losses": dict(losses),
            "pass_length_m": lengths, "flight_time_s": flight_times, "duration_s": steps * dt}


def evaluate_drill(drill: str = "pass-endurance", policy: str = "baseline", runs: int = 10, seed: int = 10_000,
                   duration_s: float = 60.0, realism: str = "none", field: str = "div_b",
                   out: str | Path | None = None, progress: bool = True,
                   receive_policy: str | None = None) -> dict[str, Any]:
    """``runs`` drill runs (run ``i`` seeded with ``episode_seed(seed, i)``); the summary
    (completion rate with its 95 % Wilson interval, passes per minute, losses by reason)
    is written to the result folder ``out`` when given
    (:func:`~ssl_marl.runners.result.write_result_folder`)."""
    if drill not in DRILLS:
        raise ValueError(f"unknown drill {drill!r}; expected one of {DRILLS}")
    if not isinstance(runs, int) or runs < 1:
        raise ValueError(f"runs must be a positive integer, got {runs!r}")
    from tqdm import tqdm

    t0 = time.perf_counter()
    receive_policy = policy if receive_policy is None else receive_policy
    results = [run_pass_endurance(policy, episode_seed(seed, i), duration_s, realism, field,
                                  receive_policy=receive_policy)
               for i in tqdm(range(runs), desc=f"{drill} ({policy})", disable=not progress, unit="run",
                             file=sys.stderr)]
    att = sum(r["attempts"] for r in results)
    comp = sum(r["completed"] for r in results)
    losses: Counter = Counter()
    for r in results:
        losses.update(r["losses"])
    lo, hi = wilson_interval(comp, att) if att else (0.0, 1.0)
    summary = {"drill": drill, "policy": policy, "receive_policy": receive_policy, "runs": runs, "seed": seed, "duration_s": duration_s,
               "realism": realism, "field": field, "attempts": att, "completed": comp,
               "completion_rate": comp / att if att else None, "completion_ci95": [lo, hi],
               "passes_per_minute": comp / (runs * duration_s / 60.0), "losses": dict(losses),
               "wall_time_s": time.perf_counter() - t0, "runs_detail": results}
    if out is not None:
        write_result_folder(out, summary, build_manifest(
            rules={"runner": "eval-drill", "drill": drill, "policy": policy, "receive_policy": receive_policy,
                   "realism": realism, "field": field, "duration_s": duration_s},
            seeds={"seed": seed, "runs": runs}))
    return summary
