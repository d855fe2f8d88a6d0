"""Match pictures say who is who and stay legible at the match default size (480 px):
a caption strip names each team, goals are visible, robot numbers fit."""

from __future__ import annotations

import numpy as np
import pytest

from ssl_marl.envs import parallel_env
from ssl_marl.envs import render_style as style
from ssl_marl.envs.render import FieldRenderer
from ssl_marl.physics.field import FieldGeometry
from ssl_marl.physics.params import BallParams, RobotParams


def _renderer(**kw):
    return FieldRenderer(FieldGeometry.div_b(), RobotParams(), BallParams(), width_px=480, **kw)


def test_caption_strip_names_each_team_below_the_field():
    plain, cap = _renderer(), _renderer(team_labels={"blue": "learned skills", "yellow": "baseline skills"})
    assert cap.caption_height > 0 and cap.frame_shape[0] == plain.frame_shape[0] + cap.caption_height
    assert cap.world_to_px(1.0, 1.0) == plain.world_to_px(1.0, 1.0)  # field pixels unchanged
    env = parallel_env(n_blue=2, n_yellow=2, render_mode="rgb_array", render_width_px=480)
    env.reset(seed=0)
    frame = cap.draw(env.world_state())
    strip = frame[cap.field_height:].reshape(-1, 3)
    for colour in (style.BLUE, style.YELLOW, style.LINE_WHITE):  # swatches and text
        assert (strip == colour).all(axis=1).any(), colour
    with pytest.raises(ValueError, match="team_labels"):
        _renderer(team_labels={"red": "x"})


def test_goals_are_visible():
    r = _renderer()
    f = r.field
    frame = r.draw(_empty_world())
    for side in (+1, -1):
        u, v = r.world_to_px(side * (f.half_length + f.goal_depth / 2), 0.0)
        assert tuple(frame[v, u]) == style.GOAL_NET
    wall_px = max(f.goal_wall_thickness, style.MIN_GOAL_WALL_PX / r.ppm) * r.ppm
    assert wall_px >= style.MIN_GOAL_WALL_PX - 1e-9


def _empty_world():
    env = parallel_env(n_blue=1, n_yellow=1)
    env.reset(seed=0)
    return env.world_state()


def test_robot_numbers_fit_at_the_default_match_size():
    r = _renderer()
    assert r._robot_r_px >= style.MIN_ID_ROBOT_RADIUS_PX
    assert r._id_font.size("9")[1] <= 2 * r._robot_r_px + 4  # the digit fits on the body


def test_match_video_has_the_caption(tmp_path):
    import imageio.v3 as iio

    from ssl_marl.runners.match import play_match

    out = tmp_path / "m.gif"
    play_match(blue="learned", yellow="baseline", robots=2, seconds=0.5, render=out, render_fps=4,
               render_width_px=480, progress=False)
    frames = iio.imread(out, index=None)
    plain = _renderer()
    assert frames.shape[1] > plain.frame_shape[0]  # taller than the field alone: the caption strip
