"""Tests for ssl_marl.envs.render and its drawing modules (headless: SDL dummy video driver)."""

from __future__ import annotations

import os

os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")

import math  # noqa: E402
import warnings  # noqa: E402

import numpy as np  # noqa: E402
import pytest  # noqa: E402

from ssl_marl.envs import render_style as style  # noqa: E402
from ssl_marl.envs.animation import write_animation  # noqa: E402
from ssl_marl.envs.render import FieldRenderer  # noqa: E402
from ssl_marl.envs.render_style import BALL_ORANGE, BLUE, YELLOW  # noqa: E402
from ssl_marl.physics.field import FieldGeometry  # noqa: E402
from ssl_marl.physics.params import BallParams, RobotParams  # noqa: E402
from ssl_marl.physics.state import TeamState, WorldState, make_team_state, to_team_frame  # noqa: E402

CARPET = style.CARPET


def team(pos, heading):
    pos = np.asarray(pos, float).reshape(-1, 2)
    n = pos.shape[0]
    return make_team_state(pos, np.asarray(heading, float).reshape(n), np.zeros((n, 2)), np.zeros(n),
                           np.zeros(n, bool), np.ones(n, bool))


def world(blue=None, yellow=None, ball=(0.3, 0.2), t=0.0, ball_visible=True):
    return WorldState(t=t, ball_pos=np.array(ball, float), ball_vel=np.zeros(2),
                      blue=blue if blue is not None else TeamState.empty(),
                      yellow=yellow if yellow is not None else TeamState.empty(), ball_visible=ball_visible)


def renderer(field="div_a", **kw):
    return FieldRenderer(FieldGeometry.from_name(field), RobotParams(), BallParams(), **kw)


def px(frame, r, x, y):
    u, v = r.world_to_px(x, y)
    return tuple(int(c) for c in frame[v, u])


@pytest.mark.parametrize("field", ["div_a", "div_b"])
def test_frame_shape_dtype(field):
    f = FieldGeometry.from_name(field)
    r = renderer(field, width_px=960)
    fr = r.draw(world(team([[1.0, 1.0], [-2.0, 0.5]], [0.0, 1.0]), team([[2.0, -1.0]], [math.pi])),
                info_text="t=12.3 s  blue 1 - 0 yellow")
    assert fr.dtype == np.uint8 and fr.ndim == 3 and fr.shape[2] == 3
    assert fr.shape[1] == 960 and fr.shape == r.frame_shape
    aspect = (f.wall_half_width + style.OUTER_WALL_M) / (f.wall_half_length + style.OUTER_WALL_M)
    assert abs(fr.shape[0] / fr.shape[1] - aspect) < 0.01
    assert fr.flags.writeable
    # carpet covers the run-off area; the outer wall is dark; centre is on the half-way line
    hl, hw, bw = f.half_length, f.half_width, f.boundary_width
    assert px(fr, r, -hl - bw / 2, -hw - bw / 2) == CARPET  # (top-left holds the info text)
    assert px(fr, r, hl - 0.5, -hw + 0.5) == CARPET
    assert fr[0, 0].tolist() == list(style.WALL_DARK)
    assert px(fr, r, 0.0, 1.5) == (255, 255, 255)  # half-way line
    assert px(fr, r, 1.0, hw) == (255, 255, 255)  # touch line
    assert px(fr, r, hl, 1.0) == (255, 255, 255)  # goal line
    assert px(fr, r, hl - f.defense_depth, 0.5) == (255, 255, 255)  # defense area front line
    assert px(fr, r, f.center_circle_radius, 0.0) == (255, 255, 255)  # centre circle
    # goal back wall behind the +x goal line
    gx = hl + f.goal_depth + f.goal_wall_thickness / 2
    assert px(fr, r, gx, 0.0) == style.GOAL_COLOURS[+1]
    assert px(fr, r, -gx, 0.0) == style.GOAL_COLOURS[-1]
    # info text at the top-left changes pixels there
    assert (fr[2:20, 2:60] != np.array(style.WALL_DARK, np.uint8)).any()


def test_custom_field_and_pixels_per_metre():
    f = FieldGeometry(name="custom", length=4.0, width=3.0, goal_width=0.6, defense_width=1.0,
                      defense_depth=0.5, center_circle_radius=0.3, boundary_width=0.25)
    r = FieldRenderer(f, RobotParams(), BallParams(), pixels_per_metre=100.0)
    fr = r.draw(world(team([[0.5, 0.5]], [0.0])))
    assert fr.shape == (int(round(2 * (1.75 + style.OUTER_WALL_M) * 100)),
                        int(round(2 * (2.25 + style.OUTER_WALL_M) * 100)), 3)
    assert px(fr, r, f.half_length, -1.0) == (255, 255, 255)


