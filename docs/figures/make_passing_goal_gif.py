"""Make docs/figures/passing_goal.gif: a goal that follows a completed pass, from a match series.

Usage (after a series written with ``ssl-marl match ... --json FILE``)::

    python docs/figures/make_passing_goal_gif.py results/match_passing_learned_vs_baseline_snap.json \
        --out docs/figures/passing_goal.gif

It replays, in order, the series' matches in which ``--team`` scored (step mode is
deterministic for a seed: the same controllers, seeds and start jitter as
:func:`ssl_marl.runners.match.play_match`), with the match-statistics tracker, until a goal
by ``--team`` comes at most ``--within`` seconds after a completed pass of that team,
and writes the frames from ``--before`` seconds before the pass kick to ``--after``
seconds after the goal.
"""

from __future__ import annotations

import argparse
import sys

import numpy as np


def controller(cfg: dict, side: str, field, seed: int, ck: dict):
    """The team controller the match ran: its kind, its carrier decision, and the skill
    kinds recorded in the match config (so that a replay uses the actors that played,
    even if others have been shipped since)."""
    from ssl_marl.runners.controllers import make_controller

    kind, skills = cfg[side], (cfg.get("skills") or {}).get(side)
    decision = (cfg.get("decision") or {}).get(side)
    skills = skills if kind.startswith("passing-") and isinstance(skills, dict) else None
    return make_controller(kind, side, cfg["robots"], field, seed=seed, skills=skills, decision=decision, **ck)


def replay_for_passing_goal(match: dict, team: str, within: float, before: float, after: float, width: int,
                            fps: float) -> tuple[list[np.ndarray], float, float] | None:
    """Replay ``match`` (the settings in its config) with a stats tracker and a rolling
    buffer of frames; at the first goal by ``team`` that comes at most ``within`` s after
    a completed pass of the team, return (frames from ``before`` s before the pass kick to
    ``after`` s after the goal, pass time, goal time); None if the match has none."""
    from collections import deque

    from ssl_marl.envs import parallel_env
    from ssl_marl.runners.match import start_options
    from ssl_marl.plays.stats import MatchStatsTracker

    cfg = match["config"]
    env = parallel_env(n_blue=cfg["robots"], n_yellow=cfg["robots"], field=cfg["field"], max_time_s=cfg["seconds"],
                       realism=cfg["realism"], after_goal="kickoff", realtime=False, render_mode="rgb_array",
                       render_width_px=width)
    ck = dict(robot=env.config.robot, ball=env.config.ball, dt=env.config.dt)
    ctrls = [controller(cfg, side, env.field, cfg["seed"] + k, ck) for k, side in enumerate(("blue", "yellow"))]
    env.reset(seed=cfg["seed"], options=start_options(env, cfg["seed"], cfg["start_jitter_m"]))
    tracker = MatchStatsTracker(env.field, env.config.ball)
    every = max(int(round(env.config.control_hz / fps)), 1)
    frames: deque = deque(maxlen=int((within + before + 2.0) * fps))
    step, goal = 0, None
    try:
        while env.agents:
            t = env.world_state().t
            if step % every == 0:
                frames.append((t, env.render()))
            if goal is not None and t >= goal[1] + after:
                return [f for tf, f in frames if tf >= goal[0] - before], goal[0], goal[1]
            actions = {}
            for c in ctrls:
                actions.update(c.act(env))
            _, _, _, _, infos = env.step(actions)
            step += 1
            events = next(iter(infos.values()))["events"] if infos else []
            tracker.observe(env.world_state(), events)
            if goal is None and any(e["type"] == "goal" and e["team"] == team for e in events):
                t_goal = env.world_state().t
                log = tracker.log
                done = [e for e in log if e["type"] == "pass_completed" and e["team"] == team
                        and t_goal - within <= e["t"] <= t_goal]
                if done:
                    kicks = [e["t"] for e in log if e["type"] == "pass" and e["team"] == team
                             and e["t"] <= done[-1]["t"]]
                    goal = (kicks[-1] if kicks else done[-1]["t"], t_goal)
    finally:
        env.close()
    return None


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("series", help="series JSON written by ssl-marl match --json")
    ap.add_argument("--out", default="docs/figures/passing_goal.gif", help="output GIF")
    ap.add_argument("--team", default="blue", choices=("blue", "yellow"), help="scoring team (default blue)")
    ap.add_argument("--within", type=float, default=6.0, help="goal at most this long after the pass (s)")
    ap.add_argument("--before", type=float, default=1.0, help="seconds before the pass kick")
    ap.add_argument("--after", type=float, default=0.5, help="seconds after the goal")
    ap.add_argument("--width", type=int, default=360, help="frame width (px)")
    ap.add_argument("--fps", type=float, default=12.0, help="frames per simulated second")
    args = ap.parse_args(argv)
    from ssl_marl.runners.result import load_result

    series = load_result(args.series)
    for match in series["matches"]:
        if not any(g["team"] == args.team for g in match["goals"]):
            continue
        found = replay_for_passing_goal(match, args.team, args.within, args.before, args.after, args.width, args.fps)
        if found is None:
            continue
        frames, t_pass, t_goal = found
        from ssl_marl.envs.animation import write_animation

        write_animation(frames, args.out, fps=int(round(args.fps)))
        print(f"seed {match['seed']}: pass at {t_pass:.2f} s, goal at {t_goal:.2f} s, {len(frames)} frames "
              f"-> {args.out}")
        return 0
    print(f"no {args.team} goal within {args.within} s of a completed pass in {args.series}", file=sys.stderr)
    return 1


if __name__ == "__main__":
    sys.exit(main())
