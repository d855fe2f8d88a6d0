"""go-to-ball's ball-velocity state (go_to_ball/v2) and rolling-ball spawns."""

import math

import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

from ssl_marl.physics import FieldGeometry
from ssl_marl.physics.state import TeamState, WorldState, make_team_state, to_team_frame
from ssl_marl.skills import make_skill
from ssl_marl.skills.batched_features import go_to_ball_features_batch
from ssl_marl.skills.demos import go_to_ball_baseline_demos
from ssl_marl.skills.features import (GO_TO_BALL_NAMES, GO_TO_BALL_SPECS, GO_TO_BALL_V2_NAMES, go_to_ball_env_action,
                                      go_to_ball_features)
from ssl_marl.skills.learned import LearnedGoToBall
from ssl_marl.skills.registry import get_task
from ssl_marl.skills.wrappers import GoToBallEnv

from test_batched import _go_to_ball_policy, _skill_pair
from test_learned_skills import tiny_checkpoint

F = FieldGeometry.div_b()


def world(ball_vel, heading=0.7):
    ts = make_team_state([[1.0, -0.5]], [heading], [[0.3, 0.2]], [0.4], [False], [True])
    return to_team_frame(WorldState(t=0.0, ball_pos=np.array([2.0, 1.0]), ball_vel=np.asarray(ball_vel, float),
                                    blue=ts, yellow=TeamState.empty()), "blue")


def test_v2_state_is_the_paper_state_and_the_ball_velocity_in_the_robot_frame():
    w = world([1.5, -0.5], heading=math.pi / 2)
    v1, v2 = go_to_ball_features(w, 0, F), go_to_ball_features(w, 0, F, "ball_velocity")
    assert v1.shape == (14,) and v2.shape == (16,) and len(GO_TO_BALL_V2_NAMES) == 16
    np.testing.assert_array_equal(v2[:14], v1)
    # heading +y: the team frame's +x is the robot's -y, the team frame's -y its -x
    np.testing.assert_allclose(v2[14:], [-0.5, -1.5], atol=1e-6)
    assert GO_TO_BALL_V2_NAMES[:14] == GO_TO_BALL_NAMES
    with pytest.raises(ValueError, match="state"):
        go_to_ball_features(w, 0, F, "ball_speed")
    with pytest.raises(ValueError, match="state"):
        go_to_ball_env_action(np.zeros(3), "nonsense")


def test_v2_batched_features_equal_the_per_world_function():
    rng = np.random.default_rng(0)
    K = 6
    pos, hd = rng.uniform(-4, 4, (K, 2)), rng.uniform(-3, 3, K)
    vel, om = rng.uniform(-2, 2, (K, 2)), rng.uniform(-5, 5, K)
    bp, bv = rng.uniform(-4, 4, (K, 2)), rng.uniform(-4, 4, (K, 2))
    batch = go_to_ball_features_batch(pos, hd, vel, om, bp, F, bv)
    assert batch.shape == (K, 16)
    for i in range(K):
        ts = make_team_state([pos[i]], [hd[i]], [vel[i]], [om[i]], [False], [True])
        w = to_team_frame(WorldState(t=0.0, ball_pos=bp[i], ball_vel=bv[i], blue=ts, yellow=TeamState.empty()), "blue")
        np.testing.assert_allclose(batch[i], go_to_ball_features(w, 0, F, "ball_velocity"), atol=2e-6)


def test_registry_knows_both_state_forms():
    task = get_task("go_to_ball")
    assert task.spec_of("ball_velocity") == GO_TO_BALL_SPECS["ball_velocity"] == "go_to_ball/v2"
    assert task.names_of("ball_velocity")[0] == GO_TO_BALL_V2_NAMES
    assert task.names_of()[0] == GO_TO_BALL_NAMES


def test_v2_task_env_passes_the_gymnasium_checker_and_names_its_spec():
    env = GoToBallEnv(state="ball_velocity", rolling=0.5)
    check_env(env, skip_render_check=True)
    obs, _ = env.reset(seed=3)
    assert obs.shape == (16,) and env.spec_version == "go_to_ball/v2" and env.observation_space.contains(obs)


def test_rolling_spawns_move_the_ball_within_the_speed_range():
    env = GoToBallEnv(state="ball_velocity", rolling=1.0, rolling_speed=(1.0, 3.0))
    speeds = []
    for seed in range(20):
        env.reset(seed=seed)
        w = env.truth()
        speeds.append(float(np.hypot(*w.ball_vel)))
        d = float(np.hypot(*(w.ball_pos - w.team("blue").pos[0])))
        assert 0.9 <= d <= 4.01
    assert 0.9 <= min(speeds) and max(speeds) <= 3.0 and np.std(speeds) > 0.2
    still = GoToBallEnv(rolling=0.0)
    for seed in range(5):
        still.reset(seed=seed)
        assert np.hypot(*still.truth().ball_vel) < 1e-9
    half = GoToBallEnv(rolling=0.5)
    moving = 0
    for seed in range(40):
        half.reset(seed=seed)
        moving += np.hypot(*half.truth().ball_vel) > 0.1
    assert 8 <= moving <= 32


@pytest.mark.parametrize("kwargs", [{"rolling": -0.1}, {"rolling": float("nan")}, {"rolling": 2},
                                    {"rolling_speed": (3.0, 1.0)}, {"rolling_speed": (0.0, float("inf"))},
                                    {"rolling_speed": 2.0}, {"state": "velocity"}])
def test_bad_rolling_options_are_refused(kwargs):
    with pytest.raises(ValueError, match=next(iter(kwargs))):
        GoToBallEnv(**kwargs)


def test_v2_vector_env_matches_sync_vector_env_on_rolling_balls():
    kw = {"max_time_s": 2.0, "state": "ball_velocity", "rolling": 0.5}
    ends, _ = _skill_pair("go-to-ball", 4, 300, 5, kw, _go_to_ball_policy)
    assert ends >= 4


def test_learned_go_to_ball_reads_the_state_its_checkpoint_names(tmp_path):
    tiny_checkpoint(tmp_path / "v2.pt", spec="go_to_ball/v2", obs_dim=16)
    skill = make_skill("go_to_ball", "learned", F, checkpoint=tmp_path / "v2.pt")
    assert isinstance(skill, LearnedGoToBall) and skill.state == "ball_velocity"
    a1, a2 = skill.act(world([0.0, 0.0]), 0), skill.act(world([3.0, 0.0]), 0)
    assert a1.shape == (5,) and not np.array_equal(a1, a2)  # the ball's velocity changes the action
    tiny_checkpoint(tmp_path / "v1.pt")
    assert make_skill("go_to_ball", "learned", F, checkpoint=tmp_path / "v1.pt").state == "default"


def test_baseline_demos_are_successful_v2_episodes():
    demos = list(go_to_ball_baseline_demos(600, seed=1, state="ball_velocity", rolling=1.0))
    assert len(demos) == 600
    assert all(t.obs.shape == (16,) and np.all(np.abs(t.action) <= 1.0) for t in demos)
    ends = [t for t in demos if t.terminated or t.truncated]
    assert ends and all(t.info["is_success"] for t in ends)
