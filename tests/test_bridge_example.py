"""examples/bridge_round_trip.py runs on loopback and does what its docstring says."""

import importlib.util
from pathlib import Path

import pytest

pytest.importorskip("google.protobuf")


def test_bridge_round_trip(capsys):
    path = Path(__file__).resolve().parent.parent / "examples" / "bridge_round_trip.py"
    spec = importlib.util.spec_from_file_location("example_bridge_round_trip", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    res = mod.main([])
    assert res["robot_mm"][0] > -700.0  # blue 1 started at x = -800 mm and drove forward
    assert res["score"] == (1, 0) and res["step_error"] == "INVALID_STEP"
    assert "referee:" in capsys.readouterr().out
