"""Plays, play selection, and the TeamController on real env scenes."""

import math
from types import SimpleNamespace

import numpy as np
import pytest

from ssl_marl.envs import parallel_env
from ssl_marl.physics import FieldGeometry
from ssl_marl.physics.params import RobotParams
from ssl_marl.plays.play import (Play, PlaySelector, defense_applicable, kickoff_applicable, make_context,
                                 offense_applicable, standard_plays)
from ssl_marl.plays.scene import make_world
from ssl_marl.plays.shoot import GoToBallAndShoot
from ssl_marl.plays.team import TeamController

F = FieldGeometry.div_b()


def legal(actions, agents):
    assert set(actions) == set(agents)
    for a in actions.values():
        a = np.asarray(a)
        assert a.shape == (5,) and np.isfinite(a).all() and (np.abs(a) <= 1.0).all()


# ------------------------------------------------------------- play selection
def fake_play(name, flag, priority=0, timeout_s=25.0):
    return Play(name, lambda ctx: bool(ctx.flags.get(flag)), (), timeout_s=timeout_s, priority=priority)


def test_selector_holds_a_play_for_the_minimum_time():
    a, b = fake_play("a", "a"), fake_play("b", "b")
    sel = PlaySelector([a, b], min_hold_s=0.5)
    assert sel.select(SimpleNamespace(flags={"a": 1}), 0.0) is a
    only_b = SimpleNamespace(flags={"b": 1})
    assert sel.select(only_b, 0.2) is a  # hysteresis
    assert sel.select(only_b, 0.6) is b
    both = SimpleNamespace(flags={"a": 1, "b": 1})
    assert sel.select(both, 2.0) is b  # still applicable: kept
    assert sel.stats["a"].selections == 1 and sel.stats["b"].selections == 1


def test_selector_preemption_timeout_and_fallback():
    kick, a = fake_play("kickoff", "k", priority=1), fake_play("a", "a", timeout_s=1.0)
    sel = PlaySelector([a, kick], min_hold_s=0.5)
    assert sel.select(SimpleNamespace(flags={"a": 1}), 0.0) is a
    assert sel.select(SimpleNamespace(flags={"a": 1, "k": 1}), 0.7) is kick  # higher priority preempts
    assert sel.select(SimpleNamespace(flags={"a": 1}), 1.3) is a
    assert sel.select(SimpleNamespace(flags={"a": 1}), 2.4) is a  # timed out, re-selected (only one)
    assert sel.since == pytest.approx(2.4)
    assert sel.select(SimpleNamespace(flags={}), 3.0) is a  # nothing applicable: keep the current
    with pytest.raises(ValueError):
        PlaySelector([])
    with pytest.raises(ValueError, match="duplicate"):
        PlaySelector([a, fake_play("a", "x")])


def test_adaptive_weights_follow_outcomes_and_selection_is_seeded():
    a, b = fake_play("a", "x"), fake_play("b", "x")
    sel = PlaySelector([a, b], adaptive=True, learning_rate=0.5, seed=3)
    sel.current = a
    sel.record_goal(True)
    assert sel.weights["a"] == pytest.approx(1.5) and sel.stats["a"].goals_for == 1
    sel.current = b
    sel.record_goal(False)
    assert sel.weights["b"] == pytest.approx(1 / 1.5) and sel.stats["b"].goals_against == 1

    def picks(seed):
        s = PlaySelector([a, b], adaptive=True, min_hold_s=0.0, seed=seed)
        s.weights = {"a": 3.0, "b": 1.0}
        out = []
        for k in range(200):
            s.current = None
            out.append(s.select(SimpleNamespace(flags={"x": 1}), float(k)).name)
        return out

    p = picks(1)
    assert p == picks(1)
    assert 0.6 < p.count("a") / len(p) < 0.9  # ~3:1
    # non-adaptive: the largest weight (ties: list order), weights fixed
    s = PlaySelector([a, b])
    assert s.select(SimpleNamespace(flags={"x": 1}), 0.0) is a
    s.record_goal(False)
    assert s.weights["a"] == 1.0


