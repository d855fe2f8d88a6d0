"""Tactic state machines and geometry on hand-built scenes (no physics)."""

import math

import numpy as np
import pytest

from ssl_marl.physics import FieldGeometry
from ssl_marl.physics.params import BallParams, RobotParams
from ssl_marl.plays.defense import (Defender, DefenderInputs, DefenderState, Goalie, GoalieInputs, GoalieState, Mark,
                                    MarkState, block_position, goalie_guard_position, mark_position)
from ssl_marl.skills.navigation import (NavigateToPoint, NavParams, defense_corner_waypoint, detour_waypoint,
                                       repulsion_velocity, sanitize_target)
from ssl_marl.plays.scene import ball_in_front, make_world
from ssl_marl.plays.shoot import Attacker, GoToBallAndShoot, ShootInputs, ShootParams, ShootState
from ssl_marl.plays.skillset import make_tactic_skill, validate_skills
from ssl_marl.plays.support import Support, SupportState, open_space_scores
from ssl_marl.skills.base import SkillStatus
from ssl_marl.skills.baseline import AimToShootBaseline, GoToBallBaseline

from attacker_helpers import act_at_aim  # noqa: E402  (tests/ is on the path)

F = FieldGeometry.div_b()
RP, BP = RobotParams(), BallParams()
DT = 1.0 / 60.0


def legal(a):
    a = np.asarray(a)
    return a.shape == (5,) and np.isfinite(a).all() and (np.abs(a) <= 1.0).all()


def scene(robot=(0.0, 0.0, 0.0), ball=None, gap=None, t=0.0, frame="blue", **kw):
    """Blue robot 0 at ``robot``; ball ``gap`` m in front of its dribbler, or at ``ball``."""
    if ball is None:
        ball = ball_in_front(*robot, gap=gap or 0.0)
    return make_world(blue=[robot], ball=ball, t=t, frame=frame, **kw)


# --------------------------------------------------------- go-to-ball-and-shoot
S = ShootState


@pytest.mark.parametrize("state,inputs,expected", [
    (S.GO_TO_BALL, ShootInputs(d_db=0.036), S.GO_TO_BALL),
    (S.GO_TO_BALL, ShootInputs(d_db=0.035), S.DRIVE_FORWARD),
    (S.DRIVE_FORWARD, ShootInputs(d_db=0.0, skill_status=SkillStatus.RUNNING), S.DRIVE_FORWARD),
    (S.DRIVE_FORWARD, ShootInputs(d_db=0.2, skill_status=SkillStatus.RUNNING), S.DRIVE_FORWARD),
    (S.DRIVE_FORWARD, ShootInputs(d_db=0.01, skill_status=SkillStatus.SUCCEEDED), S.AIM_TO_SHOOT),
    (S.DRIVE_FORWARD, ShootInputs(d_db=0.05, skill_status=SkillStatus.SUCCEEDED), S.GO_TO_BALL),
    (S.AIM_TO_SHOOT, ShootInputs(d_db=0.0), S.AIM_TO_SHOOT),
    (S.AIM_TO_SHOOT, ShootInputs(d_db=0.04), S.GO_TO_BALL),
    (S.AIM_TO_SHOOT, ShootInputs(d_db=0.0, skill_status=SkillStatus.FAILED), S.GO_TO_BALL),
    (S.AIM_TO_SHOOT, ShootInputs(d_db=0.0, skill_status=SkillStatus.SUCCEEDED), S.GO_TO_BALL),
    (S.AIM_TO_SHOOT, ShootInputs(d_db=0.0, kicked=True), S.GO_TO_BALL),
    # the paper's machine ignores the defense area
    (S.GO_TO_BALL, ShootInputs(d_db=1.0, ball_in_own_defense=True, ball_near_own_defense=True), S.GO_TO_BALL),
])
def test_go_to_ball_and_shoot_transition_is_fig2(state, inputs, expected):
    assert GoToBallAndShoot.transition(state, inputs, ShootParams()) is expected


