"""The algorithm interface: TD3's update, the registry, exploration kinds, resume across
algorithms and checkpoint versions, TensorBoard logs and the CPU-dependent bf16 default."""

from __future__ import annotations

import copy
import csv
import dataclasses
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import torch

from ssl_marl.skills.checkpoint import load_actor
from train.offpolicy.agent import td_target
from train.offpolicy.algos import ALGOS, TD3, Agent, make_agent
from train.offpolicy.checkpoints import CHECKPOINT, read_train_state
from train.offpolicy.config import (DDPGConfig, TD3Config, TrainConfig, apply_overrides, config_from_dict,
                                    cpu_has_fast_bf16, default_config)
from train.offpolicy.exploration import GaussianNoise, OUNoise, make_exploration
from train.offpolicy.export import export_checkpoint_actor
from train.offpolicy.loop import Trainer, train
from train.offpolicy.replay import Batch

torch.set_num_threads(1)
TOY = "train.offpolicy.toy:train_toy/MoveToTarget-v0"


def toy_config(**kw: Any) -> TrainConfig:
    """The toy run config with ``kw`` on top (a section given as a dict updates only its keys)."""
    base = config_from_dict(dict(
        skill="toy", env_id=TOY, buffer_size=20_000, batch_size=64, total_samples=2_000, warmup_samples=250,
        eval_interval=0, eval_episodes=10, checkpoint_interval=10_000, torch_threads=1, log_interval=50,
        autocast_bf16=False, exploration={"ou_sigma": 0.5},
        ddpg={"actor_hidden": (64, 64), "critic_hidden": (64, 64), "actor_lr": 1e-3, "critic_lr": 1e-3, "gamma": 0.95,
              "tau": 0.02}))
    return config_from_dict(kw, base=base)


SMALL = {"actor_hidden": (32,), "critic_hidden": (32,)}


def _batch(n: int = 16, terminated: float = 0.0, seed: int = 1) -> Batch:
    g = torch.Generator().manual_seed(seed)
    return Batch(torch.randn(n, 4, generator=g), torch.rand(n, 2, generator=g) * 2 - 1, torch.randn(n, generator=g),
                 torch.randn(n, 4, generator=g), torch.full((n,), terminated))


def _rows(path: Path) -> list[dict[str, str]]:
    with path.open(newline="") as f:
        return [{k: v for k, v in r.items() if k != "wall_time"} for r in csv.DictReader(f)]


def _td3(gamma: float = 0.99, **td3: Any) -> TD3:
    torch.manual_seed(0)
    return TD3(4, 2, DDPGConfig(actor_hidden=(8,), critic_hidden=(8,), gamma=gamma), TD3Config(**td3))


def test_every_registered_algorithm_implements_the_interface() -> None:
    assert {"ddpg", "td3"} <= set(ALGOS)
    for name in ALGOS:
        torch.manual_seed(0)
        cfg = TrainConfig(algo=name, ddpg=DDPGConfig(actor_hidden=(8,), critic_hidden=(8,)), batch_size=16,
                          autocast_bf16=False)
        agent = make_agent(4, 2, cfg)
        assert isinstance(agent, Agent)
        assert agent.act(np.zeros((3, 4), np.float32)).shape == (3, 2)
        for _ in range(4):
            agent.update(_batch())
        losses = agent.read_losses()
        assert set(losses) == set(agent.loss_names) and all(np.isfinite(v) for v in losses.values())
        clone = make_agent(4, 2, cfg)
        clone.load_state_dict(copy.deepcopy(agent.state_dict()))
        torch.manual_seed(5)
        agent.update(_batch(seed=2))
        torch.manual_seed(5)
        clone.update(_batch(seed=2))  # same state + same batch and RNG -> the same next update
        obs = np.random.default_rng(0).standard_normal((5, 4)).astype(np.float32)
        np.testing.assert_array_equal(agent.act(obs), clone.act(obs))
        assert clone.updates == agent.updates == 5
    with pytest.raises(ValueError, match="algo must be one of"):
        TrainConfig(algo="sac")


def test_td3_target_is_the_smaller_twin_q_of_the_smoothed_target_action() -> None:
    agent = _td3(gamma=0.9)
    b = _batch()
    eps = agent.smoothing_noise(b)
    with torch.no_grad():
        a2 = (agent.actor_target(b.next_obs) + eps).clamp(-1, 1)
        q = torch.minimum(agent.critic1_target(b.next_obs, a2), agent.critic2_target(b.next_obs, a2)).squeeze(-1)
        y = td_target(b.rew, b.terminated, q, 0.9)
        expected = ((agent.critic1(b.obs, b.act).squeeze(-1) - y) ** 2).mean() \
            + ((agent.critic2(b.obs, b.act).squeeze(-1) - y) ** 2).mean()
    torch.testing.assert_close(agent.critic_loss(b, eps).detach(), expected)
    # twin critics start different, so the min is not just one of them
    assert not torch.equal(agent.critic1(b.obs, b.act), agent.critic2(b.obs, b.act))


