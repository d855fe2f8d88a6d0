"""The ``ssl-marl`` command line: demo, match, eval-skill, eval-drill, eval-tactic, eval-task, bench, train, export-onnx.

Every long-running command shows a progress bar; ``ssl-marl COMMAND --help``
explains every option. Output paths follow one rule (:data:`OUTPUT_RULE`),
checked before any simulation starts.

``train`` is the single exception to "ssl_marl never imports train": its handler
forwards the command line to ``train.__main__.main`` through a lazy import, so
``ssl_marl`` itself still loads without the trainer.
"""

from __future__ import annotations

import argparse
import sys

from .runners.controllers import TEAM_KINDS
from .runners.pool import BACKENDS

FIELDS = ("div_a", "div_b")
VIDEO_SUFFIXES = (".gif", ".mp4")
OUTPUT_RULE = ("Output paths (--out, --render, --json, export-onnx OUT): missing parent folders are created; a path that "
               "cannot be written is refused before any simulation starts.")
#: subcommands whose options belong to another program: everything after the name is forwarded
FORWARDED = ("bench", "train")


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


def _int_at_least(name: str, lowest: int):
    def parse(text: str) -> int:
        try:
            v = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{name} must be an integer, got {text!r}") from None
        if v < lowest:
            raise argparse.ArgumentTypeError(f"{name} must be >= {lowest}, got {v}")
        return v
    return parse


def _finite_float(name: str, lowest: float, inclusive: bool, rule: str):
    """Parser of a finite float above ``lowest`` (or equal to it when ``inclusive``);
    ``rule`` completes "NAME must be ..." in the error."""
    def parse(text: str) -> float:
        try:
            v = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{name} must be a number, got {text!r}") from None
        if not ((v >= lowest if inclusive else v > lowest) and v < float("inf")):
            raise argparse.ArgumentTypeError(f"{name} must be {rule}, got {text}")
        return v
    return parse


def _positive_float(name: str):
    return _finite_float(name, 0.0, False, "a positive number")


def _non_negative_float(name: str):
    return _finite_float(name, 0.0, True, "a finite number >= 0")


def _team(text: str) -> str:
    if text in TEAM_KINDS or text.lower().endswith(".json"):
        return text
    raise argparse.ArgumentTypeError(f"invalid choice: {text!r} (choose from {', '.join(TEAM_KINDS)}, "
                                     "or a JSON team file ending in .json)")


def _skill_source(text: str) -> tuple[str, str]:
    from .runners.controllers import parse_skill_source

    try:
        return parse_skill_source(text)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


SKILL_SOURCE_HELP = ("SKILL=SOURCE: run SKILL (go-to-ball, aim-to-shoot) from SOURCE: baseline, learned (shipped "
                     "actor) or an actor checkpoint path, e.g. go-to-ball=runs/gtb/actor.pt (repeatable)")


def _add_backend(p: argparse.ArgumentParser, what: str) -> None:
    p.add_argument("--backend", choices=BACKENDS, default="local",
                   help=f"where {what} run: local (process pool of --workers, default) or ray (a Ray cluster; "
                        "--workers = tasks in flight)")
    p.add_argument("--address", default=None, metavar="ADDR",
                   help="Ray cluster address (HOST:6379 or auto; default: start a local Ray instance); "
                        "needs --backend ray")


def _workers(args: argparse.Namespace) -> int | None:
    """--workers, defaulting to 1 locally and to the whole cluster with Ray."""
    return args.workers if args.workers is not None else (None if args.backend == "ray" else 1)


def _resolve_team(team: str, value: str, sources: list[tuple[str, str]]):
    """(kind, skills spec or None) for a team option and its skill sources."""
    from .runners.controllers import load_team_file, team_skills

    kind, own = (load_team_file(value) if value.lower().endswith(".json") else (value, {}))
    merged = {**{k.replace("-", "_"): v for k, v in own.items()}, **dict(sources)}  # later wins
    if not merged:
        return kind, None
    return kind, team_skills(kind, merged, where=f"--{team}")


