"""Chip pass and one-touch redirect tactics in a chip env, and the attacking team kinds."""

import math

import numpy as np
import pytest

from ssl_marl.physics import FieldGeometry
from ssl_marl.physics.params import BallParams
from ssl_marl.plays.attack_decision import chip_kick
from ssl_marl.plays.chip_pass_tactic import ChipPass
from ssl_marl.plays.pass_tactic import PassState
from ssl_marl.plays.receive_tactic import ReceiveState
from ssl_marl.plays.redirect_tactic import Redirect
from ssl_marl.plays.scene import ball_in_front
from ssl_marl.plays.spot_support_tactic import SpotSupport

F = FieldGeometry.div_b()
BP = BallParams()


def _chip_env(n_blue, n_yellow=0):
    from ssl_marl.envs import parallel_env

    env = parallel_env(n_blue=n_blue, n_yellow=n_yellow, field="div_b", max_time_s=30.0, chip_kicks=True)
    return env, env.config.robot


def test_chip_pass_flies_over_a_blocker_and_lands_short_of_the_receiver():
    env, rp = _chip_env(2, 1)
    ball = ball_in_front(-1.0, 0.0, 0.0)
    env.reset(seed=0, options={"ball": {"pos": ball}, "robots": {"blue_0": (-1.0, 0.0, 0.0),
                                                                   "blue_1": (2.0, 0.0, math.pi),
                                                                   "yellow_0": (-0.3, 0.0, math.pi)}})
    target = (2.0, 0.0)
    length = float(np.hypot(*(np.array(target) - ball)))
    speed, d_land = chip_kick(length, math.radians(60), 0.8, rp, BP)
    passer = ChipPass(F, rp, BP, target_robot=1, target_point=target, receiver_ready=True,
                      chip_angle=math.radians(60), chip_speed=speed)
    max_h = 0.0
    for _ in range(4 * 60):
        a = passer.act(env.vision_state("blue"), 0)
        assert a.shape == (6,)
        env.step({"blue_0": a, "blue_1": np.zeros(6), "yellow_0": np.zeros(6)})
        max_h = max(max_h, env.world_state().ball_height)
        if passer.status.state is PassState.DONE and env.world_state().ball_height == 0.0 and max_h > 0:
            break
    assert passer.status.state is PassState.DONE
    assert max_h > 0.5  # well over the blocker's 0.15 m
    bx = float(env.world_state().ball_pos[0])
    assert bx > -0.3  # past the blocker


def test_redirect_receiver_kicks_a_pass_on_towards_the_goal():
    env, rp = _chip_env(1)
    recv_pt = (2.6, 0.6)
    env.reset(seed=0, options={"ball": {"pos": (3.6, -2.0), "vel": (-1.26, 3.27)},
                               "robots": {"blue_0": (2.5, 0.65, -0.4)}})
    aim = (F.half_length, -0.2)
    r = Redirect(F, rp, BP, receive_point=recv_pt, ball_from=(3.6, -2.0), redirect_target=aim)
    scored = False
    for _ in range(3 * 60):
        a = r.act(env.vision_state("blue"), 0)
        assert a.shape == (6,)
        _, _, _, _, infos = env.step({"blue_0": a})
        ev = next(iter(infos.values()))["events"] if infos else []
        scored |= any(e.get("type") == "goal" for e in ev)
        if r.status.state in (ReceiveState.CONTROLLED, ReceiveState.FAILED) or scored or not env.agents:
            break
    w = env.world_state()
    assert scored or (r.status.state is ReceiveState.CONTROLLED and float(w.ball_vel[0]) > 1.5)


def test_redirect_without_a_target_is_an_ordinary_receive_and_supports_emit_six_entries():
    env, rp = _chip_env(1)
    env.reset(seed=0, options={"ball": {"pos": (0.0, 0.0)}, "robots": {"blue_0": (1.0, 1.0, 0.0)}})
    r = Redirect(F, rp, BP, receive_point=(1.0, 1.0))
    assert r.act(env.vision_state("blue"), 0).shape == (6,)
    s = SpotSupport(F, rp, BP, spot=(2.0, 1.0))
    assert s.act(env.vision_state("blue"), 0).shape == (6,)
    with pytest.raises(ValueError):
        s.set_params(spot=(9.0, 0.0))


def test_attack_team_plays_a_short_match_in_a_chip_env():
    from ssl_marl.runners.controllers import CHIP_KINDS, team_spec
    from ssl_marl.envs.actions import fit_action
    from ssl_marl.runners.match import play_match

    assert "attack-learned" in CHIP_KINDS and team_spec("attack-baseline").plays.__name__ == "attack_plays"
    assert fit_action(np.zeros(5, np.float32), 6).shape == (6,)
    assert fit_action(np.zeros(5, np.float32), 5).shape == (5,)
    res = play_match("attack-baseline", "baseline", robots=3, seconds=6.0, seed=3, progress=False)
    assert set(res.score) == {"blue", "yellow"}


