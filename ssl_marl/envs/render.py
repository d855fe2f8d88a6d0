"""Top-down pygame-ce renderer for SSL world states.

:class:`FieldRenderer` draws a :class:`~ssl_marl.physics.state.WorldState` onto an
off-screen ``pygame.Surface`` and returns an ``(H, W, 3)`` ``uint8`` RGB frame
("rgb_array" mode). :meth:`FieldRenderer.show` additionally blits frames into a
window ("human" mode, :mod:`ssl_marl.envs.window`); if opening the window fails (no
video device), :meth:`~FieldRenderer.show` warns once and does nothing, and callers
keep getting frames from :meth:`~FieldRenderer.draw`, exactly as in "rgb_array" mode.
:func:`ssl_marl.envs.animation.write_animation` and
:class:`~ssl_marl.envs.animation.VideoSink` write frames to a GIF or MP4.

The picture covers the whole walled area (playing area + ``boundary_width`` on each
side) plus a thin dark border that stands for the outer wall; field-frame +x (the
goal blue attacks) points right, +y up (:class:`~ssl_marl.envs.render_canvas.PixelMap`).
With ``team_labels`` a caption strip below the field says what each team is (e.g.
"blue: learned skills", "yellow: baseline skills") and which way it attacks.

The static field is drawn once (:mod:`ssl_marl.envs.render_field`); robots, ball,
trails and info text every frame (:mod:`ssl_marl.envs.render_bodies`); colours and
sizes are in :mod:`ssl_marl.envs.render_style`. With ``show_ids`` robots are drawn
with a radius of at least :data:`~ssl_marl.envs.render_style.MIN_ID_ROBOT_RADIUS_PX`
so that their number fits (at the match default of 480 px they are drawn about 1.6x
their true size).
"""

from __future__ import annotations

import math
import warnings
from typing import Mapping

import numpy as np

from ssl_marl.physics.field import FieldGeometry
from ssl_marl.physics.params import BallParams, RobotParams
from ssl_marl.physics.state import TeamState, WorldState

from .render_bodies import RobotLook, Trails, draw_ball, draw_info, draw_team
from .render_canvas import PixelMap, new_surface, pygame, rgb24_layout_ok, surface_to_array
from .render_field import draw_caption, draw_field
from .render_style import (LINE_WIDTH_M, MIN_BALL_RADIUS_PX, MIN_ID_ROBOT_RADIUS_PX, MIN_ROBOT_RADIUS_PX,
                           OUTER_WALL_M, TEAM_COLOURS, TEAM_MARK)
from .window import Window

__all__ = ["FieldRenderer"]


