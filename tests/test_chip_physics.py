"""The ball in the air: chip flight against the drag-free projectile, clearing a robot,
the bounce sequence, the goal rule's "height since the last touch", and the batched
worlds bit-equal to single worlds with chips."""

from __future__ import annotations

import math

import numpy as np
import pytest

from ssl_marl.envs.actions import scale_actions
from ssl_marl.physics import ball_flight
from ssl_marl.physics.batched import BatchedPhysics
from ssl_marl.physics.field import FieldGeometry
from ssl_marl.physics.params import BallParams, RobotParams
from ssl_marl.physics.world import PhysicsWorld

RP, BP = RobotParams(), BallParams()
KICKER_X = -3.0
BALL0 = np.array([KICKER_X + RP.front_distance + BP.radius, 0.0])  # on the kicker's face


def _world(blocker_x: float | None = None) -> PhysicsWorld:
    n = 1 if blocker_x is None else 2
    w = PhysicsWorld(FieldGeometry.div_b(), RP, BP, n, 0)
    pose = [[KICKER_X, 0.0, 0.0]] + ([[blocker_x, 0.0, math.pi]] if blocker_x is not None else [])
    w.reset(np.array(pose), BALL0)
    return w


def _step(w: PhysicsWorld, kick: float = 0.0, chip: float = 0.0) -> None:
    n = w.n
    k = np.zeros(n)
    c = np.zeros(n)
    k[0], c[0] = kick, chip
    w.step(np.zeros((n, 2)), np.zeros(n), np.zeros(n, bool), k, c)


@pytest.mark.parametrize("deg", [10, 25, 40, 50, 60])
def test_chip_flight_distance_and_apex_match_the_drag_free_projectile(deg):
    angle = math.radians(deg)
    w = _world()
    _step(w, 1.0, angle)
    assert w.kicks_this_step and w.kicks_this_step[0][1] == pytest.approx(RP.kick_speed_max)  # 3-D speed capped
    touchdowns, apex = list(w.touchdowns), w.ball_max_height
    while not touchdowns:
        _step(w)
        touchdowns += w.touchdowns
        apex = max(apex, w.ball_max_height)
    dist_ref, apex_ref = ball_flight.projectile_reference(RP.kick_speed_max, angle, BP.gravity)
    assert touchdowns[0][0] - BALL0[0] == pytest.approx(dist_ref, rel=0.02)
    assert apex == pytest.approx(apex_ref, rel=0.02)
    assert abs(touchdowns[0][1]) < 1e-6


def test_a_chip_clears_a_robot_in_its_path_and_a_flat_kick_does_not():
    blocker = KICKER_X + 2.0  # the chip at 45 deg is ~0.8 m high there
    for chip, passes in ((math.radians(45), True), (0.0, False)):
        w = _world(blocker)
        _step(w, 1.0, chip)
        for _ in range(90):
            _step(w)
        beyond = w.ball_pos[0] > blocker + RP.radius
        assert beyond == passes, f"chip={chip}: ball at {w.ball_pos}"


def test_a_low_chip_hits_a_robot():
    w = _world(KICKER_X + 0.6)  # at 10 deg the ball is ~6 cm high there: below the robot's 0.15 m
    _step(w, 1.0, math.radians(10))
    for _ in range(60):
        _step(w)
    assert w.ball_pos[0] < KICKER_X + 0.6


