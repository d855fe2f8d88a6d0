"""The moving part of a field picture: robots, the ball, trajectory trails and the info text.

Robots are drawn as their body outline (a circle cut by the flat front chord) in the
team colour with a darker outline, the dribbler bar along the front chord as the
heading marker, and optionally their index; the ball as an orange disc with a dark
rim, or a hollow ring at the last seen position when vision dropped it. A ball in the
air (``WorldState.ball_height`` > 0) casts a dark shadow at its ground position and is
drawn :data:`~ssl_marl.envs.render_style.BALL_LIFT_PER_M` m up the picture per metre of
height, larger by :data:`~ssl_marl.envs.render_style.BALL_GROWTH_PER_M` per metre. Non-finite
positions are skipped; far-off ones are clipped to a safe pixel range.
"""

from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass
from typing import Callable

import numpy as np

from ssl_marl.physics.params import RobotParams
from ssl_marl.physics.state import TeamState, WorldState

from .render_canvas import PixelMap, pygame
from .render_style import (ARC_POINTS, BALL_GROWTH_PER_M, BALL_LIFT_PER_M, BALL_ORANGE, BALL_SHADOW, COORD_LIMIT,
                           LINE_WHITE, TEAM_COLOURS, TEAM_MARK, TEAM_OUTLINE, TRAIL_COLOURS, TRAIL_WIDTH_M, WALL_DARK)


@dataclass(frozen=True)
class RobotLook:
    """How robots are drawn at one scale (pixels, drawn ``scale`` times their true size).

    Attributes:
        outline: (K, 2) body outline in the robot frame, heading +x, y up (px).
        front_px: centre to the flat front face (px).
        bar_half_px: half-width of the dribbler bar (px).
        radius_px: body radius (px).
    """

    outline: np.ndarray
    front_px: float
    bar_half_px: float
    radius_px: float

    @classmethod
    def of(cls, robot: RobotParams, ppm: float, scale: float) -> RobotLook:
        """The look of ``robot`` at ``ppm`` pixels per metre, drawn ``scale`` times its size."""
        r, d = robot.radius, robot.front_distance
        a0 = math.acos(d / r)  # half angle of the removed cap
        ang = np.linspace(a0, 2.0 * math.pi - a0, ARC_POINTS)
        outline = np.stack([np.cos(ang), np.sin(ang)], axis=1) * r * ppm * scale
        return cls(outline=outline, front_px=robot.front_distance * ppm * scale,
                   bar_half_px=robot.dribbler_half_width * ppm * scale, radius_px=robot.radius * ppm * scale)


def draw_team(surf: pygame.Surface, pm: PixelMap, team: str, ts: TeamState, look: RobotLook,
              id_label: Callable[[str, int], pygame.Surface] | None) -> None:
    """Draw the robots of ``team`` ("blue" / "yellow"); ``id_label(team, index)`` gives the
    number drawn on each robot (None: no numbers)."""
    if ts.n == 0:
        return
    pos = np.asarray(ts.pos, float)
    head = np.asarray(ts.heading, float)
    ok = np.isfinite(pos).all(axis=1) & np.isfinite(head)
    head = np.where(ok, head, 0.0)
    centre_ok = np.where(ok[:, None], pos, 0.0)
    c, s = np.cos(head), np.sin(head)
    shp = look.outline  # (K, 2), screen y flips below
    centre = pm.to_px(centre_ok)  # (n, 2)
    # rotate in the field frame, then flip y for the screen
    xs = c[:, None] * shp[None, :, 0] - s[:, None] * shp[None, :, 1]
    ys = s[:, None] * shp[None, :, 0] + c[:, None] * shp[None, :, 1]
    poly = np.stack([centre[:, None, 0] + xs, centre[:, None, 1] - ys], axis=2)
    # heading marker: the dribbler bar along the flat front chord (keeps the centre free for the id)
    fd = look.front_px
    hw = look.bar_half_px
    fx, fy = centre[:, 0] + c * fd, centre[:, 1] - s * fd  # front-face midpoint (screen)
    bar_a = np.stack([fx - s * hw, fy - c * hw], axis=1)  # left end (+y side of the robot)
    bar_b = np.stack([fx + s * hw, fy + c * hw], axis=1)
    # pygame truncates float coordinates: round them so drawing agrees with world_to_px
    poly_i = np.rint(np.clip(poly, -COORD_LIMIT, COORD_LIMIT)).astype(np.int64)
    bar_a_i = np.rint(np.clip(bar_a, -COORD_LIMIT, COORD_LIMIT)).astype(np.int64)
    bar_b_i = np.rint(np.clip(bar_b, -COORD_LIMIT, COORD_LIMIT)).astype(np.int64)
    colour, outline, mark = TEAM_COLOURS[team], TEAM_OUTLINE[team], TEAM_MARK[team]
    mark_w = max(2, int(round(look.radius_px / 5.0)))
    draw_outline = look.radius_px >= 5.0
    draw_bar = look.radius_px >= 4.0  # below that the bar would cover the whole body
    draw_ids = id_label is not None and look.radius_px >= 4.0
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
            lab = id_label(team, i)
            surf.blit(lab, lab.get_rect(center=(int(round(centre[i, 0])), int(round(centre[i, 1])))))


