"""Keepaway 3v2 (ssl_marl/decisions/keepaway/, ssl_marl/envs/tasks/keepaway.py): API,
termination and scoring on constructed scenes, honest decision flags, determinism, bounds,
bad inputs and the benchmark policies."""

from __future__ import annotations

import math

import numpy as np
import pytest

from ssl_marl.decisions import make_decision_env, make_decision_policy
from ssl_marl.decisions.keepaway.env import KeepawayEnv
from ssl_marl.decisions.keepaway.observation import OBS_DIM, STATE_DIM
from ssl_marl.decisions.keepaway.params import HOLD, PASS1, PASS2, KeepawayParams
from ssl_marl.decisions.keepaway.policies import AlwaysHoldPolicy, HandcodedKeepawayPolicy
from ssl_marl.decisions.policies import RandomPolicy, run_episode
from ssl_marl.envs.tasks.keepaway import KeepawayRules

SHORT = KeepawayRules(max_time_s=6.0)
REACH = 0.08 + 0.0215 + 0.002  # robot centre -> ball centre with the ball on the dribbler (m)


def _env(**kw):
    kw.setdefault("rules", SHORT)
    return KeepawayEnv(**kw)


def test_spaces_and_registry():
    env = make_decision_env("keepaway")
    assert isinstance(env, KeepawayEnv)
    assert env.possible_agents == ["keeper_0", "keeper_1", "keeper_2"]
    assert env.option_names == ("hold", "pass_to_1", "pass_to_2")
    assert env.action_space("keeper_1").n == 3
    sp = env.observation_space("keeper_0")
    assert sp.shape == (OBS_DIM,) and np.isfinite(sp.low).all() and np.isfinite(sp.high).all()
    assert env.state_space.shape == (STATE_DIM,) and np.isfinite(env.state_space.high).all()
    with pytest.raises(ValueError, match="unknown agent"):
        env.observation_space("taker_0")


def test_parallel_api_test():
    from pettingzoo.test import parallel_api_test

    parallel_api_test(_env(illegal_option="default", rules=KeepawayRules(max_time_s=3.0)), num_cycles=6)


def test_start_first_keeper_decides_at_t0():
    env = _env()
    obs, infos = env.reset(seed=1)
    assert [a for a in infos if infos[a]["decision"]] == ["keeper_0"]
    assert all(infos[a]["elapsed_s"] == 0.0 for a in infos)
    assert obs["keeper_0"][6] == 1.0 and obs["keeper_1"][6] == 0.0
    w = env.engine.world_state()
    assert np.all(np.abs(w.blue.pos) <= 2.5) and np.all(np.abs(w.yellow.pos) <= 2.5)


def _taker_on_ball_options():
    return {"robots": {"yellow_0": (0.0, 0.0, 0.0)}, "ball": {"pos": (REACH, 0.0)}}


def test_taker_on_the_ball_terminates_with_taker_control():
    env = _env()
    obs, infos = env.reset(seed=2, options=_taker_on_ball_options())
    assert not any(infos[a]["decision"] for a in infos)  # no keeper has the ball
    total = 0.0
    while env.agents:
        obs, rew, term, trunc, infos = env.step({a: 0 for a in env.possible_agents})
        total += rew["keeper_0"]
    assert term["keeper_0"] and not trunc["keeper_0"]
    info = infos["keeper_0"]
    assert info["outcome"] == "taker_control"
    assert env.task.taker_control_by == 0
    # contact for 0.1 s (6 ticks) from the start
    assert 0.09 <= info["duration_s"] <= 0.2
    assert total == pytest.approx(info["duration_s"], abs=1e-9)


def test_ball_leaving_the_square_terminates_with_out():
    env = _env()
    obs, infos = env.reset(seed=3, options={"ball": {"pos": (2.3, 0.0), "vel": (3.0, 0.0)}})
    while env.agents:
        obs, rew, term, trunc, infos = env.step({a: 0 for a in env.possible_agents})
    assert term["keeper_1"] and infos["keeper_1"]["outcome"] == "out"
    assert infos["keeper_1"]["duration_s"] < 0.3
    assert abs(env.engine.world_state().ball_pos[0]) > 2.5


