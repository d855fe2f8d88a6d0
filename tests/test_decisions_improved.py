"""The hand-coded decision improved by a value actor at an episode's first decisions."""

import gymnasium
import numpy as np
import pytest
import torch

from ssl_marl.decisions.learned import DecisionActor, ImprovedDecisionPolicy


class FixedPolicy:
    """A benchmark stand-in: always ``option``; counts its calls and resets."""

    def __init__(self, option: int) -> None:
        self.option, self.calls, self.resets = option, 0, 0

    def reset(self, env) -> None:
        self.resets += 1

    def act(self, env, agent, obs, info) -> int:
        self.calls += 1
        return self.option


class TinyEnv:
    """What the policies check on reset: one agent, 3 observation values, 4 options."""

    possible_agents = ["a"]
    option_names = None

    def observation_space(self, agent):
        return gymnasium.spaces.Box(-1.0, 1.0, (3,), np.float32)

    def action_space(self, agent):
        return gymnasium.spaces.Discrete(4)


def value_actor(values) -> DecisionActor:
    """A value actor that predicts ``values`` (one per option) whatever it observes."""
    actor = DecisionActor(3, 4, ())
    with torch.no_grad():
        actor.net[0].weight.zero_()
        actor.net[0].bias.copy_(torch.tensor(values, dtype=torch.float32))
    return actor


def play(policy, n: int, mask=(1, 1, 1, 1)) -> list[int]:
    obs, info = np.zeros(3, np.float32), {"action_mask": np.array(mask, np.int8)}
    return [policy.act(TinyEnv(), "a", obs, info) for _ in range(n)]


def test_the_value_actor_decides_only_the_first_decisions_and_only_for_a_clear_gain():
    base = FixedPolicy(0)
    pol = ImprovedDecisionPolicy(base, value_actor([0.3, 0.6, 0.2, 0.9]), margin=0.1)
    pol.reset(TinyEnv())
    assert play(pol, 3) == [3, 0, 0]  # 0.9 beats the benchmark's 0.3 by more than 0.1, once
    assert base.calls == 3 and pol.deviations == 1  # the benchmark decides every time (its own state)
    pol.reset(TinyEnv())
    assert base.resets == 2 and play(pol, 1, mask=(1, 1, 1, 0)) == [1]  # the best legal option
    assert play(ImprovedDecisionPolicy(FixedPolicy(0), value_actor([0.3, 0.6, 0.2, 0.9]), margin=0.7), 2) == [0, 0]
    assert play(ImprovedDecisionPolicy(FixedPolicy(2), value_actor([0.3, 0.6, 0.2, 0.9]), first_k=2), 3) == [3, 3, 2]
    assert play(ImprovedDecisionPolicy(FixedPolicy(1), value_actor([0.3, 0.6, 0.2, 0.9]), first_k=0), 2) == [1, 1]


def test_bad_settings_and_a_mismatched_actor_are_refused():
    with pytest.raises(ValueError, match="margin"):
        ImprovedDecisionPolicy(FixedPolicy(0), value_actor([0, 0, 0, 0]), margin=float("nan"))
    with pytest.raises(ValueError, match="first_k"):
        ImprovedDecisionPolicy(FixedPolicy(0), value_actor([0, 0, 0, 0]), first_k=-1)
    pol = ImprovedDecisionPolicy(FixedPolicy(0), DecisionActor(5, 4, (4,)))
    with pytest.raises(ValueError, match="observations of size 5"):
        pol.reset(TinyEnv())


def test_a_value_actor_file_records_how_it_is_played(tmp_path):
    """``first_k`` and ``margin`` default to the file's ``improve`` record; arguments override it."""
    from ssl_marl.skills.checkpoint import save_actor_file

    actor = value_actor([0.3, 0.6, 0.2, 0.9])
    state = {f"net.{k}": v for k, v in actor.net.state_dict().items()}
    meta = {"task": None, "obs_dim": 3, "n_options": 4, "hidden": [], "agent_ids": None, "option_names": None}
    plain, recorded = tmp_path / "plain.pt", tmp_path / "k2.pt"
    save_actor_file(plain, "decision", state, meta)
    save_actor_file(recorded, "decision", state, {**meta, "improve": {"first_k": 2, "margin": 0.5}})
    assert play(ImprovedDecisionPolicy(FixedPolicy(0), plain), 3) == [3, 0, 0]  # 1 decision, margin 0.1
    pol = ImprovedDecisionPolicy(FixedPolicy(0), recorded)
    assert (pol.first_k, pol.margin) == (2, 0.5) and play(pol, 3) == [3, 3, 0]
    assert play(ImprovedDecisionPolicy(FixedPolicy(0), recorded, margin=0.7), 2) == [0, 0]
    assert play(ImprovedDecisionPolicy(FixedPolicy(0), recorded, first_k=1), 2) == [3, 0]


def test_in_a_match_the_value_actor_decides_once_per_possession():
    from types import SimpleNamespace

    from ssl_marl.decisions.match_decider import DRILL_TASK, TASK, ImprovedAttackDecider, make_match_decider
    from ssl_marl.runners.match import play_match

    dec = make_match_decider("improved", task=DRILL_TASK)
    assert isinstance(dec, ImprovedAttackDecider)
    assert dec.margin == 0.0  # the margin the shipped value actor file records
    first = [dec._first_of_possession(SimpleNamespace(t=t, carrier=c)) for t, c in
             [(0.0, 2), (0.1, 2), (0.2, 2), (1.0, 3), (1.1, 3)]]
    assert first == [True, False, False, True, False]  # a request after a gap opens a possession
    dec._passed_to = 4
    assert dec._first_of_possession(SimpleNamespace(t=3.0, carrier=4)) is False  # our own pass arrived
    with pytest.raises(ValueError, match="attacking plays"):
        make_match_decider("improved", task=TASK)

    deviations = decisions = 0
    for seed in (6, 7):  # two short matches (one deviates once of 38 decisions, the other 13 times of 28, shipped actors)
        dec = make_match_decider("improved", task=DRILL_TASK)
        play_match("attack-learned", "attack-learned", robots=6, seconds=40, seed=seed, render=None, progress=False,
                   blue_decision=dec)
        deviations, decisions = deviations + dec.deviations, decisions + sum(vars(dec.counters).values())
    assert 1 <= deviations < decisions / 4
