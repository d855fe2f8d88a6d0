"""The passing game: decision values, Pass / Receive tactics, the coordinator, match stats."""

import dataclasses
import math

import numpy as np
import pytest

from ssl_marl.physics import FieldGeometry, ball_model
from ssl_marl.physics.params import BallParams, RobotParams
from ssl_marl.plays.pass_decision import (Choice, DecisionParams, decide, evaluate_passes, motion_time,
                                          open_goal_interval, pass_kick_speed, path_margin, shot_value)
from ssl_marl.plays.pass_tactic import Pass, PassInputs, PassParams, PassState
from ssl_marl.plays.receive_tactic import Receive, ReceiveInputs, ReceiveParams, ReceiveState, ball_incoming
from ssl_marl.plays.scene import ball_in_front, make_world
from ssl_marl.plays.shoot import Attacker, ShootInputs, ShootParams, ShootState
from ssl_marl.plays.stats import MatchStatsTracker
from ssl_marl.skills.base import SkillStatus

F = FieldGeometry.div_b()
RP, BP = RobotParams(), BallParams()
DP = DecisionParams()
GOALIE = (4.3, 0.0)


# ------------------------------------------------------------ value functions
def test_motion_time_accelerates_then_cruises():
    assert motion_time(0.0, 3.0, 3.0) == pytest.approx(0.0)
    assert motion_time(1.5, 3.0, 3.0) == pytest.approx(1.0)  # d = a t^2 / 2 up to v^2 / 2a = 1.5 m
    assert motion_time(4.5, 3.0, 3.0) == pytest.approx(4.5 / 3.0 + 0.5)


def test_tabulated_ball_times_match_the_ball_model_while_the_ball_moves():
    for v0 in (1.63, 2.43, 3.5, 5.21, 6.5):  # on and between the table's rows
        s = np.linspace(0.05, 10.0, 200)
        s = s[np.array([ball_model.speed_at_distance(v0, float(x), BP) for x in s]) >= 0.8]
        ref = np.array([ball_model.time_to_distance(v0, float(x), BP) for x in s])
        assert np.abs(ball_model.times_to_distances(v0, s, BP) - ref).max() < 0.05
    assert math.isinf(float(ball_model.times_to_distances(2.0, ball_model.stop_distance(2.0, BP) + 0.2, BP)))


def test_pass_kick_speed_arrives_at_the_requested_speed():
    for d in (1.0, 3.0, 5.5):
        v0 = pass_kick_speed(d, BP, RP, DP)
        assert ball_model.speed_at_distance(v0, d, BP) == pytest.approx(DP.pass_arrive_speed, abs=0.1)


def test_path_margin_negative_with_an_opponent_on_the_lane_and_positive_without():
    start, end = np.array([0.0, 0.0]), np.array([3.0, 0.0])
    v0 = pass_kick_speed(3.0, BP, RP, DP)
    assert path_margin(start, end, v0, np.array([[1.5, 0.05]]), RP, BP, DP) < 0.0
    assert path_margin(start, end, v0, np.array([[-1.0, 2.5]]), RP, BP, DP) > 0.2
    assert math.isinf(path_margin(start, end, v0, np.zeros((0, 2)), RP, BP, DP))
    # a ball too slow to get there
    assert path_margin(start, end, 0.5, np.array([[1.5, 2.5]]), RP, BP, DP) == -math.inf


def test_receiver_guard_gives_the_last_metres_to_a_receiver_that_gets_there_first():
    start, end = np.array([0.0, 0.0]), np.array([3.0, 0.0])
    v0 = pass_kick_speed(3.0, BP, RP, DP)
    guard = dataclasses.replace(DP, receiver_guard_m=0.5)
    marker = np.array([[3.35, 0.0]])  # 0.35 m behind the receiver, as the defence's marks stand
    assert path_margin(start, end, v0, marker, RP, BP, DP, receiver=end) < 0.0  # no guard: the marker "intercepts"
    assert path_margin(start, end, v0, marker, RP, BP, guard, receiver=end) > 0.05
    wide = dataclasses.replace(DP, receiver_guard_m=1.0)  # the receiver meets the ball up to 1 m ahead
    assert path_margin(start, end, v0, marker, RP, BP, wide, receiver=end) > 0.3
    assert path_margin(start, end, v0, marker, RP, BP, guard) < 0.0  # the guard needs the receiver
    # an opponent on the lane, away from the receiver, still intercepts
    assert path_margin(start, end, v0, np.array([[1.5, 0.05]]), RP, BP, guard, receiver=end) < 0.0
    with pytest.raises(ValueError, match="receiver_guard_m"):
        DecisionParams(receiver_guard_m=-0.1)


def test_open_goal_interval_full_mouth_and_split_by_a_robot():
    p = np.array([2.5, 0.0])
    full, aim = open_goal_interval(p, np.zeros((0, 2)), F, RP, BP)
    assert full == pytest.approx(2 * math.atan2(0.5, 2.0))
    assert aim == pytest.approx(0.0, abs=1e-9)
    blocked, aim2 = open_goal_interval(p, np.array([[3.5, 0.0]]), F, RP, BP)
    assert blocked < full / 2 + 1e-9 and abs(aim2) > 0.05  # the widest gap beside the robot
    wall, _ = open_goal_interval(p, np.array([[3.0, -0.15], [3.0, 0.0], [3.0, 0.15]]), F, RP, BP)
    assert wall == 0.0
    # robots behind the shooter do not block
    assert open_goal_interval(p, np.array([[1.0, 0.0]]), F, RP, BP)[0] == pytest.approx(full)


def test_shot_value_open_goal_beats_a_walled_goal_and_falls_with_distance():
    near = shot_value(np.array([3.0, 0.0]), np.array([[4.3, 0.35]]), np.zeros((0, 2)), F, RP, BP, DP)
    far = shot_value(np.array([-2.0, 0.0]), np.array([[4.3, 0.35]]), np.zeros((0, 2)), F, RP, BP, DP)
    walled = shot_value(np.array([3.0, 0.0]), np.array([[3.6, -0.15], [3.6, 0.0], [3.6, 0.15]]), np.zeros((0, 2)),
                        F, RP, BP, DP)
    assert near > 0.8 and far < near and walled == 0.0


# -------------------------------------------------------------- the decision
def test_decision_open_goal_shoots():
    mates = np.array([[-4.2, 0.0], [3.0, 0.0], [1.0, 2.0]])
    d = decide(np.array([3.08, 0.0]), 1, mates, np.array([[4.3, 0.35]]), F)
    assert d.choice is Choice.SHOOT and d.shot >= DP.shoot_threshold


