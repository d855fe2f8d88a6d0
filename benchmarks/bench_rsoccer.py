"""rSoccer / rSim and ssl_marl side by side in one process, in simulated seconds per wall second.

    python benchmarks/bench_rsoccer.py [--seconds 2] [--rounds 3] [--worlds 64] [--out results/bench_rsoccer.json]

rSoccer (``rsoccer-gym``, with its rSim/ODE simulator ``rc-robosim``) installs only on
Python 3.10; run this script with such a venv (see docs/BENCHMARKS.md, "rSoccer
comparison"). Without rSoccer it measures ssl_marl alone and says so.

Three configurations, each alternating round by round between the
systems (median over rounds reported):

==========  ====================================================  ==========================
config      rSoccer side                                          ssl_marl side
==========  ====================================================  ==========================
1 robot     ``gym.make("SSLGoToBallShoot-v0").unwrapped`` (its    1v0, Division B
            registered kwargs, 40 Hz), random actions, reset on
            done
6v6 Div B   raw ``robosim.SSL`` (no gym layer), field_type 1,     6v6, Division B
            25 ms steps (40 Hz), random vx, vy, omega, kick,
            dribbler per robot, ``step`` + ``get_state``
11v11 Div A raw ``robosim.SSL``, field_type 0, 40 Hz, as above     11v11, Division A
==========  ====================================================  ==========================

ssl_marl: the single env (``SSLParallelEnv``, 60 Hz, 2 Box2D sub-steps) and the
batched env (``BatchedSSLEnv``, ``--worlds`` worlds in this one process), random
actions for every robot, ``randomize_reset``. Everything runs on one core (one
process, no threads), so the figures are per core. Simulated seconds per wall
second = steps/s x control period (rSoccer 0.025 s, ssl_marl 1/60 s; batched:
world-steps/s x 1/60).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import sys
import time
import warnings
from datetime import datetime, timezone
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from ssl_marl.envs import SSLParallelEnv  # noqa: E402
from ssl_marl.envs.batched_env import BatchedSSLEnv  # noqa: E402
from ssl_marl.io import atomic_write_json  # noqa: E402

RSOCCER_DT = 0.025
OURS_DT = 1.0 / 60.0
CONFIGS = {"1_robot": dict(ours=dict(n_blue=1, n_yellow=0, field="div_b"), rsoccer="SSLGoToBallShoot-v0"),
           "6v6_div_b": dict(ours=dict(n_blue=6, n_yellow=6, field="div_b"), rsim=(1, 6, 6)),
           "11v11_div_a": dict(ours=dict(n_blue=11, n_yellow=11, field="div_a"), rsim=(0, 11, 11))}


def _import_rsoccer():
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            import gym  # rSoccer is built on the old gym API
            import robosim
            import rsoccer_gym  # noqa: F401  (registers the envs)
        return gym, robosim
    except Exception as e:  # noqa: BLE001  (absent or broken: skip that side)
        print(f"rSoccer not available ({type(e).__name__}: {e}); measuring ssl_marl only", file=sys.stderr)
        return None, None


class RSoccerGym:
    """rSoccer's gym env (unwrapped), random actions, reset when done."""

    def __init__(self, gym, env_id: str, seed: int) -> None:
        self.env = gym.make(env_id).unwrapped
        self.env.action_space.seed(seed)
        self.env.reset()
        self.acts = [self.env.action_space.sample() for _ in range(256)]
        self.i = 0

    def step(self) -> None:
        out = self.env.step(self.acts[self.i & 255])
        self.i += 1
        if out[2]:
            self.env.reset()


class RawRSim:
    """rSim (robosim.SSL) with no gym layer: random commands, step, read the state."""

    def __init__(self, robosim, field_type: int, nb: int, ny: int, seed: int) -> None:
        rng = np.random.default_rng(seed)
        blue = [[-0.3 * (i + 1), 0.4 * ((i % 3) - 1), 0.0] for i in range(nb)]
        yellow = [[0.3 * (i + 1), 0.4 * ((i % 3) - 1), 180.0] for i in range(ny)]
        self.sim = robosim.SSL(field_type, nb, ny, int(RSOCCER_DT * 1000), [0.0, 0.0, 0.0, 0.0], blue, yellow)
        n = nb + ny
        cmds = np.zeros((256, n, 8))
        cmds[..., 1:3] = rng.uniform(-2.0, 2.0, (256, n, 2))  # vx, vy (m/s)
        cmds[..., 3] = rng.uniform(-10.0, 10.0, (256, n))  # omega (rad/s)
        cmds[..., 5] = np.where(rng.random((256, n)) < 0.05, rng.uniform(0, 6.5, (256, n)), 0.0)  # kick vx
        cmds[..., 7] = rng.random((256, n)) < 0.5  # dribbler
        self.cmds, self.i = cmds, 0

    def step(self) -> None:
        self.sim.step(self.cmds[self.i & 255])
        self.sim.get_state()
        self.i += 1


