"""The redirect's aim action form (spec redirect/v3): the actor picks the aim point along
the goal mouth, the hand-coded contact planner executes it. Mapping (0, limits, NaN /
inf), the task env's spaces and bounds, the hand-coded aims driven through it, the
registry, a checkpoint of the form, the shipped actor and the trainer config."""

import math
from pathlib import Path

import numpy as np
import pytest
import torch

import ssl_marl  # noqa: F401  (registers the ids)
from ssl_marl.physics import BallParams, FieldGeometry, RobotParams
from ssl_marl.skills import make_skill
from ssl_marl.skills.checkpoint import save_actor
from ssl_marl.skills.networks import Actor
from ssl_marl.skills.redirect import (REDIRECT_AIM_NAMES, REDIRECT_AIM_POST_MARGIN, REDIRECT_SPEC_AIM, LearnedRedirect,
                                      RedirectBaseline, redirect_aim_features, redirect_aim_of, redirect_aim_point)
from ssl_marl.skills.redirect_task import (RedirectEnv, redirect_baseline_all_demos, redirect_baseline_demos,
                                           redirect_skill_action)
from ssl_marl.skills.registry import get_skill, get_task

FIELD, RP, BP = FieldGeometry.from_name("div_b"), RobotParams(kick_on_contact=True), BallParams()
HALF = FIELD.goal_width / 2.0 - REDIRECT_AIM_POST_MARGIN
REPO = Path(__file__).resolve().parents[1]


def _scene(deflection: float = 0.7) -> dict:
    """A 3.5 m/s pass from 3 m at ``deflection`` to a robot at (1.5, 0.5) facing the goal."""
    robot = np.array([1.5, 0.5])
    to_goal = math.atan2(-robot[1], FIELD.half_length - robot[0])
    ball = robot + 3.0 * np.array([math.cos(to_goal + deflection), math.sin(to_goal + deflection)])
    return {"robot_pose": (*robot, to_goal), "ball_pos": tuple(ball), "ball_vel": tuple(3.5 * (robot - ball) / 3.0)}


def test_aim_mapping_zero_limits_and_bad_values():
    assert np.array_equal(redirect_aim_point(np.zeros(1), FIELD), [FIELD.half_length, 0.0])
    assert redirect_aim_point(np.ones(1), FIELD)[1] == pytest.approx(HALF)
    assert redirect_aim_point(-np.ones(1), FIELD)[1] == pytest.approx(-HALF)
    assert redirect_aim_point(np.array([7.0]), FIELD)[1] == pytest.approx(HALF)  # clipped to the limit
    for bad in (np.nan, np.inf, -np.inf):
        with pytest.raises(ValueError, match="NaN or inf"):
            redirect_aim_point(np.array([bad]), FIELD)
    for a in (-1.0, -0.3, 0.0, 0.55, 1.0):  # inverse
        assert redirect_aim_of(redirect_aim_point(np.array([a]), FIELD), FIELD) == pytest.approx([a], abs=1e-6)
    assert np.array_equal(redirect_aim_of(None, FIELD), np.zeros(1, np.float32))
    assert redirect_aim_of(np.array([FIELD.half_length, 3.0]), FIELD) == pytest.approx([1.0])


def test_aim_env_spaces_bounds_and_bad_actions():
    env = RedirectEnv(action_form="aim")
    assert env.spec_version == REDIRECT_SPEC_AIM
    assert env.observation_space.shape == (len(REDIRECT_AIM_NAMES),) == (21,) and env.action_space.shape == (1,)
    space = env.observation_space
    assert np.all(space.low < space.high)
    obs, _ = env.reset(seed=2)
    rng = np.random.default_rng(0)
    for _ in range(200):
        assert space.contains(obs), obs
        obs, r, term, trunc, info = env.step(rng.uniform(-1, 1, 1))
        if term or trunc:
            break
    assert r == (1.0 if info["is_success"] else -1.0) or info["failure_reason"] == "timeout"
    env.reset(seed=0)
    with pytest.raises(ValueError, match="NaN"):
        env.step(np.array([np.nan]))
    with pytest.raises(ValueError, match="shape"):
        env.step(np.zeros(3))
    with pytest.raises(ValueError, match="aim action"):
        env.from_direct(np.zeros(3))


