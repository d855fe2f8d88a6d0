"""Run logs: ``progress.csv`` (one row per episode), ``eval.csv`` and the optional TensorBoard mirror.

CSV files are append-only and flushed per row, so a crashed run keeps its log; on
resume they are cut back to the rows the checkpoint counted (:meth:`CsvLog.truncate`).
TensorBoard (``pip install -e ".[tb]"``) gets the same scalars under ``OUT/tb/``:
``train/*`` and ``demo/*`` per episode (return, length, success, ``r_<term>`` reward
terms), ``loss/<name>`` per loss read-out and ``eval/*`` per evaluation (mean and std
return, mean length, success rate). The step axis is stored transitions (demonstrations
plus env samples), as in the learning-curve plots: unique and increasing across demo
burn-in and training, so a resumed run can purge what a crash logged after its checkpoint.
"""

from __future__ import annotations

import csv
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from ssl_marl.io import atomic_write_bytes

EVAL_FIELDS = ["samples", "transitions", "updates", "mean_return", "std_return", "mean_length", "success_rate",
               "wall_time"]


def progress_fields(loss_names: Sequence[str], reward_terms: Sequence[str]) -> list[str]:
    """``progress.csv`` columns: counters, episode figures, one ``<name>_loss`` per agent loss, reward terms."""
    return (["phase", "samples", "transitions", "episode", "return", "length", "success"]
            + [f"{n}_loss" for n in loss_names] + ["updates", "wall_time"] + [f"r_{k}" for k in sorted(reward_terms)])


class CsvLog:
    """Append-only CSV, flushed per row. Columns fixed by the existing header or the first row."""

    def __init__(self, path: Path, fields: list[str] | None = None) -> None:
        self.path, self.fields, self.rows, self._initial_fields = path, fields, 0, fields
        if path.exists() and path.stat().st_size > 0:
            with path.open(newline="") as f:
                reader = csv.reader(f)
                self.fields = next(reader)
                self.rows = sum(1 for _ in reader)
        self._f = None

    def write(self, row: Mapping[str, Any]) -> None:
        if self._f is None:
            new = self.rows == 0
            if self.fields is None:
                self.fields = list(row)
            self._f = self.path.open("a" if not new else "w", newline="")
            self._w = csv.DictWriter(self._f, self.fields, extrasaction="ignore")
            if new:
                self._w.writeheader()
        self._w.writerow({k: ("" if v is None else v) for k, v in row.items()})
        self._f.flush()
        self.rows += 1

    def truncate(self, rows: int) -> None:
        """Keep the header and the first ``rows`` rows (drop what was logged after a checkpoint)."""
        self.close()
        if not self.path.exists():
            return
        lines = self.path.read_text().splitlines(keepends=True)
        atomic_write_bytes(self.path, "".join(lines[: rows + 1]).encode())
        self.rows = min(rows, max(len(lines) - 1, 0))

    def clear(self) -> None:
        """Start the file afresh (a new run in a folder left by a run that never checkpointed)."""
        self.close()
        self.path.unlink(missing_ok=True)
        self.fields, self.rows = self._initial_fields, 0

    def close(self) -> None:
        if self._f is not None:
            self._f.close()
            self._f = None


class TensorBoardLog:
    """Scalars to ``logdir`` when TensorBoard is installed (the ``tb`` extra); a no-op otherwise.

    ``purge_step``: on resume, the checkpoint's step, so events a crashed run logged after
    its last checkpoint are dropped (they are logged again)."""

    def __init__(self, logdir: Path, purge_step: int | None = None) -> None:
        self.writer: Any = None
        try:
            from torch.utils.tensorboard import SummaryWriter
        except ImportError:  # tensorboard not installed: optional
            return
        self.writer = SummaryWriter(str(logdir), purge_step=purge_step)

    @property
    def enabled(self) -> bool:
        return self.writer is not None

    def scalars(self, prefix: str, values: Mapping[str, Any], step: int) -> None:
        """``prefix/key`` for each numeric value (None and non-numbers are skipped)."""
        if self.writer is None:
            return
        for k, v in values.items():
            if isinstance(v, (int, float)):  # bools count as 0 / 1
                self.writer.add_scalar(f"{prefix}/{k}", float(v), step)

    def close(self) -> None:
        if self.writer is not None:
            self.writer.close()
            self.writer = None