class OursSingle:
    def __init__(self, config: dict, seed: int) -> None:
        self.env = SSLParallelEnv(**config, randomize_reset=True, max_time_s=1e9)
        self.env.reset(seed=seed)
        a = np.random.default_rng(seed).uniform(-1, 1, (256, self.env.n, 5)).astype(np.float32)
        self.acts = [dict(zip(self.env.possible_agents, x)) for x in a]
        self.i = 0

    def step(self) -> None:
        self.env.step(self.acts[self.i & 255])
        self.i += 1


class OursBatched:
    def __init__(self, config: dict, worlds: int, seed: int) -> None:
        self.env = BatchedSSLEnv(worlds, **config, randomize_reset=True, max_time_s=1e9)
        self.env.reset(seed=seed)
        self.acts = np.random.default_rng(seed).uniform(-1, 1, (64, worlds, self.env.n, 5)).astype(np.float32)
        self.i = 0

    def step(self) -> None:
        self.env.step(self.acts[self.i & 63])
        self.i += 1


def _rate(step, seconds: float) -> float:
    """Calls per wall second of step() over about ``seconds``."""
    calls, t0 = 0, time.perf_counter()
    while True:
        for _ in range(5):
            step()
        calls += 5
        el = time.perf_counter() - t0
        if el >= seconds:
            return calls / el


def measure(name: str, spec: dict, gym, robosim, worlds: int, seconds: float, rounds: int, seed: int = 0) -> dict:
    systems: dict[str, tuple] = {}  # name -> (step function, world-steps per call, control period s)
    if gym is not None:
        if "rsoccer" in spec:
            systems["rsoccer"] = (RSoccerGym(gym, spec["rsoccer"], seed).step, 1, RSOCCER_DT)
        else:
            systems["rsoccer"] = (RawRSim(robosim, *spec["rsim"], seed).step, 1, RSOCCER_DT)
    systems["ours_single"] = (OursSingle(spec["ours"], seed).step, 1, OURS_DT)
    systems["ours_batched"] = (OursBatched(spec["ours"], worlds, seed).step, worlds, OURS_DT)
    rates: dict[str, list[float]] = {k: [] for k in systems}
    for r in range(rounds + 1):  # round 0: warm-up
        for k, (fn, per_call, _) in systems.items():
            x = _rate(fn, seconds if r else min(0.3, seconds)) * per_call
            if r:
                rates[k].append(x)
    out: dict = {}
    for k, (_, _, dt) in systems.items():
        med = statistics.median(rates[k])
        out[k] = {"steps_per_s": round(med, 1), "control_hz": round(1 / dt, 2), "sim_s_per_wall_s": round(med * dt, 2),
                  "rounds_steps_per_s": [round(x, 1) for x in rates[k]]}
    if "rsoccer" in out:
        base = out["rsoccer"]["sim_s_per_wall_s"]
        for k in ("ours_single", "ours_batched"):
            out[k]["sim_time_ratio_vs_rsoccer"] = round(out[k]["sim_s_per_wall_s"] / base, 2)
    return out


def main(argv: list[str] | None = None) -> dict:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--seconds", type=float, default=2.0, help="timed seconds per system, config and round (default 2)")
    p.add_argument("--rounds", type=int, default=3, help="interleaved rounds, median reported (default 3)")
    p.add_argument("--worlds", type=int, default=64, help="worlds in ssl_marl's batched env (default 64)")
    p.add_argument("--configs", nargs="+", choices=sorted(CONFIGS), default=list(CONFIGS), help="configurations")
    p.add_argument("--out", default="results/bench_rsoccer.json", help="output JSON (default results/bench_rsoccer.json)")
    args = p.parse_args(argv)
    gym, robosim = _import_rsoccer()
    res: dict = {"date_utc": datetime.now(timezone.utc).isoformat(timespec="seconds"),
                 "machine": f"{platform.machine()}, {os.cpu_count()} cores", "python": platform.python_version(),
                 "rsoccer_available": gym is not None, "load_avg_before": os.getloadavg(), "worlds": args.worlds,
                 "seconds": args.seconds, "rounds": args.rounds, "configs": {}}
    if gym is not None:
        from importlib.metadata import version

        res["versions"] = {p_: version(p_) for p_ in ("rsoccer-gym", "rc-robosim")}
    for name in args.configs:
        res["configs"][name] = measure(name, CONFIGS[name], gym, robosim, args.worlds, args.seconds, args.rounds)
        print(name, json.dumps(res["configs"][name]), flush=True)
    res["load_avg_after"] = os.getloadavg()
    atomic_write_json(args.out, res)
    return res


if __name__ == "__main__":
    main()
