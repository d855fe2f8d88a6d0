"""Top-down pygame-ce renderer for SSL world states, plus GIF/MP4 export.

:class:`FieldRenderer` draws a :class:`~ssl_marl.physics.state.WorldState` onto an
off-screen ``pygame.Surface`` and returns an ``(H, W, 3)`` ``uint8`` RGB frame
("rgb_array" mode).  :meth:`FieldRenderer.show` additionally blits frames into a
window ("human" mode, :mod:`ssl_marl.envs.window`); :func:`write_animation` (from
:mod:`ssl_marl.envs.animation`) writes frames to a GIF or MP4.

Headless operation: drawing never touches the SDL video subsystem (it only needs
``pygame.Surface``, ``pygame.draw`` and ``pygame.font``), so the off-screen path
works without a display.  Before the first ``import pygame`` we default
``SDL_VIDEODRIVER`` to ``"dummy"`` *only* when there is no sign of a display
(no ``DISPLAY`` / ``WAYLAND_DISPLAY`` on Linux), so that a later ``show()`` in a
desktop session still gets a real window.  If opening the window fails anyway
(no video device), :meth:`show` warns once and degrades to a no-op: callers keep
getting frames from :meth:`draw`, exactly as in "rgb_array" mode.

Screen mapping: field-frame +x (the goal blue attacks) points right, +y points
up.  The picture covers the whole walled area (playing area + ``boundary_width``
on each side) plus a thin dark border that stands for the outer wall.  With
``team_labels`` a caption strip below the field says what each team is (e.g.
"blue: learned skills", "yellow: baseline skills") and which way it attacks.

Legibility at small sizes: goals are drawn as a light net inside walls at least
2 px thick, tinted with the defending team's colour; with ``show_ids`` robots are
drawn with a radius of at least :data:`MIN_ID_ROBOT_RADIUS_PX` so that their number
fits (at the match default of 480 px they are drawn about 1.6x their true size).
"""

from __future__ import annotations

import math
import os
import sys
import warnings
from collections import deque
from typing import Mapping

import numpy as np

from ssl_marl.physics.field import FieldGeometry
from ssl_marl.physics.params import BallParams, RobotParams
from ssl_marl.physics.state import TeamState, WorldState

