"""Golden wire tests of the bridge's SSL messages: bytes worked out by hand from the
protobuf wire format (tag = field_number << 3 | wire type; 0 varint, 1 64-bit,
2 length-delimited, 5 32-bit; little-endian floats), so compatibility with the SSL
tools does not rest on our schema alone. Also: varint framing, the SSL log layout,
and that regenerating the Python modules changes nothing."""

import struct

import pytest

pytest.importorskip("google.protobuf")

from ssl_marl.bridge import wire  # noqa: E402
from ssl_marl.bridge.proto import grsim_packet_pb2 as grsim_pb  # noqa: E402
from ssl_marl.bridge.proto import ssl_referee_pb2 as ref_pb  # noqa: E402
from ssl_marl.bridge.proto import ssl_simulation_pb2 as sim_pb  # noqa: E402
from ssl_marl.bridge.proto import ssl_vision_detection_pb2 as det_pb  # noqa: E402
from ssl_marl.bridge.proto import ssl_vision_tracked_pb2 as trk_pb  # noqa: E402
from ssl_marl.bridge.proto import ssl_vision_wrapper_pb2 as wrap_pb  # noqa: E402

F1 = bytes.fromhex("0000803f")  # 1.0f
F0 = bytes.fromhex("00000000")  # 0.0f
F2 = bytes.fromhex("00000040")  # 2.0f
D2 = bytes.fromhex("0000000000000040")  # 2.0 (double)

DETECTION_FRAME = bytes.fromhex("0801") + b"\x11" + D2 + b"\x19" + D2 + bytes.fromhex("2000")


def test_detection_ball_bytes():
    ball = det_pb.SSL_DetectionBall(confidence=1.0, x=100.0, y=-50.0, pixel_x=0.0, pixel_y=0.0)
    expected = (b"\x0d" + F1 + b"\x1d" + bytes.fromhex("0000c842") + b"\x25" + bytes.fromhex("000048c2")
                + b"\x35" + F0 + b"\x3d" + F0)
    assert ball.SerializeToString() == expected


def test_wrapper_with_detection_frame_bytes():
    frame = det_pb.SSL_DetectionFrame(frame_number=1, t_capture=2.0, t_sent=2.0, camera_id=0)
    assert frame.SerializeToString() == DETECTION_FRAME
    packet = wrap_pb.SSL_WrapperPacket(detection=frame)
    assert packet.SerializeToString() == b"\x0a\x16" + DETECTION_FRAME
    parsed = wrap_pb.SSL_WrapperPacket.FromString(b"\x0a\x16" + DETECTION_FRAME)
    assert parsed.detection.t_capture == 2.0 and parsed.detection.camera_id == 0


def test_detection_robot_decodes_from_hand_bytes():
    # confidence 1, robot_id 5, x 1, y 2 (mm), orientation 0, pixel 0, 0
    data = (b"\x0d" + F1 + b"\x10\x05" + b"\x1d" + F1 + b"\x25" + F2 + b"\x2d" + F0 + b"\x35" + F0 + b"\x3d" + F0)
    r = det_pb.SSL_DetectionRobot.FromString(data)
    assert (r.robot_id, r.x, r.y, r.orientation) == (5, 1.0, 2.0, 0.0)


def test_robot_control_bytes():
    msg = sim_pb.RobotControl()
    cmd = msg.robot_commands.add(id=3)
    cmd.move_command.local_velocity.forward = 1.0
    cmd.move_command.local_velocity.left = 0.0
    cmd.move_command.local_velocity.angular = 0.0
    local = b"\x0d" + F1 + b"\x15" + F0 + b"\x1d" + F0  # 15 bytes
    move = b"\x12\x0f" + local  # RobotMoveCommand.local_velocity = field 2
    command = b"\x08\x03" + b"\x12\x11" + move  # id, move_command
    assert msg.SerializeToString() == b"\x0a\x15" + command


def test_simulator_command_bytes():
    msg = sim_pb.SimulatorCommand()
    msg.control.teleport_ball.x = 1.0
    msg.control.teleport_ball.y = 2.0
    msg.control.simulation_speed = 2.0
    ball = b"\x0d" + F1 + b"\x15" + F2
    control = b"\x0a\x0a" + ball + b"\x1d" + F2
    assert msg.SerializeToString() == b"\x0a\x11" + control


def test_teleport_robot_and_response_decode():
    # TeleportRobot{id{id 2, team BLUE(2)}, x 1.0}
    data = b"\x0a\x04\x08\x02\x10\x02" + b"\x15" + F1
    tr = sim_pb.TeleportRobot.FromString(data)
    assert (tr.id.id, tr.id.team, tr.x) == (2, sim_pb.BLUE, 1.0)
    resp = sim_pb.SimulatorResponse.FromString(b"\x0a\x05\x0a\x03ABC")
    assert resp.errors[0].code == "ABC"
    # SimulatorError: code 1, unsupported_capability 2 (enum), message 3
    err = sim_pb.SimulatorError(code="A", unsupported_capability=sim_pb.SIMULATOR_CAPABILITY_MOVE_WHEEL_VELOCITY,
                                message="m")
    assert err.SerializeToString() == b"\x0a\x01A" + b"\x10\x02" + b"\x1a\x01m"