class FieldRenderer:
    """Render :class:`WorldState` snapshots of one field.

    Args:
        field: field geometry (any division or a custom one).
        robot, ball: physical parameters (sizes of the drawn bodies).
        pixels_per_metre: scale; if ``None`` it is derived from ``width_px`` so that
            the whole walled area (plus the drawn outer wall) fits exactly.
        width_px: frame width when ``pixels_per_metre`` is ``None``.
        trails: draw trajectory polylines of robots and ball.
        trail_length: number of past positions kept per trail.
        show_ids: draw each robot's index on it.
        render_fps: frame rate :meth:`show` ticks at.
        team_labels: ``{"blue": text, "yellow": text}`` (either may be missing): adds a
            caption strip below the field naming each team (frames get taller by
            :attr:`caption_height`; field pixel coordinates do not change).
    """

    def __init__(self, field: FieldGeometry, robot: RobotParams, ball: BallParams, *,
                 pixels_per_metre: float | None = None, width_px: int = 960, trails: bool = False,
                 trail_length: int = 120, show_ids: bool = True, render_fps: int = 30,
                 team_labels: Mapping[str, str] | None = None) -> None:
        self.field = field
        self.robot = robot
        self.ball = ball
        half_w_m = field.wall_half_length + OUTER_WALL_M
        half_h_m = field.wall_half_width + OUTER_WALL_M
        if pixels_per_metre is None:
            if not (isinstance(width_px, (int, np.integer)) and width_px >= 16):
                raise ValueError(f"FieldRenderer: width_px must be an int >= 16, got {width_px!r}")
            self.width = int(width_px)
            self.ppm = self.width / (2.0 * half_w_m)
        else:
            if not (isinstance(pixels_per_metre, (int, float)) and math.isfinite(pixels_per_metre)
                    and pixels_per_metre > 0):
                raise ValueError(f"FieldRenderer: pixels_per_metre must be a positive finite number, "
                                 f"got {pixels_per_metre!r}")
            self.ppm = float(pixels_per_metre)
            self.width = max(16, int(round(2.0 * half_w_m * self.ppm)))
        self.field_height = max(16, int(round(2.0 * half_h_m * self.ppm)))
        self.team_labels = dict(team_labels or {})
        unknown = sorted(set(self.team_labels) - set(TEAM_COLOURS))
        if unknown or not all(isinstance(v, str) for v in self.team_labels.values()):
            raise ValueError(f"FieldRenderer: team_labels must map 'blue'/'yellow' to text, got {team_labels!r}")
        self.caption_height = max(16, self.width // 28) if self.team_labels else 0
        self.height = self.field_height + self.caption_height
        if self.width * self.height > 64_000_000:
            raise ValueError(f"FieldRenderer: frame {self.width}x{self.height} px is too large")
        if not (isinstance(trail_length, (int, np.integer)) and trail_length >= 2):
            raise ValueError(f"FieldRenderer: trail_length must be an int >= 2, got {trail_length!r}")
        if not (isinstance(render_fps, (int, float)) and render_fps > 0):
            raise ValueError(f"FieldRenderer: render_fps must be positive, got {render_fps!r}")
        # Pixel-centre convention: pixel index i is centred on continuous coordinate i.
        self._map = PixelMap(ppm=self.ppm, cx=(self.width - 1) / 2.0, cy=(self.field_height - 1) / 2.0)
        self.trails = bool(trails)
        self.trail_length = int(trail_length)
        self.show_ids = bool(show_ids)
        self.render_fps = render_fps

        self._line_px = max(1, int(round(LINE_WIDTH_M * self.ppm)))
        # robots are drawn at least MIN_ROBOT_RADIUS_PX in radius so that they stay visible at
        # small scales, and big enough for their number when ids are shown
        min_r = MIN_ID_ROBOT_RADIUS_PX if self.show_ids else MIN_ROBOT_RADIUS_PX
        self._robot_scale = max(1.0, min_r / (robot.radius * self.ppm))
        self._robot_look = RobotLook.of(robot, self.ppm, self._robot_scale)
        self._robot_r_px = self._robot_look.radius_px
        self._ball_r_px = max(MIN_BALL_RADIUS_PX, int(round(ball.radius * self.ppm)))

        self._font_ok = self._init_fonts()
        self._id_cache: dict[tuple[str, int], pygame.Surface] = {}
        self._fast_rgb = rgb24_layout_ok()
        self._background = self._draw_background()
        self._surface = new_surface((self.width, self.height), self._fast_rgb)
        self._trails = Trails(self.trail_length)

        self._window = Window(f"ssl_marl - {field.name}", render_fps)
        self._closed = False

    # ------------------------------------------------------------ coordinates
    def world_to_px(self, x: float, y: float) -> tuple[int, int]:
        """Pixel (column, row) of the field-frame point (x, y) in frames from :meth:`draw`
        (index the frame as ``frame[py, px]``)."""
        return self._map.world_to_px(x, y)

    @property
    def frame_shape(self) -> tuple[int, int, int]:
        return (self.height, self.width, 3)

    # --------------------------------------------------------------- set-up
    def _init_fonts(self) -> bool:
        try:
            if not pygame.font.get_init():
                pygame.font.init()
            id_size = max(12, int(round(self._robot_r_px * 1.9)))
            self._id_font = pygame.font.Font(None, id_size)
            self._id_font.set_bold(True)
            self._info_font = pygame.font.Font(None, max(14, self.width // 45))
            self._caption_font = pygame.font.Font(None, max(15, int(self.caption_height * 0.95)))
            return True
        except Exception as exc:  # pygame.error, missing SDL_ttf, ...
            warnings.warn(f"FieldRenderer: font initialisation failed ({exc}); robot ids and info text "
                          "will not be drawn", RuntimeWarning, stacklevel=3)
            return False

    def _draw_background(self) -> pygame.Surface:
        bg = new_surface((self.width, self.height), self._fast_rgb)
        draw_field(bg, self._map, self.field, self._line_px)
        if self.caption_height:
            draw_caption(bg, self.field_height, self.caption_height, self._caption_font if self._font_ok else None,
                         self.team_labels)
        return bg

    # ---------------------------------------------------------------- drawing
    @staticmethod
    def _field_frame(world: WorldState) -> WorldState:
        if world.frame in ("field", "blue"):
            return world
        if world.frame == "yellow":  # undo to_team_frame(..., "yellow"): rotate by pi
            def flip(ts: TeamState) -> TeamState:
                return TeamState(-ts.pos, ts.heading + math.pi, -ts.vel, ts.omega, ts.ball_on_dribbler,
                                 ts.kick_ready)
            return WorldState(t=world.t, ball_pos=-np.asarray(world.ball_pos), ball_vel=-np.asarray(world.ball_vel),
                              blue=flip(world.blue), yellow=flip(world.yellow), ball_visible=world.ball_visible,
                              frame="field", ball_height=world.ball_height)
        raise ValueError(f"FieldRenderer.draw: unknown WorldState.frame {world.frame!r}")

    def reset_trails(self) -> None:
        """Forget all trajectory history."""
        self._trails.clear()

    def _id_label(self, team: str, idx: int) -> pygame.Surface:
        key = (team, idx)
        lab = self._id_cache.get(key)
        if lab is None:
            lab = self._id_font.render(str(idx), True, TEAM_MARK[team])
            self._id_cache[key] = lab
        return lab

    def draw(self, world: WorldState, *, info_text: str | None = None) -> np.ndarray:
        """Render ``world`` and return the frame as an ``(H, W, 3)`` ``uint8`` RGB array."""
        if self._closed:
            raise RuntimeError("FieldRenderer.draw: renderer is closed")
        world = self._field_frame(world)
        surf = self._surface
        surf.blit(self._background, (0, 0))
        if self.trails:
            self._trails.update(world, self._map)
            self._trails.draw(surf, self.ppm)
        id_label = self._id_label if self.show_ids and self._font_ok else None
        draw_team(surf, self._map, "blue", world.blue, self._robot_look, id_label)
        draw_team(surf, self._map, "yellow", world.yellow, self._robot_look, id_label)
        draw_ball(surf, self._map, world, self._ball_r_px)
        if info_text and self._font_ok:
            draw_info(surf, self._info_font, info_text)
        return surface_to_array(surf, self._fast_rgb)

    # ------------------------------------------------------------ human mode
    @property
    def window_available(self) -> bool:
        """False once opening the window failed (then :meth:`show` is a no-op)."""
        return self._window.available

    def show(self, frame_or_world) -> None:
        """Blit a frame (``(H, W, 3)`` uint8 array) or a freshly drawn :class:`WorldState`
        into a window (:class:`~ssl_marl.envs.window.Window`), pump window events and tick
        at ``render_fps``.

        Without a usable display this warns once and does nothing."""
        if self._closed:
            raise RuntimeError("FieldRenderer.show: renderer is closed")
        if isinstance(frame_or_world, WorldState):
            self.draw(frame_or_world)
            self._window.present(self._surface)
            return
        frame = np.ascontiguousarray(frame_or_world, dtype=np.uint8)
        if frame.ndim != 3 or frame.shape[2] != 3:
            raise ValueError(f"FieldRenderer.show: expected an (H, W, 3) frame or a WorldState, "
                             f"got shape {frame.shape}")
        # the surface borrows the frame's buffer: keep ``frame`` alive until presented
        self._window.present(pygame.image.frombuffer(frame, (frame.shape[1], frame.shape[0]), "RGB"))

    def close(self) -> None:
        """Close the window (if any) and drop the surfaces. Idempotent."""
        self._window.close()
        self._trails.clear()
        self._id_cache.clear()
        self._closed = True