def test_standard_play_predicates():
    rp = RobotParams()
    ours = make_world(blue=[(-4.0, 0.0, 0.0), (0.5, 0.0, 0.0)], yellow=[(3.0, 0.0, math.pi)], ball=(1.0, 0.0),
                      frame="blue")
    ctx = make_context(ours, "blue", F, rp)
    assert offense_applicable(ctx) and not defense_applicable(ctx)
    theirs = make_context(to_yellow := make_world(blue=[(-4.0, 0.0, 0.0), (0.5, 0.0, 0.0)],
                                                 yellow=[(3.0, 0.0, math.pi)], ball=(1.0, 0.0), frame="yellow"),
                          "yellow", F, rp)
    assert to_yellow.frame == "yellow"
    assert defense_applicable(theirs) and not offense_applicable(theirs)
    kick = make_world(blue=[(-4.0, 0.0, 0.0), (-0.8, 0.0, 0.0)], yellow=[(0.8, 0.0, math.pi)], frame="blue")
    kctx = make_context(kick, "blue", F, rp)
    assert kickoff_applicable(kctx) and offense_applicable(kctx) and defense_applicable(kctx)
    held = make_world(blue=[(-4.0, 0.0, 0.0), (0.5, 0.0, 0.0)], yellow=[(0.0, 0.0, math.pi)], ball=(0.0, 0.1),
                      yellow_on_dribbler=[True], frame="blue")
    hctx = make_context(held, "blue", F, rp)
    assert hctx.they_have_ball and defense_applicable(hctx) and not offense_applicable(hctx)
    assert [p.name for p in standard_plays()] == ["kickoff", "offense", "defense"]


# ------------------------------------------------------------ team controller
@pytest.mark.parametrize("n,field", [(1, "div_b"), (2, "div_b"), (3, "div_b"), (6, "div_b"), (11, "div_a")])
def test_team_controller_any_size_either_colour(n, field):
    env = parallel_env(n_blue=n, n_yellow=n, field=field, max_time_s=5.0)
    env.reset(seed=n)
    ctrls = {t: TeamController(t, n, field=field) for t in ("blue", "yellow")}
    for _ in range(8):
        acts = {}
        for t, c in ctrls.items():
            a = c.act(env)
            legal(a, c.agents)
            acts.update(a)
        env.step(acts)
    for t, c in ctrls.items():
        roles = c.roles
        assert sorted(roles) == list(range(n))  # everybody has a role
        assert "attacker" in roles.values()
        if n >= 2:
            assert roles[0] == "goalie"
        else:
            assert roles == {0: "attacker"}
        assert c.play is not None and c.play.name in ("kickoff", "offense", "defense")


def test_team_controller_accepts_snapshots_and_checks_them():
    ws = make_world(blue=[(-4.0, 0.0, 0.0), (-1.0, 0.0, 0.0)], yellow=[(1.0, 0.0, math.pi)], ball=(0.0, 0.0))
    c = TeamController("yellow", 1)
    legal(c.act(ws), ["yellow_0"])  # field frame is converted
    legal(c.act(make_world(yellow=[(1.0, 0.0, math.pi)], frame="yellow")), ["yellow_0"])
    with pytest.raises(ValueError, match="frame"):
        c.act(make_world(yellow=[(1.0, 0.0, math.pi)], frame="blue"))
    with pytest.raises(ValueError, match="robots"):
        TeamController("blue", 3).act(ws)
    with pytest.raises(ValueError):
        TeamController("green", 2)
    with pytest.raises(ValueError):
        TeamController("blue", 12)
    with pytest.raises(TypeError):
        c.act(42)


def test_team_controller_credits_goals_to_the_running_play():
    env = parallel_env(n_blue=2, n_yellow=0, max_time_s=5.0)
    env.reset(seed=0)
    c = TeamController("blue", 2, adaptive=True)
    c.act(env)
    env.score["blue"] += 1  # as the referee would
    c.act(env)
    assert sum(s["goals_for"] for s in c.selector.summary().values()) == 1


