"""OU noise statistics and the replay ring buffer."""

from __future__ import annotations

import numpy as np
import pytest
import torch

from train.offpolicy.exploration import OUNoise
from train.offpolicy.replay import ReplayBuffer

torch.set_num_threads(1)


def _ou_samples(dt: float, steps: int, theta: float = 0.15, sigma: float = 0.3) -> np.ndarray:
    noise = OUNoise(64, 4, theta=theta, mu=0.0, sigma=sigma, dt=dt, rng=np.random.default_rng(0))
    burn = int(20 / (theta * dt))  # ~20 relaxation times
    for _ in range(burn):
        noise()
    return np.stack([noise() for _ in range(steps)])


def test_ou_stationary_statistics_dt1() -> None:
    theta, sigma = 0.15, 0.3
    x = _ou_samples(1.0, 4000, theta, sigma)  # 4000 x 256 correlated samples
    assert abs(x.mean()) < 0.02
    exact = sigma / np.sqrt(2 * theta - theta**2)  # discrete AR(1) stationary std, 0.569
    assert x.std() == pytest.approx(exact, rel=0.03)
    assert x.std() == pytest.approx(sigma / np.sqrt(2 * theta), rel=0.06)  # continuous-time value, 0.548
    # lag-1 autocorrelation of the AR(1) is 1 - theta * dt
    rho = np.mean(x[1:] * x[:-1]) / np.mean(x * x)
    assert rho == pytest.approx(1 - theta, abs=0.01)


def test_ou_small_dt_approaches_continuous_std() -> None:
    x = _ou_samples(0.1, 4000)
    assert x.std() == pytest.approx(0.3 / np.sqrt(0.3), rel=0.05)


def test_ou_reset_per_env_and_state_roundtrip() -> None:
    noise = OUNoise(3, 2, mu=0.5, rng=np.random.default_rng(1))
    for _ in range(10):
        noise()
    noise.reset(np.array([False, True, False]))
    assert np.all(noise.x[1] == 0.5) and not np.all(noise.x[0] == 0.5)
    state = noise.state_dict()
    a = noise()
    noise.load_state_dict(state)
    np.testing.assert_array_equal(noise(), a)
    noise.reset()
    assert np.all(noise.x == 0.5)


def _add_rows(buf: ReplayBuffer, ids: list[int]) -> None:
    ids_a = np.asarray(ids, np.float32)
    buf.add(np.stack([ids_a, -ids_a], 1), np.stack([ids_a] * 2, 1) / 100, ids_a * 10, np.stack([ids_a + 1, -ids_a], 1),
            (ids_a % 2 == 0))


def test_replay_wraps_around_in_order() -> None:
    buf = ReplayBuffer(5, 2, 2, batch_size=4, rng=np.random.default_rng(0))
    _add_rows(buf, [0, 1, 2])
    assert len(buf) == 3 and buf.ptr == 3
    _add_rows(buf, [3, 4, 5, 6])  # 5 and 6 overwrite rows 0 and 1
    assert len(buf) == 5 and buf.ptr == 2
    np.testing.assert_array_equal(buf.obs[:, 0], [5, 6, 2, 3, 4])
    np.testing.assert_array_equal(buf.rew, [50, 60, 20, 30, 40])
    np.testing.assert_array_equal(buf.terminated, [0, 1, 1, 0, 1])
    _add_rows(buf, list(range(10, 22)))  # more than capacity at once: the newest 5 survive
    assert sorted(buf.obs[:, 0].tolist()) == [17, 18, 19, 20, 21] and len(buf) == 5
    _add_rows(buf, [])  # no-op
    assert len(buf) == 5


def test_replay_sample_shapes_and_contents() -> None:
    buf = ReplayBuffer(100, 2, 2, batch_size=32, rng=np.random.default_rng(0))
    with pytest.raises(ValueError):
        buf.sample()
    _add_rows(buf, list(range(7)))
    b = buf.sample()
    assert b.obs.shape == (32, 2) and b.act.shape == (32, 2) and b.rew.shape == (32,)
    assert b.next_obs.shape == (32, 2) and b.terminated.shape == (32,)
    assert all(t.dtype == torch.float32 for t in b[:5]) and b.discount is None  # one-step: no per-row discount
    ids = b.obs[:, 0]
    assert set(ids.tolist()) <= set(range(7)) and len(set(ids.tolist())) > 3  # only stored rows, several of them
    # every field of a sampled row belongs to the same transition
    torch.testing.assert_close(b.rew, ids * 10)
    torch.testing.assert_close(b.next_obs[:, 0], ids + 1)
    torch.testing.assert_close(b.act[:, 1], ids / 100)
    torch.testing.assert_close(b.terminated, (ids % 2 == 0).float())


def test_replay_save_load_roundtrip(tmp_path) -> None:
    buf = ReplayBuffer(6, 2, 2, batch_size=3, rng=np.random.default_rng(0))
    _add_rows(buf, list(range(8)))
    buf.save(tmp_path / "r.npz")
    other = ReplayBuffer(6, 2, 2, batch_size=3)
    other.load(tmp_path / "r.npz")
    assert (other.ptr, other.size) == (buf.ptr, buf.size)
    np.testing.assert_array_equal(other.obs, buf.obs)
    with pytest.raises(ValueError, match="does not match"):
        ReplayBuffer(7, 2, 2, batch_size=3).load(tmp_path / "r.npz")
    (tmp_path / "bad.npz").write_bytes(b"not a zip")
    with pytest.raises(ValueError, match="not a valid replay"):
        other.load(tmp_path / "bad.npz")
    assert not list(tmp_path.glob("*.tmp"))


def test_ou_noise_per_dimension_sigma():
    import numpy as np

    from train.offpolicy.exploration import OUNoise

    noise = OUNoise(1, 3, theta=0.15, sigma=[0.3, 0.0, 0.05], rng=np.random.default_rng(0))
    xs = np.array([noise()[0] for _ in range(20000)])
    std = xs[2000:].std(axis=0)
    assert std[1] == 0.0
    assert abs(std[0] / std[2] - 6.0) < 0.6
