"""The ``ssl-marl`` command line: demo, match, eval-skill, eval-drill, eval-tactic, bench.

Every long-running command shows a progress bar; ``ssl-marl COMMAND --help``
explains every option.
"""

from __future__ import annotations

import argparse
import sys

FIELDS = ("div_a", "div_b")
TEAM_POLICIES = ("learned", "baseline", "random", "idle", "passing-learned", "passing-baseline")


def _positive_int(name: str):
    def parse(text: str) -> int:
        try:
            v = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{name} must be an integer, got {text!r}") from None
        if v < 1:
            raise argparse.ArgumentTypeError(f"{name} must be >= 1, got {v}")
        return v
    return parse


def _robots(text: str) -> int:
    try:
        v = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"--robots must be an integer, got {text!r}") from None
    if not 1 <= v <= 11:
        raise argparse.ArgumentTypeError(f"--robots must be between 1 and 11 (SSL allows at most 11), got {v}")
    return v


def _positive_float(name: str):
    def parse(text: str) -> float:
        try:
            v = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{name} must be a number, got {text!r}") from None
        if not (v > 0 and v < float("inf")):
            raise argparse.ArgumentTypeError(f"{name} must be a positive number, got {text}")
        return v
    return parse


# ---------------------------------------------------------------------- demo
def cmd_demo(args: argparse.Namespace) -> int:
    """A real episode on the full field with scripted robots, written to a GIF."""
    from tqdm import tqdm

    from .envs import parallel_env
    from .envs.render import write_animation
    from .skills import SkillStatus, make_skill

    env = parallel_env(n_blue=args.robots, n_yellow=args.robots, field=args.field, max_time_s=args.seconds,
                       render_mode="rgb_array", render_trails=True)
    env.reset(seed=args.seed)
    skills = {a: (make_skill("go_to_ball", "baseline", env.field), make_skill("aim_to_shoot", "baseline", env.field))
              for a in env.possible_agents}
    aiming = {a: False for a in env.possible_agents}
    frames, every = [], max(1, round(60 / args.fps))
    steps = int(round(args.seconds * 60))
    kicks = 0
    for k in tqdm(range(steps), desc="demo", unit="step", disable=args.quiet):
        acts = {}
        for team in ("blue", "yellow"):
            ws = env.vision_state(team)
            for i in range(ws.team(team).n):
                agent = f"{team}_{i}"
                go, aim = skills[agent]
                if not aiming[agent] and bool(ws.team(team).ball_on_dribbler[i]):
                    aiming[agent] = True
                    aim.reset()
                acts[agent] = (aim if aiming[agent] else go).act(ws, i)
                if aiming[agent] and aim.status != SkillStatus.RUNNING:
                    aiming[agent] = False
        _, _, _, _, infos = env.step(acts)
        kicks += sum(ev["type"] == "kick" for ev in next(iter(infos.values()), {}).get("events", []))
        if k % every == 0:
            frames.append(env.render())
        if not env.agents:
            break
    write_animation(frames, args.out, fps=args.fps)
    print(f"demo: {args.robots}v{args.robots} {args.field}, {env.world_state().t:.1f} s simulated, "
          f"score blue {env.score['blue']} - {env.score['yellow']} yellow, {kicks} kicks, GIF -> {args.out}")
    return 0


# --------------------------------------------------------------------- match
def _match_line(res) -> str:
    s, sh, po = res.score, res.shots, res.possession
    return (f"blue ({res.config.get('blue')}) {s['blue']} - {s['yellow']} yellow ({res.config.get('yellow')})"
            f"  | shots {sh.get('blue', 0)}-{sh.get('yellow', 0)}"
            f"  | possession {100 * po.get('blue', 0):.0f}%-{100 * po.get('yellow', 0):.0f}%"
            f"  | {res.sim_time_s:.0f} s simulated in {res.wall_time_s:.1f} s wall"
            + (f"  | missed deadlines {res.missed_deadlines}" if res.config.get("realtime") else ""))