def test_decision_blocked_shot_with_a_free_teammate_passes_to_it():
    mates = np.array([[-4.2, 0.0], [2.0, 0.0], [2.5, 2.0], [-1.0, -2.0]])
    wall = np.array([[4.3, 0.0], [3.0, -0.15], [3.0, 0.0], [3.0, 0.15], [2.4, 0.3]])  # shot blocked, carrier pressed
    d = decide(np.array([2.08, 0.0]), 1, mates, wall, F, candidates=(2, 3))
    assert d.shot == 0.0
    assert d.choice is Choice.PASS and d.target == 2
    assert d.best_pass.success >= DP.min_pass_success and d.best_pass.receiver_shot > 0.0


def test_decision_intercepted_lane_is_no_pass():
    mates = np.array([[-4.2, 0.0], [2.0, 0.0], [2.5, 2.0]])
    wall = np.array([[4.3, 0.0], [3.0, -0.15], [3.0, 0.0], [3.0, 0.15], [2.4, 0.3]])
    lane = np.vstack([wall, [[2.3, 1.0]]])  # an opponent in the middle of the pass lane
    d = decide(np.array([2.08, 0.0]), 1, mates, lane, F, candidates=(2,))
    assert d.choice is not Choice.PASS
    (option,) = d.passes
    assert option.margin < 0.0 and option.success == 0.0


def test_pass_candidates_respect_length_and_field_limits():
    p = np.array([0.0, 0.0])
    pts = {2: np.array([0.5, 0.0]), 3: np.array([7.0, 0.0]), 4: np.array([2.0, 1.0]), 5: np.array([4.0, 0.0])}
    opts = evaluate_passes(p, pts, np.zeros((6, 2)), np.zeros((0, 2)), F, RP, BP, DP)
    assert [o.teammate for o in opts] == [4]  # too short, too long / outside, inside the defense area
    with pytest.raises(ValueError, match="carrier index"):
        decide(p, 7, np.zeros((3, 2)), np.zeros((0, 2)), F)


def test_receive_margin_keeps_passes_off_the_side_line():
    """A receiver 0.25 m inside the side line is a pass target with the default margin
    (0.15 m) and not with a 0.6 m one; one 1 m inside is a target with both."""
    p = np.array([0.0, F.half_width - 0.2])  # a free kick on the side line
    pts = {2: np.array([2.0, F.half_width - 0.25]), 3: np.array([2.0, F.half_width - 1.0])}
    mates = np.zeros((6, 2))
    assert [o.teammate for o in evaluate_passes(p, pts, mates, np.zeros((0, 2)), F, RP, BP, DP)] == [2, 3]
    wide = dataclasses.replace(DP, receive_margin_m=0.6)
    assert [o.teammate for o in evaluate_passes(p, pts, mates, np.zeros((0, 2)), F, RP, BP, wide)] == [3]
    with pytest.raises(ValueError, match="receive_margin_m"):
        DecisionParams(receive_margin_m=float("nan"))


def test_decision_params_validation_names_the_field():
    with pytest.raises(ValueError, match="min_pass_m"):
        DecisionParams(min_pass_m=7.0)
    with pytest.raises(ValueError, match="shot_speed"):
        DecisionParams(shot_speed=-1.0)


# ----------------------------------------------------------------- Pass tactic
P = PassState


@pytest.mark.parametrize("state,inputs,expected", [
    (P.GET_BALL, PassInputs(d_db=0.2), P.GET_BALL),
    (P.GET_BALL, PassInputs(d_db=0.03), P.HOLD),
    (P.HOLD, PassInputs(d_db=0.0, receiver_ready=False), P.HOLD),  # handshake: wait for the receiver
    (P.HOLD, PassInputs(d_db=0.0, receiver_ready=True, aim_err=0.1, speed=0.1), P.KICK),
    (P.HOLD, PassInputs(d_db=0.0, receiver_ready=True, aim_err=1.0, speed=0.1), P.HOLD),  # still turning
    (P.HOLD, PassInputs(d_db=0.0, receiver_ready=True, aim_err=0.1, speed=0.8), P.HOLD),  # still braking
    (P.HOLD, PassInputs(d_db=0.0, receiver_ready=True, has_target=False), P.HOLD),
    (P.HOLD, PassInputs(d_db=0.08, receiver_ready=True), P.GET_BALL),
    (P.HOLD, PassInputs(d_db=0.0, time_in_state=2.5), P.FAILED),
    (P.KICK, PassInputs(d_db=0.0), P.KICK),
    (P.KICK, PassInputs(d_db=0.0, kicked=True), P.DONE),
    (P.KICK, PassInputs(d_db=0.0, skill_status=SkillStatus.SUCCEEDED), P.DONE),
    (P.KICK, PassInputs(d_db=0.1, skill_status=SkillStatus.FAILED), P.FAILED),
    (P.DONE, PassInputs(d_db=0.5), P.DONE),
    (P.FAILED, PassInputs(d_db=0.0, receiver_ready=True), P.FAILED),
])
def test_pass_transitions(state, inputs, expected):
    assert Pass.transition(state, inputs, PassParams()) is expected


def test_a_passer_near_the_dribbling_limit_kicks_moving():
    """``kick_moving``: HOLD -> KICK once facing the target, however fast the robot moves
    (a passer pushed along with the ball); still only when facing it."""
    moving = PassInputs(d_db=0.0, receiver_ready=True, aim_err=0.1, speed=0.8)
    assert Pass.transition(P.HOLD, moving, PassParams()) is P.HOLD
    assert Pass.transition(P.HOLD, moving, PassParams(kick_moving=True)) is P.KICK
    turning = dataclasses.replace(moving, aim_err=1.0)
    assert Pass.transition(P.HOLD, turning, PassParams(kick_moving=True)) is P.HOLD


R = ReceiveState