# ---------------------------------------------------------------------- demo
def cmd_demo(args: argparse.Namespace) -> int:
    """A real episode on the full field with scripted robots, written to a GIF."""
    from tqdm import tqdm

    from .envs import parallel_env
    from .io import prepare_output_file
    from .envs.animation import VideoSink
    from .skills import SkillStatus, make_skill

    prepare_output_file(args.out, VIDEO_SUFFIXES, "--out")
    env = parallel_env(n_blue=args.robots, n_yellow=args.robots, field=args.field, max_time_s=args.seconds,
                       render_mode="rgb_array", render_trails=True,
                       render_team_labels={"blue": "scripted, baseline skills", "yellow": "scripted, baseline skills"})
    env.reset(seed=args.seed)
    skills = {a: (make_skill("go_to_ball", "baseline", env.field), make_skill("aim_to_shoot", "baseline", env.field))
              for a in env.possible_agents}
    aiming = {a: False for a in env.possible_agents}
    every = max(1, round(60 / args.fps))
    steps = int(round(args.seconds * 60))
    kicks = 0
    sink = VideoSink(args.out, args.fps)  # frames go to disk as they come (constant memory)
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
            sink.add(env.render())
        if not env.agents:
            break
    sink.close()  # publish atomically; after an exception the sink deletes its partial file
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
    from .io import atomic_write_json, prepare_output_file
    from .runners.match import play_match
    from .runners.series import play_series

    if args.address is not None and args.backend != "ray":
        raise ValueError("--address needs --backend ray")
    blue, blue_skills = _resolve_team("blue", args.blue, args.skill + args.blue_skill)
    yellow, yellow_skills = _resolve_team("yellow", args.yellow, args.skill + args.yellow_skill)
    common = dict(robots=args.robots, field=args.field, seconds=args.seconds, realism=args.realism,
                  realtime=args.realtime, blue_skills=blue_skills, yellow_skills=yellow_skills,
                  tracker=args.tracker, blue_decision=args.blue_decision, yellow_decision=args.yellow_decision,
                  env_kwargs={"no_progress_s": args.no_progress_s or None})
    render = None if str(args.render).lower() == "none" else args.render
    if render is not None and args.matches == 1:
        prepare_output_file(render, VIDEO_SUFFIXES, "--render")
    if args.json:
        prepare_output_file(args.json, None, "--json")
    if args.matches == 1:
        res = play_match(blue=blue, yellow=yellow, seed=args.seed, render=render,
                         render_fps=args.render_fps, render_width_px=args.render_width, progress=not args.quiet,
                         **common)
        print(_match_line(res) + (f"  | video -> {render}" if render else ""))
        if args.json:
            atomic_write_json(args.json, res.to_dict())
        return 0
    results, summary = play_series(blue=blue, yellow=yellow, matches=args.matches, workers=_workers(args),
                                   seed=args.seed, progress=not args.quiet, backend=args.backend,
                                   address=args.address, **common)
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
    from .io import prepare_output_dir
    from .runners.skill_eval import evaluate_skill

    if args.out:
        prepare_output_dir(args.out, "--out")
    s = evaluate_skill(args.skill, args.policy, episodes=args.episodes, seed=args.seed, workers=_workers(args),
                       out=args.out, realism=args.realism, field=args.field, progress=not args.quiet,
                       realtime=args.realtime, backend=args.backend, address=args.address, tracker=args.tracker)
    t = s["time_to_success_s"]
    lo, hi = s["success_ci95"]
    mean = "n/a" if t["mean"] is None else f"{t['mean']:.2f} +/- {t['std']:.2f} s"
    print(f"{args.skill} ({args.policy}): success {s['success_rate']:.3f} [95% CI {lo:.3f}-{hi:.3f}] over "
          f"{s['episodes']} episodes, time to success {mean}, failures {s['failure_reasons']}"
          + (f" -> {args.out}/results.json" if args.out else ""))
    return 0