def test_robot_feedback_bytes():
    # RobotControlResponse{feedback [RobotFeedback{id RobotId{id 1, team YELLOW(1)}, dribbler_ball_contact true}]}
    resp = sim_pb.RobotControlResponse()
    fb = resp.feedback.add(dribbler_ball_contact=True)
    fb.id.id, fb.id.team = 1, sim_pb.YELLOW
    feedback = b"\x0a\x04\x08\x01\x10\x01" + b"\x10\x01"
    assert resp.SerializeToString() == b"\x12\x08" + feedback


def test_grsim_packet_bytes():
    packet = grsim_pb.grSim_Packet()
    packet.commands.timestamp = 0.0
    packet.commands.isteamyellow = True
    packet.commands.robot_commands.add(id=1, kickspeedx=0.0, kickspeedz=0.0, veltangent=1.0, velnormal=0.0,
                                       velangular=0.0, spinner=False, wheelsspeed=False)
    robot = (b"\x08\x01" + b"\x15" + F0 + b"\x1d" + F0 + b"\x25" + F1 + b"\x2d" + F0 + b"\x35" + F0
             + b"\x38\x00" + b"\x40\x00")
    assert len(robot) == 31
    commands = b"\x09" + bytes(8) + b"\x10\x01" + b"\x1a\x1f" + robot
    assert packet.SerializeToString() == b"\x0a\x2c" + commands


def test_referee_bytes():
    msg = ref_pb.Referee(packet_timestamp=1, stage=ref_pb.Referee.NORMAL_FIRST_HALF, stage_time_left=-1,
                         command=ref_pb.Referee.NORMAL_START, command_counter=3, command_timestamp=4)
    for info in (msg.yellow, msg.blue):
        info.name, info.score, info.red_cards, info.yellow_cards = "", 0, 0, 0
        info.timeouts, info.timeout_time, info.goalkeeper = 0, 0, 0
    msg.designated_position.x = 0.0
    msg.designated_position.y = 0.0
    team = bytes.fromhex("0a00" "1000" "1800" "2800" "3000" "3800" "4000")
    expected = (bytes.fromhex("0801" "1001" "1801" "2002" "2803" "3004")  # stage_time_left -1: zigzag 1
                + b"\x3a\x0e" + team + b"\x42\x0e" + team + b"\x4a\x0a\x0d" + F0 + b"\x15" + F0)
    assert msg.SerializeToString() == expected


def test_sync_request_and_tracker_bytes():
    req = sim_pb.SimulationSyncRequest(sim_step=1.0 / 60.0)
    assert req.SerializeToString() == b"\x0d" + bytes.fromhex("8988883c")
    assert trk_pb.TrackerWrapperPacket(uuid="a").SerializeToString() == b"\x0a\x01a"


def test_varint_framing():
    assert wire.encode_varint(300) == b"\xac\x02"
    assert wire.decode_varint(b"\xac\x02") == (300, 2)
    assert wire.decode_varint(b"\xac") is None
    reader = wire.FrameReader()
    data = wire.encode_frame(b"abc") + wire.encode_frame(b"x" * 200)
    assert reader.feed(data[:3]) == []
    assert reader.feed(data[3:]) == [b"abc", b"x" * 200]
    with pytest.raises(wire.FrameError):
        wire.FrameReader(max_bytes=10).feed(wire.encode_varint(11))
    with pytest.raises(wire.FrameError):
        reader.feed(b"\xff" * 11)


def test_ssl_log_layout(tmp_path):
    from ssl_marl.bridge.ssl_log import LogWriter, read_log

    path = tmp_path / "match.log"
    with LogWriter(path) as log:
        log.write_vision(5, b"ab")
        log.write_referee(6, b"")
    raw = path.read_bytes()
    assert raw[:16] == b"SSL_LOG_FILE" + b"\x00\x00\x00\x01"
    assert raw[16:32] == struct.pack(">qii", 5, 4, 2) and raw[32:34] == b"ab"
    assert [(m.timestamp_ns, m.message_type, m.payload) for m in read_log(path)] == [(5, 4, b"ab"), (6, 3, b"")]


def test_regeneration_changes_nothing():
    pytest.importorskip("grpc_tools")
    from importlib.metadata import version

    from ssl_marl.bridge import gen_proto

    if version("grpcio-tools") != gen_proto.GRPCIO_TOOLS_VERSION:
        pytest.skip(f"grpcio-tools {version('grpcio-tools')} is not the pinned {gen_proto.GRPCIO_TOOLS_VERSION}")
    assert gen_proto.changed_files() == []
