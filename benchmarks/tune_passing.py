"""Tune the passing plays on tuning seeds: N matches of ``passing-learned`` with overridden
:class:`~ssl_marl.plays.pass_coordinator.PassingParams` / ``DecisionParams`` fields against an
opponent team kind, played on a process pool; writes one JSON (per-match score, possession,
referee statistics, no-progress restarts and the blue coordinator's own pass counters: planned,
kicked, completed, aborted) and prints a summary line.

    python benchmarks/tune_passing.py --opponent baseline --seed 45220 --matches 40 \\
        --override '{"passing": {"contested_kick": false}}' --out results/tuning/passing_nocont.json

``--override`` is ``{"passing": {field: value}, "decision": {field: value}}``. Tuning seeds
(45000+) are never used by the reported series (30000+). 6v6, Division B, 90 s, step mode.
"""

from __future__ import annotations

import argparse
import json
import sys
from multiprocessing import get_context


def play(args: tuple) -> dict:
    seed, opponent, override, kind, seconds, skills = args
    from ssl_marl.plays.pass_decision import DecisionParams
    from functools import partial

    from ssl_marl.plays.pass_coordinator import PassingParams
    from ssl_marl.plays.passing_play import passing_plays
    from ssl_marl.runners.controllers import make_controller
    from ssl_marl.runners.match import play_match

    params = PassingParams(decision=DecisionParams(**override.get("decision", {})), **override.get("passing", {}))
    blue = make_controller(kind, "blue", 6, "div_b", seed=seed, plays=partial(passing_plays, params), skills=skills)
    r = play_match(blue, opponent, robots=6, field="div_b", seconds=seconds, seed=seed, progress=False)
    from dataclasses import asdict

    from ssl_marl.plays.passing_play import coordinator_of

    return dict(seed=seed, score=r.score, possession=r.possession,
                stats={k: v for k, v in r.stats.items() if k != "events"},
                no_progress=sum(e["type"] == "no_progress" for e in r.stats["events"]),
                coordinator=asdict(coordinator_of(blue.selector.plays).counters))


def summary(matches: list[dict]) -> str:
    """One line: W-D-L, goals, shots, kicks and passes (completed/attempted) per side."""
    w = sum(m["score"]["blue"] > m["score"]["yellow"] for m in matches)
    lost = sum(m["score"]["blue"] < m["score"]["yellow"] for m in matches)
    gf, ga = (sum(m["score"][t] for m in matches) for t in ("blue", "yellow"))

    def tot(team: str, key: str) -> int:
        return sum(m["stats"][team][key] for m in matches)

    sides = " | ".join(f"{t}: shots {tot(t, 'shots')}, kicks {tot(t, 'kicks')}, passes "
                       f"{tot(t, 'passes_completed')}/{tot(t, 'passes_attempted')}" for t in ("blue", "yellow"))
    coord = ""
    if all("coordinator" in m for m in matches):
        c = {k: sum(m["coordinator"][k] for m in matches) for k in ("planned", "kicked", "completed", "aborted")}
        coord = (f" | blue's planned passes: {c['planned']} planned, {c['kicked']} kicked, {c['completed']} "
                 f"completed, {c['aborted']} aborted")
    restarts = ("" if any("no_progress" not in m for m in matches)
                else f" | no-progress restarts {sum(m['no_progress'] for m in matches)}")
    return (f"{len(matches)} matches: W-D-L {w}-{len(matches) - w - lost}-{lost}, goals {gf}-{ga} | {sides}"
            f"{restarts}{coord}")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--opponent", default="baseline", help="yellow team kind (default baseline)")
    ap.add_argument("--kind", default="passing-learned", help="blue passing team kind (default passing-learned)")
    ap.add_argument("--seed", type=int, default=45200, help="first match seed (tuning seeds: 45000+)")
    ap.add_argument("--matches", type=int, default=20, help="number of matches (seeds seed, seed+1, ...)")
    ap.add_argument("--seconds", type=float, default=90.0, help="match length (s)")
    ap.add_argument("--override", default="{}", help='JSON {"passing": {...}, "decision": {...}}')
    ap.add_argument("--skills", default=None,
                    help='JSON {skill: "learned"|"baseline"} replacing the blue team\'s skill set (ablations)')
    ap.add_argument("--workers", type=int, default=2, help="processes")
    ap.add_argument("--out", required=True, help="output JSON")
    args = ap.parse_args(argv)
    override = json.loads(args.override)
    unknown = set(override) - {"passing", "decision"}
    if unknown:
        ap.error(f"--override: unknown keys {sorted(unknown)}; expected 'passing' and/or 'decision'")
    skills = json.loads(args.skills) if args.skills else None
    jobs = [(args.seed + i, args.opponent, override, args.kind, args.seconds, skills) for i in range(args.matches)]
    with get_context("spawn").Pool(args.workers) as pool:
        matches = pool.map(play, jobs, chunksize=1)
    from ssl_marl.io import atomic_write_json

    atomic_write_json(args.out, {"override": override, "opponent": args.opponent, "kind": args.kind, "skills": skills,
                                 "matches": matches, "summary": summary(matches)})
    print(f"{args.out}: {summary(matches)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
