"""n-step returns (train.offpolicy.nstep): hand-computed windows, terminal vs truncated, n = 1, the loop and resume."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import torch

from train.offpolicy.agent import td_target
from train.offpolicy.config import DDPGConfig
from train.offpolicy.ddpg import DDPG
from train.offpolicy.loop import Trainer, train
from train.offpolicy.nstep import NStepBuffer
from train.offpolicy.replay import Batch, ReplayBuffer

from tests.test_train_loop import COUNTER_ID, read_rows, toy_config

torch.set_num_threads(1)
G = 0.5  # a gamma whose powers are exact in float32


def _run(buf: NStepBuffer, rewards: list[float], end: str) -> list:
    """Feed one episode of ``rewards`` to sub-env 0 (obs = step index); it ends with ``end``
    ("terminated", "truncated" or "open") at its last step; return every batch emitted."""
    out = []
    for t, r in enumerate(rewards):
        last = t == len(rewards) - 1
        out.append(buf.step(np.array([0]), np.array([[t]], np.float32), np.array([[t / 10]], np.float32),
                            np.array([r]), np.array([[t + 1]], np.float32),
                            np.array([last and end == "terminated"]), np.array([last and end == "truncated"])))
    return out


def test_three_step_returns_with_a_terminal_in_the_window() -> None:
    buf = NStepBuffer(1, 3, G, 1, 1)
    out = _run(buf, [1.0, 2.0, 4.0, 8.0, 16.0], "terminated")
    assert [len(b.rew) for b in out] == [0, 0, 1, 1, 3]  # windows fill at t=2; the terminal flushes 3
    rows = [(b.obs[i, 0], b.rew[i], b.next_obs[i, 0], b.terminated[i], b.discount[i]) for b in out
            for i in range(len(b.rew))]
    assert rows == [
        (0, 1 + G * 2 + G**2 * 4, 3, 0.0, G**3),
        (1, 2 + G * 4 + G**2 * 8, 4, 0.0, G**3),
        (2, 4 + G * 8 + G**2 * 16, 5, 1.0, G**3),  # the window reaches the terminal: no bootstrap
        (3, 8 + G * 16, 5, 1.0, G**2),  # truncated window, still terminal
        (4, 16.0, 5, 1.0, G),
    ]
    np.testing.assert_array_equal(out[2].act[:, 0], np.float32([0.0]))
    assert len(buf) == 0


def test_truncation_bootstraps_with_the_discount_of_the_steps_taken() -> None:
    buf = NStepBuffer(1, 3, G, 1, 1)
    out = _run(buf, [1.0, 2.0], "truncated")
    b = out[-1]
    np.testing.assert_array_equal(b.obs[:, 0], [0, 1])
    np.testing.assert_array_equal(b.rew, np.float32([1 + G * 2, 2]))
    np.testing.assert_array_equal(b.next_obs[:, 0], [2, 2])  # the last true observation
    np.testing.assert_array_equal(b.terminated, [0, 0])  # a time limit is not an end of the task
    np.testing.assert_array_equal(b.discount, np.float32([G**2, G]))
    # the target: r + discount * Q' for both, so Q'(s_2) is weighted by the steps actually taken
    y = td_target(torch.from_numpy(b.rew), torch.from_numpy(b.terminated), torch.tensor([10.0, 10.0]), G,
                  torch.from_numpy(b.discount))
    torch.testing.assert_close(y, torch.tensor([1 + G * 2 + G**2 * 10, 2 + G * 10]))


def test_flush_ends_open_windows_as_truncations_and_envs_are_independent() -> None:
    buf = NStepBuffer(2, 3, G, 1, 1)
    for t in range(2):  # env 0 and env 1 step together, different rewards
        buf.step(np.array([0, 1]), np.float32([[t], [100 + t]]), np.zeros((2, 1), np.float32), np.array([1.0, 3.0]),
                 np.float32([[t + 1], [101 + t]]), np.zeros(2, bool), np.zeros(2, bool))
    assert len(buf) == 4
    b = buf.flush(np.float32([[2], [102]]))
    assert len(buf) == 0
    np.testing.assert_array_equal(b.obs[:, 0], [0, 1, 100, 101])
    np.testing.assert_array_equal(b.rew, np.float32([1 + G, 1, 3 + 3 * G, 3]))
    np.testing.assert_array_equal(b.next_obs[:, 0], [2, 2, 102, 102])
    np.testing.assert_array_equal(b.terminated, [0, 0, 0, 0])
    np.testing.assert_array_equal(b.discount, np.float32([G**2, G, G**2, G]))


def test_n_equal_one_is_the_one_step_transition() -> None:
    buf = NStepBuffer(1, 1, 0.99, 1, 1)
    out = _run(buf, [1.0, -2.0, 3.0], "terminated")
    assert [len(b.rew) for b in out] == [1, 1, 1]
    np.testing.assert_array_equal(np.concatenate([b.rew for b in out]), np.float32([1, -2, 3]))
    np.testing.assert_array_equal(np.concatenate([b.next_obs[:, 0] for b in out]), [1, 2, 3])
    np.testing.assert_array_equal(np.concatenate([b.terminated for b in out]), [0, 0, 1])
    np.testing.assert_array_equal(np.concatenate([b.discount for b in out]), np.float32([0.99] * 3))
    # and a per-row discount equal to gamma gives the one-step target bit for bit
    g = torch.Generator().manual_seed(0)
    rew, term, q = torch.randn(64, generator=g), (torch.rand(64, generator=g) < 0.3).float(), torch.randn(64, generator=g)
    assert torch.equal(td_target(rew, term, q, 0.99), td_target(rew, term, q, 0.99, torch.full((64,), 0.99)))


def test_bad_n_and_bad_discount_use_are_rejected() -> None:
    with pytest.raises(ValueError, match="n_step"):
        NStepBuffer(1, 0, 0.9, 1, 1)
    with pytest.raises(ValueError, match="n_step must be >= 1"):
        toy_config(n_step=0)
    with pytest.raises(ValueError, match="discount"):
        ReplayBuffer(10, 1, 1, 2).add(np.zeros((1, 1)), np.zeros((1, 1)), np.zeros(1), np.zeros((1, 1)), np.zeros(1),
                                      np.ones(1))


def test_default_n_step_keeps_the_one_step_replay() -> None:
    assert toy_config().n_step == 1
    buf = ReplayBuffer(10, 2, 1, 4)
    assert buf.sample.__self__ is buf and "discount" not in buf._FIELDS
    buf.add(np.zeros((3, 2)), np.zeros((3, 1)), np.ones(3), np.zeros((3, 2)), np.zeros(3))
    assert buf.sample().discount is None


def test_ddpg_critic_target_uses_the_row_discount() -> None:
    agent = DDPG(3, 1, DDPGConfig(actor_hidden=(8,), critic_hidden=(8,), gamma=0.9))
    g = torch.Generator().manual_seed(2)
    b = Batch(torch.randn(8, 3, generator=g), torch.rand(8, 1, generator=g), torch.randn(8, generator=g),
              torch.randn(8, 3, generator=g), torch.zeros(8))
    same = agent.critic_loss(b._replace(discount=torch.full((8,), 0.9)))
    assert torch.equal(same, agent.critic_loss(b))
    assert not torch.equal(agent.critic_loss(b._replace(discount=torch.full((8,), 0.5))), same)


def test_loop_stores_n_step_rows_over_real_episodes(tmp_path) -> None:
    """CounterEnv (reward 1 per step, obs = [episode, t, L, terminates]) through 3 sub-envs."""
    cfg = toy_config(env_id=COUNTER_ID, num_envs=3, n_step=3, ddpg={"gamma": G}, warmup_samples=10**9, buffer_size=1000,
                     total_samples=10**6)
    tr = Trainer(cfg, seed=0, out=tmp_path, progress=False)
    tr._reset_envs()
    for _ in range(60):
        tr.collect_step()
    b = tr.buffer
    obs, nxt, term, rew, disc = (getattr(b, k)[: b.size] for k in ("obs", "next_obs", "terminated", "rew", "discount"))
    k = nxt[:, 1] - obs[:, 1]
    np.testing.assert_array_equal(nxt[:, 0], obs[:, 0])  # never crosses an episode boundary
    np.testing.assert_array_equal(k, np.minimum(3, obs[:, 2] - obs[:, 1]))  # window truncated at the end
    np.testing.assert_array_equal(disc, np.float32(G) ** k)
    np.testing.assert_allclose(rew, (1 - G**k) / (1 - G), rtol=1e-6)  # sum of G^i, i < k
    ends = nxt[:, 1] == nxt[:, 2]
    np.testing.assert_array_equal(term, (ends & (nxt[:, 3] == 1)).astype(np.float32))
    assert (ends & (nxt[:, 3] == 0)).any() and (ends & (nxt[:, 3] == 1)).any()
    assert b.size + len(tr.nstep) == tr.samples  # every env step is stored once or still pending
    tr.buffer.add(*tr.nstep.flush(tr.obs))  # what a checkpoint cut does
    assert b.size == tr.samples
    tr.envs.close()


def test_n_step_resume_continues_exactly(tmp_path) -> None:
    cfg = toy_config(total_samples=900, checkpoint_interval=450, n_step=3, warmup_samples=100,
                     demo_fn="train.offpolicy.toy:toy_demos", demo_steps=100)
    train(cfg, 1, tmp_path / "full", progress=False)
    train(dataclasses.replace(cfg, total_samples=450), 1, tmp_path / "part", progress=False)
    train(cfg, 1, tmp_path / "part", resume=True, progress=False)
    full = torch.load(tmp_path / "full" / "actor.pt", weights_only=True)
    part = torch.load(tmp_path / "part" / "actor.pt", weights_only=True)
    for key, v in full["state_dict"].items():
        assert torch.equal(part["state_dict"][key], v), key
    assert read_rows(tmp_path / "part" / "progress.csv") == read_rows(tmp_path / "full" / "progress.csv")


def test_three_step_training_learns_the_toy_task(tmp_path) -> None:
    """3-step returns end to end on the CI-sized toy task: success >= 0.8 after 2,000 samples.
    (The whole go_to_ball_fast recipe, 3-step + 4 envs + 0.5 updates per sample, scored 0.7 and
    1.0 on toy seeds 0 and 1 at 2,000 samples: too few updates for this task; not asserted.)"""
    result = Trainer(toy_config(n_step=3), seed=0, out=tmp_path, progress=False).run()
    assert result["success_rate"] >= 0.8 and result["mean_return"] > -5
