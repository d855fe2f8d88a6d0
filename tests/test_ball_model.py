"""The closed-form ball model against the Box2D simulator and against itself."""

import math

import numpy as np
import pytest

from ssl_marl.physics import BallParams, FieldGeometry, PhysicsWorld, RobotParams
from ssl_marl.physics import ball_model as bm

RP, BP = RobotParams(), BallParams()
FACE = RP.front_distance + BP.radius


def _kick(strength: float, heading: float = 0.0):
    """A robot at the -x end of the Division A field kicks the ball along ``heading``;
    returns the world, the kick time, the ball's start and its kick speed."""
    w = PhysicsWorld(FieldGeometry.from_name("div_a"), RP, BP, 1, 0)
    start = np.array([-5.5, 0.0])
    u = np.array([math.cos(heading), math.sin(heading)])
    w.reset(np.array([[*(start - FACE * u), heading]]), start)
    w.step(np.zeros((1, 2)), np.zeros(1), np.zeros(1, bool), np.array([strength]))
    assert w.kicks_this_step, "the kick did not fire"
    return w, w.t - w.control_dt, start, w.kicks_this_step[0][1]


def _idle(w):
    w.step(np.zeros((1, 2)), np.zeros(1), np.zeros(1, bool), np.zeros(1))


@pytest.mark.parametrize("strength", [0.25, 0.5, 0.8, 1.0])
def test_predict_matches_a_kicked_ball_in_the_simulator(strength):
    w, t0, start, v0 = _kick(strength, heading=0.05)
    u = np.array([math.cos(0.05), math.sin(0.05)])
    worst_p = worst_v = 0.0
    for _ in range(600):
        t = w.t - t0
        p, v = bm.predict(start, v0 * u, t, BP, sliding=True)
        if abs(p[0]) > 5.6 or t > 3.0:  # before the ball could reach a wall; a pass lasts < 3 s
            break
        worst_p = max(worst_p, float(np.hypot(*(p - w.ball_pos))))
        worst_v = max(worst_v, float(np.hypot(*(v - w.ball_vel))))
        _idle(w)
    # sub-centimetre, except where the slide/roll switch falls exactly on a friction step
    # (strengths 0.5 and 1.0): the simulator's float32 rounding then decides, the model
    # splits the difference (0.016 m/s, < 5 cm after 3 s)
    assert worst_p < (0.05 if strength in (0.5, 1.0) else 0.01)  # metres
    assert worst_v < 0.02  # m/s


def test_continuous_model_is_within_a_few_centimetres_of_the_simulator():
    w, t0, start, v0 = _kick(0.3)
    worst = 0.0
    for _ in range(300):
        p, _ = bm.predict(start, (v0, 0.0), w.t - t0, BP, sliding=True, friction_dt=None)
        worst = max(worst, abs(p[0] - w.ball_pos[0]))
        _idle(w)
    assert 0.005 < worst < 0.06  # the discretisation matters, but only by centimetres


def test_ball_stops_where_the_model_says():
    w, t0, start, v0 = _kick(0.3)
    for _ in range(int(bm.stop_time(v0, BP) / w.control_dt) + 30):
        _idle(w)
    assert float(np.hypot(*w.ball_vel)) == 0.0
    assert w.ball_pos[0] - start[0] == pytest.approx(bm.stop_distance(v0, BP), abs=0.005)


@pytest.mark.parametrize("d,v_arrive", [(1.0, 1.5), (3.0, 1.0), (4.5, 2.0)])
def test_kick_speed_for_arrival_arrives_at_the_wanted_speed_in_the_simulator(d, v_arrive):
    v0 = bm.kick_speed_for_arrival(d, v_arrive, BP)
    w, t0, start, got = _kick(v0 / RP.kick_speed_max)
    assert got == pytest.approx(v0)
    while w.ball_pos[0] - start[0] < d:
        _idle(w)
    assert float(np.hypot(*w.ball_vel)) == pytest.approx(v_arrive, abs=0.03)
    assert w.t - t0 == pytest.approx(bm.time_to_distance(v0, d, BP), abs=w.control_dt + 1e-9)


