"""The attacking carrier's choice on constructed scenes (team frame, Division B)."""

import dataclasses
import math

import numpy as np
import pytest

from ssl_marl.physics.field import FieldGeometry
from ssl_marl.physics.params import BallParams, RobotParams
from ssl_marl.plays.attack_decision import AttackChoice, AttackParams, chip_margin, decide_attack, redirect_factor
from ssl_marl.plays.pass_decision import DecisionParams
from ssl_marl.skills.chip_pass import chip_kick, lane_chip

F = FieldGeometry.div_b()
RP, BP = RobotParams(), BallParams()


def test_redirect_factor_follows_the_rating():
    assert redirect_factor(0.0) == 1.0 and redirect_factor(0.9) == 1.0
    assert redirect_factor(1.05) == pytest.approx(0.5)
    assert redirect_factor(1.2) == 0.0 and redirect_factor(2.0) == 0.0


def test_chip_flies_over_a_blocker_a_flat_pass_hits():
    k = chip_kick(1.5, 3.0 - RP.front_distance - BP.radius, RP, BP)
    blocker = np.array([[1.5, 0.0]])
    assert chip_margin(np.zeros(2), np.array([3.0, 0.0]), k.speed, k.angle, blocker, RP, BP,
                       DecisionParams()) > 0.2
    assert chip_margin(np.zeros(2), np.array([3.0, 0.0]), k.speed, k.angle, np.array([[2.4, 0.0]]), RP,
                       BP, DecisionParams()) < 0.0  # it can reach the landing point


def _chips(d):
    return {o.teammate: o for o in d.options if o.kind is AttackChoice.CHIP}


@pytest.mark.parametrize("length", [2.0, 2.5, 3.0, 3.5, 4.0, 4.5, 5.0])
@pytest.mark.parametrize("blocker", ["midway", "marker", "near_ball", "beside_lane", "none"])
def test_a_chip_is_offered_exactly_where_the_chip_pass_skill_kicks_one(length, blocker):
    """The decision's chip option is the hand-coded chip-pass skill's chip over the lane's
    blocker (same speed and elevation); where the skill finds none, no chip option."""
    p = np.array([-2.0, 0.3])
    q = p + length * np.array([math.cos(0.2), math.sin(0.2)])
    u = (q - p) / length
    n = np.array([-u[1], u[0]])
    opp = {"midway": [p + 0.5 * length * u + 0.05 * n], "marker": [q - 0.35 * u],
           "near_ball": [p + 0.4 * u], "beside_lane": [p + 0.5 * length * u + 0.6 * n], "none": []}[blocker]
    opp = np.array([[F.half_length - 0.1, 0.0], *opp]).reshape(-1, 2)  # the goalie
    mates = np.array([[-F.half_length + 0.2, 0.0], p, q])
    d = decide_attack(p, 1, mates, opp, F, RP, BP, candidates=(2,), heading=0.2)
    if d.choice is AttackChoice.SHOOT:
        pytest.skip("the shot is taken before passes are rated")
    kick = lane_chip(p, q, opp, RP, BP)
    chips = _chips(d)
    assert (2 in chips) == (kick is not None)
    if kick is not None:
        assert chips[2].kick_speed == kick.speed and chips[2].chip_angle == kick.angle


def test_no_chip_over_a_marker_in_front_of_the_receiver():
    """A marker 0.35 m in front of the receiver: no chip lands past it and short of the
    receiver, so the decision offers none (a flat pass or another option instead)."""
    p, q = np.array([0.0, 0.0]), np.array([3.0, 0.0])
    d = decide_attack(p, 1, np.array([[-4.0, 0.0], p, q]), np.array([[4.4, 0.0], [2.65, 0.0]]), F, RP, BP,
                      candidates=(2,), heading=0.0)
    assert d.choice is not AttackChoice.CHIP and not _chips(d)


