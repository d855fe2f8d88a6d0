"""Chip passes: the kick from the flight model clears a blocker midway and lands short
of the receiver; the chip-pass task (``ssl_marl/ChipPass-v0``) passes the Gymnasium
checker, the hand-coded chip over its blocker is completed where a flat kick is
blocked, and its action mapping, features and errors are what the docs say."""

import math

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import ssl_marl  # noqa: F401  (registers the envs)
from ssl_marl.physics.ball_flight import flight_height, projectile_reference
from ssl_marl.physics.field import FieldGeometry
from ssl_marl.physics.params import BallParams, RobotParams
from ssl_marl.physics.state import TeamState, WorldState
from ssl_marl.skills import get_skill
from ssl_marl.skills.chip_pass import (ChipPassBaseline, LearnedChipPass, chip_kick, chip_pass_task_action,
                                       expand_chip_pass_action, lane_blocker)
from ssl_marl.skills.chip_pass_task import ChipPassEnv, chip_pass_skill_action

RP, BP = RobotParams(), BallParams()


@pytest.mark.parametrize("receiver", [3.0, 4.0, 4.5])
def test_chip_kick_clears_the_blocker_and_lands_short(receiver):
    k = chip_kick(receiver / 2, receiver, RP, BP)
    body = RP.radius + BP.radius
    for x in (receiver / 2 - body, receiver / 2, receiver / 2 + body):
        assert flight_height(x, k.speed, k.angle, BP.gravity) > RP.height
    landing, _ = projectile_reference(k.speed, k.angle, BP.gravity)
    assert math.isclose(landing, k.landing) and receiver / 2 + body < landing <= receiver - 0.6
    assert k.speed <= RP.kick_speed_max and k.angle <= RP.chip_angle_max


def test_no_chip_raises():
    with pytest.raises(ValueError, match="no chip"):
        chip_kick(0.3, 0.6, RP, BP)


def _world(opponents):
    n = len(opponents)
    blue = TeamState(pos=np.array([[0.0, 0.0]]), heading=np.zeros(1), vel=np.zeros((1, 2)), omega=np.zeros(1),
                     ball_on_dribbler=np.array([True]), kick_ready=np.array([True]))
    yellow = TeamState(pos=np.array(opponents, float).reshape(n, 2), heading=np.zeros(n), vel=np.zeros((n, 2)),
                       omega=np.zeros(n), ball_on_dribbler=np.zeros(n, bool), kick_ready=np.ones(n, bool))
    return WorldState(t=0.0, ball_pos=np.array([0.1, 0.0]), ball_vel=np.zeros(2), blue=blue, yellow=yellow,
                      frame="blue")


def test_lane_blocker_is_the_opponent_nearest_the_lane_else_the_midpoint():
    target = np.array([4.1, 0.0])
    w = _world([[2.0, 0.3], [1.5, -0.1], [3.0, 1.5], [4.05, 0.0]])  # off the lane, in it, far aside, at the target
    assert np.allclose(lane_blocker(w, target), [1.5, -0.1])
    assert np.allclose(lane_blocker(_world([[3.0, 1.5]]), target), [2.1, 0.0])  # nobody in the lane


def test_action_mapping_round_trip_and_flat_kick():
    a6 = expand_chip_pass_action(np.array([0.2, 1.0, 0.4, 0.0]), RP)
    assert a6.shape == (6,) and a6[3] > 0 and a6[4] > 0 and math.isclose(a6[5], 0.5, abs_tol=1e-6)
    assert np.allclose(chip_pass_task_action(a6, RP), [0.2, 1.0, 0.4, 0.0], atol=1e-5)
    no_kick = expand_chip_pass_action(np.array([0.0, -1.0, 1.0, 1.0]), RP)
    assert no_kick[4] == -1.0 and no_kick[5] == 0.0
    assert chip_pass_task_action(np.array([0, 0, 0, 1, 0.5], np.float32), RP)[3] == -1.0  # a 5-entry action is flat