def test_bounce_sequence_damps_height_and_speed_then_rolls():
    w = _world()
    _step(w, 0.8, math.radians(45))
    hops, speeds_at_bounce, heights = [], [], []
    vz_prev = w.ball_vz
    v_before = float(np.hypot(*w.ball_vel))
    for _ in range(600):
        _step(w)
        if w.touchdowns:
            speeds_at_bounce.append((v_before, float(np.hypot(*w.ball_vel))))
        v_before = float(np.hypot(*w.ball_vel))
        heights.append(w.ball_z)
        if w.ball_z == 0.0 and w.ball_vz == 0.0 and len(speeds_at_bounce) >= 3:
            break
        vz_prev = w.ball_vz
    del vz_prev
    # horizontal damping: 0.8 at the first bounce, 0.85 after (velocity at the end of the sub-step)
    assert speeds_at_bounce[0][1] / speeds_at_bounce[0][0] == pytest.approx(BP.bounce_damping_xy_first, abs=0.01)
    assert speeds_at_bounce[1][1] / speeds_at_bounce[1][0] == pytest.approx(BP.bounce_damping_xy_later, abs=0.01)
    # each hop's apex is damping_z^2 of the one before
    z = np.array(heights)
    peaks = [z[i] for i in range(1, len(z) - 1) if z[i] >= z[i - 1] and z[i] > z[i + 1] and z[i] > 0]
    assert len(peaks) >= 2
    assert peaks[1] / peaks[0] == pytest.approx(BP.bounce_damping_z ** 2, rel=0.05)
    # on the ground it rolls: the rolling deceleration, no sliding phase
    assert w.ball_z == 0.0 and w.ball_vz == 0.0
    v0 = float(np.hypot(*w.ball_vel))
    _step(w)
    assert v0 - float(np.hypot(*w.ball_vel)) == pytest.approx(BP.roll_decel / 60, rel=0.05)


def test_height_since_last_touch_and_no_dribbler_in_the_air():
    w = _world()
    _step(w, 1.0, math.radians(45))
    for _ in range(20):
        _step(w)
    assert w.ball_max_height > 0.5 and w.ball_z > 0.5
    assert not w.on_dribbler.any()
    # a teleport is a touch: the height record restarts
    w.set_ball(np.array([0.0, 0.0]))
    assert w.ball_max_height == 0.0 and w.ball_z == 0.0
    ws = w.snapshot()
    assert ws.ball_height == 0.0 and ws.ball_vz == 0.0


def test_flat_kicks_leave_the_ball_on_the_ground():
    w = _world()
    _step(w, 1.0, 0.0)
    for _ in range(30):
        _step(w)
        assert w.ball_z == 0.0 and w.ball_max_height == 0.0


def test_chip_angle_is_clipped_to_the_kicker_range():
    w = _world()
    _step(w, 1.0, 3.0)  # above chip_angle_max
    vz = w.ball_vz
    assert vz <= RP.kick_speed_max * math.sin(RP.chip_angle_max) + 1e-9


def test_set_ball_rejects_bad_heights():
    w = _world()
    for z, vz in ((float("nan"), 0.0), (-0.1, 0.0), (0.0, float("inf"))):
        with pytest.raises(ValueError, match="z must be finite"):
            w.set_ball(np.zeros(2), None, z, vz)


def test_bad_ball_flight_parameters_are_refused():
    with pytest.raises(ValueError, match="bounce_damping_z"):
        BallParams(bounce_damping_z=1.2)
    with pytest.raises(ValueError, match="chip_angle_max"):
        RobotParams(chip_angle_max=2.0)