@pytest.mark.parametrize("field", ["div_a", "div_b"])
def test_robot_pixels_in_team_colour(field):
    r = renderer(field, show_ids=False)
    b = team([[1.0, 1.0]], [0.3])
    y = team([[-1.5, -0.7]], [2.0])
    fr = r.draw(world(b, y, ball=(-3.0, 2.0)))
    empty = r.draw(world(ball=(-3.0, 2.0)))
    assert px(fr, r, 1.0, 1.0) == BLUE
    assert px(fr, r, -1.5, -0.7) == YELLOW
    assert px(empty, r, 1.0, 1.0) == CARPET
    # the back half of the body is team colour too; far away stays carpet
    back = np.array([1.0, 1.0]) - 0.5 * 0.09 * np.array([math.cos(0.3), math.sin(0.3)])
    assert px(fr, r, *back) == BLUE
    assert px(fr, r, 1.0 + 0.3, 1.0 + 0.3) == CARPET


def test_robot_with_id_keeps_team_colour_and_flat_front():
    r = renderer("div_b", pixels_per_metre=400.0, show_ids=True)
    fr = r.draw(world(team([[1.0, 1.0]], [0.0]), ball=(-3.0, 2.0)))
    u, v = r.world_to_px(1.0, 1.0)
    patch = fr[v - 30:v + 31, u - 30:u + 31].reshape(-1, 3)
    assert (patch == np.array(BLUE, np.uint8)).all(axis=1).sum() > 200
    # id text (white on blue) drawn on top
    assert (patch == 255).all(axis=1).sum() > 5
    # flat front: just beyond the face along the heading but inside the radius is not body colour
    assert px(fr, r, 1.0 + 0.087, 1.0) != BLUE
    assert px(fr, r, 1.0 - 0.087, 1.0) == BLUE  # round back


def test_team_frame_snapshot_drawn_in_field_frame():
    r = renderer("div_b", show_ids=False)
    w = world(team([[2.0, 1.0]], [0.0]), ball=(1.0, -1.0))
    a = r.draw(w)
    b = r.draw(to_team_frame(w, "yellow"))
    assert np.array_equal(a, b)


@pytest.mark.parametrize("field", ["div_a", "div_b"])
def test_ball_is_orange(field):
    r = renderer(field)
    fr = r.draw(world(ball=(0.3, 0.2)))
    assert px(fr, r, 0.3, 0.2) == BALL_ORANGE
    # minimum radius 3 px: neighbours 2 px away are orange too
    u, v = r.world_to_px(0.3, 0.2)
    for du, dv in ((2, 0), (-2, 0), (0, 2), (0, -2)):
        assert tuple(fr[v + dv, u + du]) == BALL_ORANGE
    hidden = r.draw(world(ball=(0.3, 0.2), ball_visible=False))
    assert px(hidden, r, 0.3, 0.2) != BALL_ORANGE  # hollow marker only


def test_ball_in_the_air_casts_a_shadow_and_is_drawn_higher_and_larger():
    from dataclasses import replace

    r = renderer("div_b")
    ground = world(ball=(0.3, 0.2))
    air = replace(ground, ball_height=0.5, ball_vz=1.0)
    fg, fa = r.draw(ground), r.draw(air)
    assert not np.array_equal(fg, fa)
    assert px(fa, r, 0.3, 0.2) == style.BALL_SHADOW  # shadow at the ground position
    lifted = 0.2 + 0.5 * style.BALL_LIFT_PER_M
    assert px(fa, r, 0.3, lifted) == BALL_ORANGE and px(fg, r, 0.3, lifted) != BALL_ORANGE
    assert (fa == BALL_ORANGE).all(axis=2).sum() > (fg == BALL_ORANGE).all(axis=2).sum()  # drawn larger
    # a team-frame snapshot keeps the height
    assert np.array_equal(r.draw(to_team_frame(air, "yellow")), fa)


