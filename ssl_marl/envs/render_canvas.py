"""pygame for off-screen drawing, frames out of surfaces, and the field-to-pixel mapping.

Headless operation: drawing never touches the SDL video subsystem (it only needs
``pygame.Surface``, ``pygame.draw`` and ``pygame.font``), so the off-screen path
works without a display. Before ``pygame`` is imported here, ``SDL_VIDEODRIVER``
defaults to ``"dummy"`` *only* when there is no sign of a display (no ``DISPLAY`` /
``WAYLAND_DISPLAY`` on Linux), so that a window (:mod:`ssl_marl.envs.window`) in a
desktop session is still a real one. The other render modules import ``pygame``
from this module, so these defaults are always set first.

Screen mapping (:class:`PixelMap`): field-frame +x (the goal blue attacks) points
right, +y points up; pixel index i is centred on continuous coordinate i.
"""

from __future__ import annotations

import math
import os
import sys
from dataclasses import dataclass

import numpy as np

from .render_style import COORD_LIMIT

os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")
if sys.platform.startswith("linux") and not (os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY")):
    # Off-screen path: no display server -> make any (accidental) video init headless.
    os.environ.setdefault("SDL_VIDEODRIVER", "dummy")

import pygame  # noqa: E402  (pygame-ce)

RGB24_MASKS = (0x0000FF, 0x00FF00, 0xFF0000, 0)


def new_surface(size: tuple[int, int], rgb24: bool) -> pygame.Surface:
    """An off-screen surface of ``size`` (width, height) px; 24-bit R-lowest when ``rgb24``."""
    if rgb24:
        return pygame.Surface(size, 0, 24, RGB24_MASKS)
    return pygame.Surface(size)


def rgb24_layout_ok() -> bool:
    """True if a 24-bit surface with R-lowest masks stores bytes as R, G, B (so frames can
    be copied straight out of the pixel buffer, ~10x faster than image.tobytes)."""
    try:
        s = pygame.Surface((2, 1), 0, 24, RGB24_MASKS)
        s.fill((1, 2, 3))
        raw = bytes(s.get_buffer().raw)
        return raw[:6] == bytes((1, 2, 3, 1, 2, 3))
    except Exception:
        return False


def surface_to_array(surf: pygame.Surface, fast_rgb: bool) -> np.ndarray:
    """The surface as a writable ``(H, W, 3)`` ``uint8`` RGB array; ``fast_rgb``: the surface
    is a :func:`new_surface` ``rgb24`` one and :func:`rgb24_layout_ok` holds."""
    w, h = surf.get_size()
    if fast_rgb:
        # 24-bit surface whose bytes are R, G, B: one strided copy of the pixel rows
        raw = np.frombuffer(surf.get_buffer(), dtype=np.uint8).reshape(h, surf.get_pitch())
        out = raw[:, :3 * w].reshape(h, w, 3).copy()
        del raw  # releases the surface lock held by the buffer
        return out
    buf = bytearray(pygame.image.tobytes(surf, "RGB"))  # writable, row-major (H, W, 3)
    return np.frombuffer(buf, dtype=np.uint8).reshape(h, w, 3)


@dataclass(frozen=True)
class PixelMap:
    """Field frame (m) -> frame pixels: column ``cx + x * ppm``, row ``cy - y * ppm``.

    Args:
        ppm: pixels per metre.
        cx, cy: pixel coordinates of the field origin (continuous; pixel i centred on i).
    """

    ppm: float
    cx: float
    cy: float

    def world_to_px(self, x: float, y: float) -> tuple[int, int]:
        """Pixel (column, row) of the field-frame point (x, y) (index a frame as ``frame[row, column]``)."""
        return (int(round(self.cx + float(x) * self.ppm)), int(round(self.cy - float(y) * self.ppm)))

    def to_px(self, pts: np.ndarray) -> np.ndarray:
        """(..., 2) metres -> (..., 2) float pixel coordinates (clipped to a safe range)."""
        pts = np.asarray(pts, dtype=float)
        out = np.empty(pts.shape, dtype=float)
        out[..., 0] = self.cx + pts[..., 0] * self.ppm
        out[..., 1] = self.cy - pts[..., 1] * self.ppm
        return np.clip(out, -COORD_LIMIT, COORD_LIMIT)

    def rect_m(self, x0: float, y0: float, x1: float, y1: float) -> pygame.Rect:
        """Pixel rect of the pixels whose centres lie in the field-frame box [x0, x1] x [y0, y1];
        at least the pixel at the box centre (so thin walls never vanish)."""
        def span(a: float, b: float) -> tuple[int, int]:
            a, b = sorted((a, b))
            lo, hi = math.ceil(a - 1e-9), math.floor(b + 1e-9)
            if hi < lo:
                lo = hi = int(round((a + b) / 2.0))
            return lo, hi - lo + 1

        left, w = span(self.cx + x0 * self.ppm, self.cx + x1 * self.ppm)
        top, h = span(self.cy - y0 * self.ppm, self.cy - y1 * self.ppm)
        return pygame.Rect(left, top, w, h)
