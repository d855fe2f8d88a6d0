"""The training loop: autoreset handling, demo burn-in, learning, resume, CLI."""

from __future__ import annotations

import csv
import dataclasses
import json
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
import pytest
import torch

from train.offpolicy.cli import main as cli_main
from train.offpolicy.config import TrainConfig, config_from_dict
from train.offpolicy.evaluate import main as evaluate_main, run_episodes
from train.offpolicy.loop import Trainer, train
from train.offpolicy.toy import ENV_ID as TOY_ID, toy_demos

torch.set_num_threads(1)
TOY = "train.offpolicy.toy:" + TOY_ID
COUNTER_ID = "test_train/Counter-v0"


class CounterEnv(gym.Env):
    """obs = [episode id, t, episode length L, 1 if it terminates else 0 (truncates)]."""

    def __init__(self) -> None:
        self.observation_space = gym.spaces.Box(-np.inf, np.inf, (4,), np.float32)
        self.action_space = gym.spaces.Box(-1.0, 1.0, (1,), np.float32)

    def _obs(self) -> np.ndarray:
        return np.array([self.ep, self.t, self.length, self.terminates], np.float32)

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None):
        super().reset(seed=seed)
        self.ep = int(self.np_random.integers(1, 2**24))
        self.length = int(self.np_random.integers(1, 5))
        self.terminates = int(self.np_random.integers(0, 2))
        self.t = 0
        return self._obs(), {}

    def step(self, action):
        self.t += 1
        end = self.t >= self.length
        return self._obs(), 1.0, end and bool(self.terminates), end and not self.terminates, {}


if COUNTER_ID not in gym.registry:
    gym.register(id=COUNTER_ID, entry_point=CounterEnv)


def toy_config(**kw: Any) -> TrainConfig:
    """The toy run config with ``kw`` on top (a section given as a dict updates only its keys)."""
    base = config_from_dict(dict(
        skill="toy", env_id=TOY, buffer_size=20_000, batch_size=64, total_samples=2_000, warmup_samples=250,
        eval_interval=0, eval_episodes=10, checkpoint_interval=10_000, torch_threads=1, log_interval=50,
        autocast_bf16=False,  # float32 whatever the CPU (tiny networks: bf16 casts would only cost)
        exploration={"ou_sigma": 0.5},
        ddpg={"actor_hidden": (64, 64), "critic_hidden": (64, 64), "actor_lr": 1e-3, "critic_lr": 1e-3, "gamma": 0.95,
              "tau": 0.02}))
    return config_from_dict(kw, base=base)


def read_rows(path: Path, drop: tuple[str, ...] = ("wall_time",)) -> list[dict[str, str]]:
    with path.open(newline="") as f:
        return [{k: v for k, v in r.items() if k not in drop} for r in csv.DictReader(f)]


def test_autoreset_steps_are_never_stored(tmp_path) -> None:
    cfg = toy_config(env_id=COUNTER_ID, num_envs=3, warmup_samples=10**9, buffer_size=1000, total_samples=10**6)
    tr = Trainer(cfg, seed=0, out=tmp_path, progress=False)
    tr._reset_envs()
    steps = 50
    for _ in range(steps):
        tr.collect_step()
    b = tr.buffer
    obs, nxt, term = b.obs[: b.size], b.next_obs[: b.size], b.terminated[: b.size]
    assert b.size == tr.samples < steps * 3  # some steps were autoreset steps and were skipped
    np.testing.assert_array_equal(nxt[:, 0], obs[:, 0])  # never crosses an episode boundary
    np.testing.assert_array_equal(nxt[:, 1], obs[:, 1] + 1)
    ends = nxt[:, 1] == nxt[:, 2]
    np.testing.assert_array_equal(term, (ends & (nxt[:, 3] == 1)).astype(np.float32))  # truncations bootstrap
    assert ((ends & (nxt[:, 3] == 0)).sum() > 0) and ((ends & (nxt[:, 3] == 1)).sum() > 0)
    # every finished episode is stored completely, exactly once
    for ep in np.unique(obs[ends, 0]):
        ts = np.sort(obs[obs[:, 0] == ep, 1])
        np.testing.assert_array_equal(ts, np.arange(int(obs[obs[:, 0] == ep][0, 2])))
    assert tr.episodes == int(ends.sum())
    tr.envs.close()


