"""PettingZoo env: API compliance, determinism, referee, realism, bad input."""

import math
import pickle

import numpy as np
import pytest
from pettingzoo.test import api_test, parallel_api_test

from ssl_marl.envs import env as aec_env
from ssl_marl.envs import parallel_env
from ssl_marl.envs.observation import obs_names
from ssl_marl.physics import BallParams, RobotParams

FACE = RobotParams().front_distance + BallParams().radius


@pytest.mark.parametrize("kw", [dict(n_blue=1, n_yellow=0), dict(n_blue=3, n_yellow=3, field="div_b"),
                                dict(n_blue=11, n_yellow=11, field="div_a")])
# api_test resets with a dummy option key on purpose; the env warns that it ignores it.
@pytest.mark.filterwarnings("ignore:.*reset options. ignoring unknown key.*:UserWarning")
def test_pettingzoo_api(kw):
    parallel_api_test(parallel_env(**kw, max_time_s=1.0), num_cycles=100)
    api_test(aec_env(**kw, max_time_s=1.0), num_cycles=30)


def test_spaces_are_cached_and_documented():
    e = parallel_env(n_blue=2, n_yellow=3)
    assert e.observation_space("blue_0") is e.observation_space("yellow_2")
    assert e.action_space("blue_1") is e.action_space("blue_1")
    assert e.action_space("blue_0").shape == (5,)
    assert len(obs_names(10, 11)) == e.observation_space("blue_0").shape[0]
    obs, infos = e.reset(seed=1)
    assert set(obs) == set(e.possible_agents) == set(infos)
    assert e.state().shape == e.state_space.shape


def rollout(seed, steps=300, **kw):
    e = parallel_env(n_blue=3, n_yellow=3, randomize_reset=True, **kw)
    obs, _ = e.reset(seed=seed)
    rng = np.random.default_rng(123)
    traj = [np.concatenate([obs[a] for a in e.possible_agents])]
    for _ in range(steps):
        acts = {a: rng.uniform(-1, 1, 5).astype(np.float32) for a in e.agents}
        obs, rew, term, trunc, info = e.step(acts)
        traj.append(np.concatenate([obs[a] for a in e.possible_agents]))
        if not e.agents:
            break
    return np.array(traj)


def test_same_seed_same_trajectory_over_many_steps():
    a, b = rollout(7), rollout(7)
    assert np.array_equal(a, b)
    assert not np.array_equal(a, rollout(8))


def test_determinism_with_realism_on():
    a, b = rollout(3, realism="realistic"), rollout(3, realism="realistic")
    assert np.array_equal(a, b)


def test_reset_after_play_is_deterministic():
    e = parallel_env(n_blue=2, n_yellow=2, randomize_reset=True)
    o1, _ = e.reset(seed=5)
    for _ in range(50):
        e.step({a: np.ones(5, np.float32) for a in e.agents})
    o2, _ = e.reset(seed=5)
    for a in o1:
        assert np.array_equal(o1[a], o2[a])


def test_team_frame_symmetry():
    """A mirrored scene gives yellow the same observation blue had."""
    e = parallel_env(n_blue=1, n_yellow=1)
    obs, _ = e.reset(options={"robots": {"blue_0": (-1.0, 0.5, 0.3), "yellow_0": (1.0, -0.5, 0.3 + math.pi)},
                              "ball": {"pos": (0.0, 0.0)}})
    np.testing.assert_allclose(obs["blue_0"], obs["yellow_0"], atol=1e-5)
    assert obs["blue_0"][0] == pytest.approx(-1.0) and obs["blue_0"][7] == pytest.approx(1.0)


def test_reset_options_place_ball_and_robots():
    e = parallel_env(n_blue=1, n_yellow=1)
    e.reset(options={"ball": {"pos": (1.0, 2.0), "vel": (0.5, 0.0)}, "robots": {"yellow_0": (2.0, -1.0, 1.0)}})
    ws = e.world_state()
    np.testing.assert_allclose(ws.ball_pos, (1.0, 2.0))
    np.testing.assert_allclose(ws.ball_vel, (0.5, 0.0))
    np.testing.assert_allclose(ws.yellow.pos[0], (2.0, -1.0))
    assert ws.yellow.heading[0] == pytest.approx(1.0)
    assert not ws.ball_pos.flags.writeable


