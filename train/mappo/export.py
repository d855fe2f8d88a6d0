"""Select and ship a MAPPO decision actor: ``python -m train.mappo_export RUN_DIR [RUN_DIR ...] --out PATH``.

Model selection uses only the runs' greedy *validation* results (``val.csv``: seeds
``val_seed + i``, 45000 for keepaway, 46000 for attack-3v2 -- never the evaluation seeds
40000 / 41000): the snapshot ``actors/actor-<decisions>.pt`` with the highest validation score
over all given runs (ties: the earlier run, then fewer decisions). It is copied to ``--out``
with a ``selection`` metadata entry (the candidates' scores), a decision actor file
(:mod:`ssl_marl.skills.checkpoint`) as :func:`ssl_marl.decisions.learned.load_decision_actor` reads.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import Any

from ssl_marl.skills.checkpoint import read_actor_file, save_actor_file

from train.tools.plots import read_csv


def select_actor(run_dirs: list[Path]) -> tuple[Path, list[dict[str, Any]]]:
    """The best validated snapshot over ``run_dirs`` and every candidate (run, decisions, score)."""
    cands: list[dict[str, Any]] = []
    for run in run_dirs:
        val = run / "val.csv"
        if not val.exists():
            raise FileNotFoundError(f"{val} not found: {run} has no validation yet")
        v = read_csv(val)
        for d, s, a in zip(v["decisions"], v["val_score"], v["actor"]):
            if (run / str(a)).is_file():
                cands.append({"run": str(run), "decisions": int(d), "val_score": float(s), "actor": str(run / str(a))})
    if not cands:
        raise ValueError(f"no validated actor snapshot in {[str(r) for r in run_dirs]}")
    best = max(cands, key=lambda c: (c["val_score"], -run_dirs.index(Path(c["run"])), -c["decisions"]))
    return Path(best["actor"]), cands


def export(run_dirs: list[Path], out: Path, note: str = "") -> dict[str, Any]:
    path, cands = select_actor(run_dirs)
    state, data = read_actor_file(path, "decision")
    data["selection"] = {"rule": "max greedy validation score", "chosen": str(path), "note": note,
                         "candidates": [{k: c[k] for k in ("run", "decisions", "val_score")} for c in cands]}
    out.parent.mkdir(parents=True, exist_ok=True)
    save_actor_file(out, "decision", state, data)
    return {"out": str(out), "chosen": str(path), "val_score": data.get("val_score"),
            "val_seed": data.get("val_seed"), "seed": data.get("seed"), "decisions": data.get("decisions")}


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m train.mappo_export", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("runs", nargs="+", type=Path, help="MAPPO run folders (e.g. the seeds of one task)")
    p.add_argument("--out", type=Path, required=True, help="actor file to write (e.g. ssl_marl/decisions/pretrained/keepaway.pt)")
    p.add_argument("--note", default="", help="free text stored with the selection (e.g. 'partial run')")
    args = p.parse_args(argv)
    print(json.dumps(export(list(args.runs), args.out, args.note)))
    return 0