@pytest.mark.parametrize("state,inputs,expected", [
    (R.POSITION, ReceiveInputs(dist_to_point=1.0), R.POSITION),
    (R.POSITION, ReceiveInputs(dist_to_point=0.1, face_err=0.1, speed=0.1), R.READY),
    (R.POSITION, ReceiveInputs(dist_to_point=0.1, face_err=1.0, speed=0.1), R.POSITION),
    (R.POSITION, ReceiveInputs(dist_to_point=1.0, ball_incoming=True), R.RECEIVING),
    (R.READY, ReceiveInputs(dist_to_point=0.2), R.READY),
    (R.READY, ReceiveInputs(dist_to_point=0.5), R.POSITION),
    (R.READY, ReceiveInputs(dist_to_point=0.0, ball_incoming=True), R.RECEIVING),
    (R.RECEIVING, ReceiveInputs(dist_to_point=0.0, ball_speed=2.0), R.RECEIVING),
    (R.RECEIVING, ReceiveInputs(dist_to_point=0.0, ball_speed=0.5, skill_status=SkillStatus.SUCCEEDED), R.CONTROLLED),
    (R.RECEIVING, ReceiveInputs(dist_to_point=0.0, ball_speed=2.0, skill_status=SkillStatus.FAILED), R.FAILED),
    (R.RECEIVING, ReceiveInputs(dist_to_point=0.0, ball_speed=0.1), R.FETCH),
    (R.RECEIVING, ReceiveInputs(dist_to_point=0.0, ball_speed=0.1, on_dribbler=True), R.RECEIVING),
    (R.RECEIVING, ReceiveInputs(dist_to_point=0.0, ball_speed=2.0, time_in_state=3.5), R.FAILED),
    (R.FETCH, ReceiveInputs(dist_to_point=0.0, skill_status=SkillStatus.SUCCEEDED), R.CONTROLLED),
    (R.FETCH, ReceiveInputs(dist_to_point=0.0, time_in_state=3.5), R.FAILED),
    (R.CONTROLLED, ReceiveInputs(dist_to_point=2.0, ball_incoming=True), R.CONTROLLED),
])
def test_receive_transitions(state, inputs, expected):
    assert Receive.transition(state, inputs, ReceiveParams()) is expected


def test_ball_incoming_geometry():
    assert ball_incoming(np.zeros(2), np.array([2.0, 0.0]), np.array([3.0, 0.5]), 0.5, 1.0)
    assert not ball_incoming(np.zeros(2), np.array([-2.0, 0.0]), np.array([3.0, 0.5]), 0.5, 1.0)  # moving away
    assert not ball_incoming(np.zeros(2), np.array([2.0, 0.0]), np.array([3.0, 1.5]), 0.5, 1.0)  # passes wide
    assert not ball_incoming(np.zeros(2), np.array([0.2, 0.0]), np.array([3.0, 0.0]), 0.5, 1.0)  # too slow


def test_tactics_on_hand_built_scenes():
    """Pass: ball on the dribbler -> HOLD (waits for the receiver), facing the target and
    still with a ready receiver -> KICK. Receive: at its point facing the ball -> READY."""
    ball = ball_in_front(0.0, 0.0, 0.0)
    w = make_world(blue=[(-4.2, 0.0, 0.0), (0.0, 0.0, 0.0), (2.0, 0.0, math.pi)], ball=ball, frame="blue",
                   blue_on_dribbler=[False, True, False])
    p = Pass(F, RP, BP)
    p.set_params(target_robot=2, target_point=(2.0, 0.0), receiver_ready=False)
    for _ in range(3):
        p.act(w, 1)
    assert p.status.state is PassState.HOLD
    p.set_params(receiver_ready=True)
    p.act(w, 1)
    assert p.status.state is PassState.KICK
    r = Receive(F, RP, BP, receive_point=(2.0, 0.0), ball_from=tuple(ball))
    r.act(w, 2)
    assert r.status.state is ReceiveState.READY
    r2 = Receive(F, RP, BP, receive_point=(1.0, 2.0), ball_from=tuple(ball))
    a = r2.act(w, 2)
    assert r2.status.state is ReceiveState.POSITION and np.hypot(a[0], a[1]) > 0.1  # it moves there


def test_tactics_reject_bad_parameters_with_clear_errors():
    with pytest.raises(ValueError, match="unknown"):
        Pass(F, RP, BP, unknown=1)
    with pytest.raises(ValueError, match="Pass.target_point .* outside the div_b field"):
        Pass(F, RP, BP, target_point=(6.0, 0.0))
    with pytest.raises(ValueError, match="Receive.receive_point must be two"):
        Receive(F, RP, BP, receive_point=(1.0,))
    with pytest.raises(ValueError, match="Receive.ball_from must be two finite"):
        Receive(F, RP, BP, ball_from=(float("nan"), 0.0))
    assert Receive(F, RP, BP, receive_point=[1, 2]).params.receive_point == (1.0, 2.0)
    assert Receive(F, RP, BP, ball_from=(-0.9, 3.01)).params.ball_from == (-0.9, 3.01)  # ball just over a line


# --------------------------------------------------------------- attacker KEEP
def test_attacker_keep_state_holds_fire_and_returns_to_aiming():
    S = ShootState
    hold = ShootParams(hold_fire=True)
    assert Attacker.transition(S.DRIVE_FORWARD, ShootInputs(d_db=0.01, skill_status=SkillStatus.SUCCEEDED),
                               hold) is S.KEEP
    assert Attacker.transition(S.AIM_TO_SHOOT, ShootInputs(d_db=0.0), hold) is S.KEEP
    assert Attacker.transition(S.KEEP, ShootInputs(d_db=0.0), hold) is S.KEEP
    assert Attacker.transition(S.KEEP, ShootInputs(d_db=0.0), ShootParams()) is S.AIM_TO_SHOOT
    assert Attacker.transition(S.KEEP, ShootInputs(d_db=0.08), hold) is S.GO_TO_BALL
    # default (the paper's machine) never keeps
    assert Attacker.transition(S.DRIVE_FORWARD, ShootInputs(d_db=0.01, skill_status=SkillStatus.SUCCEEDED),
                               ShootParams()) is S.AIM_TO_SHOOT


@pytest.mark.parametrize("tap_m", [None, 0.7])
def test_attacker_keep_taps_the_ball_ahead_within_the_dribbling_limit(tap_m):
    """A robot keeping the ball creeps towards the goal for 8 s: without ``keep_tap_m`` the
    referee's touch watch sees it dribble more than 1 m in one touch (excessive dribbling);
    with it the robot taps the ball ahead, goes to it again, and carries it as far
    without a foul."""
    from ssl_marl.envs import parallel_env
    from ssl_marl.envs.game_control import TouchWatch

    env = parallel_env(n_blue=1, n_yellow=0, field="div_b", max_time_s=10.0, no_progress_s=None)
    pose = (-3.0, 0.0, 0.0)
    env.reset(seed=3, options={"robots": {"blue_0": list(pose)}, "ball": {"pos": list(ball_in_front(*pose))}})
    tac = Attacker(env.field, env.config.robot, env.config.ball, skills="baseline", dt=env.config.dt,
                   hold_fire=True, keep_speed=0.5, keep_tap_m=tap_m)
    watch = TouchWatch(1, 0, env.config.robot.radius, env.config.ball.radius)
    fouls, kicks = [], 0
    for _ in range(480):
        a = tac.act(env.vision_state("blue"), 0)
        kicks += int(a[4] > 0)
        env.step({"blue_0": a})
        ws = env.world_state()
        foul = watch.update(ws, watch.touching(ws, [0] if a[4] > 0 else []), env.field, True)
        fouls += [foul[0]] if foul else []
    assert env.world_state().ball_pos[0] > -1.5  # carried at least 1.4 m up the field
    if tap_m is None:
        assert "excessive_dribbling" in fouls and kicks == 0
    else:
        assert "excessive_dribbling" not in fouls and kicks >= 2


