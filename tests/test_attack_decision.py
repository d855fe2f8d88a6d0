"""The attacking carrier's choice on constructed scenes (team frame, Division B)."""

import math

import numpy as np
import pytest

from ssl_marl.physics.field import FieldGeometry
from ssl_marl.physics.params import BallParams, RobotParams
from ssl_marl.plays.attack_decision import (AttackChoice, AttackParams, chip_kick, chip_margin, decide_attack,
                                            redirect_factor)
from ssl_marl.plays.pass_decision import DecisionParams

F = FieldGeometry.div_b()
RP, BP = RobotParams(), BallParams()


def test_redirect_factor_follows_the_rating():
    assert redirect_factor(0.0) == 1.0 and redirect_factor(0.9) == 1.0
    assert redirect_factor(1.05) == pytest.approx(0.5)
    assert redirect_factor(1.2) == 0.0 and redirect_factor(2.0) == 0.0


def test_chip_kick_lands_short_of_the_receiver():
    speed, d_land = chip_kick(3.0, math.radians(60), 0.8, RP, BP)
    assert d_land == pytest.approx(2.2)
    vh, vv = speed * math.cos(math.radians(60)), speed * math.sin(math.radians(60))
    assert 2 * vh * vv / BP.gravity == pytest.approx(2.2)
    assert chip_kick(20.0, math.radians(60), 0.8, RP, BP) is None  # beyond the kicker cap


def test_chip_flies_over_a_blocker_a_flat_pass_hits():
    speed, _ = chip_kick(3.0, math.radians(60), 0.8, RP, BP)
    blocker = np.array([[0.7, 0.0]])
    assert chip_margin(np.zeros(2), np.array([3.0, 0.0]), speed, math.radians(60), blocker, RP, BP,
                       DecisionParams()) > 0.2
    assert chip_margin(np.zeros(2), np.array([3.0, 0.0]), speed, math.radians(60), np.array([[2.4, 0.0]]), RP,
                       BP, DecisionParams()) < 0.0  # it can reach the landing point


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


def test_open_goal_gives_a_shot():
    mates = np.array([[-4.0, 0.0], [2.5, 0.0], [1.0, 2.0]])
    opp = np.array([[4.45, 0.45], [-2.0, 0.0]])
    d = decide_attack(np.array([2.6, 0.0]), 1, mates, opp, F, RP, BP)
    assert d.choice is AttackChoice.SHOOT


def test_params_are_checked():
    with pytest.raises(ValueError):
        AttackParams(chip_angles=(2.0,))
    with pytest.raises(ValueError):
        AttackParams(redirect_full=1.3)
