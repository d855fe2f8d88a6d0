"""Support spots rated by pass safety x value, on constructed scenes."""

import numpy as np

from ssl_marl.physics.field import FieldGeometry
from ssl_marl.physics.params import BallParams, RobotParams
from ssl_marl.plays.pass_decision import DecisionParams, open_goal_interval, pass_success
from ssl_marl.plays.spot_rating import assign_spots, candidate_grid, lane_distances, rate_spots

F = FieldGeometry.div_b()
RP, BP = RobotParams(), BallParams()


def test_grid_stays_in_the_field_and_out_of_the_defense_area():
    c = candidate_grid(F, np.array([0.0, 0.0]))
    assert len(c) > 20
    assert (np.abs(c[:, 0]) <= F.half_length).all() and (np.abs(c[:, 1]) <= F.half_width).all()
    assert not any(F.in_defense_area(p, +1, 0.0) for p in c)
    assert (np.hypot(c[:, 0], c[:, 1]) >= 1.0).all()


def test_best_spot_has_an_open_shot_and_a_safe_lane():
    ball = np.array([0.0, -1.0])
    opp = np.array([[4.4, 0.0], [1.5, -0.5], [2.0, 1.5], [2.5, -1.8]])
    c = candidate_grid(F, ball)
    r = rate_spots(c, ball, opp, np.zeros((0, 2)), F, RP, BP)
    best = c[int(np.argmax(r))]
    assert pass_success(ball, best[None], opp, RP, BP, DecisionParams())[0] > 0.8
    assert open_goal_interval(best, opp, F, RP, BP)[0] > 0.1
    assert r.max() > np.median(r)


def test_a_teammate_in_the_lane_lowers_the_rating():
    ball = np.array([0.0, 0.0])
    spot = np.array([[2.5, 0.0]])
    opp = np.array([[4.4, 0.8]])
    free = rate_spots(spot, ball, opp, np.zeros((0, 2)), F, RP, BP)[0]
    blocked = rate_spots(spot, ball, opp, np.array([[1.2, 0.05]]), F, RP, BP)[0]
    assert blocked < 0.5 * free
    assert lane_distances(ball, spot, np.array([[1.2, 0.05]]))[0, 0] < 0.1


def test_two_supporters_get_different_spots_out_of_each_others_lane():
    ball = np.array([-1.0, 0.0])
    opp = np.array([[4.4, 0.0], [1.0, 1.0]])
    c = candidate_grid(F, ball)
    spots = assign_spots(3, c, ball, opp, F, RP, BP)
    assert spots.shape == (3, 2)
    for i in range(3):
        for j in range(3):
            if i != j:
                assert np.hypot(*(spots[i] - spots[j])) >= 1.2
    d01 = lane_distances(ball, spots[1][None], spots[0][None])[0, 0]
    assert d01 >= 0.25
