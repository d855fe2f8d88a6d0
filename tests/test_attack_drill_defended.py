"""The attack drill against the match's defence (``attack-drill-defended``): six defenders placed as
documented, the match's defense play, a contested ball that plays on, the drill's observation."""

from __future__ import annotations

import math

import numpy as np
import pytest

from ssl_marl.decisions import DECISION_TASKS, make_decision_env, make_decision_policy
from ssl_marl.decisions.attack import STATE_DIM
from ssl_marl.decisions.attack_drill import AttackDrillDefendedEnv, AttackDrillSSLEnv, HandcodedAttackDrillPolicy
from ssl_marl.decisions.attack_drill_features import ATTACK_DRILL_OBS_DIM
from ssl_marl.decisions.learned import decision_family, pretrained_path
from ssl_marl.decisions.policies import RandomPolicy, run_episode
from ssl_marl.envs.tasks.attack import MAX_DEFENCE, OUTCOMES, AttackRules
from ssl_marl.plays.scene import ball_in_front


def _poses(env) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    w = env.engine.world_state()
    return np.asarray(w.blue.pos), np.asarray(w.yellow.pos), np.asarray(w.ball_pos)


@pytest.fixture(scope="module")
def defended():
    return AttackDrillDefendedEnv(skills="baseline")


def test_the_defence_is_placed_as_documented(defended):
    env, f = defended, defended.field
    plain = AttackDrillSSLEnv(skills="baseline")
    assert env.n_defence == MAX_DEFENCE == 6
    for seed in range(159_900, 159_930):  # outside every evaluation, validation and tuning range
        env.reset(seed=seed)
        plain.reset(seed=seed)
        blue, yellow, ball = _poses(env)
        blue0, yellow0, ball0 = _poses(plain)
        assert len(yellow) == 6
        # the first six robots and the ball are drawn as in the drill with a goalie and one defender
        np.testing.assert_array_equal(blue, blue0)
        np.testing.assert_array_equal(yellow[:2], yellow0)
        np.testing.assert_array_equal(ball, ball0)
        for q in yellow[1:]:  # field defenders: outside their defense area, inside the field
            assert not f.in_defense_area(q, +1) and abs(q[1]) <= f.half_width - 0.2 + 1e-9
        centres = np.vstack([blue[1:], yellow[:2]])
        for q in yellow[2:]:  # the defenders this drill adds stand on nobody (robots are 0.18 m wide)
            assert np.hypot(*(centres - q).T).min() >= 0.18
            centres = np.vstack([centres, q])
        presser_ball = float(np.hypot(*(yellow[3] - ball)))
        assert 0.5 <= presser_ball <= 2.6  # 1.5-2.5 m, less where kept out of the defense area
        carrier = int(env.task.carrier_robot.rsplit("_", 1)[1])
        mates = [k for k in (1, 2, 3) if k != carrier]
        for mark, mate in zip(yellow[4:], blue[mates]):  # goal-side of the attackers without the ball
            near = float(np.hypot(*(mark - mate)))
            assert near <= 1.5 and near < float(np.hypot(*(mark - ball))) + 0.5


def test_a_contested_ball_plays_on_and_a_held_one_is_lost():
    """A defender and the carrier both on the ball: Attack 3v2 ends the attack, the defended drill plays on;
    the defender alone on it ends both."""
    x, y = 1.0, 0.0
    bx, by = ball_in_front(x, y, 0.0)
    # a presser facing the carrier across the ball, its dribbler on the ball too
    px = bx + (bx - x)
    robots = {"blue_0": [-4.2, 0.0, 0.0], "blue_1": [x, y, 0.0], "blue_2": [2.0, 2.5, 0.0], "blue_3": [2.0, -2.5, 0.0],
              "yellow_0": [4.25, 0.0, math.pi], "yellow_1": [3.0, 0.5, math.pi], "yellow_2": [3.0, -0.5, math.pi],
              "yellow_3": [px, by, math.pi], "yellow_4": [2.4, 2.0, math.pi], "yellow_5": [2.4, -2.0, math.pi]}
    contested = {"robots": robots, "ball": {"pos": [bx, by]}}
    alone = {"robots": {**robots, "blue_1": [x - 1.0, y, 0.0]}, "ball": {"pos": [bx, by]}}
    for rules, contested_end in ((AttackRules(fouls=True, contested_plays_on=True), None),
                                 (AttackRules(fouls=True), "lost_defender")):
        env = AttackDrillDefendedEnv(skills="baseline", rules=rules)
        env.reset(seed=1, options=contested)
        w = env.engine.world_state()
        assert bool(w.blue.ball_on_dribbler[1]) and bool(w.yellow.ball_on_dribbler[3])
        assert env.task.judge(env.engine) == contested_end
        env.reset(seed=1, options=alone)
        w = env.engine.world_state()
        assert not w.blue.ball_on_dribbler.any() and bool(w.yellow.ball_on_dribbler[3])
        assert env.task.judge(env.engine) == "lost_defender"


def test_episodes_observation_state_and_registry(defended):
    env = defended
    assert "attack-drill-defended" in DECISION_TASKS
    assert isinstance(make_decision_env("attack-drill-defended", skills="baseline"), AttackDrillDefendedEnv)
    assert isinstance(make_decision_policy("handcoded", "attack-drill-defended"), HandcodedAttackDrillPolicy)
    assert decision_family("attack-drill-defended") == "attack-drill"
    assert pretrained_path("attack-drill-defended") == pretrained_path("attack-drill")
    assert env.rules.fouls and env.rules.contested_plays_on and env.dribble_mask_m is not None
    assert env.state_space.shape == (STATE_DIM + 4 * 4,)
    assert env.observation_space("attacker_0").shape == (ATTACK_DRILL_OBS_DIM,)
    res = run_episode(env, HandcodedAttackDrillPolicy(), seed=159_950)
    assert res["outcome"] in OUTCOMES and res["terminated"] != res["truncated"]
    s = env.global_state()
    assert s.shape == (STATE_DIM + 16,) and np.isfinite(s).all()
    # the defence is the match's: its robots take the defense play's roles
    assert env.yellow.selector.plays[0].name == "match_defence"
    a = run_episode(AttackDrillDefendedEnv(skills="baseline"), RandomPolicy(3), seed=159_951, record=True)
    b = run_episode(AttackDrillDefendedEnv(skills="baseline"), RandomPolicy(3), seed=159_951, record=True)
    assert a["trace"] == b["trace"] and a["outcome"] == b["outcome"]


@pytest.mark.parametrize("bad", [2, 7, 0, 4.5, True, "6"])
def test_bad_defence_sizes_are_refused(bad):
    with pytest.raises(ValueError, match="n_defence"):
        AttackDrillDefendedEnv(skills="baseline", n_defence=bad)


def test_smaller_defences_field_the_first_roles():
    env = AttackDrillDefendedEnv(skills="baseline", n_defence=3)
    env.reset(seed=159_960)
    assert len(env.engine.world_state().yellow.pos) == 3 and env.state_space.shape == (STATE_DIM + 4,)
    assert run_episode(env, HandcodedAttackDrillPolicy(), seed=159_961)["outcome"] in OUTCOMES
