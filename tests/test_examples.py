"""Every script in examples/ runs (briefly) and does what its docstring says, so the
examples cannot rot. Each is loaded from its file and its ``main(argv)`` called."""

from __future__ import annotations

import importlib.util
import json
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def load(name: str):
    spec = importlib.util.spec_from_file_location(f"example_{name}", EXAMPLES / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_every_example_is_tested():
    tested = {"pettingzoo_random", "train_skill_curve", "evaluate_checkpoint", "custom_play_match",
              "bridge_round_trip"}  # bridge_round_trip: tests/test_bridge_example.py
    assert {p.stem for p in EXAMPLES.glob("*.py")} == tested


def test_pettingzoo_random(capsys):
    res = load("pettingzoo_random").main(["--seconds", "2", "--seed", "1"])
    assert res["steps"] == 120
    assert "score blue" in capsys.readouterr().out


def test_evaluate_checkpoint(tmp_path, capsys):
    res = load("evaluate_checkpoint").main(["--episodes", "4", "--out", str(tmp_path)])
    assert res["learned"]["episodes"] == 4 and res["learned"]["seed"] == 10_000
    assert json.loads((tmp_path / "learned" / "results.json").read_text())["episodes"] == 4
    assert "go_to_ball (go_to_ball/v2)" in capsys.readouterr().out


def test_train_skill_curve(tmp_path, capsys):
    out = tmp_path / "run"
    mod = load("train_skill_curve")
    res = mod.main(["--out", str(out), "--samples", "600"])
    assert 0.0 <= res["success_rate"] <= 1.0
    for name in ("actor.pt", "progress.csv", "eval.csv", "learning_curve.png"):
        assert (out / name).is_file(), name
    from ssl_marl.skills import make_skill
    from ssl_marl.physics.field import FieldGeometry

    make_skill("go_to_ball", "learned", FieldGeometry.div_b(), checkpoint=out / "actor.pt")  # loadable
    mod.main(["--out", str(out), "--samples", "600"])  # rerun resumes a finished run
    assert "curve ->" in capsys.readouterr().out


def test_custom_play_match(tmp_path, capsys):
    gif = tmp_path / "m.gif"
    res = load("custom_play_match").main(["--seconds", "3", "--render", str(gif)])
    assert res["steps"] == 180 and gif.stat().st_size > 1000
    assert {"goalie", "attacker"} <= set(res["blue_roles"])
    assert all(not r.startswith(("defender", "mark")) for r in res["blue_roles"])  # the custom play's roles only
    assert "all-out attack" in capsys.readouterr().out
