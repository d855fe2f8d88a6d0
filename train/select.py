"""Model selection: evaluate every actor a run exported at its checkpoints, on validation seeds.

    python -m train.select RUN_DIR [--episodes 500] [--seed 5000] [--workers 2] [--min-samples 0]

The trainer writes ``RUN_DIR/actors/actor-<samples>.pt`` at each checkpoint. Each is
evaluated with the skill protocol (:func:`ssl_marl.runners.skill_eval.evaluate_skill`,
ideal conditions) on ``--episodes`` episodes from ``--seed``, a validation seed that
is neither a training seed nor a reporting seed (this project reports skills on seed
10000 and trains on 0 and its evaluation seed 1000). The best actor (highest success,
then lowest mean time to success, then fewer samples) is named in
``RUN_DIR/selection.json``, written atomically with every candidate's figures; ship it
by copying it to ``ssl_marl/skills/pretrained/``.
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from ssl_marl.io import atomic_write_json
from ssl_marl.skills.checkpoint import load_actor
from ssl_marl.runners.skill_eval import evaluate_skill


def select(run: str | Path, episodes: int = 500, seed: int = 5000, workers: int = 1, min_samples: int = 0,
           progress: bool = True) -> dict[str, Any]:
    run = Path(run)
    actors = sorted((run / "actors").glob("actor-*.pt"))
    if not actors:
        raise FileNotFoundError(f"no exported actors in {run / 'actors'} (the trainer writes one per checkpoint)")
    rows = []
    for path in actors:
        _, meta = load_actor(path)
        if int(meta.get("samples", 0)) < min_samples:
            continue
        task = str(meta["skill"]).replace("_", "-")
        res = evaluate_skill(task, str(path), episodes=episodes, seed=seed, workers=workers, progress=progress)
        rows.append({"actor": str(path), "samples": int(meta["samples"]), "success_rate": res["success_rate"],
                     "successes": res["successes"], "mean_time_s": res["time_to_success_s"].get("mean"),
                     "failure_reasons": res["failure_reasons"]})
        print(f"{path.name}: {res['successes']}/{episodes} = {res['success_rate']:.3f}, "
              f"time {res['time_to_success_s'].get('mean')}", flush=True)
    if not rows:
        raise ValueError(f"no actor in {run / 'actors'} has >= {min_samples} samples")
    best = max(rows, key=lambda r: (r["success_rate"], -(r["mean_time_s"] or 1e9), -r["samples"]))
    out = {"run": str(run), "validation_seed": seed, "episodes": episodes, "best": best, "candidates": rows}
    atomic_write_json(run / "selection.json", out)
    return out


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(prog="python -m train.select", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("run", type=Path, help="run folder holding actors/actor-*.pt")
    p.add_argument("--episodes", type=int, default=500, help="validation episodes per actor")
    p.add_argument("--seed", type=int, default=5000, help="validation seed (not a training or reporting seed)")
    p.add_argument("--workers", type=int, default=1, help="evaluation processes")
    p.add_argument("--min-samples", type=int, default=0, help="skip actors with fewer env samples")
    p.add_argument("--no-progress", action="store_true", help="no progress bars")
    a = p.parse_args(argv)
    best = select(a.run, a.episodes, a.seed, a.workers, a.min_samples, not a.no_progress)["best"]
    print(f"best: {best['actor']} ({best['success_rate']:.3f})")


if __name__ == "__main__":
    main()
