"""Observation spaces are finite and documented, and observations really stay inside
them (clipped), for the full-field env and both skill tasks; the Gymnasium checker
passes without a warning."""

from __future__ import annotations

import warnings

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import ssl_marl  # noqa: F401  (registers the skill envs)
from ssl_marl.envs import parallel_env
from ssl_marl.envs.observation import POSITION_MARGIN_M, observation_bounds, position_extent
from ssl_marl.physics.field import FieldGeometry
from ssl_marl.physics.params import RobotParams


@pytest.mark.parametrize("realism", ["realistic", "none"])
@pytest.mark.parametrize("chip_kicks", [False, True], ids=["v0", "chip-kicks"])
def test_env_spaces_are_finite_and_hold_every_observation(chip_kicks, realism):
    env = parallel_env(n_blue=3, n_yellow=3, field="div_b", realism=realism, max_time_s=5.0, chip_kicks=chip_kicks)
    env.action_space("blue_0").seed(0)
    obs, _ = env.reset(seed=1)
    space = env.observation_space("blue_0")
    assert np.all(np.isfinite(space.low)) and np.all(np.isfinite(space.high))
    assert np.all(np.isfinite(env.state_space.low)) and np.all(np.isfinite(env.state_space.high))
    for _ in range(200):
        for a, o in obs.items():
            assert space.contains(o), a
        assert env.state_space.contains(env.state())
        obs, *_ = env.step({a: env.action_space(a).sample() for a in env.agents})
        if not env.agents:
            break


def test_position_bounds_cover_the_walls_with_margin():
    f = FieldGeometry.div_a()
    low, high = observation_bounds(f, RobotParams(), 1, 1)
    assert high[0] == pytest.approx(f.half_length + f.boundary_width + POSITION_MARGIN_M)
    assert low[1] == pytest.approx(-position_extent(f)[1])
    assert high[18] == pytest.approx(f.half_length) and low[21] == 0 and high[21] == 1  # slot mask


@pytest.mark.parametrize("env_id", ["ssl_marl/GoToBall-v0", "ssl_marl/AimToShoot-v0"])
def test_skill_tasks_are_bounded_and_pass_the_checker(env_id):
    env = gym.make(env_id)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no "infinite bounds" (or any other) warning
        check_env(env.unwrapped, skip_render_check=True)
    assert np.all(np.isfinite(env.observation_space.low)) and np.all(np.isfinite(env.observation_space.high))
    env.action_space.seed(0)
    obs, _ = env.reset(seed=0)
    for _ in range(300):
        assert env.observation_space.contains(obs)
        obs, _, term, trunc, _ = env.step(env.action_space.sample())
        if term or trunc:
            obs, _ = env.reset()
