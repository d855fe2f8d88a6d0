"""Domain randomisation: draws within the documented ranges, reproducible under
the env seed, different across episodes, and applied by the env (measured)."""

import math
from dataclasses import fields

import numpy as np
import pytest

from ssl_marl.envs import parallel_env
from ssl_marl.envs.config import RealismConfig
from ssl_marl.envs.randomization import (DomainRandomization, EpisodeConditions, RandomizationRanges,
                                         resolve_randomization)

R = RandomizationRanges()


def _draws(n=300, seed=0):
    rng = np.random.default_rng(seed)
    dr = DomainRandomization()
    return [dr.draw(rng) for _ in range(n)]


def test_draws_lie_in_the_documented_ranges_and_cover_them():
    draws = [c.as_dict() for c in _draws()]
    for f in fields(R):
        lo, hi = getattr(R, f.name)
        vals = np.array([d[f.name] for d in draws], float)
        assert vals.min() >= lo - 1e-12 and vals.max() <= hi + 1e-12, f.name
        # spread over the range, not stuck at one value
        if f.name.endswith("_steps"):
            assert set(vals.astype(int)) == set(range(lo, hi + 1)), f.name
        else:
            assert vals.max() - vals.min() > 0.8 * (hi - lo), f.name


def test_documented_ranges_match_the_sources():
    # the numbers the module docstring cites (docs/references.md, "Domain randomisation")
    assert R.max_speed == (2.2, 3.2) and R.max_accel == (1.5, 4.0)
    assert R.slide_decel[0] <= 2.79 and R.slide_decel[1] >= 3.9  # ER-Force real field .. simulator
    assert R.roll_decel[0] <= 0.26 and R.roll_decel[1] >= 0.35  # TIGERs .. ER-Force
    nominal = RealismConfig.preset("realistic")
    for name in ("obs_latency_steps", "cmd_latency_steps", "robot_pos_sigma", "robot_angle_sigma",
                 "ball_pos_sigma", "vel_sigma", "ball_dropout", "cmd_loss"):
        lo, hi = getattr(R, name)
        assert lo <= getattr(nominal, name) <= hi, name  # the nominal preset lies inside every range


def test_draw_keeps_the_other_nominal_parameters():
    from ssl_marl.physics.params import BallParams, RobotParams

    c = DomainRandomization().draw(np.random.default_rng(3), RobotParams(max_brake=5.0), BallParams())
    assert isinstance(c, EpisodeConditions)
    assert c.robot.max_brake == 5.0 and c.robot.radius == RobotParams().radius and c.ball.radius == BallParams().radius


def test_bad_ranges_name_the_field():
    with pytest.raises(ValueError, match="max_speed"):
        RandomizationRanges(max_speed=(3.2, 2.2))
    with pytest.raises(ValueError, match="obs_latency_steps"):
        RandomizationRanges(obs_latency_steps=(1.5, 3))
    with pytest.raises(ValueError, match="cmd_loss"):
        RandomizationRanges(cmd_loss=(0.0, 1.5))
    with pytest.raises(ValueError, match="roll_decel"):
        RandomizationRanges(roll_decel=(0.0, 0.3))
    with pytest.raises(ValueError, match="bogus"):
        resolve_randomization({"bogus": (0, 1)})
    assert resolve_randomization(None) is None
    assert resolve_randomization({"max_speed": (2.0, 2.0)}).ranges.max_speed == (2.0, 2.0)


def test_env_draws_are_reproducible_under_the_seed_and_differ_across_episodes():
    env = parallel_env(n_blue=1, n_yellow=1, realism="randomized")
    assert env.config.randomization is not None
    assert env.config.realism == RealismConfig.preset("realistic")  # what teams are told
    _, infos = env.reset(seed=11)
    a = env.conditions
    assert infos["blue_0"]["conditions"] == a.as_dict()
    env.reset(seed=11)
    assert env.conditions == a
    env.reset(seed=12)
    assert env.conditions != a
    # successive resets without a seed: new conditions every episode
    seen = {tuple(sorted(env.conditions.as_dict().items()))}
    for _ in range(5):
        env.reset()
        seen.add(tuple(sorted(env.conditions.as_dict().items())))
    assert len(seen) == 6
    # a second env with the same seed gives the same draw
    env2 = parallel_env(n_blue=1, n_yellow=1, realism="randomized")
    env2.reset(seed=11)
    assert env2.conditions == a