def test_a_placed_moving_ball_slides_like_a_kicked_one():
    w = PhysicsWorld(FieldGeometry.from_name("div_a"), RP, BP, 0, 0)
    w.reset(np.zeros((0, 3)), np.array([-5.0, 0.0]), ball_vel=np.array([3.0, 0.0]))
    for _ in range(120):
        w.step(np.zeros((0, 2)), np.zeros(0), np.zeros(0, bool), np.zeros(0))
    p, v = bm.predict((-5.0, 0.0), (3.0, 0.0), w.t, BP, sliding=True)
    assert np.allclose(p, w.ball_pos, atol=0.01) and np.allclose(v, w.ball_vel, atol=0.01)


def test_rolling_ball_decelerates_at_the_roll_rate():
    p, v = bm.predict((0.0, 0.0), (0.0, 1.0), 1.0, BP)  # rolling by default
    assert v[1] == pytest.approx(1.0 - BP.roll_decel)
    assert p[1] == pytest.approx(1.0 - BP.roll_decel / 2, abs=0.01)
    assert bm.stop_distance(1.0, BP, sliding=False, friction_dt=None) == pytest.approx(1.0 / (2 * BP.roll_decel))


def test_two_phases_continuous_closed_form():
    v0 = 5.0
    t_switch = (1 - BP.slide_to_roll_ratio) * v0 / BP.slide_decel
    assert bm.speed_at(v0, t_switch / 2, BP, friction_dt=None) == pytest.approx(v0 - BP.slide_decel * t_switch / 2)
    assert bm.speed_at(v0, t_switch + 1.0, BP, friction_dt=None) == pytest.approx(
        BP.slide_to_roll_ratio * v0 - BP.roll_decel)
    d1 = (v0 ** 2 - (BP.slide_to_roll_ratio * v0) ** 2) / (2 * BP.slide_decel)
    assert bm.distance_at(v0, t_switch, BP, friction_dt=None) == pytest.approx(d1)
    assert bm.speed_at(v0, 1e3, BP) == 0.0


def test_inverses_agree_and_vectorised_forms_match_scalar_ones():
    ts = np.linspace(0.0, 6.0, 25)
    for v0 in (1.0, 2.5, 4.0, 6.5):
        d = bm.distance_at(v0, ts, BP)
        s = bm.speed_at(v0, ts, BP)
        assert d.shape == s.shape == ts.shape
        assert np.all(np.diff(d) >= -1e-12) and np.all(np.diff(s) <= 1e-12)
        for t, dk, sk in zip(ts, d, s):
            assert dk == pytest.approx(bm.distance_at(v0, float(t), BP))
            if sk > 0.05:
                assert bm.time_to_distance(v0, dk, BP) == pytest.approx(t, abs=1e-6)
                assert bm.speed_at_distance(v0, dk, BP) == pytest.approx(sk, abs=1e-6)
    pos, vel = bm.predict((1.0, 2.0), (0.0, -3.0), ts, BP, sliding=True)
    assert pos.shape == vel.shape == (ts.size, 2)
    p5, v5 = bm.predict((1.0, 2.0), (0.0, -3.0), float(ts[5]), BP, sliding=True)
    assert np.allclose(pos[5], p5) and np.allclose(vel[5], v5)


def test_short_balls_and_the_kicker_cap():
    assert bm.time_to_distance(1.0, 10.0, BP) == math.inf
    assert bm.speed_at_distance(1.0, 10.0, BP) == 0.0
    assert bm.kick_speed_for_arrival(30.0, 2.0, BP) == pytest.approx(bm.KICK_SPEED_MAX)
    assert bm.KICK_SPEED_MAX == RP.kick_speed_max == 6.5
    # a faster arrival needs a faster kick, a longer pass too
    assert bm.kick_speed_for_arrival(3.0, 2.0, BP) > bm.kick_speed_for_arrival(3.0, 1.0, BP)
    assert bm.kick_speed_for_arrival(5.0, 1.0, BP) > bm.kick_speed_for_arrival(2.0, 1.0, BP)
    assert np.allclose(bm.stop_point((1.0, 1.0), (0.0, 0.0), BP), (1.0, 1.0))


@pytest.mark.parametrize("call,name", [
    (lambda: bm.speed_at(-1.0, 1.0, BP), "v0"),
    (lambda: bm.stop_distance(float("nan"), BP), "v0"),
    (lambda: bm.time_to_distance(2.0, float("inf"), BP), "d"),
    (lambda: bm.kick_speed_for_arrival(-1.0, 1.0, BP), "d"),
    (lambda: bm.kick_speed_for_arrival(2.0, -1.0, BP), "v_arrive"),
])
def test_bad_inputs_name_the_argument(call, name):
    with pytest.raises(ValueError, match=name):
        call()