# ------------------------------------------------------------------ stats
def _kick_world(kicker_xy, ball_vel, mates, opp=(), on_blue=None, on_yellow=None, t=0.0):
    blue = [(*kicker_xy, 0.0)] + [(*m, 0.0) for m in mates]
    return make_world(blue=blue, yellow=[(*o, math.pi) for o in opp], ball=kicker_xy, ball_vel=ball_vel, t=t,
                      blue_on_dribbler=on_blue, yellow_on_dribbler=on_yellow)


def test_stats_pass_completed_intercepted_and_shot():
    tr = MatchStatsTracker(F, BP)
    w = _kick_world((0.0, 0.0), (3.0, 0.0), [(2.5, 0.1)], opp=[(1.0, 2.0)])
    tr.observe(w, [{"type": "kick", "agent": "blue_0", "speed": 3.0}])
    for k in range(6):  # the teammate holds it 0.1 s
        tr.observe(_kick_world((0.0, 0.0), (0.0, 0.0), [(2.5, 0.1)], opp=[(1.0, 2.0)], on_blue=[False, True],
                               t=0.5 + k / 60))
    s = tr.summary()["blue"]
    assert (s["passes_attempted"], s["passes_completed"], s["pass_completion"]) == (1, 1, 1.0)
    # a pass the opponent takes
    tr.observe(w, [{"type": "kick", "agent": "blue_0", "speed": 3.0}])
    for k in range(6):
        tr.observe(_kick_world((0.0, 0.0), (0.0, 0.0), [(2.5, 0.1)], opp=[(1.0, 2.0)], on_yellow=[True], t=2 + k / 60))
    s = tr.summary()
    assert s["blue"]["passes_intercepted"] == 1 and s["yellow"]["interceptions"] == 1
    assert s["blue"]["pass_completion"] == pytest.approx(0.5)
    # a shot: aimed at the opponent goal mouth; a clearance at nobody is only a kick
    tr.observe(_kick_world((2.0, 0.0), (6.0, 0.3), []), [{"type": "kick", "agent": "blue_0", "speed": 6.0}])
    tr.observe(_kick_world((0.0, 0.0), (0.0, -5.0), [(2.5, 2.0)]), [{"type": "kick", "agent": "blue_0", "speed": 5}])
    tr.observe(w, [{"type": "goal", "team": "blue", "t": 3.0}])
    s = tr.summary()["blue"]
    assert (s["shots"], s["kicks"], s["goals"], s["passes_attempted"]) == (1, 4, 1, 2)


def test_stats_full_power_flat_kick_past_a_teammate_is_no_pass_but_a_chip_is():
    """A flat kick reaching the teammate 1.5 m ahead at more than 4 m/s (a clearance, a
    stray shot) is no pass; the same kick at 3 m/s is one; a chip towards it at 6 m/s is one."""
    import dataclasses

    from ssl_marl.plays.stats import MatchStatsTracker as T

    tr = T(F, BP)
    mates, u = [(1.1, 1.0)], np.array([1.0, 1.0]) / math.sqrt(2.0)  # away from the goal mouth
    assert tr.classify_kick(_kick_world((0.0, 0.0), 6.5 * u, mates), "blue", 0) == "clear"
    assert tr.classify_kick(_kick_world((0.0, 0.0), 3.0 * u, mates), "blue", 0) == "pass"
    chip = dataclasses.replace(_kick_world((0.0, 0.0), 6.0 * u, mates), ball_vz=3.0)
    assert tr.classify_kick(chip, "blue", 0) == "pass"


def test_stats_a_kick_towards_the_goal_that_dies_short_of_it_is_no_shot():
    """A 1 m/s tap from 3 m in front of the goal mouth stops short (a dribbler's push ahead):
    a kick, no shot; the same kick at 6.5 m/s, a chip at 1 m/s and a 1 m/s tap from 0.2 m
    in front of the line are shots. Both colours."""
    import dataclasses

    from ssl_marl.physics import ball_model

    tr = MatchStatsTracker(F, BP)
    x = F.half_length - 3.0
    assert ball_model.stop_distance(1.0, BP) < 3.0 < ball_model.stop_distance(6.5, BP)
    for side, team in ((1.0, "blue"), (-1.0, "yellow")):
        def kick(x0, speed, vz=0.0):
            kicker, other = [(side * x0, 0.0, 0.0 if side > 0 else math.pi)], [(-side * x0, 0.0, 0.0)]
            blue, yellow = (kicker, other) if team == "blue" else (other, kicker)
            w = make_world(blue=blue, yellow=yellow, ball=(side * x0, 0.0), ball_vel=(side * speed, 0.0))
            return dataclasses.replace(w, ball_vz=vz)
        assert tr.classify_kick(kick(x, 1.0), team, 0) == "clear"
        assert tr.classify_kick(kick(x, 6.5), team, 0) == "shot"
        assert tr.classify_kick(kick(x, 1.0, vz=1.0), team, 0) == "shot"
        assert tr.classify_kick(kick(F.half_length - 0.2, 1.0), team, 0) == "shot"
        geo = tr.shot_geometry(kick(x, 6.5), team, 0)  # the other robot stands behind the kicker
        assert geo["dist_m"] == 3.0 and geo["open_rad"] == pytest.approx(2 * math.atan(0.5 / 3.0), abs=1e-4)


def test_stats_same_step_control_goes_to_the_robot_nearest_the_ball_not_to_blue():
    """A blue pass; a blue receiver and a yellow robot both hold the ball on their dribblers
    for the control time, beginning in the same step: the one nearer the ball takes it."""
    for ball_x, outcome in ((2.45, "passes_completed"), (2.35, "passes_intercepted")):
        tr = MatchStatsTracker(F, BP)
        tr.observe(_kick_world((0.0, 0.0), (3.0, 0.0), [(2.5, 0.1)], opp=[(2.3, 0.1)]),
                   [{"type": "kick", "agent": "blue_0", "speed": 3.0}])
        for k in range(6):
            tr.observe(make_world(blue=[(0.0, 0.0, 0.0), (2.5, 0.1, math.pi)], yellow=[(2.3, 0.1, 0.0)],
                                  ball=(ball_x, 0.1), blue_on_dribbler=[False, True], yellow_on_dribbler=[True],
                                  t=0.5 + k / 60))
        s = tr.summary()["blue"]
        assert s[outcome] == 1 and s["passes_completed"] + s["passes_intercepted"] == 1, (ball_x, s)


