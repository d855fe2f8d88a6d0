"""Model selection: evaluate every actor a run exported at its checkpoints, on validation seeds.

    python -m train.select RUN_DIR [--episodes 500] [--seed 5000] [--workers 2] [--min-samples 0] [--reuse]

The trainer writes ``RUN_DIR/actors/actor-<samples>.pt`` at each checkpoint. Each is
evaluated with the skill protocol (:func:`ssl_marl.runners.skill_eval.evaluate_skill`,
ideal conditions) on ``--episodes`` episodes from ``--seed``, a validation seed that
is neither a training seed nor a reporting seed (this project reports skills on seed
10000 and trains on 0 and its evaluation seed 1000). The best actor (highest success,
then lowest mean time to success, then fewer samples) is named in
``RUN_DIR/selection.json``, written atomically with every candidate's figures; ship it
by copying it to ``ssl_marl/skills/pretrained/``. With ``--reuse`` the figures of actors
already in ``selection.json`` (same seed and episode count) are kept and only new
checkpoints are evaluated, so a running training can be selected from as it goes.
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

import json

from ssl_marl.io import atomic_write_json
from ssl_marl.skills.checkpoint import load_actor
from ssl_marl.runners.skill_eval import evaluate_skill


def _previous(run: Path, episodes: int, seed: int) -> dict[str, dict[str, Any]]:
    """Candidates of an earlier ``selection.json`` with the same protocol, by actor path."""
    try:
        old = json.loads((run / "selection.json").read_text())
    except (OSError, ValueError):
        return {}
    if old.get("episodes") != episodes or old.get("validation_seed") != seed:
        return {}
    return {c["actor"]: c for c in old.get("candidates", [])}


def select(run: str | Path, episodes: int = 500, seed: int = 5000, workers: int = 1, min_samples: int = 0,
           progress: bool = True, reuse: bool = False) -> dict[str, Any]:
    run = Path(run)
    actors = sorted((run / "actors").glob("actor-*.pt"))
    if not actors:
        raise FileNotFoundError(f"no exported actors in {run / 'actors'} (the trainer writes one per checkpoint)")
    done = _previous(run, episodes, seed) if reuse else {}
    rows = []
    for path in actors:
        _, meta = load_actor(path)
        if int(meta.get("samples", 0)) < min_samples:
            continue
        if str(path) in done:
            rows.append(done[str(path)])
            continue
        task = str(meta["skill"]).replace("_", "-")
        res = evaluate_skill(task, str(path), episodes=episodes, seed=seed, workers=workers, progress=progress)
        rows.append({"actor": str(path), "algo": meta.get("algo", "ddpg"), "samples": int(meta["samples"]),
                     "success_rate": res["success_rate"],
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
    p.add_argument("--reuse", action="store_true",
                   help="keep the figures of actors already in RUN/selection.json (same seed and episodes); "
                        "evaluate only new ones")
    p.add_argument("--no-progress", action="store_true", help="no progress bars")
    a = p.parse_args(argv)
    best = select(a.run, a.episodes, a.seed, a.workers, a.min_samples, not a.no_progress, a.reuse)["best"]
    print(f"best: {best['actor']} ({best['success_rate']:.3f})")


if __name__ == "__main__":
    main()