# ---------------------------------------------------------------- eval-drill
def cmd_eval_drill(args: argparse.Namespace) -> int:
    from .io import prepare_output_dir
    from .runners.drills import evaluate_drill

    if args.out:
        prepare_output_dir(args.out, "--out")
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
    from .io import prepare_output_dir
    from .runners.controllers import team_skills
    from .runners.tactic_eval import evaluate_tactic

    if args.out:
        prepare_output_dir(args.out, "--out")
    skills = team_skills(args.skills, dict(args.skill), where="--skill") if args.skill else args.skills
    s = evaluate_tactic(skills=skills, episodes=args.episodes, seed=args.seed, workers=_workers(args),
                        realism=args.realism, out=args.out, field=args.field, progress=not args.quiet,
                        backend=args.backend, address=args.address, tracker=args.tracker,
                        tactic=args.tactic, realtime=args.realtime)
    t = s["time_s"]
    lo, hi = s["success_ci95"]
    mean = "n/a" if t["mean"] is None else f"{t['mean']:.2f} +/- {t['std']:.2f} s"
    missed = f", missed deadlines {s['missed_deadlines']}" if args.realtime else ""
    print(f"{args.tactic} ({args.skills} skills): success {s['success_rate']:.3f} [95% CI {lo:.3f}-{hi:.3f}] "
          f"over {s['episodes']} episodes, time to goal {mean}, failures {s['failures']} "
          f"(paper: 0.755, 7.49 +/- 3.87 s){missed}" + (f" -> {args.out}/results.json" if args.out else ""))
    return 0


# ----------------------------------------------------------------- eval-task
def cmd_eval_task(args: argparse.Namespace) -> int:
    from .io import prepare_output_dir
    from .runners.task_eval import evaluate_task

    if args.out:
        prepare_output_dir(args.out, "--out")
    s = evaluate_task(args.task, args.policy, episodes=args.episodes, seed=args.seed, workers=_workers(args),
                      realism=args.realism, field=args.field, actor=args.actor, out=args.out,
                      progress=not args.quiet, backend=args.backend, address=args.address, tracker=args.tracker)
    oc = ", ".join(f"{k} {v}" for k, v in s["outcomes"].items())
    if "mean_duration_s" in s:
        lo, hi = s["mean_duration_ci95"]
        score = f"mean duration {s['mean_duration_s']:.2f} s [95% CI {lo:.2f}-{hi:.2f}]"
    else:
        lo, hi = s["goal_rate_ci95"]
        score = f"goal rate {s['goal_rate']:.3f} [95% CI {lo:.3f}-{hi:.3f}]"
    print(f"{args.task} ({args.policy}): {score} over {s['episodes']} episodes (seeds {s['seed']}+i); "
          f"outcomes: {oc}" + (f" -> {args.out}/results.json" if args.out else ""))
    return 0


def cmd_bench(args: argparse.Namespace) -> int:
    """Forward everything after ``bench`` (a leading ``--`` is dropped) to :func:`ssl_marl.bench.main`."""
    from . import bench

    bench.main(args.rest)
    return 0


def cmd_train(args: argparse.Namespace) -> int:
    """Forward everything after ``train`` to ``python -m train`` (same options, same behaviour).

    The single place ``ssl_marl`` imports ``train`` (lazily, here): the dependency still
    points one way for the library, and one command line covers the whole workflow.
    """
    from train.__main__ import main as train_main

    return int(train_main(args.rest, prog="ssl-marl train") or 0)


def cmd_export_onnx(args: argparse.Namespace) -> int:
    """Write a learned-skill actor checkpoint as an ONNX model (see :mod:`ssl_marl.skills.onnx_export`)."""
    import importlib.util

    from .io import prepare_output_file

    missing = [m for m in ("onnx", "onnxruntime") if importlib.util.find_spec(m) is None]
    if missing:
        print(f"ssl-marl export-onnx: error: needs {' and '.join(missing)}: pip install -e \".[onnx]\"",
              file=sys.stderr)
        return 2
    from .skills.onnx_export import export_onnx

    prepare_output_file(args.out, (".onnx",), "OUT")
    meta = export_onnx(args.checkpoint, args.out, opset=args.opset)
    print(f"{args.checkpoint} ({meta['skill']}, {meta['obs_spec']}, obs {meta['obs_dim']} -> act {meta['act_dim']})"
          f" -> {args.out}")
    return 0


def _add_tracker_option(p: argparse.ArgumentParser) -> None:
    p.add_argument("--tracker", choices=("auto", "on", "off"), default="auto",
                   help="vision tracker between the env's vision and the skills/tactics (Kalman filters, latency "
                        "compensation, ball on the dribbler, outlier gates): auto = on unless --realism none "
                        "(default auto)")