def test_stats_deflection_is_not_control_and_timeout_loses_the_pass():
    tr = MatchStatsTracker(F, BP)
    tr.observe(_kick_world((0.0, 0.0), (3.0, 0.0), [(2.5, 0.0)], opp=[(1.2, 0.0)]),
               [{"type": "kick", "agent": "blue_0", "speed": 3.0}])
    tr.observe(_kick_world((0.0, 0.0), (2.0, 0.5), [(2.5, 0.0)], opp=[(1.2, 0.0)], on_yellow=[True], t=0.3))
    assert tr.summary()["blue"]["passes_intercepted"] == 0  # one step on the dribbler: a deflection
    tr.observe(_kick_world((0.0, 0.0), (0.0, 0.0), [(2.5, 0.0)], opp=[(1.2, 0.0)], t=5.0))
    s = tr.summary()["blue"]
    assert s["passes_lost"] == 1 and s["pass_completion"] == 0.0
    assert [e.get("why") for e in tr.log if e["type"] == "pass_lost"] == ["timeout"]
    tr.observe(_kick_world((0.0, 0.0), (3.0, 0.0), [(2.5, 0.0)], t=6.0), [{"type": "kick", "agent": "blue_0"}])
    tr.observe(_kick_world((0.0, 0.0), (3.0, 0.0), [(2.5, 0.0)], t=6.2), [{"type": "ball_out", "t": 6.2}])
    assert [e.get("why") for e in tr.log if e["type"] == "pass_lost"] == ["timeout", "ball_out"]
    with pytest.raises(ValueError, match="field-frame"):
        tr.observe(make_world(blue=[(0, 0, 0)], frame="blue"))


def test_stats_count_set_pieces_and_their_goals():
    """A free kick for blue taken as a pass, the receiver scores: a set-piece pass and a
    set-piece goal; after yellow's free kick, yellow's kick and then a blue control end
    yellow's set-piece possession, so blue's next goal is no set-piece goal."""
    tr = MatchStatsTracker(F, BP)
    w = _kick_world((0.0, 0.0), (3.0, 0.0), [(2.5, 0.1)], opp=[(1.0, 2.0)])
    tr.observe(w, [{"type": "referee", "command": "FREE_KICK", "team": "blue", "position": [0.0, 0.0], "t": 0.0}])
    tr.observe(w, [{"type": "kick", "agent": "blue_0", "speed": 3.0}])
    tr.observe(_kick_world((2.0, 0.0), (6.0, 0.3), []), [{"type": "kick", "agent": "blue_0", "speed": 6.0}])
    tr.observe(w, [{"type": "goal", "team": "blue", "t": 1.0}])
    s = tr.summary()["blue"]
    assert (s["set_pieces"], s["set_piece_passes"], s["set_piece_shots"], s["goals_set_piece"]) == (1, 1, 0, 1)
    tr.observe(w, [{"type": "referee", "command": "FREE_KICK", "team": "yellow", "position": [0.0, 0.0], "t": 2.0}])
    tr.observe(w, [{"type": "kick", "agent": "yellow_0", "speed": 3.0}])
    for k in range(6):  # blue controls the ball: yellow's set-piece possession is over
        tr.observe(_kick_world((0.0, 0.0), (0.0, 0.0), [(2.5, 0.1)], on_blue=[False, True], t=2.5 + k / 60))
    tr.observe(w, [{"type": "goal", "team": "yellow", "t": 3.0}])
    s = tr.summary()
    assert s["yellow"]["set_pieces"] == 1 and s["yellow"]["goals_set_piece"] == 0
    assert s["blue"]["goals_set_piece"] == 1


# ------------------------------------------------------------- in the simulator
def _run_pass(env, passer, receiver, steps, tracker=None):
    """Drive blue_0 (Pass) and blue_1 (Receive) with the handshake wired as a play does."""
    for _ in range(steps):
        w = env.vision_state("blue")
        a1 = receiver.act(w, 1)
        passer.set_params(receiver_ready=receiver.status.state is ReceiveState.READY)
        a0 = passer.act(w, 0)
        _, _, _, _, infos = env.step({"blue_0": a0, "blue_1": a1})
        if tracker is not None:
            tracker.observe(env.world_state(), next(iter(infos.values()))["events"])
        if receiver.status.state in (ReceiveState.CONTROLLED, ReceiveState.FAILED):
            break


def test_pass_between_two_baseline_robots_on_an_empty_field_completes():
    from ssl_marl.envs import parallel_env

    env = parallel_env(n_blue=2, n_yellow=0, field="div_b", max_time_s=30.0)
    ball = ball_in_front(-1.0, 0.5, 0.3)
    env.reset(seed=0, options={"ball": {"pos": ball}, "robots": {"blue_0": (-1.0, 0.5, 0.3),
                                                                   "blue_1": (1.5, -1.0, 2.0)}})
    target = (1.5, -1.0)
    passer = Pass(F, RP, BP, target_robot=1, target_point=target)
    receiver = Receive(F, RP, BP, receive_point=target, ball_from=tuple(ball))
    tracker = MatchStatsTracker(F, BP)
    _run_pass(env, passer, receiver, 8 * 60, tracker)
    assert passer.status.state is PassState.DONE and passer.status.kicks == 1
    assert receiver.status.state is ReceiveState.CONTROLLED
    assert bool(env.world_state().blue.ball_on_dribbler[1])
    s = tracker.summary()["blue"]
    assert (s["passes_attempted"], s["passes_completed"]) == (1, 1)


def test_passer_waits_for_a_receiver_that_is_not_ready():
    from ssl_marl.envs import parallel_env

    env = parallel_env(n_blue=2, n_yellow=0, field="div_b", max_time_s=30.0)
    ball = ball_in_front(-1.0, 0.5, 0.0)
    env.reset(seed=0, options={"ball": {"pos": ball}, "robots": {"blue_0": (-1.0, 0.5, 0.0),
                                                                   "blue_1": (2.0, 0.5, 0.0)}})
    passer = Pass(F, RP, BP, target_robot=1, target_point=(2.0, 0.5), max_wait_s=10.0)
    receiver = Receive(F, RP, BP, receive_point=(-1.0, 2.5), ball_from=tuple(ball))  # far from its point
    _run_pass(env, passer, receiver, 30)
    assert passer.status.state is PassState.HOLD and passer.status.kicks == 0
    assert receiver.status.state is ReceiveState.POSITION


