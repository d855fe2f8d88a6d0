"""The on-screen window of "human" render mode: it presents finished surfaces
(drawing is :mod:`ssl_marl.envs.render`'s job).

Opening a window needs a display; when that fails (headless machine, no video
device) :class:`Window` warns once and from then on does nothing, so callers keep
working exactly as in "rgb_array" mode. Closing the window by hand stops showing.
"""

from __future__ import annotations

import warnings

from .render_canvas import pygame


class Window:
    """A pygame window that shows surfaces at up to ``fps`` frames per second.

    Args:
        title: window caption.
        fps: the rate :meth:`present` ticks at (frames per second).
    """

    def __init__(self, title: str, fps: float) -> None:
        self.title, self.fps = title, fps
        self._screen: pygame.Surface | None = None
        self._clock: pygame.time.Clock | None = None
        self._failed = False

    @property
    def available(self) -> bool:
        """False once opening the window failed or the user closed it."""
        return not self._failed

    def _open(self, size: tuple[int, int]) -> bool:
        if self._failed:
            return False
        if self._screen is not None and self._screen.get_size() == size and pygame.display.get_init():
            return True
        try:
            if not pygame.display.get_init():
                pygame.display.init()
            self._screen = pygame.display.set_mode(size)
            pygame.display.set_caption(self.title)
            self._clock = pygame.time.Clock()
            return True
        except Exception as exc:  # pygame.error: no video device, no display, ...
            self._failed = True
            self._screen = None
            warnings.warn(f"FieldRenderer.show: cannot open a window ({exc}); continuing without one "
                          "(frames are still returned by draw(), as in 'rgb_array' mode)",
                          RuntimeWarning, stacklevel=4)
            return False

    def present(self, surface: pygame.Surface) -> None:
        """Blit ``surface``, flip, pump window events and tick at ``fps`` (no-op without a window)."""
        if not self._open(surface.get_size()):
            return
        try:
            self._screen.blit(surface, (0, 0))
            pygame.display.flip()
            for event in pygame.event.get():
                if event.type == pygame.QUIT:
                    self.close()
                    self._failed = True  # user closed it: stop showing
                    return
            self._clock.tick(self.fps)
        except pygame.error as exc:
            self._failed = True
            warnings.warn(f"FieldRenderer.show: window error ({exc}); continuing without a window",
                          RuntimeWarning, stacklevel=3)

    def close(self) -> None:
        """Close the window if open (idempotent)."""
        if self._screen is not None:
            self._screen = None
            try:
                pygame.display.quit()
            except Exception:
                pass