def test_attacker_transition_waits_while_ball_in_own_defense_area():
    p = ShootParams(keep_out_of_own_defense_area=True)
    inside = ShootInputs(d_db=1.0, ball_in_own_defense=True, ball_near_own_defense=True)
    for s in (S.GO_TO_BALL, S.DRIVE_FORWARD, S.AIM_TO_SHOOT):
        assert GoToBallAndShoot.transition(s, inside, p) is S.WAIT_OUTSIDE_DEFENSE_AREA
    edge = ShootInputs(d_db=1.0, ball_in_own_defense=False, ball_near_own_defense=True)
    assert GoToBallAndShoot.transition(S.WAIT_OUTSIDE_DEFENSE_AREA, edge, p) is S.WAIT_OUTSIDE_DEFENSE_AREA
    out = ShootInputs(d_db=1.0)
    assert GoToBallAndShoot.transition(S.WAIT_OUTSIDE_DEFENSE_AREA, out, p) is S.GO_TO_BALL


def test_go_to_ball_and_shoot_runs_fig2_on_a_scene():
    tac = GoToBallAndShoot(F, skills="baseline")
    assert isinstance(tac.go_to_ball, GoToBallBaseline) and isinstance(tac.aim_to_shoot, AimToShootBaseline)
    far = scene(ball=(1.5, 0.5))
    a = tac.act(far, 0)
    assert tac.state is S.GO_TO_BALL and legal(a)
    # ball 20 mm from the dribbler: drive forward, dribbler on, forward velocity
    near = scene(gap=0.02, t=DT)
    a = tac.act(near, 0)
    assert tac.state is S.DRIVE_FORWARD and a[0] > 0 and a[3] > 0 and a[4] <= 0
    # 1 s of drive forward with the ball held, then aim (robot faces the goal: it kicks at once)
    k = 1
    while tac.state is S.DRIVE_FORWARD and k < 200:
        k += 1
        a = tac.act(scene(gap=0.0, t=k * DT), 0)
    assert tac.state is S.AIM_TO_SHOOT
    assert 59 <= k - 1 <= 62  # ~1 s in DRIVE_FORWARD
    assert a[4] > 0 and tac.status.kicked and tac.status.kicks == 1
    # after the kick: back to go-to-ball
    tac.act(scene(ball=(1.0, 0.0), t=(k + 1) * DT), 0)
    assert tac.state is S.GO_TO_BALL and not tac.status.kicked and tac.status.kicks == 1


def test_drive_forward_then_ball_gone_goes_back_to_go_to_ball():
    tac = GoToBallAndShoot(F)
    tac.act(scene(gap=0.01), 0)
    assert tac.state is S.DRIVE_FORWARD
    for k in range(1, 62):
        tac.act(scene(ball=(0.6, 0.4), t=k * DT), 0)
    assert tac.state is S.GO_TO_BALL


def test_ball_lost_during_aim_goes_back_to_go_to_ball():
    robot = (0.0, 0.0, math.pi / 2)  # facing +y: aim turns, does not kick
    tac = GoToBallAndShoot(F)
    tac.act(scene(robot, gap=0.0), 0)
    for k in range(1, 70):
        tac.act(scene(robot, gap=0.0, t=k * DT), 0)
        if tac.state is S.AIM_TO_SHOOT:
            break
    assert tac.state is S.AIM_TO_SHOOT and tac.status.kicks == 0
    tac.act(scene(robot, gap=0.06, t=1.5), 0)  # ball rolled 60 mm off the dribbler
    assert tac.state is S.GO_TO_BALL and tac.status.kicks == 0


def test_attacker_waits_outside_own_defense_area():
    tac = Attacker(F)
    ws = scene((-2.5, 0.5, 0.0), ball=(-4.2, 0.2))
    a = tac.act(ws, 0)
    assert tac.state is S.WAIT_OUTSIDE_DEFENSE_AREA and legal(a)
    assert not F.in_defense_area(tac.nav.target, -1, margin=0.1)
    tac.act(scene((-2.5, 0.5, 0.0), ball=(-2.0, 0.2), t=DT), 0)
    assert tac.state is S.GO_TO_BALL


