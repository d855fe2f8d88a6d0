"""Learned skills: the numpy actor, the skill protocol, checkpoint checks, shipped actors."""

import numpy as np
import pytest
import torch

from ssl_marl.physics import FieldGeometry
from ssl_marl.physics.state import TeamState, WorldState, make_team_state, to_team_frame
from ssl_marl.skills import SkillStatus, make_skill
from ssl_marl.skills.checkpoint import save_actor
from ssl_marl.skills.features import AIM_TO_SHOOT_SPEC, GO_TO_BALL_SPEC
from ssl_marl.skills.learned import LearnedAimToShoot, LearnedGoToBall, NumpyActor, load_policy
from ssl_marl.skills.networks import Actor
from ssl_marl.skills.registry import get_skill

F = FieldGeometry.div_b()


def tiny_checkpoint(path, skill="go_to_ball", spec=GO_TO_BALL_SPEC, obs_dim=14, hidden=(16, 8)):
    torch.manual_seed(0)
    actor = Actor(obs_dim, 3, hidden)
    save_actor(path, actor, {"skill": skill, "obs_spec": spec})
    return actor


def scene(on_dribbler=False):
    ts = make_team_state([[0.0, 0.0]], [0.0], [[0.0, 0.0]], [0.0], [on_dribbler], [True])
    return to_team_frame(WorldState(t=0.0, ball_pos=np.array([0.1015, 0.0]), ball_vel=np.zeros(2), blue=ts,
                                    yellow=TeamState.empty()), "blue")


def test_numpy_actor_matches_torch(tmp_path):
    actor = tiny_checkpoint(tmp_path / "a.pt", hidden=(300, 400))
    x = np.random.default_rng(0).normal(size=(64, 14)).astype(np.float32)
    np.testing.assert_allclose(NumpyActor(actor)(x), actor.act(x), atol=1e-5)


def test_learned_skills_follow_the_protocol(tmp_path):
    tiny_checkpoint(tmp_path / "g.pt")
    tiny_checkpoint(tmp_path / "a.pt", "aim_to_shoot", AIM_TO_SHOOT_SPEC, obs_dim=10)
    g = make_skill("go_to_ball", "learned", F, checkpoint=tmp_path / "g.pt")
    assert isinstance(g, LearnedGoToBall)
    a = g.act(scene(), 0)
    assert a.shape == (5,) and np.all(np.abs(a) <= 1) and g.status == SkillStatus.RUNNING
    g.act(scene(on_dribbler=True), 0)
    assert g.status == SkillStatus.SUCCEEDED
    s = make_skill("aim_to_shoot", "learned", F, checkpoint=tmp_path / "a.pt")
    assert isinstance(s, LearnedAimToShoot)
    a = s.act(scene(on_dribbler=True), 0)
    assert a.shape == (5,) and a[0] == 0 and a[1] == 0  # aim-to-shoot never translates


def test_mismatched_and_corrupt_checkpoints_raise(tmp_path):
    tiny_checkpoint(tmp_path / "g.pt")
    with pytest.raises(ValueError, match="aim_to_shoot"):
        load_policy("aim_to_shoot", tmp_path / "g.pt")
    (tmp_path / "bad.pt").write_bytes(b"not a checkpoint at all")
    with pytest.raises(ValueError, match="not a valid"):
        load_policy("go_to_ball", tmp_path / "bad.pt")
    with pytest.raises(FileNotFoundError):
        load_policy("go_to_ball", tmp_path / "missing.pt")
    with pytest.raises(ValueError, match="unknown learned skill"):
        load_policy("juggle")


def _success(task, policy, episodes=50, seed=777):
    from ssl_marl.runners.skill_eval import evaluate_skill

    return evaluate_skill(task, policy, episodes=episodes, seed=seed, workers=1, progress=False)


def test_shipped_go_to_ball_reaches_95_percent():
    assert get_skill("go_to_ball").actor.exists(), "shipped actor missing"
    s = _success("go-to-ball", "learned")
    assert s["success_rate"] >= 0.95, s["failure_reasons"]


def test_shipped_aim_to_shoot_beats_the_baseline():
    assert get_skill("aim_to_shoot").actor.exists(), "shipped actor missing"
    learned, base = _success("aim-to-shoot", "learned", 100), _success("aim-to-shoot", "baseline", 100)
    assert learned["success_rate"] > base["success_rate"], (learned["failure_reasons"], base["failure_reasons"])


def test_shipped_aim_to_shoot_reaches_95_percent():
    s = _success("aim-to-shoot", "learned")
    assert s["success_rate"] >= 0.95, s["failure_reasons"]


def test_learned_aim_to_shoot_gives_up_after_its_training_horizon():
    from dataclasses import replace

    never_kicks = lambda obs: np.array([0.2, 1.0, -1.0], np.float32)  # noqa: E731
    s = LearnedAimToShoot(F, policy=never_kicks)
    ws = scene(on_dribbler=True)
    s.act(ws, 0)
    assert s.status == SkillStatus.RUNNING
    s.act(replace(ws, t=1.5), 0)
    assert s.status == SkillStatus.RUNNING
    s.act(replace(ws, t=1.7), 0)
    assert s.status == SkillStatus.FAILED


def test_learned_aim_to_shoot_kicks_as_it_was_trained(tmp_path):
    """The checkpoint's spec picks the kick mapping: v1 = strength a_k, v2 = full strength."""
    from ssl_marl.skills.features import AIM_TO_SHOOT_SPECS

    weak_kick = lambda obs: np.array([0.0, 1.0, 0.1], np.float32)  # noqa: E731
    assert LearnedAimToShoot(F, policy=weak_kick).act(scene(on_dribbler=True), 0)[4] == pytest.approx(0.1)
    assert LearnedAimToShoot(F, policy=weak_kick, kick_action="full").act(scene(on_dribbler=True), 0)[4] == 1.0
    for kick_action, spec in AIM_TO_SHOOT_SPECS.items():
        tiny_checkpoint(tmp_path / f"{kick_action}.pt", "aim_to_shoot", spec, obs_dim=10)
        assert LearnedAimToShoot(F, checkpoint=tmp_path / f"{kick_action}.pt").kick_action == kick_action
    tiny_checkpoint(tmp_path / "v9.pt", "aim_to_shoot", "aim_to_shoot/v9", obs_dim=10)
    with pytest.raises(ValueError, match="spec mismatch"):
        LearnedAimToShoot(F, checkpoint=tmp_path / "v9.pt")
