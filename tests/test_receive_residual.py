"""The residual receive (spec receive/v2): an actor's output corrects the hand-coded
receive's action; zero output is the hand-coded receive. Registry entry, loading,
observation bounds, sparse reward, bad inputs, and the trainer's annealed cloning weight."""

import numpy as np
import pytest
import torch

import ssl_marl  # noqa: F401  (registers the ids)
from ssl_marl.physics import BallParams, FieldGeometry, RobotParams
from ssl_marl.skills import make_skill
from ssl_marl.skills.checkpoint import save_actor
from ssl_marl.skills.networks import Actor
from ssl_marl.skills.pass_tasks import receive_baseline_demos, skill_task_action
from ssl_marl.skills.passing import LearnedReceive, ReceiveBaseline
from ssl_marl.skills.receive_task import ReceiveEnv
from ssl_marl.skills.passing_features import (RECEIVE_RESIDUAL_SCALE, RECEIVE_SPEC, RECEIVE_SPEC_PRESSED,
                                              RECEIVE_SPEC_RESIDUAL,
                                              receive_residual_action, receive_residual_of)
from ssl_marl.skills.registry import get_task

FIELD, RP, BP = FieldGeometry.from_name("div_b"), RobotParams(), BallParams()
SCENE = {"robot_pose": (1.0, 0.3, 3.0), "ball_pos": (-2.0, 0.0), "ball_vel": (3.5, 0.1)}


def _zero(obs):
    return np.zeros(3, np.float32)


def test_a_zero_residual_actor_is_the_hand_coded_receive():
    """Step for step, the learned receive with a zero actor gives the baseline's action,
    and the residual env driven by zeros follows the direct env driven by the baseline."""
    direct, residual = ReceiveEnv(), ReceiveEnv(action_form="residual")
    base = ReceiveBaseline(FIELD, RP, BP)
    learned = LearnedReceive(FIELD, RP, BP, policy=_zero, action_form="residual")
    o_d, _ = direct.reset(seed=4, options=SCENE)
    o_r, _ = residual.reset(seed=4, options=SCENE)
    for _ in range(400):
        a_base = base.act(direct.seen(), 0)
        assert np.array_equal(learned.act(direct.seen(), 0), a_base)
        assert np.array_equal(skill_task_action("receive", residual, base), np.zeros(3, np.float32))
        o_d, _, term, trunc, info = direct.step(a_base[:3])
        o_r, _, term_r, trunc_r, info_r = residual.step(np.zeros(3))
        assert np.array_equal(o_d, o_r)
        if term or trunc:
            break
    assert (term, trunc) == (term_r, trunc_r) and info["is_success"] and info_r["is_success"]
    assert learned.status == base.status


def test_residual_action_is_bounded_and_inverts():
    base = np.array([0.9, -0.2, 0.0])
    assert np.array_equal(receive_residual_action(base, np.zeros(3)), base.astype(np.float32))
    a = receive_residual_action(base, np.array([1.0, 1.0, -5.0]))  # correction clipped, sum clipped
    assert a == pytest.approx([1.0, -0.2 + RECEIVE_RESIDUAL_SCALE, -RECEIVE_RESIDUAL_SCALE])
    c = np.array([-0.4, 0.3, 0.1])
    assert receive_residual_of(base, receive_residual_action(base, c)) == pytest.approx(c, abs=1e-6)


