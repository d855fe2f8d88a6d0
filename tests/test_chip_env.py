"""The env's v1 layout (``chip_kicks=True``): the chip action entry, the ball's height in
the observation, the goal rule (at most 0.15 m since the last touch), bad chip commands,
the PettingZoo checkers, and the default (v0) shapes unchanged."""

from __future__ import annotations

import math

import numpy as np
import pytest

from ssl_marl.envs import env as aec_env
from ssl_marl.envs import parallel_env
from ssl_marl.envs.actions import chip_angles, make_action, scale_actions
from ssl_marl.envs.batched_env import BatchedSSLEnv
from ssl_marl.envs.observation import BALL_AIR_NAMES, obs_dim, obs_names, observation_bounds
from ssl_marl.envs.referee import GOAL_MAX_HEIGHT_M, judge
from ssl_marl.physics.field import FieldGeometry
from ssl_marl.physics.params import BallParams, RobotParams
from ssl_marl.physics.state import TeamState, WorldState

#: blue_0 at (x, 0) facing +x with the ball on its kicker face
FACE = 0.08 + 0.0215


def _on_face(x: float, others: dict | None = None) -> dict:
    robots = {"blue_0": (x, 0.0, 0.0), **(others or {})}
    return {"robots": robots, "ball": {"pos": (x + FACE, 0.0)}}


def _kick(chip: float | None, kick: float = 1.0) -> np.ndarray:
    """A (6,) kick action; chip None: a flat kick (chip entry -1)."""
    return make_action(kick=kick, chip=-1.0 if chip is None else chip)


def _idle(dim: int) -> np.ndarray:
    return np.zeros(dim, np.float32)


def test_default_env_shapes_are_unchanged():
    e = parallel_env()
    assert e.action_space("blue_0").shape == (5,)
    assert e.observation_space("blue_0").shape == (obs_dim(10, 11),) == (168,)
    assert e.metadata["name"] == "ssl_marl_v0" and not e.config.robot.kick_on_contact
    obs, _ = e.reset(seed=0)
    assert obs["blue_0"].shape == (168,)
    e.step({a: np.zeros(5) for a in e.agents})
    with pytest.raises(ValueError, match=r"shape \(5,\)"):
        e.step({"blue_0": np.zeros(6)})


def test_chip_env_layout():
    e = parallel_env(chip_kicks=True)
    assert e.action_space("blue_0").shape == (6,)
    assert e.observation_space("blue_0").shape == (170,)
    assert e.metadata["name"] == "ssl_marl_v1" and e.config.robot.kick_on_contact
    assert obs_names(10, 11, True)[-2:] == list(BALL_AIR_NAMES)
    lo, hi = observation_bounds(e.field, e.config.robot, 10, 11, e.config.ball)
    assert lo[-2:].tolist() == [0.0, -6.5] and hi[-1] == pytest.approx(6.5)
    assert hi[-2] == pytest.approx(6.5 ** 2 / (2 * 9.81), rel=1e-6)
    # the v0 part of the bounds is unchanged
    lo0, hi0 = observation_bounds(e.field, e.config.robot, 10, 11)
    np.testing.assert_array_equal(lo[:-2], lo0)
    np.testing.assert_array_equal(hi[:-2], hi0)
    with pytest.raises(ValueError, match="chip_kicks"):
        parallel_env(chip_kicks=1)


def test_chip_angles_scale_and_clip():
    rp = RobotParams()
    a = np.array([[0, 0, 0, -1, 1, 0.5], [0, 0, 0, -1, 1, -0.3], [0, 0, 0, -1, 1, 7.0], [0, 0, 0, -1, 1, -9.0]])
    np.testing.assert_allclose(chip_angles(a, rp), [0.5 * rp.chip_angle_max, 0.0, rp.chip_angle_max, 0.0])
    # scale_actions reads the first five entries only
    for x, y in zip(scale_actions(a, rp), scale_actions(a[:, :5], rp)):
        np.testing.assert_array_equal(x, y)


