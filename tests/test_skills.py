"""The paper's skills: features, rewards, terminal conditions, baselines, demos, evaluation."""

import math

import gymnasium
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import ssl_marl  # noqa: F401  (registers the envs)
from ssl_marl.physics import BallParams, FieldGeometry, RobotParams
from ssl_marl.physics.state import TeamState, WorldState, make_team_state, to_team_frame
from ssl_marl.skills import SkillStatus, make_skill
from ssl_marl.skills.baseline import AimToShootBaseline, DriveForward, GoToBallBaseline
from ssl_marl.skills.navigation import MoveToPoint
from ssl_marl.skills.demos import aim_to_shoot_demos, go_to_ball_demos
from ssl_marl.skills.features import (aim_to_shoot_features, aim_to_shoot_reward, dribbler_ball_distance,
                                      go_to_ball_features, go_to_ball_reward)
from ssl_marl.skills.wrappers import AimToShootEnv, GoToBallEnv, task_action

F = FieldGeometry.div_b()
RP, BP = RobotParams(), BallParams()
FACE = RP.front_distance + BP.radius


def scene(robot=(0.0, 0.0, 0.0), ball=(1.0, 0.0), ball_vel=(0.0, 0.0), vel=(0.0, 0.0), omega=0.0,
          on_dribbler=False, team="blue"):
    ts = make_team_state([robot[:2]], [robot[2]], [vel], [omega], [on_dribbler], [True])
    ws = WorldState(t=0.0, ball_pos=np.array(ball, float), ball_vel=np.array(ball_vel, float), blue=ts,
                    yellow=TeamState.empty())
    return to_team_frame(ws, team)


@pytest.mark.parametrize("env_id", ["ssl_marl/GoToBall-v0", "ssl_marl/AimToShoot-v0"])
def test_gymnasium_check_env(env_id):
    check_env(gymnasium.make(env_id).unwrapped, skip_render_check=True)


@pytest.mark.parametrize("env_id", ["ssl_marl/GoToBall-v0", "ssl_marl/AimToShoot-v0"])
def test_vector_envs(env_id):
    for vec in (gymnasium.vector.SyncVectorEnv, gymnasium.vector.AsyncVectorEnv):
        envs = vec([lambda: gymnasium.make(env_id) for _ in range(2)])
        obs, _ = envs.reset(seed=0)
        for _ in range(5):
            obs, r, term, trunc, info = envs.step(envs.action_space.sample())
        assert obs.shape[0] == 2 and np.isfinite(obs).all()
        envs.close()


def test_go_to_ball_features_hand_built():
    f = go_to_ball_features(scene(), 0, F)
    assert f.shape == (14,) and f.dtype == np.float32
    np.testing.assert_allclose(f[0:2], [1.0, 0.0], atol=1e-6)
    assert f[5] == pytest.approx(1.0)
    # closest field-line points (robot at the origin facing +x): top (0, 3), bottom (0, -3), left (-4.5, 0), right (4.5, 0)
    np.testing.assert_allclose(f[6:14], [0, 3, 0, -3, -4.5, 0, 4.5, 0], atol=1e-6)
    # facing +y: the ball at (1, 0) is to the robot's right; velocity in the robot frame
    f = go_to_ball_features(scene(robot=(0, 0, math.pi / 2), vel=(0.0, 1.0), omega=2.0), 0, F)
    np.testing.assert_allclose(f[0:5], [0.0, -1.0, 1.0, 0.0, 2.0], atol=1e-6)


def test_features_identical_in_both_team_frames():
    b = go_to_ball_features(scene(robot=(1.0, 0.5, 0.3), ball=(2.0, -1.0)), 0, F)
    ws = scene(robot=(-1.0, -0.5, 0.3 + math.pi), ball=(-2.0, 1.0), team="yellow")
    # yellow robot 0 in yellow's frame: same scene mirrored
    ts = make_team_state(np.zeros((0, 2)), [], np.zeros((0, 2)), [], [], [])
    yw = WorldState(t=0.0, ball_pos=np.array([-2.0, 1.0]), ball_vel=np.zeros(2), blue=ts,
                    yellow=make_team_state([[-1.0, -0.5]], [0.3 + math.pi], [[0, 0]], [0], [False], [True]))
    y = go_to_ball_features(to_team_frame(yw, "yellow"), 0, F)
    np.testing.assert_allclose(b, y, atol=1e-5)
    assert ws.frame == "yellow"