def test_features_extend_the_v1_state_with_team_frame_values():
    env = RedirectEnv(action_form="aim")
    env.reset(seed=5)
    w = env.seen()
    f = redirect_aim_features(w, 0, env.field, env.robot_params, env.ball_params)
    assert f.shape == (21,) and f.dtype == np.float32
    assert np.allclose(f[14:16], w.blue.pos[0]) and np.allclose(f[16:18], w.yellow.pos[0])
    assert np.allclose(f[18:20], w.yellow.vel[0]) and abs(f[20]) <= HALF + 1e-6


@pytest.mark.parametrize("deflection", [0.3, 1.1])
def test_hand_coded_aims_through_the_aim_env_score_without_a_goalie(deflection):
    env = RedirectEnv(action_form="aim", goalie=None)
    skill = RedirectBaseline(env.field, env.robot_params, env.ball_params)
    env.reset(seed=0, options=_scene(deflection))
    skill.reset()
    actions = []
    while True:
        a = redirect_skill_action(env, skill)
        actions.append(a)
        _, _, term, trunc, info = env.step(a)
        if term or trunc:
            break
    assert info["is_success"], info
    assert all(a.shape == (1,) and -1.0 <= a[0] <= 1.0 for a in actions)
    rows = list(redirect_baseline_demos(30, seed=1, action_form="aim"))
    assert all(r.obs.shape == (21,) and r.action.shape == (1,) for r in rows)
    rows = list(redirect_baseline_all_demos(400, seed=1, action_form="aim"))  # failures kept
    ends = [r.reward for r in rows if r.terminated or r.truncated]
    assert len(rows) == 400 and ends and set(ends) <= {-1.0, 1.0} and -1.0 in ends


def test_registry_and_a_checkpoint_of_the_aim_form(tmp_path):
    t = get_task("redirect")
    assert t.spec_versions["aim"] == REDIRECT_SPEC_AIM and t.default_mapping == "direct"
    assert t.names_of("aim") == (REDIRECT_AIM_NAMES, ("aim_y",)) and len(t.names_of()[0]) == 14
    with pytest.raises(ValueError, match="aim action"):
        t.to_env_action(np.zeros(1), "aim")
    actor = Actor(21, 1, (16, 16))
    with torch.no_grad():  # a zero head: aim at the goal centre
        actor.head.weight.zero_()
        actor.head.bias.zero_()
    path = save_actor(tmp_path / "aim.pt", actor, {"skill": "redirect", "obs_spec": REDIRECT_SPEC_AIM})
    skill = make_skill("redirect", "learned", FIELD, RP, BP, checkpoint=path)
    assert isinstance(skill, LearnedRedirect) and skill.action_form == "aim"
    env = RedirectEnv()
    env.reset(seed=1, options=_scene())
    a = skill.act(env.seen(), 0)
    assert a.shape == (5,) and np.isfinite(a).all()
    assert np.array_equal(skill.aim_action(), np.zeros(1, np.float32))
    base = RedirectBaseline(FIELD, RP, BP)
    base.aim = np.array([FIELD.half_length, 0.0])
    assert np.allclose(a, base.act(env.seen(), 0))  # the planner with the same aim point
    with pytest.raises(ValueError, match="no aim point"):
        LearnedRedirect(FIELD, RP, BP, policy=lambda o: np.zeros(3, np.float32), action_form="residual").aim_action()


def test_the_shipped_actor_loads_and_acts_in_the_task():
    actor = get_skill("redirect").actor
    if actor is None:
        pytest.skip("no learned redirect is shipped")
    assert torch.load(actor, weights_only=True)["metadata"]["obs_spec"] == REDIRECT_SPEC_AIM
    env = RedirectEnv()
    skill = make_skill("redirect", "learned", env.field, env.robot_params, env.ball_params)
    assert isinstance(skill, LearnedRedirect) and skill.action_form == "aim"
    env.reset(seed=0, options=_scene())
    skill.reset()
    for _ in range(400):
        _, _, term, trunc, info = env.step(redirect_skill_action(env, skill))
        if term or trunc:
            break
    assert term or trunc
    assert info["failure_reason"] in (None, "saved", "missed")  # it touched the ball


def test_the_trainer_config_loads():
    from train.offpolicy.config import load_config

    cfg = load_config(REPO / "train" / "configs" / "redirect.json")
    assert cfg.skill == "redirect" and cfg.env_kwargs == {"action_form": "aim"}
    assert cfg.bc_anneal_samples >= cfg.total_samples and cfg.ddpg.bc_weight > 0
    assert cfg.checkpoint_interval == 1000 and cfg.demo_fn.endswith(":redirect_baseline_all_demos")
    assert [v.get("realism") for v in cfg.env_variants] == ["none", "realistic"] and cfg.num_envs == 2