def _kick_past_robot(chip: float | None, steps: int = 50):
    """blue_0 at x = 0 kicks at full strength towards yellow_0 standing at x = 1 m."""
    e = parallel_env(chip_kicks=True, n_blue=1, n_yellow=1, task="free_play")
    obs, _ = e.reset(seed=0, options=_on_face(0.0, {"yellow_0": (1.0, 0.0, math.pi)}))
    assert obs["blue_0"][-2:].tolist() == [0.0, 0.0]
    e.step({"blue_0": _kick(chip), "yellow_0": _idle(6)})
    heights, xs = [], []
    for _ in range(steps):
        obs, *_ = e.step({"blue_0": _idle(6), "yellow_0": _idle(6)})
        ws = e.world_state()
        heights.append(ws.ball_height)
        xs.append(float(ws.ball_pos[0]))
        assert obs["blue_0"][-2] == np.float32(ws.ball_height) and obs["blue_0"][-1] == np.float32(ws.ball_vz)
    return e, np.array(xs), np.array(heights)


def test_a_chip_clears_a_robot_a_flat_kick_hits_it():
    e, xs, hs = _kick_past_robot(chip=1.0)
    assert hs.max() > 1.0  # 60 deg at 6.5 m/s: apex 1.6 m
    assert xs.max() > 2.0  # the ball flew over the robot at x = 1 m
    np.testing.assert_allclose(e.world_state().yellow.pos[0], (1.0, 0.0), atol=1e-9)  # never touched
    e, xs, hs = _kick_past_robot(chip=None, steps=30)
    assert hs.max() == 0.0
    assert xs.max() < 1.0  # stopped by the robot at x = 1 m
    assert e.world_state().yellow.pos[0, 0] > 1.0 + 1e-4  # the ball pushed it


def test_chip_value_out_of_range_is_clipped():
    def run(chip):
        _, xs, hs = _kick_past_robot(chip, steps=20)
        return xs, hs

    for big, nominal in ((5.0, 1.0), (-7.0, None)):
        a, b = run(big), run(nominal)
        np.testing.assert_array_equal(a[0], b[0])
        np.testing.assert_array_equal(a[1], b[1])


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_bad_chip_commands_are_refused_naming_the_agent(bad):
    e = parallel_env(chip_kicks=True, n_blue=1, n_yellow=2)
    e.reset(seed=0)
    a = {ag: _idle(6) for ag in e.agents}
    a["yellow_1"] = np.array([0, 0, 0, -1, 1, bad])
    with pytest.raises(ValueError, match="agent 'yellow_1' contains NaN or inf"):
        e.step(a)
    b = BatchedSSLEnv(2, n_blue=1, n_yellow=2, chip_kicks=True)
    b.reset(seed=0)
    arr = np.zeros((2, 3, 6))
    arr[1, 2, 5] = bad
    with pytest.raises(ValueError, match="world 1: action for agent 'yellow_1' contains NaN or inf"):
        b.step(arr)
    view = b.world_view(0)
    view.reset(seed=0)
    with pytest.raises(ValueError, match="agent 'yellow_1' contains NaN or inf"):
        view.step({"yellow_1": np.array([0, 0, 0, -1, 1, bad])})


def _shot(chip: float | None, batched: bool = False):
    """blue_0 1.4 m in front of the yellow goal kicks at it (match task, after_goal
    terminate); returns the events (single env) or the info arrays (batched)."""
    opts = _on_face(3.0)
    cfg = dict(chip_kicks=True, n_blue=1, n_yellow=0, after_goal="terminate")
    if batched:
        b = BatchedSSLEnv(1, **cfg)
        b.reset(seed=0, options=opts)
        _, _, term, _, info = b.step(_kick(chip)[None, None, :])
        goals = outs = 0
        for _ in range(60):
            _, _, term, _, info = b.step(np.zeros((1, 1, 6)))
            goals, outs = goals + int(info["goal"][0]), outs + int(info["ball_out"][0])
            if outs or goals:
                break
        return goals, outs
    e = parallel_env(**cfg)
    e.reset(seed=0, options=opts)
    events = []
    a = {"blue_0": _kick(chip)}
    for _ in range(60):
        _, _, term, _, info = e.step(a)
        events += info["blue_0"]["events"]
        a = {"blue_0": _idle(6)}
        if term["blue_0"] or any(ev["type"] == "ball_out" for ev in events):
            break
    return events, e