def test_aim_to_shoot_features_hand_built():
    # robot 2 m in front of the +x goal centre, facing it: posts at +-0.5 m
    ws = scene(robot=(2.5, 0.0, 0.0), ball=(2.5 + FACE, 0.0), ball_vel=(1.0, 0.0))
    f = aim_to_shoot_features(ws, 0, F)
    assert f.shape == (10,)
    np.testing.assert_allclose(f[0:4], [FACE, 0.0, 1.0, 0.0], atol=1e-6)
    assert f[5] == pytest.approx(2.0)
    a = math.atan2(0.5, 2.0)
    np.testing.assert_allclose(f[6:10], [math.sin(a), math.cos(a), -math.sin(a), math.cos(a)], atol=1e-6)


def test_go_to_ball_reward_hand_built():
    r = go_to_ball_reward(scene(ball=(1.0, 0.0)), 0)
    assert r["contact"] == 0.0
    assert r["distance"] == pytest.approx(5 / math.sqrt(2 * math.pi) * math.exp(-0.5) - 2)
    assert r["orientation"] == pytest.approx(1 / math.sqrt(2 * math.pi))
    r = go_to_ball_reward(scene(ball=(0.0, 1.0), on_dribbler=True), 0)  # ball 90 degrees to the left
    assert r["contact"] == 100.0
    assert r["orientation"] == pytest.approx(math.exp(-2 * (math.pi / 2) ** 2 / math.pi ** 2) / math.sqrt(2 * math.pi))
    rp = go_to_ball_reward(scene(ball=(0.0, 1.0)), 0, orientation_form="printed")
    assert rp["orientation"] == pytest.approx(math.exp(-2 * (math.pi / 2) / math.pi ** 2) / math.sqrt(2 * math.pi))
    with pytest.raises(ValueError, match="orientation_form"):
        go_to_ball_reward(scene(), 0, orientation_form="cubic")


def test_aim_to_shoot_reward_hand_built():
    a = math.atan2(0.5, 2.0)
    r = aim_to_shoot_reward(scene(robot=(2.5, 0.0, 0.0), ball_vel=(4.0, 0.0)), 0, F)["aim"]
    assert r == pytest.approx(0.05 * (2 * a - a) * 4.0)  # aimed: positive, scaled by 0.05
    r = aim_to_shoot_reward(scene(robot=(2.5, 0.0, math.pi / 2), ball_vel=(0.0, 4.0)), 0, F)["aim"]
    assert r == pytest.approx((2 * a - (math.pi / 2 + a)) * 4.0)  # looking away: negative
    assert aim_to_shoot_reward(scene(robot=(2.5, 0.0, 0.0)), 0, F)["aim"] == 0.0  # ball at rest


def test_dribbler_ball_distance():
    assert dribbler_ball_distance(scene(ball=(FACE, 0.0)), 0, RP, BP) == pytest.approx(0.0)
    assert dribbler_ball_distance(scene(ball=(FACE + 0.035, 0.0)), 0, RP, BP) == pytest.approx(0.035)


def test_go_to_ball_success_terminates():
    env = GoToBallEnv()
    env.reset(seed=0, options={"ball_pos": (0.5, 0.0), "robot_pose": (0.0, 0.0, 0.0)})
    for _ in range(120):
        obs, r, term, trunc, info = env.step(np.array([0.3, 0.0, 0.0], np.float32))
        if term:
            break
    assert term and not trunc and info["is_success"] and info["failure_reason"] is None
    assert r > 90  # contact reward


def test_go_to_ball_timeout_truncates():
    env = GoToBallEnv(max_time_s=0.5)
    env.reset(seed=0, options={"ball_pos": (2.0, 0.0), "robot_pose": (0.0, 0.0, 0.0)})
    n = 0
    while True:
        n += 1
        obs, r, term, trunc, info = env.step(np.zeros(3, np.float32))
        if term or trunc:
            break
    assert trunc and not term and n == 30 and info["failure_reason"] == "timeout" and not info["is_success"]


