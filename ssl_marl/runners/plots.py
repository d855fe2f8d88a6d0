"""One plot writer for the runners: the time-to-success histogram of an evaluation.

Drawn on a private Agg canvas (no global matplotlib backend change, safe in worker
processes and threads) and written atomically (:func:`ssl_marl.io.atomic_savefig`).
"""

from __future__ import annotations

import os

import numpy as np

from ..io import atomic_savefig


def write_time_histogram(times: list[float], path: str | os.PathLike, title: str, max_time_s: float | None = None,
                         xlabel: str = "time to success (s)", bin_s: float = 0.5, dpi: int = 100) -> None:
    """Histogram of the successful episodes' times (s), written atomically to ``path``.

    Args:
        times: success times (s); may be empty (an empty plot is written).
        title: plot title (one line, ~80 characters).
        max_time_s: the episode limit (s): fixes the x axis to [0, max_time_s];
            None: up to the largest time.
        xlabel: x-axis label.
        bin_s: bin width (s).
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from matplotlib.ticker import MaxNLocator

    hi = max_time_s if max_time_s is not None else max([bin_s, *times])
    fig = Figure(figsize=(6.4, 4.0), dpi=dpi)
    FigureCanvasAgg(fig)
    ax = fig.add_subplot(1, 1, 1)
    bins = np.arange(0.0, hi + bin_s, bin_s)
    if times:
        ax.hist(times, bins=bins, color="#3070b0", edgecolor="white")
    ax.set_xlabel(xlabel)
    ax.set_ylabel("episodes")
    ax.set_xlim(0.0, hi)
    ax.yaxis.set_major_locator(MaxNLocator(integer=True))
    ax.set_title(title, fontsize=10)
    fig.tight_layout()
    atomic_savefig(fig, path)
