"""The ssl-marl command line: bad arguments are rejected clearly; commands run."""

import json
from pathlib import Path

import pytest

from ssl_marl.cli import build_parser, main


@pytest.mark.parametrize("argv,needle", [
    (["match", "--robots", "12"], "between 1 and 11"),
    (["match", "--seconds", "-5"], "positive"),
    (["match", "--blue", "telepathic"], "invalid choice"),
    (["match", "--no-progress-s", "-1"], ">= 0"),
    (["eval-skill", "go-to-ball", "--episodes", "0"], ">= 1"),
    (["eval-skill", "juggle"], "invalid choice"),
    (["demo", "--field", "div_c"], "invalid choice"),
    (["eval-tactic", "--skills", "magic"], "invalid choice"),
])
def test_bad_arguments_exit_with_a_clear_message(argv, needle, capsys):
    with pytest.raises(SystemExit) as exc:
        build_parser().parse_args(argv)
    assert exc.value.code == 2
    assert needle in capsys.readouterr().err


def test_missing_checkpoint_is_a_clear_error(capsys, tmp_path):
    assert main(["eval-skill", "go-to-ball", "--policy", str(tmp_path / "nope.pt"), "--episodes", "2"]) == 2
    assert "does not exist" in capsys.readouterr().err


def test_help_explains_every_option(capsys):
    for cmd in ("demo", "match", "eval-skill", "eval-tactic"):
        with pytest.raises(SystemExit):
            build_parser().parse_args([cmd, "--help"])
        out = capsys.readouterr().out
        assert "--seed" in out


def test_demo_writes_a_gif(tmp_path, capsys):
    out = tmp_path / "demo.gif"
    assert main(["demo", "--robots", "2", "--seconds", "1", "--fps", "10", "--out", str(out), "--quiet"]) == 0
    assert out.exists() and out.stat().st_size > 1000
    assert "score blue" in capsys.readouterr().out


def test_eval_skill_writes_results(tmp_path, capsys):
    assert main(["eval-skill", "go-to-ball", "--episodes", "4", "--seed", "1", "--out", str(tmp_path), "--quiet"]) == 0
    res = json.loads((tmp_path / "results.json").read_text())
    assert res["episodes"] == 4 and res["success_rate"] == 1.0 and res["seed"] == 1
    assert (tmp_path / "time_hist.png").exists()


@pytest.mark.parametrize("flag,expected", [("0", None), ("4", 4.0)])
def test_match_no_progress_option_reaches_the_referee(flag, expected, tmp_path):
    out = tmp_path / "m.json"
    assert main(["match", "--blue", "idle", "--yellow", "idle", "--robots", "1", "--seconds", "5", "--render", "none",
                 "--no-progress-s", flag, "--quiet", "--json", str(out)]) == 0
    res = json.loads(out.read_text())
    assert res["config"]["no_progress_s"] == expected
    # idle robots, ball resting at the centre mark: called after 4 s only when the call is on
    assert any(e["type"] == "no_progress" for e in res["stats"]["events"]) is (expected is not None)


def test_every_command_module_registers_one_documented_command_with_its_handler():
    """The interface of a command module: ``register(subparsers)`` adds one subparser whose
    every option has help text and whose ``handler`` default is the module's ``run``."""
    import argparse

    from ssl_marl.cli import COMMANDS

    names = []
    for module in COMMANDS:
        sub = argparse.ArgumentParser().add_subparsers()
        module.register(sub)
        assert len(sub.choices) == 1, module.__name__
        (name, parser), = sub.choices.items()
        names.append(name)
        assert parser.get_default("handler") is module.run, name
        assert sub._choices_actions[0].help, name  # the line in ssl-marl --help
        undocumented = [a.dest for a in parser._actions if not a.help and not isinstance(a, argparse._HelpAction)]
        assert not undocumented, (name, undocumented)
    assert len(set(names)) == len(names)


def test_python_dash_m_runs_the_command_line():
    import subprocess
    import sys

    from ssl_marl import __version__

    out = subprocess.run([sys.executable, "-m", "ssl_marl.cli", "--version"], capture_output=True, text=True,
                         check=True).stdout
    assert out.strip() == f"ssl-marl {__version__}"


def test_single_match_json_has_a_manifest_that_a_merge_keeps(tmp_path):
    """A single match with ``--json`` writes its manifest (commit, rules, seed) beside it, and a
    series merged from such parts lists each part's manifest."""
    import subprocess
    import sys

    from ssl_marl.runners.result import load_manifest

    parts = []
    for seed in (7, 8):
        out = tmp_path / f"m{seed}.json"
        assert main(["match", "--blue", "baseline", "--yellow", "idle", "--robots", "1", "--seconds", "1",
                     "--seed", str(seed), "--render", "none", "--quiet", "--json", str(out)]) == 0
        man = load_manifest(out)
        assert man is not None and man["seeds"] == {"seed": seed, "matches": 1}
        assert man["rules"]["blue"] == "baseline" and "commit" in man["git"]
        parts.append(str(out))
    merged = tmp_path / "series.json"
    root = Path(__file__).resolve().parents[1]
    subprocess.run([sys.executable, str(root / "benchmarks" / "merge_match_series.py"), *parts, "--out", str(merged)],
                   check=True, capture_output=True, cwd=root)
    assert all(v is not None and v["seeds"]["matches"] == 1 for v in load_manifest(merged)["parts"].values())


def test_match_series_resumes_from_its_partial_folder(tmp_path, capsys):
    from ssl_marl.cli.match import partial_dir

    out = tmp_path / "s.json"
    kept = partial_dir(str(out))
    kept.mkdir()
    args = ["match", "--blue", "baseline", "--yellow", "idle", "--robots", "1", "--seconds", "2", "--matches", "2",
            "--seed", "4", "--quiet", "--json", str(out)]
    assert main(args) == 0
    first = json.loads(out.read_text())["summary"]
    assert not kept.exists()  # removed once the series file is written
    out.unlink()
    kept.mkdir()
    (kept / "match_4.json").write_text("{\"key\": \"other\", \"result\": {}}")
    assert main(args) == 2 and "other options" in capsys.readouterr().err
    (kept / "match_4.json").unlink()
    assert main(args) == 0 and json.loads(out.read_text())["summary"]["goals_for"] == first["goals_for"]


def test_match_command_plays_the_ssl_format(tmp_path):
    """``ssl-marl match --format ssl``: SSL game control with fouls and a half-time at half the
    match, recorded in the match's rules; ``--format plain`` records none of them."""
    import json

    from ssl_marl.cli import main

    for fmt in ("ssl", "plain"):
        out = tmp_path / f"{fmt}.json"
        assert main(["match", "--seconds", "4", "--robots", "2", "--format", fmt, "--render", "none", "--quiet",
                     "--json", str(out)]) == 0
        rec = json.loads(out.read_text())
        rules = rec["config"]["rules"]
        if fmt == "ssl":
            assert rules["ssl_restarts"] and rules["fouls"] and rules["half_time_s"] == 2.0
            assert rec["stats"]["referee"].get("half_time") == 1
        else:
            assert not rules.get("ssl_restarts") and not rules.get("half_time_s")
            assert "half_time" not in rec["stats"]["referee"]
