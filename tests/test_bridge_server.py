"""The bridge server over loopback: lock-step (determinism, INVALID_STEP), simulator
control (teleports, a forced goal, errors), robot commands and feedback (simulation
protocol and grSim), and the serve/play command-line parsers."""

import argparse
import socket

import numpy as np
import pytest

pytest.importorskip("google.protobuf")

from bridge_helpers import LOOP, loopback_server, receive_at_least  # noqa: E402

from ssl_marl.bridge.client import PlayBrain, run_lockstep_match  # noqa: E402
from ssl_marl.bridge.lockstep import LockstepClient, whole_periods  # noqa: E402
from ssl_marl.bridge.proto import grsim_packet_pb2 as grsim_pb  # noqa: E402
from ssl_marl.bridge.proto import ssl_referee_pb2 as ref_pb  # noqa: E402
from ssl_marl.bridge.proto import ssl_simulation_pb2 as sim_pb  # noqa: E402
from ssl_marl.bridge.proto import ssl_vision_wrapper_pb2 as wrap_pb  # noqa: E402
from ssl_marl.bridge.world import BridgeWorld, WorldConfig  # noqa: E402

DT = 1.0 / 60.0


def _lockstep_match(seed: int, seconds: float = 4.0):
    server, vision, referee = loopback_server(WorldConfig(robots=2, seconds=seconds, seed=seed), lockstep=True)
    thread = server.start(max_wall_s=120)
    brains = {t: PlayBrain(t, "baseline", 2, seed=seed) for t in ("blue", "yellow")}
    try:
        steps = run_lockstep_match({t: (LOOP, server.ports[f"sync_{t}"]) for t in brains}, brains)
    finally:
        server.stop()
        thread.join(10)
        server.close()
        vision.close()
        referee.close()
    ws = server.world.env.world_state()
    return steps, ws.ball_pos.tolist(), ws.blue.pos.tolist(), ws.yellow.pos.tolist(), dict(server.world.env.score)


def test_lockstep_match_is_deterministic():
    a = _lockstep_match(3)
    assert a[0] == int(round(4.0 / DT))
    assert a == _lockstep_match(3)


def test_whole_periods():
    assert whole_periods(np.float32(1 / 60), DT) == 1
    assert whole_periods(0.05, DT) == 3
    assert whole_periods(0.0, DT) == 0
    assert whole_periods(0.01, DT) is None
    assert whole_periods(float("nan"), DT) is None
    assert whole_periods(-DT, DT) is None


def test_invalid_step_and_garbage_over_tcp():
    server, vision, referee = loopback_server(WorldConfig(robots=1, seconds=2.0), lockstep=True)
    thread = server.start(max_wall_s=60)
    try:
        client = LockstepClient((LOOP, server.ports["sync_blue"]))
        resp = client.step(0.01)
        assert resp.robot_control_response.errors[0].code == "INVALID_STEP"
        assert server.world.t == 0.0
        resp = client.step(2 * DT)
        assert len(resp.detection) == 2 and not resp.robot_control_response.errors
        client.send_raw(b"\x03\xff\xff\xff")  # a frame that is not a request
        assert client.receive().robot_control_response.errors[0].code == "PARSE_ERROR"
        assert len(client.step(DT).detection) == 1
        client.close()
    finally:
        server.stop()
        thread.join(10)
        server.close()
        vision.close()
        referee.close()
    assert server.world.valid()


def _udp(port: int, payload: bytes, reply: bool = True) -> bytes | None:
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    sock.settimeout(5.0)
    try:
        sock.sendto(payload, (LOOP, port))
        return sock.recvfrom(65507)[0] if reply else None
    finally:
        sock.close()


@pytest.fixture
def served():
    server, vision, referee = loopback_server(WorldConfig(robots=2, seconds=60.0), speed=4.0)
    thread = server.start(max_wall_s=60)
    yield server, vision, referee
    server.stop()
    thread.join(10)
    server.close()
    vision.close()
    referee.close()


