"""One run's output folder, shared by both training loops (:mod:`train.offpolicy.loop`, :mod:`train.mappo.loop`).

Layout::

    OUT/config.json          the run config and seed (JSON, written atomically)
    OUT/<name>.csv           append-only logs, flushed per row (:class:`train.logs.CsvLog`)
    OUT/tb/                  the TensorBoard mirror when TensorBoard is installed
    OUT/checkpoint.pt        the resumable train state (torch.save of plain containers and
                             tensors, written atomically, read with weights_only=True)
    OUT/actors/actor-N.pt    actor snapshots (N: env samples or decisions), in the actor-file
                             format of :mod:`ssl_marl.skills.checkpoint`
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from ssl_marl.io import atomic_write_json
from ssl_marl.skills.checkpoint import atomic_torch_save, safe_torch_load

from train.logs import CsvLog, TensorBoardLog

CHECKPOINT = "checkpoint.pt"


def read_state(path: str | Path, fmt: str, what: str) -> dict[str, Any]:
    """A train state written by :meth:`RunFolder.save_checkpoint` (``weights_only=True``) whose
    ``format`` entry is ``fmt``; ValueError naming ``what`` otherwise."""
    state = safe_torch_load(path, what)
    if not isinstance(state, dict) or state.get("format") != fmt:
        raise ValueError(f"{path} is not a valid {what} (no {fmt!r} format tag)")
    return state


class RunFolder:
    """The files of one run under ``path`` (created when missing); see the module docstring."""

    def __init__(self, path: str | Path) -> None:
        self.path = Path(path)
        self.path.mkdir(parents=True, exist_ok=True)

    @property
    def checkpoint(self) -> Path:
        """``OUT/checkpoint.pt``."""
        return self.path / CHECKPOINT

    def write_config(self, config: Mapping[str, Any]) -> Path:
        """Write ``OUT/config.json`` atomically."""
        path = self.path / "config.json"
        atomic_write_json(path, dict(config))
        return path

    def csv_log(self, name: str, fields: list[str] | None = None) -> CsvLog:
        """The log ``OUT/<name>``; ``fields``: its columns (None: those of the first row)."""
        return CsvLog(self.path / name, fields)

    def tensorboard(self, purge_step: int | None = None) -> TensorBoardLog:
        """The TensorBoard mirror under ``OUT/tb`` (``purge_step``: on resume, the checkpoint's step)."""
        return TensorBoardLog(self.path / "tb", purge_step=purge_step)

    def save_checkpoint(self, state: Mapping[str, Any]) -> Path:
        """Write the train state to ``OUT/checkpoint.pt`` atomically."""
        return atomic_torch_save(dict(state), self.checkpoint)

    def read_checkpoint(self, fmt: str, what: str) -> dict[str, Any]:
        """The train state in ``OUT/checkpoint.pt`` (:func:`read_state`)."""
        return read_state(self.checkpoint, fmt, what)

    def actor_snapshot(self, step: int, digits: int = 0) -> Path:
        """``OUT/actors/actor-<step>.pt``, ``step`` zero-padded to ``digits``."""
        return self.path / "actors" / f"actor-{int(step):0{digits}d}.pt"