def test_attacker_keeps_out_of_the_opponents_defense_area_only_when_asked():
    inside = ShootInputs(d_db=1.0, ball_in_opp_defense=True, ball_near_opp_defense=True)
    assert GoToBallAndShoot.transition(S.GO_TO_BALL, inside, ShootParams(keep_out_of_own_defense_area=True)) \
        is S.GO_TO_BALL  # the own area's guard alone goes for the ball in the opponent's area
    p = ShootParams(keep_out_of_opp_defense_area=True)
    for s in (S.GO_TO_BALL, S.DRIVE_FORWARD, S.AIM_TO_SHOOT, S.KEEP):
        assert GoToBallAndShoot.transition(s, inside, p) is S.WAIT_OUTSIDE_DEFENSE_AREA
    edge = ShootInputs(d_db=1.0, ball_near_opp_defense=True)
    assert GoToBallAndShoot.transition(S.WAIT_OUTSIDE_DEFENSE_AREA, edge, p) is S.WAIT_OUTSIDE_DEFENSE_AREA
    assert GoToBallAndShoot.transition(S.WAIT_OUTSIDE_DEFENSE_AREA, ShootInputs(d_db=1.0), p) is S.GO_TO_BALL
    tac = Attacker(F, keep_out_of_opp_defense_area=True)
    a = tac.act(scene((2.5, 0.5, 0.0), ball=(4.2, 0.2)), 0)
    assert tac.state is S.WAIT_OUTSIDE_DEFENSE_AREA and legal(a)
    target = np.asarray(tac.nav.target)
    assert not F.in_defense_area(target, +1, margin=0.1) and target[0] > 0  # beside the opponent's area
    tac.act(scene((2.5, 0.5, 0.0), ball=(2.0, 0.2), t=DT), 0)
    assert tac.state is S.GO_TO_BALL


def test_tactic_rejects_bad_use():
    tac = GoToBallAndShoot(F)
    with pytest.raises(ValueError, match="unknown parameter"):
        tac.set_params(nope=1)
    with pytest.raises(ValueError, match="team-frame"):
        tac.act(scene(frame="field"), 0)
    with pytest.raises(ValueError, match="skills"):
        GoToBallAndShoot(F, skills="magic")
    with pytest.raises(ValueError):
        validate_skills({"go_to_ball": "magic"})
    tac.set_params(near_ball_m=0.02)
    assert tac.params.near_ball_m == 0.02


def test_skills_are_swappable_through_the_factory():
    assert isinstance(make_tactic_skill("go_to_ball", "baseline", F), GoToBallBaseline)
    assert isinstance(make_tactic_skill("aim_to_shoot", {"go_to_ball": "learned"}, F), AimToShootBaseline)
    with pytest.raises(ValueError):
        make_tactic_skill("dance", "baseline", F)


def test_learned_skills_are_built_once_through_the_factory_then_copied(monkeypatch):
    import ssl_marl.skills as skills_pkg
    from ssl_marl.plays import skillset

    built = []

    class FakeLearned:
        def __init__(self, name):
            self.name, self.status, self.policy = name, SkillStatus.RUNNING, object()

        def reset(self):
            self.status = SkillStatus.RUNNING

        def act(self, world, robot):
            self.status = SkillStatus.FAILED
            return np.zeros(5, np.float32)

    def fake_make_skill(name, kind, field, robot=None, ball=None):
        built.append((name, kind))
        return FakeLearned(name) if kind == "learned" else GoToBallBaseline(field, robot, ball)

    monkeypatch.setattr(skills_pkg, "make_skill", fake_make_skill)
    skillset.clear_skill_cache()
    try:
        t1 = GoToBallAndShoot(F, skills={"go_to_ball": "learned"})
        t2 = GoToBallAndShoot(F, skills={"go_to_ball": "learned"})
        assert isinstance(t1.go_to_ball, FakeLearned) and t1.go_to_ball is not t2.go_to_ball
        assert t1.go_to_ball.policy is t2.go_to_ball.policy  # shared weights
        assert built.count(("go_to_ball", "learned")) == 1
        t1.go_to_ball.act(None, 0)
        assert t2.go_to_ball.status is SkillStatus.RUNNING  # per-instance state
    finally:
        skillset.clear_skill_cache()


