"""Write rendered frames to an animated GIF or an MP4, atomically: the one video sink.

Drawing is :mod:`ssl_marl.envs.render`'s job; writing files is this module's, with its
own dependencies (Pillow, imageio-ffmpeg), imported lazily.

One video sink for every runner: frames go to disk as they come (constant memory).

:class:`VideoSink` takes RGB frames (H, W, 3) one at a time and writes them to a
``.gif`` or ``.mp4`` file while the run goes on, so memory does not grow with the
length of the video (a 60 s match at 10 frames/s is 600 frames of ~0.5 MB each;
holding them all costs ~1.3 GB of RSS, see docs/BENCHMARKS.md).

* GIF: written with Pillow's GIF encoder one frame at a time
  (``PIL.GifImagePlugin.getheader`` / ``getdata``, Pillow's documented helpers for
  writing animations piece by piece). Like Pillow's own ``save_all``, a frame only
  stores the rectangle that changed since the previous frame (unchanged pixels
  inside it are transparent, so the previous frame shows through) and a frame
  identical to the previous one extends that frame's duration instead of being
  stored again. Frame 0 gets a 255-colour median-cut palette, the file's global
  one; a later rectangle is mapped to that palette's nearest colours (about 20x
  faster than a median cut per frame) unless a sampled pixel then lies more than
  :data:`PALETTE_TOLERANCE` off in a channel (a colour frame 0 lacked), when it gets
  its own adaptive palette. Only the previous frame and one pending frame are held
  in memory.
* MP4: frames are piped to ffmpeg (``imageio-ffmpeg``, libx264, yuv420p; odd sizes
  are padded by repeating the last row / column).

Publication is atomic: the video is written to a temporary file next to ``path``
and moved into place by :meth:`VideoSink.close` (``ok=True``); ``close(ok=False)``
(an interrupted run) deletes it and leaves any earlier file at ``path`` untouched.
"""

from __future__ import annotations

import math
import os
import tempfile
from pathlib import Path
from typing import IO, Any, Iterable

import numpy as np

__all__ = ["VideoSink", "VIDEO_SUFFIXES", "write_animation"]


VIDEO_SUFFIXES = (".gif", ".mp4")
TRANSPARENT = 255  # GIF: palette index of "unchanged since the previous frame"
#: GIF: largest error (0-255, any channel) of a sampled pixel mapped to frame 0's palette
#: before a changed rectangle gets its own palette
PALETTE_TOLERANCE = 48
_SAMPLE = 3  # GIF: the tolerance is checked on every 3rd pixel of every 3rd row


