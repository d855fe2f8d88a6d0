"""The DDPG update: Bellman target, soft update, one update step, config handling."""

from __future__ import annotations

import json

import numpy as np
import pytest
import torch

from train.offpolicy.config import DDPGConfig, TrainConfig, apply_overrides, default_config, load_config
from train.offpolicy.ddpg import DDPG, soft_update, td_target
from train.offpolicy.replay import Batch

torch.set_num_threads(1)




def test_td_target_terminal_does_not_bootstrap_truncated_does() -> None:
    rew = torch.tensor([1.0, 1.0, -2.0])
    terminated = torch.tensor([1.0, 0.0, 0.0])  # terminal, truncated (stored as not terminated), ordinary
    next_q = torch.tensor([5.0, 5.0, 10.0])
    y = td_target(rew, terminated, next_q, gamma=0.9)
    torch.testing.assert_close(y, torch.tensor([1.0, 1.0 + 0.9 * 5.0, -2.0 + 9.0]))


def test_soft_update_is_exact_lerp() -> None:
    torch.manual_seed(0)
    target = [torch.randn(3, 4), torch.randn(5)]
    online = [torch.randn(3, 4), torch.randn(5)]
    expected = [t + 0.01 * (o - t) for t, o in zip(target, online)]
    soft_update(target, online, 0.01)
    for t, e in zip(target, expected):
        torch.testing.assert_close(t, e, rtol=0, atol=1e-6)
    soft_update(target, online, 1.0)  # tau = 1 copies
    for t, o in zip(target, online):
        torch.testing.assert_close(t, o, rtol=0, atol=0)


def _batch(n: int = 16, terminated: float = 0.0) -> Batch:
    g = torch.Generator().manual_seed(1)
    return Batch(torch.randn(n, 4, generator=g), torch.rand(n, 2, generator=g) * 2 - 1, torch.randn(n, generator=g),
                 torch.randn(n, 4, generator=g), torch.full((n,), terminated))


def test_update_moves_networks_and_targets_by_tau() -> None:
    torch.manual_seed(0)
    cfg = DDPGConfig(actor_hidden=(8, 8), critic_hidden=(8, 8), tau=0.1)
    agent = DDPG(4, 2, cfg)
    before = {k: v.clone() for k, v in agent.state_dict()["actor_target"].items()}
    agent.update(_batch())
    after_online = agent.actor.state_dict()
    for k, v in agent.actor_target.state_dict().items():
        torch.testing.assert_close(v, before[k] + 0.1 * (after_online[k] - before[k]), rtol=0, atol=1e-6)
    assert agent.updates == 1
    losses = agent.read_losses()
    assert set(losses) == {"critic", "actor"}
    c, a = losses["critic"], losses["actor"]
    assert np.isfinite(c) and np.isfinite(a)
    assert agent.read_losses() is None
    assert all(p.grad is None for p in agent.critic_target.parameters())


def test_critic_fits_terminal_rewards_exactly() -> None:
    """With terminated = 1 the target is r alone, so the critic regresses Q(s, a) onto r."""
    torch.manual_seed(0)
    cfg = DDPGConfig(actor_hidden=(16,), critic_hidden=(64, 64), critic_lr=3e-3)
    agent = DDPG(4, 2, cfg)
    b = _batch(terminated=1.0)
    for _ in range(300):
        agent.update(b)
    q = agent.critic(b.obs, b.act).squeeze(-1).detach()
    assert torch.mean((q - b.rew) ** 2) < 0.05 * torch.var(b.rew)


def test_shipped_configs_follow_the_paper() -> None:
    g = default_config("go-to-ball")
    assert (g.ddpg.critic_lr, g.ddpg.actor_lr, g.ddpg.critic_hidden, g.ddpg.actor_hidden) == \
        (1e-3, 1e-4, (300, 400), (300, 400))
    assert (g.buffer_size, g.demo_steps, g.total_samples) == (1_000_000, 50_000, 500_000)
    a = default_config("aim-to-shoot")
    assert (a.ddpg.critic_lr, a.ddpg.actor_lr, a.buffer_size) == (1e-4, 1e-4, 600_000)
    assert a.ddpg.critic_hidden == a.ddpg.actor_hidden == (200, 300, 300, 300)
    # documented departures for aim-to-shoot (train/configs/aim_to_shoot.json, docs/RESULTS.md)
    assert a.demo_steps == 20_000 and a.ddpg.bc_weight == 100.0 and a.exploration.ou_sigma_per_dim == (0.3, 0.05, 0.05)
    for c in (g, a):
        assert (c.exploration.kind, c.exploration.ou_theta, c.exploration.ou_mu, c.exploration.ou_sigma) == \
            ("ou", 0.15, 0.0, 0.3)
        assert c.ddpg.layer_norm
    p = default_config("pendulum")
    assert p.env_id == "Pendulum-v1" and p.total_samples == 20_000


