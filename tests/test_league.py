"""The league: schedule, resuming, ratings, outputs, argument errors, PFSP weights."""

from __future__ import annotations

import json
from types import SimpleNamespace

import numpy as np
import pytest

pytest.importorskip("openskill")

from ssl_marl.cli import main  # noqa: E402
from ssl_marl.runners import league as lg  # noqa: E402
from ssl_marl.decisions import pfsp  # noqa: E402
from ssl_marl.runners.league import LeagueConfig  # noqa: E402

STRENGTH = {"baseline": 3, "passing-baseline": 1, "idle": 0}


def fake_play(blue, yellow, seed, **_kwargs):
    """A deterministic match: the stronger kind (STRENGTH) wins by the strength gap."""
    return SimpleNamespace(score={"blue": STRENGTH[blue] + seed % 2, "yellow": STRENGTH[yellow] + seed % 2},
                           sim_time_s=2.0, played_s=2.0)


@pytest.fixture
def fake(monkeypatch):
    monkeypatch.setattr(lg, "play_match", fake_play)


def config(**kw):
    base = dict(teams=("baseline", "passing-baseline", "idle"), rounds=2, seconds=2.0, robots=2)
    return LeagueConfig(**{**base, **kw})


def test_schedule_alternates_colours_and_seeds_are_reproducible():
    plan = lg.schedule(config())
    assert len(plan) == 6 and [m["index"] for m in plan] == list(range(6))
    assert [(m["blue"], m["yellow"]) for m in plan[:3]] == [("baseline", "passing-baseline"), ("baseline", "idle"),
                                                            ("passing-baseline", "idle")]
    assert [(m["yellow"], m["blue"]) for m in plan[3:]] == [(m["blue"], m["yellow"]) for m in plan[:3]]
    assert plan == lg.schedule(config())
    assert len({m["seed"] for m in plan}) == 6
    assert [m["seed"] for m in lg.schedule(config(seed=1))] != [m["seed"] for m in plan]
    both = lg.schedule(config(colours="both", rounds=1))
    assert {(m["blue"], m["yellow"]) for m in both} == {(a, b) for a in STRENGTH for b in STRENGTH if a != b}


def test_ratings_order_stronger_team_first(fake, tmp_path):
    state = lg.play_league(config(rounds=3), tmp_path, progress=False)
    assert [r["team"] for r in state["ratings"]] == ["baseline", "passing-baseline", "idle"]
    top = state["ratings"][0]
    assert top["wins"] == 6 and top["losses"] == 0 and top["ordinal"] == pytest.approx(top["mu"] - 3 * top["sigma"])
    cell = state["matrix"]["baseline"]["idle"]
    assert cell["wins"] == 3 and cell["mean_goal_diff"] == pytest.approx(3.0)
    assert state["matrix"]["idle"]["baseline"]["mean_goal_diff"] == pytest.approx(-3.0)
    for name in ("league.json", "ratings.md", "matrix.png"):
        assert (tmp_path / name).stat().st_size > 0
    saved = json.loads((tmp_path / "league.json").read_text())
    assert saved["played"] == saved["scheduled"] == 9 and "git" in saved["manifest"]
    from ssl_marl.runners.provenance import code_hash

    assert {m["code"] for m in saved["matches"]} == {code_hash()}  # the source each match ran
    assert "| 1 | baseline |" in (tmp_path / "ratings.md").read_text()


def test_a_draw_is_a_tie():
    rows = lg.rate(["a", "b"], [{"index": 0, "blue": "a", "yellow": "b", "score": {"blue": 1, "yellow": 1}}])
    assert rows[0]["mu"] == pytest.approx(rows[1]["mu"]) and rows[0]["draws"] == rows[1]["draws"] == 1