def cmd_match(args: argparse.Namespace) -> int:
    """Play one match (or a series) between two team controllers."""
    from .io import atomic_write_json
    from .plays.match import play_match, play_series

    common = dict(robots=args.robots, field=args.field, seconds=args.seconds, realism=args.realism,
                  realtime=args.realtime)
    render = None if str(args.render).lower() == "none" else args.render
    if args.matches == 1:
        res = play_match(blue=args.blue, yellow=args.yellow, seed=args.seed, render=render,
                         render_fps=args.render_fps, render_width_px=args.render_width, progress=not args.quiet,
                         **common)
        print(_match_line(res) + (f"  | video -> {render}" if render else ""))
        if args.json:
            atomic_write_json(args.json, res.to_dict())
        return 0
    results, summary = play_series(blue=args.blue, yellow=args.yellow, matches=args.matches, workers=args.workers,
                                   seed=args.seed, progress=not args.quiet, **common)
    print(f"{'match':>5} {'seed':>6}  {'score':>7}  {'shots':>7}  possession")
    for i, r in enumerate(results):
        print(f"{i:>5} {r.seed:>6}  {r.score['blue']:>3}-{r.score['yellow']:<3}  {r.shots['blue']:>3}-{r.shots['yellow']:<3}"
              f"  {100 * r.possession['blue']:.0f}%-{100 * r.possession['yellow']:.0f}%")
    print(f"blue ({args.blue}) vs yellow ({args.yellow}), {summary['matches']} matches: "
          f"W {summary['wins']} D {summary['draws']} L {summary['losses']}, "
          f"goals {summary['goals_for']}-{summary['goals_against']}")
    for team, st in summary.get("stats", {}).items():
        pc = "-" if st["pass_completion"] is None else f"{100 * st['pass_completion']:.0f}%"
        print(f"  {team}: shots {st['shots']}, passes {st['passes_completed']}/{st['passes_attempted']} completed "
              f"({pc}), intercepted {st['passes_intercepted']}, interceptions {st['interceptions']}, "
              f"goals {st['goals']}")
    if args.json:
        atomic_write_json(args.json, {"summary": summary, "matches": [r.to_dict() for r in results]})
    return 0


# ---------------------------------------------------------------- eval-skill
def cmd_eval_skill(args: argparse.Namespace) -> int:
    from .skills.evaluation import evaluate_skill

    s = evaluate_skill(args.skill, args.policy, episodes=args.episodes, seed=args.seed, workers=args.workers,
                       out=args.out, realism=args.realism, field=args.field, progress=not args.quiet,
                       realtime=args.realtime)
    t = s["time_to_success_s"]
    lo, hi = s["success_ci95"]
    mean = "n/a" if t["mean"] is None else f"{t['mean']:.2f} +/- {t['std']:.2f} s"
    print(f"{args.skill} ({args.policy}): success {s['success_rate']:.3f} [95% CI {lo:.3f}-{hi:.3f}] over "
          f"{s['episodes']} episodes, time to success {mean}, failures {s['failure_reasons']}"
          + (f" -> {args.out}/results.json" if args.out else ""))
    return 0


# ---------------------------------------------------------------- eval-drill
def cmd_eval_drill(args: argparse.Namespace) -> int:
    from .skills.drills import evaluate_drill

    s = evaluate_drill(args.drill, args.policy, runs=args.runs, seed=args.seed, duration_s=args.duration,
                       realism=args.realism, field=args.field, out=args.out, progress=not args.quiet,
                       receive_policy=args.receive_policy)
    lo, hi = s["completion_ci95"]
    rate = "n/a" if s["completion_rate"] is None else f"{s['completion_rate']:.3f} [95% CI {lo:.3f}-{hi:.3f}]"
    print(f"{args.drill} (pass {args.policy}, receive {s['receive_policy']}): {s['completed']} of {s['attempts']} passes completed ({rate}) in "
          f"{s['runs']} runs of {args.duration:g} s, {s['passes_per_minute']:.1f} per minute, losses {s['losses']}"
          + (f" -> {args.out}/results.json" if args.out else ""))
    return 0


# --------------------------------------------------------------- eval-tactic
def cmd_eval_tactic(args: argparse.Namespace) -> int:
    from .plays.evaluate import evaluate_tactic

    s = evaluate_tactic(skills=args.skills, episodes=args.episodes, seed=args.seed, workers=args.workers,
                        realism=args.realism, out=args.out, field=args.field, progress=not args.quiet)
    t = s["time_s"]
    lo, hi = s["success_ci95"]
    mean = "n/a" if t["mean"] is None else f"{t['mean']:.2f} +/- {t['std']:.2f} s"
    print(f"go-to-ball-and-shoot ({args.skills} skills): success {s['success_rate']:.3f} [95% CI {lo:.3f}-{hi:.3f}] "
          f"over {s['episodes']} episodes, time to goal {mean}, failures {s['failures']} "
          f"(paper: 0.755, 7.49 +/- 3.87 s)" + (f" -> {args.out}/results.json" if args.out else ""))
    return 0