def test_yellow_tactic_works_in_its_team_frame():
    # yellow robot at field (1, 0) facing -x (field) = +x in yellow's frame, ball on its dribbler
    x, y, h = 1.0, 0.0, math.pi
    ws = make_world(yellow=[(x, y, h)], ball=ball_in_front(x, y, h, gap=0.01), frame="yellow")
    tac = GoToBallAndShoot(F)
    a = tac.act(ws, 0)
    assert tac.state is S.DRIVE_FORWARD and a[0] > 0


# -------------------------------------------------------------------- goalie
def test_goalie_guard_position_between_ball_and_goal():
    g = F.goal_center(-1)
    for ball in [(0.0, 0.0), (0.0, 2.0), (-3.0, -1.5), (-4.0, 2.5)]:
        p = goalie_guard_position(np.array(ball), np.zeros(2), F, RP)
        assert F.in_defense_area(p, -1)
        assert abs(p[1]) <= F.goal_width / 2 + 1e-9
        d_ball, d_p = np.array(ball) - g, p - g
        if abs(ball[0] - g[0]) > 1.0:  # not clamped: on the goal-ball line
            assert abs(d_ball[0] * d_p[1] - d_ball[1] * d_p[0]) < 1e-6
            assert np.dot(d_ball, d_p) > 0


def test_goalie_intercepts_a_shot_on_its_path():
    ball, vel = np.array([-2.0, 0.4]), np.array([-4.0, -0.2])
    p = goalie_guard_position(ball, vel, F, RP)
    t = (p[0] - ball[0]) / vel[0]
    assert p[1] == pytest.approx(ball[1] + vel[1] * t)
    assert p[0] == pytest.approx(-F.half_length + RP.radius + 0.02)
    # a shot wide of the goal: back to the arc
    p = goalie_guard_position(np.array([-2.0, 2.0]), np.array([-4.0, 0.5]), F, RP)
    assert p[0] > -F.half_length + RP.radius + 0.03


def test_goalie_transitions():
    G, P = GoalieState, Goalie.Params()
    slow_in = GoalieInputs(ball_in_area=True, ball_near_area=True, ball_speed=0.2, d_db=0.5)
    assert Goalie.transition(G.GUARD, slow_in, P) is G.CLEAR_APPROACH
    fast_in = GoalieInputs(ball_in_area=True, ball_near_area=True, ball_speed=3.0, d_db=0.5)
    assert Goalie.transition(G.GUARD, fast_in, P) is G.GUARD
    assert Goalie.transition(G.CLEAR_APPROACH, GoalieInputs(True, True, 0.0, 0.03), P) is G.CLEAR_KICK
    assert Goalie.transition(G.CLEAR_APPROACH, GoalieInputs(False, False, 0.0, 0.5), P) is G.GUARD
    assert Goalie.transition(G.CLEAR_KICK, GoalieInputs(True, True, 0.0, 0.0, kicked=True), P) is G.GUARD
    assert Goalie.transition(G.CLEAR_KICK, GoalieInputs(True, True, 0.0, 0.2), P) is G.CLEAR_APPROACH
    assert Goalie.transition(G.CLEAR_KICK, GoalieInputs(False, False, 0.0, 0.2), P) is G.GUARD


