"""Shared helpers of the runners, the CLI and the trainer.

* Files: atomic writes (bytes, JSON, matplotlib figures: a temporary file in the
  same folder, then a rename) and the one rule for output paths
  (:func:`prepare_output_file`, :func:`prepare_output_dir`), checked before long work.
* Per-episode seeds that do not depend on the number of workers (the statistics of
  evaluations are :mod:`ssl_marl.runners.statistics`).
"""

from __future__ import annotations

import json
import os
import tempfile
from pathlib import Path
from typing import Any

import numpy as np


def atomic_write_bytes(path: str | os.PathLike, data: bytes) -> None:
    """Write ``data`` to ``path`` atomically (temp file in the same directory, then rename)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
            fh.flush()
            os.fsync(fh.fileno())
        mask = os.umask(0)  # mkstemp makes 0600 files: give the usual 0666 minus umask
        os.umask(mask)
        os.chmod(tmp, 0o666 & ~mask)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def prepare_output_file(path: str | os.PathLike, suffixes: tuple[str, ...] | None = None,
                        what: str = "output file") -> Path:
    """Check, before any long work, that ``path`` can be written as a file; return it as a Path.

    The one rule every ``ssl-marl`` output follows: missing parent folders are
    created; a path that is a folder, a parent that is a file, a folder without
    write permission or (when ``suffixes`` is given, e.g. ``(".gif", ".mp4")``) a
    wrong suffix raise ValueError naming ``path`` and what to do.
    """
    path = Path(path)
    if suffixes is not None and path.suffix.lower() not in suffixes:
        raise ValueError(f"{what} {path}: unsupported suffix {path.suffix or '(none)'!r}; use "
                         + " or ".join(suffixes))
    if path.is_dir():
        raise ValueError(f"{what} {path} is a folder; give a file path")
    _make_folder(path.parent if str(path.parent) else Path("."), what, path)
    if path.exists() and not os.access(path, os.W_OK):
        raise ValueError(f"{what} {path} exists and is not writable")
    return path


def prepare_output_dir(path: str | os.PathLike, what: str = "output folder") -> Path:
    """Like :func:`prepare_output_file` for a folder: create it (and its parents) or
    raise ValueError naming ``path`` if that is impossible or it is not writable."""
    path = Path(path)
    if path.exists() and not path.is_dir():
        raise ValueError(f"{what} {path} is a file; give a folder path")
    _make_folder(path, what, path)
    return path


def _make_folder(folder: Path, what: str, target: Path) -> None:
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except FileExistsError:
        raise ValueError(f"{what} {target}: cannot create folder {folder} (a file of that name is in the way)") from None
    except OSError as exc:
        raise ValueError(f"{what} {target}: cannot create folder {folder} ({exc.strerror})") from None
    if not os.access(folder, os.W_OK | os.X_OK):
        raise ValueError(f"{what} {target}: folder {folder} is not writable")


def atomic_write_json(path: str | os.PathLike, obj: Any) -> None:
    """Write ``obj`` as indented JSON to ``path`` atomically (numpy values and paths become JSON values)."""
    atomic_write_bytes(path, (json.dumps(obj, indent=2, sort_keys=False, default=_json_default) + "\n").encode())


def _json_default(o: Any) -> Any:
    if isinstance(o, np.generic):
        return o.item()
    if isinstance(o, np.ndarray):
        return o.tolist()
    if isinstance(o, Path):
        return str(o)
    raise TypeError(f"not JSON serialisable: {type(o).__name__}")


def atomic_savefig(fig, path: str | os.PathLike, **kwargs: Any) -> None:
    """Save a matplotlib figure atomically (format from the suffix)."""
    import io

    path = Path(path)
    buf = io.BytesIO()
    fig.savefig(buf, format=path.suffix.lstrip(".") or "png", **kwargs)
    atomic_write_bytes(path, buf.getvalue())


def episode_seed(seed: int, index: int) -> int:
    """Independent per-episode seed, a pure function of (seed, episode index), so an
    evaluation gives the same episodes whatever the number of workers."""
    return int(np.random.SeedSequence([int(seed), int(index)]).generate_state(1)[0])