def test_config_errors_and_overrides(tmp_path) -> None:
    path = tmp_path / "c.json"
    path.write_text(json.dumps({"_note": "comments allowed", "ddpg": {"gamma": 0.9, "actor_hidden": [4, 4]}}))
    cfg = load_config(path)
    assert cfg.ddpg.gamma == 0.9 and cfg.ddpg.actor_hidden == (4, 4) and cfg.ddpg.critic_lr == 1e-3
    cfg = apply_overrides(cfg, ["total_samples=2e4", "demo_fn=null", "ddpg.critic_hidden=[8, 8]", "env_id=Foo-v0",
                                "exploration.kind=gaussian", "td3.policy_delay=3.0"])
    assert cfg.total_samples == 20000 and isinstance(cfg.total_samples, int)
    assert cfg.demo_fn is None and cfg.ddpg.critic_hidden == (8, 8) and cfg.env_id == "Foo-v0"
    assert cfg.ddpg.gamma == 0.9 and cfg.exploration.kind == "gaussian" and cfg.td3.policy_delay == 3
    path.write_text(json.dumps({"gamam": 0.9}))
    with pytest.raises(ValueError, match="unknown training config key"):
        load_config(path)
    with pytest.raises(ValueError, match="ddpg.tau"):
        apply_overrides(cfg, ["ddpg.tau=0"])
    with pytest.raises(ValueError, match="key=value"):
        apply_overrides(cfg, ["tau"])
    with pytest.raises(ValueError, match=r"unknown training config key\(s\) \['ddpg.gamam'\]"):
        apply_overrides(cfg, ["ddpg.gamam=0.9"])
    with pytest.raises(ValueError, match="demo_fn"):
        TrainConfig(demo_steps=10, demo_fn=None)
    with pytest.raises(FileNotFoundError):
        load_config(tmp_path / "missing.json")


def test_behaviour_cloning_term_pulls_the_actor_to_the_demonstrations() -> None:
    torch.manual_seed(0)
    cfg = DDPGConfig(actor_hidden=(32,), critic_hidden=(32,), bc_weight=10.0, actor_lr=1e-3)
    agent = DDPG(4, 2, cfg)
    demo = Batch(torch.randn(16, 4), torch.full((16, 2), 0.8), torch.zeros(16), torch.randn(16, 4), torch.zeros(16))
    before = float(((agent.actor(demo.obs) - demo.act) ** 2).mean().detach())
    for _ in range(200):
        agent.update(_batch(), demo)
    after = float(((agent.actor(demo.obs) - demo.act) ** 2).mean().detach())
    assert after < 0.1 * before


def test_actor_step_does_not_touch_the_critic() -> None:
    """The actor step freezes the critic (no weight gradients) and unfreezes it afterwards."""
    torch.manual_seed(0)
    agent = DDPG(4, 2, DDPGConfig(actor_hidden=(8,), critic_hidden=(8,)))
    b = _batch()
    crit = agent.critic_loss(b)
    crit.backward()
    expected = [p.grad.clone() for p in agent.critic.parameters()]
    torch.manual_seed(0)
    agent2 = DDPG(4, 2, DDPGConfig(actor_hidden=(8,), critic_hidden=(8,)))
    agent2.update(b)  # critic grads left by update() must be the critic loss's alone
    for p, g in zip(agent2.critic.parameters(), expected):
        assert p.requires_grad
        torch.testing.assert_close(p.grad, g)


def test_bf16_autocast_update_tracks_float32() -> None:
    losses = {}
    for bf16 in (False, True):
        torch.manual_seed(0)
        agent = DDPG(4, 2, DDPGConfig(actor_hidden=(32, 32), critic_hidden=(32, 32)), autocast_bf16=bf16)
        for _ in range(20):
            agent.update(_batch())
        losses[bf16] = list(agent.read_losses().values())
    assert np.allclose(losses[True], losses[False], rtol=0.05, atol=1e-3), losses


@pytest.mark.slow
def test_compiled_update_matches_eager() -> None:
    """``compile=True`` runs the same maths (float32, up to kernel rounding)."""
    states = []
    for compiled in (False, True):
        torch.manual_seed(0)
        agent = DDPG(4, 2, DDPGConfig(actor_hidden=(16,), critic_hidden=(16,)), compile=compiled)
        for _ in range(5):
            agent.update(_batch())
        states.append(agent.actor.state_dict())
    for k in states[0]:
        torch.testing.assert_close(states[1][k], states[0][k], rtol=1e-4, atol=1e-5)


def test_lean_adam_is_bit_identical_to_fused_adam_and_resumes() -> None:
    import copy as _copy
    import io

    from train.offpolicy.agent import LeanAdam, adam

    torch.manual_seed(0)
    net = torch.nn.Sequential(torch.nn.Linear(5, 7), torch.nn.LayerNorm(7), torch.nn.ReLU(), torch.nn.Linear(7, 1))
    net2 = _copy.deepcopy(net)
    ref, lean = adam(net.parameters(), 1e-3, 1e-2), LeanAdam(net2.parameters(), 1e-3, 1e-2)
    for i in range(12):
        x = torch.randn(16, 5)
        for n, o in ((net, ref), (net2, lean)):
            o.zero_grad(set_to_none=True)
            n(x).pow(2).mean().backward()
            o.step()
        if i == 5:  # a checkpoint round trip in the middle (same format as torch's Adam)
            buf = io.BytesIO()
            torch.save(lean.state_dict(), buf)
            buf.seek(0)
            lean.load_state_dict(torch.load(buf, weights_only=True))
            assert lean.state_dict()["param_groups"] == ref.state_dict()["param_groups"]
    for a, b in zip(net.parameters(), net2.parameters()):
        assert torch.equal(a, b)
    assert float(lean.state_dict()["state"][0]["step"]) == 12.0