def test_goalie_clears_a_slow_ball_from_its_area():
    robot = (-4.1, 0.2, 0.3)  # facing the opponent half
    ws = scene(robot, gap=0.0)
    tac = Goalie(F)
    tac.act(ws, 0)
    assert tac.state is GoalieState.CLEAR_APPROACH
    a = tac.act(scene(robot, gap=0.0, t=DT), 0)
    assert tac.state is GoalieState.CLEAR_KICK and a[4] > 0 and tac.status.kicks == 1
    tac.act(scene(robot, ball=(-2.0, 0.2), ball_vel=(5.0, 0.0), t=2 * DT), 0)
    assert tac.state is GoalieState.GUARD


def test_goalie_turns_before_clearing_when_facing_its_goal():
    robot = (-4.1, 0.2, math.pi)
    tac = Goalie(F)
    tac.act(scene(robot, gap=0.0), 0)
    a = tac.act(scene(robot, gap=0.0, t=DT), 0)
    assert tac.state is GoalieState.CLEAR_KICK and a[4] <= 0 and abs(a[2]) > 0 and a[3] > 0


def test_goalie_guard_moves_towards_its_spot():
    tac = Goalie(F)
    a = tac.act(scene((-4.3, -0.4, 0.0), ball=(0.0, 1.0)), 0)
    assert tac.state is GoalieState.GUARD and legal(a)
    target = tac.guard_target(scene(ball=(0.0, 1.0)))
    v = a[:2]  # heading 0: body frame = team frame
    assert np.dot(v, target - np.array([-4.3, -0.4])) > 0


# ------------------------------------------------------------------ defender
def test_block_position_on_lane_outside_defense_area():
    g = F.goal_center(-1)
    p = block_position(np.array([0.0, 0.0]), F)
    assert p == pytest.approx([-F.half_length + F.defense_depth + 0.12, 0.0])
    for ball in [(0.0, 2.5), (-4.0, 2.8), (2.0, -1.0), (-4.4, 0.3)]:
        p = block_position(np.array(ball), F)
        assert not F.in_defense_area(p, -1, margin=0.1)
        d_ball, d_p = np.array(ball) - g, p - g
        if ball[0] > -4.3:
            assert abs(d_ball[0] * d_p[1] - d_ball[1] * d_p[0]) < 1e-6
    left = block_position(np.array([0.0, 1.0]), F, lane_offset=0.11)
    right = block_position(np.array([0.0, 1.0]), F, lane_offset=-0.11)
    assert np.hypot(*(left - right)) == pytest.approx(0.22, abs=0.03)
    assert not F.in_defense_area(left, -1, margin=0.1) and not F.in_defense_area(right, -1, margin=0.1)


def test_defender_transitions():
    D, P = DefenderState, Defender.Params()
    near = DefenderInputs(ball_dist=0.3, ball_speed=0.2, ball_in_own_defense=False, teammate_has_ball=False, d_db=0.2)
    assert Defender.transition(D.BLOCK, near, P) is D.CLEAR_APPROACH
    held = DefenderInputs(0.3, 0.2, False, True, 0.2)
    assert Defender.transition(D.BLOCK, held, P) is D.BLOCK
    assert Defender.transition(D.CLEAR_APPROACH, held, P) is D.BLOCK
    far = DefenderInputs(2.0, 0.2, False, False, 1.9)
    assert Defender.transition(D.BLOCK, far, P) is D.BLOCK
    assert Defender.transition(D.CLEAR_APPROACH, far, P) is D.BLOCK
    got = DefenderInputs(0.1, 0.0, False, False, 0.01)
    assert Defender.transition(D.CLEAR_APPROACH, got, P) is D.CLEAR_KICK
    kicked = DefenderInputs(0.1, 0.0, False, False, 0.0, kicked=True)
    assert Defender.transition(D.CLEAR_KICK, kicked, P) is D.BLOCK
    in_area = DefenderInputs(0.3, 0.0, True, False, 0.2)
    assert Defender.transition(D.BLOCK, in_area, P) is D.BLOCK
    off = Defender.Params(challenge_radius=0.0)
    assert Defender.transition(D.BLOCK, near, off) is D.BLOCK


