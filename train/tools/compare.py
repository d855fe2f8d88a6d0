"""Compare training runs side by side, from their logs (never hand-typed numbers).

    python -m train.compare RUN [RUN ...] [--window 10000] [--upto N] [--target 0.99]

For each run folder (or ``results/training/<run>`` copy): its algorithm (from
``config.json``), the success rate and mean return of its training episodes (with
exploration noise) in windows of ``--window`` env samples (``progress.csv``), its
deterministic evaluations (``eval.csv``, the trainer's 10-episode checks on seed + 1000),
its validation selection (``selection.json`` from ``python -m train.select``) and the
first checkpoint whose validation success reaches ``--target`` ("samples to target") with the
trainer's wall clock at that checkpoint (``eval.csv``; demo burn-in included, checkpoint
selection not).
Prints markdown.
"""

from __future__ import annotations

import argparse
import csv
import json
from pathlib import Path
from typing import Any


def _csv(path: Path) -> list[dict[str, str]]:
    if not path.exists():
        return []
    with path.open(newline="") as f:
        return list(csv.DictReader(f))


def summarize(run: Path, window: int, upto: int | None, target: float) -> dict[str, Any]:
    cfg = json.loads((run / "config.json").read_text()) if (run / "config.json").exists() else {}
    progress, eval_rows = _csv(run / "progress.csv"), _csv(run / "eval.csv")
    train = [r for r in progress if r["phase"] == "train"]
    last = max((int(r["samples"]) for r in train), default=0)
    end = min(last, upto) if upto else last
    windows = []
    for lo in range(0, end, window):
        rows = [r for r in train if lo < int(r["samples"]) <= lo + window]
        succ = [int(r["success"]) for r in rows if r["success"] != ""]
        rets = [float(r["return"]) for r in rows]
        windows.append({"samples": min(lo + window, end), "episodes": len(rows),
                        "success": sum(succ) / len(succ) if succ else None,
                        "mean_return": sum(rets) / len(rets) if rets else None})
    evals = {int(r["samples"]): r for r in eval_rows if not upto or int(r["samples"]) <= upto}
    sel = json.loads((run / "selection.json").read_text()) if (run / "selection.json").exists() else None
    cands = sorted(sel["candidates"], key=lambda c: c["samples"]) if sel else []
    hit = next((c["samples"] for c in cands if c["success_rate"] >= target), None)
    return {"run": run.name, "algo": cfg.get("algo", "ddpg"), "seed": cfg.get("seed"), "windows": windows,
            "evals": evals, "selection": sel, "candidates": cands, "samples_to_target": hit,
            "wall_s_to_target": None if hit is None else _wall_at(eval_rows, progress, hit)}


def _wall_at(eval_rows: list[dict[str, str]], progress: list[dict[str, str]], samples: int) -> float | None:
    """The trainer's wall clock (s since its start, demo burn-in included) when it had
    ``samples`` env samples: the ``eval.csv`` row taken at that checkpoint, else the
    last ``progress.csv`` row at or before it (None without logs)."""
    for r in eval_rows:
        if int(r["samples"]) == samples and r.get("wall_time"):
            return float(r["wall_time"])
    rows = [r for r in progress if int(r["samples"]) <= samples and r.get("wall_time")]
    return float(rows[-1]["wall_time"]) if rows else None


def _fmt(v: float | None, spec: str) -> str:
    return "-" if v is None else format(v, spec)


def markdown(runs: list[dict[str, Any]], target: float) -> str:
    out = ["| run | algo | samples (window end) | training episodes | training success | mean training return |",
           "|---|---|---|---|---|---|"]
    for r in runs:
        for w in r["windows"]:
            out.append(f"| `{r['run']}` | {r['algo']} | {w['samples']:,} | {w['episodes']} | "
                       f"{_fmt(w['success'], '.3f')} | {_fmt(w['mean_return'], '.1f')} |")
    out += ["", "| run | algo | deterministic evaluations (samples: success of 10 episodes, seed + 1000) |", "|---|---|---|"]
    for r in runs:
        evs = ", ".join(f"{s // 1000}k: {_fmt(None if e['success_rate'] == '' else float(e['success_rate']), '.1f')}"
                        for s, e in sorted(r["evals"].items()))
        out.append(f"| `{r['run']}` | {r['algo']} | {evs or '-'} |")
    out += ["", f"| run | algo | validation (seed x episodes) | success per checkpoint | samples to {target} "
                f"| trainer wall time to it |", "|---|---|---|---|---|---|"]
    for r in runs:
        sel = r["selection"]
        if sel is None:
            out.append(f"| `{r['run']}` | {r['algo']} | - | not selected yet | - | - |")
            continue
        per = ", ".join(f"{c['samples'] // 1000}k: {c['success_rate']:.3f}" for c in r["candidates"])
        hit = f"{r['samples_to_target']:,}" if r["samples_to_target"] else \
            f"not reached (checkpoints up to {r['candidates'][-1]['samples']:,})"
        wall = "-" if r["wall_s_to_target"] is None else f"{r['wall_s_to_target']:,.0f} s"
        out.append(f"| `{r['run']}` | {r['algo']} | {sel['validation_seed']} x {sel['episodes']} | {per} | {hit} "
                   f"| {wall} |")
    return "\n".join(out)


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(prog="python -m train.compare", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("runs", nargs="+", type=Path, help="run folders (progress.csv, eval.csv, selection.json)")
    p.add_argument("--window", type=int, default=10_000, help="env samples per training-success window")
    p.add_argument("--upto", type=int, default=None, help="only up to this many env samples")
    p.add_argument("--target", type=float, default=0.99, help="validation success that counts as reached")
    a = p.parse_args(argv)
    print(markdown([summarize(r, a.window, a.upto, a.target) for r in a.runs], a.target))