def test_aim_to_shoot_terminal_conditions():
    env = AimToShootEnv()
    # straight shot from in front of the goal: success
    env.reset(seed=0, options={"robot_pose": (2.5, 0.0, 0.0)})
    for _ in range(120):
        obs, r, term, trunc, info = env.step(np.array([0.0, 1.0, 1.0], np.float32))
        if term or trunc:
            break
    assert term and info["is_success"]
    # kicking away from the goal: missed
    env.reset(seed=0, options={"robot_pose": (2.5, 0.0, math.pi / 2)})
    for _ in range(120):
        obs, r, term, trunc, info = env.step(np.array([0.0, 1.0, 1.0], np.float32))
        if term or trunc:
            break
    assert term and info["failure_reason"] == "missed" and r < 0
    # spinning at full rate loses the ball before any kick
    env.reset(seed=0, options={"robot_pose": (2.5, 0.0, 0.0)})
    for _ in range(120):
        obs, r, term, trunc, info = env.step(np.array([1.0, 1.0, -1.0], np.float32))
        if term or trunc:
            break
    assert term and info["failure_reason"] == "ball_lost"
    # holding still without kicking: timeout at 1.6 s
    env.reset(seed=0, options={"robot_pose": (2.5, 0.0, 0.0)})
    n = 0
    while True:
        n += 1
        obs, r, term, trunc, info = env.step(np.array([0.0, 1.0, -1.0], np.float32))
        if term or trunc:
            break
    assert trunc and info["failure_reason"] == "timeout" and n == 96


def run_skill(env, skill, task, seed, options=None):
    env.reset(seed=seed, options=options)
    skill.reset()
    while True:
        _, _, term, trunc, info = env.step(task_action(task, skill.act(env.seen(), 0)))
        if term or trunc:
            return info


def test_go_to_ball_baseline_succeeds_99_of_100():
    env = GoToBallEnv()
    skill = GoToBallBaseline(env.field)
    wins = sum(run_skill(env, skill, "go-to-ball", seed)["is_success"] for seed in range(100))
    assert wins >= 99


def test_aim_to_shoot_baseline_scores_from_easy_scene():
    env = AimToShootEnv()
    skill = AimToShootBaseline(env.field)
    info = run_skill(env, skill, "aim-to-shoot", 0, {"robot_pose": (2.5, 0.5, -1.0)})
    assert info["is_success"]
    assert skill.status == SkillStatus.SUCCEEDED


def test_drive_forward_and_move_to_point():
    ws = scene()
    d = DriveForward(F)
    for _ in range(59):
        a = d.act(ws, 0)
        assert d.status == SkillStatus.RUNNING and a[0] > 0 and a[3] > 0
    d.act(ws, 0)
    assert d.status == SkillStatus.SUCCEEDED
    m = MoveToPoint(F, target=(1.0, 1.0), facing=math.pi)
    a = m.act(ws, 0)
    assert a[0] > 0 and a[1] > 0 and a[2] > 0 and m.status == SkillStatus.RUNNING
    m = MoveToPoint(F, target=(0.0, 0.0), facing=0.0)
    m.act(ws, 0)
    assert m.status == SkillStatus.SUCCEEDED


@pytest.mark.parametrize("gen,env_cls", [(go_to_ball_demos, GoToBallEnv), (aim_to_shoot_demos, AimToShootEnv)])
def test_demonstrations_lie_in_spaces_and_succeed(gen, env_cls):
    env = env_cls()
    trans = list(gen(600, seed=0))
    assert len(trans) == 600
    ends = [t for t in trans if t.terminated or t.truncated]
    assert ends and all(t.info["is_success"] for t in ends)
    for t in trans:
        assert env.observation_space.contains(t.obs) and env.observation_space.contains(t.next_obs)
        assert env.action_space.contains(t.action)