def test_goal_detection_scores_and_kickoff():
    e = parallel_env(n_blue=1, n_yellow=1)
    e.reset(options={"ball": {"pos": (4.3, 0.0), "vel": (3.0, 0.0)},
                     "robots": {"blue_0": (0.0, 1.0, 0.0), "yellow_0": (0.0, -1.0, 0.0)}})
    scored = False
    for _ in range(30):
        obs, rew, term, trunc, info = e.step({})
        if any(ev["type"] == "goal" for ev in info["blue_0"]["events"]):
            scored = True
            break
    assert scored
    assert rew["blue_0"] == 1.0 and rew["yellow_0"] == -1.0
    assert info["blue_0"]["score"] == {"blue": 1, "yellow": 0}
    assert not term["blue_0"]
    np.testing.assert_allclose(e.world_state().ball_pos, (0.0, 0.0), atol=1e-9)  # kickoff
    assert e.world_state().blue.pos[0, 0] < 0 < e.world_state().yellow.pos[0, 0]


def test_goal_terminates_when_configured():
    e = parallel_env(n_blue=1, n_yellow=1, after_goal="terminate")
    e.reset(options={"ball": {"pos": (-4.3, 0.0), "vel": (-3.0, 0.0)},
                     "robots": {"blue_0": (0.0, 1.0, 0.0), "yellow_0": (0.0, -1.0, 0.0)}})
    for _ in range(30):
        obs, rew, term, trunc, info = e.step({a: np.zeros(5, np.float32) for a in e.agents})
        if term.get("yellow_0"):
            break
    assert term["yellow_0"] and rew["yellow_0"] == 1.0 and e.agents == []


def test_ball_just_on_the_line_is_not_a_goal():
    e = parallel_env(n_blue=1, n_yellow=0)
    e.reset(options={"ball": {"pos": (4.5, 0.0)}, "robots": {"blue_0": (0.0, 0.0, 0.0)}})
    _, _, _, _, info = e.step({})
    assert info["blue_0"]["score"]["blue"] == 0


def test_ball_out_is_placed_inside_field():
    e = parallel_env(n_blue=1, n_yellow=0)
    e.reset(options={"ball": {"pos": (1.0, 2.9), "vel": (0.0, 2.0)}, "robots": {"blue_0": (1.0, 2.6, 0.0)}})
    seen = False
    for _ in range(30):
        _, _, _, _, info = e.step({})
        if any(ev["type"] == "ball_out" for ev in info["blue_0"]["events"]):
            seen = True
            break
    assert seen
    ws = e.world_state()
    assert e.field.in_field(ws.ball_pos, margin=0.1)
    assert np.hypot(*ws.ball_vel) == 0.0
    assert np.hypot(*(ws.blue.pos[0] - ws.ball_pos)) >= 0.5 - 1e-6


def test_truncation_at_max_time():
    e = parallel_env(n_blue=1, n_yellow=1, max_time_s=0.5)
    e.reset(seed=0)
    n = 0
    while e.agents:
        _, _, term, trunc, _ = e.step({})
        n += 1
    assert n == 30 and trunc["blue_0"] is True and term["blue_0"] is False


def test_shaped_reward_terms_in_infos():
    e = parallel_env(n_blue=1, n_yellow=1, reward_scales={"ball_progress": 1.0, "possession": 1.0})
    e.reset(options={"ball": {"pos": (0.0, 0.0), "vel": (2.0, 0.0)}})
    _, rew, _, _, info = e.step({})
    terms = info["blue_0"]["reward_terms"]
    assert set(terms) == {"goal", "ball_progress", "possession"}
    assert terms["ball_progress"] > 0 and info["yellow_0"]["reward_terms"]["ball_progress"] < 0
    assert rew["blue_0"] == pytest.approx(sum(terms.values()))


def test_kick_event_through_the_env():
    e = parallel_env(n_blue=1, n_yellow=0)
    e.reset(options={"ball": {"pos": (FACE, 0.0)}, "robots": {"blue_0": (0.0, 0.0, 0.0)}})
    _, _, _, _, info = e.step({"blue_0": np.array([0, 0, 0, 1, 1], np.float32)})
    kicks = [ev for ev in info["blue_0"]["events"] if ev["type"] == "kick"]
    assert kicks and kicks[0]["speed"] == pytest.approx(6.5)