def test_registry_entry_has_the_action_forms(tmp_path):
    t = get_task("receive")
    assert dict(t.spec_versions) == {"direct": RECEIVE_SPEC, "residual": RECEIVE_SPEC_RESIDUAL,
                                     "pressed": RECEIVE_SPEC_PRESSED}
    assert t.default_mapping == "direct" and ReceiveEnv().spec_version == RECEIVE_SPEC
    assert ReceiveEnv(action_form="residual").spec_version == RECEIVE_SPEC_RESIDUAL
    assert t.to_env_action(np.array([0.1, 0.2, 0.3]), "direct").shape == (5,)
    with pytest.raises(ValueError, match="residual receive action"):
        t.to_env_action(np.zeros(3), "residual")
    # a checkpoint's spec picks the form: a v2 actor with a zero head acts as the baseline
    actor = Actor(t.obs_dim, t.act_dim, (16, 16))
    with torch.no_grad():
        actor.head.weight.zero_()
        actor.head.bias.zero_()
    for spec, form in ((RECEIVE_SPEC_RESIDUAL, "residual"), (RECEIVE_SPEC, "direct")):
        path = save_actor(tmp_path / f"{form}.pt", actor, {"skill": "receive", "obs_spec": spec})
        skill = make_skill("receive", "learned", FIELD, RP, BP, checkpoint=path)
        assert isinstance(skill, LearnedReceive) and skill.action_form == form
    env = ReceiveEnv()
    env.reset(seed=1, options=SCENE)
    base = ReceiveBaseline(FIELD, RP, BP)
    assert np.allclose(skill.act(env.seen(), 0)[:3], 0.0)  # direct form: 0 = stand still
    skill = make_skill("receive", "learned", FIELD, RP, BP, checkpoint=tmp_path / "residual.pt")
    assert np.allclose(skill.act(env.seen(), 0), base.act(env.seen(), 0), atol=1e-6)


def test_observations_stay_in_bounds_and_the_outcome_reward_is_sparse():
    env = ReceiveEnv(action_form="residual", reward_form="outcome")
    space = env.observation_space
    assert space.shape == (11,) and np.all(space.low < space.high)
    rng = np.random.default_rng(0)
    outcomes = []
    for ep in range(3):
        obs, _ = env.reset(seed=ep)
        rewards = []
        while True:
            assert space.contains(obs), obs
            obs, r, term, trunc, info = env.step(rng.uniform(-1, 1, 3))
            rewards.append(r)
            assert set(info["reward_terms"]) == {"outcome"}
            if term or trunc:
                break
        assert all(r == 0.0 for r in rewards[:-1]) and rewards[-1] == (1.0 if info["is_success"] else -1.0)
        outcomes.append(info["is_success"])
    rows = list(receive_baseline_demos(50, seed=2, action_form="residual"))
    assert all(np.array_equal(r.action, np.zeros(3, np.float32)) for r in rows)  # demos = zero corrections


def test_bad_action_and_reward_forms_raise():
    with pytest.raises(ValueError, match="action_form"):
        ReceiveEnv(action_form="delta")
    with pytest.raises(ValueError, match="reward_form"):
        ReceiveEnv(reward_form="dense")
    with pytest.raises(ValueError, match="action_form"):
        LearnedReceive(FIELD, policy=_zero, action_form="delta")


def test_trainer_anneals_the_cloning_weight(tmp_path):
    from train.offpolicy.config import apply_overrides, default_config
    from train.offpolicy.loop import Trainer

    cfg = apply_overrides(default_config("pendulum"), ["ddpg.bc_weight=4.0", "bc_anneal_samples=100", "warmup_samples=20",
                                                       "ddpg.actor_hidden=[8]", "ddpg.critic_hidden=[8]"])
    tr = Trainer(cfg, 0, tmp_path, progress=False)
    for samples, weight, on in ((20, 4.0, True), (70, 2.0, True), (120, 0.0, False), (500, 0.0, False)):
        tr.samples = samples
        assert tr.anneal_bc() is on and tr.agent.cfg.bc_weight == pytest.approx(weight)
    assert tr.cfg.ddpg.bc_weight == 4.0  # the saved config keeps the starting weight
    tr.envs.close()
    tr.eval_env.close()


def test_shipped_receive_is_pressed_and_receives():
    from ssl_marl.skills.passing import load_passing_policy
    from ssl_marl.skills.registry import get_skill

    assert get_skill("receive").actor is not None and get_skill("receive").actor.exists()
    _, meta = load_passing_policy("receive")
    assert meta["skill"] == "receive" and meta["obs_spec"] == RECEIVE_SPEC_PRESSED
    env = ReceiveEnv()
    skill = make_skill("receive", "learned", env.field, env.robot_params, env.ball_params)
    assert isinstance(skill, LearnedReceive) and skill.action_form == "pressed"
    env.reset(seed=4, options=SCENE)
    skill.reset()
    while True:
        _, _, term, trunc, info = env.step(skill_task_action("receive", env, skill))
        if term or trunc:
            break
    assert info["is_success"], info
