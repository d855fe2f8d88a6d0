"""The attack drill under SSL rules (``attack-drill-ssl``): the attackers' fouls end the attack,
and the dribble options are masked as the match's learned decider masks them."""

from __future__ import annotations

import math

import numpy as np
import pytest

from ssl_marl.decisions import DECISION_TASKS, make_decision_env, make_decision_policy
from ssl_marl.decisions.attack_drill import AttackDrillEnv, AttackDrillSSLEnv, HandcodedAttackDrillPolicy
from ssl_marl.decisions.attack_drill_features import DRIBBLE_GOAL_OPTION, DRIBBLE_OPTIONS, SHOOT
from ssl_marl.decisions.dribble_limit import DRIBBLE_MASK_M
from ssl_marl.decisions.learned import decision_family, pretrained_path
from ssl_marl.decisions.policies import run_episode
from ssl_marl.envs.tasks.attack import OUTCOMES, AttackRules
from ssl_marl.plays.scene import ball_in_front


class _Dribbler:
    """Dribbles towards the goal whenever the mask allows it, else shoots; records the masks."""

    def __init__(self) -> None:
        self.masks: list[np.ndarray] = []

    def reset(self, env) -> None:
        self.masks.clear()

    def act(self, env, agent, obs, info):
        mask = np.asarray(info["action_mask"])
        self.masks.append(mask.copy())
        return DRIBBLE_GOAL_OPTION if mask[DRIBBLE_GOAL_OPTION] else SHOOT


def _scene(carrier=(0.0, 0.0, 0.0), defender=(1.0, 2.7, math.pi)) -> dict:
    """The carrier (blue_1) with the ball at its dribbler in the middle of the attacking half, its
    mates wide, the goalie on its line and the defender out of the way (field frame, m, rad)."""
    return {"robots": {"blue_0": [-4.2, 0.0, 0.0], "blue_1": list(carrier), "blue_2": [2.0, 2.5, 0.0],
                       "blue_3": [2.0, -2.5, 0.0], "yellow_0": [4.25, 0.0, math.pi], "yellow_1": list(defender)},
            "ball": {"pos": list(ball_in_front(*carrier))}}


def _events(env_cls, **kw):
    env = env_cls(skills="baseline", rules=AttackRules(max_time_s=8.0, fouls=kw.pop("fouls", True)), **kw)
    fouls = []
    orig = env.task.after_tick

    def spy(engine, events):
        done = orig(engine, events)
        fouls.extend(e for e in events if e["type"] == "foul" and e not in fouls)
        return done

    env.task.after_tick = spy
    return env, fouls


def test_an_unmasked_dribble_past_1_m_is_a_foul_that_ends_the_attack():
    env, fouls = _events(AttackDrillSSLEnv, dribble_mask_m=None)
    res = run_episode(env, _Dribbler(), seed=1, options=_scene())
    assert res["outcome"] == "foul" and res["goal"] == 0 and res["terminated"]
    assert [f["foul"] for f in fouls] == ["excessive_dribbling"] and fouls[0]["team"] == "blue"
    # the same attack in the plain drill (no fouls called) runs on past the foul's time
    plain, plain_fouls = _events(AttackDrillEnv, fouls=False)
    res_plain = run_episode(plain, _Dribbler(), seed=1, options=_scene())
    assert res_plain["outcome"] != "foul" and not plain_fouls and res_plain["t_s"] > res["t_s"]


def test_the_dribble_mask_stops_the_dribble_before_the_limit():
    env, fouls = _events(AttackDrillSSLEnv)
    assert env.dribble_mask_m == DRIBBLE_MASK_M == 0.5
    pol = _Dribbler()
    res = run_episode(env, pol, seed=1, options=_scene())
    assert res["outcome"] != "foul" and not fouls
    masked = [m for m in pol.masks if not m[list(DRIBBLE_OPTIONS)].any()]
    assert masked and all(m[SHOOT] for m in masked)  # it was made to shoot (or pass) before 1 m


def test_touching_the_ball_in_the_goalies_defense_area_is_a_foul():
    env, fouls = _events(AttackDrillSSLEnv)
    x = env.field.half_length - 0.6  # inside the +x defense area (1 m deep on Division B)
    res = run_episode(env, HandcodedAttackDrillPolicy(), seed=1, options=_scene(carrier=(x, 0.4, 0.0)))
    assert res["outcome"] == "foul" and fouls[0]["foul"] == "attacker_in_defense_area"


def test_registry_api_and_errors():
    from pettingzoo.test import parallel_api_test

    assert "foul" in OUTCOMES and AttackRules().fouls is False
    env = make_decision_env("attack-drill-ssl", skills="baseline", rules=AttackRules(max_time_s=2.0, fouls=True),
                            illegal_option="default")
    assert isinstance(env, AttackDrillSSLEnv) and "attack-drill-ssl" in DECISION_TASKS
    assert env.passing.dribble_cut_m is not None  # the match's dribble cut
    parallel_api_test(env, num_cycles=20)
    assert isinstance(make_decision_policy("handcoded", "attack-drill-ssl"), HandcodedAttackDrillPolicy)
    # the drill's actors play it (one decision family, one shipped actor)
    assert decision_family("attack-drill-ssl") == "attack-drill"
    assert pretrained_path("attack-drill-ssl") == pretrained_path("attack-drill")
    with pytest.raises(ValueError, match="must call fouls"):
        AttackDrillSSLEnv(skills="baseline", rules=AttackRules())
    with pytest.raises(ValueError, match="dribble_mask_m"):
        AttackDrillSSLEnv(skills="baseline", dribble_mask_m=float("nan"))


def test_deterministic_under_the_seed():
    from ssl_marl.decisions.policies import RandomPolicy

    a = run_episode(make_decision_env("attack-drill-ssl", skills="baseline"), RandomPolicy(3), seed=49605, record=True)
    b = run_episode(make_decision_env("attack-drill-ssl", skills="baseline"), RandomPolicy(3), seed=49605, record=True)
    assert a["trace"] == b["trace"] and a["outcome"] == b["outcome"]
