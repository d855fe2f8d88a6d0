"""``ssl-marl match``: a full-team STP match (or a series) between two team controllers."""

from __future__ import annotations

import argparse
import shutil
from pathlib import Path

from ..envs.animation import VIDEO_SUFFIXES
from .options import (FIELDS, SKILL_SOURCE_HELP, add_backend, add_tracker_option, int_at_least, non_negative_float,
                      positive_float, positive_int, robots, skill_source, team, workers)


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``match`` subparser."""
    m = subparsers.add_parser("match", help="full-team match (or series) between two team controllers",
                              description="Play a full-team STP match in the parallel env: kickoffs, restarts after "
                                          "goals and out-of-play. Prints the score and stats; writes a GIF/MP4 with "
                                          "--render.")
    m.add_argument("--blue", type=team, default="learned", metavar="TEAM",
                   help="blue team: learned (STP with the shipped DDPG actors), baseline (STP with hand-coded "
                        "skills), passing-learned / passing-baseline (the passing plays: shoot, pass or keep by "
                        "cost, set plays with passes, with those skills), passing-learned-decision (passing-learned "
                        "whose ball carrier uses the learned Attack 3v2 decision), attack-learned / "
                        "attack-baseline (the attacking plays: shot, flat pass, chip pass, pass into a one-touch "
                        "redirect or dribble by cost, supports on rated spots; the match then runs with chip kicks), "
                        "attack-learned-decision (attack-learned whose ball carrier uses the learned attack-drill "
                        "decision in open play), random, idle, or a JSON team file "
                        "{\"kind\": ..., \"skills\": {SKILL: SOURCE}, \"decision\": DECISION} (skills and "
                        "decision optional; default learned)")
    m.add_argument("--yellow", type=team, default="baseline", metavar="TEAM",
                   help="yellow team, as --blue (default baseline)")
    m.add_argument("--skill", type=skill_source, action="append", default=[], metavar="SKILL=SOURCE",
                   help="for both STP teams: " + SKILL_SOURCE_HELP)
    m.add_argument("--blue-skill", type=skill_source, action="append", default=[], metavar="SKILL=SOURCE",
                   help="as --skill, for the blue team only (wins over --skill)")
    m.add_argument("--yellow-skill", type=skill_source, action="append", default=[], metavar="SKILL=SOURCE",
                   help="as --skill, for the yellow team only (wins over --skill)")
    for side in ("blue", "yellow"):
        m.add_argument(f"--{side}-decision", default=None, metavar="DECISION",
                       help=f"{side} passing or attacking team's ball-carrier decision: handcoded (the cost "
                            "decision), learned (the shipped actor: Attack 3v2 for passing-* teams, the attack "
                            "drill's for attack-* teams), improved (attack-* teams: the cost decision, except at "
                            "the first decision of a possession in the attacking half, where the shipped attack-drill "
                            "value actor's option is played if its logit, the predicted log-odds of a goal, is 0.1 above "
                            "the cost decision's option's) or PATH to a decision "
                            "actor checkpoint of that task; needs "
                            "a passing-* or attack-* team; wins over a team file's decision (default: the team's own: "
                            "the team file's, learned for *-learned-decision, else handcoded)")
    m.add_argument("--robots", type=robots, default=6, help="robots per team, 1-11 (default 6)")
    m.add_argument("--field", choices=FIELDS, default="div_b", help="field geometry (default div_b)")
    m.add_argument("--seconds", type=positive_float("--seconds"), default=30.0,
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
    m.add_argument("--render-fps", type=positive_float("--render-fps"), default=10.0,
                   help="video frames per simulated second (default 10)")
    m.add_argument("--render-width", type=int_at_least("--render-width", 64), default=480,
                   help="video width in pixels, >= 64 (default 480)")
    m.add_argument("--matches", type=positive_int("--matches"), default=1, help="number of matches (default 1)")
    m.add_argument("--workers", type=positive_int("--workers"), default=None,
                   help="parallel worker processes for a series (default 1; with --backend ray: matches in flight, "
                        "default the cluster's CPUs)")
    add_backend(m, "the matches of a series")
    m.add_argument("--json", default=None, metavar="PATH",
                   help="also write the result as JSON to PATH (missing folders are created) with its manifest "
                        "(commit, actors' hashes, rules, seeds) beside it as <stem>.manifest.json; a series keeps "
                        "each finished match in PATH.partial/ until PATH is written, so the same command run "
                        "again after an interruption plays only the missing matches")
    m.add_argument("--quiet", action="store_true", help="no progress bar")
    m.add_argument("--ssl-log", default=None, metavar="PATH",
                   help="also write the match as an SSL log file (the SSL log recorder's format: vision and "
                        "referee packets, readable by SSL log players): the bridge plays the same seeded match "
                        "again and records it, in either --format (ssl: the referee packets carry SSL's game "
                        "control); single matches of named teams without --skill or --*-decision options "
                        "(needs the ssl extra)")
    m.add_argument("--no-progress-s", type=non_negative_float("--no-progress-s"), default=10.0,
                   help="the referee restarts play when the ball stays within 0.25 m of one spot this long "
                        "(SSL force start after a lack of progress; seconds, default 10; 0 switches the call off)")
    m.add_argument("--restart-jitter-m", type=non_negative_float("--restart-jitter-m"), default=0.1,
                   help="every restart (kickoff after a goal, placement after an out or a no-progress call) "
                        "places the robots within this many metres of the fixed placement, drawn from the match "
                        "seed: the same seed replays the same match, but no restart repeats an earlier one "
                        "(metres, default 0.1; 0: the fixed placements, so a deterministic kickoff can replay "
                        "itself after every goal)")
    m.add_argument("--format", choices=("plain", "ssl"), default="plain",
                   help="plain: one period, play restarted at once after the ball leaves the field; ssl: SSL's "
                        "format: two halves of --seconds / 2 of playing time (the clock stops during STOP, as SSL's does) "
                        "with ends changed at half-time, referee commands "
                        "(STOP, kickoff, free kick to the team that did not touch the ball last), the fouls "
                        "excessive dribbling, double touch and attacker in the defense area, and restart "
                        "placements drawn from the match seed (use --seconds 600 for an SSL match)")
    m.add_argument("--team-processes", choices=("auto", "on", "off"), default="auto",
                   help="single matches: 'on' runs yellow's team software in its own process, deciding while "
                        "blue's decides (as SSL teams do on their own computers): the same match, bit for bit, in "
                        "less wall time; 'auto' (default) does so on machines with two or more CPUs where the "
                        "match allows it (step mode, a named yellow team); 'off': one process")
    add_tracker_option(m)
    m.set_defaults(handler=run)


def resolve_team(side: str, value: str, sources: list[tuple[str, str]], decision: str | None = None):
    """(kind, skills spec or None, decision or None) for a team option (``--blue`` /
    ``--yellow``), its skill sources and its ``--*-decision`` (which wins over a team file's)."""
    from ..runners.controllers import resolve_team_option

    return resolve_team_option(value, sources, where=f"--{side}", decision=decision)


def match_line(res) -> str:
    """One line of a single match's result: score, kicks (every kick event), possession, times."""
    s, sh, po = res.score, res.shots, res.possession
    return (f"blue ({res.config.get('blue')}) {s['blue']} - {s['yellow']} yellow ({res.config.get('yellow')})"
            f"  | kicks {sh.get('blue', 0)}-{sh.get('yellow', 0)}"
            f"  | possession {100 * po.get('blue', 0):.0f}%-{100 * po.get('yellow', 0):.0f}%"
            f"  | {res.sim_time_s:.0f} s simulated in {res.wall_time_s:.1f} s wall"
            + (f"  | missed deadlines {res.missed_deadlines}" if res.config.get("realtime") else ""))


def series_line(st: dict) -> str:
    """The series' intervals (:func:`~ssl_marl.runners.statistics.series_statistics`, blue's view)."""
    return (f"  win rate {100 * st['win_rate']:.0f}% (95% {100 * st['win_rate_ci95'][0]:.0f}-"
            f"{100 * st['win_rate_ci95'][1]:.0f}%), goal difference per match {st['goal_diff_per_match']:+.2f} "
            f"(95% {st['goal_diff_per_match_ci95'][0]:+.2f} to {st['goal_diff_per_match_ci95'][1]:+.2f}), "
            f"per 600 s {st['goal_diff_per_600s']:+.2f} (95% {st['goal_diff_per_600s_ci95'][0]:+.2f} to "
            f"{st['goal_diff_per_600s_ci95'][1]:+.2f})")


def run(args: argparse.Namespace) -> int:
    """Play one match (or a series) between two team controllers."""
    from ..io import atomic_write_json, prepare_output_file
    from ..runners.match import format_options, play_match
    from ..runners.provenance import build_manifest
    from ..runners.result import manifest_path, write_series_file
    from ..runners.series import play_series

    if args.address is not None and args.backend != "ray":
        raise ValueError("--address needs --backend ray")
    blue, blue_skills, blue_decision = resolve_team("blue", args.blue, args.skill + args.blue_skill,
                                                    args.blue_decision)
    yellow, yellow_skills, yellow_decision = resolve_team("yellow", args.yellow, args.skill + args.yellow_skill,
                                                          args.yellow_decision)
    common = dict(robots=args.robots, field=args.field, seconds=args.seconds, realism=args.realism,
                  realtime=args.realtime, blue_skills=blue_skills, yellow_skills=yellow_skills,
                  tracker=args.tracker, blue_decision=blue_decision, yellow_decision=yellow_decision,
                  restart_jitter_m=args.restart_jitter_m,
                  env_kwargs={"no_progress_s": args.no_progress_s or None, **format_options(args.format, args.seconds)})
    render = None if str(args.render).lower() == "none" else args.render
    if render is not None and args.matches == 1:
        prepare_output_file(render, VIDEO_SUFFIXES, "--render")
    if args.json:
        prepare_output_file(args.json, None, "--json")
    if args.ssl_log:
        if args.matches != 1 or blue_skills or yellow_skills or blue_decision \
                or yellow_decision or args.realtime or args.no_progress_s != 10.0 \
                or args.restart_jitter_m != 0.1:
            raise ValueError("--ssl-log records single matches of named teams (no --matches > 1, "
                             "--skill, --*-decision, --realtime, --no-progress-s or --restart-jitter-m)")
        prepare_output_file(args.ssl_log, None, "--ssl-log")
    rules = {"runner": "match", "blue": args.blue, "yellow": args.yellow, **common,
             "no_progress_s": common["env_kwargs"]["no_progress_s"]}
    if args.matches == 1:
        res = play_match(blue=blue, yellow=yellow, seed=args.seed, render=render,
                         render_fps=args.render_fps, render_width_px=args.render_width, progress=not args.quiet,
                         team_processes=args.team_processes, **common)
        print(match_line(res) + (f"  | video -> {render}" if render else ""))
        if args.json:
            atomic_write_json(args.json, res.to_dict())
            atomic_write_json(manifest_path(args.json),
                              build_manifest(rules=rules, seeds={"seed": args.seed, "matches": 1}))
        if args.ssl_log:
            _write_ssl_log(args, res)
        return 0
    keep_dir = partial_dir(args.json) if args.json else None
    results, summary = play_series(blue=blue, yellow=yellow, matches=args.matches, workers=workers(args),
                                   seed=args.seed, progress=not args.quiet, backend=args.backend,
                                   address=args.address, keep_dir=keep_dir, **common)
    print(f"{'match':>5} {'seed':>6}  {'score':>7}  {'kicks':>7}  possession")
    for i, r in enumerate(results):
        print(f"{i:>5} {r.seed:>6}  {r.score['blue']:>3}-{r.score['yellow']:<3}  {r.shots['blue']:>3}-{r.shots['yellow']:<3}"
              f"  {100 * r.possession['blue']:.0f}%-{100 * r.possession['yellow']:.0f}%")
    print(f"blue ({args.blue}) vs yellow ({args.yellow}), {summary['matches']} matches: "
          f"W {summary['wins']} D {summary['draws']} L {summary['losses']}, "
          f"goals {summary['goals_for']}-{summary['goals_against']}")
    print(series_line(summary["statistics"]))
    for team_name, st in summary.get("stats", {}).items():
        pc = "-" if st["pass_completion"] is None else f"{100 * st['pass_completion']:.0f}%"
        print(f"  {team_name}: shots {st['shots']}, passes {st['passes_completed']}/{st['passes_attempted']} completed "
              f"({pc}), intercepted {st['passes_intercepted']}, interceptions {st['interceptions']}, "
              f"goals {st['goals']}")
    referee = {}
    for r in results:
        for k, v in r.stats.get("referee", {}).items():
            referee[k] = referee.get(k, 0) + v
    if referee:
        print("  referee calls: " + ", ".join(f"{k} {v}" for k, v in sorted(referee.items())))
    if args.json:
        write_series_file(args.json, summary, [r.to_dict() for r in results], build_manifest(
            rules=rules, seeds={"seed": args.seed, "matches": args.matches}))
        shutil.rmtree(keep_dir, ignore_errors=True)
    return 0


def partial_dir(json_path: str) -> Path:
    """Where a series with ``--json PATH`` keeps its finished matches until PATH is written
    (``PATH.partial/``): the same command run again resumes from there."""
    return Path(str(json_path) + ".partial")


def _write_ssl_log(args: argparse.Namespace, res) -> None:
    """Record the match just played as an SSL log (the bridge's world replays the same
    seeded match) and check that it ended with the same score."""
    from ..bridge.log_tools import record_match_log

    score = record_match_log(args.ssl_log, blue=args.blue, yellow=args.yellow, robots=args.robots, field=args.field,
                             seconds=args.seconds, seed=args.seed, realism=args.realism, format=args.format)
    same = score == dict(res.score)
    print(f"SSL log -> {args.ssl_log} (score {score['blue']}:{score['yellow']}"
          + ("" if same else f"; the recorded replay differs from the match played, {res.score}") + ")")