def test_truncation_at_max_time_and_score_is_duration():
    env = _env(rules=KeepawayRules(max_time_s=1.0))
    obs, infos = env.reset(seed=4)
    total, elapsed = 0.0, 0.0
    while env.agents:
        obs, rew, term, trunc, infos = env.step({a: HOLD for a in env.possible_agents})
        total += rew["keeper_2"]
        elapsed += infos["keeper_2"]["elapsed_s"]
    assert trunc["keeper_0"] and not term["keeper_0"]
    assert infos["keeper_0"]["outcome"] == "time"
    assert infos["keeper_0"]["duration_s"] == pytest.approx(1.0, abs=1e-6)
    assert total == pytest.approx(1.0, abs=1e-6) and elapsed == pytest.approx(1.0, abs=1e-6)


def test_decision_flags_are_honest_and_obs_in_bounds():
    env = _env()
    obs, infos = env.reset(seed=5)
    pol = RandomPolicy(3)
    pol.reset(env)
    n_dec = 0
    while env.agents:
        deciders = [a for a in infos if infos[a]["decision"]]
        assert len(deciders) <= 1
        for a in env.possible_agents:
            assert env.observation_space(a).contains(obs[a]), a
        assert env.state_space.contains(env.state())
        if deciders:
            a = deciders[0]
            i = int(a[-1])
            assert env.controller() == i and env.holder is None
            assert env._dribbler_distances()[i] <= env.params.control_m + 1e-9
            assert obs[a][6] == 1.0
            n_dec += 1
        acts = {a: (pol.act(env, a, obs[a], infos[a]) if infos[a]["decision"] else 0) for a in env.possible_agents}
        obs, rew, term, trunc, infos = env.step(acts)
        for a in env.possible_agents:
            assert 0.0 < infos[a]["elapsed_s"] <= env.max_interval_s + 1e-9
    assert n_dec >= 1


def test_deterministic_under_seed():
    env = _env()
    a = run_episode(env, RandomPolicy(1), seed=7, record=True)
    b = run_episode(_env(), RandomPolicy(1), seed=7, record=True)
    assert a == b
    c = run_episode(env, RandomPolicy(1), seed=8, record=True)
    assert c["trace"] != a["trace"] or c["t_s"] != a["t_s"]


def test_bad_inputs_raise_naming_the_problem():
    env = _env()
    env.reset(seed=0)
    with pytest.raises(ValueError, match="keeper_0"):
        env.step({"keeper_0": float("nan"), "keeper_1": 0, "keeper_2": 0})
    with pytest.raises(ValueError, match="outside"):
        env.step({"keeper_0": 3, "keeper_1": 0, "keeper_2": 0})
    with pytest.raises(ValueError, match="keeper_1"):
        env.step({"keeper_0": 0, "keeper_1": -1, "keeper_2": 0})
    with pytest.raises(ValueError, match="unknown agent 'taker_0'"):
        env.step({"keeper_0": 0, "taker_0": 0})
    with pytest.raises(ValueError, match="keeper_0.*no action"):
        env.step({"keeper_1": 0})
    with pytest.raises(ValueError, match="keeper_2"):
        env.step({"keeper_0": 0, "keeper_1": 0, "keeper_2": "pass"})
    with pytest.raises(ValueError, match="illegal_option"):
        KeepawayEnv(illegal_option="ignore")
    with pytest.raises(ValueError, match="side_m"):
        KeepawayRules(side_m=1.0)


def _scene(keeper0, takers, k1, k2):
    """keeper_0 at ``keeper0`` facing +x with the ball on its dribbler; takers and the
    other keepers at the given points (field frame, m)."""
    x, y = keeper0
    robots = {"blue_0": (x, y, 0.0), "blue_1": (*k1, math.pi), "blue_2": (*k2, math.pi),
              "yellow_0": (*takers[0], math.pi), "yellow_1": (*takers[1], math.pi)}
    return {"robots": robots, "ball": {"pos": (x + REACH, y)}}


