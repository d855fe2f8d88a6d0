"""Chip kicks through the bridge: a client's chip (simulation protocol ``kick_speed`` +
``kick_angle``, grSim ``kickspeedx`` + ``kickspeedz``) flies as the drag-free projectile
says, a kick beyond the kicker is clipped with a ``VALUE_CLIPPED`` error, vision and
tracker packets carry the ball's height, grSim's robot status reports the chip, and
every team kind of ours drives robots through the bridge's world."""

import math
import socket
import time

import numpy as np
import pytest

pytest.importorskip("google.protobuf")

from bridge_helpers import LOOP, loopback_server  # noqa: E402

from ssl_marl.bridge.client import PlayBrain  # noqa: E402
from ssl_marl.bridge.command_codec import encode_grsim_packet  # noqa: E402
from ssl_marl.bridge.proto import grsim_packet_pb2 as grsim_pb  # noqa: E402
from ssl_marl.bridge.proto import ssl_simulation_pb2 as sim_pb  # noqa: E402
from ssl_marl.bridge.proto import ssl_vision_tracked_pb2 as trk_pb  # noqa: E402
from ssl_marl.bridge.tracker_codec import tracker_packet  # noqa: E402
from ssl_marl.bridge.transport import UdpReceiver  # noqa: E402
from ssl_marl.bridge.vision_codec import detection_frames, merge_frames  # noqa: E402
from ssl_marl.bridge.world import BridgeWorld, WorldConfig  # noqa: E402
from ssl_marl.envs.camera import CameraRig  # noqa: E402
from ssl_marl.physics.ball_flight import projectile_reference  # noqa: E402
from ssl_marl.runners.controllers import TEAM_KINDS  # noqa: E402

ROBOT_X = -1.0  # blue 0 stands here facing +x; the ball lies on its kicker face


def _kicker_ready(world: BridgeWorld) -> float:
    """Blue robot 0 at (ROBOT_X, 0) facing +x with the ball on its face; the ball's x (m)."""
    ctl = sim_pb.SimulatorCommand()
    tr = ctl.control.teleport_robot.add(x=ROBOT_X, y=0.0, orientation=0.0)
    tr.id.id, tr.id.team = 0, sim_pb.BLUE
    rp = world.robot
    ctl.control.teleport_ball.x = ROBOT_X + rp.front_distance + world.ball.radius + 0.002
    ctl.control.teleport_ball.y = 0.0
    assert world.simulator_command(ctl) == []
    return float(world.env.world_state().ball_pos[0])


def _robot_command(speed: float, angle_deg: float) -> sim_pb.RobotControl:
    control = sim_pb.RobotControl()
    cmd = control.robot_commands.add(id=0, kick_speed=speed, kick_angle=angle_deg)
    lv = cmd.move_command.local_velocity
    lv.forward, lv.left, lv.angular = 0.0, 0.0, 0.0
    return control


def _grsim_command(x: float, z: float) -> grsim_pb.grSim_Packet:
    packet = grsim_pb.grSim_Packet()
    packet.commands.timestamp = 0.0
    packet.commands.isteamyellow = False
    packet.commands.robot_commands.add(id=0, kickspeedx=x, kickspeedz=z, veltangent=0.0, velnormal=0.0,
                                       velangular=0.0, spinner=False, wheelsspeed=False)
    return packet


def _fly(world: BridgeWorld, steps: int = 60) -> tuple[list, list]:
    """Step the world; (first touchdown (x, y) or None, [(vision z mm, tracker z m, tracker vz m/s)] per
    step while the ball is above the ground)."""
    touchdowns, airborne = [], []
    for _ in range(steps):
        world.step(0)
        touchdowns += world.env.physics.touchdowns
        if world.env.world_state().ball_height > 0.0:
            z_mm = [b.z for f in world.detections(0.0, 0.0) for b in f.balls]
            trk = world.tracker(0.0, "u").tracked_frame.balls[0]
            airborne.append((z_mm[0], trk.pos.z, trk.vel.z))
    return (touchdowns[0] if touchdowns else None), airborne


