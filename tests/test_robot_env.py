"""The per-robot skill wrapper: any robot of any full-field env as a skill task.

The central check: the go-to-ball / aim-to-shoot task seen by ``yellow_3`` in a 6v6
match (the match's referee on, the other eleven robots standing in the kickoff
formation) gives the same features, rewards and outcomes, in that robot's team frame,
as ``blue_0`` alone in ``ssl_marl/GoToBall-v0`` / ``AimToShoot-v0``, for every episode
in which nothing came near another robot (yellow's frame is the field frame rotated by
pi, so values agree to Box2D's float32 rounding, 1e-4, not bit for bit).
"""

import numpy as np
import pytest

from ssl_marl.envs import parallel_env
from ssl_marl.envs.referee import kickoff_poses
from ssl_marl.physics.state import to_team_frame
from ssl_marl.skills import make_skill
from ssl_marl.skills.registry import get_task
from ssl_marl.skills.robot_env import RobotSkillEnv, SkillDriver, StaticDriver, team_to_field_pose
from ssl_marl.skills.wrappers import AimToShootEnv, AimToShootTask, GoToBallEnv, GoToBallTask


def _episode(env, skill_name, seed):
    """Run the baseline skill through ``env``; per-step records and the final info."""
    skill = make_skill(skill_name, "baseline", env.field, env.robot_params, env.ball_params)
    to_task = get_task(skill_name).to_task_action
    obs, _ = env.reset(seed=seed)
    skill.reset()
    steps, robot_xy, ball_xy = [], [], []
    while True:
        obs_prev = obs
        obs, r, term, trunc, info = env.step(to_task(skill.act(env.seen(), env.robot)))
        truth = env.truth()
        robot_xy.append(truth.team(truth.frame).pos[env.robot].copy())
        ball_xy.append(truth.ball_pos.copy())
        steps.append((obs_prev, obs, r, term, trunc))
        if term or trunc:
            return steps, info, np.array(robot_xy), np.array(ball_xy)


def _clear_of(points, obstacles, dist):
    d = np.hypot(points[:, None, 0] - obstacles[None, :, 0], points[:, None, 1] - obstacles[None, :, 1])
    return bool((d > dist).all())


@pytest.mark.parametrize("after_goal", ["terminate", "kickoff"])
@pytest.mark.parametrize("skill_name,alone_cls,task_cls", [("go_to_ball", GoToBallEnv, GoToBallTask),
                                                           ("aim_to_shoot", AimToShootEnv, AimToShootTask)])
def test_yellow_3_in_a_6v6_match_sees_the_task_blue_0_sees_alone(skill_name, alone_cls, task_cls, after_goal):
    """With ``after_goal="kickoff"`` the match's referee restarts play in the step of a
    goal, so that last step's observation and reward show the kickoff; the outcome
    (success, time) is still the same, read from the referee's goal event."""
    alone = alone_cls()
    match = parallel_env(n_blue=6, n_yellow=6, field="div_b", after_goal=after_goal)
    inside = RobotSkillEnv(match, "yellow_3", task_cls(), drivers=[StaticDriver()], others_placement="env")
    assert inside.observation_space == alone.observation_space and inside.action_space == alone.action_space
    # the eleven others stand in the kickoff formation; in yellow's frame:
    others = kickoff_poses(match.field, 6, 6)[:, :2] * -1.0
    others = np.delete(others, match.agent_index("yellow_3"), axis=0)
    compared = 0
    for seed in range(12):
        a_steps, a_info, a_robot, a_ball = _episode(alone, skill_name, seed)
        if not (_clear_of(a_robot, others, 0.45) and _clear_of(a_ball, others, 0.35)):
            continue  # this episode would meet another robot of the match
        m_steps, m_info, m_robot, m_ball = _episode(inside, skill_name, seed)
        assert len(m_steps) == len(a_steps), f"seed {seed}: episode lengths differ"
        restarted = after_goal == "kickoff" and m_info["is_success"] and skill_name == "aim_to_shoot"
        for k, ((ao0, ao1, ar, at, au), (mo0, mo1, mr, mt, mu)) in enumerate(zip(a_steps, m_steps)):
            np.testing.assert_allclose(mo0, ao0, atol=1e-4)
            assert (mt, mu) == (at, au)
            if restarted and k == len(a_steps) - 1:
                continue
            np.testing.assert_allclose(mo1, ao1, atol=1e-4)
            assert mr == pytest.approx(ar, abs=1e-4)
        np.testing.assert_allclose(m_robot[:-1], a_robot[:-1], atol=1e-4)
        for key in ("is_success", "failure_reason"):
            assert m_info[key] == a_info[key], f"seed {seed}: {key}"
        assert m_info["time_s"] == pytest.approx(a_info["time_s"], abs=1e-9)
        compared += 1
    assert compared >= 3, f"only {compared} episodes stayed clear of the other robots"


def test_blue_and_yellow_starts_are_mirror_images():
    env = parallel_env(n_blue=2, n_yellow=4)
    wrapper = RobotSkillEnv(env, "yellow_3", GoToBallTask(), others_placement="env")
    wrapper.reset(seed=3, options={"robot_pose": (1.0, -0.5, 0.3), "ball_pos": (2.0, 1.0)})
    truth = to_team_frame(env.world_state(), "yellow")
    np.testing.assert_allclose(truth.yellow.pos[3], (1.0, -0.5), atol=1e-9)
    np.testing.assert_allclose(truth.ball_pos, (2.0, 1.0), atol=1e-9)
    np.testing.assert_allclose(env.world_state().yellow.pos[3], (-1.0, 0.5), atol=1e-9)
    np.testing.assert_allclose(team_to_field_pose((1.0, 2.0, 0.5), "yellow"), (-1.0, -2.0, 0.5 - np.pi))