def test_defender_blocks_on_a_scene():
    tac = Defender(F, lane_offset=0.11)
    a = tac.act(scene((-2.0, 1.0, 0.0), ball=(1.0, 1.0)), 0)
    assert tac.state is DefenderState.BLOCK and legal(a)
    assert tac.nav.target == pytest.approx(block_position(np.array([1.0, 1.0]), F, lane_offset=0.11))


# ---------------------------------------------------------------------- mark
def test_mark_position_is_goal_side_of_the_opponent():
    opp, ball = np.array([-1.0, 1.0]), np.array([1.0, -1.0])
    p = mark_position(opp, ball, F, distance=0.35, ball_bias=0.0)
    g = F.goal_center(-1)
    assert np.hypot(*(p - opp)) == pytest.approx(0.35)
    assert np.hypot(*(p - g)) < np.hypot(*(opp - g))
    d_o = opp - g
    assert abs(d_o[0] * (p - g)[1] - d_o[1] * (p - g)[0]) < 1e-6


def test_mark_states():
    ws = make_world(blue=[(-2.0, 0.0, 0.0)], yellow=[(0.0, 1.0, 0.0), (1.0, -1.0, 0.0)], ball=(2.0, 0.0),
                    frame="blue")
    tac = Mark(F)
    tac.act(ws, 0)
    assert tac.state is MarkState.NO_TARGET
    tac.set_params(opponent=1)
    a = tac.act(ws, 0)
    assert tac.state is MarkState.MARK and legal(a)
    assert tac.mark_target(ws) == pytest.approx(mark_position(np.array([1.0, -1.0]), ws.ball_pos, F))
    tac.set_params(opponent=5)
    tac.act(ws, 0)
    assert tac.state is MarkState.NO_TARGET
    assert Mark.transition(MarkState.NO_TARGET, Mark.Inputs(True), Mark.Params()) is MarkState.MARK


def test_mark_on_the_goal_line_blocks_a_one_touch_shot():
    """An opponent waiting for a pass in our half, our goalie guarding against the ball:
    the attacking plays' mark (ball_bias 0, on the opponent's line to our goal centre)
    leaves its one-touch shot at most 0.05 rad of goal mouth in >= 95 % of 500 random
    scenes; the mark turned 25 % towards the ball (the other teams') leaves more open
    in at least a third of them."""
    from ssl_marl.physics.params import BallParams, RobotParams
    from ssl_marl.plays.defense import goalie_guard_position
    from ssl_marl.plays.pass_decision import open_goal_interval

    rp, bp = RobotParams(), BallParams()
    rng = np.random.default_rng(7)
    shut = {0.0: 0, 0.25: 0}
    for _ in range(500):
        opp = np.array([rng.uniform(-3.3, 0.0), rng.uniform(-2.8, 2.8)])
        ball = np.array([rng.uniform(-2.0, 4.4), rng.uniform(-2.9, 2.9)])
        goalie = goalie_guard_position(ball, np.zeros(2), F, rp)
        for bias in shut:
            marker = mark_position(opp, ball, F, ball_bias=bias)  # seen from the opponent, mirrored to the +x goal
            shut[bias] += open_goal_interval(-opp, -np.array([goalie, marker]), F, rp, bp)[0] <= 0.05
    assert shut[0.0] >= 475 and shut[0.25] <= 333


# ------------------------------------------------------------------- support
def test_support_takes_open_space_ahead_in_opponent_half():
    opps = [(2.0, 1.0, math.pi), (2.0, -1.0, math.pi)]
    ws = make_world(blue=[(-1.0, 0.0, 0.0), (0.0, 2.0, 0.0)], yellow=opps, ball=(-0.5, 0.0), frame="blue")
    tac = Support(F)
    a = tac.act(ws, 1)
    assert legal(a) and tac.state is SupportState.SEEK
    spot = tac.target
    assert spot[0] > 0.0
    assert min(np.hypot(*(spot - np.array(o[:2]))) for o in opps) > 0.5
    assert not F.in_defense_area(spot, 1, margin=0.2)
    # band parameter restricts y
    tac2 = Support(F, y_range=(-3.0, 0.0))
    tac2.act(ws, 1)
    assert tac2.target[1] <= 0.0