def test_async_vector_env_collects_the_same_data(tmp_path) -> None:
    buffers = []
    for mode in ("sync", "async"):
        cfg = toy_config(env_id=COUNTER_ID, num_envs=2, vector_mode=mode, warmup_samples=10**9, buffer_size=500)
        tr = Trainer(cfg, seed=3, out=tmp_path / mode, progress=False)
        tr._reset_envs()
        for _ in range(25):
            tr.collect_step()
        tr.envs.close()
        buffers.append((tr.buffer.obs[: tr.buffer.size].copy(), tr.buffer.act[: tr.buffer.size].copy()))
    np.testing.assert_array_equal(buffers[0][0], buffers[1][0])
    np.testing.assert_array_equal(buffers[0][1], buffers[1][1])


def test_demo_burn_in_fills_buffer_with_demos_in_spaces(tmp_path) -> None:
    cfg = toy_config(demo_fn="train.offpolicy.toy:toy_demos", demo_steps=300)
    tr = Trainer(cfg, seed=4, out=tmp_path, progress=False)
    tr._reset_envs()
    tr.burn_in()
    demos = list(toy_demos(300, seed=4))
    b = tr.buffer
    assert b.size == tr.transitions == 300 and tr.samples == 0
    np.testing.assert_array_equal(b.obs[:300, 0], [d.obs[0] for d in demos])
    np.testing.assert_array_equal(b.next_obs[:300, 0], [d.next_obs[0] for d in demos])
    np.testing.assert_allclose(b.act[:300, 0], [d.action[0] / 2 for d in demos])  # Box(-2, 2) -> [-1, 1]
    np.testing.assert_array_equal(b.terminated[:300], [float(d.terminated) for d in demos])
    np.testing.assert_allclose(b.rew[:300], [d.reward for d in demos], rtol=1e-6)
    space = tr.eval_env.observation_space
    assert all(space.contains(o) for o in b.obs[:300]) and np.all(np.abs(b.act[:300]) <= 1)
    tr.log.close()
    rows = read_rows(tmp_path / "progress.csv")
    assert rows and all(r["phase"] == "demo" for r in rows) and rows[0]["success"] == "1"
    assert {"r_distance", "r_bonus"} <= set(rows[0])
    assert len(rows) == sum(d.terminated or d.truncated for d in demos)
    tr.envs.close()


def _bad_demos(n_steps: int, seed: int = 0, **kw: Any):
    for t in toy_demos(n_steps, seed, **kw):
        yield t._replace(action=t.action * 3)  # outside Box(-2, 2)


def test_demos_outside_the_spaces_are_rejected(tmp_path) -> None:
    tr = Trainer(toy_config(demo_steps=50, demo_fn="x:y"), seed=0, out=tmp_path / "a", demo_fn=_bad_demos,
                 progress=False)
    with pytest.raises(ValueError, match="outside"):
        tr.burn_in()
    tr = Trainer(toy_config(demo_steps=50, demo_fn="x:y"), seed=0, out=tmp_path / "b",
                 demo_fn=lambda n_steps, seed: toy_demos(10, seed), progress=False)
    with pytest.raises(ValueError, match="produced 10 transitions"):
        tr.burn_in()