# -------------------------------------------------------------------- parser
def build_parser() -> argparse.ArgumentParser:
    from . import __version__

    p = argparse.ArgumentParser(prog="ssl-marl", description="RoboCup SSL simulator, learned skills and STP matches.",
                                epilog=OUTPUT_RULE)
    p.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    sub = p.add_subparsers(dest="command", required=True, metavar="COMMAND")

    d = sub.add_parser("demo", help="one scripted episode on the full field, written to a GIF",
                       description="Play one episode with scripted robots (baseline go-to-ball, then aim-to-shoot) "
                                   "on the full field and write it to a GIF.")
    d.add_argument("--robots", type=_robots, default=6, help="robots per team, 1-11 (default 6)")
    d.add_argument("--field", choices=FIELDS, default="div_b", help="field geometry (default div_b)")
    d.add_argument("--seconds", type=_positive_float("--seconds"), default=20.0, help="simulated seconds (default 20)")
    d.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    d.add_argument("--fps", type=_positive_int("--fps"), default=20, help="GIF frames per second (default 20)")
    d.add_argument("--out", default="demo.gif",
                   help="output GIF/MP4 path; missing folders are created (default demo.gif)")
    d.add_argument("--quiet", action="store_true", help="no progress bar")
    d.set_defaults(func=cmd_demo)

    m = sub.add_parser("match", help="full-team match (or series) between two team controllers",
                       description="Play a full-team STP match in the parallel env: kickoffs, restarts after goals "
                                   "and out-of-play. Prints the score and stats; writes a GIF/MP4 with --render.")
    m.add_argument("--blue", type=_team, default="learned", metavar="TEAM",
                   help="blue team: learned (STP with the shipped DDPG actors), baseline (STP with hand-coded "
                        "skills), passing-learned / passing-baseline (the passing plays: shoot, pass or keep by "
                        "cost, set plays with passes, with those skills), passing-learned-decision (passing-learned "
                        "whose ball carrier uses the learned Attack 3v2 decision), random, idle, or a JSON team file "
                        "{\"kind\": ..., \"skills\": {SKILL: SOURCE}} (default learned)")
    m.add_argument("--yellow", type=_team, default="baseline", metavar="TEAM",
                   help="yellow team, as --blue (default baseline)")
    m.add_argument("--skill", type=_skill_source, action="append", default=[], metavar="SKILL=SOURCE",
                   help="for both STP teams: " + SKILL_SOURCE_HELP)
    m.add_argument("--blue-skill", type=_skill_source, action="append", default=[], metavar="SKILL=SOURCE",
                   help="as --skill, for the blue team only (wins over --skill)")
    m.add_argument("--yellow-skill", type=_skill_source, action="append", default=[], metavar="SKILL=SOURCE",
                   help="as --skill, for the yellow team only (wins over --skill)")
    for team in ("blue", "yellow"):
        m.add_argument(f"--{team}-decision", default=None, metavar="DECISION",
                       help=f"{team} passing team's ball-carrier decision (shoot / pass / dribble): handcoded (the "
                            "cost decision), learned (the shipped Attack 3v2 actor) or PATH to a decision actor "
                            "checkpoint; needs a passing team (default: the team kind's own, learned for "
                            "passing-learned-decision, else handcoded)")
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
                   help="write a single match to PATH (.gif or .mp4; missing folders are created); 'none' "
                        "to skip (default match.gif)")
    m.add_argument("--render-fps", type=_positive_float("--render-fps"), default=10.0,
                   help="video frames per simulated second (default 10)")
    m.add_argument("--render-width", type=_int_at_least("--render-width", 64), default=480,
                   help="video width in pixels, >= 64 (default 480)")
    m.add_argument("--matches", type=_positive_int("--matches"), default=1, help="number of matches (default 1)")
    m.add_argument("--workers", type=_positive_int("--workers"), default=None,
                   help="parallel worker processes for a series (default 1; with --backend ray: matches in flight, "
                        "default the cluster's CPUs)")
    _add_backend(m, "the matches of a series")
    m.add_argument("--json", default=None, metavar="PATH",
                   help="also write the result as JSON to PATH (missing folders are created)")
    m.add_argument("--quiet", action="store_true", help="no progress bar")
    m.add_argument("--no-progress-s", type=_non_negative_float("--no-progress-s"), default=10.0,
                   help="the referee restarts play when the ball stays within 0.25 m of one spot this long "
                        "(SSL force start after a lack of progress; seconds, default 10; 0 switches the call off, "
                        "as in matches recorded before 2026-11-26)")
    _add_tracker_option(m)
    m.set_defaults(func=cmd_match)

    e = sub.add_parser("eval-skill", help="the paper's skill evaluation protocol (section 5.1)",
                       description="Run a skill from random spawns for N episodes; writes OUT/results.json "
                                   "(success rate with 95% CI, times, failure reasons) and OUT/time_hist.png.")
    from .skills.registry import cli_choices

    e.add_argument("skill", choices=cli_choices(), help="which skill (every registered skill with a task)")
    e.add_argument("--policy", default="baseline",
                   help="'baseline' (hand-coded), 'learned' (shipped actor) or a path to an actor checkpoint")
    e.add_argument("--episodes", type=_positive_int("--episodes"), default=1000, help="episodes (default 1000)")
    e.add_argument("--seed", type=int, default=10_000, help="evaluation seed (default 10000; training uses < 1000)")
    e.add_argument("--workers", type=_positive_int("--workers"), default=None,
                   help="worker processes (default 1; with --backend ray: tasks in flight, default the cluster's CPUs)")
    e.add_argument("--out", default=None,
                   help="output folder for results.json and time_hist.png, created if missing (default: none)")
    e.add_argument("--realism", choices=("none", "realistic", "randomized"), default="none",
                   help="vision noise / latency preset (default none); randomized: each episode draws its own "
                        "latency, noise, command loss, robot speed / acceleration and ball model "
                        "(ssl_marl/envs/randomization.py)")
    e.add_argument("--realtime", action="store_true", help="run in real-time mode (slow: 60 steps per second)")
    e.add_argument("--field", choices=FIELDS, default="div_b", help="field geometry (default div_b)")
    _add_backend(e, "the episodes")
    e.add_argument("--quiet", action="store_true", help="no progress bar")
    _add_tracker_option(e)
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
    dr.add_argument("--out", default=None, help="output folder for results.json, created if missing (default: none)")
    dr.add_argument("--realism", choices=("none", "realistic"), default="none",
                    help="vision noise / latency preset (default none)")
    dr.add_argument("--field", choices=FIELDS, default="div_b", help="field geometry (default div_b)")
    dr.add_argument("--quiet", action="store_true", help="no progress bar")
    dr.set_defaults(func=cmd_eval_drill)

    t = sub.add_parser("eval-tactic", help="the paper's go-to-ball-and-shoot tactic evaluation (section 5.2)",
                       description="One robot and the ball at random; run go-to-ball-and-shoot until a goal or "
                                   "15 s. Writes OUT/results.json and OUT/time_hist.png.")
    t.add_argument("--skills", choices=("learned", "baseline"), default="learned",
                   help="skills inside the tactic (default learned)")
    t.add_argument("--tactic", choices=("go-to-ball-and-shoot", "dribble-and-shoot"), default="go-to-ball-and-shoot",
                   help="the tactic: the paper's go-to-ball-and-shoot (default) or dribble-and-shoot (take the ball "
                        "gently, dribble it to a shooting window, aim, shoot; issue 13)")
    t.add_argument("--realtime", action="store_true",
                   help="hold the tactic to the 1/60 s control deadline: a command computed too slowly is dropped "
                        "(the robot keeps the previous one) and counted as a missed deadline")
    t.add_argument("--skill", type=_skill_source, action="append", default=[], metavar="SKILL=SOURCE",
                   help="replace one skill of --skills: " + SKILL_SOURCE_HELP)
    t.add_argument("--episodes", type=_positive_int("--episodes"), default=500, help="episodes (default 500)")
    t.add_argument("--seed", type=int, default=20_000, help="evaluation seed (default 20000)")
    t.add_argument("--workers", type=_positive_int("--workers"), default=None,
                   help="worker processes (default 1; with --backend ray: tasks in flight, default the cluster's CPUs)")
    t.add_argument("--realism", choices=("none", "realistic", "randomized"), default="none",
                   help="noise / latency preset; randomized: each episode draws its own latency, noise, command "
                        "loss, robot speed / acceleration and ball model (ssl_marl/envs/randomization.py)")
    t.add_argument("--out", default=None,
                   help="output folder for results.json and time_hist.png, created if missing (default: none)")
    t.add_argument("--field", choices=FIELDS, default="div_b", help="field geometry (default div_b)")
    _add_backend(t, "the episodes")
    t.add_argument("--quiet", action="store_true", help="no progress bar")
    _add_tracker_option(t)
    t.set_defaults(func=cmd_eval_tactic)

    k = sub.add_parser("eval-task", help="evaluate a decision policy on keepaway or attack-3v2 (issue 12)",
                       description="Episodes of a decision-level multi-agent task (ssl_marl/decisions) with one "
                                   "policy for all learning agents; episode i uses seed SEED+i, so results do not "
                                   "depend on --workers. Writes OUT/results.json (keepaway: mean_duration_s, "
                                   "attack-3v2: goal_rate, with 95%% intervals, outcomes, every episode) and "
                                   "OUT/duration_hist.png.")
    k.add_argument("task", choices=("keepaway", "attack-3v2"), help="the decision task")
    k.add_argument("--policy", choices=("learned", "handcoded", "random", "always-hold"), default="handcoded",
                   help="decision policy: learned (ssl_marl.decisions.learned, the shipped actor or --actor), "
                        "handcoded (the task's benchmark), random (uniform over legal options), always-hold "
                        "(keepaway only) (default handcoded)")
    k.add_argument("--actor", default=None, metavar="PATH",
                   help="learned decision actor file (.pt, loaded with weights_only=True); only with --policy "
                        "learned (default: ssl_marl/decisions/pretrained/TASK.pt)")
    k.add_argument("--episodes", type=_positive_int("--episodes"), default=1000, help="episodes (default 1000)")
    k.add_argument("--seed", type=int, default=None,
                   help="evaluation seed: episode i uses SEED+i (default 40000 keepaway, 41000 attack-3v2)")
    k.add_argument("--workers", type=_positive_int("--workers"), default=None,
                   help="worker processes (default 1; with --backend ray: tasks in flight, default the cluster's CPUs)")
    k.add_argument("--realism", choices=("none", "realistic"), default="none", help="noise / latency preset")
    k.add_argument("--field", choices=FIELDS, default="div_b",
                   help="field around the task's area (robot parameters are the same on both; default div_b)")
    k.add_argument("--out", default=None,
                   help="output folder for results.json and duration_hist.png, created if missing (default: none)")
    _add_backend(k, "the episodes")
    k.add_argument("--quiet", action="store_true", help="no progress bar")
    _add_tracker_option(k)
    k.set_defaults(func=cmd_eval_task)

    b = sub.add_parser("bench", help="env throughput benchmark (JSON); options: ssl-marl bench --help",
                       add_help=False)
    b.add_argument("rest", nargs=argparse.REMAINDER, help="options of python -m ssl_marl.bench")
    b.set_defaults(func=cmd_bench)

    tr = sub.add_parser("train", help="train a skill with DDPG, as python -m train (ssl-marl train --help)",
                        add_help=False)
    tr.add_argument("rest", nargs=argparse.REMAINDER, help="options of python -m train")
    tr.set_defaults(func=cmd_train)

    x = sub.add_parser("export-onnx", help="write a learned-skill actor checkpoint as an ONNX model",
                       description="Export a learned-skill actor (an ssl_marl actor checkpoint, e.g. "
                                   "ssl_marl/skills/pretrained/go_to_ball.pt or a run's actor.pt) to ONNX for "
                                   "deployment in C++/Rust (onnxruntime). Input 'obs' (batch, obs_dim) float32, "
                                   "output 'action' (batch, act_dim) in [-1, 1]; the observation spec, feature "
                                   "names, normalisation and action mapping are in the model's metadata_props. "
                                   "Needs the 'onnx' extra: pip install -e \".[onnx]\".")
    x.add_argument("checkpoint", help="actor checkpoint (.pt) written by ssl_marl (weights only; never executed)")
    x.add_argument("out", help="output .onnx path (missing folders are created)")
    x.add_argument("--opset", type=_int_at_least("--opset", 13), default=17, help="ONNX opset version (default 17)")
    x.set_defaults(func=cmd_export_onnx)
    return p


def main(argv: list[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    if argv and argv[0] in FORWARDED:  # bench / train own their options (and --help): forward them verbatim
        rest = argv[1:][1:] if argv[1:2] == ["--"] else argv[1:]
        args = argparse.Namespace(command=argv[0], rest=rest,
                                  func={"bench": cmd_bench, "train": cmd_train}[argv[0]])
    else:
        args = build_parser().parse_args(argv)
    try:
        return args.func(args)
    except (ValueError, FileNotFoundError, FileExistsError) as exc:  # bad input: one clear line, exit 2
        print(f"ssl-marl {args.command}: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