def test_task_passes_the_gymnasium_checker_and_refuses_bad_input():
    env = gym.make("ssl_marl/ChipPass-v0")
    check_env(env.unwrapped, skip_render_check=True)
    assert env.observation_space.shape == (12,) and env.action_space.shape == (4,)
    env.reset(seed=0)
    for bad in ([np.nan, 0, 0, 0], [0, np.inf, 0, 0], [0, 0, 0]):
        with pytest.raises(ValueError):
            env.step(np.array(bad, np.float32))
    with pytest.raises(ValueError, match="blocker"):
        env.reset(options={"blocker": (50.0, 0.0)})
    with pytest.raises(ValueError, match="unknown option"):
        env.reset(options={"receiver_vel": (0.0, 0.0)})
    env.close()


def _episode(env, seed, flat=False):
    skill = ChipPassBaseline(env.field, env.robot_params, env.ball_params)
    env.reset(seed=seed)
    skill.reset()
    while True:
        a = chip_pass_skill_action(env, skill)
        if flat and a[1] > 0:
            a[3] = -1.0  # the same kick, flat
        _, _, terminated, truncated, info = env.step(a)
        if terminated or truncated:
            return info, info["max_height"]


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_the_chip_clears_the_blocker_a_flat_kick_does_not(seed):
    env = ChipPassEnv()
    chip, h = _episode(env, seed)
    flat, _ = _episode(env, seed, flat=True)
    assert chip["is_success"] and h > RP.height
    assert flat["failure_reason"] == "blocked" and not flat["is_success"]
    env.close()


def test_learned_chip_pass_runs_its_policy_in_the_task():
    env = ChipPassEnv()
    calls = []

    def policy(obs):
        calls.append(obs.shape)
        return np.array([0.0, 1.0, 0.0, 0.5], np.float32)  # kick at once

    skill = LearnedChipPass(env.field, env.robot_params, env.ball_params, policy=policy)
    env.reset(seed=3)
    a = chip_pass_skill_action(env, skill)
    assert calls == [(12,)] and a[1] > 0 and math.isclose(float(a[3]), 0.5, abs_tol=1e-5)
    env.close()


@pytest.mark.skipif(get_skill("chip_pass").actor is None, reason="no chip-pass actor shipped")
def test_shipped_actor_loads_and_passes():
    env = ChipPassEnv()
    skill = get_skill("chip_pass").build("learned", env.field, env.robot_params, env.ball_params)
    wins = 0
    for seed in range(5):
        env.reset(seed=seed)
        skill.reset()
        while True:
            _, _, terminated, truncated, info = env.step(chip_pass_skill_action(env, skill))
            if terminated or truncated:
                wins += bool(info["is_success"])
                break
    assert wins >= 3
    env.close()


def test_a_kick_command_that_never_fired_is_sent_again():
    """After a kick command the skill waits; a ball still held with the kicker charged
    ``kick_confirm_s`` later means the command was lost: the skill kicks again. A fired
    kicker (recharging) ends the skill."""
    from dataclasses import replace

    def at(t, ready=True, held=True):
        w = _world([])
        return replace(w, t=t, blue=replace(w.blue, kick_ready=np.array([ready]), ball_on_dribbler=np.array([held])))

    skill = LearnedChipPass(FieldGeometry.div_b(), RP, BP, target=(4.0, 0.0),
                            policy=lambda obs: np.array([0.0, 1.0, 0.0, 0.5]))
    assert skill.act(at(0.0), 0)[4] > 0                        # kicks at once
    assert skill.act(at(0.05), 0)[4] <= 0                      # waits for the kick to show
    assert skill.act(at(0.05 + skill.kick_confirm_s), 0)[4] > 0  # still held and charged: kicks again
    assert skill.act(at(0.3, ready=False, held=False), 0)[4] <= 0  # recharging, ball gone: the kick fired
    assert skill.act(at(0.5, held=False), 0)[4] <= 0                # and the skill is done
