"""Vision tracker error figures: raw vision vs the tracker against ground truth.

    python benchmarks/tracker_errors.py [--episodes 20] [--match-seconds 60] [--seed 40000]
                                        [--out results/tracker_errors.json]

Runs the env with ``realism="realistic"`` (noise, 50 ms vision delay, one step of
radio delay, 5 % ball dropout, 3 % lost commands) through
:class:`ssl_marl.envs.tracking.TrackedVisionEnv`, with the robots' controllers
reading the tracked state (the deployed configuration), and records every step:

* the truth at the time the next command starts to act (now + radio delay), the
  tracker's prediction for that time and the raw vision frame (the naive choice);
* the truth at the raw frame's capture time and the tracker's filter estimate at that
  time (noise filtering alone, no latency).

Scenarios: ``tactic``: one blue robot with the paper's go-to-ball-and-shoot tactic
(baseline skills) from random scenes (ball held, kicked, rolling, bouncing);
``match``: 6 v 6 baseline STP teams on Division B, blue's tracker (own robots
predicted through their commands, opponents at constant velocity, the ball).

Reported per scenario and object class: RMS position (m), velocity (m/s) and heading
(rad) error, and the ball split into moving (free, truth speed > 0.05 m/s), at rest,
held (truth on a dribbler) and unseen (frames the camera dropped the ball), plus the
agreement of the ball-on-dribbler flags with the truth. Seeds 40000+ (never used for
training, selection or the reported evaluations).
"""

from __future__ import annotations

import argparse
import datetime as _dt
import os
import platform
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from ssl_marl.envs import parallel_env
from ssl_marl.envs.tracking import TrackedVisionEnv
from ssl_marl.io import atomic_write_json, episode_seed
from ssl_marl.physics.state import to_team_frame, wrap_angle

TELEPORT_STEPS = 6  # vision delay (3) + radio delay (1) + 2
KINDS = ("raw_target", "tracker_target", "raw_capture", "tracker_capture")


class Acc:
    """Squared-error accumulators per (group, kind, quantity)."""

    def __init__(self) -> None:
        self.sq: dict = {}
        self.n: dict = {}

    def add(self, group: str, kind: str, qty: str, err: np.ndarray) -> None:
        err = np.atleast_1d(np.asarray(err, float))
        if err.size == 0:
            return
        key = (group, kind, qty)
        self.sq[key] = self.sq.get(key, 0.0) + float(np.sum(err ** 2))
        self.n[key] = self.n.get(key, 0) + int(err.size)

    def table(self) -> dict:
        out: dict = {}
        for (group, kind, qty), s in sorted(self.sq.items()):
            n = self.n[(group, kind, qty)]
            g = out.setdefault(group, {}).setdefault(kind, {})
            g[f"{qty}_rms"] = float(np.sqrt(s / n))
            g["samples"] = max(g.get("samples", 0), n)
        return out


def _norm(d: np.ndarray) -> np.ndarray:
    d = np.asarray(d, float)
    return np.hypot(d[..., 0], d[..., 1])


def _robots(acc: Acc, group: str, kind: str, est, truth) -> None:
    acc.add(group, kind, "pos_m", _norm(est.pos - truth.pos))
    acc.add(group, kind, "vel_mps", _norm(est.vel - truth.vel))
    acc.add(group, kind, "heading_rad", wrap_angle(est.heading - truth.heading))


def _ball_group(truth, visible: bool) -> list[str]:
    held = bool(truth.blue.ball_on_dribbler.any() or truth.yellow.ball_on_dribbler.any())
    groups = ["ball_all", "ball_held" if held else
              ("ball_moving" if float(_norm(truth.ball_vel)) > 0.05 else "ball_at_rest")]
    if not visible:
        groups.append("ball_unseen")
    return groups


