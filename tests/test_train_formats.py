"""Stored formats and entry points of the trainer: actor files of both kinds (every shipped and
stored actor loads), config files (nested sections; a top-level section key is an error naming
its place), train states of every version, and the documented ``python -m train...`` modules."""

from __future__ import annotations

import csv
import dataclasses
import json
import runpy
import sys
from pathlib import Path

import pytest
import torch

from ssl_marl.decisions.learned import load_decision_actor
from ssl_marl.skills.checkpoint import load_actor, read_actor_file, save_actor_file
from ssl_marl.skills.networks import Actor
from train.offpolicy.checkpoints import CHECKPOINT, read_train_state
from train.offpolicy.cli import main as skill_main
from train.offpolicy.config import CONFIG_DIR, SKILL_CONFIGS, config_from_dict, default_config, load_config
from train.offpolicy.loop import train

from tests.test_train_loop import toy_config

torch.set_num_threads(1)
ROOT = Path(__file__).resolve().parents[1]
SKILL_ACTORS = sorted((ROOT / "ssl_marl" / "skills" / "pretrained").glob("*.pt"))
DECISION_ACTORS = sorted((ROOT / "ssl_marl" / "decisions" / "pretrained").glob("*.pt")) \
    + [ROOT / "results" / "training" / "bc_attack_3v2.pt", ROOT / "results" / "training" / "bc_attack_3v2_snap.pt"]


# --- actor files ----------------------------------------------------------------------------------
@pytest.mark.parametrize("path", SKILL_ACTORS, ids=lambda p: p.name)
def test_every_shipped_skill_actor_loads(path: Path) -> None:
    actor, meta = load_actor(path)
    assert meta["skill"] == path.stem and actor(torch.zeros(1, actor.obs_dim)).shape == (1, actor.act_dim)


@pytest.mark.parametrize("path", DECISION_ACTORS, ids=lambda p: p.name)
def test_every_stored_decision_actor_loads_and_keeps_its_network(path: Path) -> None:
    """Stored decision actors load, in the flat layout (``ssl_marl.decision_actor/1``) or the
    current actor format (``ssl_marl.actor`` version 2), with every tensor where the loaders look."""
    actor, meta = load_decision_actor(path)
    raw = torch.load(path, weights_only=True)
    state, metadata = read_actor_file(path, "decision")
    assert "obs_mean" in state and "format" not in metadata and "state_dict" not in metadata
    if raw["format"] == "ssl_marl.actor":
        assert (raw["version"], raw["kind"]) == (2, "decision") and meta["task"] == raw["metadata"]["task"]
        flat_state, obs_mean, obs_std = raw["state_dict"], raw["state_dict"]["obs_mean"], raw["state_dict"]["obs_std"]
    else:
        assert meta["task"] == raw["task"]
        flat_state, obs_mean, obs_std = raw["state_dict"], raw["obs_mean"], raw["obs_std"]
    assert torch.equal(actor.obs_mean, obs_mean.float()) and torch.equal(state["obs_std"], obs_std)
    for k, v in flat_state.items():
        assert torch.equal(state[k], v), k


def test_decision_actor_round_trip_and_kinds(tmp_path: Path) -> None:
    src = DECISION_ACTORS[0]
    state, meta = read_actor_file(src, "decision")
    out = save_actor_file(tmp_path / "d.pt", "decision", state, meta)
    blob = torch.load(out, weights_only=True)
    assert (blob["format"], blob["version"], blob["kind"]) == ("ssl_marl.actor", 2, "decision")
    a, m = load_decision_actor(src)
    b, n = load_decision_actor(out)
    assert m == n
    for k, v in a.state_dict().items():
        assert torch.equal(b.state_dict()[k], v), k
    with pytest.raises(ValueError, match="holds a decision actor, not a skill actor"):
        load_actor(out)
    with pytest.raises(ValueError, match="holds a decision actor, not a skill actor"):
        load_actor(src)
    with pytest.raises(ValueError, match="holds a skill actor, not a decision actor"):
        load_decision_actor(SKILL_ACTORS[0])


def test_skill_actor_files_are_version_2_and_version_1_still_loads(tmp_path: Path) -> None:
    from ssl_marl.skills.checkpoint import save_actor

    torch.manual_seed(0)
    path = save_actor(tmp_path / "a.pt", Actor(5, 2, (8,)), {"skill": "toy", "obs_spec": "toy/v1"})
    blob = torch.load(path, weights_only=True)
    assert (blob["version"], blob["kind"]) == (2, "skill")
    del blob["kind"]
    blob["version"] = 1
    torch.save(blob, tmp_path / "v1.pt")
    old, _ = load_actor(tmp_path / "v1.pt")
    new, _ = load_actor(path)
    for k, v in new.state_dict().items():
        assert torch.equal(old.state_dict()[k], v)


