"""The receive under pressure (spec receive/v3): the state with the opponent nearest the
ball's path, the task's interceptors and its "intercepted" failure, a v3 actor in the
registry, and evaluation / selection under the task options an actor was trained with."""

import dataclasses
import math

import numpy as np
import pytest
import torch
from gymnasium.utils.env_checker import check_env

import ssl_marl  # noqa: F401  (registers the ids)
from ssl_marl.physics import BallParams, FieldGeometry, RobotParams
from ssl_marl.physics.state import make_team_state
from ssl_marl.skills import make_skill
from ssl_marl.skills.checkpoint import save_actor
from ssl_marl.skills.networks import Actor
from ssl_marl.skills.pass_tasks import skill_task_action
from ssl_marl.skills.passing import LearnedReceive, ReceiveBaseline
from ssl_marl.skills.passing_features import (RECEIVE_PRESS_GATE_M, RECEIVE_PRESSED_NAMES, RECEIVE_SPEC_PRESSED,
                                              path_threat, receive_features, receive_press_active,
                                              receive_pressed_features)
from ssl_marl.skills.receive_task import ReceiveEnv, first_reach
from ssl_marl.skills.registry import get_task

FIELD, RP, BP = FieldGeometry.from_name("div_b"), RobotParams(), BallParams()
PRESSED = {"interceptors": 1, "hold_s": 0.1}


def _world(opponents):
    """A blue-frame world: blue robot 0 at (1, 0) facing -x, the ball at (-2, 0) rolling
    towards it at 3 m/s, yellow robots at ``opponents`` (list of (x, y)), at rest."""
    env = ReceiveEnv()
    env.reset(seed=0, options={"robot_pose": (1.0, 0.0, math.pi), "ball_pos": (-2.0, 0.0), "ball_vel": (3.0, 0.0)})
    w = env.seen()
    n = len(opponents)
    yellow = make_team_state(np.asarray(opponents, float).reshape(n, 2), np.zeros(n), np.zeros((n, 2)), np.zeros(n),
                             np.zeros(n, bool), np.zeros(n, bool))
    return dataclasses.replace(w, yellow=yellow)


def test_pressed_features_name_the_opponent_nearest_the_ball_path():
    w = _world([(4.0, 0.0), (-0.5, 0.8), (-1.0, -2.5)])
    assert path_threat(w, 0) == 1  # 0.8 m off the segment, the others further
    f = receive_pressed_features(w, 0, RP, BP)
    assert f.shape == (len(RECEIVE_PRESSED_NAMES),) == (18,)
    assert np.array_equal(f[:11], receive_features(w, 0, RP, BP))
    # robot frame of a robot at (1, 0) facing -x: the opponent at (-0.5, 0.8) is 1.5 ahead, 0.8 to the right
    assert f[11:13] == pytest.approx([1.5, -0.8], abs=1e-5)
    reach = RP.front_distance + BP.radius
    assert f[15] == pytest.approx(0.8, abs=1e-5) and f[16] == pytest.approx(1.5 - reach, abs=1e-5)
    assert f[17] == 1.0
    alone = receive_pressed_features(_world([]), 0, RP, BP)
    assert path_threat(_world([]), 0) is None and np.array_equal(alone[11:], np.zeros(7, np.float32))


def test_pressed_env_passes_the_checker_and_is_seeded():
    env = ReceiveEnv(action_form="pressed", reward_form="outcome", **PRESSED)
    check_env(env, skip_render_check=True)
    a, _ = env.reset(seed=11)
    b, _ = ReceiveEnv(action_form="pressed", **PRESSED).reset(seed=11)
    assert a.shape == (18,) and np.array_equal(a, b) and a[17] == 1.0


def test_interceptors_start_where_the_receiver_meets_the_path_first_and_can_win_the_ball():
    env = ReceiveEnv(**PRESSED)
    base = ReceiveBaseline(env.field, env.robot_params, env.ball_params)
    outcomes = []
    for ep in range(40):
        env.reset(seed=300 + ep)
        w = env.truth()
        mine = first_reach(w.blue.pos[0], w.ball_pos, w.ball_vel, RP, BP, env.field)
        theirs = first_reach(w.yellow.pos[0], w.ball_pos, w.ball_vel, RP, BP, env.field, margin_s=0.0,
                             max_closing=math.inf)
        assert math.isfinite(mine) and theirs > mine
        base.reset()
        while True:
            _, _, term, trunc, info = env.step(skill_task_action("receive", env, base))
            if term or trunc:
                break
        outcomes.append("success" if info["is_success"] else info["failure_reason"])
    assert "success" in outcomes and "intercepted" in outcomes  # a contest, not a formality


def test_interceptors_are_placed_for_a_given_scene():
    env = ReceiveEnv(**PRESSED)
    scene = {"robot_pose": (1.0, 0.0, math.pi), "ball_pos": (-2.0, 0.0), "ball_vel": (3.0, 0.0)}
    env.reset(seed=2, options=scene)
    w = env.truth()
    mine = first_reach(w.blue.pos[0], w.ball_pos, w.ball_vel, RP, BP, env.field)
    assert first_reach(w.yellow.pos[0], w.ball_pos, w.ball_vel, RP, BP, env.field, margin_s=0.0,
                       max_closing=math.inf) > mine
    assert -2.0 < w.yellow.pos[0][0] < 1.0  # beside the segment from the ball to the robot


