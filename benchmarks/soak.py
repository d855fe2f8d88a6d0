"""Soak test of the simulator (on demand, not in CI): many world-steps of random and
adversarial actions, checking invariants after every step.

    python benchmarks/soak.py [--steps 10000000] [--worlds 64] [--seed 0] [--out results/soak.json]
                              [--state runs/soak/state.json] [--fresh]

Drives :class:`ssl_marl.envs.batched_env.BatchedSSLEnv` through the three
configurations (1v0 Division B, 6v6 Division B, 11v11 Division A) and both realism
presets ("none", "realistic"), ``--steps`` world-steps in all, split evenly over
the six combinations and run in chunks of 100 batched steps. Each world follows one
action pattern, by world index:

0. uniform random actions;
1. bang-bang: every value at -1 or +1, held for 5-60 steps;
2. spinning at full angular speed while driving, dribbler on, kicking at full strength;
3. kicking into walls and goal corners: chase the ball, dribble, and kick at full
   strength whenever the robot faces a wall or a goal corner;
4. pushed together: every robot drives at full speed at the ball (a scrum), kicking now and then.

Episodes last 20 s (then autoreset); the referee is on (goals, ball out) and after a
goal play restarts at kickoff. Checked after every step (ground truth):

* non-finite values in positions, headings, velocities, angular velocities, ball
  state, observations or rewards;
* bodies outside the walls (robot centre beyond the wall minus its radius, ball
  centre beyond the wall minus its radius, by more than 1 cm);
* balls inside robots (the ball overlapping a robot's body, round part or flat
  front face, by more than 5 mm);
* speeds above the caps by more than 1 %: robot speed > ``max_speed``, robot
  angular speed > ``max_omega``, ball speed > ``kick_speed_max``.

Counts, the largest values seen and the first few offending cases (config, world,
step) are written to ``--out``; progress is kept in ``--state`` after each chunk so
that an interrupted soak resumes where it stopped (``--fresh`` starts over).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import sys
import time
from datetime import datetime, timezone
from pathlib import Path

import numpy as np
from tqdm import tqdm

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from ssl_marl.envs.batched_env import BatchedSSLEnv  # noqa: E402
from ssl_marl.io import atomic_write_json  # noqa: E402

CONFIGS = {"1v0_div_b": dict(n_blue=1, n_yellow=0, field="div_b"),
           "6v6_div_b": dict(n_blue=6, n_yellow=6, field="div_b"),
           "11v11_div_a": dict(n_blue=11, n_yellow=11, field="div_a")}
REALISM = ("none", "realistic")
CHUNK = 100  # batched steps between progress saves
CHECKS = ("non_finite", "outside_walls", "ball_inside_robot", "robot_speed_over_cap", "robot_omega_over_cap",
          "ball_speed_over_cap")


class Adversary:
    """Per-world action patterns (see the module docstring), as (K, n, 5) arrays."""

    def __init__(self, K: int, n: int, rng: np.random.Generator) -> None:
        self.K, self.n, self.rng = K, n, rng
        self.pattern = np.arange(K) % 5
        self.bang = rng.choice([-1.0, 1.0], (K, n, 5))
        self.hold = rng.integers(5, 60, (K, n))

    def __call__(self, env: BatchedSSLEnv) -> np.ndarray:
        K, n, rng, ph = self.K, self.n, self.rng, env.physics
        a = rng.uniform(-1, 1, (K, n, 5))
        # 1: bang-bang, values held for a random number of steps
        self.hold -= 1
        flip = self.hold <= 0
        self.bang[flip] = rng.choice([-1.0, 1.0], (int(flip.sum()), 5))
        self.hold[flip] = rng.integers(5, 60, int(flip.sum()))
        m = self.pattern == 1
        a[m] = self.bang[m]
        # heading to the ball in each robot's body frame
        d = ph.ball_pos[:, None, :] - ph.pos
        ang = np.angle(np.exp(1j * (np.arctan2(d[..., 1], d[..., 0]) - ph.heading)))
        chase = np.stack([np.cos(ang), np.sin(ang), np.clip(2 * ang, -1, 1)], axis=-1)
        # 2: spinning, driving, dribbling, kicking
        m = self.pattern == 2
        a[m, :, 2] = np.where(rng.random((int(m.sum()), n)) < 0.5, 1.0, -1.0)
        a[m, :, 3] = 1.0
        a[m, :, 4] = 1.0
        # 3: chase, dribble, kick at walls / goal corners
        m = self.pattern == 3
        f = env.field
        hx, hy = np.cos(ph.heading), np.sin(ph.heading)
        wall_ahead = (np.abs(ph.pos[..., 0] + hx * 1.0) > f.half_length) | (np.abs(ph.pos[..., 1] + hy * 1.0) > f.half_width)
        a[m, :, 0:3] = chase[m]
        a[m, :, 3] = 1.0
        a[m, :, 4] = np.where(wall_ahead[m], 1.0, -1.0)
        # 4: everyone drives at the ball at full speed (robots pushed together)
        m = self.pattern == 4
        a[m, :, 0:3] = chase[m] * 1.5
        a[m, :, 3] = 1.0
        a[m, :, 4] = np.where(rng.random((int(m.sum()), n)) < 0.02, 1.0, -1.0)
        return np.clip(a, -1, 1)


def check(env: BatchedSSLEnv, obs: np.ndarray, rew: np.ndarray) -> dict[str, np.ndarray]:
    """(K,) counts of each violation this step, and the values used for the maxima."""
    ph, cfg, f = env.physics, env.config, env.field
    rp, br = cfg.robot, cfg.ball.radius
    arrays = (ph.pos, ph.heading, ph.vel, ph.omega, ph.ball_pos, ph.ball_vel)
    nonfinite = sum((~np.isfinite(a)).reshape(env.K, -1).sum(axis=1) for a in arrays)
    nonfinite = nonfinite + (~np.isfinite(obs)).reshape(env.K, -1).sum(axis=1) + (~np.isfinite(rew)).sum(axis=1)
    tol = 0.01
    wx, wy = f.wall_half_length, f.wall_half_width
    outside = ((np.abs(ph.pos[..., 0]) > wx - rp.radius + tol) | (np.abs(ph.pos[..., 1]) > wy - rp.radius + tol)).sum(axis=1)
    outside += (np.abs(ph.ball_pos[:, 0]) > wx - br + tol) | (np.abs(ph.ball_pos[:, 1]) > wy - br + tol)
    d = ph.ball_pos[:, None, :] - ph.pos
    dist = np.hypot(d[..., 0], d[..., 1])
    lx = np.cos(ph.heading) * d[..., 0] + np.sin(ph.heading) * d[..., 1]
    pen = 0.005
    inside = ((dist < rp.radius + br - pen) & (lx < rp.front_distance + br - pen)).sum(axis=1)
    sp = np.hypot(ph.vel[..., 0], ph.vel[..., 1])
    bsp = np.hypot(ph.ball_vel[:, 0], ph.ball_vel[:, 1])
    return {"non_finite": nonfinite, "outside_walls": outside, "ball_inside_robot": inside,
            "robot_speed_over_cap": (sp > rp.max_speed * 1.01).sum(axis=1),
            "robot_omega_over_cap": (np.abs(ph.omega) > rp.max_omega * 1.01).sum(axis=1),
            "ball_speed_over_cap": bsp > rp.kick_speed_max * 1.01,
            "_max": {"robot_speed": float(np.nanmax(sp)), "robot_omega": float(np.nanmax(np.abs(ph.omega))),
                     "ball_speed": float(np.nanmax(bsp)),
                     "ball_penetration": float(np.nanmax(np.minimum(rp.radius + br - dist, rp.front_distance + br - lx)))}}


def run(args) -> dict:
    state_path = Path(args.state)
    combos = [(c, r) for c in args.configs for r in args.realism]
    per_combo = args.steps // len(combos)
    state = None
    if state_path.exists() and not args.fresh:
        state = json.loads(state_path.read_text())
        if state.get("steps") != args.steps or state.get("worlds") != args.worlds or state.get("seed") != args.seed:
            raise SystemExit(f"{state_path} belongs to another soak (steps/worlds/seed differ): use --fresh")
    if state is None:
        state = {"steps": args.steps, "worlds": args.worlds, "seed": args.seed, "done": {}, "wall_s": {},
                 "counts": {}, "max": {}, "examples": []}
    total_done = sum(state["done"].values())
    bar = tqdm(total=per_combo * len(combos), initial=total_done, unit="world-step", unit_scale=True, smoothing=0.05,
               disable=args.report_only)
    for cname, realism in combos:
        ci = list(CONFIGS).index(cname) * len(REALISM) + REALISM.index(realism)  # seeds as in a full soak
        key = f"{cname}/{realism}"
        done = state["done"].get(key, 0)
        if done >= per_combo or args.report_only:
            continue
        env = BatchedSSLEnv(args.worlds, **CONFIGS[cname], realism=realism, max_time_s=20.0, randomize_reset=True)
        rng = np.random.default_rng([args.seed, ci, done])
        env.reset(seed=args.seed * 1000 + ci * 100 + done // args.worlds)
        adv = Adversary(args.worlds, env.n, rng)
        counts = state["counts"].setdefault(key, {c: 0 for c in CHECKS})
        mx = state["max"].setdefault(key, {})
        while done < per_combo:
            t0 = time.perf_counter()
            steps = min(CHUNK, math.ceil((per_combo - done) / args.worlds))
            for s in range(steps):
                obs, rew, _, _, _ = env.step(adv(env))
                res = check(env, obs, rew)
                for c in CHECKS:
                    bad = res[c]
                    nbad = int(np.sum(bad))
                    if nbad:
                        counts[c] += nbad
                        if len(state["examples"]) < 50:
                            state["examples"].append({"check": c, "config": key, "world": int(np.flatnonzero(bad)[0]),
                                                      "world_step_of_combo": done + s * args.worlds})
                for k, v in res["_max"].items():
                    mx[k] = max(mx.get(k, -math.inf), v)
            n_ws = steps * args.worlds
            done += n_ws
            state["done"][key] = done
            state["wall_s"][key] = state["wall_s"].get(key, 0.0) + time.perf_counter() - t0
            atomic_write_json(state_path, state)
            bar.update(n_ws)
        env.close()
    bar.close()
    total = sum(state["done"].values())
    wall = sum(state["wall_s"].values())
    return {"date_utc": datetime.now(timezone.utc).isoformat(timespec="seconds"),
            "machine": f"{platform.machine()}, {os.cpu_count()} cores", "python": platform.python_version(),
            "requested_world_steps": args.steps, "combinations": [f"{c}/{r}" for c, r in combos], "world_steps_run": total, "wall_s": round(wall, 1),
            "world_steps_per_s": round(total / wall) if wall else None, "worlds": args.worlds, "seed": args.seed,
            "totals": {c: sum(v[c] for v in state["counts"].values()) for c in CHECKS},
            "per_combination": {k: {"world_steps": state["done"][k], "wall_s": round(state["wall_s"][k], 1),
                                    "counts": state["counts"][k], "max": state["max"][k]} for k in state["done"]},
            "examples": state["examples"]}


def main(argv: list[str] | None = None) -> dict:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--steps", type=int, default=10_000_000, help="world-steps in all (default 10,000,000)")
    p.add_argument("--worlds", type=int, default=64, help="worlds stepped together (default 64)")
    p.add_argument("--seed", type=int, default=0, help="seed (default 0)")
    p.add_argument("--out", default="results/soak.json", help="result JSON (default results/soak.json)")
    p.add_argument("--state", default="runs/soak/state.json", help="progress file for resuming (default runs/soak/state.json)")
    p.add_argument("--fresh", action="store_true", help="ignore an existing progress file and start over")
    p.add_argument("--configs", nargs="+", choices=list(CONFIGS), default=list(CONFIGS),
                   help="configurations to soak (default: all three); --steps is split over the chosen combinations")
    p.add_argument("--realism", nargs="+", choices=list(REALISM), default=list(REALISM),
                   help="realism presets to soak (default: both)")
    p.add_argument("--report-only", action="store_true",
                   help="write --out from the progress file as it stands (e.g. of an interrupted soak), run nothing")
    args = p.parse_args(argv)
    if args.steps < 1 or args.worlds < 1:
        p.error("--steps and --worlds must be positive")
    res = run(args)
    atomic_write_json(args.out, res)
    print(json.dumps({k: res[k] for k in ("world_steps_run", "wall_s", "world_steps_per_s", "totals")}, indent=2))
    return res


if __name__ == "__main__":
    main()
