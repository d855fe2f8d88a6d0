"""Env tasks and realism effects: what an episode is about plugs into the engine."""

import numpy as np
import pytest
from pettingzoo.test import parallel_api_test

from ssl_marl.envs import parallel_env
from ssl_marl.envs.config import MatchRules, RealismConfig
from ssl_marl.envs.realism import (BallDropout, CommandDelay, CommandEffect, CommandLoss, Radio, Vision,
                                   VisionNoise, command_effects, vision_effects)
from ssl_marl.envs.tasks import Engine, FreePlayTask, MatchTask, Scene, Task, make_task


class KeepawayToy(Task):
    """A two-team drill: blue keeps the ball in a 2 m circle; per-agent rewards; ends when
    the ball leaves the circle (terminated) or after 2 s (truncated)."""

    name = "keepaway_toy"

    def reset_scene(self, env, options):
        n = len(env.possible_agents)
        ang = np.linspace(0, 2 * np.pi, n, endpoint=False)
        pose = np.column_stack([1.2 * np.cos(ang), 1.2 * np.sin(ang), ang + np.pi])
        return Scene(pose, np.zeros(2), np.array([0.5, 0.0]))

    def after_tick(self, env, events):
        out = float(np.hypot(*env.world_state().ball_pos)) > 2.0
        if out:
            events.append({"type": "drill_over"})
        return out

    def rewards(self, env):
        inside = float(np.hypot(*env.world_state().ball_pos)) <= 2.0
        r = {a: (1.0 if inside else -1.0) * (1 if env.team_of(a) == "blue" else -1) for a in env.agents}
        return r, {"blue": {"keep": r.get("blue_0", 0.0)}, "yellow": {"keep": -r.get("blue_0", 0.0)}}

    def end(self, env):
        over = float(np.hypot(*env.world_state().ball_pos)) > 2.0
        return over, (not over) and env.world_state().t >= 2.0 - 1e-9


def test_a_multi_agent_drill_plugs_in_as_a_task():
    env = parallel_env(n_blue=3, n_yellow=2, task=KeepawayToy())
    obs, _ = env.reset(seed=0)
    np.testing.assert_allclose(env.world_state().ball_vel, (0.5, 0.0), atol=1e-6)
    steps = 0
    while env.agents:
        _, rew, term, trunc, infos = env.step({})
        steps += 1
        assert set(rew.values()) <= {1.0, -1.0}
        assert infos["blue_0"]["reward_terms"]["keep"] in (1.0, -1.0)
    assert any(term.values()) or steps == 120
    parallel_api_test(parallel_env(n_blue=2, n_yellow=1, task=KeepawayToy()), num_cycles=50)


def test_free_play_has_no_rules_rewards_or_end():
    env = parallel_env(n_blue=1, n_yellow=0, task="free_play", max_time_s=0.1)
    env.reset(seed=0, options={"robots": {"blue_0": (4.4, 0.0, 0.0)}, "ball": {"pos": (4.45, 0.0), "vel": (5.0, 0.0)}})
    goals = 0
    for _ in range(60):  # past max_time_s (a match parameter): no truncation; the ball enters the goal: no goal
        _, rew, term, trunc, infos = env.step({})
        goals += sum(ev["type"] == "goal" for ev in infos["blue_0"]["events"])
        assert rew["blue_0"] == 0.0 and not term["blue_0"] and not trunc["blue_0"]
    assert goals == 0 and env.score == {"blue": 0, "yellow": 0}


def test_task_argument_errors_are_clear():
    with pytest.raises(ValueError, match="task must be one of"):
        parallel_env(task="penalty_shootout")
    task = MatchTask()
    parallel_env(n_blue=1, n_yellow=1, task=task)
    with pytest.raises(ValueError, match="already belongs"):
        parallel_env(n_blue=1, n_yellow=1, task=task)
    assert isinstance(make_task("free_play"), FreePlayTask) and make_task(task) is task


def test_match_task_rules_come_from_the_env_config():
    env = parallel_env(n_blue=1, n_yellow=1, after_goal="terminate", max_time_s=5.0, referee=False)
    rules = env.task.rules
    assert (rules.after_goal, rules.max_time_s, rules.referee) == ("terminate", 5.0, False)
    assert rules is env.config.match
    assert rules == MatchRules(after_goal="terminate", max_time_s=5.0, referee=False)


def test_match_parameters_as_keywords_or_as_one_match_option():
    by_keywords = parallel_env(n_blue=1, n_yellow=1, max_time_s=5.0, reward_scales={"possession": 1.0})
    by_dict = parallel_env(n_blue=1, n_yellow=1, match={"max_time_s": 5.0, "reward_scales": {"possession": 1.0}})
    by_rules = parallel_env(n_blue=1, n_yellow=1, match=MatchRules(max_time_s=5.0, reward_scales={"possession": 1.0}))
    assert by_keywords.config.match == by_dict.config.match == by_rules.config.match
    assert by_rules.config.match.reward_scales == {"goal": 1.0, "ball_progress": 0.0, "possession": 1.0}
    with pytest.raises(ValueError, match="not both"):
        parallel_env(match=MatchRules(), max_time_s=5.0)
    with pytest.raises(ValueError, match="match"):
        parallel_env(match=5)


def test_the_env_offers_what_the_engine_protocol_names():
    env = parallel_env(n_blue=1, n_yellow=1)
    members = set(Engine.__annotations__) | {n for n in vars(Engine) if not n.startswith("_")}
    assert members >= {"config", "field", "np_random", "world_state", "place_ball", "award_goal"}
    assert all(hasattr(env, m) for m in members), sorted(m for m in members if not hasattr(env, m))


def test_the_config_module_imports_nothing_else_from_envs():
    import ast
    from pathlib import Path

    import ssl_marl.envs.config as config

    tree = ast.parse(Path(config.__file__).read_text())
    relative = [n.module for n in ast.walk(tree) if isinstance(n, ast.ImportFrom) and n.level]
    assert relative and all(m.startswith("physics") for m in relative), relative


def test_realism_effects_are_a_composable_list():
    cfg = RealismConfig.preset("realistic")
    assert [type(e) for e in vision_effects(cfg)] == [BallDropout, VisionNoise]
    assert [type(e) for e in command_effects(cfg)] == [CommandDelay, CommandLoss]
    assert vision_effects(RealismConfig()) == [] and command_effects(RealismConfig()) == []

    class Invert(CommandEffect):  # a new effect: one class, put in the list
        def apply(self, actions, rng):
            return -actions

    radio = Radio(None, 2, 5, effects=[CommandDelay(1), Invert()])
    radio.reset()
    rng = np.random.default_rng(0)
    a = np.ones((2, 5))
    np.testing.assert_array_equal(radio.transmit(a, rng), np.zeros((2, 5)))  # delayed: zeros first
    np.testing.assert_array_equal(radio.transmit(2 * a, rng), -a)
    env = parallel_env(n_blue=1, n_yellow=0)
    env.reset(seed=0)
    truth = env.world_state()
    vision = Vision(effects=[VisionNoise(ball_pos_sigma=0.01)], latency_steps=0)
    seen = vision.reset(truth, np.random.default_rng(1))
    assert not np.allclose(seen.ball_pos, truth.ball_pos) and np.allclose(seen.blue.pos, truth.blue.pos)
    assert Vision(RealismConfig()).reset(truth, rng) is truth
