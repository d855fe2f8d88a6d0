"""Learning curves of MAPPO runs, drawn from their CSV logs.

``python -m train.mappo_report RUN_DIR [RUN_DIR ...] [--out FIG.png]``: with one folder, writes
``RUN_DIR/learning_curve.png``; with several (e.g. the seeds of one task) and ``--out``, one
figure with a line per run. Panels against training decisions: the training episodes' score and team return (rolling
means over rollouts), the greedy validation score and return, the policy entropy, decisions/s.
Also prints per run: decisions, wall time, mean decisions/s and agent-steps/s, best validation.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import Any

import numpy as np

from ssl_marl.io import atomic_savefig

from train.tools.plots import read_csv, rolling_mean


def run_summary(run_dir: str | Path) -> dict[str, Any]:
    """Counters, throughput and the best validation of one run folder."""
    run_dir = Path(run_dir)
    p = read_csv(run_dir / "progress.csv")
    v = read_csv(run_dir / "val.csv") if (run_dir / "val.csv").exists() else {}
    out: dict[str, Any] = {"run": str(run_dir)}
    if p:
        wall = float(p["wall_time"][-1])
        out.update(decisions=int(p["decisions"][-1]), agent_steps=int(p["agent_steps"][-1]),
                   episodes=int(p["episodes"][-1]), wall_time_s=round(wall, 1),
                   decisions_per_s=round(float(p["decisions"][-1]) / wall, 1),
                   agent_steps_per_s=round(float(p["agent_steps"][-1]) / wall, 1))
    if v and len(v.get("val_score", [])):
        best = int(np.nanargmax(v["val_score"]))
        out.update(best_val_score=float(v["val_score"][best]), best_val_decisions=int(v["decisions"][best]),
                   best_actor=str(v["actor"][best]), last_val_score=float(v["val_score"][-1]))
    return out


def plot_mappo_runs(run_dirs: list[str | Path], out: str | Path, window: int = 20, title: str | None = None) -> Path:
    """One figure, a line per run (score, validation score, entropy vs decisions)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axs = plt.subplots(2, 3, figsize=(14, 7))
    axes = axs.flatten()
    for run in run_dirs:
        run = Path(run)
        p = read_csv(run / "progress.csv")
        if not p:
            continue
        label = run.name
        x = p["decisions"]
        line = axes[0].plot(x, rolling_mean(p["mean_score"], window), label=label)[0]
        c = line.get_color()
        axes[1].plot(x, rolling_mean(p["mean_return"], window), color=c, label=label)
        if (run / "val.csv").exists():
            v = read_csv(run / "val.csv")
            if v:
                axes[2].plot(v["decisions"], v["val_score"], "o-", ms=3, color=c, label=label)
                axes[3].plot(v["decisions"], v["val_return"], "o-", ms=3, color=c, label=label)
        axes[4].plot(x, p["entropy"], color=c, label=label)
        axes[5].plot(x, p["decisions_per_s"], color=c, label=label)
    titles = ("training episodes' score (rolling mean)", "training episodes' team return (rolling mean)",
              "greedy validation score", "greedy validation return", "policy entropy", "decisions / s")
    for ax, t in zip(axes, titles):
        ax.set_title(t, fontsize=10)
        ax.set_xlabel("training decisions")
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=8)
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    out = Path(out)
    atomic_savefig(fig, out, dpi=110)
    plt.close(fig)
    return out


def plot_mappo_run(run_dir: str | Path) -> Path:
    return plot_mappo_runs([run_dir], Path(run_dir) / "learning_curve.png")


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m train.mappo_report", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("runs", nargs="+", type=Path, help="MAPPO run folders")
    p.add_argument("--out", type=Path, default=None, help="one combined figure (default: a figure per run folder)")
    p.add_argument("--title", default=None, help="figure title")
    args = p.parse_args(argv)
    if args.out is not None:
        print(plot_mappo_runs(args.runs, args.out, title=args.title))
    else:
        for r in args.runs:
            print(plot_mappo_run(r))
    for r in args.runs:
        print(json.dumps(run_summary(r)))
    return 0