def test_teleport_forces_a_goal_and_the_referee_reports_it(served):
    server, vision, referee = served
    cmd = sim_pb.SimulatorCommand()
    tb = cmd.control.teleport_ball
    tb.x, tb.y, tb.vx, tb.vy = 4.4, 0.35, 2.0, 0.0  # past the keeper into yellow's goal: blue scores
    resp = sim_pb.SimulatorResponse.FromString(_udp(server.ports["control"], cmd.SerializeToString()))
    assert not resp.errors
    import time

    deadline = time.monotonic() + 20
    scored = None
    while time.monotonic() < deadline and scored is None:
        for data, _ in referee.receive():
            msg = ref_pb.Referee.FromString(data)
            if msg.blue.score == 1:
                scored = msg
        time.sleep(0.02)
    assert scored is not None and scored.yellow.score == 0
    assert scored.command in (ref_pb.Referee.PREPARE_KICKOFF_YELLOW, ref_pb.Referee.NORMAL_START)
    packets = [wrap_pb.SSL_WrapperPacket.FromString(d) for d, _ in vision.receive()]
    assert any(p.HasField("geometry") for p in packets) or server.world.t < 3.0
    assert any(p.HasField("detection") for p in packets)


def test_simulator_errors_for_unsupported_requests(served):
    server, _, _ = served
    cmd = sim_pb.SimulatorCommand()
    cmd.control.teleport_ball.z = 1.0
    tr = cmd.control.teleport_robot.add(x=float("nan"))
    tr.id.id, tr.id.team = 0, sim_pb.BLUE
    tr = cmd.control.teleport_robot.add(x=0.0)
    tr.id.id, tr.id.team = 7, sim_pb.YELLOW
    cmd.control.simulation_speed = -1.0
    cmd.config.robot_specs.add().id.id = 0
    resp = sim_pb.SimulatorResponse.FromString(_udp(server.ports["control"], cmd.SerializeToString()))
    codes = {e.code for e in resp.errors}
    assert {"BALL_HEIGHT_UNSUPPORTED", "INVALID_VALUE", "UNKNOWN_ROBOT", "ROBOT_SPECS_UNSUPPORTED"} <= codes
    garbage = sim_pb.SimulatorResponse.FromString(_udp(server.ports["control"], b"\xff\x00garbage"))
    assert garbage.errors[0].code == "PARSE_ERROR"
    assert server.world.valid()


def test_robot_commands_move_robots_and_get_feedback(served):
    server, _, _ = served
    control = sim_pb.RobotControl()
    cmd = control.robot_commands.add(id=1)
    cmd.move_command.global_velocity.x = 0.0
    cmd.move_command.global_velocity.y = 1.0
    cmd.move_command.global_velocity.angular = 0.0
    bad = control.robot_commands.add(id=9)
    nan = control.robot_commands.add(id=0)
    nan.move_command.local_velocity.forward = float("nan")
    nan.move_command.local_velocity.left = 0.0
    nan.move_command.local_velocity.angular = 0.0
    del bad
    y0 = float(server.world.env.world_state().blue.pos[1, 1])
    import time

    for _ in range(20):
        resp = sim_pb.RobotControlResponse.FromString(_udp(server.ports["blue"], control.SerializeToString()))
        time.sleep(0.01)
    assert {e.code for e in resp.errors} == {"UNKNOWN_ROBOT", "INVALID_VALUE"}
    assert [(f.id.id, f.id.team) for f in resp.feedback] == [(0, sim_pb.BLUE), (1, sim_pb.BLUE)]
    assert resp.feedback[0].HasField("dribbler_ball_contact")
    assert float(server.world.env.world_state().blue.pos[1, 1]) > y0 + 0.05