def test_each_teams_row_is_the_statistics_helpers_view_of_its_matches():
    """Wins, goals, the win rate's Wilson interval and the goal difference per 600 s with its t
    interval come from the one statistics helper (either colour; a 300 s match counts double
    per 600 s), and the ratings table shows them."""
    from ssl_marl.runners.statistics import series_statistics

    matches = [{"index": 0, "blue": "a", "yellow": "b", "score": {"blue": 2, "yellow": 0}, "sim_time_s": 600.0},
               {"index": 1, "blue": "b", "yellow": "a", "score": {"blue": 1, "yellow": 1}, "sim_time_s": 600.0},
               {"index": 2, "blue": "b", "yellow": "a", "score": {"blue": 0, "yellow": 1}, "sim_time_s": 300.0}]
    rows = {r["team"]: r for r in lg.rate(["a", "b"], matches)}
    want = series_statistics([2, 1, 1], [0, 1, 0], [600.0, 600.0, 300.0])
    for k in ("wins", "draws", "losses", "goals_for", "goals_against", "win_rate", "win_rate_ci95",
              "goal_diff_per_600s", "goal_diff_per_600s_ci95"):
        assert rows["a"][k] == want[k], k
    assert rows["a"]["goal_diff_per_600s"] == pytest.approx((2 + 0 + 2) / 3)
    assert rows["b"]["losses"] == 2 and rows["b"]["goal_diff_per_600s"] == pytest.approx(-4 / 3)
    state = {"config": {"seconds": 600.0, "match_format": "plain", "robots": 6, "field": "div_b", "realism": "none",
                        "rounds": 1, "colours": "both", "seed": 0},
             "played": 3, "scheduled": 3, "ratings": lg.rate(["a", "b"], matches), "matches": matches}
    table = lg.ratings_markdown(state)
    lo, hi = want["goal_diff_per_600s_ci95"]
    assert "goal diff per 600 s [95% CI]" in table and f"+1.33 [{lo:+.2f}, {hi:+.2f}]" in table


def test_resume_skips_played_matches_and_rates_like_one_run(fake, monkeypatch, tmp_path):
    whole = lg.play_league(config(), tmp_path / "whole", progress=False)
    calls = []

    def failing_after_two(blue, yellow, seed, **kw):
        if len(calls) == 2:
            raise KeyboardInterrupt
        calls.append(seed)
        return fake_play(blue, yellow, seed)

    monkeypatch.setattr(lg, "play_match", failing_after_two)
    with pytest.raises(KeyboardInterrupt):
        lg.play_league(config(), tmp_path / "cut", progress=False, chunk=2)
    assert json.loads((tmp_path / "cut" / "league.json").read_text())["played"] == 2
    replayed = []
    monkeypatch.setattr(lg, "play_match", lambda blue, yellow, seed, **kw: replayed.append(seed)
                        or fake_play(blue, yellow, seed))
    resumed = lg.play_league(config(), tmp_path / "cut", progress=False)
    assert sorted(replayed) == sorted(m["seed"] for m in whole["matches"][2:])
    assert resumed["ratings"] == whole["ratings"] and resumed["matches"] == whole["matches"]
    replayed.clear()
    lg.play_league(config(), tmp_path / "cut", progress=False)
    assert replayed == []


def test_bad_arguments_give_clear_errors(fake, tmp_path):
    with pytest.raises(ValueError, match="at least two teams"):
        lg.play_league(config(teams=("baseline",)), tmp_path, progress=False)
    with pytest.raises(ValueError, match="unknown team 'champions'"):
        lg.play_league(config(teams=("baseline", "champions")), tmp_path, progress=False)
    with pytest.raises(ValueError, match="once"):
        lg.play_league(config(teams=("baseline", "baseline")), tmp_path, progress=False)
    with pytest.raises(FileNotFoundError):
        lg.play_league(config(teams=("baseline", str(tmp_path / "missing.json"))), tmp_path, progress=False)
    lg.play_league(config(), tmp_path / "l", progress=False)
    with pytest.raises(ValueError, match="other arguments .*rounds"):
        lg.play_league(config(rounds=1), tmp_path / "l", progress=False)
    with pytest.raises(ValueError, match="other arguments .*seed"):
        lg.play_league(config(rounds=3, seed=5), tmp_path / "l", progress=False)


def test_more_rounds_extend_a_league_and_keep_the_earlier_runs_manifest(fake, tmp_path, monkeypatch):
    calls = []
    monkeypatch.setattr(lg, "play_match", lambda **kw: calls.append(kw["seed"]) or fake_play(**kw))
    first = lg.play_league(config(), tmp_path, progress=False, argv=["first"])
    assert len(calls) == 6 and "earlier_manifests" not in first
    calls.clear()
    longer = lg.play_league(config(rounds=3), tmp_path, progress=False, argv=["second"])
    assert len(calls) == 3 and longer["played"] == 9
    assert longer["matches"][:6] == first["matches"]
    assert longer["matches"] == lg.play_league(config(rounds=3), tmp_path / "fresh", progress=False)["matches"]
    assert [m["command"] for m in longer["earlier_manifests"]] == [["first"]]
    assert longer["manifest"]["command"] == ["second"]
    again = lg.play_league(config(rounds=3), tmp_path, progress=False, argv=["second"])
    assert [m["command"] for m in again["earlier_manifests"]] == [["first"]]