class VideoSink:
    """Stream RGB frames to a GIF or MP4 at ``path``.

    Args:
        path: output file; its suffix (``.gif`` / ``.mp4``) picks the format.
        fps: frames per second of the video (positive).

    Use as a context manager (``with VideoSink(p, 10) as sink: sink.add(frame)``;
    an exception inside the block discards the file) or call :meth:`close`; a sink
    that is garbage-collected unclosed discards its file too.
    """

    def __init__(self, path: str | os.PathLike, fps: float) -> None:
        self.path = Path(path)
        self.suffix = self.path.suffix.lower()
        if self.suffix not in VIDEO_SUFFIXES:
            raise ValueError(f"render: unsupported suffix {self.path.suffix!r} for {self.path}; use .gif or .mp4")
        if not (isinstance(fps, (int, float)) and math.isfinite(fps) and fps > 0):
            raise ValueError(f"render: fps must be a positive number, got {fps!r}")
        self.fps = float(fps)
        self.frames_added = 0
        self._tmp: str | None = None
        self._shape: tuple[int, ...] | None = None
        self._ffmpeg = None  # MP4: the imageio-ffmpeg generator
        self._fp: IO[bytes] | None = None  # GIF: the open temporary file
        self._prev: np.ndarray | None = None  # GIF: previous RGB frame
        self._palette: Any = None  # GIF: frame 0's P image (its palette is the global one)
        self._palette_rgb: np.ndarray | None = None  # GIF: (256, 3) uint8, that palette
        self._pending: list[Any] | None = None  # GIF: [P image, offset, duration ms, first?]

    # ------------------------------------------------------------------ API
    def add(self, frame: np.ndarray) -> None:
        """Append one RGB frame (H, W, 3); every frame must have frame 0's shape."""
        frame = np.asarray(frame)
        if frame.ndim != 3 or frame.shape[2] != 3:
            raise ValueError(f"render: frame {self.frames_added} must be (H, W, 3) RGB, got shape {frame.shape}")
        if self._shape is None:
            self._shape = frame.shape
            self._open()
        elif frame.shape != self._shape:
            raise ValueError(f"render: frame {self.frames_added} has shape {frame.shape}, frame 0 had {self._shape}")
        frame = np.ascontiguousarray(frame, dtype=np.uint8)
        if self.suffix == ".gif":
            self._add_gif(frame)
        else:
            self._add_mp4(frame)
        self.frames_added += 1

    def close(self, ok: bool = True) -> None:
        """Finish the file and publish it at ``path`` (``ok``), or discard it. Idempotent."""
        if self._tmp is None:
            return
        try:
            if self.suffix == ".gif" and self._fp is not None:
                if ok:
                    self._flush_pending()
                    self._fp.write(b";")  # GIF trailer
                self._fp.close()
                self._fp = None
            if self._ffmpeg is not None:
                self._ffmpeg.close()
                self._ffmpeg = None
            if ok:
                mask = os.umask(0)  # mkstemp files are 0600: publish with the usual 0666 minus umask
                os.umask(mask)
                os.chmod(self._tmp, 0o666 & ~mask)
                os.replace(self._tmp, self.path)
                self._tmp = None
        finally:
            if self._tmp is not None:
                try:
                    os.unlink(self._tmp)
                except OSError:
                    pass
                self._tmp = None
            self._prev = self._pending = None

    def __del__(self) -> None:  # never closed (an exception unwound the caller): discard
        try:
            self.close(ok=False)
        except Exception:
            pass

    def __enter__(self) -> "VideoSink":
        return self

    def __exit__(self, exc_type, exc, tb) -> None:
        self.close(ok=exc_type is None)

    # -------------------------------------------------------------- helpers
    def _open(self) -> None:
        directory = self.path.parent if str(self.path.parent) else Path(".")
        try:  # the one output rule (ssl_marl.io.prepare_output_file): missing parent folders are created
            directory.mkdir(parents=True, exist_ok=True)
            fd, self._tmp = tempfile.mkstemp(prefix=f".{self.path.stem}.", suffix=f".tmp{self.suffix}",
                                             dir=directory)
        except OSError as exc:  # name the target, never the hidden temp file
            raise OSError(f"render: cannot write {self.path} ({exc.strerror})") from None
        if self.suffix == ".gif":
            self._fp = os.fdopen(fd, "wb")
            return
        os.close(fd)
        try:
            import imageio_ffmpeg
        except ImportError:
            raise RuntimeError("render: writing .mp4 needs the 'imageio-ffmpeg' package "
                               "(pip install imageio-ffmpeg); or write a .gif instead") from None
        h, w = self._shape[:2]
        self._ffmpeg = imageio_ffmpeg.write_frames(self._tmp, (w + w % 2, h + h % 2), fps=self.fps, codec="libx264",
                                                   macro_block_size=1, quality=6)
        self._ffmpeg.send(None)

    def _add_mp4(self, frame: np.ndarray) -> None:
        h, w = frame.shape[:2]
        if h % 2 or w % 2:  # yuv420p needs even sizes
            frame = np.ascontiguousarray(np.pad(frame, ((0, h % 2), (0, w % 2), (0, 0)), mode="edge"))
        self._ffmpeg.send(frame.tobytes())

    def _add_gif(self, frame: np.ndarray) -> None:
        from PIL import Image

        duration_ms = 1000.0 / self.fps
        if self._prev is None:
            first = Image.fromarray(frame).quantize(255)
            pal = (first.getpalette()[:3 * 255] + [0, 0, 0] * 255)[:3 * 255]
            pal += pal[:3]  # entry 255 (transparent in later frames) repeats entry 0's colour
            first.putpalette(pal)
            self._palette = first
            self._palette_rgb = np.asarray(pal, np.uint8).reshape(256, 3)
            self._pending = [first, (0, 0), duration_ms, True, False]
            self._prev = frame
            return
        diff = frame != self._prev
        changed = diff[..., 0] | diff[..., 1] | diff[..., 2]  # 10x faster than .any(axis=2)
        if not changed.any():  # identical: show the pending frame longer
            self._pending[2] += duration_ms
            return
        rows = np.flatnonzero(changed.any(axis=1))
        cols = np.flatnonzero(changed.any(axis=0))
        y0, y1, x0, x1 = int(rows[0]), int(rows[-1]) + 1, int(cols[0]), int(cols[-1]) + 1
        self._flush_pending()
        rect = np.ascontiguousarray(frame[y0:y1, x0:x1])
        # the changed rectangle in 255 colours; its unchanged pixels become the
        # transparent index 255 (the previous frame shows through: smaller files)
        mapped = Image.fromarray(rect).quantize(palette=self._palette, dither=Image.Dither.NONE)
        idx = np.asarray(mapped).copy()
        idx[idx == TRANSPARENT] = 0  # the same colour as entry 0
        err = np.abs(self._palette_rgb[idx[::_SAMPLE, ::_SAMPLE]].astype(np.int16) - rect[::_SAMPLE, ::_SAMPLE])
        own = bool(err.max() > PALETTE_TOLERANCE)
        pal = self._palette_rgb.ravel().tolist()
        if own:  # a colour frame 0's palette lacks: this rectangle's own palette
            crop = Image.fromarray(rect).quantize(255)
            idx = np.asarray(crop).copy()
            pal = crop.getpalette()[:3 * 255] + [0, 0, 0]
        idx[~changed[y0:y1, x0:x1]] = TRANSPARENT
        crop = Image.fromarray(idx, mode="P")
        crop.putpalette(pal)
        self._pending = [crop, (x0, y0), duration_ms, False, own]
        self._prev = frame

    def _flush_pending(self) -> None:
        if self._pending is None:
            return
        from PIL import GifImagePlugin

        im, offset, duration_ms, first, own_palette = self._pending
        self._pending = None
        if first:  # global header: canvas size, frame 0's palette, loop forever
            header, _ = GifImagePlugin.getheader(im, info={"loop": 0, "duration": duration_ms})
            for chunk in header:
                self._fp.write(chunk)
            params: dict[str, Any] = {"duration": duration_ms}
        else:  # a changed rectangle over the previous frame (own palette or the global one)
            params = {"duration": duration_ms, "include_color_table": own_palette, "disposal": 1,
                      "transparency": TRANSPARENT}
        for chunk in GifImagePlugin.getdata(im, offset, **params):
            self._fp.write(chunk)


def write_animation(frames: Iterable[np.ndarray] | list[np.ndarray], path: str | os.PathLike,
                    fps: int = 30) -> None:
    """Write RGB frames to ``path`` as an animated GIF (``.gif``) or an MP4 (``.mp4``)
    through :class:`VideoSink` (so the file is encoded exactly as a streamed video and
    published atomically). GIF: a frame identical to the previous one extends its
    duration, so a still scene gives fewer frames than were passed. MP4 needs the
    ``imageio-ffmpeg`` package.
    """
    frames = [np.asarray(f) for f in frames]
    if not frames:
        raise ValueError("write_animation: no frames given")
    shape = frames[0].shape
    for i, f in enumerate(frames):
        if f.ndim != 3 or f.shape[2] != 3 or f.shape != shape:
            raise ValueError(f"write_animation: frame {i} has shape {f.shape}; all frames must be "
                             f"(H, W, 3) with the same shape as frame 0 {shape}")
    with VideoSink(path, fps) as sink:
        for f in frames:
            sink.add(f)