def test_goal_rule_a_chip_arriving_high_is_ball_out_a_flat_shot_scores():
    events, e = _shot(chip=0.5)  # 30 deg: 0.5 m high at the goal line
    types = [ev["type"] for ev in events]
    assert "goal" not in types and "ball_out" in types
    assert e.score == {"blue": 0, "yellow": 0}
    events, e = _shot(chip=None)
    assert [ev["type"] for ev in events].count("goal") == 1 and e.score["blue"] == 1
    assert _shot(0.5, batched=True) == (0, 1)
    assert _shot(None, batched=True) == (1, 0)


def _in_goal_state(max_height: float, height: float = 0.0) -> WorldState:
    f = FieldGeometry.div_b()
    empty = TeamState.empty()
    return WorldState(t=0.0, ball_pos=np.array([f.half_length + 0.05, 0.0]), ball_vel=np.zeros(2), blue=empty,
                      yellow=empty, ball_height=height, ball_max_height=max_height)


def test_judge_goal_only_at_most_0_15_m_since_the_last_touch():
    f, r = FieldGeometry.div_b(), BallParams().radius
    assert GOAL_MAX_HEIGHT_M == 0.15
    assert judge(_in_goal_state(0.0), f, r).goal_for == "blue"
    assert judge(_in_goal_state(0.15), f, r).goal_for == "blue"  # at most 150 mm: a goal
    call = judge(_in_goal_state(0.151), f, r)
    assert call.goal_for is None and call.ball_out and call.placement is not None
    # a ball that flew high but was touched since (its maximum restarts) rolls in: a goal
    assert judge(_in_goal_state(0.02, height=0.0), f, r).goal_for == "blue"


def test_a_chip_touched_by_a_robot_after_its_flight_counts_from_the_touch():
    """The highest point restarts at a robot touch: a ball that flew high, landed and
    rolled into a robot's armed kicker (kick on contact) has ``ball_max_height`` 0 again."""
    e = parallel_env(chip_kicks=True, n_blue=1, n_yellow=0, task="free_play")
    e.reset(seed=0, options=_on_face(-3.0))
    e.step({"blue_0": _kick(0.6, kick=0.6)})
    for _ in range(60):
        e.step({"blue_0": _idle(6)})
    ws = e.world_state()
    assert ws.ball_max_height > GOAL_MAX_HEIGHT_M and ws.ball_height == 0.0 and ws.ball_vel[0] > 0.3
    # a robot ahead of the rolling ball, facing it, kicker armed
    e.place_robots(np.array([[ws.ball_pos[0] + FACE + 0.06, 0.0, math.pi]]))
    kicked = False
    for _ in range(30):
        _, _, _, _, info = e.step({"blue_0": _kick(None, kick=0.3)})
        if any(ev["type"] == "kick" for ev in info["blue_0"]["events"]):
            kicked = True
            break
    assert kicked and e.world_state().ball_max_height == 0.0


@pytest.mark.filterwarnings("ignore:.*reset options. ignoring unknown key.*:UserWarning")  # api_test's junk option
def test_pettingzoo_checkers_pass_with_chip_kicks():
    from pettingzoo.test import api_test, parallel_api_test

    parallel_api_test(parallel_env(chip_kicks=True, n_blue=2, n_yellow=2, max_time_s=0.5), num_cycles=40)
    api_test(aec_env(chip_kicks=True, n_blue=1, n_yellow=1, max_time_s=0.3), num_cycles=20)
    b = BatchedSSLEnv(2, chip_kicks=True, n_blue=1, n_yellow=1, max_time_s=0.3)
    b.reset(seed=0)
    parallel_api_test(b.world_view(1), num_cycles=20)


def test_observations_stay_inside_the_bounds_through_a_chip():
    e = parallel_env(chip_kicks=True, n_blue=1, n_yellow=1, task="free_play")
    obs, _ = e.reset(seed=0, options=_on_face(-2.0))
    a = {"blue_0": _kick(1.0), "yellow_0": _idle(6)}
    space = e.observation_space("blue_0")
    for _ in range(90):
        obs, *_ = e.step(a)
        a = {"blue_0": _idle(6), "yellow_0": _idle(6)}
        assert all(space.contains(o) for o in obs.values())