def test_handcoded_holds_when_takers_far_and_passes_to_the_open_keeper_when_pressed():
    env = _env()
    pol = HandcodedKeepawayPolicy()
    # takers far (> hold_dist_m = 2 m): hold
    obs, infos = env.reset(seed=0, options=_scene((-1.5, 0.0), [(2.0, 2.0), (2.0, -2.0)], (1.5, 1.8), (1.5, -1.8)))
    assert infos["keeper_0"]["decision"]
    assert pol.act(env, "keeper_0", obs["keeper_0"], infos["keeper_0"]) == HOLD
    # pressed by a taker 0.5 m away; taker 2 stands on the lane to keeper_2: pass to keeper_1 (pass_to_1)
    obs, infos = env.reset(seed=0, options=_scene((-1.5, 0.0), [(-1.5, -0.5), (0.0, -0.9)], (1.5, 1.8), (1.5, -1.8)))
    assert infos["keeper_0"]["decision"]
    assert pol.act(env, "keeper_0", obs["keeper_0"], infos["keeper_0"]) == PASS1
    # mirrored: keeper_1's lane blocked -> pass_to_2
    obs, infos = env.reset(seed=0, options=_scene((-1.5, 0.0), [(-1.5, 0.5), (0.0, 0.9)], (1.5, 1.8), (1.5, -1.8)))
    assert pol.act(env, "keeper_0", obs["keeper_0"], infos["keeper_0"]) == PASS2
    assert AlwaysHoldPolicy().act(env, "keeper_0", obs["keeper_0"], infos["keeper_0"]) == HOLD


def test_pass_option_kicks_to_the_chosen_teammate():
    """An open pass from a constructed scene reaches keeper_1, who then decides."""
    env = _env()
    obs, infos = env.reset(seed=0, options=_scene((-1.5, -1.5), [(2.0, 2.0), (2.2, 1.8)], (1.5, -1.5), (-1.5, 1.5)))
    obs, rew, term, trunc, infos = env.step({"keeper_0": PASS1, "keeper_1": 0, "keeper_2": 0})
    assert env.passes_kicked == 1 and env.passes_completed == 1
    assert [a for a in infos if infos[a]["decision"]] == ["keeper_1"]
    assert 0.5 < infos["keeper_1"]["elapsed_s"] < 4.0


def test_policy_registry_and_random_is_legal():
    env = _env()
    for name in ("random", "always-hold", "handcoded"):
        pol = make_decision_policy(name, "keepaway", seed=0)
        r = run_episode(env, pol, seed=11)
        assert r["outcome"] in ("taker_control", "out", "time")
        assert r["duration_s"] == pytest.approx(r["return"], abs=1e-6)
        assert r["duration_s"] == pytest.approx(r["t_s"], abs=1e-9)
    with pytest.raises(ValueError, match="always-hold"):
        make_decision_policy("always-hold", "attack-3v2")


def test_both_takers_go_for_a_held_ball_and_end_a_hold():
    """The standard 3v2 takers ("with two takers both go for the ball"): against a keeper
    that only holds, both takers close on the ball (the presser on the flank the chaser
    leaves open) and win it; the earlier lane-blocking second taker stays away."""
    scene = _scene((0.0, 0.0), [(1.2, 0.8), (-1.2, 0.9)], (-2.0, 2.0), (-2.0, -2.0))

    def closest_approach(params):
        env = _env(params=params)
        obs, infos = env.reset(seed=0, options=scene)
        pol = AlwaysHoldPolicy()
        near = [np.inf, np.inf]
        while env.agents:
            acts = {a: pol.act(env, a, obs[a], infos[a]) if infos[a]["decision"] else 0 for a in env.agents}
            obs, _, _, _, infos = env.step(acts)
            w = env.engine.world_state()
            d = np.sqrt(((w.yellow.pos - w.ball_pos) ** 2).sum(axis=1))
            near = [min(near[i], float(d[i])) for i in range(2)]
        return near, env.task.outcome, infos["keeper_0"]["t"]

    near, outcome, t = closest_approach(KeepawayParams())
    assert max(near) < 0.35, near  # both takers reached the ball
    assert outcome == "taker_control" and t < 4.0
    near_block, _, _ = closest_approach(KeepawayParams(takers="block"))
    assert max(near_block) > 0.2  # the blocker stays on a lane
    with pytest.raises(ValueError, match="takers"):
        KeepawayParams(takers="zone")
