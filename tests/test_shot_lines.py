"""Shot lines rated by the opponents' reach times (ssl_marl.plays.shot_lines) and the attacker's
``aim_reach`` (kick along the line the goalie and defenders reach last)."""

import math

import numpy as np
import pytest

from ssl_marl.physics import FieldGeometry
from ssl_marl.physics.params import BallParams, RobotParams
from ssl_marl.plays.pass_decision import DecisionParams
from ssl_marl.plays.scene import ball_in_front, make_world
from ssl_marl.plays.shoot import Attacker
from ssl_marl.plays.shot_lines import (best_shot_line, blocked_by, goal_line_targets, heading_goal_point,
                                       shot_line_margins)

from attacker_helpers import act_at_aim  # noqa: E402  (tests/ is on the path)

F = FieldGeometry.div_b()
RP, BP = RobotParams(), BallParams()


def test_goal_line_targets_span_the_mouth_inside_the_posts():
    t = goal_line_targets(F, 11, inset_m=0.05)
    assert t.shape == (11, 2) and np.all(t[:, 0] == F.half_length)
    assert t[0, 1] == pytest.approx(-F.goal_width / 2 + 0.05) and t[-1, 1] == pytest.approx(F.goal_width / 2 - 0.05)
    with pytest.raises(ValueError, match="n must be"):
        goal_line_targets(F, 1)
    with pytest.raises(ValueError, match="no goal mouth"):
        goal_line_targets(F, 5, inset_m=0.6)


def test_a_goalie_and_a_defender_on_the_ball_goal_line_leave_the_corners_best():
    p = np.array([2.0, 0.0])
    goalie = np.array([F.half_length - 0.4, 0.0])
    defender = np.array([F.half_length - 1.12, 0.0])
    t = goal_line_targets(F, 21)
    m = shot_line_margins(p, t, np.stack([goalie, defender]), np.zeros((0, 2)), RP, BP, DecisionParams(), 0.1)
    assert m[10] < 0.0  # straight at them: they are already there
    assert m[0] > 0.05 and m[-1] > 0.05  # the corners: the ball is there first
    assert np.argmax(m) in (0, 20)
    # symmetric scene, symmetric margins
    assert np.allclose(m, m[::-1], atol=1e-9)


def test_a_later_reaction_only_raises_the_margins():
    p = np.array([2.5, 0.4])
    opp = np.array([[F.half_length - 0.3, 0.1], [F.half_length - 1.1, 0.2]])
    t = goal_line_targets(F, 15)
    m0 = shot_line_margins(p, t, opp, np.zeros((0, 2)), RP, BP, DecisionParams(), 0.0)
    m1 = shot_line_margins(p, t, opp, np.zeros((0, 2)), RP, BP, DecisionParams(), 0.2)
    assert np.allclose(m1 - m0, 0.2)


def test_a_teammate_in_the_line_blocks_it_and_only_it():
    p = np.array([2.0, 0.0])
    t = goal_line_targets(F, 21)
    mate = np.array([[3.0, 0.0]])
    m = shot_line_margins(p, t, np.zeros((0, 2)), mate, RP, BP, DecisionParams(), 0.1)
    assert m[10] == -np.inf and np.isposinf(m[0]) and np.isposinf(m[-1])
    assert blocked_by(p, t, np.array([[1.0, 0.0]]), 0.11).sum() == 0  # behind the ball: no block


def test_heading_goal_point():
    g = heading_goal_point(np.array([2.0, 0.0]), 0.0, F)
    assert g is not None and g[1] == pytest.approx(0.0)
    assert heading_goal_point(np.array([2.0, 0.0]), math.pi, F) is None  # away from the goal
    assert heading_goal_point(np.array([2.0, 0.0]), 0.6, F) is None  # past the left post


def _reach_attacker(heading, opponents):
    """Attacker at (2, 0) with the ball on its dribbler facing ``heading``, yellow ``opponents``."""
    robot = (2.0, 0.0, heading)

    def world(t):
        return make_world(blue=[robot], yellow=list(opponents), ball=ball_in_front(*robot, gap=0.0), t=t,
                          frame="blue")

    return act_at_aim(Attacker(F, snap_shot=True, aim_reach=True), world)


def test_reach_aim_turns_away_from_the_wall_and_kicks_along_a_corner():
    wall = [(F.half_length - 0.4, 0.0, math.pi), (F.half_length - 1.12, 0.0, math.pi)]
    a, _ = _reach_attacker(0.0, wall)  # facing the goalie and the defender: turn, no kick
    assert a[4] <= 0.0 and a[2] != 0.0 and a[3] > 0.0
    corner = math.atan2(F.goal_width / 2 - 0.05, F.half_length - 2.0 - 0.09)
    a, _ = _reach_attacker(corner * 0.97, wall)  # aimed at the left corner: a full-strength kick
    assert a[4] == 1.0
    a, _ = _reach_attacker(0.0, [(F.half_length - 0.2, 1.5, math.pi)])  # no one near the line: shoot at once
    assert a[4] == 1.0


def test_the_reach_shot_rule_shoots_where_the_open_interval_is_shut_but_a_line_is_free():
    from ssl_marl.plays.attack_decision import AttackChoice, AttackParams, decide_attack

    p = np.array([2.5, 0.0])
    # a goalie on the line and one defender right in front of the ball: the mouth is shut
    # seen from p except past the defender's edge; the goalie stands off-centre
    opp = np.array([[F.half_length - 0.2, -0.3], [2.8, 0.05]])
    mates = np.array([[-4.0, 0.0], p, [0.0, 2.5]])
    plain = decide_attack(p, 1, mates, opp, F, params=AttackParams())
    reach = decide_attack(p, 1, mates, opp, F, params=AttackParams(reach_shot_s=0.05))
    _, margin = best_shot_line(p, opp, np.delete(mates, 1, axis=0), F, RP, BP, DecisionParams())
    assert margin >= 0.05
    assert plain.choice is not AttackChoice.SHOOT and reach.choice is AttackChoice.SHOOT
    far = decide_attack(np.array([-1.0, 0.0]), 1, mates, opp, F, params=AttackParams(reach_shot_s=0.05))
    assert far.choice is not AttackChoice.SHOOT or far.shot >= DecisionParams().shoot_threshold  # beyond 3.5 m: off


@pytest.mark.parametrize("field,value", [("reach_shot_s", math.nan), ("reach_shot_s", "0.1"),
                                         ("reach_shot_max_m", 0.0), ("reach_shot_max_m", math.inf)])
def test_bad_reach_shot_parameters_are_refused(field, value):
    from ssl_marl.plays.attack_decision import AttackParams

    with pytest.raises(ValueError, match=field):
        AttackParams(**{field: value})