def draw_ball(surf: pygame.Surface, pm: PixelMap, world: WorldState, radius_px: int) -> None:
    """Draw the ball: a disc with a dark rim, or a hollow ring when ``world.ball_visible``
    is False; in the air, a shadow at its ground position and the ball lifted and larger."""
    bp = np.asarray(world.ball_pos, float)
    if not np.isfinite(bp).all():
        return
    u, v = pm.to_px(bp)
    centre = (int(round(u)), int(round(v)))
    z = float(world.ball_height)
    if z > 0.0 and math.isfinite(z):
        pygame.draw.circle(surf, BALL_SHADOW, centre, radius_px)
        v = max(v - z * BALL_LIFT_PER_M * pm.ppm, -COORD_LIMIT)
        centre = (int(round(u)), int(round(v)))
        radius_px = int(round(radius_px * (1.0 + BALL_GROWTH_PER_M * min(z, 10.0))))
    if world.ball_visible:
        pygame.draw.circle(surf, BALL_ORANGE, centre, radius_px)
        if radius_px >= 4:  # dark rim: the ball stands out on the carpet and on white lines
            pygame.draw.circle(surf, WALL_DARK, centre, radius_px, width=1)
    else:  # vision dropped it: hollow ring at the last seen position
        pygame.draw.circle(surf, BALL_ORANGE, centre, radius_px, width=1)


def draw_info(surf: pygame.Surface, font: pygame.font.Font, text: str) -> None:
    """Lines of ``text`` in a translucent box at the top-left corner."""
    if not text:
        return
    lines = [font.render(line, True, LINE_WHITE) for line in str(text).splitlines() or [""]]
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


class Trails:
    """Trajectory polylines of every robot and the ball: the last ``length`` pixel positions each.

    Time going backwards (a new episode) clears them; a robot that leaves the field
    (or whose position is not finite) loses its trail.
    """

    def __init__(self, length: int) -> None:
        self.length = length
        self._paths: dict[tuple[str, int], deque] = {}
        self._last_t: float | None = None

    def clear(self) -> None:
        """Forget all trajectory history."""
        self._paths.clear()
        self._last_t = None

    def _append(self, key: tuple[str, int], point: tuple[int, int]) -> None:
        dq = self._paths.get(key)
        if dq is None:
            dq = self._paths[key] = deque(maxlen=self.length)
        dq.append(point)

    def update(self, world: WorldState, pm: PixelMap) -> None:
        """Add the positions of ``world`` (field frame) to the trails."""
        t = float(world.t)
        if self._last_t is not None and t < self._last_t:  # time went backwards: a new episode
            self._paths.clear()
        self._last_t = t
        seen = set()
        for team in ("blue", "yellow"):
            ts = world.team(team)
            if ts.n == 0:
                continue
            px = pm.to_px(ts.pos)
            ok = np.isfinite(np.asarray(ts.pos, float)).all(axis=1)
            for i in range(ts.n):
                if not ok[i]:
                    continue
                key = (team, i)
                seen.add(key)
                self._append(key, (int(round(px[i, 0])), int(round(px[i, 1]))))
        bp = np.asarray(world.ball_pos, float)
        if np.isfinite(bp).all():
            key = ("ball", 0)
            seen.add(key)
            u, v = pm.to_px(bp)
            self._append(key, (int(round(u)), int(round(v))))
        for key in [k for k in self._paths if k not in seen]:  # robots that left the field
            del self._paths[key]

    def draw(self, surf: pygame.Surface, ppm: float) -> None:
        """Draw every trail of two or more points, :data:`~ssl_marl.envs.render_style.TRAIL_WIDTH_M` wide."""
        w = max(1, int(round(TRAIL_WIDTH_M * ppm)))
        for (team, _), pts in self._paths.items():
            if len(pts) >= 2:
                pygame.draw.lines(surf, TRAIL_COLOURS[team], False, list(pts), w)