def test_vision_noise_and_dropout_take_effect():
    e = parallel_env(n_blue=1, n_yellow=0, realism={"robot_pos_sigma": 0.01, "ball_dropout": 0.5})
    e.reset(seed=0, options={"ball": {"pos": (1.0, 0.0)}, "robots": {"blue_0": (0.0, 0.0, 0.0)}})
    errs, vis = [], []
    for _ in range(200):
        obs, *_ = e.step({})
        errs.append(obs["blue_0"][0] - e.world_state().blue.pos[0, 0])
        vis.append(obs["blue_0"][13])
    assert 0.005 < np.std(errs) < 0.02
    assert 0.3 < 1 - np.mean(vis) < 0.7


def test_observation_latency_delays_what_is_seen():
    e = parallel_env(n_blue=1, n_yellow=0, realism={"obs_latency_steps": 3})
    e.reset(options={"ball": {"pos": (2.0, 2.0)}, "robots": {"blue_0": (0.0, 0.0, 0.0)}})
    xs_true, xs_seen = [], []
    for _ in range(20):
        obs, *_ = e.step({"blue_0": np.array([1, 0, 0, 0, 0], np.float32)})
        xs_true.append(e.world_state().blue.pos[0, 0])
        xs_seen.append(obs["blue_0"][0])
    np.testing.assert_allclose(xs_seen[3:], xs_true[:-3])


def test_command_latency_delays_motion():
    e = parallel_env(n_blue=1, n_yellow=0, realism={"cmd_latency_steps": 2})
    e.reset(options={"ball": {"pos": (2.0, 2.0)}, "robots": {"blue_0": (0.0, 0.0, 0.0)}})
    speeds = []
    for _ in range(4):
        e.step({"blue_0": np.array([1, 0, 0, 0, 0], np.float32)})
        speeds.append(e.world_state().blue.vel[0, 0])
    assert speeds[0] == 0 and speeds[1] == 0 and speeds[2] > 0


def test_realtime_mode_misses_late_commands():
    import time

    e = parallel_env(n_blue=1, n_yellow=0, realtime=True)
    e.reset(options={"ball": {"pos": (2.0, 2.0)}, "robots": {"blue_0": (0.0, 0.0, 0.0)}})
    _, _, _, _, info = e.step({})
    assert not any(ev["type"] == "missed_deadline" for ev in info["blue_0"]["events"])
    time.sleep(0.05)  # a controller that takes 50 ms misses ~2-3 control ticks
    _, _, _, _, info = e.step({})
    missed = [ev for ev in info["blue_0"]["events"] if ev["type"] == "missed_deadline"]
    assert missed and missed[0]["steps"] >= 2
    assert e.world_state().t == pytest.approx((2 + missed[0]["steps"]) / 60.0)


@pytest.mark.parametrize("action,match", [
    (np.array([np.nan, 0, 0, 0, 0]), "blue_0"),
    (np.array([0, np.inf, 0, 0, 0]), "blue_0"),
    (np.zeros(3), "blue_0"),
])
def test_bad_actions_raise_naming_the_agent(action, match):
    e = parallel_env(n_blue=1, n_yellow=1)
    e.reset(seed=0)
    with pytest.raises(ValueError, match=match):
        e.step({"blue_0": action})


def test_unknown_agent_raises():
    e = parallel_env(n_blue=1, n_yellow=1)
    e.reset(seed=0)
    with pytest.raises(ValueError, match="blue_7"):
        e.step({"blue_7": np.zeros(5)})


@pytest.mark.parametrize("kw,field", [
    (dict(n_blue=12), "n_blue"), (dict(n_yellow=-1), "n_yellow"), (dict(n_blue=0, n_yellow=0), "at least 1"),
    (dict(field="div_z"), "field"), (dict(realism={"robot_pos_sigma": -0.1}), "robot_pos_sigma"),
    (dict(max_time_s=-5), "max_time_s"), (dict(realism={"ball_dropout": 1.5}), "ball_dropout"),
    (dict(reward_scales={"speed": 1.0}), "reward_scales"), (dict(bogus=1), "bogus"),
    (dict(render_mode="vr"), "render_mode"), (dict(n_blue=7, enforce_division_limit=True), "n_blue"),
])
def test_impossible_config_names_the_field(kw, field):
    with pytest.raises(ValueError, match=field):
        parallel_env(**kw)


