"""Pass and receive skills: tasks, hand-coded baselines, features, drill, errors."""

import math

import gymnasium
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import ssl_marl  # noqa: F401  (registers the ids)
from ssl_marl.physics import BallParams, FieldGeometry, RobotParams
from ssl_marl.physics import ball_model as bm
from ssl_marl.skills import SkillStatus, make_skill
from ssl_marl.skills.pass_tasks import (PassEnv, make_task_env, pass_baseline_demos, receive_baseline_demos,
                                        skill_task_action)
from ssl_marl.skills.passing import LearnedPass, LearnedReceive, PassBaseline, ReceiveBaseline
from ssl_marl.skills.receive_task import ReceiveEnv, receive_feasible
from ssl_marl.skills.passing_features import (PASS_NAMES, RECEIVE_NAMES, expand_pass_action, pass_features,
                                              pass_kick_speed, pass_task_action, receive_features)

FIELD, RP, BP = FieldGeometry.from_name("div_b"), RobotParams(), BallParams()


def _run(task, env, skill, options=None, seed=0):
    env.reset(seed=seed, options=options)
    skill.reset()
    while True:
        _, _, term, trunc, info = env.step(skill_task_action(task, env, skill))
        if term or trunc:
            return info


@pytest.mark.parametrize("env_id", ["ssl_marl/Pass-v0", "ssl_marl/Receive-v0"])
def test_tasks_pass_the_gymnasium_checker_and_are_deterministic(env_id):
    env = gymnasium.make(env_id)
    check_env(env.unwrapped, skip_render_check=True)
    o1, _ = env.reset(seed=3)
    a = env.action_space.sample()
    s1 = env.step(a)[0]
    o2, _ = env.reset(seed=3)
    s2 = env.step(a)[0]
    assert np.array_equal(o1, o2) and np.array_equal(s1, s2)
    assert env.observation_space.shape == ((len(PASS_NAMES),) if "Pass" in env_id else (len(RECEIVE_NAMES),))


def test_a_pass_between_two_baseline_robots_on_an_empty_field_completes():
    env = PassEnv()
    skill = make_skill("pass", "baseline", env.field, env.robot_params, env.ball_params)
    assert isinstance(skill, PassBaseline)
    info = _run("pass", env, skill, {"passer_pose": (-2.0, 0.0, 2.5), "target": (1.5, -1.0), "receiver_vel": (0, 0)})
    assert info["is_success"], info
    d = math.hypot(3.5, 1.0) - RP.front_distance - BP.radius
    assert info["kick_speed"] == pytest.approx(bm.kick_speed_for_arrival(d, 1.5, BP), abs=0.05)
    assert 1.0 < bm.speed_at_distance(info["kick_speed"], d, BP) < 2.0  # arrives at 1-2 m/s


def test_the_pass_leads_a_moving_receiver():
    env = PassEnv()
    skill = PassBaseline(env.field, env.robot_params, env.ball_params)
    info = _run("pass", env, skill, {"passer_pose": (-2.0, -1.0, 0.0), "target": (1.0, -1.5), "receiver_vel": (0, 0.4)})
    assert info["is_success"], info


def test_baselines_succeed_on_most_random_spawns():
    for task, n_ok in (("pass", 9), ("receive", 9)):
        env = make_task_env(task)
        skill = make_skill(task, "baseline", env.field, env.robot_params, env.ball_params)
        ok = sum(_run(task, env, skill, seed=100 + i)["is_success"] for i in range(10))
        assert ok >= n_ok, (task, ok)


def test_receive_cushions_a_fast_ball_and_holds_it():
    env = ReceiveEnv()
    skill = make_skill("receive", "baseline", env.field, env.robot_params, env.ball_params)
    assert isinstance(skill, ReceiveBaseline)
    env.reset(seed=0, options={"robot_pose": (2.0, 0.0, math.pi), "ball_pos": (-2.0, 0.5),
                               "ball_vel": (4.0, -0.5)})
    skill.reset()
    contact_closing = None
    while True:
        truth = env.truth()
        rel = float(np.hypot(*(truth.ball_vel - truth.blue.vel[0])))
        _, _, term, trunc, info = env.step(skill_task_action("receive", env, skill))
        if contact_closing is None and env.truth().blue.ball_on_dribbler[0]:
            contact_closing = rel
        if term or trunc:
            break
    assert info["is_success"], info
    assert contact_closing is not None and contact_closing < 1.5  # a standing robot would meet it at ~3.5 m/s
    assert skill.status == SkillStatus.SUCCEEDED or info["held_s"] >= 0.5 - 1e-9


def test_receive_feasibility_rejects_impossible_balls():
    robot = np.array([0.0, 0.0])
    # 6 m/s from 2 m, passing 0.8 m to the side: no robot gets there in time
    assert not receive_feasible(robot, np.array([-2.0, 0.8]), np.array([6.0, 0.0]), RP, BP, FIELD)
    assert receive_feasible(robot, np.array([-3.0, 0.3]), np.array([2.5, 0.0]), RP, BP, FIELD)


def test_features_of_a_constructed_scene():
    env = PassEnv()
    env.reset(seed=0, options={"passer_pose": (0.0, 0.0, 0.0), "target": (3.0, 0.0), "receiver_vel": (0, 0)})
    f = pass_features(env.seen(), 0, np.array([3.0, 0.0]))
    assert f[0] == pytest.approx(3.0, abs=1e-6) and f[1] == pytest.approx(0.0, abs=1e-6)
    assert f[4] == pytest.approx(3.0 - RP.front_distance - BP.radius, abs=1e-3)
    assert (f[5], f[6]) == pytest.approx((0.0, 1.0), abs=1e-6)
    assert f[7] == pytest.approx(RP.front_distance + BP.radius, abs=2e-3)
    r_env = ReceiveEnv()
    r_env.reset(seed=0, options={"robot_pose": (1.0, 0.3, math.pi), "ball_pos": (-2.0, 0.0), "ball_vel": (3.0, 0.0)})
    g = receive_features(r_env.seen(), 0, RP, BP)
    assert g[7] == pytest.approx(0.3, abs=1e-6)  # robot 0.3 m left of the ball's line
    assert g[8] == pytest.approx(3.0 - RP.front_distance - BP.radius, abs=1e-6)
    assert g[9] == pytest.approx(3.0, abs=1e-6) and g[10] == 0.0


