"""The static part of a field picture: carpet, walls, field lines, goals and the caption strip.

Drawn once per :class:`~ssl_marl.envs.render.FieldRenderer` into a background surface.
Lines follow the SSL field drawing (touch, goal, half-way and centre lines, centre
circle, defense areas, penalty and centre marks); goals are a light net inside walls
at least :data:`~ssl_marl.envs.render_style.MIN_GOAL_WALL_PX` thick, tinted with the
defending team's colour.
"""

from __future__ import annotations

from typing import Mapping

import numpy as np

from ssl_marl.physics.field import FieldGeometry

from .render_canvas import PixelMap, pygame
from .render_style import (CAPTION_BG, CARPET, GOAL_COLOURS, GOAL_NET, LINE_WHITE, MIN_GOAL_WALL_PX, TEAM_COLOURS,
                           WALL_DARK)


def draw_line_m(surf: pygame.Surface, pm: PixelMap, line_px: int, x0: float, y0: float, x1: float, y1: float,
                colour: tuple[int, int, int] = LINE_WHITE) -> None:
    """Axis-aligned field line from (x0, y0) to (x1, y1) (m), ``line_px`` wide, centred on the segment."""
    lw = line_px
    (u0, v0), (u1, v1) = pm.to_px(np.array([[x0, y0], [x1, y1]]))
    u0, u1 = sorted((u0, u1))
    v0, v1 = sorted((v0, v1))
    off = (lw - 1) / 2.0
    left, top = int(round(u0 - off)), int(round(v0 - off))
    w = int(round(u1 - u0)) + lw
    h = int(round(v1 - v0)) + lw
    surf.fill(colour, pygame.Rect(left, top, w, h))


def draw_field(bg: pygame.Surface, pm: PixelMap, f: FieldGeometry, line_px: int) -> None:
    """Outer wall, carpet (playing area + ``boundary_width`` run-off), field lines and goals of ``f``."""
    bg.fill(WALL_DARK)  # outer boundary wall
    # carpet: playing area + boundary_width run-off on every side
    bg.fill(CARPET, pm.rect_m(-f.wall_half_length, -f.wall_half_width, f.wall_half_length, f.wall_half_width))
    hl, hw = f.half_length, f.half_width
    # touch lines, goal lines, half-way line, centre line
    draw_line_m(bg, pm, line_px, -hl, hw, hl, hw)
    draw_line_m(bg, pm, line_px, -hl, -hw, hl, -hw)
    draw_line_m(bg, pm, line_px, -hl, -hw, -hl, hw)
    draw_line_m(bg, pm, line_px, hl, -hw, hl, hw)
    draw_line_m(bg, pm, line_px, 0.0, -hw, 0.0, hw)
    draw_line_m(bg, pm, line_px, -hl, 0.0, hl, 0.0)
    # centre circle (pygame draws the ring inwards from the given radius)
    c = pm.world_to_px(0.0, 0.0)
    r_out = int(round(f.center_circle_radius * pm.ppm + line_px / 2.0))
    pygame.draw.circle(bg, LINE_WHITE, c, max(1, r_out), width=min(line_px, max(1, r_out)))
    # defense areas
    dw, dd = f.defense_width / 2.0, f.defense_depth
    for s in (+1, -1):
        xg, xi = s * hl, s * (hl - dd)
        draw_line_m(bg, pm, line_px, xi, -dw, xi, dw)
        draw_line_m(bg, pm, line_px, xi, dw, xg, dw)
        draw_line_m(bg, pm, line_px, xi, -dw, xg, -dw)
    # penalty marks and centre mark (small dots)
    dot = max(1, line_px)
    for p in ((0.0, 0.0), (hl - f.penalty_mark_distance, 0.0), (-hl + f.penalty_mark_distance, 0.0)):
        if abs(p[0]) < hl:
            pygame.draw.circle(bg, LINE_WHITE, pm.world_to_px(*p), dot + 1)
    # goals: a light net inside (goal_depth x goal_width behind the goal line), side
    # walls and back wall at least MIN_GOAL_WALL_PX thick, tinted by the defending team
    gw, gd = f.goal_width / 2.0, f.goal_depth
    t = max(f.goal_wall_thickness, MIN_GOAL_WALL_PX / pm.ppm)
    for s in (+1, -1):
        col = GOAL_COLOURS[s]
        x_line, x_back = s * hl, s * (hl + gd)
        x_out = s * (hl + gd + t)
        bg.fill(GOAL_NET, pm.rect_m(x_line + s * line_px / (2 * pm.ppm), -gw, x_back, gw))
        bg.fill(col, pm.rect_m(x_line, gw, x_out, gw + t))  # wall at +y
        bg.fill(col, pm.rect_m(x_line, -gw - t, x_out, -gw))  # wall at -y
        bg.fill(col, pm.rect_m(x_back, -gw - t, x_out, gw + t))  # back wall


def draw_caption(bg: pygame.Surface, top: int, height: int, font: pygame.font.Font | None,
                 team_labels: Mapping[str, str]) -> None:
    """Caption strip from row ``top``, ``height`` px tall: each labelled team's colour swatch,
    name, label and attacking direction (no text when ``font`` is None)."""
    bg.fill(CAPTION_BG, pygame.Rect(0, top, bg.get_width(), height))
    if font is None:
        return
    attacks = {"blue": "attacks right", "yellow": "attacks left"}
    x, sw = 6, max(8, height - 8)
    for team in ("blue", "yellow"):
        if team not in team_labels:
            continue
        cy = top + height // 2
        bg.fill(TEAM_COLOURS[team], pygame.Rect(x, cy - sw // 2, sw, sw))
        text = font.render(f"{team}: {team_labels[team]} ({attacks[team]})", True, LINE_WHITE)
        bg.blit(text, text.get_rect(midleft=(x + sw + 4, cy)))
        x += sw + 4 + text.get_width() + 14