def test_blocker_in_the_lane_gives_a_chip_pass():
    mates = np.array([[-4.0, 0.0], [0.0, 0.0], [2.5, -0.8]])
    opp = np.array([[4.4, 0.0], [0.67, -0.19], [1.0, 2.0]])
    d = decide_attack(np.array([0.1, 0.0]), 1, mates, opp, F, RP, BP, candidates=(2,), heading=0.0)
    assert d.choice is AttackChoice.CHIP, d
    assert d.best.teammate == 2 and d.best.chip_angle > 0
    flat = [o for o in d.options if o.kind is AttackChoice.PASS]
    assert flat and flat[0].success < d.best.success


def test_open_teammate_with_a_good_deflection_gets_a_redirect():
    mates = np.array([[-4.0, 0.0], [3.6, -2.0], [2.6, 0.6]])
    opp = np.array([[4.4, -0.35], [0.0, 2.0], [-1.0, -1.0]])  # the goalie covers the passer's side
    d = decide_attack(np.array([3.6, -2.0]), 1, mates, opp, F, RP, BP, candidates=(2,))
    assert d.choice is AttackChoice.REDIRECT, d
    assert d.best.deflection < 1.2 and d.best.aim is not None
    assert d.best.aim[0] == pytest.approx(F.half_length)


def test_a_pass_into_a_redirect_is_rated_at_its_own_arrival_speed():
    """The redirect option's kick and success are those of a pass arriving at
    ``redirect_arrive_speed``, not the flat pass's: a firmer pass beats a defender the slow one loses to."""
    from ssl_marl.physics import ball_model

    mates = np.array([[-4.0, 0.0], [3.6, -2.0], [2.6, 0.6]])
    opp = np.array([[4.4, -0.35], [3.1, -0.2], [-1.0, -1.0]])  # a defender 0.65 m beside the lane
    p = np.array([3.6, -2.0])
    length = float(np.hypot(*(mates[2] - p)))
    rated = {}
    for v in (2.0, 4.5):
        d = decide_attack(p, 1, mates, opp, F, RP, BP, AttackParams(redirect_arrive_speed=v), candidates=(2,))
        flat = next(o for o in d.options if o.kind is AttackChoice.PASS)
        red = next(o for o in d.options if o.kind is AttackChoice.REDIRECT)
        assert red.kick_speed == pytest.approx(ball_model.kick_speed_for_arrival(length, v, BP, RP.kick_speed_max),
                                               abs=0.05)
        assert flat.kick_speed < red.kick_speed or v == 2.0
        rated[v] = red.success
    assert rated[2.0] < DecisionParams().min_pass_success <= rated[4.5], rated


def test_open_teammate_up_the_field_with_a_clear_lane_gets_a_flat_pass():
    """No shot from the own half, an opponent 0.7 m behind the carrier (the keep value falls)
    and a teammate 1.7 m up the field with nobody near the lane: a flat pass, rated safe."""
    mates = np.array([[-4.0, 0.0], [-1.0, 0.0], [0.5, 1.5]])
    opp = np.array([[4.4, 0.0], [3.2, -0.3], [3.2, 0.3], [-1.5, -0.4]])
    d = decide_attack(np.array([-0.9, 0.0]), 1, mates, opp, F, RP, BP, candidates=(2,), heading=0.0)
    assert d.choice is AttackChoice.PASS, d
    assert d.best.kind is AttackChoice.PASS and d.best.teammate == 2 and d.best.chip_angle == 0.0
    assert d.best.success > 0.9 and d.best.value >= d.keep + DecisionParams().pass_gain


def test_no_shot_and_only_a_marked_teammate_behind_gives_a_dribble():
    """The only teammate stands behind the carrier with a marker on it (its pass rated 0) and
    the goal is 5 m away: the carrier keeps the ball (no pass, no forced shot)."""
    mates = np.array([[-4.0, 0.0], [-1.0, 0.0], [-3.0, 2.5]])
    opp = np.array([[4.4, 0.0], [3.0, 0.0], [-2.2, 2.3]])
    d = decide_attack(np.array([-0.9, 0.0]), 1, mates, opp, F, RP, BP, candidates=(2,), heading=0.0)
    assert d.choice is AttackChoice.DRIBBLE, d
    assert d.best is None and d.shot < DecisionParams().shoot_threshold
    assert d.keep >= DecisionParams().min_keep