def test_td3_smoothing_noise_is_clipped() -> None:
    agent = _td3(policy_noise=10.0, noise_clip=0.3)
    eps = agent.smoothing_noise(_batch(n=256))
    assert eps.abs().max() <= 0.3 and (eps.abs() == 0.3).float().mean() > 0.9
    agent = _td3(policy_noise=0.2, noise_clip=0.5)
    assert agent.smoothing_noise(_batch(n=4096)).std() == pytest.approx(0.2, rel=0.1)


def test_td3_updates_actor_and_targets_every_delay_th_step_only() -> None:
    agent = _td3(policy_delay=3)
    snap = lambda m: [p.detach().clone() for p in m.parameters()]  # noqa: E731
    changed = lambda a, b: any(not torch.equal(x, y) for x, y in zip(a, b))  # noqa: E731
    moved = []
    for _ in range(6):
        actor, target, critic = snap(agent.actor), snap(agent.critic1_target), snap(agent.critic2)
        agent.update(_batch())
        assert changed(critic, snap(agent.critic2))  # both critics learn at every update
        moved.append((changed(actor, snap(agent.actor)), changed(target, snap(agent.critic1_target))))
    assert moved == [(True, True), (False, False), (False, False)] * 2
    losses = agent.read_losses()
    assert set(losses) == {"critic", "actor"}


def test_td3_bf16_autocast_update_tracks_float32() -> None:
    losses = {}
    for bf16 in (False, True):
        torch.manual_seed(0)
        agent = TD3(4, 2, DDPGConfig(actor_hidden=(32, 32), critic_hidden=(32, 32)), TD3Config(), autocast_bf16=bf16)
        for _ in range(20):
            agent.update(_batch())
        losses[bf16] = list(agent.read_losses().values())
    assert np.allclose(losses[True], losses[False], rtol=0.05, atol=1e-3), losses


def test_td3_learns_the_toy_task_and_ships_like_ddpg(tmp_path) -> None:
    result = train(toy_config(algo="td3"), 0, tmp_path, progress=False)
    assert result["success_rate"] >= 0.8 and result["mean_return"] > -8
    actor, meta = load_actor(tmp_path / "actor.pt", expected_skill="toy")  # the ssl_marl loader, as for DDPG
    assert meta["algo"] == "td3" and meta["hyperparameters"]["algo"] == "td3" and actor.hidden == (64, 64)
    exported = export_checkpoint_actor(tmp_path, tmp_path / "exported.pt")
    _, meta2 = load_actor(exported)
    drop = ("exported_from", "created", "git_commit")
    assert {k: v for k, v in meta2.items() if k not in drop} == {k: v for k, v in meta.items() if k not in drop}


def test_td3_with_gaussian_exploration_resumes_exactly(tmp_path) -> None:
    """TD3's twin critics, delayed steps and smoothing noise (torch RNG) and the Gaussian
    exploration state survive a checkpoint: a resumed run equals the uninterrupted one."""
    cfg = toy_config(algo="td3", exploration={"kind": "gaussian", "gaussian_sigma": 0.3}, total_samples=400,
                     checkpoint_interval=200, eval_interval=150, eval_episodes=2, warmup_samples=100, log_interval=7,
                     ddpg=SMALL)
    train(cfg, 2, tmp_path / "full", progress=False)
    train(dataclasses.replace(cfg, total_samples=200), 2, tmp_path / "part", progress=False)
    train(cfg, 2, tmp_path / "part", resume=True, progress=False)
    full = torch.load(tmp_path / "full" / "actor.pt", weights_only=True)["state_dict"]
    part = torch.load(tmp_path / "part" / "actor.pt", weights_only=True)["state_dict"]
    for k, v in full.items():
        torch.testing.assert_close(part[k], v, rtol=0, atol=0)
    assert _rows(tmp_path / "part" / "progress.csv") == _rows(tmp_path / "full" / "progress.csv")
    assert _rows(tmp_path / "part" / "eval.csv") == _rows(tmp_path / "full" / "eval.csv")
    with pytest.raises(ValueError, match="trained with algo 'td3', not 'ddpg'"):
        Trainer(dataclasses.replace(cfg, algo="ddpg"), 2, tmp_path / "part", progress=False).load_checkpoint()