def test_camera_reports_a_ball_in_the_air_projected_onto_the_ground_plane():
    from ssl_marl.envs.camera import CAMERA_HEIGHT_M, CameraRig

    f, r = FieldGeometry.div_b(), BallParams().radius
    rig = CameraRig(f, r)
    np.testing.assert_array_equal(rig.camera_over(np.array([1.0, -0.5])), (f.half_length / 2, -f.half_width / 2))
    p = np.array([0.25, 0.4])
    assert rig.seen_position(p, 0.0) is not None and np.array_equal(rig.seen_position(p, 0.0), p)
    cam = rig.camera_over(p)
    z = 0.5
    seen = rig.seen_position(p, z)
    # on the ray from the camera through the ball's centre, at the ground-ball plane
    np.testing.assert_allclose((seen - cam) * (CAMERA_HEIGHT_M - r - z), (p - cam) * (CAMERA_HEIGHT_M - r))
    assert np.hypot(*(seen - cam)) > np.hypot(*(p - cam))  # displaced away from the camera


def test_realism_vision_reports_no_height_and_the_camera_position():
    from ssl_marl.envs.camera import CameraRig

    # realism on (a tiny heading noise), no ball noise, no latency: the ball as the camera sees it
    e = parallel_env(chip_kicks=True, n_blue=1, n_yellow=0, task="free_play", realism={"robot_angle_sigma": 1e-6})
    e.reset(seed=0, options=_on_face(-2.0))
    obs, *_ = e.step({"blue_0": _kick(1.0)})
    rig = CameraRig(e.field, e.config.ball.radius)
    flying = 0
    for _ in range(40):
        obs, *_ = e.step({"blue_0": _idle(6)})
        truth, seen = e.world_state(), e.vision_state()
        assert seen.ball_height == 0.0 and seen.ball_vz == 0.0
        assert obs["blue_0"][-2:].tolist() == [0.0, 0.0]
        np.testing.assert_array_equal(seen.ball_pos, rig.seen_position(truth.ball_pos, truth.ball_height))
        flying += truth.ball_height > 0.3
    assert flying > 10
    # without realism the observation holds the true height
    e = parallel_env(chip_kicks=True, n_blue=1, n_yellow=0, task="free_play")
    e.reset(seed=0, options=_on_face(-2.0))
    e.step({"blue_0": _kick(1.0)})
    obs, *_ = e.step({"blue_0": _idle(6)})
    assert obs["blue_0"][-2] == np.float32(e.world_state().ball_height) > 0.0


@pytest.mark.parametrize("chip", [0.1, 0.3, 0.5, 0.75, 1.0])
def test_chip_through_the_env_flies_as_the_drag_free_projectile(chip):
    """Five launch angles through the env's action: the first touchdown and the apex
    within 2 % of the drag-free projectile (speed 4 m/s, elevation chip x 60 deg)."""
    from ssl_marl.physics.ball_flight import projectile_reference

    e = parallel_env(chip_kicks=True, n_blue=1, n_yellow=0, task="free_play")
    e.reset(seed=0, options=_on_face(-4.0))
    start = np.array(e.world_state().ball_pos)
    speed = 4.0
    e.step({"blue_0": _kick(chip, kick=speed / e.config.robot.kick_speed_max)})
    touchdown = None
    apex = 0.0
    for _ in range(120):
        apex = max(apex, e.world_state().ball_max_height)
        if e.physics.touchdowns:
            touchdown = np.array(e.physics.touchdowns[0])
            break
        e.step({"blue_0": _idle(6)})
    assert touchdown is not None
    dist_ref, apex_ref = projectile_reference(speed, chip * e.config.robot.chip_angle_max, e.config.ball.gravity)
    assert np.hypot(*(touchdown - start)) == pytest.approx(dist_ref, rel=0.02)
    assert apex == pytest.approx(apex_ref, rel=0.02)


def test_the_tracker_runs_on_the_chip_env():
    from ssl_marl.envs import parallel_env
    from ssl_marl.envs.tracking import with_tracker

    env = with_tracker(parallel_env(n_blue=1, n_yellow=1, chip_kicks=True, realism="realistic"), "on")
    env.reset(seed=3)
    for _ in range(10):
        env.step({a: np.array([0.5, 0.0, 0.0, 1.0, 0.5, 0.5], np.float32) for a in env.possible_agents})
    assert np.isfinite(env.vision_state("blue").ball_pos).all()