def test_team_controller_starts_afresh_after_an_env_reset():
    env = parallel_env(n_blue=3, n_yellow=0, max_time_s=5.0)
    env.reset(seed=0)
    c = TeamController("blue", 3)
    for _ in range(40):
        env.step(c.act(env))
    old = c.tactic(0)
    selections = sum(st["selections"] for st in c.selector.summary().values())
    env.reset(seed=1)
    legal(c.act(env), c.agents)
    assert c.tactic(0) is not old and c.selector.since == 0.0
    assert sum(st["selections"] for st in c.selector.summary().values()) == selections + 1


def run_until_goal(env, act, team, limit_s=15.0):
    goal = None
    while env.agents and goal is None:
        _, _, _, _, infos = env.step(act())
        for e in next(iter(infos.values()))["events"]:
            if e["type"] == "goal":
                goal = e
    return goal


def test_go_to_ball_and_shoot_baseline_scores_on_empty_field():
    env = parallel_env(n_blue=1, n_yellow=0, after_goal="terminate", max_time_s=15.0)
    env.reset(seed=0, options={"ball": {"pos": (1.5, 0.3)}, "robots": {"blue_0": (-1.0, -0.5, 2.0)}})
    tac = GoToBallAndShoot(env.field, skills="baseline")
    goal = run_until_goal(env, lambda: {"blue_0": tac.act(env.vision_state("blue"), 0)}, "blue")
    assert goal is not None and goal["team"] == "blue" and goal["t"] <= 15.0
    assert tac.status.kicks >= 1


def test_yellow_attacker_scores_into_the_minus_x_goal():
    env = parallel_env(n_blue=0, n_yellow=1, after_goal="terminate", max_time_s=15.0)
    env.reset(seed=0, options={"ball": {"pos": (-1.5, -0.3)}, "robots": {"yellow_0": (1.0, 0.5, 0.0)}})
    c = TeamController("yellow", 1)
    goal = run_until_goal(env, lambda: c.act(env), "yellow")
    assert goal is not None and goal["team"] == "yellow"
    assert env.world_state().ball_pos[0] < -F.half_length  # in the -x goal (field frame)


def test_build_team_from_a_spec_acts_like_the_controller_it_builds():
    from ssl_marl.plays.passing_play import coordinator_of, passing_plays
    from ssl_marl.plays.team import TeamSpec, build_team, standard_team_plays

    spec = TeamSpec(skills="baseline", adaptive=True, stickiness=0.1)
    team = build_team(spec, "blue", 3, "div_b", seed=4)
    assert [p.name for p in team.selector.plays] == ["kickoff", "offense", "defense"]
    assert team.skills == "baseline" and team.stickiness == 0.1 and team.selector.adaptive
    direct = TeamController("blue", 3, "div_b", skills="baseline", adaptive=True, stickiness=0.1, seed=4)
    env = parallel_env(n_blue=3, n_yellow=3, max_time_s=1.0)
    env.reset(seed=1, options={"formation": "kickoff"})
    for _ in range(20):
        a, b = team.act(env), direct.act(env)
        assert all(np.array_equal(a[k], b[k]) for k in a)
        env.step({**a, **{f"yellow_{i}": np.zeros(5, np.float32) for i in range(3)}})
    decider = SimpleNamespace(decide=lambda request: None)
    passing = build_team(TeamSpec(plays=passing_plays, decider=decider), "yellow", 4)
    assert coordinator_of(passing.selector.plays).decider is decider
    two = [build_team(TeamSpec(plays=passing_plays), "blue", 4) for _ in range(2)]
    assert coordinator_of(two[0].selector.plays) is not coordinator_of(two[1].selector.plays)
    with pytest.raises(ValueError, match="carrier decider"):
        standard_team_plays(ball=None, decider=decider)
