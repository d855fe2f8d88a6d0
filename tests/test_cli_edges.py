"""Edges of the ``ssl-marl`` command line a new user hits: forwarded
subcommands, one rule for output paths checked before any simulation, clear errors
for bad files, and help texts that say what they mean."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from ssl_marl import __version__
from ssl_marl.cli import build_parser, main
from ssl_marl.skills.registry import get_skill

SHIPPED_ACTOR = str(get_skill("go_to_ball").actor)


# ------------------------------------------------------------------ forwarding
@pytest.mark.parametrize("argv", [["bench", "--", "--help"], ["bench", "--help"]])
def test_bench_help_reaches_the_benchmark(argv, capsys):
    with pytest.raises(SystemExit) as exc:
        main(argv)
    assert exc.value.code == 0
    out = capsys.readouterr().out
    assert "--steps" in out and "--resets" in out and "--no-skills" in out


def test_bench_options_reach_the_benchmark(capsys, monkeypatch):
    import ssl_marl.cli.bench as bench

    calls = []
    monkeypatch.setattr(bench, "bench_env", lambda cfg, steps, resets: calls.append((cfg, steps, resets)) or {})
    assert main(["bench", "--steps", "100", "--resets", "3", "--configs", "1v0_div_b", "--no-skills"]) == 0
    assert calls == [(bench.CONFIGS["1v0_div_b"], 100, 3)]
    res = json.loads(capsys.readouterr().out)
    assert "1v0_div_b" in res and "learned_skill_inference" not in res
    assert main(["bench", "--", "--steps", "7", "--configs", "1v0_div_b", "--no-skills"]) == 0
    assert calls[-1][1] == 7


def test_bench_rejects_a_bad_option_as_the_benchmark_would(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["bench", "--steps", "many"])
    assert exc.value.code == 2
    assert "--steps" in capsys.readouterr().err


def test_train_help_shows_the_trainers_options(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["train", "--help"])
    assert exc.value.code == 0
    out = capsys.readouterr().out
    assert "ssl-marl train" in out
    for opt in ("--seed", "--out", "--resume", "--samples", "--set", "--config"):
        assert opt in out


def test_train_runs_the_trainer_with_the_same_options(tmp_path, capsys):
    out = tmp_path / "run"
    assert main(["train", "pendulum", "--seed", "0", "--out", str(out), "--samples", "300", "--no-progress",
                 "--set", "eval_interval=300", "--set", "checkpoint_interval=300"]) == 0
    assert (out / "actor.pt").is_file()
    assert json.loads(capsys.readouterr().out.strip().splitlines()[-1])["out"] == str(out)


def test_train_bad_skill_is_an_argparse_error(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["train", "juggle", "--out", "x"])
    assert exc.value.code == 2
    assert "invalid choice" in capsys.readouterr().err


def test_importing_ssl_marl_cli_does_not_import_train():
    code = "import sys, ssl_marl.cli, ssl_marl.plays, ssl_marl.skills.learned; print('train' in sys.modules)"
    assert subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          check=True).stdout.strip() == "False"


# ---------------------------------------------------------------- output paths
def _fail_fast(argv, capsys, monkeypatch, needle):
    """The command fails with exit 2 before any simulation (the env is never built)."""
    import ssl_marl.envs as envs
    import ssl_marl.envs.ssl_env as ssl_env

    def boom(*a, **k):
        raise AssertionError("simulation started before the output path was checked")

    monkeypatch.setattr(ssl_env.SSLParallelEnv, "reset", boom)
    monkeypatch.setattr(envs, "parallel_env", boom)
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert needle in err
    assert ".tmp" not in err  # never a hidden temp file
    return err


@pytest.mark.parametrize("flag_argv", [
    ["match", "--seconds", "1", "--quiet", "--render"],
    ["match", "--seconds", "1", "--quiet", "--render", "none", "--json"],
    ["demo", "--seconds", "1", "--quiet", "--out"],
    ["eval-skill", "go-to-ball", "--episodes", "1", "--quiet", "--out"],
    ["eval-tactic", "--episodes", "1", "--quiet", "--out"],
])
def test_unwritable_output_is_refused_before_simulating(flag_argv, tmp_path, capsys, monkeypatch):
    blocker = tmp_path / "a_file"
    blocker.write_text("in the way")
    target = blocker / "sub" / ("x.gif" if flag_argv[0] in ("match", "demo") else "x")
    if "--json" in flag_argv:
        target = blocker / "sub" / "x.json"
    err = _fail_fast(flag_argv + [str(target)], capsys, monkeypatch, str(target))
    assert "cannot create folder" in err


@pytest.mark.parametrize("argv", [["match", "--quiet", "--render"], ["demo", "--quiet", "--out"]])
def test_video_suffix_is_checked_before_simulating(argv, tmp_path, capsys, monkeypatch):
    _fail_fast(argv + [str(tmp_path / "x.avi")], capsys, monkeypatch, "use .gif or .mp4")


def test_output_that_is_a_folder_is_refused(tmp_path, capsys, monkeypatch):
    (tmp_path / "v.gif").mkdir()
    _fail_fast(["demo", "--quiet", "--out", str(tmp_path / "v.gif")], capsys, monkeypatch, "is a folder")


def test_missing_output_folders_are_created_for_every_command(tmp_path, capsys):
    """The one rule (documented in ``ssl-marl --help``): missing parents are created."""
    demo = tmp_path / "new" / "deeper" / "demo.gif"
    assert main(["demo", "--robots", "1", "--seconds", "0.5", "--fps", "5", "--out", str(demo), "--quiet"]) == 0
    video, js = tmp_path / "m1" / "x.gif", tmp_path / "m2" / "x.json"
    assert main(["match", "--robots", "1", "--seconds", "0.5", "--render", str(video), "--json", str(js),
                 "--quiet", "--render-fps", "4"]) == 0
    ev = tmp_path / "e" / "f"
    assert main(["eval-skill", "go-to-ball", "--episodes", "1", "--out", str(ev), "--quiet"]) == 0
    assert demo.is_file() and video.is_file() and js.is_file() and (ev / "results.json").is_file()
    capsys.readouterr()
    with pytest.raises(SystemExit):
        build_parser().parse_args(["--help"])
    assert "missing parent folders are created" in " ".join(capsys.readouterr().out.split())  # any wrap width


# ----------------------------------------------------------- argparse checks
def test_render_width_is_an_argparse_error(capsys):
    with pytest.raises(SystemExit) as exc:
        build_parser().parse_args(["match", "--render-width", "5"])
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert "--render-width must be >= 64" in err and "render_width_px" not in err


def test_version(capsys):
    with pytest.raises(SystemExit) as exc:
        build_parser().parse_args(["--version"])
    assert exc.value.code == 0
    assert capsys.readouterr().out.strip() == f"ssl-marl {__version__}"


def test_help_texts_have_no_stray_percent_and_show_defaults(capsys):
    with pytest.raises(SystemExit):
        build_parser().parse_args(["eval-skill", "--help"])
    out = capsys.readouterr().out
    assert "95% CI" in out and "%%" not in out
    with pytest.raises(SystemExit):
        build_parser().parse_args(["eval-task", "--help"])
    out = capsys.readouterr().out
    assert "95% intervals" in out and "%%" not in out
    with pytest.raises(SystemExit):
        build_parser().parse_args(["eval-tactic", "--help"])
    out = " ".join(capsys.readouterr().out.split())
    assert "skills inside the tactic (default learned)" in out


def test_every_command_is_listed_in_top_level_help(capsys):
    with pytest.raises(SystemExit):
        build_parser().parse_args(["--help"])
    out = capsys.readouterr().out
    for cmd in ("demo", "match", "eval-skill", "eval-tactic", "bench", "train", "export-onnx"):
        assert cmd in out


# ---------------------------------------------------------------- bad files
@pytest.mark.parametrize("content,says", [
    (b"hello, I am a text file\n", "not a PyTorch file"),
    (b"", "empty file"),
    (b"PK\x03\x04 truncated zip", "damaged or truncated PyTorch archive"),
])
def test_corrupt_checkpoint_says_what_it_is_not_and_what_is_valid(content, says, tmp_path, capsys):
    bad = tmp_path / "bad.pt"
    bad.write_bytes(content)
    assert main(["eval-skill", "go-to-ball", "--policy", str(bad), "--episodes", "1", "--quiet"]) == 2
    err = capsys.readouterr().err
    assert f"{bad} is not a valid ssl_marl checkpoint" in err and says in err
    assert "actor.pt" in err  # what a valid one is
    assert "weights_only" not in err and "KeyError" not in err


class Gadget:
    """A class outside PyTorch's weights-only allow-list (unpickling it could run code)."""


def test_checkpoint_with_code_is_refused_without_pytorchs_advice(tmp_path, capsys):
    import torch

    bad = tmp_path / "code.pt"
    torch.save({"x": Gadget()}, bad)
    assert main(["export-onnx", str(bad), str(tmp_path / "x.onnx")]) == 2
    err = capsys.readouterr().err
    assert "never loaded" in err and "weights_only" not in err and "trust" not in err


def test_export_onnx_without_the_extra_says_how_to_install(monkeypatch, tmp_path, capsys):
    import importlib.util

    real = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec", lambda name, *a: None if name == "onnx" else real(name, *a))
    assert main(["export-onnx", SHIPPED_ACTOR, str(tmp_path / "x.onnx")]) == 2
    assert 'pip install -e ".[onnx]"' in capsys.readouterr().err


def test_train_into_an_existing_run_is_a_clear_error(tmp_path, capsys):
    out = tmp_path / "run"
    out.mkdir()
    (out / "checkpoint.pt").write_bytes(b"x")
    assert main(["train", "pendulum", "--out", str(out), "--no-progress"]) == 2
    assert "already holds a run" in capsys.readouterr().err