def test_bad_inputs_give_clear_errors(tmp_path):
    with pytest.raises(ValueError, match="unknown skill"):
        make_skill("dance", "baseline", F)
    with pytest.raises(ValueError, match="kind"):
        make_skill("go_to_ball", "magic", F)
    with pytest.raises(FileNotFoundError, match="nope.pt"):
        make_skill("go_to_ball", "learned", F, checkpoint=tmp_path / "nope.pt")
    from ssl_marl.runners.skill_eval import evaluate_skill

    with pytest.raises(ValueError, match="unknown skill"):
        evaluate_skill("fly", "baseline", episodes=1)
    with pytest.raises(FileNotFoundError, match="does not exist"):
        evaluate_skill("go-to-ball", str(tmp_path / "missing.pt"), episodes=1)
    env = GoToBallEnv()
    env.reset(seed=0)
    with pytest.raises(ValueError, match="NaN"):
        env.step(np.array([np.nan, 0, 0]))
    with pytest.raises(ValueError, match="shape"):
        env.step(np.zeros(5))


def test_evaluation_is_deterministic_whatever_the_workers(tmp_path):
    from ssl_marl.runners.skill_eval import evaluate_skill

    a = evaluate_skill("aim-to-shoot", "baseline", episodes=12, seed=5, workers=1, progress=False)
    b = evaluate_skill("aim-to-shoot", "baseline", episodes=12, seed=5, workers=2, progress=False, out=tmp_path)
    assert a["episodes_detail"] == b["episodes_detail"]
    assert (tmp_path / "results.json").exists() and (tmp_path / "time_hist.png").exists()


def test_aim_to_shoot_reward_options():
    env = AimToShootEnv(reward_form="kick_only", success_bonus=5.0)
    env.reset(seed=0, options={"robot_pose": (2.5, 0.0, 2.0)})
    _, r, *_ = env.step(np.array([0.5, 1.0, -1.0], np.float32))  # turning with the ball: free before a kick
    assert r == 0.0
    env.reset(seed=0, options={"robot_pose": (2.5, 0.0, 0.0)})
    total, info = 0.0, {}
    for _ in range(120):
        _, r, term, trunc, info = env.step(np.array([0.0, 1.0, 1.0], np.float32))
        total += r
        if term or trunc:
            break
    assert info["is_success"] and info["reward_terms"]["success_bonus"] == 5.0 and total > 5.0
    paper = AimToShootEnv()
    paper.reset(seed=0, options={"robot_pose": (2.5, 0.0, 2.0)})
    _, r, *_ = paper.step(np.array([0.5, 1.0, -1.0], np.float32))
    assert r < 0.0  # the printed reward charges the ball's motion while turning unaimed
    with pytest.raises(ValueError, match="reward_form"):
        AimToShootEnv(reward_form="dense")


def test_aim_to_shoot_baseline_demos_show_turning_and_succeed():
    from ssl_marl.skills.demos import aim_to_shoot_baseline_demos

    trans = list(aim_to_shoot_baseline_demos(400, seed=0))
    ends = [t for t in trans if t.terminated or t.truncated]
    assert ends and all(t.info["is_success"] for t in ends)
    assert any(abs(t.action[0]) > 0.1 for t in trans)  # omega used: the robot turns


@pytest.mark.parametrize("kick_action, speed_fraction", [("strength", 0.2), ("full", 1.0)])
def test_aim_to_shoot_kick_action(kick_action, speed_fraction):
    """A kick action of 0.2 kicks at 20 % ("strength", the paper's) or 100 % ("full")."""
    env = AimToShootEnv(kick_action=kick_action)
    assert env.spec_version == {"strength": "aim_to_shoot/v1", "full": "aim_to_shoot/v2"}[kick_action]
    env.reset(seed=0)
    env.step(np.array([0.0, 1.0, -1.0], np.float32))  # let the kicker see the ball
    env.step(np.array([0.0, 1.0, 0.2], np.float32))
    speed = float(np.hypot(*env.truth().ball_vel))
    assert speed == pytest.approx(speed_fraction * RobotParams().kick_speed_max, rel=0.05)
    with pytest.raises(ValueError, match="kick_action"):
        AimToShootEnv(kick_action="soft")
