"""Decisions per CPU-second: the decision drills (keepaway, attack 3v2, the attack drills) and full matches.

A benchmark, not a test. CPU time (``time.process_time``), one process, so the load of a
shared machine does not enter; the record keeps the load average and the machine anyway.

* **Drills**: hand-coded decision policy (or ``--policy``), ``--episodes`` episodes per
  task from ``--seed``: control ticks, simulated seconds and option-level decisions per
  CPU-second.
* **Matches**: ``--match-seconds`` of a 6v6 Division B match (plain format) of the
  attacking team with hand-coded skills against the no-pass baseline team: ticks and
  simulated seconds per CPU-second, and the carrier decisions the attacking team's pass
  coordinator took (every ``decide_every`` ticks while a carrier has settled the ball,
  and at set pieces).
* **Full matches as the decision task** (``attack-match``, what MAPPO trains on): one
  ``--match-seconds`` episode, the attacking team's carrier decisions by the shipped
  attack-drill actor, against the attacking team with the cost decision: option-level
  decisions per CPU-second; once in the plain format and once under SSL rules (``ssl_rules``:
  game control and the dribble mask).

    python benchmarks/decision_speed.py [--episodes 20] [--match-seconds 120] [--out results/bench_decisions.json]
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import time

from ssl_marl.decisions import make_decision_env, make_decision_policy
from ssl_marl.decisions.policies import run_episode
from ssl_marl.io import atomic_write_json
from ssl_marl.runners.provenance import build_manifest

DRILLS = ("keepaway", "attack-3v2", "attack-drill", "attack-drill-ssl", "attack-drill-defended")


def drill_speed(task: str, policy: str, episodes: int, seed: int) -> dict:
    """Per-CPU-second throughput of ``episodes`` episodes of the decision drill ``task``."""
    env = make_decision_env(task)
    pol = make_decision_policy(policy, task)
    run_episode(env, pol, seed=seed - 1)  # warm-up (imports, first allocations)
    c0 = time.process_time()
    sim = dec = ticks = 0
    for s in range(episodes):
        r = run_episode(env, pol, seed=seed + s)
        sim, dec, ticks = sim + r["t_s"], dec + r["decisions"], ticks + env.ticks
    cpu = time.process_time() - c0
    return {"task": task, "policy": policy, "episodes": episodes, "seeds": [seed, seed + episodes - 1],
            "ticks": ticks, "sim_s": sim, "decisions": dec, "cpu_s": cpu, "ticks_per_cpu_s": ticks / cpu,
            "sim_s_per_cpu_s": sim / cpu, "decisions_per_cpu_s": dec / cpu}


def match_speed(seconds: float, seed: int) -> dict:
    """Per-CPU-second throughput of one attack-baseline vs baseline match of ``seconds``."""
    from ssl_marl.envs.config import EnvConfig
    from ssl_marl.physics.field import FieldGeometry
    from ssl_marl.plays.attack_play import attack_decider_of
    from ssl_marl.runners.controllers import make_controller
    from ssl_marl.runners.match import play_match

    cfg = EnvConfig(chip_kicks=True)
    blue = make_controller("attack-baseline", "blue", 6, FieldGeometry.div_b(), seed=seed, robot=cfg.robot,
                           ball=cfg.ball, dt=cfg.dt)
    c0 = time.process_time()
    res = play_match(blue, "baseline", robots=6, seconds=seconds, seed=seed, progress=False,
                     env_kwargs={"chip_kicks": True})
    cpu = time.process_time() - c0
    counters = vars(attack_decider_of(blue.selector.plays).counters)
    dec = sum(v for k, v in counters.items() if k != "redirected")
    ticks = round(seconds / cfg.dt)
    return {"match": "attack-baseline vs baseline, 6v6 div_b, plain", "seed": seed, "seconds": seconds,
            "score": res.score, "decisions": dec, "decisions_by_kind": counters, "ticks": ticks, "cpu_s": cpu,
            "ticks_per_cpu_s": ticks / cpu, "sim_s_per_cpu_s": seconds / cpu, "decisions_per_cpu_s": dec / cpu}


def match_task_speed(seconds: float, seed: int, ssl_rules: bool = False) -> dict:
    """Per-CPU-second throughput of one ``seconds`` episode of the attack-match decision task
    (``ssl_rules``: under SSL game control)."""
    from ssl_marl.decisions import make_decision_policy
    from train.mappo.tasks import get_task

    env = get_task("attack-match").factory(opponents=("attack-learned",), seconds=seconds, ssl_rules=ssl_rules)
    pol = make_decision_policy("learned", "attack-drill")
    c0 = time.process_time()
    r = run_episode(env, pol, seed=seed)
    cpu = time.process_time() - c0
    return {"task": "attack-match", "ssl_rules": ssl_rules, "policy": "learned (attack_drill.pt)", "opponent": r["opponent"], "seed": seed,
            "seconds": seconds, "goals": [r["goals_for"], r["goals_against"]], "ticks": env.ticks,
            "decisions": r["decisions"], "cpu_s": cpu, "ticks_per_cpu_s": env.ticks / cpu,
            "sim_s_per_cpu_s": r["t_s"] / cpu, "decisions_per_cpu_s": r["decisions"] / cpu}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--episodes", type=int, default=20, help="episodes per drill (default 20)")
    ap.add_argument("--seed", type=int, default=44990, help="first drill episode seed (default 44990)")
    ap.add_argument("--policy", default="handcoded", help="drill decision policy (default handcoded)")
    ap.add_argument("--match-seconds", type=float, default=120.0,
                    help="simulated seconds of the timed match (default 120; 0 skips it)")
    ap.add_argument("--match-seed", type=int, default=44990, help="match seed (default 44990)")
    ap.add_argument("--out", default=None, help="write the record (JSON) here")
    a = ap.parse_args()
    rows = [drill_speed(t, a.policy, a.episodes, a.seed) for t in DRILLS]
    match = match_speed(a.match_seconds, a.match_seed) if a.match_seconds > 0 else None
    match_task = match_task_speed(a.match_seconds, a.match_seed) if a.match_seconds > 0 else None
    match_task_ssl = match_task_speed(a.match_seconds, a.match_seed, ssl_rules=True) if a.match_seconds > 0 else None
    rec = {"drills": rows, "match": match, "match_task": match_task, "match_task_ssl": match_task_ssl,
           "load_average": list(os.getloadavg()),
           "machine": {"cpu_count": os.cpu_count(), "processor": platform.processor() or platform.machine()},
           "date": time.strftime("%Y-%m-%d"),
           "manifest": build_manifest(rules={"policy": a.policy}, seeds={"seed": a.seed, "episodes": a.episodes,
                                                                         "match_seed": a.match_seed})}
    print(json.dumps(rec, indent=1, default=str))
    if a.out:
        atomic_write_json(a.out, rec)


if __name__ == "__main__":
    main()
