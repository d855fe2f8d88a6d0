"""Throughput benchmark: ``ssl-marl bench`` (or ``python -m ssl_marl.cli bench``) prints JSON.

Env steps/s with uniformly random actions for every robot, single process, 60 Hz
control, for 1v0 (Division B), 6v6 Division B and 11v11 Division A; mean reset
time; and, when the shipped actors exist, the per-call time of a learned skill.
A benchmark, not a test: numbers depend on the machine (see docs/BENCHMARKS.md).
"""

from __future__ import annotations

import argparse
import json
import platform
import time
from datetime import date

import numpy as np

from .options import add_forwarded_parser

CONFIGS = {"1v0_div_b": dict(n_blue=1, n_yellow=0, field="div_b"),
           "6v6_div_b": dict(n_blue=6, n_yellow=6, field="div_b"),
           "11v11_div_a": dict(n_blue=11, n_yellow=11, field="div_a")}


def bench_env(config: dict, steps: int, resets: int, seed: int = 0) -> dict:
    """Steps per second, time per step (us) and per reset (ms) of one env configuration
    (``parallel_env`` keyword arguments) with uniformly random actions."""
    from ..envs import parallel_env

    env = parallel_env(**config, randomize_reset=True, max_time_s=1e9)
    env.reset(seed=seed)
    rng = np.random.default_rng(seed)
    acts = rng.uniform(-1, 1, (steps, env.n, 5)).astype(np.float32)
    actions = [dict(zip(env.possible_agents, acts[k])) for k in range(steps)]
    for k in range(min(200, steps)):  # warm-up
        env.step(actions[k])
    t0 = time.perf_counter()
    for a in actions:
        env.step(a)
    t_step = (time.perf_counter() - t0) / steps
    t0 = time.perf_counter()
    for _ in range(resets):
        env.reset()
    t_reset = (time.perf_counter() - t0) / resets
    return {"steps_per_s": round(1.0 / t_step), "step_us": round(t_step * 1e6, 1),
            "reset_ms": round(t_reset * 1e3, 3), "robots": env.n}


def bench_skill_inference(calls: int = 2000) -> dict:
    """Per-call time of the learned skills' act() (features + numpy actor)."""
    from ..envs import parallel_env
    from ..skills import make_skill
    from ..skills.registry import get_skill

    out = {}
    env = parallel_env(n_blue=1, n_yellow=0)
    reach = env.config.robot.front_distance + env.config.ball.radius
    for name in ("go_to_ball", "aim_to_shoot"):
        ball = (2.0, 1.0) if name == "go_to_ball" else (2.0 + reach, 0.0)  # aim-to-shoot: ball on the dribbler
        env.reset(options={"robots": {"blue_0": (2.0, 0.0, 0.0)}, "ball": {"pos": ball}})
        ws = env.vision_state("blue")
        if not get_skill(name).actor.exists():
            out[name] = None
            continue
        skill = make_skill(name, "learned", env.field)
        skill.act(ws, 0)
        t0 = time.perf_counter()
        for _ in range(calls):
            skill.reset()  # aim-to-shoot would otherwise stop after its first kick
            skill.act(ws, 0)
        out[name + "_act_ms"] = round((time.perf_counter() - t0) / calls * 1e3, 4)
    return out


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``bench`` subparser (its options are this module's :func:`main`'s)."""
    b = add_forwarded_parser(subparsers, "bench", "env throughput benchmark (JSON); options: ssl-marl bench --help",
                             "the benchmark (this module's main)")
    b.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Forward everything after ``bench`` (a leading ``--`` is dropped) to :func:`main`."""
    main(args.rest)
    return 0


def main(argv: list[str] | None = None) -> dict:
    """Parse the benchmark's options (``argv``), run it and print the result as JSON."""
    p = argparse.ArgumentParser(prog="ssl-marl bench", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--steps", type=int, default=5000, help="env steps timed per configuration (default 5000)")
    p.add_argument("--resets", type=int, default=200, help="resets timed per configuration (default 200)")
    p.add_argument("--configs", nargs="+", choices=sorted(CONFIGS), default=list(CONFIGS),
                   help="configurations to run (default: all)")
    p.add_argument("--no-skills", action="store_true", help="skip the learned-skill inference timing")
    args = p.parse_args(argv)
    result = {"date": date.today().isoformat(), "machine": f"{platform.machine()} {platform.processor() or ''}".strip(),
              "python": platform.python_version(), "control_hz": 60}
    for name in args.configs:
        result[name] = bench_env(CONFIGS[name], args.steps, args.resets)
    if not args.no_skills:
        result["learned_skill_inference"] = bench_skill_inference()
    print(json.dumps(result, indent=2))
    return result