def test_short_training_improves_on_untrained_policy(tmp_path) -> None:
    tr = Trainer(toy_config(), seed=0, out=tmp_path, progress=False)
    before = run_episodes(tr.eval_env, lambda o: tr.agent.act(o[None])[0], 10, seed=1000)
    result = tr.run()
    assert before["mean_return"] < -10  # idle-ish policy
    assert result["mean_return"] > before["mean_return"] + 8
    assert result["success_rate"] >= 0.8
    for name in ("actor.pt", "eval.json", "progress.csv", "checkpoint.pt", "config.json", "learning_curve.png"):
        assert (tmp_path / name).exists(), name


def test_resume_continues_exactly(tmp_path) -> None:
    cfg = toy_config(total_samples=1_200, checkpoint_interval=600, eval_interval=400, eval_episodes=3,
                     demo_fn="train.offpolicy.toy:toy_demos", demo_steps=100, warmup_samples=100)
    train(cfg, 1, tmp_path / "full", progress=False)
    train(dataclasses.replace(cfg, total_samples=600), 1, tmp_path / "part", progress=False)
    with pytest.raises(FileExistsError):
        train(cfg, 1, tmp_path / "part", progress=False)
    assert len(list((tmp_path / "part").glob("replay-*.npz"))) == 1
    train(cfg, 1, tmp_path / "part", resume=True, progress=False)

    full = torch.load(tmp_path / "full" / "actor.pt", weights_only=True)
    part = torch.load(tmp_path / "part" / "actor.pt", weights_only=True)
    for k, v in full["state_dict"].items():
        torch.testing.assert_close(part["state_dict"][k], v, rtol=0, atol=0)
    assert part["metadata"]["samples"] == 1_200
    rows_full, rows_part = read_rows(tmp_path / "full" / "progress.csv"), read_rows(tmp_path / "part" / "progress.csv")
    assert rows_part == rows_full  # same episodes, same losses, nothing lost or duplicated
    assert [r["phase"] for r in rows_part].count("demo") > 0
    assert read_rows(tmp_path / "part" / "eval.csv") == read_rows(tmp_path / "full" / "eval.csv")
    assert int(rows_part[-1]["samples"]) <= 1_200 and int(rows_part[-1]["episode"]) == len(rows_part)


def test_resume_errors(tmp_path) -> None:
    with pytest.raises(FileNotFoundError, match="checkpoint.pt"):
        train(toy_config(), 0, tmp_path / "empty", resume=True, progress=False)
    (tmp_path / "bad").mkdir()
    (tmp_path / "bad" / "checkpoint.pt").write_bytes(b"\x80\x04junk")
    with pytest.raises(ValueError, match="not a valid ssl_marl training checkpoint"):
        train(toy_config(), 0, tmp_path / "bad", resume=True, progress=False)


def test_cli_runs_and_resumes(tmp_path, capsys) -> None:
    cfg_path = tmp_path / "toy.json"
    cfg_path.write_text(json.dumps(toy_config(total_samples=300, warmup_samples=100).to_dict()))
    out = tmp_path / "run"
    args = ["pendulum", "--config", str(cfg_path), "--seed", "2", "--out", str(out), "--no-progress"]
    assert cli_main(args + ["--set", "eval_episodes=2", "--set", "ddpg.actor_hidden=[16]"]) == 0
    assert '"mean_return"' in capsys.readouterr().out
    assert cli_main(args + ["--resume", "--samples", "500"]) == 0
    rows = read_rows(out / "progress.csv")
    assert int(rows[-1]["samples"]) > 300
    meta = torch.load(out / "actor.pt", weights_only=True)["metadata"]
    assert meta["samples"] == 500 and meta["hidden"] == [16] and meta["obs_spec"] == "toy_move_to_target/v1"
    assert meta["skill"] == "toy" and meta["hyperparameters"]["eval_episodes"] == 2
    assert evaluate_main([TOY, str(out / "actor.pt"), "--episodes", "2", "--out", str(tmp_path / "e.json")]) == 0
    result = json.loads((tmp_path / "e.json").read_text())
    assert result["episodes"] == 2 and result["skill"] == "toy" and np.isfinite(result["mean_return"])