def test_support_hysteresis_and_hold():
    ws = make_world(blue=[(-1.0, 0.0, 0.0), (0.0, 2.0, 0.0)], yellow=[(2.0, 1.0, math.pi)], ball=(-0.5, 0.0),
                    frame="blue")
    tac = Support(F)
    tac.act(ws, 1)
    spot = tac.target.copy()
    at_spot = make_world(blue=[(-1.0, 0.0, 0.0), (spot[0], spot[1], 0.0)], yellow=[(2.0, 1.0, math.pi)],
                         ball=(-0.5, 0.0), t=DT, frame="blue")
    tac.act(at_spot, 1)
    assert tac.state is SupportState.HOLD and np.allclose(tac.target, spot)
    # transition function
    I, P = Support.Inputs, Support.Params()
    assert Support.transition(SupportState.HOLD, I(0.0, True), P) is SupportState.SEEK
    assert Support.transition(SupportState.HOLD, I(0.5, False), P) is SupportState.SEEK
    assert Support.transition(SupportState.SEEK, I(0.05, False), P) is SupportState.HOLD


def test_open_space_scores_prefer_spots_away_from_opponents():
    cands = np.array([[2.0, 1.0], [2.0, -1.0]])
    s = open_space_scores(cands, np.zeros(2), np.array([[2.0, 1.1]]), np.zeros((0, 2)), F)
    assert s[1] > s[0]


# ---------------------------------------------------------------- navigation
def test_sanitize_target_keeps_field_players_out_of_defense_areas():
    p = sanitize_target(np.array([-4.2, 0.3]), F, NavParams())
    assert not F.in_defense_area(p, -1, margin=0.11)
    p = sanitize_target(np.array([4.2, 0.3]), F, NavParams())
    assert not F.in_defense_area(p, 1, margin=0.11)
    goalie = NavParams(avoid_own_defense=False)
    assert sanitize_target(np.array([-4.2, 0.3]), F, goalie) == pytest.approx([-4.2, 0.3])
    assert sanitize_target(np.array([10.0, -10.0]), F, NavParams()) == pytest.approx([F.half_length, -F.half_width])
    assert sanitize_target(np.array([10.0, 0.0]), F, NavParams()) == pytest.approx([F.half_length - 1.12, 0.0])


def test_detour_waypoint_passes_a_blocking_robot():
    pos, target = np.array([0.0, 0.0]), np.array([2.0, 0.0])
    w = detour_waypoint(pos, target, np.array([[1.0, 0.05]]), 0.25, 0.08)
    assert w is not None and w[1] < -0.25 and w[0] == pytest.approx(1.0)
    assert detour_waypoint(pos, target, np.array([[1.0, 0.6]]), 0.25, 0.08) is None  # not in the way
    assert detour_waypoint(pos, target, np.array([[-1.0, 0.0]]), 0.25, 0.08) is None  # behind us


def test_route_around_own_defense_area():
    pos, target = np.array([-4.0, 1.5]), np.array([-4.0, -1.5])
    w = defense_corner_waypoint(pos, target, F, 0.12)
    assert w is not None and w[0] > -F.half_length + F.defense_depth + 0.12
    nav = NavigateToPoint(F)
    nav.target = target
    a = nav.act(scene((-4.0, 1.5, 0.0), ball=(0.0, 0.0)), 0)
    assert a[0] > 0  # heads out (+x) around the area first
    assert defense_corner_waypoint(np.array([-3.0, 1.5]), np.array([-3.0, -1.5]), F, 0.12) is None


def test_repulsion_brakes_towards_close_robots():
    v = repulsion_velocity(np.zeros(2), np.array([1.0, 0.0]), np.array([[0.2, 0.0]]), NavParams())
    assert v[0] < 0.0  # no component towards the robot 0.2 m ahead, pushed back
    v = repulsion_velocity(np.zeros(2), np.array([1.0, 0.0]), np.array([[2.0, 0.0]]), NavParams())
    assert v == pytest.approx([1.0, 0.0])


