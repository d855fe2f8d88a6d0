"""Bridge vs in-process matches: N lock-step matches through the bridge (both teams
``PlayBrain`` clients on loopback TCP, seeing only SSL-Vision detections) against N
in-process matches (:func:`ssl_marl.runners.match.play_match`) of the same teams and
seeds. Reports goals per match and goal difference (blue - yellow) with 95 %
intervals (mean +- 1.96 standard errors) and whether each mean lies in the other's interval.

    PYTHONPATH=. python benchmarks/bench_bridge_matches.py [--matches 20] [--robots 3] [--seconds 120]

Writes results/bridge/bench_bridge_matches.json. A benchmark, not a test.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from bench_bridge_common import provenance  # noqa: E402
from bridge_helpers import LOOP, loopback_server  # noqa: E402

from ssl_marl.bridge.client import PlayBrain, run_lockstep_match  # noqa: E402
from ssl_marl.bridge.world import WorldConfig  # noqa: E402


def bridge_match(kind: str, robots: int, seconds: float, seed: int) -> dict:
    server, vision, referee = loopback_server(WorldConfig(robots=robots, seconds=seconds, seed=seed), lockstep=True)
    thread = server.start()
    brains = {t: PlayBrain(t, kind, robots, seed=seed + k) for k, t in enumerate(("blue", "yellow"))}
    try:
        run_lockstep_match({t: (LOOP, server.ports[f"sync_{t}"]) for t in brains}, brains)
    finally:
        server.stop()
        thread.join(30)
        server.close()
        vision.close()
        referee.close()
    return dict(server.world.env.score)


def inprocess_match(kind: str, robots: int, seconds: float, seed: int) -> dict:
    from ssl_marl.runners.match import play_match

    return dict(play_match(kind, kind, robots=robots, seconds=seconds, seed=seed, progress=False).score)


def summary(scores: list[dict]) -> dict:
    diff = np.array([s["blue"] - s["yellow"] for s in scores], float)
    total = np.array([s["blue"] + s["yellow"] for s in scores], float)
    out = {}
    for name, x in (("goal_difference", diff), ("goals_per_match", total)):
        half = 1.96 * x.std(ddof=1) / np.sqrt(len(x)) if len(x) > 1 else float("nan")
        out[name] = {"mean": round(float(x.mean()), 3), "ci95": [round(float(x.mean() - half), 3),
                                                                 round(float(x.mean() + half), 3)]}
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--matches", type=int, default=20)
    parser.add_argument("--robots", type=int, default=3)
    parser.add_argument("--seconds", type=float, default=120.0)
    parser.add_argument("--kind", default="baseline")
    parser.add_argument("--out", default="results/bridge/bench_bridge_matches.json")
    args = parser.parse_args()
    seeds = range(args.matches)
    bridge = [bridge_match(args.kind, args.robots, args.seconds, s) for s in seeds]
    local = [inprocess_match(args.kind, args.robots, args.seconds, s) for s in seeds]
    sb, sl = summary(bridge), summary(local)
    within = {k: (sl[k]["ci95"][0] <= sb[k]["mean"] <= sl[k]["ci95"][1]
                  and sb[k]["ci95"][0] <= sl[k]["mean"] <= sb[k]["ci95"][1]) for k in sb}
    result = {**provenance(), "teams": args.kind, "robots": args.robots, "seconds": args.seconds,
              "bridge": {"scores": bridge, **sb}, "in_process": {"scores": local, **sl},
              "within_each_others_interval": within}
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text(json.dumps(result, indent=2) + "\n")
    print(json.dumps({k: v for k, v in result.items() if k not in ("bridge", "in_process")} | {"bridge": sb,
                     "in_process": sl}, indent=2))


if __name__ == "__main__":
    main()