def test_env_pickles():
    e = parallel_env(n_blue=2, n_yellow=2, field="div_a")
    e2 = pickle.loads(pickle.dumps(e))
    obs, _ = e2.reset(seed=0)
    assert len(obs) == 4 and e2.field.name == "div_a"


def test_rgb_render_both_divisions():
    for field in ("div_a", "div_b"):
        e = parallel_env(n_blue=2, n_yellow=2, field=field, render_mode="rgb_array", render_trails=True)
        e.reset(seed=0)
        e.step({})
        frame = e.render()
        assert frame.ndim == 3 and frame.shape[2] == 3 and frame.dtype == np.uint8
        e.close()


@pytest.mark.parametrize("nb,ny,k,m", [(6, 6, 10, 11), (1, 0, 10, 11), (0, 3, 2, 2), (3, 5, 1, 2), (4, 4, 0, 0)])
def test_vectorised_observations_match_per_team_reference(nb, ny, k, m):
    from ssl_marl.envs.observation import all_observations, team_observations

    e = parallel_env(n_blue=nb, n_yellow=ny, randomize_reset=True, obs_max_teammates=k, obs_max_opponents=m)
    e.reset(seed=1)
    rng = np.random.default_rng(0)
    for _ in range(10):
        e.step({a: rng.uniform(-1, 1, 5) for a in e.agents})
    ws = e.world_state()
    ref = np.concatenate([team_observations(ws, "blue", e.field, k, m), team_observations(ws, "yellow", e.field, k, m)])
    np.testing.assert_array_equal(all_observations(ws, e.field, k, m), ref)


def test_chip_observations_append_the_ball_in_air_to_the_v0_layout():
    """v1 (chip kicks): the v0 entries unchanged, then ball height and vertical velocity;
    the vectorised pass equals the per-team reference with the ball in the air."""
    from ssl_marl.envs.observation import all_observations, team_observations

    e = parallel_env(n_blue=2, n_yellow=3, chip_kicks=True, task="free_play")
    e.reset(seed=1, options={"robots": {"blue_0": (0.0, 0.0, 0.0)}, "ball": {"pos": (0.1015, 0.0)}})
    obs, *_ = e.step({"blue_0": np.array([0, 0, 0, -1, 1.0, 0.7])})
    for _ in range(5):
        obs, *_ = e.step({})
    ws = e.world_state()
    assert ws.ball_height > 0.1
    d = e.observation_space("blue_0").shape[0]
    for team in ("blue", "yellow"):
        ref = team_observations(ws, team, e.field, 10, 11, ball_air=True)
        np.testing.assert_array_equal(ref[:, :d - 2], team_observations(ws, team, e.field, 10, 11))
        np.testing.assert_array_equal(ref[:, d - 2:], np.float32([[ws.ball_height, ws.ball_vz]] * len(ref)))
    full = all_observations(ws, e.field, 10, 11, ball_air=True)
    np.testing.assert_array_equal(full[:, :d - 2], all_observations(ws, e.field, 10, 11))
    np.testing.assert_array_equal(full[:, d - 2:], np.float32([[ws.ball_height, ws.ball_vz]] * len(full)))
    np.testing.assert_array_equal(np.stack([obs[a] for a in e.possible_agents]), full)


def test_observation_slots_sorted_and_masked():
    e = parallel_env(n_blue=3, n_yellow=1)
    obs, _ = e.reset(options={"robots": {"blue_0": (0.0, 0.0, 0.0), "blue_1": (2.0, 0.0, 0.0),
                                         "blue_2": (1.0, 0.0, 0.0), "yellow_0": (-1.0, 1.0, 0.0)},
                              "ball": {"pos": (0.0, 2.0)}})
    o = obs["blue_0"]
    mates = o[21:21 + 7 * 10].reshape(10, 7)
    assert mates[0, 0] == 1 and mates[0, 1] == pytest.approx(1.0)  # nearest first
    assert mates[1, 0] == 1 and mates[1, 1] == pytest.approx(2.0)
    assert np.all(mates[2:] == 0)
    opps = o[21 + 70:].reshape(11, 7)
    assert opps[0, 0] == 1 and opps[0, 1:3] == pytest.approx([-1.0, 1.0]) and np.all(opps[1:] == 0)