def _check_flight(world: BridgeWorld, x0: float, speed: float, angle: float) -> None:
    touchdown, airborne = _fly(world)
    distance, apex = projectile_reference(speed, angle, world.ball.gravity)
    assert world.env.world_state().ball_max_height == pytest.approx(apex, rel=0.02)
    assert touchdown is not None and touchdown[0] - x0 == pytest.approx(distance, abs=0.02)
    assert len(airborne) > 10 and max(a[0] for a in airborne) == pytest.approx(1000.0 * apex, rel=0.05)
    assert all(a[0] > 0.0 and a[1] > 0.0 for a in airborne)  # vision z (mm), tracker pos.z (m)
    assert max(a[2] for a in airborne) > 0.5 > -0.5 > min(a[2] for a in airborne)  # tracker vel.z up, then down
    assert world.take_kicks("blue") == {0: "chip"}


def test_sim_protocol_chip_flies_the_projectile():
    world = BridgeWorld(WorldConfig(robots=1, seconds=10.0))
    x0 = _kicker_ready(world)
    assert world.robot_control("blue", _robot_command(4.0, 45.0)) == []
    _check_flight(world, x0, 4.0, math.radians(45.0))


def test_grsim_chip_flies_the_projectile():
    world = BridgeWorld(WorldConfig(robots=1, seconds=10.0))
    x0 = _kicker_ready(world)
    a = math.radians(45.0)
    team, errors = world.grsim_packet(_grsim_command(4.0 * math.cos(a), 4.0 * math.sin(a)))
    assert team == "blue" and errors == []
    _check_flight(world, x0, 4.0, a)


def test_a_chip_above_the_cap_kicks_at_the_cap_with_an_error():
    world = BridgeWorld(WorldConfig(robots=1, seconds=10.0))
    cap = world.robot.chip_angle_max
    x0 = _kicker_ready(world)
    errors = world.robot_control("blue", _robot_command(4.0, 75.0))
    assert [e.code for e in errors] == ["VALUE_CLIPPED"] and "kick_angle" in errors[0].message
    assert world.stats["error:VALUE_CLIPPED"] == 1
    _check_flight(world, x0, 4.0, cap)

    world = BridgeWorld(WorldConfig(robots=1, seconds=10.0))
    x0 = _kicker_ready(world)
    _, errors = world.grsim_packet(_grsim_command(1.0, 3.0))  # 71.6 deg
    assert [e.code for e in errors] == ["VALUE_CLIPPED"] and "kickspeedz" in errors[0].message
    _check_flight(world, x0, math.hypot(1.0, 3.0), cap)


def test_a_kick_above_the_kicker_speed_is_clipped_with_an_error():
    world = BridgeWorld(WorldConfig(robots=1, seconds=10.0))
    errors = world.robot_control("blue", _robot_command(9.0, 30.0))
    assert [e.code for e in errors] == ["VALUE_CLIPPED"] and "kick_speed" in errors[0].message
    assert world.commands["blue"][0, 4] == 1.0 and world.commands["blue"][0, 5] == pytest.approx(0.5)
    errors = world.robot_control("blue", _robot_command(3.0, -10.0))
    assert [e.code for e in errors] == ["VALUE_CLIPPED"] and world.commands["blue"][0, 5] == 0.0  # flat


@pytest.mark.parametrize("angle", [float("nan"), float("inf"), -float("inf")])
def test_non_finite_kick_angle_is_refused(angle):
    world = BridgeWorld(WorldConfig(robots=1, seconds=10.0))
    errors = world.robot_control("blue", _robot_command(4.0, angle))
    assert [(e.code, e.message) for e in errors] == [("INVALID_VALUE", "robot 0: non-finite field")]
    assert not np.isfinite(world.command_time["blue"][0])  # nothing stored


