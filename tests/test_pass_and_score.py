"""The 2v0 pass-then-score drill (ssl_marl/envs/tasks/pass_and_score.py) on constructed scenes."""

from __future__ import annotations

import numpy as np
import pytest

from ssl_marl.envs.tasks.pass_and_score import PassAndScoreEnv, PassAndScoreParams

IDLE = {"blue_0": np.zeros(5), "blue_1": np.zeros(5)}


def _run(env: PassAndScoreEnv, max_ticks: int = 400) -> tuple[float, dict]:
    total, infos = 0.0, {}
    for _ in range(max_ticks):
        _, rew, term, trunc, infos = env.step(IDLE)
        total += rew["blue_0"]
        assert rew["blue_0"] == rew["blue_1"]            # team-shared
        if not env.agents:
            break
    return total, infos["blue_0"]


def _scene(env: PassAndScoreEnv, passer, receiver, ball, vel) -> None:
    env.engine.place_robots(np.array([[*passer, 0.0], [*receiver, np.pi]]))
    env.engine.place_ball(np.array(ball, float), np.array(vel, float))
    env.task.start(env.engine)


def test_start_scene_has_the_ball_on_the_passers_dribbler_and_is_deterministic() -> None:
    env = PassAndScoreEnv()
    obs, infos = env.reset(seed=5)
    ws = env.engine.world_state()
    assert infos["blue_0"]["decision"] and infos["blue_0"]["elapsed_s"] == 0.0
    assert np.linalg.norm(ws.ball_pos - ws.blue.pos[0]) < 0.13
    assert np.linalg.norm(ws.blue.pos[1] - ws.blue.pos[0]) >= 1.5
    obs2, _ = PassAndScoreEnv().reset(seed=5)
    np.testing.assert_array_equal(obs["blue_0"], obs2["blue_0"])
    assert env.observation_space("blue_0").contains(obs["blue_0"])


def test_a_pass_then_a_shot_into_the_goal_is_a_success_with_the_documented_rewards() -> None:
    env = PassAndScoreEnv()
    env.reset(seed=0)
    _scene(env, passer=(0.0, 0.0), receiver=(2.0, 0.0), ball=(0.5, 0.0), vel=(3.0, 0.0))
    d0, total = env.task._d, 0.0
    for _ in range(60):
        _, rew, _, _, _ = env.step(IDLE)
        total += rew["blue_0"]
        if env.task.passed:
            break
    assert env.task.passed and env.agents
    # shaped pass reward: the ball-to-receiver distance gained, plus the pass bonus
    assert total == pytest.approx(d0 - env.task._d + 1.0, abs=1e-6)
    assert env.task._d < 0.15
    # now shoot: ball from in front of the receiver into the +x goal
    env.engine.place_robots(np.array([[0.0, 0.0, 0.0], [2.0, 1.0, np.pi]]))
    env.engine.place_ball(np.array([3.0, 0.0]), np.array([4.0, 0.0]))
    env.task._g = float(np.linalg.norm(np.array([3.0, 0.0]) - env.task._goal))
    total, info = _run(env, 120)
    assert info["outcome"] == "goal" and info["success"] == 1.0 and info["passed"] == 1.0
    assert total == pytest.approx(5.0 + 1.5 + env.engine.config.ball.radius, abs=0.1)


def test_a_direct_goal_without_a_pass_is_not_a_success() -> None:
    env = PassAndScoreEnv()
    env.reset(seed=0)
    _scene(env, passer=(2.0, 0.0), receiver=(0.0, 2.0), ball=(3.0, 0.0), vel=(4.0, 0.0))
    _, info = _run(env, 120)
    assert info["outcome"] == "goal_without_pass" and info["success"] == 0.0 and info["passed"] == 0.0


def test_ball_out_terminates_and_time_truncates() -> None:
    env = PassAndScoreEnv()
    env.reset(seed=0)
    _scene(env, passer=(0.0, 0.0), receiver=(1.0, -2.0), ball=(0.0, 2.5), vel=(0.0, 3.0))
    _, info = _run(env, 120)
    assert info["outcome"] == "ball_out"
    short = PassAndScoreEnv(PassAndScoreParams(max_time_s=0.5))
    short.reset(seed=1)
    n = 0
    while short.agents:
        _, _, term, trunc, info = short.step(IDLE)
        n += 1
    assert n == 30 and trunc["blue_0"] and not term["blue_0"] and info["blue_0"]["outcome"] == "time"


def test_parallel_api() -> None:
    from pettingzoo.test import parallel_api_test

    parallel_api_test(PassAndScoreEnv(PassAndScoreParams(max_time_s=0.5)), num_cycles=40)