def record(acc: Acc, flags: dict, team: str, tracked, raw, past, truth_target, truth_capture) -> None:
    other = "yellow" if team == "blue" else "blue"
    pairs = (("tracker_target", tracked, truth_target), ("raw_target", raw, truth_target),
             ("tracker_capture", past, truth_capture), ("raw_capture", raw, truth_capture))
    for kind, est, tru in pairs:
        _robots(acc, "own_robots", kind, est.team(team), tru.team(team))
        if est.team(other).n:
            _robots(acc, "opponent_robots", kind, est.team(other), tru.team(other))
        for g in _ball_group(tru, bool(raw.ball_visible)):
            acc.add(g, kind, "pos_m", _norm(est.ball_pos - tru.ball_pos))
            acc.add(g, kind, "vel_mps", _norm(est.ball_vel - tru.ball_vel))
    truth_flag = truth_target.team(team).ball_on_dribbler
    for kind, est in (("tracker_target", tracked), ("raw_target", raw)):
        f = flags.setdefault(kind, [0, 0])
        f[0] += int(np.sum(est.team(team).ball_on_dribbler == truth_flag))
        f[1] += int(truth_flag.size)


def _step_all(env, team: str, acc: Acc, flags: dict, history: dict, act) -> dict:
    """One step; the errors are recorded except within TELEPORT_STEPS after a referee
    teleport (goal -> kickoff formation, ball out -> placement), where vision and tracker
    both show the old scene until the new one has come through the vision delay."""
    tracked = env.vision_state(team)
    raw = env.raw_vision_state(team)
    past = env.trackers[team].predict(raw.t)
    actions = act()
    out = env.step(actions)
    truth = to_team_frame(env.world_state(), team)
    k = round(truth.t / env.dt)
    history[k] = truth
    infos = out[4]
    events = next(iter(infos.values()))["events"] if infos else []
    if any(e["type"] in ("goal", "ball_out") for e in events):
        history["teleport"] = k
    cap = history.get(round(raw.t / env.dt))
    if k - history.get("teleport", -10 ** 9) <= TELEPORT_STEPS:
        flags["excluded_steps"] = flags.get("excluded_steps", 0) + 1
    elif cap is not None and abs(tracked.t - truth.t) < 1e-9:
        record(acc, flags, team, tracked, raw, past, truth, cap)
    return infos


def run_tactic(episodes: int, seed: int, acc: Acc, flags: dict, progress: bool) -> dict:
    from tqdm import tqdm

    from ssl_marl.runners.tactic_eval import sample_scene
    from ssl_marl.plays.shoot import GoToBallAndShoot

    env = TrackedVisionEnv(parallel_env(n_blue=1, n_yellow=0, realism="realistic", referee=True,
                                        after_goal="terminate", max_time_s=15.0))
    goals = kicks = steps = 0
    for i in tqdm(range(episodes), desc="tactic episodes", disable=not progress):
        es = episode_seed(seed, i)
        ball, pose = sample_scene(np.random.default_rng(es), env.field)
        env.reset(seed=es, options={"ball": {"pos": ball.tolist()}, "robots": {"blue_0": pose.tolist()}})
        truth0 = to_team_frame(env.world_state(), "blue")
        history = {0: truth0}
        tac = GoToBallAndShoot(env.field, env.config.robot, env.config.ball, skills="baseline")
        while env.agents:
            infos = _step_all(env, "blue", acc, flags, history,
                              lambda: {"blue_0": tac.act(env.vision_state("blue"), 0)})
            steps += 1
            for e in infos["blue_0"]["events"]:
                goals += e["type"] == "goal"
                kicks += e["type"] == "kick"
    return {"episodes": episodes, "steps": steps, "goals": goals, "kicks": kicks}


