"""Why the ball leaves the field so often: every ball-out of a few matches, classified.

For each ``ball_out`` event of ``ssl-marl match``-style matches (the same runner,
:func:`ssl_marl.runners.match.play_match`) this records, from the world one control step
before the call: the ball's speed (m/s), the line it crossed (touch line or goal line), the
team of the robot nearest the ball and its distance (m), and the time since the previous
restart (kickoff or placement, s). The summary counts outs by line, by exit speed (slow,
< 1 m/s: pushed or dribbled over the line; medium, 1-3 m/s; fast, > 3 m/s: kicked) and how
many came within 3 s of the previous restart (a placed ball that goes out again at once).

    python benchmarks/ball_out_probe.py --blue attack-learned --yellow baseline --seconds 600 \\
        --seeds 61000-61001 --out results/tuning/ball_out_probe.json
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))


def seed_range(text: str) -> list[int]:
    lo, _, hi = text.partition("-")
    return list(range(int(lo), int(hi or lo) + 1))


def probe_match(blue: str, yellow: str, seconds: float, seed: int) -> list[dict]:
    """The ball-outs of one match (see the module docstring)."""
    from ssl_marl.runners import match as match_runner

    outs: list[dict] = []
    last = {"truth": None, "restart_t": 0.0}
    original = match_runner.MatchStats.record

    def record(self, events, truth):
        prev = last["truth"]
        for e in events:
            if e.get("type") in ("no_progress", "goal"):  # play restarts (a ball-out below)
                last["restart_t"] = float(e.get("t", truth.t))
            if e.get("type") == "ball_out" and prev is not None:
                ball, vel = np.asarray(prev.ball_pos, float), np.asarray(prev.ball_vel, float)
                near = []
                for team in ("blue", "yellow"):
                    ts = prev.team(team)
                    if ts.n:
                        d = np.linalg.norm(ts.pos - ball, axis=1)
                        near.append((float(d.min()), team))
                dist, team = min(near)
                place = np.asarray(e["placement"], float)
                line = "goal" if abs(place[0]) > abs(place[1]) * 1.5 and abs(place[0]) > 4.0 else "touch"
                outs.append({"t": float(e["t"]), "speed": float(np.linalg.norm(vel)), "line": line,
                             "nearest_team": team, "nearest_m": dist, "since_restart_s": float(e["t"]) - last["restart_t"],
                             "ball": ball.round(3).tolist(), "placement": place.round(3).tolist()})
                last["restart_t"] = float(e["t"])
        last["truth"] = truth
        return original(self, events, truth)

    match_runner.MatchStats.record = record
    try:
        res = match_runner.play_match(blue=blue, yellow=yellow, seconds=seconds, seed=seed, progress=False)
    finally:
        match_runner.MatchStats.record = original
    return [{**o, "seed": seed, "score": res.score} for o in outs]


def summarize(outs: list[dict], matches: int, seconds: float) -> dict:
    speed = np.array([o["speed"] for o in outs]) if outs else np.zeros(0)
    since = np.array([o["since_restart_s"] for o in outs]) if outs else np.zeros(0)
    per = 600.0 / seconds / max(matches, 1)
    return {"outs": len(outs), "outs_per_600s": len(outs) * per,
            "by_line": {k: sum(o["line"] == k for o in outs) for k in ("touch", "goal")},
            "by_speed": {"slow_lt_1": int((speed < 1).sum()), "medium_1_3": int(((speed >= 1) & (speed <= 3)).sum()),
                         "fast_gt_3": int((speed > 3).sum())},
            "within_3s_of_restart": int((since < 3).sum()),
            "median_since_restart_s": float(np.median(since)) if since.size else None,
            "nearest_team": {k: sum(o["nearest_team"] == k for o in outs) for k in ("blue", "yellow")}}


def probe_args(description: str, default_seeds: str, out_help: str, argv: list[str] | None,
               extra=None) -> argparse.Namespace:
    """The match probes' command line: --blue, --yellow, --seconds, --seeds A-B, --out, and
    what ``extra(parser)`` adds."""
    ap = argparse.ArgumentParser(description=description)
    if extra is not None:
        extra(ap)
    ap.add_argument("--blue", default="attack-learned", help="blue team kind (default attack-learned)")
    ap.add_argument("--yellow", default="baseline", help="yellow team kind (default baseline)")
    ap.add_argument("--seconds", type=float, default=600.0, help="match length, s (default 600)")
    ap.add_argument("--seeds", type=seed_range, default=seed_range(default_seeds),
                    help=f"seed range A-B (tuning seeds; default {default_seeds})")
    ap.add_argument("--out", default=None, help=out_help)
    return ap.parse_args(argv)


def write_probe(args: argparse.Namespace, record: dict) -> None:
    """Print the record's summary; write the record with its manifest to ``args.out`` (if given)."""
    from ssl_marl.io import atomic_write_json
    from ssl_marl.runners.provenance import build_manifest

    print(json.dumps(record["summary"], indent=1))
    if args.out:
        atomic_write_json(args.out, {**record, "manifest": build_manifest(
            rules={"blue": args.blue, "yellow": args.yellow, "seconds": args.seconds,
                   **{k: getattr(args, k) for k in ("format", "robots", "field") if hasattr(args, k)}},
            seeds={"seeds": args.seeds})})


def main(argv: list[str] | None = None) -> int:
    args = probe_args(__doc__.splitlines()[0], "61000-61001", "JSON output (summary and every out)", argv)
    outs = [o for s in args.seeds for o in probe_match(args.blue, args.yellow, args.seconds, s)]
    write_probe(args, {"summary": summarize(outs, len(args.seeds), args.seconds), "outs": outs})
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
