"""The generic DecisionEnv (ssl_marl/decisions/base.py) on a toy task: one blue robot decides
every 0.1 s between "stay" and "go"; reward dt per tick; the episode truncates at 1 s."""

from __future__ import annotations

import numpy as np
import pytest

from ssl_marl.decisions import DECISION_POLICIES, DECISION_TASKS, make_decision_policy
from ssl_marl.decisions.base import DecisionEnv
from ssl_marl.decisions.policies import RandomPolicy, run_episode
from ssl_marl.envs.tasks import Task


class _ToyTask(Task):
    name = "toy"

    def start(self, env):
        self.outcome = None

    def rewards(self, env):
        return {a: env.config.dt for a in env.agents}, {"blue": {}, "yellow": {}}

    def end(self, env):
        if env.world_state().t >= 1.0 - 1e-9:
            self.outcome = "time"
            return False, True
        return False, False


class _ToyEnv(DecisionEnv):
    task_name = "toy"
    option_names = ("stay", "go")
    agent_prefix = "bot"
    n_agents = 1

    def make_task(self):
        return _ToyTask()

    def engine_kwargs(self):
        return {"n_blue": 1, "n_yellow": 0}

    def on_reset(self):
        self.opt, self.since = 0, 0.0

    def decision_agents(self):
        return frozenset({"bot_0"}) if self.t - self.since >= 0.1 - 1e-9 or self.t == 0.0 else frozenset()

    def action_mask(self, agent):
        return np.array([1, 1], np.int8)

    def start_options(self, chosen):
        self.opt, self.since = chosen["bot_0"], self.t

    def tick_actions(self):
        return {"blue_0": np.array([0.5 * self.opt, 0, 0, 0, 0], np.float32)}

    def observe(self):
        return {"bot_0": np.array([self.t], np.float32)}

    def observation_bounds(self):
        return np.zeros(1), np.full(1, 100.0)

    def global_state(self):
        return np.array([self.t], np.float32)

    def state_bounds(self):
        return np.zeros(1), np.full(1, 100.0)


def test_toy_decision_env_steps_until_decisions_and_sums_rewards():
    env = _ToyEnv()
    obs, infos = env.reset(seed=3)
    assert infos["bot_0"]["decision"] and infos["bot_0"]["elapsed_s"] == 0.0
    total, steps = 0.0, 0
    while env.agents:
        obs, rew, term, trunc, infos = env.step({"bot_0": 1})
        total += rew["bot_0"]
        steps += 1
        assert infos["bot_0"]["elapsed_s"] == pytest.approx(rew["bot_0"])
    assert trunc["bot_0"] and not term["bot_0"]
    assert infos["bot_0"]["outcome"] == "time"
    assert total == pytest.approx(1.0, abs=1e-6)
    assert steps == 10


def test_bad_actions_name_the_problem():
    env = _ToyEnv()
    env.reset(seed=0)
    with pytest.raises(ValueError, match="bot_0"):
        env.step({"bot_0": float("nan")})
    with pytest.raises(ValueError, match="outside"):
        env.step({"bot_0": 2})
    with pytest.raises(ValueError, match="unknown agent"):
        env.step({"bot_9": 0})
    with pytest.raises(ValueError, match="no action"):
        env.step({})
    with pytest.raises(ValueError, match="max_interval_s"):
        _ToyEnv(max_interval_s=0)


def test_run_episode_and_registries():
    env = _ToyEnv()
    r1 = run_episode(env, RandomPolicy(5), seed=11)
    r2 = run_episode(env, RandomPolicy(5), seed=11)
    assert r1 == r2 and r1["decisions"] == 10 and r1["outcome"] == "time"
    assert set(DECISION_TASKS) >= {"keepaway", "attack-3v2"}
    assert set(DECISION_POLICIES) == {"learned", "handcoded", "random", "always-hold", "improved"}
    with pytest.raises(ValueError, match="unknown decision policy"):
        make_decision_policy("nope", "keepaway")
    with pytest.raises(ValueError, match="unknown decision task"):
        make_decision_policy("random", "nope")


def test_toy_passes_parallel_api_test():
    """PettingZoo's API test (it resets once with ``options={"options": 1}``, a key no task
    knows: the engine warns and ignores it)."""
    from pettingzoo.test import parallel_api_test

    with pytest.warns(UserWarning, match=r"reset options: ignoring unknown key\(s\) \['options'\]"):
        parallel_api_test(_ToyEnv(), num_cycles=30)
