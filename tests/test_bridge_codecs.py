"""Bridge codecs: cameras and merging, commands <-> actions, referee commands, tracker packets."""

import numpy as np
import pytest

pytest.importorskip("google.protobuf")

from ssl_marl.bridge.command_codec import decode_robot_command, encode_robot_control  # noqa: E402
from ssl_marl.bridge.proto import ssl_referee_pb2 as ref_pb  # noqa: E402
from ssl_marl.bridge.proto import ssl_vision_tracked_pb2 as trk_pb  # noqa: E402
from ssl_marl.bridge.referee_codec import RefereeState  # noqa: E402
from ssl_marl.bridge.tracker_codec import tracker_packet  # noqa: E402
from ssl_marl.bridge.vision_codec import (camera_regions, detection_frames, field_from_geometry,  # noqa: E402
                                          geometry_data, merge_frames)
from ssl_marl.physics.field import FieldGeometry  # noqa: E402
from ssl_marl.physics.params import BallParams, RobotParams  # noqa: E402
from ssl_marl.physics.state import WorldState, make_team_state  # noqa: E402


def _world(ball=(0.02, 0.0)):
    blue = make_team_state([[-1.0, 0.5], [0.01, -0.2]], [0.3, -3.0], np.zeros((2, 2)), [0, 0], [False, False],
                           [True, True])
    yellow = make_team_state([[2.0, 1.0]], [3.1], np.zeros((1, 2)), [0], [False], [True])
    return WorldState(t=1.0, ball_pos=np.array(ball), ball_vel=np.array([1.0, 0.0]), blue=blue, yellow=yellow)


@pytest.mark.parametrize("n", [1, 2, 4, 8])
def test_cameras_cover_the_field_and_merge_back(n):
    field = FieldGeometry.div_b()
    regions = camera_regions(field, n)
    frames = detection_frames(_world(), regions, [0] * n, 10.0, 10.0)
    assert [f.camera_id for f in frames] == list(range(n))
    if n > 1:  # the ball at the centre lies in every camera's overlap
        assert sum(len(f.balls) for f in frames) > 1
    det = merge_frames(frames)
    assert np.allclose(det.ball, [0.02, 0.0], atol=1e-6)
    assert set(det.blue) == {0, 1} and set(det.yellow) == {0}
    assert np.allclose(det.blue[1], (0.01, -0.2, -3.0), atol=1e-5)
    assert abs(abs(det.yellow[0][2]) - 3.1) < 1e-5


def test_geometry_round_trip():
    field = FieldGeometry.div_a()
    back = field_from_geometry(geometry_data(field, RobotParams(), BallParams()))
    assert (back.length, back.width, back.goal_width, back.defense_depth) == (12.0, 9.0, 1.8, 1.8)


def test_robot_command_round_trip():
    robot = RobotParams()
    action = np.array([0.5, -0.25, 0.1, 1.0, 0.5], np.float32)
    msg = encode_robot_control({3: action}, robot)
    back, errors = decode_robot_command(msg.robot_commands[0], 0.0, robot)
    assert not errors and np.allclose(back[:5], action, atol=1e-6) and back[5] == 0.0  # flat
    chip = np.array([0.0, 0.0, 0.0, -1.0, 0.8, 0.5], np.float32)  # 5.2 m/s at half the chip cap
    msg = encode_robot_control({0: chip}, robot)
    assert msg.robot_commands[0].kick_angle == pytest.approx(np.degrees(0.5 * robot.chip_angle_max), rel=1e-6)
    back, errors = decode_robot_command(msg.robot_commands[0], 0.0, robot)
    assert not errors and np.allclose(back, chip, atol=1e-6)
    cmd = msg.robot_commands[0]
    cmd.move_command.global_velocity.x = 1.0  # field frame: +x is the robot's left when it faces -y
    cmd.move_command.global_velocity.y = 0.0
    cmd.move_command.global_velocity.angular = 0.0
    back, _ = decode_robot_command(cmd, -np.pi / 2, robot)
    assert np.allclose(back[:2], [0.0, 1.0 / robot.max_speed], atol=1e-6)


def test_referee_commands_follow_events():
    ref = RefereeState()
    ref.start(0)
    assert ref.message(1).command == ref_pb.Referee.PREPARE_KICKOFF_BLUE
    ws = _world()
    assert ref.update([], ws, {"blue": 0, "yellow": 0}, 10.0, False, 2)
    assert ref.message(3).command == ref_pb.Referee.NORMAL_START
    assert ref.update([{"type": "goal", "team": "blue", "t": 1.0}], ws, {"blue": 1, "yellow": 0}, 9.0, False, 4)
    msg = ref.message(5)
    assert msg.command == ref_pb.Referee.PREPARE_KICKOFF_YELLOW and msg.blue.score == 1
    assert msg.stage_time_left == 9_000_000 and msg.command_counter == 3
    ref.update([], ws, {"blue": 1, "yellow": 0}, 8.9, False, 6)
    ref.update([{"type": "ball_out", "t": 2.0, "placement": [1.5, 0.8]}], ws, {"blue": 1, "yellow": 0}, 8, False, 7)
    msg = ref.message(8)
    assert msg.command == ref_pb.Referee.BALL_PLACEMENT_YELLOW  # yellow 0 stands nearest to (1.5, 0.8)
    assert (msg.designated_position.x, msg.designated_position.y) == (1500.0, 800.0)
    assert msg.next_command == ref_pb.Referee.FORCE_START
    ref.update([], ws, {"blue": 1, "yellow": 0}, 0.0, True, 9)
    assert ref.message(10).stage == ref_pb.Referee.POST_GAME


def test_tracker_packet():
    packet = trk_pb.TrackerWrapperPacket.FromString(tracker_packet(_world(), 7, 1.5, "u").SerializeToString())
    frame = packet.tracked_frame
    assert frame.frame_number == 7 and len(frame.robots) == 3 and frame.balls[0].vel.x == 1.0
    yellow = [r for r in frame.robots if r.robot_id.team_color == trk_pb.TEAM_COLOR_YELLOW]
    assert len(yellow) == 1 and yellow[0].pos.x == 2.0