# --- config files ---------------------------------------------------------------------------------
@pytest.mark.parametrize("path", sorted(CONFIG_DIR.glob("*.json")), ids=lambda p: p.name)
def test_every_shipped_config_loads_in_the_nested_layout(path: Path) -> None:
    cfg = load_config(path)
    data = json.loads(path.read_text())
    assert config_from_dict(cfg.to_dict()) == cfg
    assert {k for k in data if not k.startswith("_")} <= set(cfg.to_dict())


def test_every_skill_has_its_default_config() -> None:
    for skill in SKILL_CONFIGS:
        assert default_config(skill).skill


@pytest.mark.parametrize("data, new_key", [({"actor_lr": 3e-4}, "ddpg.actor_lr"), ({"bc_weight": 1.0}, "ddpg.bc_weight"),
                                           ({"td3_policy_delay": 3}, "td3.policy_delay"),
                                           ({"ou_sigma": 0.1}, "exploration.ou_sigma"),
                                           ({"exploration": "gaussian"}, "exploration.kind")])
def test_a_section_key_at_the_top_level_names_its_place(tmp_path: Path, data: dict, new_key: str) -> None:
    path = tmp_path / "flat.json"
    path.write_text(json.dumps({"skill": "toy", **data}))
    with pytest.raises(ValueError, match=new_key.replace(".", r"\.")) as err:
        load_config(path)
    assert str(path) in str(err.value)


def test_cli_set_of_a_section_key_at_the_top_level_names_its_place(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match=r"ddpg\.actor_hidden"):
        skill_main(["pendulum", "--out", str(tmp_path / "r"), "--set", "actor_hidden=[16]", "--no-progress"])
    with pytest.raises(ValueError, match="unknown config section 'ddgp'"):
        skill_main(["pendulum", "--out", str(tmp_path / "r"), "--set", "ddgp.actor_lr=1", "--no-progress"])


# --- train states ---------------------------------------------------------------------------------
def _rows(path: Path) -> list[dict[str, str]]:
    with path.open(newline="") as f:
        return [{k: v for k, v in r.items() if k != "wall_time"} for r in csv.DictReader(f)]


def test_a_version_2_train_state_with_a_flat_config_resumes_exactly(tmp_path: Path) -> None:
    cfg = toy_config(algo="td3", exploration={"kind": "gaussian", "gaussian_sigma": 0.3}, total_samples=400,
                     checkpoint_interval=200, warmup_samples=100, log_interval=7, td3={"policy_delay": 3},
                     ddpg={"actor_hidden": (32,), "critic_hidden": (32,)})
    train(cfg, 4, tmp_path / "full", progress=False)
    train(dataclasses.replace(cfg, total_samples=200), 4, tmp_path / "old", progress=False)
    state = torch.load(tmp_path / "old" / CHECKPOINT, weights_only=True)
    nested = state["config"]
    flat = {k: v for k, v in nested.items() if k not in ("ddpg", "td3", "exploration")}
    flat.update(nested["ddpg"])
    flat.update({f"td3_{k}": v for k, v in nested["td3"].items()})
    flat.update({k: v for k, v in nested["exploration"].items() if k != "kind"}, exploration="gaussian")
    state["config"], state["version"] = flat, 2
    torch.save(state, tmp_path / "old" / CHECKPOINT)
    assert read_train_state(tmp_path / "old" / CHECKPOINT)["config"] == nested
    assert skill_main(["pendulum", "--out", str(tmp_path / "old"), "--seed", "4", "--resume", "--samples", "400",
                       "--no-progress"]) == 0
    full = torch.load(tmp_path / "full" / "actor.pt", weights_only=True)["state_dict"]
    old = torch.load(tmp_path / "old" / "actor.pt", weights_only=True)["state_dict"]
    for k, v in full.items():
        assert torch.equal(old[k], v), k
    assert _rows(tmp_path / "old" / "progress.csv") == _rows(tmp_path / "full" / "progress.csv")


# --- documented entry points ----------------------------------------------------------------------
@pytest.mark.parametrize("module", ["train", "train.select", "train.compare", "train.sweep", "train.report",
                                    "train.plots", "train.export", "train.mappo_bc", "train.mappo_rollout_pi", "train.mappo_eval",
                                    "train.mappo_export", "train.mappo_report"])
def test_documented_module_commands_answer_help(module: str, monkeypatch, capsys) -> None:
    argv = [module, "--help"] if module != "train" else [module, "go-to-ball", "--help"]
    monkeypatch.setattr(sys, "argv", argv)
    for name in (module, f"{module}.__main__"):  # runpy warns when the module it runs is already imported
        if name != "train":
            monkeypatch.delitem(sys.modules, name, raising=False)
    with pytest.raises(SystemExit) as exc:
        runpy.run_module(module, run_name="__main__", alter_sys=True)
    assert exc.value.code == 0
    assert "usage: python -m " + module in capsys.readouterr().out


def test_train_mappo_command_answers_help(capsys) -> None:
    from train.__main__ import main

    with pytest.raises(SystemExit) as exc:
        main(["mappo", "--help"])
    assert exc.value.code == 0 and "usage: python -m train mappo" in capsys.readouterr().out