def test_pass_action_mapping_round_trip():
    for a in ([0.3, 1.0, -0.5], [-1.0, 1.0, 1.0], [0.0, 1.0, 0.2]):
        full = expand_pass_action(np.array(a), RP)
        assert full[4] * RP.kick_speed_max == pytest.approx(pass_kick_speed(a[2], RP))
        assert pass_task_action(full, RP) == pytest.approx(np.array(a, np.float32), abs=1e-5)
    assert expand_pass_action(np.array([0.0, -0.2, 1.0]), RP)[4] == -1.0  # no kick


def test_bad_inputs_raise_clear_errors():
    skill = PassBaseline(FIELD)
    with pytest.raises(ValueError, match="pass target .* outside"):
        skill.set_target((7.0, 0.0))
    with pytest.raises(ValueError, match="pass target"):
        skill.set_target((float("nan"), 0.0))
    env = PassEnv()
    with pytest.raises(ValueError, match="no pass target"):
        env.reset(seed=0)
        skill.act(env.seen(), 0)
    with pytest.raises(ValueError, match="pass target .* outside"):
        env.reset(seed=0, options={"target": (0.0, 3.5)})
    r_env = ReceiveEnv()
    with pytest.raises(ValueError, match="ball_vel .* moving ball"):
        r_env.reset(seed=0, options={"ball_vel": (0.0, 0.0)})
    with pytest.raises(ValueError, match="unknown option"):
        r_env.reset(seed=0, options={"bal_vel": (1.0, 0.0)})
    with pytest.raises(ValueError, match="action must have shape"):
        env.reset(seed=0)
        env.step(np.zeros(5))
    with pytest.raises(ValueError, match="speed_range"):
        ReceiveEnv(speed_range=(1.0, 9.0))
    with pytest.raises(FileNotFoundError):
        LearnedPass(FIELD, checkpoint="/nonexistent/pass.pt")
    with pytest.raises(FileNotFoundError):
        LearnedReceive(FIELD, checkpoint="/nonexistent/receive.pt")


def test_demonstrations_come_from_successful_baseline_episodes():
    for gen, obs_dim in ((pass_baseline_demos, 10), (receive_baseline_demos, 11)):
        rows = list(gen(60, seed=1))
        assert len(rows) == 60
        assert rows[0].obs.shape == (obs_dim,) and np.asarray(rows[0].action).shape == (3,)
        ends = [r for r in rows if r.terminated]
        assert all(r.info["is_success"] for r in ends)


def test_pass_endurance_drill_completes_passes():
    from ssl_marl.runners.drills import run_pass_endurance

    r = run_pass_endurance("baseline", seed=2, duration_s=12.0)
    assert r["completed"] >= 2
    assert r["completed"] <= r["attempts"] and sum(r["losses"].values()) == r["attempts"] - r["completed"]
    assert 2.0 <= r["home_distance_m"] <= 5.0
    with pytest.raises(ValueError, match="policy"):
        run_pass_endurance("random")


def test_cli_eval_skill_and_eval_drill_write_results(tmp_path, capsys):
    import json

    from ssl_marl.cli import build_parser, main

    assert main(["eval-skill", "pass", "--episodes", "2", "--seed", "1", "--out", str(tmp_path / "p"), "--quiet"]) == 0
    res = json.loads((tmp_path / "p" / "results.json").read_text())
    assert res["skill"] == "pass" and res["episodes"] == 2 and res["paper_success_rate"] is None
    assert main(["eval-drill", "pass-endurance", "--runs", "1", "--duration", "8", "--seed", "1",
                 "--out", str(tmp_path / "d"), "--quiet"]) == 0
    res = json.loads((tmp_path / "d" / "results.json").read_text())
    assert res["drill"] == "pass-endurance" and res["attempts"] >= res["completed"] >= 1
    assert "passes completed" in capsys.readouterr().out
    for argv, needle in ((["eval-drill", "juggle"], "invalid choice"),
                         (["eval-drill", "pass-endurance", "--duration", "-1"], "positive"),
                         (["eval-drill", "pass-endurance", "--policy", "magic"], "invalid choice")):
        with pytest.raises(SystemExit):
            build_parser().parse_args(argv)
        assert needle in capsys.readouterr().err
    with pytest.raises(SystemExit):
        build_parser().parse_args(["eval-drill", "--help"])
    assert "--seed" in capsys.readouterr().out


def test_shipped_learned_pass_completes_a_pass():
    from ssl_marl.skills.passing import load_passing_policy

    _, meta = load_passing_policy("pass")
    assert meta["skill"] == "pass" and meta["obs_spec"] == "pass/v1"
    env = PassEnv()
    skill = make_skill("pass", "learned", env.field, env.robot_params, env.ball_params)
    assert isinstance(skill, LearnedPass)
    info = _run("pass", env, skill, {"passer_pose": (-2.0, 0.0, 2.5), "target": (1.5, -1.0), "receiver_vel": (0, 0)})
    assert info["is_success"], info
    with pytest.raises(ValueError, match="unknown learned skill"):
        load_passing_policy("juggle")
