"""``ssl-marl league``: scheduled matches among teams, ratings and a results matrix."""

from __future__ import annotations

import argparse

from .options import FIELDS, add_backend, positive_float, positive_int, robots, team, workers


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``league`` subparser."""
    p = subparsers.add_parser("league", help="round-robin league among teams: ratings and a results matrix",
                              description="Play a round-robin league among TEAMs (SSL-format 600 s matches by "
                                          "default), rate every team with openskill's Plackett-Luce model (mu, "
                                          "sigma, ordinal = mu - 3 sigma; a draw is a tie) and write OUT/league.json "
                                          "(matches with seeds and scores, ratings, results matrix, manifest), "
                                          "OUT/ratings.md and OUT/matrix.png. A rerun with the same arguments "
                                          "resumes, playing only the missing matches; one with more --rounds extends the league. "
                                          "Needs the league extra "
                                          "(pip install -e \".[league]\").")
    p.add_argument("teams", nargs="+", type=team, metavar="TEAM",
                   help="two or more teams: learned, baseline, passing-learned, passing-baseline, "
                        "passing-learned-decision, attack-learned, attack-baseline, attack-learned-decision, random, "
                        "idle, or a JSON team file {\"kind\": ..., \"skills\": {SKILL: SOURCE}, \"decision\": "
                        "DECISION} (a learned snapshot: skill checkpoints, or a decision actor PATH, handcoded or "
                        "learned; skills and decision optional)")
    p.add_argument("--rounds", type=positive_int("--rounds"), default=1,
                   help="round-robin rounds (default 1); more than a league folder holds extend it")
    p.add_argument("--colours", choices=("alternate", "both"), default="alternate",
                   help="alternate: each pair plays once per round, colours swapped from round to round; both: "
                        "each pair plays twice per round, once in each colour (default alternate)")
    p.add_argument("--seed", type=int, default=0,
                   help="league seed; match i's seed is derived from it and i, so a league is reproducible "
                        "(default 0)")
    p.add_argument("--seconds", type=positive_float("--seconds"), default=600.0,
                   help="simulated match length in seconds (default 600, an SSL match)")
    p.add_argument("--format", choices=("plain", "ssl"), default="ssl",
                   help="ssl: two halves of --seconds / 2 of playing time (the clock stops during STOP), referee commands, "
                        "fouls and seeded restarts; plain: one "
                        "period, play restarted at once after the ball leaves the field (default ssl)")
    p.add_argument("--robots", type=robots, default=6, help="robots per team, 1-11 (default 6)")
    p.add_argument("--field", choices=FIELDS, default="div_b", help="field geometry (default div_b)")
    p.add_argument("--realism", choices=("none", "realistic"), default="none",
                   help="vision noise / latency preset (default none)")
    p.add_argument("--out", default="runs/league", metavar="DIR",
                   help="output folder (missing folders are created; a league already there resumes; default "
                        "runs/league)")
    p.add_argument("--workers", type=positive_int("--workers"), default=None,
                   help="parallel worker processes (default 1; with --backend ray: matches in flight, default the "
                        "cluster's CPUs)")
    add_backend(p, "the matches")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Play (or resume) the league and print the ratings table."""
    from ..runners.league import MATRIX_FILE, LeagueConfig, play_league, ratings_markdown

    if args.address is not None and args.backend != "ray":
        raise ValueError("--address needs --backend ray")
    config = LeagueConfig(teams=tuple(args.teams), rounds=args.rounds, colours=args.colours, seed=args.seed,
                          seconds=args.seconds, robots=args.robots, field=args.field, realism=args.realism,
                          match_format=args.format)
    state = play_league(config, args.out, workers=workers(args), backend=args.backend, address=args.address,
                        progress=not args.quiet)
    print(ratings_markdown(state))
    print(f"-> {args.out}/league.json, {args.out}/ratings.md, {args.out}/{MATRIX_FILE}")
    return 0
