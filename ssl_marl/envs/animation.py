"""Write rendered frames to an animated GIF or an MP4, atomically.

Split from :mod:`ssl_marl.envs.render` (drawing) because writing files is a separate
job with its own dependencies (imageio, imageio-ffmpeg), imported lazily.
"""

from __future__ import annotations

import math
import os
import tempfile
from pathlib import Path
from typing import Iterable

import numpy as np

__all__ = ["write_animation"]


def write_animation(frames: Iterable[np.ndarray] | list[np.ndarray], path: str | os.PathLike,
                    fps: int = 30) -> None:
    """Write RGB frames to ``path`` as an animated GIF (``.gif``) or an MP4 (``.mp4``).

    The file is written atomically (temp file in the same directory, then
    ``os.replace``).  GIF: Pillow merges consecutive identical frames (adding up
    their durations), so a still scene gives fewer frames than were passed.  MP4
    needs the ``imageio-ffmpeg`` package.
    """
    # imageio: the standard, well-maintained image/video IO library for numpy arrays
    # (GIF through Pillow, MP4 through imageio-ffmpeg); imported lazily so that
    # drawing does not depend on it.
    import imageio.v3 as iio

    frames = [np.asarray(f) for f in frames]
    if not frames:
        raise ValueError("write_animation: no frames given")
    shape = frames[0].shape
    for i, f in enumerate(frames):
        if f.ndim != 3 or f.shape[2] != 3 or f.shape != shape:
            raise ValueError(f"write_animation: frame {i} has shape {f.shape}; all frames must be "
                             f"(H, W, 3) with the same shape as frame 0 {shape}")
    if not (isinstance(fps, (int, float)) and math.isfinite(fps) and fps > 0):
        raise ValueError(f"write_animation: fps must be positive, got {fps!r}")
    frames = [np.ascontiguousarray(f, dtype=np.uint8) if f.dtype != np.uint8 else f for f in frames]

    path = Path(path)
    suffix = path.suffix.lower()
    if suffix not in (".gif", ".mp4"):
        raise ValueError(f"write_animation: unsupported suffix {path.suffix!r} for {path}; use .gif or .mp4")
    if suffix == ".mp4":
        try:
            import imageio_ffmpeg  # noqa: F401
        except ImportError:
            raise RuntimeError("write_animation: writing .mp4 needs the 'imageio-ffmpeg' package "
                               "(pip install imageio-ffmpeg); or write a .gif instead") from None
    directory = path.parent if str(path.parent) else Path(".")
    try:  # the one output rule (ssl_marl.io.prepare_output_file): missing parent folders are created
        directory.mkdir(parents=True, exist_ok=True)
        fd, tmp_name = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=f".tmp{suffix}", dir=directory)
    except OSError as exc:  # name the target, never the hidden temp file
        raise OSError(f"write_animation: cannot write {path} ({exc.strerror})") from None
    os.close(fd)
    try:
        if suffix == ".gif":
            iio.imwrite(tmp_name, np.stack(frames), extension=".gif", duration=1000.0 / fps, loop=0)
        else:
            h, w = shape[:2]
            if h % 2 or w % 2:  # yuv420p needs even sizes: pad by repeating the last row/column
                frames = [np.pad(f, ((0, h % 2), (0, w % 2), (0, 0)), mode="edge") for f in frames]
            iio.imwrite(tmp_name, np.stack(frames), extension=".mp4", plugin="FFMPEG", fps=fps,
                        codec="libx264", macro_block_size=1)
        mask = os.umask(0)  # mkstemp files are 0600: publish with the usual 0666 minus umask
        os.umask(mask)
        os.chmod(tmp_name, 0o666 & ~mask)
        os.replace(tmp_name, path)
    except BaseException:
        try:
            os.unlink(tmp_name)
        except OSError:
            pass
        raise