def test_behind_ball_waypoint_walks_round_the_ball_to_the_pass_line():
    from ssl_marl.plays.pass_tactic import BESIDE_M, PassParams, behind_ball_waypoint

    rp, p = _chip_env(1)[1], PassParams()
    ball, target = np.array([0.0, 0.0]), np.array([3.0, 0.0])
    back = rp.front_distance + BP.radius + p.behind_gap_m
    # in front of the ball: first sideways (BESIDE_M off the line, on the robot's side), then back
    np.testing.assert_allclose(behind_ball_waypoint((0.5, 0.1), math.pi, ball, target, rp, BP, p), (0.5, BESIDE_M))
    np.testing.assert_allclose(behind_ball_waypoint((0.5, 0.32), math.pi, ball, target, rp, BP, p),
                               (-back, BESIDE_M))
    np.testing.assert_allclose(behind_ball_waypoint((-0.05, -0.1), 0.0, ball, target, rp, BP, p),
                               (-0.05, -BESIDE_M))
    # beside and behind: the staging point on the line
    np.testing.assert_allclose(behind_ball_waypoint((-0.5, -0.6), 0.0, ball, target, rp, BP, p), (-back, 0.0))
    # behind on the line but facing away: still the staging point (turn there)
    np.testing.assert_allclose(behind_ball_waypoint((-back, 0.0), math.pi / 2, ball, target, rp, BP, p), (-back, 0.0))
    # behind, on the line, facing the target: the go-to-ball skill takes over
    assert behind_ball_waypoint((-back, 0.01), 0.05, ball, target, rp, BP, p) is None
    # ... unless it waits for the receiver: it stays on the staging point, off the ball
    np.testing.assert_allclose(behind_ball_waypoint((-back, 0.01), 0.05, ball, target, rp, BP, p, wait=True),
                               (-back, 0.0))


def test_attack_team_takes_its_free_kick_as_a_set_piece():
    """A free kick for blue (ball out over the side line in blue's half, nobody touched
    it): the attacking plays plan the pass before anyone reaches the ball (a set-piece
    plan), the kicker walks round behind the ball and passes within the free kick."""
    from ssl_marl.envs import parallel_env
    from ssl_marl.envs.game_control import FREE_KICK
    from ssl_marl.plays.attack_play import attack_decider_of
    from ssl_marl.runners.controllers import make_controller
    from ssl_marl.runners.match import fit_action

    env = parallel_env(n_blue=4, n_yellow=2, field="div_b", max_time_s=12.0, chip_kicks=True, ssl_restarts=True,
                       fouls=True, stop_s=0.5)
    cfg = env.config
    blue = make_controller("attack-baseline", "blue", 4, F, robot=cfg.robot, ball=cfg.ball, dt=cfg.dt)
    yellow = make_controller("idle", "yellow", 2, F)
    env.reset(seed=0, options={"ball": {"pos": (-1.0, 2.9), "vel": (0.0, 2.0)},
                               "robots": {"blue_0": (-4.0, 0.0, 0.0), "blue_1": (-2.0, 1.5, 0.0),
                                          "blue_2": (0.5, 1.0, math.pi), "blue_3": (-0.5, -1.5, 0.0),
                                          "yellow_0": (4.0, 0.0, math.pi), "yellow_1": (2.0, -2.0, math.pi)}})
    coord = next(p.prepare.coordinator for p in blue.selector.plays if p.prepare is not None)
    restart_plans, fk_seen, fouls, kicked_in_fk = 0, False, [], False
    while env.agents and env.world_state().t < 10.0:
        st = env.task.referee_state
        in_fk = st.command == FREE_KICK and st.team == "blue"
        fk_seen |= in_fk
        actions = {k: fit_action(v, 6) for k, v in {**blue.act(env), **yellow.act(env)}.items()}
        if coord.plan is not None and coord.plan.restart and coord.plan.phase.value == "setup":
            restart_plans += 1
        _, _, _, _, infos = env.step(actions)
        ev = infos["blue_0"]["events"]
        fouls += [e for e in ev if e["type"] == "foul"]
        kicked_in_fk |= in_fk and any(e["type"] == "kick" and e["agent"].startswith("blue") for e in ev)
        if coord.counters.kicked:
            break
    assert fk_seen and restart_plans > 0  # planned while the ball still rested at the spot
    assert coord.counters.kicked == 1 and attack_decider_of(blue.selector.plays).counters.shoot == 0
    assert not fouls