def test_navigate_to_point_arrives():
    nav = NavigateToPoint(F)
    nav.target, nav.facing = np.array([0.0, 0.0]), 0.0
    a = nav.act(scene((0.0, 0.0, 0.0), ball=(1.0, 1.0)), 0)
    assert nav.status is SkillStatus.SUCCEEDED and np.allclose(a[:3], 0.0)


def test_goalie_and_defender_share_one_clearing_behaviour():
    from ssl_marl.plays.clearing import BallClearing, ClearPhase, clear_phase
    from ssl_marl.plays.defense import Defender, DefenderParams, Goalie, GoalieParams
    from ssl_marl.skills.features import BALL_LOST_DISTANCE

    p = GoalieParams()
    assert clear_phase(False, p.near_ball_m, False, p) is ClearPhase.KICK
    assert clear_phase(False, p.near_ball_m + 0.01, False, p) is ClearPhase.APPROACH
    assert clear_phase(True, 0.0, True, p) is ClearPhase.DONE
    assert clear_phase(True, BALL_LOST_DISTANCE + 0.01, False, p) is ClearPhase.LOST
    assert clear_phase(True, BALL_LOST_DISTANCE, False, DefenderParams()) is ClearPhase.KICK
    g, d = Goalie(F), Defender(F)
    assert isinstance(g.clearing, BallClearing) and isinstance(d.clearing, BallClearing)


def _aiming_attacker(robot, snap_shot):
    tac = Attacker(F, snap_shot=snap_shot)
    a, _ = act_at_aim(tac, lambda t: scene(robot, gap=0.0, t=t))
    return tac, a


def _open_goal_attacker(heading, goalie_y):
    """Attacker at (2, 0) with the ball on its dribbler, a yellow goalie at (L/2 - 0.15, goalie_y)."""
    goalie = (F.half_length - 0.15, goalie_y, math.pi)

    def world(t):
        robot = (2.0, 0.0, heading)
        return make_world(blue=[robot], yellow=[goalie], ball=ball_in_front(*robot, gap=0.0), t=t, frame="blue")

    return act_at_aim(Attacker(F, snap_shot=True, aim_open_goal=True), world)


def test_open_goal_aim_kicks_into_the_gap_not_at_the_goalie():
    from ssl_marl.plays.pass_decision import open_goal_interval

    a, w = _open_goal_attacker(0.0, 0.0)  # facing the goalie in the middle of the goal: turn, do not shoot
    assert a[4] <= 0.0 and a[3] > 0.0 and a[2] != 0.0
    open_angle, aim = open_goal_interval(w.ball_pos, w.yellow.pos, F, RobotParams(), BallParams())
    assert open_angle > 0.06 and abs(aim) > 0.03  # the open part lies beside the goalie
    assert np.sign(a[2]) == np.sign(aim)  # turning towards it
    a, _ = _open_goal_attacker(aim, 0.0)  # aimed into the gap: a full-strength shot
    assert a[4] == 1.0 and legal(a)
    a, _ = _open_goal_attacker(0.0, 0.9)  # goalie out of the mouth: the goal centre is open, shoot at once
    assert a[4] == 1.0


@pytest.mark.parametrize("heading,snap_shot,kicks", [
    (0.0, True, True),            # facing the goal centre from (2, 0): between the posts -> kick at once
    (0.0, False, False),          # without the snap shot the skill alone decides (this one never kicks)
    (math.pi / 2, True, False),   # facing +y: not between the posts, the skill keeps turning
])
def test_snap_shot_kicks_when_the_heading_is_between_the_posts(heading, snap_shot, kicks):
    tac, a = _aiming_attacker((2.0, 0.0, heading), snap_shot)
    assert bool(a[4] > 0.0) is kicks
    if kicks:
        assert a[4] == 1.0 and legal(a)
