"""The referee's no-progress call (SSL force start after a clear lack of progress)."""

import numpy as np
import pytest

from ssl_marl.envs import parallel_env
from ssl_marl.envs.batched_env import BatchedSSLEnv
from ssl_marl.envs.referee import NO_PROGRESS_RADIUS_M, NoProgressWatch

#: blue_0 holds the ball on its dribbler facing the touch line, 0.1 m inside it; yellow_0 stands next to it
PINNED = {"ball": {"pos": (1.0, 2.9)},
          "robots": {"blue_0": (1.0, 2.7985, np.pi / 2), "yellow_0": (1.2, 2.75, np.pi)}}
PUSH = np.array([0.0, 0.0, 0.0, 1.0, 0.0], np.float32)  # stand still, dribbler on


def _events(info):
    return next(iter(info.values()))["events"]


def test_held_ball_is_restarted_after_ten_seconds():
    e = parallel_env(n_blue=1, n_yellow=1)
    e.reset(seed=0, options=PINNED)
    t_call = None
    for _ in range(int(12 * 60)):
        _, _, _, _, info = e.step({"blue_0": PUSH, "yellow_0": PUSH})
        ev = [x for x in _events(info) if x["type"] == "no_progress"]
        if ev:
            t_call = ev[0]["t"]
            break
    assert t_call is not None and 10.0 - 1e-6 <= t_call <= 10.0 + 2.0 / 60.0
    ws = e.world_state()
    assert e.field.half_width - ws.ball_pos[1] >= 0.2 - 1e-6  # placed 0.2 m inside the touch line
    for team in (ws.blue, ws.yellow):
        assert np.hypot(*(team.pos[0] - ws.ball_pos)) >= 0.5 - 1e-6


def test_a_moving_ball_is_not_called():
    e = parallel_env(n_blue=1, n_yellow=0)
    # rolls slowly across the field: more than 0.25 m every 10 s for 12 s
    e.reset(seed=0, options={"ball": {"pos": (-3.0, 0.0), "vel": (0.6, 0.0)}, "robots": {"blue_0": (-3.0, 2.0, 0.0)}})
    for _ in range(int(4 * 60)):
        _, _, _, _, info = e.step({})
        assert not any(x["type"] == "no_progress" for x in _events(info))


def test_switched_off_with_none():
    e = parallel_env(n_blue=1, n_yellow=1, no_progress_s=None)
    e.reset(seed=0, options=PINNED)
    for _ in range(int(11 * 60)):
        _, _, _, _, info = e.step({"blue_0": PUSH, "yellow_0": PUSH})
        assert not any(x["type"] == "no_progress" for x in _events(info))


@pytest.mark.parametrize("bad", [0.0, -1.0, float("nan"), float("inf"), "10", True])
def test_bad_no_progress_s_names_the_field(bad):
    with pytest.raises(ValueError, match="no_progress_s"):
        parallel_env(no_progress_s=bad)


def test_batched_env_calls_it_at_the_same_step():
    single = parallel_env(n_blue=1, n_yellow=1, no_progress_s=2.0)
    single.reset(seed=0, options=PINNED)
    batched = BatchedSSLEnv(2, n_blue=1, n_yellow=1, no_progress_s=2.0)
    batched.reset(seed=0, options=PINNED)
    a = np.stack([PUSH, PUSH])[None].repeat(2, axis=0)
    for step in range(int(3 * 60)):
        _, _, _, _, info = single.step({"blue_0": PUSH, "yellow_0": PUSH})
        _, _, _, _, binfo = batched.step(a)
        called = any(x["type"] == "no_progress" for x in _events(info))
        assert bool(binfo["no_progress"][0]) == called == bool(binfo["no_progress"][1]), step
        np.testing.assert_allclose(batched.physics.ball_pos[0], single.world_state().ball_pos, atol=1e-9)


def test_watch_restarts_when_the_ball_moves():
    w = NoProgressWatch(2, 1.0)
    w.restart(np.arange(2), np.zeros((2, 2)), np.zeros(2))
    moved = np.array([[NO_PROGRESS_RADIUS_M + 0.01, 0.0], [0.1, 0.0]])
    assert not w.update(np.arange(2), moved, np.full(2, 0.5)).any()
    np.testing.assert_array_equal(w.update(np.arange(2), moved, np.full(2, 1.0)), [False, True])
    assert w.update(np.arange(2), moved, np.full(2, 1.5))[0]