def test_other_robots_follow_their_drivers_and_the_controlled_one_only_the_task():
    """An STP team drives everyone (the controlled robot's action from it is ignored);
    a chasing skill driver moves its robots; episodes still end with an outcome."""
    from ssl_marl.plays.team import TeamController

    env = parallel_env(n_blue=3, n_yellow=3, max_time_s=30.0)
    drivers = [TeamController("blue", 3, env.field), TeamController("yellow", 3, env.field)]
    wrapper = RobotSkillEnv(env, "yellow_1", GoToBallTask(max_time_s=2.0), drivers=drivers)
    wrapper.reset(seed=0)
    start = env.world_state().blue.pos.copy()
    info = {}
    for _ in range(200):
        _, _, term, trunc, info = wrapper.step(np.zeros(3))  # the controlled robot stands still
        if term or trunc:
            break
    assert term or trunc
    assert np.abs(env.world_state().blue.pos - start).max() > 0.05  # STP moved blue
    assert info["is_success"] in (True, False)
    # the controlled robot was commanded zero velocity throughout: it barely moved unless pushed
    chase = SkillDriver(["blue_0"], lambda f, r, b: make_skill("go_to_ball", "baseline", f, r, b), env.field)
    wrapper2 = RobotSkillEnv(parallel_env(n_blue=1, n_yellow=1), "yellow_0", GoToBallTask(max_time_s=1.0),
                             drivers=[chase])
    wrapper2.reset(seed=1)
    p0 = wrapper2.env.world_state().blue.pos.copy()
    for _ in range(30):
        wrapper2.step(np.zeros(3))
    assert np.hypot(*(wrapper2.env.world_state().blue.pos[0] - p0[0])) > 0.05


def test_bad_wrapper_arguments_fail_clearly():
    env = parallel_env(n_blue=1, n_yellow=1)
    with pytest.raises(ValueError, match="unknown agent"):
        RobotSkillEnv(env, "blue_7", GoToBallTask())
    with pytest.raises(ValueError, match="others_placement"):
        RobotSkillEnv(env, "blue_0", GoToBallTask(), others_placement="nowhere")
    w = RobotSkillEnv(env, "blue_0", GoToBallTask())
    w.reset(seed=0)
    with pytest.raises(ValueError, match="shape"):
        w.step(np.zeros(2))
    with pytest.raises(ValueError, match="NaN"):
        w.step(np.array([np.nan, 0, 0]))


def test_a_training_config_can_name_the_traffic():
    """env_kwargs of a skill config pick teammates, opponents and their drivers (here STP teams)."""
    import gymnasium

    from train.offpolicy.config import apply_overrides, default_config

    cfg = apply_overrides(default_config("go-to-ball"), ['env_kwargs={"n_teammates": 1, "n_opponents": 2, '
                                                          '"traffic": "ssl_marl.plays.team:stp_traffic"}'])
    env = gymnasium.make(cfg.env_id, **cfg.env_kwargs)
    env.reset(seed=0)
    inner = env.unwrapped.env
    assert inner.possible_agents == ["blue_0", "blue_1", "yellow_0", "yellow_1"]
    start = inner.robot_poses().copy()
    for _ in range(40):
        env.step(np.zeros(3, np.float32))
    moved = np.hypot(*(inner.robot_poses()[1:, :2] - start[1:, :2]).T)
    assert (moved > 0.02).any()
    with pytest.raises(ValueError, match="opponent_policy"):
        GoToBallEnv(opponent_policy="teleport")


def test_a_task_places_other_robots_and_a_step_can_run_on():
    """``Start.others`` puts named robots where the task says (team frame; the rest are
    placed by the wrapper) and refuses a robot the env lacks; ``Judgement.run_on``
    advances the env within one step until the task ends it (the pass task resolves
    its pass so)."""
    from ssl_marl.skills.robot_env import Judgement, Start

    class _PlaceAndRun(GoToBallTask):
        def __init__(self, others, ticks):
            super().__init__()
            self.others, self.ticks, self.seen_steps = others, ticks, 0

        def sample_start(self, rng, options):
            s = super().sample_start(rng, options)
            return Start(s.robot_pose, s.ball_pos, others=self.others)

        def begin_step(self, seen, robot):
            self.seen_steps += 1

        def judge(self, truth, robot, events, t):
            j = super().judge(truth, robot, events, t)
            self.ticks -= 1
            return Judgement(j.terms, j.terminated, j.truncated, j.success, j.failure_reason, run_on=self.ticks > 0)

    env = parallel_env(n_blue=1, n_yellow=2, field="div_b", task="free_play")
    pose = np.array([1.0, -2.0, 0.5])
    task = _PlaceAndRun({"yellow_1": pose}, ticks=5)
    wrapped = RobotSkillEnv(env, "blue_0", task)
    wrapped.reset(seed=0)
    truth = env.world_state()
    np.testing.assert_allclose(truth.yellow.pos[1], pose[:2], atol=1e-6)
    _, _, _, _, info = wrapped.step(np.zeros(3, np.float32))
    assert task.seen_steps == 1 and info["t"] == pytest.approx(5 * env.config.dt)
    with pytest.raises(ValueError, match="not another robot"):
        RobotSkillEnv(env, "blue_0", _PlaceAndRun({"yellow_5": pose}, 1)).reset(seed=0)
