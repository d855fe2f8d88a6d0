"""The Box2D floor: how fast can the env's own Box2D world go, and how close are the envs?

    python benchmarks/bench_floor.py [--worlds 64] [--seconds 2] [--rounds 3] [--out results/bench_floor.json]

For 1v0 Division B, 6v6 Division B and 11v11 Division A, in one process and
alternating round by round (so that load from other jobs hits all alike):

* ``floor``: K worlds built by :class:`ssl_marl.physics.world.PhysicsWorld` itself
  (same fixtures, shapes, ``SCALE``, sub-steps, solver iterations, contact handling)
  doing only "set every robot's velocity, take the sub-steps, read every body".
  Velocities are written and bodies read the fastest way this package knows (one
  numpy scatter / gather over Box2D's memory, :mod:`ssl_marl.physics.body_memory`);
  ``floor_swig`` is the same per world through pybox2d's SWIG accessors.
* ``single_env``: :class:`ssl_marl.envs.ssl_env.SSLParallelEnv`, random actions.
* ``batched_env``: :class:`ssl_marl.envs.batched_env.BatchedSSLEnv` with K worlds,
  random actions (world-steps/s = K x batched steps/s).

Reports world-steps/s (median over rounds) and the ratio of each env's time per
world-step to the floor's. Random actions for every robot, 60 Hz, 2 sub-steps,
``randomize_reset`` on, no referee events excluded (they happen as they happen).
A benchmark, not a test.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import sys
import time
from datetime import datetime, timezone
from pathlib import Path

import numpy as np
from Box2D._Box2D import b2World_Step

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from ssl_marl.envs import SSLParallelEnv  # noqa: E402
from ssl_marl.envs.batched_env import BatchedSSLEnv  # noqa: E402
from ssl_marl.io import atomic_write_json  # noqa: E402
from ssl_marl.physics import body_memory as bm  # noqa: E402
from ssl_marl.physics.units import POS_ITERS, SCALE, VEL_ITERS  # noqa: E402
from ssl_marl.physics.world import PhysicsWorld  # noqa: E402

CONFIGS = {"1v0_div_b": dict(n_blue=1, n_yellow=0, field="div_b"),
           "6v6_div_b": dict(n_blue=6, n_yellow=6, field="div_b"),
           "11v11_div_a": dict(n_blue=11, n_yellow=11, field="div_a")}


class Floor:
    """K bare worlds: set velocities, step, read. Nothing else."""

    def __init__(self, config: dict, n_worlds: int, seed: int = 0, swig: bool = False) -> None:
        env = SSLParallelEnv(**config, randomize_reset=True)  # only to draw the same kind of initial scene
        cfg = env.config
        self.worlds = []
        for k in range(n_worlds):
            env.reset(seed=seed + k)
            ws = env.world_state()
            w = PhysicsWorld(cfg.field, cfg.robot, cfg.ball, cfg.n_blue, cfg.n_yellow, cfg.dt, cfg.physics_substeps)
            pose = np.column_stack([np.concatenate([ws.blue.pos, ws.yellow.pos]),
                                    np.concatenate([ws.blue.heading, ws.yellow.heading])])
            w.reset(pose, ws.ball_pos)
            self.worlds.append(w)
        self.n, self.K, self.swig = env.n, n_worlds, swig
        self.substeps, self.sub_dt = cfg.physics_substeps, cfg.dt / cfg.physics_substeps
        self.vmax, self.wmax = cfg.robot.max_speed, cfg.robot.max_omega
        self.b2 = [w.world for w in self.worlds]
        self.bodies = [w._robot_bodies + [w._ball_body] for w in self.worlds]
        addr = np.array([[bm.address(b) for b in bodies] for bodies in self.bodies])
        self.mem, self.slot = bm.span_view(addr)
        self.rng = np.random.default_rng(seed)

    def step(self, actions: np.ndarray) -> np.ndarray:
        """actions (K, n, 3) in [-1, 1]: field-frame vx, vy, omega (no controller)."""
        S, n = SCALE, self.n
        vals = actions * np.array([self.vmax * S, self.vmax * S, self.wmax])
        if self.swig:
            for bodies, v in zip(self.bodies, vals.tolist()):
                for b, (vx, vy, w) in zip(bodies, v):
                    b.linearVelocity = (vx, vy)
                    b.angularVelocity = w
        else:
            self.mem[self.slot[:, :n, None] + np.array([16, 17, 18])] = vals
        for _ in range(self.substeps):
            for w in self.b2:
                b2World_Step(w, self.sub_dt, VEL_ITERS, POS_ITERS)
        if self.swig:
            out = np.empty((self.K, n + 1, 6))
            for k, bodies in enumerate(self.bodies):
                for i, b in enumerate(bodies):
                    p, v = b.position, b.linearVelocity
                    out[k, i] = (p[0], p[1], b.angle, v[0], v[1], b.angularVelocity)
            return out
        return self.mem[self.slot[..., None] + np.array([3, 4, 14, 16, 17, 18])].astype(np.float64)


def _time_loop(step, acts: np.ndarray, seconds: float) -> tuple[int, float]:
    """Call step(acts[i % len]) for about ``seconds``; return (calls, elapsed)."""
    n_a = len(acts)
    calls, t0 = 0, time.perf_counter()
    while True:
        for _ in range(10):
            step(acts[calls % n_a])
            calls += 1
        el = time.perf_counter() - t0
        if el >= seconds:
            return calls, el


def measure(config: dict, n_worlds: int, seconds: float, rounds: int, seed: int = 0) -> dict:
    n = config["n_blue"] + config["n_yellow"]
    rng = np.random.default_rng(seed)
    floor = Floor(config, n_worlds, seed)
    floor_swig = Floor(config, n_worlds, seed, swig=True)
    single = SSLParallelEnv(**config, randomize_reset=True, max_time_s=1e9)
    single.reset(seed=seed)
    batched = BatchedSSLEnv(n_worlds, **config, randomize_reset=True, max_time_s=1e9)
    batched.reset(seed=seed)
    acts_floor = rng.uniform(-1, 1, (64, n_worlds, n, 3))
    acts_batched = rng.uniform(-1, 1, (64, n_worlds, n, 5)).astype(np.float32)
    acts_single = [dict(zip(single.possible_agents, a)) for a in acts_batched[:, 0]]
    runs: dict[str, list[float]] = {k: [] for k in ("floor", "floor_swig", "single_env", "batched_env")}
    for r in range(rounds + 1):  # round 0 warms up, not reported
        for name, fn, acts, per_call in (("floor", floor.step, acts_floor, n_worlds),
                                         ("floor_swig", floor_swig.step, acts_floor, n_worlds),
                                         ("single_env", single.step, acts_single, 1),
                                         ("batched_env", batched.step, acts_batched, n_worlds)):
            calls, el = _time_loop(fn, acts, seconds if r else min(seconds, 0.3))
            if r:
                runs[name].append(calls * per_call / el)
    med = {k: statistics.median(v) for k, v in runs.items()}
    out = {k: {"world_steps_per_s": round(v), "us_per_world_step": round(1e6 / v, 2),
               "rounds": [round(x) for x in runs[k]]} for k, v in med.items()}
    for k in ("floor_swig", "single_env", "batched_env"):
        out[k]["time_ratio_to_floor"] = round(med["floor"] / med[k], 3)
    out["batched_over_single"] = round(med["batched_env"] / med["single_env"], 2)
    return out


def main(argv: list[str] | None = None) -> dict:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--worlds", type=int, default=64, help="K worlds for the floor and the batched env (default 64)")
    p.add_argument("--seconds", type=float, default=2.0, help="timed seconds per configuration and round (default 2)")
    p.add_argument("--rounds", type=int, default=3, help="interleaved rounds; the median is reported (default 3)")
    p.add_argument("--configs", nargs="+", choices=sorted(CONFIGS), default=list(CONFIGS), help="configurations")
    p.add_argument("--out", default="results/bench_floor.json", help="output JSON (default results/bench_floor.json)")
    args = p.parse_args(argv)
    res: dict = {"date_utc": datetime.now(timezone.utc).isoformat(timespec="seconds"),
                 "machine": f"{platform.machine()}, {os.cpu_count()} cores", "python": platform.python_version(),
                 "load_avg_before": os.getloadavg(), "worlds": args.worlds, "seconds": args.seconds,
                 "rounds": args.rounds, "body_memory_fast_path": bm.layout_ok(), "configs": {}}
    for name in args.configs:
        res["configs"][name] = measure(CONFIGS[name], args.worlds, args.seconds, args.rounds)
        print(name, json.dumps(res["configs"][name]), flush=True)
    res["load_avg_after"] = os.getloadavg()
    atomic_write_json(args.out, res)
    return res


if __name__ == "__main__":
    main()
