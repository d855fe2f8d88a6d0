"""Model selection: evaluate every actor a run exported at its checkpoints, on validation seeds.

    python -m train.select RUN_DIR [--episodes 500] [--seed 5000] [--workers 2] [--min-samples 0] [--reuse]
                                   [--fields div_a,div_b]

The trainer writes ``RUN_DIR/actors/actor-<samples>.pt`` at each checkpoint. Each is
evaluated with the skill protocol (:func:`ssl_marl.runners.skill_eval.evaluate_skill`,
ideal conditions, the task options it was trained under: :func:`training_task_options`) on ``--episodes`` episodes from ``--seed``, a validation seed that
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


def _previous(run: Path, episodes: int, seed: int, fields: list[str] | None) -> dict[str, dict[str, Any]]:
    """Candidates of an earlier ``selection.json`` with the same protocol, by actor path."""
    try:
        old = json.loads((run / "selection.json").read_text())
    except (OSError, ValueError):
        return {}
    if old.get("episodes") != episodes or old.get("validation_seed") != seed or old.get("fields") != fields:
        return {}
    return {c["actor"]: c for c in old.get("candidates", [])}


def training_fields(meta: dict[str, Any]) -> list[str]:
    """The fields an actor was trained on, from its metadata (``env_kwargs`` and
    ``env_variants``; default Division B)."""
    hp = meta.get("hyperparameters") if isinstance(meta.get("hyperparameters"), dict) else {}
    base = (hp.get("env_kwargs") or {}).get("field", "div_b")
    fields = [v.get("field", base) for v in hp.get("env_variants") or [] if isinstance(v, dict)] or [base]
    return list(dict.fromkeys(fields))


def training_task_options(meta: dict[str, Any]) -> dict[str, Any]:
    """The task conditions an actor was trained under, from its metadata's ``env_kwargs``
    (e.g. receive's interceptors and hold time), without the action and reward forms and
    the protocol's own options: the validation runs the task it was trained on."""
    hp = meta.get("hyperparameters") if isinstance(meta.get("hyperparameters"), dict) else {}
    return _task_options(hp.get("env_kwargs") or {})


def _task_options(kwargs: dict[str, Any]) -> dict[str, Any]:
    skip = {"action_form", "reward_form", "field", "realism", "realtime", "tracker", "render_mode"}
    return {k: v for k, v in kwargs.items() if k not in skip}


def training_variants(meta: dict[str, Any], fields: list[str] | None = None) -> list[tuple[str, str, dict[str, Any]]]:
    """(label, field, task options) of each condition an actor was trained under: one per
    field of :func:`training_fields` (or of ``fields``) times each distinct set of task
    options of ``env_kwargs`` / ``env_variants``. The label is the field, followed by
    the options where any differ between variants (``"div_b interceptors=1 hold_s=0.1"``)."""
    hp = meta.get("hyperparameters") if isinstance(meta.get("hyperparameters"), dict) else {}
    base = hp.get("env_kwargs") or {}
    opts = [_task_options({**base, **v}) for v in hp.get("env_variants") or [] if isinstance(v, dict)]
    opts = [o for k, o in enumerate(opts) if o not in opts[:k]] or [_task_options(base)]
    out = []
    for fld in fields or training_fields(meta):
        for o in opts:
            label = fld if len(opts) == 1 else " ".join([fld] + [f"{k}={json.dumps(v)}" for k, v in sorted(o.items())])
            out.append((label, fld, o))
    return out


def select(run: str | Path, episodes: int = 500, seed: int = 5000, workers: int = 1, min_samples: int = 0,
           progress: bool = True, reuse: bool = False, fields: list[str] | None = None) -> dict[str, Any]:
    """Evaluate each exported actor of ``run`` on ``episodes`` validation episodes per
    training condition (:func:`training_variants`: each field, ``fields`` or the fields it
    was trained on, times each set of task options it was trained under) and name the best
    in ``RUN/selection.json``. With several conditions an actor's ``success_rate`` is its
    lowest over them (it is shipped for all of them) and ``mean_time_s`` the mean of their
    means; each condition's figures are kept under ``by_field``, keyed by its label."""
    run = Path(run)
    actors = sorted((run / "actors").glob("actor-*.pt"))
    if not actors:
        raise FileNotFoundError(f"no exported actors in {run / 'actors'} (the trainer writes one per checkpoint)")
    done = _previous(run, episodes, seed, fields) if reuse else {}
    rows = []
    for path in actors:
        _, meta = load_actor(path)
        if int(meta.get("samples", 0)) < min_samples:
            continue
        if str(path) in done:
            rows.append(done[str(path)])
            continue
        task = str(meta["skill"]).replace("_", "-")
        by_field = {}
        for label, fld, options in training_variants(meta, fields):
            res = evaluate_skill(task, str(path), episodes=episodes, seed=seed, workers=workers, progress=progress,
                                 field=fld, task_options=options)
            by_field[label] = {"success_rate": res["success_rate"], "successes": res["successes"],
                             "mean_time_s": res["time_to_success_s"].get("mean"),
                             "failure_reasons": res["failure_reasons"]}
            print(f"{path.name} ({label}): {res['successes']}/{episodes} = {res['success_rate']:.3f}, "
                  f"time {res['time_to_success_s'].get('mean')}", flush=True)
        figs = list(by_field.values())
        times = [f["mean_time_s"] for f in figs]
        row = {"actor": str(path), "algo": meta.get("algo", "ddpg"), "samples": int(meta["samples"]),
               "success_rate": min(f["success_rate"] for f in figs),
               "successes": sum(f["successes"] for f in figs),
               "mean_time_s": None if None in times else sum(times) / len(times),
               "failure_reasons": figs[0]["failure_reasons"] if len(figs) == 1 else None}
        if len(figs) > 1:
            row["by_field"] = by_field
        rows.append(row)
    if not rows:
        raise ValueError(f"no actor in {run / 'actors'} has >= {min_samples} samples")
    best = max(rows, key=lambda r: (r["success_rate"], -(r["mean_time_s"] or 1e9), -r["samples"]))
    out = {"run": str(run), "validation_seed": seed, "episodes": episodes, "fields": fields, "best": best,
           "candidates": rows}
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
    p.add_argument("--fields", default=None,
                   help="comma-separated fields to validate on, e.g. div_a,div_b (default: the fields each actor "
                        "was trained on; with several, an actor's success is its lowest over them)")
    a = p.parse_args(argv)
    fields = None if a.fields is None else [f.strip() for f in a.fields.split(",") if f.strip()]
    best = select(a.run, a.episodes, a.seed, a.workers, a.min_samples, not a.no_progress, a.reuse, fields)["best"]
    print(f"best: {best['actor']} ({best['success_rate']:.3f})")