def test_cli_league_real_matches(tmp_path, capsys):
    out = tmp_path / "league"
    rc = main(["league", "baseline", "idle", "--seconds", "2", "--robots", "2", "--out", str(out), "--quiet"])
    assert rc == 0 and "ordinal" in capsys.readouterr().out
    state = json.loads((out / "league.json").read_text())
    assert state["played"] == 1 and state["manifest"]["rules"]["match_format"] == "ssl"
    assert main(["league", "baseline", "idle", "--seconds", "3", "--robots", "2", "--out", str(out), "--quiet"]) == 2
    assert "other arguments" in capsys.readouterr().err
    assert main(["league", "baseline", "--out", str(tmp_path / "x"), "--quiet"]) == 2
    with pytest.raises(SystemExit):
        main(["league", "baseline", "champions"])


def test_pfsp_weights():
    w = pfsp.pfsp_weights([0.0, 0.5, 1.0])
    assert w == pytest.approx([0.8, 0.2, 0.0])
    assert pfsp.pfsp_weights([0.5, 0.9], "even") == pytest.approx([0.25, 0.09] / np.sum([0.25, 0.09]))
    assert pfsp.pfsp_weights([1.0, 1.0]) == pytest.approx([0.5, 0.5])
    for bad in ([], [1.5], [float("nan")]):
        with pytest.raises(ValueError):
            pfsp.pfsp_weights(bad)
    with pytest.raises(ValueError, match="kind"):
        pfsp.pfsp_weights([0.5], "easy")
    rng = np.random.default_rng(0)
    draws = [pfsp.sample_opponent(["strong", "weak"], [0.1, 0.9], rng) for _ in range(400)]
    assert draws.count("strong") > 300
    with pytest.raises(ValueError):
        pfsp.sample_opponent(["a"], [0.1, 0.2], rng)


def test_win_probabilities_from_the_matrix(fake, tmp_path):
    state = lg.play_league(config(), tmp_path, progress=False)
    assert lg.win_probabilities(state, "idle") == {"baseline": 0.0, "passing-baseline": 0.0}
    assert lg.win_probabilities(state, "baseline") == {"passing-baseline": 1.0, "idle": 1.0}


def test_team_file_joins_the_league(fake, tmp_path):
    snapshot = tmp_path / "snapshot.json"
    snapshot.write_text(json.dumps({"kind": "idle"}))
    state = lg.play_league(config(teams=("baseline", str(snapshot)), rounds=1), tmp_path / "l", progress=False)
    assert [r["team"] for r in state["ratings"]] == ["baseline", str(snapshot)]
    assert state["manifest"]["rules"]["team_files"] == {str(snapshot): {"kind": "idle", "skills": {},
                                                                        "decision": None}}


def test_a_team_files_decision_reaches_the_match(monkeypatch, tmp_path):
    seen = []

    def record(blue, yellow, seed, blue_decision=None, yellow_decision=None, **_kwargs):
        seen.extend([(blue, blue_decision), (yellow, yellow_decision)])
        return SimpleNamespace(score={"blue": 1, "yellow": 0}, sim_time_s=2.0, played_s=2.0)

    monkeypatch.setattr(lg, "play_match", record)
    team = tmp_path / "drill.json"
    team.write_text(json.dumps({"kind": "attack-learned", "decision": "learned"}))
    state = lg.play_league(config(teams=(str(team), "attack-learned-decision", "attack-learned"), rounds=1),
                           tmp_path / "l", progress=False)
    assert state["played"] == 3
    # the file's decision reaches both of its matches; the kinds keep their own (None: the kind's default)
    assert sorted(seen, key=str) == sorted([("attack-learned", "learned")] * 2 + [("attack-learned", None)] * 2
                                           + [("attack-learned-decision", None)] * 2, key=str)
    assert state["manifest"]["rules"]["team_files"][str(team)]["decision"] == "learned"
