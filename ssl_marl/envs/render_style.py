"""Colours and drawn sizes of the top-down field pictures (:class:`ssl_marl.envs.render.FieldRenderer`).

Colours are RGB tuples (0-255). Sizes ending in ``_M`` are metres in the field frame,
``_PX`` pixels of the frame.
"""

from __future__ import annotations

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
TRAIL_WIDTH_M = 0.015  # drawn width of the trajectory polylines (m; at least 1 px)
ARC_POINTS = 20  # vertices on the round part of the robot outline
COORD_LIMIT = 20000.0  # clip pixel coordinates (far-off / inf positions must not overflow SDL)
MIN_GOAL_WALL_PX = 2  # goal walls are drawn at least this thick
MIN_ID_ROBOT_RADIUS_PX = 7.0  # with show_ids, robots are drawn at least this big so the number fits
MIN_ROBOT_RADIUS_PX = 3.0  # without ids, robots are drawn at least this big so they stay visible
MIN_BALL_RADIUS_PX = 4  # the ball is drawn at least this big (seen at 480 px width)
BALL_SHADOW = (15, 55, 20)  # shadow of a ball in the air, on the carpet under it
BALL_LIFT_PER_M = 1.0  # a ball in the air is drawn this many metres up the picture per metre of height
BALL_GROWTH_PER_M = 0.5  # ... and 1 + this x height (m) times its radius
