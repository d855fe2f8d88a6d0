"""Attack drill: the attacking plays' carrier options as a decision task (mask, options and
observation on constructed scenes, the hand-coded benchmark = the attacking plays' cost
decision, PettingZoo API, determinism) and the learned decision in attacking-team matches."""

from __future__ import annotations

import math

import numpy as np
import pytest

from ssl_marl.decisions import make_decision_env, make_decision_policy
from ssl_marl.decisions.attack_drill import AttackDrillEnv, HandcodedAttackDrillPolicy
from ssl_marl.decisions.attack_drill_features import (ATTACK_DRILL_OBS_DIM, ATTACK_DRILL_OPTIONS, PASS_OPTIONS,
                                                      SHOOT, attack_decision_option, attack_drill_mask,
                                                      attack_drill_observation, option_play_decision, slot_passes)
from ssl_marl.decisions.attack_features import attack_observation
from ssl_marl.decisions.policies import RandomPolicy, run_episode
from ssl_marl.envs.tasks.attack import AttackRules
from ssl_marl.physics import FieldGeometry
from ssl_marl.physics.params import BallParams, RobotParams
from ssl_marl.plays.attack_decision import AttackChoice, AttackParams, decide_attack
from ssl_marl.plays.pass_decision import Choice
from ssl_marl.plays.scene import ball_in_front, make_world

F = FieldGeometry.div_b()
RP, BP, AP = RobotParams(), BallParams(), AttackParams()
PARKED = (-4.2, 0.0, 0.0)
CHIP_1, CHIP_2, REDIRECT_1 = 3, 4, 5


def _world(blue, yellow, carrier=1):
    x, y, h = blue[carrier]
    return make_world(blue=blue, yellow=yellow, ball=ball_in_front(x, y, h), frame="blue",
                      blue_on_dribbler=[i == carrier for i in range(len(blue))])


#: the defender stands midway in the lane to teammate 2 (slot 1): a chip over it; the lane to teammate 3
#: (slot 2) is open and too short for a chip (the chip-pass skill's ``lane_chip`` finds none)
CHIP_SCENE = dict(blue=[PARKED, (0.5, 0.0, 0.0), (3.0, 1.5, 0.0), (2.5, -2.0, 0.0)],
                  yellow=[(4.3, 0.0, math.pi), (1.75, 0.75, math.pi)])
#: the carrier near the goal line: a pass back to teammate 2 can be redirected at the goal
REDIRECT_SCENE = dict(blue=[PARKED, (3.6, -2.2, math.atan2(2.5, -0.8)), (2.8, 0.3, 0.0), (0.0, -2.0, 0.0)],
                      yellow=[(4.3, -0.3, math.pi), (1.0, 2.6, math.pi)])


def test_options_mask_and_observation_on_constructed_scenes():
    w = _world(**CHIP_SCENE)
    passes = slot_passes(w, "blue", 1, F, RP, BP, AP)
    mask = attack_drill_mask(passes)
    assert mask.dtype == np.int8 and mask.shape == (len(ATTACK_DRILL_OPTIONS),)
    assert mask[SHOOT] == 1 and mask[7:].all()  # shot and dribbles always legal
    for option, key in PASS_OPTIONS.items():
        assert mask[option] == int(key in passes)
    assert mask[CHIP_1] == 1 and mask[CHIP_2] == 0 and mask[REDIRECT_1] == 0
    o = attack_drill_observation(w, "blue", 1, F, RP, BP, AP, passes=passes)
    assert o.shape == (ATTACK_DRILL_OBS_DIM,) and o.dtype == np.float32 and np.isfinite(o).all()
    np.testing.assert_array_equal(o[:40], attack_observation(w, "blue", 1, F, RP, BP, AP.decision))
    chip = passes[(AttackChoice.CHIP, 0)]
    assert o[40 + 1] == pytest.approx(chip.success) and o[40 + 2] == pytest.approx(chip.value)
    np.testing.assert_array_equal(o, attack_drill_observation(w, "blue", 1, F, RP, BP, AP))  # computed alike
    assert attack_drill_mask(slot_passes(w, "blue", 1, F, RP, BP, AP, candidates=())).tolist() == \
        [1, 0, 0, 0, 0, 0, 0, 1, 1, 1]  # cooldown after a dropped pass: no pass of any kind
    w2 = _world(**REDIRECT_SCENE)
    passes2 = slot_passes(w2, "blue", 1, F, RP, BP, AP)
    assert attack_drill_mask(passes2)[REDIRECT_1] == 1
    r = passes2[(AttackChoice.REDIRECT, 0)]
    assert r.teammate == 2 and r.aim is not None and r.deflection < AP.redirect_zero


