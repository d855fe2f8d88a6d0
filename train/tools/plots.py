"""Learning-curve PNGs from a run's CSV logs (like the paper's Figs. 3 and 6).

``python -m train.plots RUN_DIR [RUN_DIR ...]`` writes ``RUN_DIR/learning_curve.png``:
episode return, success rate and episode length against transitions stored
(demonstrations first, shaded, then the learner's own samples), with a rolling
mean, and the deterministic evaluations from ``eval.csv`` when present.
"""

from __future__ import annotations

import argparse
import csv
from pathlib import Path

import numpy as np

from ssl_marl.io import atomic_savefig


def read_csv(path: str | Path) -> dict[str, np.ndarray]:
    """Columns of a CSV as arrays (numeric where every non-empty cell parses; blanks -> nan)."""
    with Path(path).open(newline="") as f:
        rows = list(csv.DictReader(f))
    cols: dict[str, np.ndarray] = {}
    for key in (rows[0].keys() if rows else []):
        vals = [r[key] for r in rows]
        try:
            cols[key] = np.array([float(v) if v != "" else np.nan for v in vals])
        except ValueError:
            cols[key] = np.array(vals)
    return cols


def rolling_mean(x: np.ndarray, window: int) -> np.ndarray:
    """Trailing mean over up to ``window`` points, ignoring nans."""
    out = np.full(len(x), np.nan)
    for i in range(len(x)):
        seg = x[max(0, i - window + 1): i + 1]
        seg = seg[~np.isnan(seg)]
        if len(seg):
            out[i] = seg.mean()
    return out


def plot_run(run_dir: str | Path, out: str | Path | None = None, window: int = 50) -> Path:
    """Draw ``learning_curve.png`` for one run folder; return its path."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    run_dir = Path(run_dir)
    prog = read_csv(run_dir / "progress.csv")
    if not prog:
        raise ValueError(f"{run_dir / 'progress.csv'} has no episodes yet")
    ev = read_csv(run_dir / "eval.csv") if (run_dir / "eval.csv").exists() else {}
    x = prog["transitions"]
    demo = prog["phase"] == "demo"
    panels = [("return", "episode return")]
    if "success" in prog and not np.all(np.isnan(prog["success"])):
        panels.append(("success", "success rate"))
    panels.append(("length", "episode length (steps)"))
    fig, axes = plt.subplots(len(panels), 1, figsize=(8, 2.6 * len(panels)), sharex=True)
    axes = np.atleast_1d(axes)
    for ax, (key, label) in zip(axes, panels):
        y = prog[key]
        ax.plot(x, y, ".", ms=2, alpha=0.25, color="tab:blue")
        for phase, color in (("demo", "0.35"), ("train", "tab:blue")):  # separate means: no blur at the seam
            m = prog["phase"] == phase
            if m.any():
                ax.plot(x[m], rolling_mean(y[m], window), color=color, lw=1.5,
                        label=f"{'demonstrations' if phase == 'demo' else 'training'} (mean of {window})")
        if key == "return" and "mean_return" in ev:
            ax.plot(ev["transitions"], ev["mean_return"], "o-", color="tab:red", ms=3, label="evaluation")
        if key == "success" and "success_rate" in ev and not np.all(np.isnan(ev["success_rate"])):
            ax.plot(ev["transitions"], ev["success_rate"], "o-", color="tab:red", ms=3, label="evaluation")
        if demo.any():
            ax.axvspan(x[demo].min() if len(x[demo]) else 0, x[demo].max(), color="0.85", zorder=0,
                       label="demonstration burn-in")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    axes[0].legend(loc="best", fontsize=8)
    axes[-1].set_xlabel("transitions stored (demonstrations + environment samples)")
    fig.suptitle(run_dir.name)
    fig.tight_layout()
    out = Path(out) if out is not None else run_dir / "learning_curve.png"
    atomic_savefig(fig, out, dpi=110)
    plt.close(fig)
    return out


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m train.plots", description=__doc__)
    p.add_argument("runs", nargs="+", type=Path)
    p.add_argument("--window", type=int, default=50, help="rolling-mean window (episodes)")
    args = p.parse_args(argv)
    for run in args.runs:
        print(plot_run(run, window=args.window))
    return 0