def test_batched_worlds_with_chips_are_bit_equal_to_single_worlds():
    f, rp, bp = FieldGeometry.div_b(), RP, BP
    K, nb, ny = 3, 2, 2
    n = nb + ny
    singles = [PhysicsWorld(f, rp, bp, nb, ny) for _ in range(K)]
    batch = BatchedPhysics(f, rp, bp, nb, ny, K)
    rng = np.random.default_rng(7)
    for k in range(K):
        pose = rng.uniform(-0.8, 0.8, (n, 3))
        pose[0] = (0.0, 0.0, rng.uniform(-3, 3))
        ball = 0.1015 * np.array([np.cos(pose[0, 2]), np.sin(pose[0, 2])])
        singles[k].reset(pose, ball)
        batch.reset_world(k, pose, ball)
    chips = 0
    for step in range(400):
        d = batch.ball_pos[:, None, :] - batch.pos
        ang = np.angle(np.exp(1j * (np.arctan2(d[..., 1], d[..., 0]) - batch.heading)))
        a = rng.uniform(-1, 1, (K, n, 5)) * 0.3
        a[..., 0] += np.cos(ang) * 0.7
        a[..., 1] += np.sin(ang) * 0.7
        a[..., 2] += np.clip(ang, -1, 1)
        a[..., 3] = 1.0
        a[..., 4] = np.where(rng.random((K, n)) < 0.08, rng.uniform(0.3, 1.0, (K, n)), -1.0)
        chip = np.where(rng.random((K, n)) < 0.6, rng.uniform(0.0, 1.0, (K, n)), 0.0)
        for k in range(K):
            v, w, dr, kk = scale_actions(a[k], rp)
            singles[k].step(v, w, dr, kk, chip[k])
            chips += any(chip[k][i] > 0 for i, _ in singles[k].kicks_this_step)
        v, w, dr, kk = scale_actions(a.reshape(-1, 5), rp)
        batch.step(v.reshape(K, n, 2), w.reshape(K, n), dr.reshape(K, n), kk.reshape(K, n), chip=chip)
        for k in range(K):
            s = singles[k]
            for name in ("pos", "heading", "vel", "omega", "ball_pos", "ball_vel", "on_dribbler", "kick_cooldown"):
                np.testing.assert_array_equal(getattr(s, name), getattr(batch, name)[k], err_msg=f"{name} step {step}")
            bw = batch.worlds[k]
            assert (s.ball_z, s.ball_vz, s.ball_max_height) == (bw.ball_z, bw.ball_vz, bw.ball_max_height), step
            assert batch.snapshot(k).ball_height == s.snapshot().ball_height
    assert chips >= 3


def test_kick_on_contact_redirects_a_moving_ball_and_is_off_by_default():
    """A robot facing the target with its kicker armed meets a pass: with kick_on_contact
    the ball leaves along the robot's heading at the kick speed; without it the ball
    bounces off the face."""
    import dataclasses

    for on in (True, False):
        rp = dataclasses.replace(RP, kick_on_contact=on)
        w = PhysicsWorld(FieldGeometry.div_b(), rp, BP, 1, 0)
        heading = math.pi - 0.5  # rad: the ball comes from -x; the robot faces it, turned 0.5 rad
        face_y = RP.front_distance * math.sin(heading)
        w.reset(np.array([[0.0, 0.0, heading]]), np.array([-2.0, face_y]), ball_vel=np.array([4.0, 0.0]))
        fired_at = None
        for step in range(90):
            w.step(np.zeros((1, 2)), np.zeros(1), np.zeros(1, bool), np.array([0.8]), np.zeros(1))
            if w.kicks_this_step and fired_at is None:
                fired_at = step
        if on:
            assert fired_at is not None
            v = w.ball_vel
            assert math.atan2(v[1], v[0]) == pytest.approx(heading, abs=0.05)
        else:
            assert fired_at is None or w.ball_vel[0] < 0  # no redirect along the heading


def test_batched_kick_on_contact_is_bit_equal_to_single_worlds():
    import dataclasses

    rp = dataclasses.replace(RP, kick_on_contact=True)
    f, K, n = FieldGeometry.div_b(), 3, 2
    singles = [PhysicsWorld(f, rp, BP, n, 0) for _ in range(K)]
    batch = BatchedPhysics(f, rp, BP, n, 0, K)
    rng = np.random.default_rng(11)
    for k in range(K):
        h = math.pi + rng.uniform(-0.6, 0.6)
        pose = np.array([[0.0, 0.0, h], [1.5, 1.0, 0.0]])
        ball = np.array([-2.0, RP.front_distance * math.sin(h) + rng.uniform(-0.01, 0.01)])
        vel = np.array([rng.uniform(2.0, 5.0), 0.0])
        singles[k].reset(pose, ball, vel)
        batch.reset_world(k, pose, ball, vel)
    fired = 0
    for step in range(120):
        kick = np.where(rng.random((K, n)) < 0.7, rng.uniform(0.3, 1.0, (K, n)), 0.0)
        chip = np.where(rng.random((K, n)) < 0.3, 0.5, 0.0)
        v = rng.uniform(-0.05, 0.05, (K, n, 2))
        for k in range(K):
            singles[k].step(v[k], np.zeros(n), np.zeros(n, bool), kick[k], chip[k])
            fired += len(singles[k].kicks_this_step)
        batch.step(v, np.zeros((K, n)), np.zeros((K, n), bool), kick, chip=chip)
        for k in range(K):
            s = singles[k]
            for name in ("pos", "heading", "vel", "omega", "ball_pos", "ball_vel", "on_dribbler", "kick_cooldown"):
                np.testing.assert_array_equal(getattr(s, name), getattr(batch, name)[k], err_msg=f"{name} step {step}")
            assert (s.kicks_this_step[0] if s.kicks_this_step else (-1, 0.0)) == (batch.kicker[k], batch.kick_speed[k])
    assert fired >= 3