def test_passing_team_passes_around_a_blocked_shot():
    """A passing team (goalie, carrier, free teammate) against a wall of three robots in
    front of the goal: the carrier passes to the free teammate, who takes the ball."""
    from ssl_marl.envs import parallel_env
    from ssl_marl.plays.passing_play import coordinator_of, passing_plays
    from ssl_marl.plays.team import TeamController

    env = parallel_env(n_blue=3, n_yellow=3, field="div_b", max_time_s=30.0)
    ball = ball_in_front(1.5, 0.0, 0.0)
    robots = {"blue_0": (-4.2, 0.0, 0.0), "blue_1": (1.5, 0.0, 0.0), "blue_2": (2.0, 2.2, -1.8),
              "yellow_0": (3.3, -0.2, math.pi), "yellow_1": (3.3, 0.0, math.pi), "yellow_2": (3.3, 0.2, math.pi)}
    env.reset(seed=0, options={"ball": {"pos": ball}, "robots": robots})
    plays = passing_plays()
    team = TeamController("blue", 3, plays=plays)
    coord = coordinator_of(plays)
    tracker = MatchStatsTracker(F, BP)
    for _ in range(6 * 60):
        acts = team.act(env)
        acts.update({f"yellow_{i}": np.zeros(5, np.float32) for i in range(3)})
        _, _, _, _, infos = env.step(acts)
        tracker.observe(env.world_state(), next(iter(infos.values()))["events"])
        if coord.counters.completed:
            break
    assert coord.counters.planned >= 1 and coord.counters.kicked >= 1 and coord.counters.completed == 1
    s = tracker.summary()["blue"]
    assert s["passes_completed"] == 1 and s["shots"] == 0


def test_passing_team_kinds_in_matches_report_stats():
    from ssl_marl.runners.controllers import TEAM_KINDS as CONTROLLERS, make_controller
    from ssl_marl.runners.match import play_match
    from ssl_marl.runners.result import summarize
    from ssl_marl.plays.passing_play import coordinator_of
    from ssl_marl.plays.skillset import team_skill_set
    from ssl_marl.plays.team import required_skills

    assert {"passing-learned", "passing-baseline"} <= set(CONTROLLERS)
    c = make_controller("passing-baseline", "yellow", 6, "div_b")
    assert coordinator_of(c.selector.plays) is not None
    assert set(required_skills(c.selector.plays)) == {"go_to_ball", "aim_to_shoot", "pass", "receive"}
    assert team_skill_set("baseline") == {k: "baseline" for k in ("go_to_ball", "aim_to_shoot", "pass",
                                                                         "receive")}
    learned = team_skill_set("learned")
    assert learned["go_to_ball"] == learned["aim_to_shoot"] == "learned"
    with pytest.raises(ValueError, match="passing team: skills must be one of"):
        team_skill_set("expert", where="passing team")
    r = play_match("passing-baseline", "baseline", robots=3, seconds=2.0, seed=3, progress=False)
    assert set(r.stats) >= {"blue", "yellow", "events"}
    assert r.config["skills"]["blue"]["pass"] == "baseline"
    for team in ("blue", "yellow"):
        assert r.stats[team]["goals"] == r.score[team]
    s = summarize([r, r])
    assert s["stats"]["blue"]["kicks"] == 2 * r.stats["blue"]["kicks"]


# ----------------------------------------------------------- the coordinator
def _ctx(world, role_status=None, role_holders=None):
    from dataclasses import replace

    from ssl_marl.plays.play import make_context

    return replace(make_context(world, "blue", F, RP), role_status=role_status or {}, role_holders=role_holders or {})


def _status(state):
    from ssl_marl.plays.tactic_base import TacticStatus

    return TacticStatus(state)


BLOCKED = dict(blue=[(-4.2, 0.0, 0.0), (1.5, 0.0, 0.0), (2.0, 2.2, -1.8)],
               yellow=[(3.3, -0.2, math.pi), (3.3, 0.0, math.pi), (3.3, 0.2, math.pi)],
               ball=ball_in_front(1.5, 0.0, 0.0), blue_on_dribbler=[False, True, False])


def test_coordinator_plans_a_pass_only_once_the_carrier_has_settled():
    from ssl_marl.plays.pass_coordinator import PassCoordinator, PassPhase

    c = PassCoordinator()
    w = make_world(**BLOCKED, t=1.0, frame="blue")
    c.prepare(_ctx(w, {"attacker": _status(ShootState.DRIVE_FORWARD)}, {"attacker": 1}))
    assert c.plan is None and c.hold_fire()  # no decision yet: the attacker must not shoot
    for k in range(3):
        c.prepare(_ctx(make_world(**BLOCKED, t=1.1 + k / 60, frame="blue"), {"attacker": _status(ShootState.KEEP)},
                       {"attacker": 1}))
    assert c.plan is not None and (c.plan.passer, c.plan.receiver, c.plan.phase) == (1, 2, PassPhase.SETUP)
    assert c.counters.planned == 1


@pytest.mark.parametrize("expiry, passes", [("shoot", False), ("pass", True)])
def test_an_expired_keep_shoots_or_makes_the_best_eligible_pass(expiry, passes):
    from ssl_marl.plays.pass_coordinator import PassCoordinator, PassingParams
    from ssl_marl.plays.pass_decision import Decision, PassOption

    option = PassOption(2, np.array([2.0, 2.2]), 3.0, 0.2, 0.6, 0.0, 0.1)

    class KeepDecider:  # keeps with a worthless shot and one eligible pass that does not beat keeping
        def decide(self, request):
            return Decision(Choice.KEEP, 0.0, 0.3, (option,), option)

    c = PassCoordinator(PassingParams(max_keep_s=0.5, keep_expiry=expiry), decider=KeepDecider())
    for k in range(0, 60, 3):  # a decision every 3 ticks for 1 s
        c.prepare(_ctx(make_world(**BLOCKED, t=1.0 + k / 60, frame="blue"), {"attacker": _status(ShootState.KEEP)},
                       {"attacker": 1}))
        if c.plan is not None or not c.hold_fire():
            break
    assert k / 60 > 0.5  # nothing happens before the keep expires
    if passes:
        assert c.plan is not None and (c.plan.passer, c.plan.receiver) == (1, 2)
    else:
        assert c.plan is None and c.decision.choice is Choice.SHOOT and not c.hold_fire()
    with pytest.raises(ValueError, match="keep_expiry"):
        PassingParams(keep_expiry="dribble")