def test_env_without_randomization_is_unchanged():
    env = parallel_env(n_blue=1, n_yellow=0, realism="realistic")
    _, infos = env.reset(seed=1)
    assert env.config.randomization is None and env.conditions is None and "conditions" not in infos["blue_0"]


def _roll(env, seed, v0=2.0, seconds=1.5):
    env.reset(seed=seed, options={"robots": {"blue_0": (-3.0, -2.0, 0.0)},
                                  "ball": {"pos": (-2.0, 0.0), "vel": (v0, 0.0)}})
    speeds = []
    for _ in range(int(seconds * 60)):
        env.step({"blue_0": np.zeros(5, np.float32)})
        speeds.append(float(np.hypot(*env.world_state().ball_vel)))
    return np.array(speeds)


def _fit_decel(speeds, lo, hi, dt=1.0 / 60.0):
    sel = (speeds > lo) & (speeds < hi)
    t = np.flatnonzero(sel) * dt
    return -float(np.polyfit(t, speeds[sel], 1)[0])


def test_env_applies_the_ball_model_it_drew():
    env = parallel_env(n_blue=1, n_yellow=0, realism="randomized", referee=False)
    measured = []
    for seed in (1, 2, 3):
        sp = _roll(env, seed)
        c = env.conditions
        switch = c.ball.slide_to_roll_ratio * 2.0
        slide = _fit_decel(sp, switch + 0.05, 1.97)
        roll = _fit_decel(sp, 0.05, switch - 0.05)
        assert slide == pytest.approx(c.ball.slide_decel, rel=0.03)
        assert roll == pytest.approx(c.ball.roll_decel, rel=0.05)
        measured.append(roll)
    assert max(measured) - min(measured) > 0.02  # the draws differ, and so does the measured deceleration
    # the nominal env rolls at the nominal 0.35 m/s^2
    nominal = parallel_env(n_blue=1, n_yellow=0, realism="realistic", referee=False)
    sp = _roll(nominal, 1)
    assert _fit_decel(sp, 0.05, 0.69 * 2.0 - 0.05) == pytest.approx(0.35, rel=0.05)


def test_env_applies_robot_speed_accel_and_latencies():
    env = parallel_env(n_blue=1, n_yellow=0, realism="randomized", referee=False)
    for seed in (4, 5):
        env.reset(seed=seed, options={"robots": {"blue_0": (-4.0, 0.0, 0.0)}, "ball": {"pos": (0.0, 2.5)}})
        c = env.conditions
        assert env.physics.robot == c.robot and env.physics.ball_params == c.ball
        assert env.vision.delay._queue.maxlen == c.realism.obs_latency_steps + 1
        full = np.array([1.0, 0.0, 0.0, -1.0, -1.0], np.float32)
        speeds, seen_t = [], []
        for _ in range(150):
            env.step({"blue_0": full})
            speeds.append(float(np.hypot(*env.world_state().blue.vel[0])))
            seen_t.append(env.vision_state().t - env.world_state().t)
        speeds = np.array(speeds)
        # the top speed is the drawn one (capped by the nominal 3 m/s command)
        assert speeds.max() == pytest.approx(min(c.robot.max_speed, 3.0), abs=0.02)
        # the vision lag is the drawn latency
        assert seen_t[-1] == pytest.approx(-c.realism.obs_latency_steps / 60.0, abs=1e-9)
        # the initial acceleration is the drawn one (after the radio delay and any lost command)
        moving = np.flatnonzero(speeds > 0.05)
        k = moving[0]
        a = (speeds[k + 10] - speeds[k]) * 6.0
        assert a == pytest.approx(c.robot.max_accel, rel=0.15)


def test_batched_env_refuses_randomization_clearly():
    from ssl_marl.envs.batched_env import BatchedSSLEnv

    with pytest.raises(ValueError, match="randomization"):
        BatchedSSLEnv(2, n_blue=1, n_yellow=0, realism="randomized")


def test_tracker_is_on_and_tuned_to_the_nominal_preset():
    from ssl_marl.envs.tracking import TrackedVisionEnv, with_tracker
    from ssl_marl.envs.tracking.params import TrackerParams

    env = with_tracker(parallel_env(n_blue=1, n_yellow=0, realism="randomized"), "auto")
    assert isinstance(env, TrackedVisionEnv)
    assert env.params == TrackerParams.for_realism("realistic", env.dt)
    env.reset(seed=0)
    for _ in range(5):
        env.step({"blue_0": np.zeros(5, np.float32)})
    assert math.isfinite(env.vision_state("blue").ball_pos[0])