def run_match(seconds: float, seed: int, acc: Acc, flags: dict, progress: bool) -> dict:
    from tqdm import tqdm

    from ssl_marl.envs.referee import match_start_options
    from ssl_marl.plays.team import TeamSpec, build_team

    env = TrackedVisionEnv(parallel_env(n_blue=6, n_yellow=6, field="div_b", realism="realistic",
                                        after_goal="kickoff", max_time_s=float(seconds)))
    cfg = env.config
    ctrls = [build_team(TeamSpec(skills="baseline"), team, 6, env.field, cfg.robot, cfg.ball, seed=seed + k, dt=cfg.dt)
             for k, team in enumerate(("blue", "yellow"))]
    env.reset(seed=seed, options=match_start_options(env, seed, 0.05))
    history = {0: to_team_frame(env.world_state(), "blue")}
    kicks = goals = steps = 0

    def act():
        a = {}
        for c in ctrls:
            a.update(c.act(env))
        return a

    bar = tqdm(total=int(round(seconds / cfg.dt)), desc="match steps", disable=not progress)
    while env.agents:
        infos = _step_all(env, "blue", acc, flags, history, act)
        steps += 1
        bar.update(1)
        for e in next(iter(infos.values()))["events"]:
            goals += e["type"] == "goal"
            kicks += e["type"] == "kick"
    bar.close()
    return {"seconds": seconds, "steps": steps, "goals": goals, "kicks": kicks, "score": dict(env.score)}


def main(argv: list[str] | None = None) -> dict:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--episodes", type=int, default=20, help="tactic episodes (default 20)")
    p.add_argument("--match-seconds", type=float, default=60.0, help="simulated seconds of the 6v6 match (default 60)")
    p.add_argument("--seed", type=int, default=40000, help="seed (default 40000)")
    p.add_argument("--out", default="results/tracker_errors.json", help="output JSON")
    p.add_argument("--quiet", action="store_true", help="no progress bars")
    args = p.parse_args(argv)
    if args.episodes < 1 or args.match_seconds <= 0:
        p.error("--episodes must be >= 1 and --match-seconds > 0")
    t0 = time.perf_counter()
    result: dict = {"command": "python benchmarks/tracker_errors.py " + " ".join(argv if argv is not None else sys.argv[1:]),
                    "date_utc": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
                    "machine": {"platform": platform.platform(), "machine": platform.machine(),
                                "cpus": os.cpu_count(), "load_avg": list(os.getloadavg())},
                    "realism": "realistic", "kinds": {
                        "raw_target": "raw vision frame vs truth when the next command starts to act",
                        "tracker_target": "tracker prediction vs truth at that time",
                        "raw_capture": "raw vision frame vs truth at its capture time (noise only)",
                        "tracker_capture": "tracker filter estimate at the capture time vs truth then"},
                    "scenarios": {}}
    for name, fn, arg in (("tactic", run_tactic, args.episodes), ("match", run_match, args.match_seconds)):
        acc, flags = Acc(), {}
        info = fn(arg, args.seed, acc, flags, not args.quiet)
        info["errors"] = acc.table()
        info["excluded_teleport_steps"] = flags.pop("excluded_steps", 0)
        info["dribbler_flag_agreement"] = {k: v[0] / max(v[1], 1) for k, v in flags.items()}
        result["scenarios"][name] = info
    result["wall_time_s"] = time.perf_counter() - t0
    atomic_write_json(args.out, result)
    for name, sc in result["scenarios"].items():
        print(f"== {name}: {', '.join(f'{k}={v}' for k, v in sc.items() if k not in ('errors', 'dribbler_flag_agreement'))}")
        print(f"{'group':<16} {'kind':<16} {'pos m':>8} {'vel m/s':>8} {'head rad':>9} {'n':>7}")
        for group, kinds in sc["errors"].items():
            for kind in KINDS:
                m = kinds.get(kind)
                if m:
                    h = m.get("heading_rad_rms")
                    print(f"{group:<16} {kind:<16} {m['pos_m_rms']:8.4f} {m['vel_mps_rms']:8.3f} "
                          f"{'' if h is None else f'{h:9.4f}':>9} {m['samples']:7d}")
        print("ball-on-dribbler flag agreement:", sc["dribbler_flag_agreement"])
    print(f"-> {args.out}")
    return result


if __name__ == "__main__":
    main()
