"""The attacking plays' shot threshold in the attack drill: does a carrier that shoots less score more.

The cost decision shoots at once when the shot value reaches ``DecisionParams.shoot_threshold``
(and, without a good pass, at ``shoot_fallback``; the attacking team plays 0.25 for both). This
probe plays the attack drill (``ssl_marl.decisions.attack_drill``, the hand-coded cost decision
for the carrier) with both set to each given value and reports the goal rate and outcomes per
value on the same episodes (episode i: seed ``SEED + i``)::

    python benchmarks/attack_drill_shoot_probe.py --thresholds 0.25 0.35 0.5 0.7 --episodes 200 --seed 46000 \\
        --out results/tuning/attack_drill_shoot_threshold.json
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import sys
from pathlib import Path

from ssl_marl.decisions.attack_drill import DRILL_PASSING, AttackDrillEnv
from ssl_marl.io import atomic_write_json
from ssl_marl.runners.provenance import build_manifest

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from benchmarks.attack_drill_aim_probe import add_drill_options, drill_outcomes  # noqa: E402


def run(threshold: float, episodes: int, seed: int, progress: bool) -> dict:
    """Goal rate and outcomes of the hand-coded drill with shot threshold and fallback ``threshold``."""
    decision = dataclasses.replace(DRILL_PASSING.decision, shoot_threshold=threshold, shoot_fallback=threshold)
    env = AttackDrillEnv(passing=dataclasses.replace(DRILL_PASSING, decision=decision))
    outcomes = drill_outcomes(env, episodes, seed, f"threshold {threshold}", progress)
    return {"shoot_threshold": threshold, "episodes": episodes, "goal_rate": outcomes["goal"] / episodes,
            "outcomes": dict(outcomes)}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--thresholds", nargs="+", type=float, default=[0.25, 0.35, 0.5],
                    help="shot values to try as shoot_threshold and shoot_fallback (default 0.25 0.35 0.5)")
    add_drill_options(ap, "threshold")
    a = ap.parse_args(argv)
    bad = [t for t in a.thresholds if not (math.isfinite(t) and 0.0 <= t <= 1.0)]
    if bad or a.episodes < 1:
        ap.error(f"thresholds must lie in [0, 1] (got {bad}) and --episodes be >= 1 (got {a.episodes})")
    rows = [run(t, a.episodes, a.seed, not a.quiet) for t in a.thresholds]
    for r in rows:
        print(r, flush=True)
    atomic_write_json(a.out, {"rows": rows, "manifest": build_manifest(
        rules={"probe": "attack_drill_shoot_threshold", "skills": "learned"},
        seeds={"seed": a.seed, "episodes": a.episodes})})
    return 0


if __name__ == "__main__":
    sys.exit(main())
