"""A team in its own process (ssl_marl.runners.team_process): the same match, bit for bit."""

import numpy as np
import pytest

from ssl_marl.envs import parallel_env
from ssl_marl.runners.controllers import make_controller
from ssl_marl.runners.match import play_match, use_team_processes
from ssl_marl.runners.team_process import TeamProcess, TeamView, team_view


def _record(res) -> dict:
    d = res.to_dict()
    for k in ("wall_time_s", "act_time_ms"):
        d.pop(k, None)
    return d


def test_a_match_with_yellow_in_its_own_process_is_the_same_match():
    kw = dict(blue="attack-learned", yellow="passing-baseline", seconds=6.0, seed=3, progress=False)
    one = play_match(team_processes="off", **kw)
    two = play_match(team_processes="on", **kw)
    assert _record(two) == _record(one)
    assert two.act_time_ms["yellow"] > 0.0  # timed in the child


def test_team_view_carries_what_a_team_reads():
    env = parallel_env(n_blue=2, n_yellow=2, field="div_b", ssl_restarts=True)
    env.reset(seed=0)
    view = team_view(env, "yellow")
    assert view.vision_state("yellow").frame == "yellow"
    assert view.score == {"blue": 0, "yellow": 0}
    assert view.task.referee_state == env.task.referee_state
    with pytest.raises(ValueError, match="no vision frame for 'blue'"):
        view.vision_state("blue")
    ctrl = make_controller("baseline", "yellow", 2, "div_b")
    a_view = ctrl.act(view)
    ctrl2 = make_controller("baseline", "yellow", 2, "div_b")
    a_env = ctrl2.act(env)
    for k in a_env:
        np.testing.assert_array_equal(a_view[k], a_env[k])
    assert isinstance(view, TeamView)


def test_team_process_reports_the_childs_error_and_refuses_misuse():
    with pytest.raises(ValueError, match="unknown controller 'no-such-team'"):  # the child's own error
        TeamProcess(make_controller, "no-such-team", "yellow", 2, "div_b").agents
    with TeamProcess(make_controller, "baseline", "yellow", 2, "div_b") as tp:
        assert tp.agents == ["yellow_0", "yellow_1"]
        with pytest.raises(RuntimeError, match="nothing was submitted"):
            tp.result()
        env = parallel_env(n_blue=2, n_yellow=2, field="div_b")
        env.reset(seed=1)
        tp.submit(team_view(env, "yellow"))
        with pytest.raises(RuntimeError, match="not collected"):
            tp.submit(team_view(env, "yellow"))
        actions, seconds = tp.result()
        assert sorted(actions) == ["yellow_0", "yellow_1"] and seconds >= 0.0
        with pytest.raises(TypeError, match="expects an SSL env or a WorldState") as info:
            tp.submit("not a view")
            tp.result()
        assert "raised in the team's process while computing actions" in "".join(info.value.__notes__)


def test_team_processes_mode_is_checked():
    with pytest.raises(ValueError, match="team_processes must be one of"):
        use_team_processes("sometimes", False, "baseline", None, None, {})
    with pytest.raises(ValueError, match="real-time mode"):
        use_team_processes("on", True, "baseline", None, None, {})
    with pytest.raises(ValueError, match="controller object"):
        use_team_processes("on", False, object(), None, None, {})
    with pytest.raises(ValueError, match="do not pickle"):
        use_team_processes("on", False, "attack-learned", None, lambda *a: 0, {})
    assert use_team_processes("auto", True, "baseline", None, None, {}) is False
    assert use_team_processes("on", False, "baseline", None, None, {}) is True
    assert use_team_processes("off", False, "baseline", None, None, {}) is False


def test_env_without_observations_returns_an_empty_dict():
    env = parallel_env(n_blue=1, n_yellow=1, observations=False)
    obs, _ = env.reset(seed=0)
    assert obs == {}
    obs, *_ = env.step({a: np.zeros(5, np.float32) for a in env.agents})
    assert obs == {}
    with pytest.raises(ValueError, match="observations must be True or False"):
        parallel_env(observations="no")


def test_frames_and_actions_cross_the_pipe_unchanged():
    import dataclasses
    import pickle

    from ssl_marl.physics.state import TeamState, WorldState
    from ssl_marl.runners.team_process import pack_actions, unpack_actions

    env = parallel_env(n_blue=3, n_yellow=2, field="div_b", chip_kicks=True)
    env.reset(seed=5)
    for _ in range(30):
        env.step({a: env.action_space(a).sample() for a in env.agents})
    view = team_view(env, "yellow")
    back = pickle.loads(pickle.dumps(view))

    def same(a, b) -> bool:  # every field of the snapshots, so a field added later cannot be dropped unseen
        if isinstance(a, TeamState):
            return all(same(getattr(a, f.name), getattr(b, f.name)) for f in dataclasses.fields(TeamState))
        if isinstance(a, np.ndarray):
            return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()
        return type(a) is type(b) and a == b

    for f in dataclasses.fields(WorldState):
        assert same(getattr(back.world, f.name), getattr(view.world, f.name)), f.name
    actions = {"yellow_0": np.arange(6, dtype=np.float32), "yellow_1": np.ones(5, np.float32)}
    out = unpack_actions(pickle.loads(pickle.dumps(pack_actions(actions))))
    assert out.keys() == actions.keys() and all(np.array_equal(out[k], actions[k]) and out[k].dtype == np.float32
                                                for k in actions)
    out["yellow_0"][0] = 9.0  # writable
    assert unpack_actions({"x": 1}) == {"x": 1} and pack_actions({"x": [1.0]}) == {"x": [1.0]}  # others as they are
