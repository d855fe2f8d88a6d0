"""Full matches as the attacking team's decision task: PFSP weights, the league with the
learner's improving snapshots, the env's episodes (API, score, determinism) and bad input."""

from __future__ import annotations

import math

import numpy as np
import pytest

from ssl_marl.decisions.attack_drill_features import ATTACK_DRILL_OBS_DIM, ATTACK_DRILL_OPTIONS
from ssl_marl.decisions.attack_match import AttackMatchEnv, improving_snapshots
from ssl_marl.decisions.pfsp import pfsp_weights, win_probability
from ssl_marl.decisions.policies import RandomPolicy, run_episode
from ssl_marl.plays.team import TeamSpec


def test_pfsp_prefers_the_opponents_the_learner_beats_least():
    w = pfsp_weights(win_probability([9.0, 5.0, 0.0], [10.0, 10.0, 10.0]))
    assert w.sum() == pytest.approx(1.0) and w[0] < w[1] < w[2]
    assert np.allclose(pfsp_weights(win_probability(np.zeros(3), np.zeros(3))), 1 / 3)  # no games yet: uniform
    assert (pfsp_weights(win_probability([100.0, 0.0], [100.0, 0.0])) > 0).all()  # never zero
    with pytest.raises(ValueError, match="wins"):
        win_probability([3.0], [2.0])


def test_improving_snapshots_follow_the_validation_record(tmp_path):
    (tmp_path / "actors").mkdir()
    rows = [(0.5, "a1"), (0.4, "a2"), (0.6, "a3"), (0.6, "a4"), (0.7, "a5")]
    lines = ["rollout,decisions,val_score,actor"]
    for i, (score, name) in enumerate(rows):
        (tmp_path / "actors" / f"{name}.pt").write_bytes(b"x")
        lines.append(f"{i},{i},{score},actors/{name}.pt")
    (tmp_path / "val.csv").write_text("\n".join(lines) + "\n")
    got = [p.stem for p in improving_snapshots(tmp_path, max_snapshots=5)]
    assert got == ["a1", "a3", "a5"]
    assert [p.stem for p in improving_snapshots(tmp_path, max_snapshots=2)] == ["a3", "a5"]
    assert improving_snapshots(tmp_path / "missing") == []


def _env(**kw):
    kw.setdefault("seconds", 3.0)
    return AttackMatchEnv({"baseline": TeamSpec(skills="baseline")}, skills="baseline", robots=3, **kw)


def test_episode_score_spaces_and_determinism():
    env = _env()
    assert env.possible_agents == ["attacker_0", "attacker_1"] and env.option_names == ATTACK_DRILL_OPTIONS
    assert env.decider.coordinator is not None  # waiting for an answer, the carrier holds its dribble
    a = run_episode(env, RandomPolicy(1), seed=5, record=True)
    b = run_episode(_env(), RandomPolicy(1), seed=5, record=True)
    assert a["trace"] == b["trace"] and a["t_s"] == pytest.approx(3.0, abs=0.05) and a["truncated"]
    assert {"goal_diff", "goals_for", "goals_against", "opponent"} <= set(a) and a["opponent"] == "baseline"
    assert a["outcome"] in ("win", "draw", "loss") and a["goal_diff"] == a["goals_for"] - a["goals_against"]
    assert env.results["baseline"][1] == 1.0
    obs, _ = env.reset(seed=6)
    assert all(o.shape == (ATTACK_DRILL_OBS_DIM,) for o in obs.values())
    assert env.state().shape == (4 + 8 * 3 + 2,) and env.state_space.contains(env.state())


def test_an_episode_does_not_depend_on_the_one_before():
    """The attacking plays' coordinator and spots are reset with the team (6 robots: the supports' spots)."""
    env = AttackMatchEnv({"baseline": TeamSpec(skills="baseline")}, skills="baseline", robots=6, seconds=4.0)
    first = run_episode(env, RandomPolicy(1), seed=5, record=True)
    run_episode(env, RandomPolicy(1), seed=9)
    again = run_episode(env, RandomPolicy(1), seed=5, record=True)
    assert again["trace"] == first["trace"] and again["goal_diff"] == first["goal_diff"]


def test_parallel_api():
    from pettingzoo.test import parallel_api_test

    parallel_api_test(_env(seconds=2.0, illegal_option="default"), num_cycles=10)


def test_league_draw_follows_pfsp_and_snapshots_join(tmp_path):
    env = AttackMatchEnv({"easy": TeamSpec(skills="baseline"), "hard": TeamSpec(skills="baseline")},
                         skills="baseline", robots=2, seconds=1.0, snapshot_dir=str(tmp_path))
    env.results = {"easy": [19.0, 20.0], "hard": [1.0, 20.0]}
    env.np_random = np.random.default_rng(0)
    draws = [env.draw_opponent() for _ in range(400)]
    assert draws.count("hard") > 3 * draws.count("easy")
    (tmp_path / "actors").mkdir()
    (tmp_path / "actors" / "actor-1.pt").write_bytes(b"x")
    (tmp_path / "val.csv").write_text("rollout,decisions,val_score,actor\n1,10,0.5,actors/actor-1.pt\n")
    assert env.league() == ["easy", "hard", f"snapshot:{tmp_path / 'actors' / 'actor-1.pt'}"]


@pytest.mark.parametrize("kw, match", [(dict(robots=1), "robots"), (dict(seconds=math.nan), "seconds"),
                                       (dict(seconds=-1.0), "seconds")])
def test_bad_configs_are_refused(kw, match):
    with pytest.raises(ValueError, match=match):
        AttackMatchEnv({"baseline": TeamSpec(skills="baseline")}, **kw)
    with pytest.raises(ValueError, match="at least one opponent"):
        AttackMatchEnv({})


def test_attack_drill_actors_play_the_full_match_task():
    from ssl_marl.decisions.learned import LearnedDecisionPolicy, decision_family, pretrained_path
    from ssl_marl.decisions.match_decider import check_actor_file

    assert decision_family("attack-match") == "attack-drill" and decision_family("keepaway") == "keepaway"
    actor = pretrained_path("attack-drill")
    policy = LearnedDecisionPolicy(actor, task="attack-match")
    env = _env(seconds=2.0)
    policy.reset(env)  # same observation size and options
    assert isinstance(check_actor_file(actor, task="attack-drill"), dict)
    with pytest.raises(ValueError, match="not 'attack-3v2'"):
        LearnedDecisionPolicy(actor, task="attack-3v2")


def test_ssl_rules_play_game_control_and_the_dribble_mask():
    """With ``ssl_rules`` the episode is a match under SSL game control (a kickoff command at
    the start, the referee's fouls on) and the learned decider's dribble mask is on, as in
    ``ssl-marl match --format ssl``; deterministic under the seed."""
    from ssl_marl.decisions.dribble_limit import DRIBBLE_MASK_M
    from ssl_marl.envs.game_control import KICKOFF

    env = _env(seconds=6.0, ssl_rules=True)
    assert env.dribble_mask_m == DRIBBLE_MASK_M and _env().dribble_mask_m is None
    env.reset(seed=5)
    rules = env.engine.task.rules
    assert rules.ssl_restarts and rules.fouls and env.engine.task.referee_state.command == KICKOFF
    assert not _env().engine.task.rules.ssl_restarts
    a = run_episode(env, RandomPolicy(1), seed=5, record=True)
    b = run_episode(_env(seconds=6.0, ssl_rules=True), RandomPolicy(1), seed=5, record=True)
    assert a["trace"] == b["trace"] and a["goal_diff"] == b["goal_diff"]
