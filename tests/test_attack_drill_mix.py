"""The attack drill with its defence drawn per episode (``attack-drill-mix``): each episode is the
drawn drill's own episode on that seed, the draw follows ``p_defended``, the critic's state says which
drill plays, and two teachers can be cloned into one actor."""

from __future__ import annotations

import numpy as np
import pytest

from ssl_marl.decisions import DECISION_TASKS, make_decision_env, make_decision_policy
from ssl_marl.decisions.attack_drill import AttackDrillDefendedEnv, AttackDrillSSLEnv, HandcodedAttackDrillPolicy
from ssl_marl.decisions.attack_drill_mix import MIX_DRILLS, AttackDrillMixEnv, PerDrillPolicy, drill_of_seed
from ssl_marl.decisions.learned import decision_family, pretrained_path
from ssl_marl.decisions.policies import run_episode

SEEDS = range(159_970, 159_990)  # outside every evaluation, validation and tuning range


@pytest.fixture(scope="module")
def mix():
    return AttackDrillMixEnv(skills="baseline")


def test_registered_as_a_drill_of_the_attacking_decision():
    assert "attack-drill-mix" in DECISION_TASKS
    assert isinstance(make_decision_env("attack-drill-mix", skills="baseline"), AttackDrillMixEnv)
    assert isinstance(make_decision_policy("handcoded", "attack-drill-mix"), HandcodedAttackDrillPolicy)
    assert decision_family("attack-drill-mix") == "attack-drill"
    assert pretrained_path("attack-drill-mix") == pretrained_path("attack-drill")


def test_an_episode_is_the_drawn_drills_own_episode(mix):
    drills = {"one-defender": AttackDrillSSLEnv(skills="baseline"), "defended": AttackDrillDefendedEnv(skills="baseline")}
    seen = set()
    for seed in list(SEEDS)[:8]:
        obs, _ = mix.reset(seed=seed)
        assert mix.drill_name == MIX_DRILLS[drill_of_seed(seed, 0.5)]
        seen.add(mix.drill_name)
        own, _ = drills[mix.drill_name].reset(seed=seed)
        for a in mix.possible_agents:
            np.testing.assert_array_equal(obs[a], own[a])
        assert len(mix.engine.world_state().yellow.pos) == (6 if mix.drill_name == "defended" else 2)
    assert seen == set(MIX_DRILLS)


def test_the_draw_follows_p_defended():
    assert all(drill_of_seed(s, 0.0) == 0 and drill_of_seed(s, 1.0) == 1 for s in range(200))
    share = np.mean([drill_of_seed(s, 0.3) for s in range(2000)])
    assert abs(share - 0.3) < 0.04
    only = AttackDrillMixEnv(p_defended=1.0, skills="baseline")
    only.reset(seed=SEEDS[0])
    assert only.drill_name == "defended"


def test_state_pads_to_the_defended_drill_and_flags_it(mix):
    n = AttackDrillDefendedEnv(skills="baseline").state_space.shape[0] + 1
    assert mix.state_space.shape == (n,)
    for seed in SEEDS:
        mix.reset(seed=seed)
        s = mix.state()
        assert s.shape == (n,) and mix.state_space.contains(s)
        assert s[-1] == (1.0 if mix.drill_name == "defended" else 0.0)
        if mix.drill_name == "one-defender":
            assert not s[len(mix.drill.state()):-1].any()


def test_finished_episodes_name_their_drill(mix):
    pol = HandcodedAttackDrillPolicy()
    for seed in list(SEEDS)[:6]:
        obs, infos = mix.reset(seed=seed)
        pol.reset(mix)
        while mix.agents:
            act = {a: pol.act(mix, a, obs[a], infos[a]) for a in mix.agents if infos[a]["decision"]}
            obs, _, _, _, infos = mix.step(act)
        assert all(i["drill"] == mix.drill_name and "outcome" in i for i in infos.values())


def test_hand_coded_episodes_are_deterministic(mix):
    pol = make_decision_policy("handcoded", "attack-drill-mix")
    a = [run_episode(mix, pol, seed=s)["outcome"] for s in list(SEEDS)[:4]]
    b = [run_episode(mix, pol, seed=s)["outcome"] for s in list(SEEDS)[:4]]
    assert a == b


def test_parallel_api():
    from pettingzoo.test import parallel_api_test

    parallel_api_test(AttackDrillMixEnv(skills="baseline", illegal_option="default"), num_cycles=60)


@pytest.mark.parametrize("p", [-0.1, 1.5, float("nan"), True, "0.5"])
def test_bad_p_defended_is_refused(p):
    with pytest.raises(ValueError, match="p_defended"):
        AttackDrillMixEnv(p_defended=p, skills="baseline")


def test_per_drill_policy_needs_every_drill_and_plays_each():
    hc = HandcodedAttackDrillPolicy()
    with pytest.raises(ValueError, match="missing"):
        PerDrillPolicy({"one-defender": hc})
    with pytest.raises(ValueError, match="unknown"):
        PerDrillPolicy({"one-defender": hc, "defended": hc, "two": hc})

    class Count(HandcodedAttackDrillPolicy):
        def __init__(self):
            super().__init__()
            self.n = 0

        def act(self, env, agent, obs, info):
            self.n += 1
            return super().act(env, agent, obs, info)

    one, defended = Count(), Count()
    pol = PerDrillPolicy({"one-defender": one, "defended": defended})
    env = AttackDrillMixEnv(skills="baseline")
    for seed in list(SEEDS)[:8]:
        before = (one.n, defended.n)
        run_episode(env, pol, seed=seed)
        changed = (one.n > before[0], defended.n > before[1])
        assert not changed[1 - MIX_DRILLS.index(env.drill_name)]


def test_bc_teachers_are_parsed_with_clear_errors():
    from train.mappo.bc import parse_teachers

    pol = parse_teachers("attack-drill-mix", ["one-defender=handcoded", "defended=random"])
    assert isinstance(pol, PerDrillPolicy)
    with pytest.raises(ValueError, match="DRILL=POLICY"):
        parse_teachers("attack-drill-mix", ["one-defender"])
    with pytest.raises(ValueError, match="missing"):
        parse_teachers("attack-drill-mix", ["one-defender=handcoded"])