def test_trails_mark_the_path_and_reset():
    r = renderer("div_b", trails=True, trail_length=50, show_ids=False)
    xs = np.linspace(-3.0, -1.0, 21)
    for i, x in enumerate(xs):
        fr = r.draw(world(team([[x, 2.0]], [0.0]), ball=(x, -2.0), t=0.1 * i))
    for x in (-2.8, -2.3, -1.7):
        assert px(fr, r, x, 2.0) != CARPET  # robot trail
        assert px(fr, r, x, -2.0) != CARPET  # ball trail
    r.reset_trails()
    fr = r.draw(world(team([[-1.0, 2.0]], [0.0]), ball=(-1.0, -2.0), t=5.0))
    assert px(fr, r, -2.3, 2.0) == CARPET
    # time going backwards (new episode) also clears the trails
    for i, x in enumerate(xs):
        r.draw(world(team([[x, 2.0]], [0.0]), t=0.1 * i))
    fr = r.draw(world(team([[2.0, -1.0]], [0.0]), t=0.0))
    assert px(fr, r, -2.3, 2.0) == CARPET
    # trails off: no path
    r2 = renderer("div_b", trails=False, show_ids=False)
    for x in xs:
        fr = r2.draw(world(team([[x, 2.0]], [0.0])))
    assert px(fr, r2, -2.3, 2.0) == CARPET


def test_trail_length_limits_history():
    r = renderer("div_b", trails=True, trail_length=5, show_ids=False)
    for i, x in enumerate(np.linspace(-3.0, 0.0, 31)):
        fr = r.draw(world(team([[x, 2.0]], [0.0]), t=0.1 * i))
    assert px(fr, r, -2.0, 2.0) == CARPET
    assert px(fr, r, -0.3, 2.0) != CARPET


def test_non_finite_positions_do_not_crash():
    r = renderer("div_b", trails=True)
    b = team([[np.nan, 0.0], [1e12, -1e12]], [0.0, np.inf])
    fr = r.draw(world(b, ball=(np.inf, 0.0)))
    assert fr.shape == r.frame_shape


def test_write_animation_gif_roundtrip(tmp_path):
    import imageio.v3 as iio

    r = renderer("div_b", width_px=200, show_ids=False)
    frames = [r.draw(world(team([[-3.0 + 0.5 * i, 0.0]], [0.1 * i]), ball=(0.0, -1.0 + 0.2 * i)))
              for i in range(6)]
    path = tmp_path / "anim.gif"
    write_animation(frames, path, fps=10)
    back = iio.imread(path, index=None)
    assert back.shape[0] == len(frames)
    assert back.shape[1:3] == frames[0].shape[:2]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["anim.gif"]  # no temp files left
    write_animation(frames[:3], str(path), fps=10)  # overwrite
    assert iio.imread(path, index=None).shape[0] == 3


def test_write_animation_errors(tmp_path):
    f = np.zeros((10, 12, 3), np.uint8)
    with pytest.raises(ValueError):
        write_animation([], tmp_path / "a.gif")
    with pytest.raises(ValueError):
        write_animation([f, np.zeros((10, 13, 3), np.uint8)], tmp_path / "a.gif")
    with pytest.raises(ValueError):
        write_animation([f], tmp_path / "a.avi")
    try:
        import imageio_ffmpeg  # noqa: F401
    except ImportError:
        with pytest.raises(RuntimeError, match="imageio-ffmpeg"):
            write_animation([f, f], tmp_path / "a.mp4")
    else:
        write_animation([f, f + 50], tmp_path / "a.mp4")
        assert (tmp_path / "a.mp4").stat().st_size > 0
    assert [p.name for p in tmp_path.iterdir() if "tmp" in p.name] == []


def test_human_mode_headless_does_not_raise():
    r = renderer("div_b", width_px=240, render_fps=1000)
    w = world(team([[1.0, 1.0]], [0.0]))
    r.show(w)
    r.show(r.draw(w))
    r.close()
    r.close()


def test_human_mode_falls_back_when_window_cannot_open(monkeypatch):
    import pygame

    def boom(*a, **k):
        raise pygame.error("No available video device")

    monkeypatch.setattr(pygame.display, "set_mode", boom)
    r = renderer("div_b", width_px=240, render_fps=1000)
    w = world(team([[1.0, 1.0]], [0.0]))
    with pytest.warns(RuntimeWarning, match="window"):
        r.show(w)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # warned once only
        r.show(w)
        fr = r.draw(w)
    assert not r.window_available
    assert fr.shape == r.frame_shape
    r.close()


def test_invalid_arguments():
    f = FieldGeometry.div_b()
    with pytest.raises(ValueError):
        FieldRenderer(f, RobotParams(), BallParams(), pixels_per_metre=-1.0)
    with pytest.raises(ValueError):
        FieldRenderer(f, RobotParams(), BallParams(), width_px=0)
    r = FieldRenderer(f, RobotParams(), BallParams())
    with pytest.raises(ValueError):
        r.show(np.zeros((4, 4), np.uint8))