def test_option_execution_and_errors():
    w = _world(**CHIP_SCENE)
    passes = slot_passes(w, "blue", 1, F, RP, BP, AP)
    d, o = option_play_decision(CHIP_1, w.ball_pos, F, passes)
    assert d.choice is Choice.PASS and d.target == 2 and o.kind is AttackChoice.CHIP and o.chip_angle > 0
    d, o = option_play_decision(SHOOT, w.ball_pos, F, passes)
    assert d.choice is Choice.SHOOT and o is None and d.commit_s > 0
    d, o = option_play_decision(8, w.ball_pos, F, passes)  # dribble left
    assert d.choice is Choice.KEEP and d.dribble_to[1] > w.ball_pos[1] and o is None
    with pytest.raises(ValueError, match="not legal"):
        option_play_decision(REDIRECT_1, w.ball_pos, F, passes)
    for bad in (10, -1, 2.0, True, float("nan")):
        with pytest.raises(ValueError, match="option must be an integer"):
            option_play_decision(bad, w.ball_pos, F, passes)


def test_handcoded_option_is_the_attack_decision():
    for scene in (CHIP_SCENE, REDIRECT_SCENE):
        w = _world(**scene)
        ours = w.team("blue")
        d = decide_attack(w.ball_pos, 1, ours.pos, w.opponents("blue").pos, F, RP, BP, AP, candidates=(2, 3),
                          heading=float(ours.heading[1]))
        option = attack_decision_option(d, w, "blue", 1)
        if d.choice is AttackChoice.SHOOT:
            assert option == SHOOT
        elif d.choice is AttackChoice.DRIBBLE:
            assert option == 7
        else:
            kind, slot = PASS_OPTIONS[option]
            assert kind is d.best.kind and [2, 3][slot] == d.best.teammate
    w = _world(**CHIP_SCENE)
    ours = w.team("blue")
    d = decide_attack(w.ball_pos, 1, ours.pos, w.opponents("blue").pos, F, RP, BP, AP, candidates=(2, 3), heading=0.0)
    assert attack_decision_option(d, w, "blue", 1) == CHIP_1  # the chip over the defender beats both flat lanes


def _env(max_time_s=15.0, **kw):
    return AttackDrillEnv(skills="baseline", rules=AttackRules(max_time_s=max_time_s), **kw)


def test_registry_decision_points_and_spaces():
    env = make_decision_env("attack-drill", skills="baseline")
    assert isinstance(env, AttackDrillEnv) and env.option_names == ATTACK_DRILL_OPTIONS
    assert env.engine.config.chip_kicks
    obs, infos = env.reset(seed=49000)
    for _ in range(20):
        obs, _, _, _, infos = env.step({a: 0 for a in env.possible_agents})
        deciding = [a for a in env.possible_agents if infos[a]["decision"]]
        if deciding or not env.agents:
            break
    assert len(deciding) == 1
    a = deciding[0]
    req = env.pending_request
    assert env.agent_of(req.carrier) == a
    assert infos[a]["action_mask"].tolist() == attack_drill_mask(env._passes).tolist()
    for b in env.possible_agents:
        assert obs[b].shape == (ATTACK_DRILL_OBS_DIM,) and env.observation_space(b).contains(obs[b])
    assert isinstance(make_decision_policy("handcoded", "attack-drill"), HandcodedAttackDrillPolicy)


def test_parallel_api():
    from pettingzoo.test import parallel_api_test

    parallel_api_test(_env(max_time_s=2.0, illegal_option="default"), num_cycles=20)