def test_bad_interceptor_options_raise():
    for bad in (-1, 5, 1.0, "1"):
        with pytest.raises(ValueError, match="interceptors"):
            ReceiveEnv(interceptors=bad)
    with pytest.raises(ValueError, match="interceptor_offset"):
        ReceiveEnv(interceptors=1, interceptor_offset=(2.0, 1.0))
    with pytest.raises(ValueError, match="interceptor_lead_m"):
        ReceiveEnv(interceptors=1, interceptor_lead_m=float("nan"))


def test_a_v3_actor_reads_18_values_and_zero_is_the_hand_coded_receive(tmp_path):
    t = get_task("receive")
    assert t.names_of("pressed")[0] == RECEIVE_PRESSED_NAMES
    actor = Actor(18, 3, (16, 16))
    with torch.no_grad():
        actor.head.weight.zero_()
        actor.head.bias.zero_()
    path = save_actor(tmp_path / "pressed.pt", actor, {"skill": "receive", "obs_spec": RECEIVE_SPEC_PRESSED})
    skill = make_skill("receive", "learned", FIELD, RP, BP, checkpoint=path)
    assert isinstance(skill, LearnedReceive) and skill.action_form == "pressed"
    env = ReceiveEnv(**PRESSED)
    env.reset(seed=5)
    assert np.allclose(skill.act(env.seen(), 0), ReceiveBaseline(FIELD, RP, BP).act(env.seen(), 0), atol=1e-6)
    with pytest.raises(ValueError, match="residual receive action"):
        t.to_env_action(np.zeros(3), "pressed")


def test_task_options_reach_the_evaluation_and_bad_ones_are_named():
    from ssl_marl.runners.skill_eval import check_task_options, evaluate_skill

    s = evaluate_skill("receive", "baseline", episodes=4, seed=7, progress=False, task_options=PRESSED)
    assert s["config"]["interceptors"] == 1 and s["config"]["hold_s"] == 0.1
    with pytest.raises(ValueError, match="field"):
        check_task_options("receive", {"field": "div_a"})
    with pytest.raises(ValueError, match="bogus"):
        check_task_options("receive", {"bogus": 1})


def test_eval_skill_cli_parses_task_options():
    from ssl_marl.cli import build_parser

    args = build_parser().parse_args(["eval-skill", "receive", "--task-option", "interceptors=1",
                                      "--task-option", "hold_s=0.1"])
    assert dict(args.task_option) == PRESSED
    with pytest.raises(SystemExit):
        build_parser().parse_args(["eval-skill", "receive", "--task-option", "interceptors"])


def test_selection_validates_under_the_training_task_options():
    from train.tools.select import training_task_options, training_variants

    meta = {"hyperparameters": {"env_kwargs": {"action_form": "pressed", "reward_form": "outcome", "field": "div_b",
                                               "interceptors": 1, "hold_s": 0.1}}}
    assert training_task_options(meta) == PRESSED and training_task_options({}) == {}
    assert training_variants(meta) == [("div_b", "div_b", PRESSED)]
    meta["hyperparameters"]["env_variants"] = [PRESSED, {"interceptors": 0, "hold_s": 0.5}]
    assert training_variants(meta) == [("div_b hold_s=0.1 interceptors=1", "div_b", PRESSED),
                                       ("div_b hold_s=0.5 interceptors=0", "div_b", {"interceptors": 0, "hold_s": 0.5})]
    both = {"hyperparameters": {"env_kwargs": {"field": "div_b"}, "env_variants": [{"field": "div_a"}, {}]}}
    assert training_variants(both) == [("div_a", "div_a", {}), ("div_b", "div_b", {})]  # fields alone: as before


def test_the_pressed_correction_applies_only_under_press():
    w = _world([(-0.5, 0.8)])
    f = receive_pressed_features(w, 0, RP, BP)
    assert receive_press_active(f)
    for idx, value in ((17, 0.0), (10, 1.0), (15, RECEIVE_PRESS_GATE_M + 0.1), (16, f[8]), (16, f[8] + 1.5)):
        g = f.copy()
        g[idx] = value  # no opponent / ball controlled / far off the line / beside the robot / behind it
        assert not receive_press_active(g)
    assert not receive_press_active(receive_pressed_features(_world([]), 0, RP, BP))


def test_a_v3_actor_is_the_hand_coded_receive_outside_the_press(tmp_path):
    actor = Actor(18, 3, (16, 16))
    with torch.no_grad():
        actor.head.bias.fill_(1.0)  # a large correction everywhere
    path = save_actor(tmp_path / "pressed.pt", actor, {"skill": "receive", "obs_spec": RECEIVE_SPEC_PRESSED})
    skill = make_skill("receive", "learned", FIELD, RP, BP, checkpoint=path)
    base = ReceiveBaseline(FIELD, RP, BP)
    plain = _world([])
    assert np.array_equal(skill.act(plain, 0), base.act(plain, 0))
    pressed = _world([(-0.5, 0.8)])
    assert not np.allclose(skill.act(pressed, 0), base.act(pressed, 0))
    env = ReceiveEnv(action_form="pressed")  # the task env gates the same way: no opponent, no correction
    direct = ReceiveEnv()
    o, _ = env.reset(seed=3)
    direct.reset(seed=3)
    for _ in range(30):
        _, _, term, trunc, _ = env.step(np.ones(3, np.float32))
        _, _, term_d, trunc_d, _ = direct.step(base.act(direct.seen(), 0)[:3])
        assert np.array_equal(env.truth().blue.pos, direct.truth().blue.pos)
        if term or trunc:
            break