def test_vision_and_tracker_heights_follow_the_camera_model():
    world = BridgeWorld(WorldConfig(robots=1, seconds=10.0))
    _kicker_ready(world)
    world.robot_control("blue", _robot_command(4.0, 45.0))
    for _ in range(15):
        world.step(0)
    truth = world.env.world_state()
    assert truth.ball_height > 0.2
    frames = detection_frames(truth, world.regions, [0], 0.0, 0.0)
    assert frames[0].balls[0].z == pytest.approx(1000.0 * truth.ball_height, rel=1e-6)
    seen = CameraRig(world.field, world.ball.radius).observe(truth)  # a realistic camera: projected, no height
    ball = detection_frames(seen, world.regions, [0], 0.0, 0.0)[0].balls[0]
    assert ball.z == 0.0 and ball.x == pytest.approx(1000.0 * seen.ball_pos[0], rel=1e-6)
    assert abs(seen.ball_pos[0] - truth.ball_pos[0]) > 0.01
    packet = trk_pb.TrackerWrapperPacket.FromString(tracker_packet(truth, 1, 0.0, "u").SerializeToString())
    ball = packet.tracked_frame.balls[0]
    assert ball.pos.z == pytest.approx(truth.ball_height, rel=1e-6)
    assert ball.vel.z == pytest.approx(truth.ball_vz, rel=1e-6)


def test_grsim_status_reports_the_chip():
    status_in = UdpReceiver((LOOP, 0))
    server, vision, referee = loopback_server(WorldConfig(robots=1, seconds=30.0), speed=4.0,
                                              grsim_status_ports=(status_in.port, status_in.port))
    _kicker_ready(server.world)
    a = math.radians(45.0)
    payload = _grsim_command(4.0 * math.cos(a), 4.0 * math.sin(a)).SerializeToString()
    thread = server.start(max_wall_s=30)
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    chips, flats = 0, 0
    try:
        deadline = time.monotonic() + 10
        while time.monotonic() < deadline and not chips:
            sock.sendto(payload, (LOOP, server.ports["grsim"]))
            time.sleep(0.02)
            for data, _ in status_in.receive():
                status = grsim_pb.grSim_Robots_Status.FromString(data)
                chips += sum(r.chip_kick for r in status.robots_status)
                flats += sum(r.flat_kick for r in status.robots_status)
    finally:
        sock.close()
        server.stop()
        thread.join(10)
        server.close()
        for s in (vision, referee, status_in):
            s.close()
    assert chips == 1 and flats == 0


def test_a_world_without_chip_kicks_kicks_client_chips_flat():
    world = BridgeWorld(WorldConfig(robots=1, seconds=10.0, chip_kicks=False))
    assert world.action_dim == 5
    errors = world.robot_control("blue", _robot_command(4.0, 45.0))
    assert [e.code for e in errors] == ["CHIP_KICK_UNSUPPORTED"] and world.commands["blue"].shape == (1, 5)
    with pytest.raises(ValueError, match="chip_kicks"):
        BridgeWorld(WorldConfig(robots=1, chip_kicks=False, blue_team="attack-baseline"))


@pytest.mark.parametrize("kind", [k for k in TEAM_KINDS if k != "idle"])
def test_every_team_kind_drives_robots_through_the_bridge(kind):
    world = BridgeWorld(WorldConfig(robots=2, seconds=2.0, blue_team=kind, yellow_team="attack-baseline"))
    start = world.env.world_state()
    for _ in range(20):
        world.step(0)
    now = world.env.world_state()
    assert np.abs(now.blue.pos - start.blue.pos).max() > 0.01
    assert np.abs(now.yellow.pos - start.yellow.pos).max() > 0.01


def test_a_chipping_play_client_sends_chips():
    brain = PlayBrain("blue", "attack-baseline", 2)
    world = BridgeWorld(WorldConfig(robots=2, seconds=2.0))
    actions = None
    for _ in range(5):
        det = merge_frames(world.detections(world.t + 1.0, world.t + 1.0))
        actions = brain.decide(det) or actions
        control = brain.robot_control(actions)
        assert world.robot_control("blue", control) == []
        world.step(0)
    assert all(a.shape == (6,) for a in actions.values())
    chip = {0: np.array([0.0, 0.0, 0.0, -1.0, 0.6, 0.75], np.float32)}
    cmd = encode_grsim_packet(chip, False, 0.0, brain.robot).commands.robot_commands[0]
    elevation = 0.75 * brain.robot.chip_angle_max
    assert math.degrees(math.atan2(cmd.kickspeedz, cmd.kickspeedx)) == pytest.approx(math.degrees(elevation), rel=1e-5)
    assert math.hypot(cmd.kickspeedx, cmd.kickspeedz) == pytest.approx(0.6 * brain.robot.kick_speed_max, rel=1e-5)