@pytest.mark.parametrize("max_m, shoots", [(None, True), (4.0, True), (2.0, False)])
def test_an_expired_keep_shoots_only_within_keep_shot_max_m_of_the_goal(max_m, shoots):
    from ssl_marl.plays.pass_coordinator import PassCoordinator, PassingParams
    from ssl_marl.plays.pass_decision import Decision

    class KeepDecider:  # keeps with a worthless shot and no pass
        def decide(self, request):
            return Decision(Choice.KEEP, 0.0, 0.3, (), None)

    c = PassCoordinator(PassingParams(max_keep_s=0.5, keep_shot_max_m=max_m), decider=KeepDecider())
    w = make_world(**BLOCKED, t=1.0, frame="blue")
    d_goal = float(np.hypot(*(w.ball_pos - F.goal_center(+1))))
    assert 2.0 < d_goal < 4.0  # the ball is about 2.9 m from the goal centre
    for k in range(0, 60, 3):  # a decision every 3 ticks for 1 s
        c.prepare(_ctx(make_world(**BLOCKED, t=1.0 + k / 60, frame="blue"), {"attacker": _status(ShootState.KEEP)},
                       {"attacker": 1}))
    assert (c.decision.choice is Choice.SHOOT) is shoots and c.hold_fire() is not shoots
    with pytest.raises(ValueError, match="keep_shot_max_m"):
        PassingParams(keep_shot_max_m=float("nan"))


def test_coordinator_follows_the_handshake_to_completion_and_aborts_on_failure():
    from ssl_marl.plays.pass_coordinator import PassCoordinator, PassPhase, PassPlan

    c = PassCoordinator()
    w = make_world(**BLOCKED, t=2.0, frame="blue")
    c.plan = PassPlan(1, 2, np.array([2.0, 2.2]), PassPhase.SETUP, 1.9)
    c.prepare(_ctx(w, {"passer": _status(PassState.KICK), "receiver": _status(ReceiveState.READY)}))
    assert c.plan.phase is PassPhase.SETUP
    c.prepare(_ctx(make_world(**BLOCKED, t=2.1, frame="blue"),
                   {"passer": _status(PassState.DONE), "receiver": _status(ReceiveState.RECEIVING)}))
    assert c.plan.phase is PassPhase.IN_FLIGHT and c.counters.kicked == 1
    c.prepare(_ctx(make_world(**BLOCKED, t=2.9, frame="blue"),
                   {"passer": _status(PassState.DONE), "receiver": _status(ReceiveState.CONTROLLED)}))
    assert c.plan is None and c.counters.completed == 1
    # a passer that loses the ball before the kick ends the plan
    c.plan = PassPlan(1, 2, np.array([2.0, 2.2]), PassPhase.SETUP, 3.0)
    c.prepare(_ctx(make_world(**BLOCKED, t=3.1, frame="blue"),
                   {"passer": _status(PassState.FAILED), "receiver": _status(ReceiveState.READY)}))
    assert c.plan is None and c.counters.aborted == 1
    # a pass in flight that nobody controls times out
    c.plan = PassPlan(1, 2, np.array([2.0, 2.2]), PassPhase.IN_FLIGHT, 3.2, t_kick=3.3)
    c.prepare(_ctx(make_world(**BLOCKED, t=3.3 + c.params.max_flight_s + 0.1, frame="blue"),
                   {"receiver": _status(ReceiveState.RECEIVING)}))
    assert c.plan is None and c.counters.aborted == 2


def test_set_piece_plan_turns_urgent_after_its_wait_and_a_dead_pass_is_dropped():
    from ssl_marl.plays.pass_coordinator import PassCoordinator, PassingParams, PassPhase, PassPlan

    c = PassCoordinator(PassingParams(set_piece_wait_s=2.0, dead_ball_s=0.6))
    c.plan = PassPlan(1, 2, np.array([2.0, 2.2]), PassPhase.SETUP, 1.0, restart=True)
    waiting = {"passer": _status(PassState.GET_BALL), "receiver": _status(ReceiveState.POSITION)}
    c.prepare(_ctx(make_world(**BLOCKED, t=2.5, frame="blue"), waiting))
    assert c.plan is not None and not c.plan.urgent
    c.prepare(_ctx(make_world(**BLOCKED, t=3.1, frame="blue"), waiting))
    assert c.plan is not None and c.plan.urgent  # kicks without the receiver's READY now
    c.prepare(_ctx(make_world(**BLOCKED, t=3.2, frame="blue"), {"passer": _status(PassState.DONE)}))
    assert c.plan.phase is PassPhase.IN_FLIGHT
    # the ball lies still 0.6 s after the kick and the receiver is not on it: dropped
    c.prepare(_ctx(make_world(**BLOCKED, t=3.7, frame="blue"), {"receiver": _status(ReceiveState.READY)}))
    assert c.plan is not None
    c.prepare(_ctx(make_world(**BLOCKED, t=3.9, frame="blue"), {"receiver": _status(ReceiveState.READY)}))
    assert c.plan is None and c.counters.aborted == 1
    # an open-play plan (restart False) has no such wait; without dead_ball_s a still ball waits max_flight_s
    c = PassCoordinator()
    c.plan = PassPlan(1, 2, np.array([2.0, 2.2]), PassPhase.IN_FLIGHT, 1.0, t_kick=1.0)
    c.prepare(_ctx(make_world(**BLOCKED, t=2.0, frame="blue"), {"receiver": _status(ReceiveState.READY)}))
    assert c.plan is not None


CONTESTED = dict(BLOCKED, yellow=[(3.3, -0.2, math.pi), (3.3, 0.0, math.pi), (1.75, 0.0, math.pi)],
                 yellow_on_dribbler=[False, False, True])


class _Recorder:
    def set_params(self, **kw):
        self.params = kw


def test_contested_setup_turns_urgent_and_the_passer_kicks_without_ready():
    from ssl_marl.plays.pass_coordinator import PassCoordinator, PassingParams, PassPhase, PassPlan
    from ssl_marl.plays.passing_roles import passer_role

    c = PassCoordinator(PassingParams(contested_kick=True))
    c.plan = PassPlan(1, 2, np.array([2.0, 2.2]), PassPhase.SETUP, 1.9)
    ctx = _ctx(make_world(**CONTESTED, t=2.0, frame="blue"),
               {"passer": _status(PassState.HOLD), "receiver": _status(ReceiveState.POSITION)})
    c.prepare(ctx)
    assert c.plan is not None and c.plan.urgent and c.counters.aborted == 0
    rec = _Recorder()
    passer_role(c).update(rec, ctx, None)
    assert rec.params["receiver_ready"] is True  # the receiver is still positioning: no READY needed
    # in flight, an opponent on the ball is an interception
    c.plan.phase, c.plan.t_kick = PassPhase.IN_FLIGHT, 2.1
    c.prepare(_ctx(make_world(**CONTESTED, t=2.2, frame="blue"), {"receiver": _status(ReceiveState.RECEIVING)}))
    assert c.plan is None and c.counters.aborted == 1
    # with contested_kick off (the default), the contested setup is dropped
    c = PassCoordinator()
    c.plan = PassPlan(1, 2, np.array([2.0, 2.2]), PassPhase.SETUP, 1.9)
    c.prepare(ctx)
    assert c.plan is None and c.counters.aborted == 1