def _as_version_1(path: Path) -> None:
    """Rewrite a DDPG train state in the version-1 layout (DDPG only, no algorithm interface)."""
    state = torch.load(path, weights_only=True)
    meter = state["agent"].pop("losses")
    assert meter["counts"][0] == meter["counts"][1]
    state["pending_losses"] = [meter["sums"], meter["counts"][0]]
    state["noise"] = state.pop("exploration")
    state["losses"] = None if state["losses"] is None else [state["losses"]["critic"], state["losses"]["actor"]]
    del state["algo"]
    config = state["config"]  # version 1: flat, without the keys of exploration kinds and algorithms
    state["config"] = {**{k: v for k, v in config.items() if k not in ("algo", "ddpg", "td3", "exploration")},
                       **config["ddpg"], **{k: v for k, v in config["exploration"].items()
                                            if k not in ("kind", "gaussian_sigma")}}
    state["version"] = 1
    torch.save(state, path)


def test_a_version_1_checkpoint_resumes_exactly(tmp_path) -> None:
    cfg = toy_config(total_samples=400, checkpoint_interval=200, warmup_samples=100, log_interval=7,
                     demo_fn="train.offpolicy.toy:toy_demos", demo_steps=100, ddpg=SMALL)
    train(cfg, 3, tmp_path / "full", progress=False)
    train(dataclasses.replace(cfg, total_samples=200), 3, tmp_path / "old", progress=False)
    _as_version_1(tmp_path / "old" / CHECKPOINT)
    assert read_train_state(tmp_path / "old" / CHECKPOINT)["algo"] == "ddpg"
    train(cfg, 3, tmp_path / "old", resume=True, progress=False)
    full = torch.load(tmp_path / "full" / "actor.pt", weights_only=True)["state_dict"]
    old = torch.load(tmp_path / "old" / "actor.pt", weights_only=True)["state_dict"]
    for k, v in full.items():
        torch.testing.assert_close(old[k], v, rtol=0, atol=0)
    assert _rows(tmp_path / "old" / "progress.csv") == _rows(tmp_path / "full" / "progress.csv")
    blob = torch.load(tmp_path / "old" / CHECKPOINT, weights_only=True)
    blob["version"] = 99
    torch.save(blob, tmp_path / "old" / CHECKPOINT)
    with pytest.raises(ValueError, match="unsupported version 99"):
        read_train_state(tmp_path / "old" / CHECKPOINT)


def test_exploration_kinds() -> None:
    cfg = toy_config(exploration={"kind": "gaussian", "gaussian_sigma": 0.2})
    noise = make_exploration(cfg.exploration, 4, 3, np.random.default_rng(0))
    assert isinstance(noise, GaussianNoise)
    x = np.stack([noise() for _ in range(3000)])
    assert x.shape == (3000, 4, 3) and x.std() == pytest.approx(0.2, rel=0.03)
    assert abs(np.corrcoef(x[1:, 0, 0], x[:-1, 0, 0])[0, 1]) < 0.06  # independent steps (OU: 0.85)
    state = noise.state_dict()
    a = noise()
    noise.load_state_dict(state)
    np.testing.assert_array_equal(noise(), a)
    assert isinstance(make_exploration(toy_config().exploration, 4, 3, np.random.default_rng(0)), OUNoise)
    with pytest.raises(ValueError, match="exploration.kind must be one of"):
        toy_config(exploration={"kind": "eps-greedy"})
    with pytest.raises(ValueError, match="ou_sigma_per_dim has 2 values"):
        make_exploration(toy_config(exploration={"ou_sigma_per_dim": (0.1, 0.2)}).exploration, 1, 3,
                         np.random.default_rng(0))


def test_algo_by_config_and_cli_override() -> None:
    assert default_config("go-to-ball").algo == "ddpg"
    assert apply_overrides(default_config("go-to-ball"), ["algo=td3"]).algo == "td3"
    from train.offpolicy.cli import build_parser

    assert build_parser().parse_args(["pendulum", "--out", "x", "--algo", "td3"]).algo == "td3"
    with pytest.raises(SystemExit):
        build_parser().parse_args(["pendulum", "--out", "x", "--algo", "nope"])


def test_bf16_default_follows_the_cpu_flags(tmp_path) -> None:
    cases = {"amx": "fpu sse amx_bf16 amx_tile avx512f", "zen4": "fpu avx2 avx512f avx512_bf16",
             "old": "fpu sse avx2 avx512f"}
    found = {}
    for name, flags in cases.items():
        (tmp_path / name).write_text(f"processor\t: 0\nflags\t\t: {flags}\n")
        found[name] = cpu_has_fast_bf16(tmp_path / name)
    assert found == {"amx": True, "zen4": True, "old": False}
    assert cpu_has_fast_bf16(tmp_path / "missing") is False
    assert TrainConfig().autocast_bf16 == cpu_has_fast_bf16() and TrainConfig().compile is False


