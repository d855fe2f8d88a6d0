"""Actor checkpoints: round trip, metadata, and clear errors for bad files."""

from __future__ import annotations

import importlib.util
import os
import pickle
from pathlib import Path

import pytest
import torch

from ssl_marl.skills.checkpoint import load_actor, save_actor
from ssl_marl.skills.networks import Actor, Critic

torch.set_num_threads(1)
ROOT = Path(__file__).resolve().parents[1]


def _actor() -> Actor:
    torch.manual_seed(0)
    return Actor(14, 3, (16, 8))


def test_networks_shapes_and_ranges() -> None:
    actor, critic = Actor(14, 3, (16, 8)), Critic(14, 3, (16, 8), layer_norm=False)
    obs = torch.randn(5, 14) * 100
    a = actor(obs)
    assert a.shape == (5, 3) and torch.all(a.abs() <= 1)
    assert critic(obs, a).shape == (5, 1)
    kinds = [type(m).__name__ for m in actor.trunk]
    assert kinds == ["Linear", "LayerNorm", "ReLU", "Linear", "LayerNorm", "ReLU"]
    assert "LayerNorm" not in [type(m).__name__ for m in critic.trunk]
    assert actor.act(obs[0].numpy()).shape == (3,)


def test_save_load_roundtrip(tmp_path) -> None:
    actor = _actor()
    path = save_actor(tmp_path / "sub" / "actor.pt", actor,
                      {"skill": "go_to_ball", "obs_spec": "go_to_ball/v1", "hyperparameters": {"gamma": 0.99,
                       "hidden": (16, 8)}, "seed": 3, "samples": 1000})
    assert not [p for p in path.parent.iterdir() if p.name != "actor.pt"]  # no temp files left
    loaded, meta = load_actor(path, expected_skill="go_to_ball", expected_spec="go_to_ball/v1")
    obs = torch.randn(7, 14)
    torch.testing.assert_close(loaded(obs), actor(obs), rtol=0, atol=0)
    assert (meta["obs_dim"], meta["act_dim"], meta["hidden"], meta["layer_norm"]) == (14, 3, [16, 8], True)
    assert meta["seed"] == 3 and meta["samples"] == 1000 and meta["hyperparameters"]["hidden"] == [16, 8]
    assert isinstance(meta["git_commit"], str) and meta["git_commit"]
    assert meta["created"].startswith("20")
    assert not loaded.training and not any(p.requires_grad for p in loaded.parameters())


def test_metadata_must_be_plain(tmp_path) -> None:
    with pytest.raises(TypeError, match="not allowed"):
        save_actor(tmp_path / "a.pt", _actor(), {"skill": "x", "obs_spec": "y", "bad": object()})
    assert not list(tmp_path.iterdir())


def test_missing_file_raises_file_not_found(tmp_path) -> None:
    with pytest.raises(FileNotFoundError, match="nope.pt"):
        load_actor(tmp_path / "nope.pt")


@pytest.mark.parametrize("content", [b"", b"garbage bytes \x00\x01", "truncated"])
def test_corrupt_file_raises_value_error(tmp_path, content) -> None:
    path = tmp_path / "actor.pt"
    if content == "truncated":
        save_actor(path, _actor(), {"skill": "s", "obs_spec": "v"})
        data = path.read_bytes()
        path.write_bytes(data[: len(data) // 2])
    else:
        path.write_bytes(content)
    with pytest.raises(ValueError, match="is not a valid ssl_marl checkpoint"):
        load_actor(path)


class _Evil:
    def __reduce__(self):
        return (os.system, ("touch PWNED_BY_CHECKPOINT",))


def test_loading_never_executes_code(tmp_path, monkeypatch) -> None:
    monkeypatch.chdir(tmp_path)
    path = tmp_path / "evil.pt"
    torch.save({"format": "ssl_marl.actor", "payload": _Evil()}, path)
    with pytest.raises(ValueError, match="is not a valid ssl_marl checkpoint"):
        load_actor(path)
    plain = tmp_path / "plain.pkl"
    plain.write_bytes(pickle.dumps(_Evil()))
    with pytest.raises(ValueError, match="is not a valid ssl_marl checkpoint"):
        load_actor(plain)
    assert not (tmp_path / "PWNED_BY_CHECKPOINT").exists()


def test_wrong_structure_raises_value_error(tmp_path) -> None:
    path = tmp_path / "other.pt"
    torch.save({"some": torch.zeros(3)}, path)
    with pytest.raises(ValueError, match="is not a valid ssl_marl checkpoint"):
        load_actor(path)
    save_actor(path, _actor(), {"skill": "s", "obs_spec": "v"})
    blob = torch.load(path, weights_only=True)
    blob["metadata"]["hidden"] = [99]
    torch.save(blob, path)
    with pytest.raises(ValueError, match="does not match its metadata"):
        load_actor(path)


def test_skill_and_spec_mismatch(tmp_path) -> None:
    path = save_actor(tmp_path / "a.pt", _actor(), {"skill": "go_to_ball", "obs_spec": "go_to_ball/v1"})
    with pytest.raises(ValueError, match=r"expected 'aim_to_shoot', found 'go_to_ball'"):
        load_actor(path, expected_skill="aim_to_shoot")
    with pytest.raises(ValueError, match=r"expected 'go_to_ball/v2', found 'go_to_ball/v1'"):
        load_actor(path, expected_skill="go_to_ball", expected_spec="go_to_ball/v2")


def test_select_picks_among_exported_actors(tmp_path) -> None:
    import json

    from ssl_marl.skills.checkpoint import save_actor
    from ssl_marl.skills.features import AIM_TO_SHOOT_SPECS
    from ssl_marl.skills.networks import Actor
    from train.tools.select import select

    for samples in (1000, 2000):
        torch.manual_seed(samples)
        save_actor(tmp_path / "actors" / f"actor-{samples:09d}.pt", Actor(10, 3, (8,)),
                   {"skill": "aim_to_shoot", "obs_spec": AIM_TO_SHOOT_SPECS["full"], "samples": samples})
    out = select(tmp_path, episodes=3, seed=5, min_samples=1500, progress=False)
    assert [c["samples"] for c in out["candidates"]] == [2000]
    assert json.loads((tmp_path / "selection.json").read_text())["best"]["samples"] == 2000
    with pytest.raises(FileNotFoundError, match="actors"):
        select(tmp_path / "empty", episodes=1)


def test_diagnose_kicks_reports_failures_and_kick_strengths(tmp_path) -> None:
    from ssl_marl.skills.checkpoint import save_actor
    from ssl_marl.skills.features import AIM_TO_SHOOT_SPECS
    from ssl_marl.skills.networks import Actor

    spec = importlib.util.spec_from_file_location("diagnose_kicks", ROOT / "benchmarks" / "diagnose_kicks.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    diagnose = module.diagnose

    torch.manual_seed(0)
    save_actor(tmp_path / "a.pt", Actor(10, 3, (8,)), {"skill": "aim_to_shoot", "obs_spec": AIM_TO_SHOOT_SPECS["full"]})
    out = diagnose(str(tmp_path / "a.pt"), episodes=3, seed=1)
    assert out["kick_action"] == "full"  # taken from the checkpoint's spec
    assert out["success_rate"] * 3 + sum(out["failure_reasons"].values()) == pytest.approx(3)
    assert all(k == 1.0 for k in out["failed_kick_strengths"])