def cmd_bench(args: argparse.Namespace) -> int:
    from . import bench

    bench.main(args.rest)
    return 0


# -------------------------------------------------------------------- parser
def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="ssl-marl", description="RoboCup SSL simulator, learned skills and STP matches.")
    sub = p.add_subparsers(dest="command", required=True, metavar="COMMAND")

    d = sub.add_parser("demo", help="one scripted episode on the full field, written to a GIF",
                       description="Play one episode with scripted robots (baseline go-to-ball, then aim-to-shoot) "
                                   "on the full field and write it to a GIF.")
    d.add_argument("--robots", type=_robots, default=6, help="robots per team, 1-11 (default 6)")
    d.add_argument("--field", choices=FIELDS, default="div_b", help="field geometry (default div_b)")
    d.add_argument("--seconds", type=_positive_float("--seconds"), default=20.0, help="simulated seconds (default 20)")
    d.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    d.add_argument("--fps", type=_positive_int("--fps"), default=20, help="GIF frames per second (default 20)")
    d.add_argument("--out", default="demo.gif", help="output GIF/MP4 path (default demo.gif)")
    d.add_argument("--quiet", action="store_true", help="no progress bar")
    d.set_defaults(func=cmd_demo)

    m = sub.add_parser("match", help="full-team match (or series) between two team controllers",
                       description="Play a full-team STP match in the parallel env: kickoffs, restarts after goals "
                                   "and out-of-play. Prints the score and stats; writes a GIF/MP4 with --render.")
    m.add_argument("--blue", choices=TEAM_POLICIES, default="learned",
                   help="blue team's skills: learned (shipped DDPG actors), baseline (hand-coded), random, idle; "
                        "passing-learned / passing-baseline: the passing plays (shoot, pass or keep by cost, "
                        "set plays with passes) with those skills (default learned)")
    m.add_argument("--yellow", choices=TEAM_POLICIES, default="baseline", help="yellow team's skills (default baseline)")
    m.add_argument("--robots", type=_robots, default=6, help="robots per team, 1-11 (default 6)")
    m.add_argument("--field", choices=FIELDS, default="div_b", help="field geometry (default div_b)")
    m.add_argument("--seconds", type=_positive_float("--seconds"), default=30.0,
                   help="simulated match length in seconds (default 30)")
    m.add_argument("--seed", type=int, default=0, help="random seed; match i of a series uses seed + i (default 0)")
    m.add_argument("--realism", choices=("none", "realistic"), default="none",
                   help="vision noise / latency preset (default none)")
    m.add_argument("--realtime", action="store_true",
                   help="paper's evaluation mode: a team whose controller misses the 16.7 ms deadline loses "
                        "that command")
    m.add_argument("--render", default="match.gif", metavar="PATH",
                   help="write a single match to PATH (.gif or .mp4); 'none' to skip (default match.gif)")
    m.add_argument("--render-fps", type=_positive_float("--render-fps"), default=10.0,
                   help="video frames per simulated second (default 10)")
    m.add_argument("--render-width", type=_positive_int("--render-width"), default=480,
                   help="video width in pixels (default 480)")
    m.add_argument("--matches", type=_positive_int("--matches"), default=1, help="number of matches (default 1)")
    m.add_argument("--workers", type=_positive_int("--workers"), default=1,
                   help="parallel worker processes for a series (default 1)")
    m.add_argument("--json", default=None, metavar="PATH", help="also write the result as JSON to PATH")
    m.add_argument("--quiet", action="store_true", help="no progress bar")
    m.set_defaults(func=cmd_match)

    e = sub.add_parser("eval-skill", help="the paper's skill evaluation protocol (section 5.1)",
                       description="Run a skill from random spawns for N episodes; writes OUT/results.json "
                                   "(success rate with 95%% CI, times, failure reasons) and OUT/time_hist.png.")
    e.add_argument("skill", choices=("go-to-ball", "aim-to-shoot", "pass", "receive"), help="which skill")
    e.add_argument("--policy", default="baseline",
                   help="'baseline' (hand-coded), 'learned' (shipped actor) or a path to an actor checkpoint")
    e.add_argument("--episodes", type=_positive_int("--episodes"), default=1000, help="episodes (default 1000)")
    e.add_argument("--seed", type=int, default=10_000, help="evaluation seed (default 10000; training uses < 1000)")
    e.add_argument("--workers", type=_positive_int("--workers"), default=1, help="worker processes (default 1)")
    e.add_argument("--out", default=None, help="output directory for results.json and time_hist.png")
    e.add_argument("--realism", choices=("none", "realistic"), default="none",
                   help="vision noise / latency preset (default none)")
    e.add_argument("--realtime", action="store_true", help="run in real-time mode (slow: 60 steps per second)")
    e.add_argument("--field", choices=FIELDS, default="div_b", help="field geometry (default div_b)")
    e.add_argument("--quiet", action="store_true", help="no progress bar")
    e.set_defaults(func=cmd_eval_skill)

    dr = sub.add_parser("eval-drill", help="passing drills (pass-endurance: two robots pass back and forth)",
                        description="Run a drill with the pass and receive skills; writes OUT/results.json "
                                    "(passes attempted and completed, losses by reason).")
    dr.add_argument("drill", choices=("pass-endurance",), help="which drill")
    dr.add_argument("--policy", choices=("baseline", "learned"), default="baseline",
                    help="hand-coded or shipped learned pass and receive skills (default baseline)")
    dr.add_argument("--receive-policy", choices=("baseline", "learned"), default=None,
                    help="receive skill, if different from --policy (default: as --policy)")
    dr.add_argument("--runs", type=_positive_int("--runs"), default=10, help="drill runs (default 10)")
    dr.add_argument("--duration", type=_positive_float("--duration"), default=60.0,
                    help="simulated seconds per run (default 60)")
    dr.add_argument("--seed", type=int, default=10_000, help="seed (default 10000)")
    dr.add_argument("--out", default=None, help="output directory for results.json")
    dr.add_argument("--realism", choices=("none", "realistic"), default="none",
                    help="vision noise / latency preset (default none)")
    dr.add_argument("--field", choices=FIELDS, default="div_b", help="field geometry (default div_b)")
    dr.add_argument("--quiet", action="store_true", help="no progress bar")
    dr.set_defaults(func=cmd_eval_drill)

    t = sub.add_parser("eval-tactic", help="the paper's go-to-ball-and-shoot tactic evaluation (section 5.2)",
                       description="One robot and the ball at random; run go-to-ball-and-shoot until a goal or "
                                   "15 s. Writes OUT/results.json and OUT/time_hist.png.")
    t.add_argument("--skills", choices=("learned", "baseline"), default="learned", help="skills inside the tactic")
    t.add_argument("--episodes", type=_positive_int("--episodes"), default=500, help="episodes (default 500)")
    t.add_argument("--seed", type=int, default=20_000, help="evaluation seed (default 20000)")
    t.add_argument("--workers", type=_positive_int("--workers"), default=1, help="worker processes (default 1)")
    t.add_argument("--realism", choices=("none", "realistic"), default="none", help="noise / latency preset")
    t.add_argument("--out", default=None, help="output directory")
    t.add_argument("--field", choices=FIELDS, default="div_b", help="field geometry (default div_b)")
    t.add_argument("--quiet", action="store_true", help="no progress bar")
    t.set_defaults(func=cmd_eval_tactic)

    b = sub.add_parser("bench", help="env throughput benchmark (JSON); options: ssl-marl bench -- --help",
                       description="Env steps/s for 1v0, 6v6 Division B and 11v11 Division A, reset time and "
                                   "learned-skill inference time, as JSON. Options after '--' go to the benchmark "
                                   "(--steps, --resets, --configs, --no-skills).", add_help=True)
    b.add_argument("rest", nargs=argparse.REMAINDER, help="options passed to python -m ssl_marl.bench")
    b.set_defaults(func=cmd_bench)
    return p


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    try:
        return args.func(args)
    except (ValueError, FileNotFoundError) as exc:
        print(f"ssl-marl {args.command}: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