def test_tensorboard_logs_the_progress_scalars_and_eval_success(tmp_path) -> None:
    pytest.importorskip("tensorboard")
    from tensorboard.backend.event_processing.event_accumulator import EventAccumulator

    cfg = toy_config(total_samples=300, warmup_samples=100, eval_interval=150, eval_episodes=2,
                     demo_fn="train.offpolicy.toy:toy_demos", demo_steps=60, log_interval=20, ddpg=SMALL)
    train(cfg, 0, tmp_path, progress=False)
    events = list((tmp_path / "tb").glob("events.out.tfevents.*"))
    assert events
    acc = EventAccumulator(str(tmp_path / "tb"))
    acc.Reload()
    tags = set(acc.Tags()["scalars"])
    expected = {f"{phase}/{k}" for phase in ("train", "demo") for k in ("return", "length", "success", "r_distance",
                                                                         "r_bonus")}
    expected |= {"loss/critic", "loss/actor", "eval/mean_return", "eval/std_return", "eval/mean_length",
                 "eval/success_rate"}
    assert expected <= tags, expected - tags
    train_rows = [r for r in _rows(tmp_path / "progress.csv") if r["phase"] == "train"]
    returns = [e.value for e in acc.Scalars("train/return")]
    np.testing.assert_allclose(returns, [float(r["return"]) for r in train_rows], rtol=1e-5)
    assert [e.step for e in acc.Scalars("eval/success_rate")] == [60 + 150, 60 + 300]  # demos + samples


@pytest.mark.slow
def test_td3_solves_pendulum_within_20k_samples(tmp_path) -> None:
    """The shipped pendulum config with algo=td3: deterministic return >= -200 (10 episodes, seed 1000)."""
    cfg = dataclasses.replace(default_config("pendulum"), algo="td3")
    result = train(cfg, 0, tmp_path, progress=False)
    assert cfg.total_samples == 20_000 and result["mean_return"] >= -200


def test_select_reuse_evaluates_only_new_checkpoints(tmp_path, monkeypatch) -> None:
    import train.tools.select as sel
    from ssl_marl.skills.checkpoint import save_actor
    from ssl_marl.skills.features import AIM_TO_SHOOT_SPECS
    from ssl_marl.skills.networks import Actor

    calls: list[str] = []

    def fake_eval(task, path, episodes, seed, workers, progress, field, task_options):
        assert field == "div_b" and task_options == {}  # the actors' metadata names no field: the default one
        calls.append(Path(path).name)
        return {"success_rate": 0.5, "successes": episodes // 2, "time_to_success_s": {"mean": 1.0},
                "failure_reasons": {}}

    monkeypatch.setattr(sel, "evaluate_skill", fake_eval)
    for samples in (1000, 2000):
        save_actor(tmp_path / "actors" / f"actor-{samples:09d}.pt", Actor(10, 3, (8,)),
                   {"skill": "aim_to_shoot", "obs_spec": AIM_TO_SHOOT_SPECS["full"], "samples": samples,
                    "algo": "td3"})
        sel.select(tmp_path, episodes=4, seed=5, progress=False, reuse=True)
    assert calls == ["actor-000001000.pt", "actor-000002000.pt"]  # the first was not evaluated twice
    out = sel.select(tmp_path, episodes=4, seed=6, progress=False, reuse=True)  # another protocol: all again
    assert len(calls) == 4 and [c["algo"] for c in out["candidates"]] == ["td3", "td3"]


def test_compare_reports_windows_evaluations_and_samples_to_target(tmp_path, capsys) -> None:
    import json

    from train.tools.compare import main as compare_main

    run = tmp_path / "r"
    run.mkdir()
    (run / "config.json").write_text(json.dumps({"algo": "td3", "seed": 1}))
    (run / "progress.csv").write_text("phase,samples,return,success\ndemo,0,-1,1\ntrain,400,-10,0\ntrain,900,-5,1\n"
                                      "train,1500,-2,1\n")
    (run / "eval.csv").write_text("samples,success_rate,wall_time\n1000,0.5,12.5\n2000,0.8,30.25\n")
    (run / "selection.json").write_text(json.dumps({"validation_seed": 5000, "episodes": 100, "candidates": [
        {"samples": 2000, "success_rate": 0.995}, {"samples": 1000, "success_rate": 0.9}]}))
    compare_main([str(run), "--window", "1000", "--target", "0.99"])
    out = capsys.readouterr().out
    assert "| `r` | td3 | 1,000 | 2 | 0.500 | -7.5 |" in out  # demo rows are not training episodes
    assert "| `r` | td3 | 1,500 | 1 | 1.000 | -2.0 |" in out  # the last, partial window
    assert "1k: 0.5" in out and "1k: 0.900, 2k: 0.995 | 2,000 | 30 s |" in out  # wall clock at that checkpoint