def test_pressed_open_play_setup_turns_urgent_only_with_press_urgent_m():
    """An opponent 0.5 m from the ball (not on it) during an open-play setup: with
    ``press_urgent_m`` 0.6 the plan turns urgent (the passer kicks without READY); with
    0.4, or off, it waits; a set piece's plan ignores it."""
    from ssl_marl.plays.pass_coordinator import PassCoordinator, PassingParams, PassPhase, PassPlan

    ball = np.asarray(BLOCKED["ball"])
    pressed = dict(BLOCKED, yellow=[(3.3, -0.2, math.pi), (3.3, 0.0, math.pi), (ball[0] + 0.5, ball[1], math.pi)])
    status = {"passer": _status(PassState.HOLD), "receiver": _status(ReceiveState.POSITION)}
    for press, restart, urgent in ((0.6, False, True), (0.4, False, False), (None, False, False), (0.6, True, False)):
        c = PassCoordinator(PassingParams(press_urgent_m=press))
        c.plan = PassPlan(1, 2, np.array([2.0, 2.2]), PassPhase.SETUP, 1.9, restart=restart)
        c.prepare(_ctx(make_world(**pressed, t=2.0, frame="blue"), status))
        assert c.plan is not None and c.plan.urgent is urgent and c.counters.aborted == 0, (press, restart)
    for bad in (0.0, -1.0, math.nan, math.inf):
        with pytest.raises(ValueError, match="press_urgent_m"):
            PassingParams(press_urgent_m=bad)


def test_open_play_setup_turns_urgent_once_the_passer_has_dribbled_the_cut():
    """A passer in HOLD waiting for its receiver's READY: once the team's account of its
    dribble reaches ``dribble_cut_m`` the plan turns urgent (it kicks before SSL's 1 m limit);
    below the cut, without the cut, or at a set piece it waits. The passer's role then kicks
    moving (``kick_moving``)."""
    from dataclasses import replace

    from ssl_marl.plays.pass_coordinator import PassCoordinator, PassingParams, PassPhase, PassPlan
    from ssl_marl.plays.passing_roles import passer_role

    status = {"passer": _status(PassState.HOLD), "receiver": _status(ReceiveState.POSITION)}
    for cut, dribbled, restart, urgent in ((0.8, 0.85, False, True), (0.8, 0.6, False, False),
                                           (None, 0.95, False, False), (0.8, 0.95, True, False)):
        c = PassCoordinator(PassingParams(dribble_cut_m=cut))
        c.plan = PassPlan(1, 2, np.array([2.0, 2.2]), PassPhase.SETUP, 1.9, restart=restart)
        ctx = replace(_ctx(make_world(**BLOCKED, t=2.0, frame="blue"), status),
                      dribbled_m=np.array([0.0, dribbled, 0.0]))
        c.prepare(ctx)
        assert c.plan is not None and c.plan.urgent is urgent and c.counters.aborted == 0, (cut, dribbled, restart)
        assert c.plan.spent is urgent
        rec = _Recorder()
        passer_role(c).update(rec, ctx, None)
        assert rec.params["kick_moving"] is urgent and rec.params["receiver_ready"] is urgent


def test_restart_play_applies_at_the_centre_mark_and_free_kick_spots():
    from ssl_marl.plays.passing_play import restart_applicable

    mates = [(-4.2, 0.0, 0.0), (-0.8, 0.0, 0.0)]
    opp = [(4.2, 0.0, math.pi), (1.5, 0.0, math.pi)]
    assert restart_applicable(_ctx(make_world(blue=mates, yellow=opp, ball=(0.0, 0.0), frame="blue")))
    assert not restart_applicable(_ctx(make_world(blue=mates, yellow=opp, ball=(0.0, 0.0), ball_vel=(1.0, 0.0),
                                                  frame="blue")))
    spot = (-1.0, F.half_width - 0.2)  # where the referee places a ball that left over the touch line
    assert restart_applicable(_ctx(make_world(blue=mates, yellow=opp, ball=spot, frame="blue")))
    assert not restart_applicable(_ctx(make_world(blue=mates, yellow=opp, ball=(-1.0, 1.0), frame="blue")))
    far = [(-4.2, 0.0, 0.0), (-3.0, -2.0, 0.0)]  # they are much closer: no restart for us
    near_them = make_world(blue=far, yellow=[(4.2, 0, math.pi), (-0.8, 2.0, math.pi)], ball=spot, frame="blue")
    assert not restart_applicable(_ctx(near_them))
    # ... unless the referee gave us the free kick (SSL game control): then anywhere the ball rests
    assert restart_applicable(dataclasses.replace(_ctx(near_them), set_piece=True))
    mid = make_world(blue=far, yellow=[(4.2, 0, math.pi), (-0.8, 1.4, math.pi)], ball=(-1.0, 1.0), frame="blue")
    assert restart_applicable(dataclasses.replace(_ctx(mid), set_piece=True)) and not restart_applicable(_ctx(mid))


def test_stats_shot_geometry_sees_the_goalie_shadow_for_either_team():
    """A robot on the goal line in front of the goal centre halves the open mouth of a shot from
    3 m straight in front: the same for a blue shot at +x and a yellow shot at -x."""
    tr = MatchStatsTracker(F, BP)
    x = F.half_length - 3.0
    for side, team in ((1.0, "blue"), (-1.0, "yellow")):
        kicker, keeper = [(side * x, 0.0, 0.0)], [(side * (F.half_length - 0.1), 0.0, 0.0)]
        blue, yellow = (kicker, keeper) if team == "blue" else (keeper, kicker)
        w = make_world(blue=blue, yellow=yellow, ball=(side * (x + 0.1), 0.0), ball_vel=(side * 6.0, 0.0))
        geo = tr.shot_geometry(w, team, 0)
        assert 0.0 < geo["open_rad"] < math.atan(0.5 / 2.9)  # one side of the goalie