os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")
if sys.platform.startswith("linux") and not (os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY")):
    # Off-screen path: no display server -> make any (accidental) video init headless.
    os.environ.setdefault("SDL_VIDEODRIVER", "dummy")

import pygame  # noqa: E402  (pygame-ce)

from .animation import write_animation  # noqa: E402  (re-exported: frames -> GIF/MP4)
from .window import Window  # noqa: E402  (human mode)

__all__ = ["FieldRenderer", "write_animation", "BLUE", "YELLOW", "BALL_ORANGE"]

# ----------------------------------------------------------------------- colours
BLUE = (0, 90, 255)
YELLOW = (255, 220, 0)
BALL_ORANGE = (255, 140, 0)
CARPET = (0, 120, 40)
LINE_WHITE = (255, 255, 255)
WALL_DARK = (35, 35, 35)
GOAL_COLOURS = {  # goal walls tinted with the colour of the team defending that goal
    +1: (150, 130, 20),  # +x goal: yellow defends (blue attacks +x)
    -1: (20, 60, 160),  # -x goal: blue defends
}
GOAL_NET = (215, 215, 215)  # inside of the goals (light, so the goal mouth stands out on the carpet)
CAPTION_BG = (20, 20, 20)
TEAM_COLOURS = {"blue": BLUE, "yellow": YELLOW}
TEAM_MARK = {"blue": (255, 255, 255), "yellow": (0, 0, 0)}  # heading marker / id text
TEAM_OUTLINE = {"blue": (0, 40, 120), "yellow": (120, 100, 0)}
TRAIL_COLOURS = {"blue": (110, 170, 255), "yellow": (255, 240, 130), "ball": (255, 175, 90)}

OUTER_WALL_M = 0.05  # drawn thickness of the outer boundary wall (m)
LINE_WIDTH_M = 0.01  # SSL field-line width (m)
_ARC_POINTS = 20  # vertices on the round part of the robot outline
_COORD_LIMIT = 20000.0  # clip pixel coordinates (far-off / inf positions must not overflow SDL)
MIN_GOAL_WALL_PX = 2  # goal walls are drawn at least this thick
MIN_ID_ROBOT_RADIUS_PX = 7.0  # with show_ids, robots are drawn at least this big so the number fits


_RGB24_MASKS = (0x0000FF, 0x00FF00, 0xFF0000, 0)


def _new_surface(size: tuple[int, int], rgb24: bool) -> pygame.Surface:
    if rgb24:
        return pygame.Surface(size, 0, 24, _RGB24_MASKS)
    return pygame.Surface(size)


def _rgb24_layout_ok() -> bool:
    """True if a 24-bit surface with R-lowest masks stores bytes as R, G, B (so frames can
    be copied straight out of the pixel buffer, ~10x faster than image.tobytes)."""
    try:
        s = pygame.Surface((2, 1), 0, 24, _RGB24_MASKS)
        s.fill((1, 2, 3))
        raw = bytes(s.get_buffer().raw)
        return raw[:6] == bytes((1, 2, 3, 1, 2, 3))
    except Exception:
        return False


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
        self._cx = (self.width - 1) / 2.0
        self._cy = (self.field_height - 1) / 2.0
        self.trails = bool(trails)
        self.trail_length = int(trail_length)
        self.show_ids = bool(show_ids)
        self.render_fps = render_fps

        self._line_px = max(1, int(round(LINE_WIDTH_M * self.ppm)))
        # robots are drawn at least 3 px in radius so that they stay visible at small scales,
        # and big enough for their number when ids are shown
        min_r = MIN_ID_ROBOT_RADIUS_PX if self.show_ids else 3.0
        self._robot_scale = max(1.0, min_r / (robot.radius * self.ppm))
        self._robot_r_px = robot.radius * self.ppm * self._robot_scale
        self._ball_r_px = max(4, int(round(ball.radius * self.ppm)))  # >= 4 px: seen at 480 px width
        self._robot_shape = self._make_robot_shape()  # (K, 2) px, robot frame, y up

        self._font_ok = self._init_fonts()
        self._id_cache: dict[tuple[str, int], pygame.Surface] = {}
        self._fast_rgb = _rgb24_layout_ok()
        self._background = self._draw_background()
        self._surface = _new_surface((self.width, self.height), self._fast_rgb)
        self._trails: dict[tuple[str, int], deque] = {}
        self._last_t: float | None = None

        self._window = Window(f"ssl_marl - {field.name}", render_fps)
        self._closed = False

    # ------------------------------------------------------------ coordinates
    def world_to_px(self, x: float, y: float) -> tuple[int, int]:
        """Pixel (column, row) of the field-frame point (x, y) in frames from :meth:`draw`
        (index the frame as ``frame[py, px]``)."""
        return (int(round(self._cx + float(x) * self.ppm)), int(round(self._cy - float(y) * self.ppm)))

    def _to_px(self, pts: np.ndarray) -> np.ndarray:
        """(..., 2) metres -> (..., 2) float pixel coordinates (clipped to a safe range)."""
        pts = np.asarray(pts, dtype=float)
        out = np.empty(pts.shape, dtype=float)
        out[..., 0] = self._cx + pts[..., 0] * self.ppm
        out[..., 1] = self._cy - pts[..., 1] * self.ppm
        return np.clip(out, -_COORD_LIMIT, _COORD_LIMIT)

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

    def _make_robot_shape(self) -> np.ndarray:
        """Outline of the robot body (circle cut by the flat front chord), heading +x."""
        r, d = self.robot.radius, self.robot.front_distance
        a0 = math.acos(d / r)  # half angle of the removed cap
        ang = np.linspace(a0, 2.0 * math.pi - a0, _ARC_POINTS)
        return np.stack([np.cos(ang), np.sin(ang)], axis=1) * r * self.ppm * self._robot_scale

    def _rect_m(self, x0: float, y0: float, x1: float, y1: float) -> pygame.Rect:
        """Pixel rect of the pixels whose centres lie in the field-frame box [x0, x1] x [y0, y1];
        at least the pixel at the box centre (so thin walls never vanish)."""
        def span(a: float, b: float) -> tuple[int, int]:
            a, b = sorted((a, b))
            lo, hi = math.ceil(a - 1e-9), math.floor(b + 1e-9)
            if hi < lo:
                lo = hi = int(round((a + b) / 2.0))
            return lo, hi - lo + 1

        left, w = span(self._cx + x0 * self.ppm, self._cx + x1 * self.ppm)
        top, h = span(self._cy - y0 * self.ppm, self._cy - y1 * self.ppm)
        return pygame.Rect(left, top, w, h)

    def _line_m(self, surf: pygame.Surface, x0: float, y0: float, x1: float, y1: float,
                colour=LINE_WHITE) -> None:
        """Axis-aligned field line of width ``_line_px`` centred on the segment."""
        lw = self._line_px
        (u0, v0), (u1, v1) = self._to_px(np.array([[x0, y0], [x1, y1]]))
        u0, u1 = sorted((u0, u1))
        v0, v1 = sorted((v0, v1))
        off = (lw - 1) / 2.0
        left, top = int(round(u0 - off)), int(round(v0 - off))
        w = int(round(u1 - u0)) + lw
        h = int(round(v1 - v0)) + lw
        surf.fill(colour, pygame.Rect(left, top, w, h))

    def _draw_background(self) -> pygame.Surface:
        f = self.field
        bg = _new_surface((self.width, self.height), self._fast_rgb)
        bg.fill(WALL_DARK)  # outer boundary wall
        # carpet: playing area + boundary_width run-off on every side
        bg.fill(CARPET, self._rect_m(-f.wall_half_length, -f.wall_half_width, f.wall_half_length,
                                     f.wall_half_width))
        hl, hw = f.half_length, f.half_width
        # touch lines, goal lines, half-way line, centre line
        self._line_m(bg, -hl, hw, hl, hw)
        self._line_m(bg, -hl, -hw, hl, -hw)
        self._line_m(bg, -hl, -hw, -hl, hw)
        self._line_m(bg, hl, -hw, hl, hw)
        self._line_m(bg, 0.0, -hw, 0.0, hw)
        self._line_m(bg, -hl, 0.0, hl, 0.0)
        # centre circle (pygame draws the ring inwards from the given radius)
        c = self.world_to_px(0.0, 0.0)
        r_out = int(round(f.center_circle_radius * self.ppm + self._line_px / 2.0))
        pygame.draw.circle(bg, LINE_WHITE, c, max(1, r_out), width=min(self._line_px, max(1, r_out)))
        # defense areas
        dw, dd = f.defense_width / 2.0, f.defense_depth
        for s in (+1, -1):
            xg, xi = s * hl, s * (hl - dd)
            self._line_m(bg, xi, -dw, xi, dw)
            self._line_m(bg, xi, dw, xg, dw)
            self._line_m(bg, xi, -dw, xg, -dw)
        # penalty marks and centre mark (small dots)
        dot = max(1, self._line_px)
        for p in ((0.0, 0.0), (hl - f.penalty_mark_distance, 0.0), (-hl + f.penalty_mark_distance, 0.0)):
            if abs(p[0]) < hl:
                pygame.draw.circle(bg, LINE_WHITE, self.world_to_px(*p), dot + 1)
        # goals: a light net inside (goal_depth x goal_width behind the goal line), side
        # walls and back wall at least MIN_GOAL_WALL_PX thick, tinted by the defending team
        gw, gd = f.goal_width / 2.0, f.goal_depth
        t = max(f.goal_wall_thickness, MIN_GOAL_WALL_PX / self.ppm)
        for s in (+1, -1):
            col = GOAL_COLOURS[s]
            x_line, x_back = s * hl, s * (hl + gd)
            x_out = s * (hl + gd + t)
            bg.fill(GOAL_NET, self._rect_m(x_line + s * self._line_px / (2 * self.ppm), -gw, x_back, gw))
            bg.fill(col, self._rect_m(x_line, gw, x_out, gw + t))  # wall at +y
            bg.fill(col, self._rect_m(x_line, -gw - t, x_out, -gw))  # wall at -y
            bg.fill(col, self._rect_m(x_back, -gw - t, x_out, gw + t))  # back wall
        if self.caption_height:
            self._draw_caption(bg)
        return bg

    def _draw_caption(self, bg: pygame.Surface) -> None:
        """Caption strip below the field: each team's colour swatch, name and label."""
        top = self.field_height
        bg.fill(CAPTION_BG, pygame.Rect(0, top, self.width, self.caption_height))
        if not self._font_ok:
            return
        attacks = {"blue": "attacks right", "yellow": "attacks left"}
        x, sw = 6, max(8, self.caption_height - 8)
        for team in ("blue", "yellow"):
            if team not in self.team_labels:
                continue
            cy = top + self.caption_height // 2
            bg.fill(TEAM_COLOURS[team], pygame.Rect(x, cy - sw // 2, sw, sw))
            text = self._caption_font.render(f"{team}: {self.team_labels[team]} ({attacks[team]})", True,
                                             LINE_WHITE)
            bg.blit(text, text.get_rect(midleft=(x + sw + 4, cy)))
            x += sw + 4 + text.get_width() + 14

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
                              frame="field")
        raise ValueError(f"FieldRenderer.draw: unknown WorldState.frame {world.frame!r}")

    def reset_trails(self) -> None:
        """Forget all trajectory history."""
        self._trails.clear()
        self._last_t = None

    def _update_trails(self, world: WorldState) -> None:
        t = float(world.t)
        if self._last_t is not None and t < self._last_t:  # time went backwards: a new episode
            self._trails.clear()
        self._last_t = t
        seen = set()
        for team in ("blue", "yellow"):
            ts = world.team(team)
            if ts.n == 0:
                continue
            px = self._to_px(ts.pos)
            ok = np.isfinite(np.asarray(ts.pos, float)).all(axis=1)
            for i in range(ts.n):
                if not ok[i]:
                    continue
                key = (team, i)
                seen.add(key)
                dq = self._trails.get(key)
                if dq is None:
                    dq = self._trails[key] = deque(maxlen=self.trail_length)
                dq.append((int(round(px[i, 0])), int(round(px[i, 1]))))
        bp = np.asarray(world.ball_pos, float)
        if np.isfinite(bp).all():
            key = ("ball", 0)
            seen.add(key)
            dq = self._trails.get(key)
            if dq is None:
                dq = self._trails[key] = deque(maxlen=self.trail_length)
            u, v = self._to_px(bp)
            dq.append((int(round(u)), int(round(v))))
        for key in [k for k in self._trails if k not in seen]:  # robots that left the field
            del self._trails[key]

    def _draw_trails(self, surf: pygame.Surface) -> None:
        w = max(1, int(round(0.015 * self.ppm)))
        for (team, _), pts in self._trails.items():
            if len(pts) >= 2:
                pygame.draw.lines(surf, TRAIL_COLOURS[team], False, list(pts), w)

    def _id_label(self, team: str, idx: int) -> pygame.Surface:
        key = (team, idx)
        lab = self._id_cache.get(key)
        if lab is None:
            lab = self._id_font.render(str(idx), True, TEAM_MARK[team])
            self._id_cache[key] = lab
        return lab

    def _draw_team(self, surf: pygame.Surface, team: str, ts: TeamState) -> None:
        if ts.n == 0:
            return
        pos = np.asarray(ts.pos, float)
        head = np.asarray(ts.heading, float)
        ok = np.isfinite(pos).all(axis=1) & np.isfinite(head)
        head = np.where(ok, head, 0.0)
        centre_ok = np.where(ok[:, None], pos, 0.0)
        c, s = np.cos(head), np.sin(head)
        shp = self._robot_shape  # (K, 2), screen y flips below
        centre = self._to_px(centre_ok)  # (n, 2)
        # rotate in the field frame, then flip y for the screen
        xs = c[:, None] * shp[None, :, 0] - s[:, None] * shp[None, :, 1]
        ys = s[:, None] * shp[None, :, 0] + c[:, None] * shp[None, :, 1]
        poly = np.stack([centre[:, None, 0] + xs, centre[:, None, 1] - ys], axis=2)
        # heading marker: the dribbler bar along the flat front chord (keeps the centre free for the id)
        fd = self.robot.front_distance * self.ppm * self._robot_scale
        hw = self.robot.dribbler_half_width * self.ppm * self._robot_scale
        fx, fy = centre[:, 0] + c * fd, centre[:, 1] - s * fd  # front-face midpoint (screen)
        bar_a = np.stack([fx - s * hw, fy - c * hw], axis=1)  # left end (+y side of the robot)
        bar_b = np.stack([fx + s * hw, fy + c * hw], axis=1)
        # pygame truncates float coordinates: round them so drawing agrees with world_to_px
        poly_i = np.rint(np.clip(poly, -_COORD_LIMIT, _COORD_LIMIT)).astype(np.int64)
        bar_a_i = np.rint(np.clip(bar_a, -_COORD_LIMIT, _COORD_LIMIT)).astype(np.int64)
        bar_b_i = np.rint(np.clip(bar_b, -_COORD_LIMIT, _COORD_LIMIT)).astype(np.int64)
        colour, outline, mark = TEAM_COLOURS[team], TEAM_OUTLINE[team], TEAM_MARK[team]
        mark_w = max(2, int(round(self._robot_r_px / 5.0)))
        draw_outline = self._robot_r_px >= 5.0
        draw_bar = self._robot_r_px >= 4.0  # below that the bar would cover the whole body
        draw_ids = self.show_ids and self._font_ok and self._robot_r_px >= 4.0
        for i in range(ts.n):
            if not ok[i]:
                continue
            pts = poly_i[i].tolist()
            pygame.draw.polygon(surf, colour, pts)
            if draw_outline:
                pygame.draw.polygon(surf, outline, pts, 1)
            if draw_bar:
                pygame.draw.line(surf, mark, bar_a_i[i].tolist(), bar_b_i[i].tolist(), mark_w)
            if draw_ids:
                lab = self._id_label(team, i)
                surf.blit(lab, lab.get_rect(center=(int(round(centre[i, 0])), int(round(centre[i, 1])))))

    def _draw_ball(self, surf: pygame.Surface, world: WorldState) -> None:
        bp = np.asarray(world.ball_pos, float)
        if not np.isfinite(bp).all():
            return
        u, v = self._to_px(bp)
        centre = (int(round(u)), int(round(v)))
        if world.ball_visible:
            pygame.draw.circle(surf, BALL_ORANGE, centre, self._ball_r_px)
            if self._ball_r_px >= 4:  # dark rim: the ball stands out on the carpet and on white lines
                pygame.draw.circle(surf, WALL_DARK, centre, self._ball_r_px, width=1)
        else:  # vision dropped it: hollow ring at the last seen position
            pygame.draw.circle(surf, BALL_ORANGE, centre, self._ball_r_px, width=1)

    def _draw_info(self, surf: pygame.Surface, text: str) -> None:
        if not self._font_ok or not text:
            return
        lines = [self._info_font.render(line, True, LINE_WHITE) for line in str(text).splitlines() or [""]]
        pad = 4
        w = max(ln.get_width() for ln in lines) + 2 * pad
        h = sum(ln.get_height() for ln in lines) + 2 * pad
        box = pygame.Surface((w, h), pygame.SRCALPHA)
        box.fill((0, 0, 0, 150))
        surf.blit(box, (2, 2))
        y = 2 + pad
        for ln in lines:
            surf.blit(ln, (2 + pad, y))
            y += ln.get_height()

    def draw(self, world: WorldState, *, info_text: str | None = None) -> np.ndarray:
        """Render ``world`` and return the frame as an ``(H, W, 3)`` ``uint8`` RGB array."""
        if self._closed:
            raise RuntimeError("FieldRenderer.draw: renderer is closed")
        world = self._field_frame(world)
        surf = self._surface
        surf.blit(self._background, (0, 0))
        if self.trails:
            self._update_trails(world)
            self._draw_trails(surf)
        self._draw_team(surf, "blue", world.blue)
        self._draw_team(surf, "yellow", world.yellow)
        self._draw_ball(surf, world)
        if info_text:
            self._draw_info(surf, info_text)
        return self._surface_to_array(surf)

    def _surface_to_array(self, surf: pygame.Surface) -> np.ndarray:
        w, h = surf.get_size()
        if self._fast_rgb:
            # 24-bit surface whose bytes are R, G, B: one strided copy of the pixel rows
            raw = np.frombuffer(surf.get_buffer(), dtype=np.uint8).reshape(h, surf.get_pitch())
            out = raw[:, :3 * w].reshape(h, w, 3).copy()
            del raw  # releases the surface lock held by the buffer
            return out
        buf = bytearray(pygame.image.tobytes(surf, "RGB"))  # writable, row-major (H, W, 3)
        return np.frombuffer(buf, dtype=np.uint8).reshape(h, w, 3)

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