def test_grsim_commands_and_replacement():
    world = BridgeWorld(WorldConfig(robots=2, seconds=10.0, client_teams=("yellow",)))
    packet = grsim_pb.grSim_Packet()
    packet.commands.timestamp = 0.0
    packet.commands.isteamyellow = False
    packet.commands.robot_commands.add(id=0, kickspeedx=0, kickspeedz=0, veltangent=1, velnormal=0, velangular=0,
                                       spinner=False, wheelsspeed=False)
    team, errors = world.grsim_packet(packet)
    assert team == "blue" and errors[0].code == "WRONG_TEAM"
    packet.commands.isteamyellow = True
    packet.commands.robot_commands[0].kickspeedz = 2.0  # a chip: 2 m/s up, no forward part -> at the cap
    team, errors = world.grsim_packet(packet)
    assert team == "yellow" and [e.code for e in errors] == ["VALUE_CLIPPED"]
    assert world.commands["yellow"][0, 5] == 1.0  # the steepest chip
    rep = grsim_pb.grSim_Packet()
    rep.replacement.ball.x, rep.replacement.ball.y = 1.0, -1.0
    rep.replacement.robots.add(x=-1.0, y=1.0, dir=90.0, id=1, yellowteam=False)
    _, errors = world.grsim_packet(rep)
    assert not errors
    ws = world.env.world_state()
    assert np.allclose(ws.ball_pos, [1.0, -1.0]) and np.allclose(ws.blue.pos[1], [-1.0, 1.0])
    assert abs(ws.blue.heading[1] - np.pi / 2) < 1e-6


def test_serve_and_play_parsers():
    from ssl_marl.bridge.commands import play, serve

    parser = argparse.ArgumentParser()
    sub = parser.add_subparsers()
    serve.register(sub)
    play.register(sub)
    args = parser.parse_args(["serve", "--vision", "127.0.0.1:1", "--vision", "127.0.0.1:2", "--lockstep"])
    assert args.handler is serve.run and args.vision == ["127.0.0.1:1", "127.0.0.1:2"] and args.lockstep
    args = parser.parse_args(["play", "--team", "yellow", "--protocol", "grsim", "--vision", "127.0.0.1:3"])
    assert args.handler is play.run and args.team == "yellow" and args.protocol == "grsim"


def test_tracker_stream_and_several_vision_addresses():
    from ssl_marl.bridge.proto import ssl_vision_tracked_pb2 as trk_pb
    from ssl_marl.bridge.transport import UdpReceiver

    tracker, second = UdpReceiver((LOOP, 0)), UdpReceiver((LOOP, 0))
    server, vision, referee = loopback_server(WorldConfig(robots=2, seconds=5.0, realism="realistic", n_cameras=4,
                                                          tracker=True), tracker=(f"{LOOP}:{tracker.port}",))
    server.vision_out.destinations.append((LOOP, second.port))
    try:
        for _ in range(5):
            server.advance()
        packets = [trk_pb.TrackerWrapperPacket.FromString(d) for d, _ in receive_at_least(tracker, 5)]
        assert len(packets) >= 5 and len(packets[-1].tracked_frame.robots) == 4
        first, other = receive_at_least(vision, 5 * 4), receive_at_least(second, 5 * 4)
        assert min(len(first), len(other)) >= 5 * 4  # four cameras per period, both addresses
    finally:
        server.close()
        for s in (vision, referee, tracker, second):
            s.close()


def test_play_command_runs_on_loopback(capsys):
    from ssl_marl.bridge.commands import play

    parser = argparse.ArgumentParser()
    play.register(parser.add_subparsers())
    args = parser.parse_args(["play", "--robots", "2", "--vision", f"{LOOP}:0", "--referee", f"{LOOP}:0",
                              "--simulator", f"{LOOP}:9", "--max-wall-s", "0.3"])
    assert args.handler(args) == 0
    assert "sent 0 command packets" in capsys.readouterr().out  # no simulator: nothing seen, nothing sent


def test_play_command_in_lockstep_against_a_served_team(capsys):
    from ssl_marl.bridge.commands import play

    server, vision, referee = loopback_server(WorldConfig(robots=2, seconds=1.0, yellow_team="baseline"),
                                              lockstep=True)
    thread = server.start(max_wall_s=60)
    parser = argparse.ArgumentParser()
    play.register(parser.add_subparsers())
    args = parser.parse_args(["play", "--robots", "2", "--lockstep", f"{LOOP}:{server.ports['sync_blue']}"])
    try:
        assert args.handler(args) == 0
    finally:
        server.stop()
        thread.join(10)
        server.close()
        vision.close()
        referee.close()
    assert "played 60 lock-step periods" in capsys.readouterr().out
    assert server.world.stats["commands:blue"] > 0 and server.world.finished
