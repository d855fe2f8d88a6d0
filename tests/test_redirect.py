"""The redirect skill and its task ssl_marl/Redirect-v0: Gymnasium's checker,
determinism under a seed, the hand-coded redirect on constructed scenes, bad actions."""

import math

import gymnasium
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import ssl_marl  # noqa: F401  (registers the tasks)
from ssl_marl.skills.registry import get_skill
from ssl_marl.skills.redirect import RedirectBaseline, open_goal_target, redirect_residual_action
from ssl_marl.skills.redirect_task import RedirectEnv, redirect_skill_action


def run_episode(env, seed, options=None):
    skill = RedirectBaseline(env.field, env.robot_params, env.ball_params)
    obs, _ = env.reset(seed=seed, options=options)
    observations = [obs]
    while True:
        obs, r, term, trunc, info = env.step(redirect_skill_action(env, skill))
        observations.append(obs)
        if term or trunc:
            return info, np.array(observations)


def test_registered_with_kick_on_contact():
    skill = get_skill("redirect")
    assert skill.task.env_id == "ssl_marl/Redirect-v0" and skill.baseline is RedirectBaseline
    env = gymnasium.make("ssl_marl/Redirect-v0").unwrapped
    assert env.robot_params.kick_on_contact and env.observation_space.shape == (14,)
    env.close()


def test_gymnasium_check_env():
    check_env(gymnasium.make("ssl_marl/Redirect-v0").unwrapped, skip_render_check=True)


def test_same_seed_same_episode():
    a = run_episode(RedirectEnv(), 3)
    b = run_episode(RedirectEnv(), 3)
    assert a[0]["failure_reason"] == b[0]["failure_reason"] and np.array_equal(a[1], b[1])


@pytest.mark.parametrize("deflection", [0.3, 0.7, 1.1])
def test_baseline_redirects_a_pass_into_the_goal(deflection):
    """A 3.5 m/s pass from 3 m at the given deflection, no goalie: the robot sends it in."""
    env = RedirectEnv(goalie=None)
    robot = np.array([1.5, 0.5])
    to_goal = math.atan2(-robot[1], env.field.half_length - robot[0])
    ball = robot + 3.0 * np.array([math.cos(to_goal + deflection), math.sin(to_goal + deflection)])
    vel = 3.5 * (robot - ball) / 3.0
    for seed in range(2):
        info, _ = run_episode(env, seed, {"robot_pose": (*robot, to_goal), "ball_pos": tuple(ball),
                                          "ball_vel": tuple(vel)})
        assert info["is_success"], info


def test_target_avoids_the_keeper():
    from tests.test_skills import scene

    env = RedirectEnv(goalie=None)
    w = scene(robot=(2.0, 0.0, 0.0), ball=(1.0, 1.0))
    ws = w.__class__(**{**w.__dict__, "yellow": w.blue.__class__(
        pos=np.array([[4.3, 0.2]]), heading=np.array([math.pi]), vel=np.zeros((1, 2)), omega=np.zeros(1),
        ball_on_dribbler=np.zeros(1, bool), kick_ready=np.ones(1, bool))})
    tgt = open_goal_target(np.array([2.0, 0.0]), ws, env.field, env.robot_params, env.ball_params)
    assert tgt[0] == env.field.half_length and tgt[1] < 0  # the keeper stands left of centre


def test_bad_actions_raise():
    env = RedirectEnv()
    env.reset(seed=0)
    with pytest.raises(ValueError, match="NaN"):
        env.step(np.array([np.nan, 0.0, 0.0]))
    with pytest.raises(ValueError, match="shape"):
        env.step(np.zeros(2))
    with pytest.raises(ValueError, match="action_form"):
        RedirectEnv(action_form="bogus")
    with pytest.raises(ValueError, match="unknown option"):
        env.reset(seed=0, options={"bogus": 1})


def test_residual_zero_is_the_baseline():
    assert np.allclose(redirect_residual_action(np.array([0.2, -0.3, 0.5]), np.zeros(3)), [0.2, -0.3, 0.5])
    env = RedirectEnv(action_form="residual")
    assert env.spec_version == "redirect/v2"
    env.reset(seed=1)
    assert np.allclose(env.from_direct(env.base_action()), 0.0)


def test_the_kept_contact_point_follows_the_ball_path_as_seen():
    """The planner keeps its contact point while the ball's path stays near it, moved
    onto the path as now seen (same distance along it): a path seen 3 cm to the side a
    step later moves the contact point (and the robot's spot) 3 cm with it."""
    from tests.test_skills import scene

    env = RedirectEnv(goalie=None)
    planner = RedirectBaseline(env.field, env.robot_params, env.ball_params)
    first = planner.contact_plan(scene(robot=(2.5, -0.5, 0.0), ball=(2.5, 1.5), ball_vel=(0.0, -3.0)), 0)
    contact = planner._contact.copy()
    assert first is not None and abs(contact[0] - 2.5) < 1e-9
    later = planner.contact_plan(scene(robot=(2.5, -0.5, 0.0), ball=(2.53, 1.45), ball_vel=(0.0, -3.0)), 0)
    assert np.allclose(planner._contact, [2.53, contact[1]]), planner._contact
    assert np.allclose(later[0], first[0] + [0.03, 0.0], atol=2e-3) and abs(later[1] - first[1]) < 0.01