def test_deterministic_under_the_seed_and_the_handcoded_scores():
    a = run_episode(_env(max_time_s=4.0), RandomPolicy(3), seed=49005, record=True)
    b = run_episode(_env(max_time_s=4.0), RandomPolicy(3), seed=49005, record=True)
    assert a["trace"] == b["trace"] and a["outcome"] == b["outcome"] and a["decisions"] >= 1
    env, pol = _env(), HandcodedAttackDrillPolicy()
    goals = sum(run_episode(env, pol, seed=49100 + i)["goal"] for i in range(6))
    assert goals >= 1  # the cost decision scores in the drill (about 0.6 of episodes)


def test_the_attackers_build_the_attacking_teams_skills():
    """The drill's attackers run the skills ``attack-learned`` runs in matches (the learned chip
    pass and redirect included); the flat-kicking defence builds the passing team's."""
    from ssl_marl.runners.controllers import kind_skills

    env = AttackDrillEnv(skills="learned")
    assert env.skills == kind_skills("attack-learned") and "redirect" in env.skills
    assert "redirect" not in env.defence_skills
    assert _env().skills == kind_skills("attack-baseline")


def test_an_episode_does_not_depend_on_the_one_before():
    """The plays' state between ticks (the pass coordinator's plan, the supports' rated
    spots) is reset with the team: an episode replayed on the same env after another one
    repeats itself exactly (evaluations and rollouts do not depend on episode order)."""
    env, pol = _env(max_time_s=6.0), HandcodedAttackDrillPolicy()
    first = run_episode(env, pol, seed=46003, record=True)
    run_episode(env, pol, seed=46010)
    again = run_episode(env, pol, seed=46003, record=True)
    assert again["trace"] == first["trace"] and again["outcome"] == first["outcome"]
    assert again["steps"] == first["steps"]


class _Fixed:
    def __init__(self, option):
        self.option, self.calls, self.spaces = option, 0, None

    def reset(self, env):
        self.spaces = (env.observation_space("attacker_0").shape, env.action_space("attacker_0").n)

    def act(self, env, agent, obs, info):
        assert obs.shape == (ATTACK_DRILL_OBS_DIM,) and info["action_mask"][SHOOT] == 1
        self.calls += 1
        return self.option


def test_attacking_team_plays_a_policy_decision_in_a_match():
    from ssl_marl.decisions.match_decider import PolicyAttackDecider, make_match_decider
    from ssl_marl.runners.match import play_match

    pol = _Fixed(SHOOT)
    dec = make_match_decider(pol, task="attack-drill")
    assert isinstance(dec, PolicyAttackDecider) and pol.spaces == ((ATTACK_DRILL_OBS_DIM,), len(ATTACK_DRILL_OPTIONS))
    r = play_match(blue="attack-baseline", yellow="baseline", blue_decision=dec, robots=3, seconds=6.0, seed=2,
                   progress=False, start_jitter_m=0.0)
    assert r.config["decision"]["blue"] == "PolicyAttackDecider" and pol.calls >= 1
    assert dec.counters.shoot == pol.calls == dec.decisions  # the policy's shots counted as the cost decision's


def test_attacking_team_decision_errors(tmp_path):
    import torch

    from ssl_marl.decisions.match_decider import make_match_decider

    bad = tmp_path / "attack_3v2_actor.pt"
    torch.save({"format": "ssl_marl.decision_actor/1", "task": "attack-3v2", "obs_dim": 40, "n_options": 6,
                "hidden": [8], "state_dict": {}}, bad)
    with pytest.raises(ValueError, match="obs_dim=40"):
        make_match_decider(str(bad), task="attack-drill")
    with pytest.raises(ValueError, match="unknown decision task"):
        make_match_decider("learned", task="keepaway")
    from ssl_marl.decisions.learned import pretrained_path

    with pytest.raises(ValueError, match="obs_dim=40"):  # the shipped Attack 3v2 actor for an attacking team
        make_match_decider(str(pretrained_path("attack-3v2")), task="attack-drill")