def test_open_goal_gives_a_shot():
    mates = np.array([[-4.0, 0.0], [2.5, 0.0], [1.0, 2.0]])
    opp = np.array([[4.45, 0.45], [-2.0, 0.0]])
    d = decide_attack(np.array([2.6, 0.0]), 1, mates, opp, F, RP, BP)
    assert d.choice is AttackChoice.SHOOT


def test_params_are_checked():
    with pytest.raises(ValueError):
        AttackParams(chip_samples=1)
    with pytest.raises(ValueError):
        AttackParams(redirect_full=1.3)


def test_set_piece_passes_go_inside_the_side_line():
    """A free kick 0.2 m inside the side line: with the attacking plays' restart parameters
    the kicker passes to the support 1.5 m inside, not to the one 0.3 m inside the line
    ahead of it (the pass along the line that runs out), which open play would still offer."""
    from ssl_marl.plays.attack_play import ATTACK_RESTART_DECISION

    hw = F.half_width
    ball = np.array([0.0, -(hw - 0.2)])
    mates = np.array([[-4.2, 0.0], [-0.3, -(hw - 0.2)], [2.5, -(hw - 0.3)], [1.0, -(hw - 1.5)], [-2.0, 0.0],
                      [-3.0, 1.0]])
    opponents = np.array([[4.3, 0.0], [3.0, 0.0], [2.0, 1.0], [-1.0, 1.5]])
    restart = AttackParams(decision=ATTACK_RESTART_DECISION)
    d = decide_attack(ball, 1, mates, opponents, F, RP, BP, restart)
    assert d.choice in (AttackChoice.PASS, AttackChoice.CHIP, AttackChoice.REDIRECT) and d.best.teammate == 3
    assert 2 not in {o.teammate for o in d.options}
    wide_open = AttackParams(decision=dataclasses.replace(ATTACK_RESTART_DECISION, receive_margin_m=0.15))
    assert 2 in {o.teammate for o in decide_attack(ball, 1, mates, opponents, F, RP, BP, wide_open).options}


def test_set_pieces_weight_redirects_with_their_own_weight():
    """``restart_w_redirect`` sets the redirect weight of restart requests only; open play
    keeps ``w_redirect``; None keeps ``w_redirect`` everywhere; a bad weight is refused."""
    from ssl_marl.plays.attack_play import ATTACK_RESTART_DECISION, AttackDecider
    from ssl_marl.plays.pass_coordinator import CarrierRequest

    def request(restart: bool) -> CarrierRequest:
        params = ATTACK_RESTART_DECISION if restart else DecisionParams()
        return CarrierRequest(None, 1, (2,), params, restart, BP, 0.0)

    dec = AttackDecider(AttackParams(restart_w_redirect=2.5))
    assert dec.request_params(request(True)).w_redirect == 2.5
    assert dec.request_params(request(True)).decision == ATTACK_RESTART_DECISION
    assert dec.request_params(request(False)).w_redirect == 1.0
    assert AttackDecider(AttackParams()).request_params(request(True)).w_redirect == 1.0
    # a corner kick: the pass into a redirect is worth w times the receiver's shot value
    hw = F.half_width
    ball = np.array([3.8, -(hw - 0.2)])
    mates = np.array([[-4.2, 0.0], [3.5, -(hw - 0.2)], [2.8, 0.0], [1.0, -1.5], [-2.0, 0.0], [-3.0, 1.0]])
    opp = np.array([[4.4, 0.0], [3.6, -1.0], [3.4, 0.9], [1.5, 1.5], [-1.0, -1.5]])
    red = {}
    for w in (1.0, 3.0):
        d = decide_attack(ball, 1, mates, opp, F, RP, BP,
                          dataclasses.replace(dec.request_params(request(True)), w_redirect=w))
        red[w] = next(o for o in d.options if o.kind is AttackChoice.REDIRECT and o.teammate == 2)
    assert red[3.0].value == pytest.approx(3.0 * red[1.0].value) and red[1.0].value > 0
    for bad in (-1.0, math.nan, math.inf):
        with pytest.raises(ValueError, match="restart_w_redirect"):
            AttackParams(restart_w_redirect=bad)