def _fly(speed: float, angle: float, until_m: float) -> list[tuple[float, float, float]]:
    """(distance from the launch (m), height (m), horizontal speed (m/s)) of a chip kicked
    in the world at ``speed`` (m/s, 3-D) and ``angle`` (rad), every step until ``until_m``."""
    w = _world()
    _step(w, speed / RP.kick_speed_max, angle)
    path = []
    while float(w.ball_pos[0] - BALL0[0]) < until_m and len(path) < 600:
        path.append((float(w.ball_pos[0] - BALL0[0]), float(w.ball_z), float(np.hypot(*w.ball_vel))))
        _step(w)
    return path


def test_chip_hops_predicts_where_the_world_s_ball_hops_below_the_dribbler_bar():
    from ssl_marl.skills.chip_pass import chip_hops

    for speed, deg in ((5.0, 40.0), (6.5, 25.0), (4.0, 55.0)):
        x_low, _, v_low = chip_hops(speed, math.radians(deg), BP)
        path = _fly(speed, math.radians(deg), float(x_low) + 1.0)
        assert all(z <= BP.radius + 1e-9 for x, z, _ in path if x >= float(x_low))  # below the bar from there on
        assert any(z > BP.radius for x, z, _ in path if float(x_low) - 0.6 < x < float(x_low))  # the hop before: above
        after = [v for x, _, v in path if float(x_low) + 0.05 < x < float(x_low) + 0.5]
        assert after and max(after) == pytest.approx(float(v_low), abs=0.05)


@pytest.mark.parametrize("receiver", [3.5, 4.0, 4.5])
def test_a_receivable_chip_reaches_the_receiver_low_and_slow_the_fastest_chip_does_not(receiver):
    from ssl_marl.skills.chip_pass import CHIP_GROUND_RUN, chip_kick

    blocker, cap = 1.5, 3.0
    run = []
    for arrive in (cap, None):
        k = chip_kick(blocker, receiver, RP, BP, arrive_speed_max=arrive)
        path = _fly(k.speed, k.angle, receiver)
        run.append([(z, v) for x, z, v in path if receiver - CHIP_GROUND_RUN <= x <= receiver])
        assert run[-1]
    assert max(z for z, _ in run[0]) <= BP.radius + 1e-9  # below the dribbler bar over the last run
    assert max(v for _, v in run[0]) <= cap + 0.05
    # the shortest flight still hops above the bar there, or comes faster
    assert max(z for z, _ in run[1]) > BP.radius or max(v for _, v in run[1]) > cap + 0.3


def test_receivable_chip_arguments_are_checked():
    from ssl_marl.plays.attack_decision import AttackParams
    from ssl_marl.skills.chip_pass import chip_kick

    with pytest.raises(ValueError, match="m/s fast"):
        chip_kick(1.0, 2.5, RP, BP, arrive_speed_max=3.0)  # too short for the hops to die down
    for bad in (0.0, -1.0, math.nan, math.inf):
        with pytest.raises(ValueError, match="chip_arrive_speed"):
            AttackParams(restart_chip_arrive_speed=bad)
