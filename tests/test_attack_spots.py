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


def _marked_open_angle(spot: np.ndarray, ball: np.ndarray) -> float:
    """Open goal angle (rad) of a supporter at ``spot`` (attackers' frame) marked on its line
    to the goal (0.35 m goal-side, ball bias 0: the shot-blocking mark, kept out of its defence
    area) with the goalie on the goal line: the marker works in its own team frame (x and y
    negated)."""
    from ssl_marl.plays.defense import mark_position
    from ssl_marl.skills.navigation import NavParams, sanitize_target

    m = -sanitize_target(mark_position(-spot, -ball, F, ball_bias=0.0), F, NavParams())
    goalie = np.array([F.half_length - 0.1, 0.0])
    return open_goal_interval(spot, np.array([goalie, m]), F, RP, BP)[0]


def test_edge_spots_lie_on_the_defense_area_border_where_no_marker_stands_goal_side():
    import pytest

    from ssl_marl.plays.spot_rating import SpotParams, defense_edge_spots

    params = SpotParams(edge_spots=5)
    edge = defense_edge_spots(F, params)
    assert edge.shape == (9, 2)
    assert not any(F.in_defense_area(p, +1, 0.13) for p in edge)  # outside it by the margin ...
    assert all(F.in_defense_area(p, +1, 0.15) for p in edge)      # ... and no further
    ball = np.array([0.0, -1.5])
    plain, with_edge = candidate_grid(F, ball), candidate_grid(F, ball, params)
    assert len(with_edge) == len(plain) + 9
    # a supporter on the border keeps an open shot when marked; one a grid step back does not
    front = np.array([F.half_length - F.defense_depth - params.edge_margin_m, 0.5])
    assert _marked_open_angle(front, ball) > 0.1
    assert _marked_open_angle(front - [0.5, 0.0], ball) < 0.02
    with pytest.raises(ValueError, match="edge_spots"):
        SpotParams(edge_spots=-1)


def test_spot_planner_rerates_every_rate_every_ticks_as_the_play_moves():
    """The supports' spots follow the ball: kept between ratings, re-rated on the
    ``rate_every``-th tick from the ball and opponents of that tick, and rated at once after a
    reset."""
    from types import SimpleNamespace

    from ssl_marl.plays.attack_play import SpotPlanner

    opp = np.array([[4.4, 0.0], [1.0, 1.0]])
    planner = SpotPlanner(n_spots=3, rate_every=6, ball=BP)

    def ctx(ball):
        return SimpleNamespace(field=F, robot=RP, ball=np.array(ball), opp_pos=opp)

    def rated(ball):
        b = np.array(ball)
        return assign_spots(3, candidate_grid(F, b, planner.params), b, opp, F, RP, BP, planner.params)

    planner.update(ctx([-2.0, 0.0]))  # tick 1: no spots yet, rated now
    first = planner.spots.copy()
    np.testing.assert_array_equal(first, rated([-2.0, 0.0]))
    for _ in range(4):  # ticks 2-5: kept, though the ball moved 3 m up the field
        planner.update(ctx([1.0, -1.0]))
        np.testing.assert_array_equal(planner.spots, first)
    planner.update(ctx([1.0, -1.0]))  # tick 6: re-rated from this tick's ball
    np.testing.assert_array_equal(planner.spots, rated([1.0, -1.0]))
    assert not np.array_equal(planner.spots, first)
    assert planner.spots[:, 0].mean() > first[:, 0].mean()  # the spots moved up with the ball
    planner.reset()
    planner.update(ctx([-3.0, 1.0]))  # a new episode: rated at its first tick
    np.testing.assert_array_equal(planner.spots, rated([-3.0, 1.0]))
