"""The bridge in SSL's format: the game controller's commands, stages and clock in the referee
packets, and a client team that obeys them."""

from dataclasses import replace

import numpy as np
import pytest

pytest.importorskip("google.protobuf")

from ssl_marl.bridge.client import PlayBrain  # noqa: E402
from ssl_marl.bridge.proto import ssl_referee_pb2 as ref_pb  # noqa: E402
from ssl_marl.bridge.referee_codec import GameView, RefereeFollower, RefereeState  # noqa: E402
from ssl_marl.bridge.vision_codec import camera_regions, detection_frames, merge_frames  # noqa: E402
from ssl_marl.bridge.world import BridgeWorld, WorldConfig  # noqa: E402
from ssl_marl.envs import game_control as gc  # noqa: E402
from ssl_marl.physics.field import FieldGeometry  # noqa: E402
from ssl_marl.physics.state import WorldState, make_team_state  # noqa: E402

R = ref_pb.Referee
SCORE = {"blue": 0, "yellow": 0}


def _world(ball=(0.0, 0.0), near=None):
    """Blue: two robots (the second ``near`` the ball if given); yellow: one robot."""
    second = [ball[0] - 0.2, ball[1]] if near else [-1.5, -1.0]
    blue = make_team_state([[-3.5, 0.0], second], [0.0, 0.0], np.zeros((2, 2)), [0, 1], [False, False], [True, True])
    yellow = make_team_state([[3.5, 0.0]], [np.pi], np.zeros((1, 2)), [0], [False], [True])
    return WorldState(t=1.0, ball_pos=np.array(ball, float), ball_vel=np.zeros(2), blue=blue, yellow=yellow)


def test_the_codec_sends_the_env_commands_stages_and_half_clock():
    ref = RefereeState()
    kickoff = gc.RefereeState(gc.KICKOFF, "blue", (0.0, 0.0), 0.0)
    ref.start(0, GameView(kickoff, 1, 300.0))
    msg = ref.message(1)
    assert (msg.stage, msg.command, msg.next_command) == (R.NORMAL_FIRST_HALF_PRE, R.PREPARE_KICKOFF_BLUE,
                                                          R.NORMAL_START)
    assert msg.stage_time_left == 300_000_000 and not msg.blue_team_on_positive_half
    assert ref.update([], _world(), SCORE, 0.0, False, 2, game=GameView(kickoff, 1, 299.98))
    assert (ref.stage, ref.command) == (R.NORMAL_FIRST_HALF, R.NORMAL_START)
    assert not ref.update([], _world(), SCORE, 0.0, False, 3, game=GameView(kickoff, 1, 299.96))  # nothing new
    taken = gc.RefereeState(gc.RUNNING, since=0.5)
    assert not ref.update([], _world(ball=(0.3, 0.0)), SCORE, 0.0, False, 4, game=GameView(taken, 1, 299.5))
    assert ref.command == R.NORMAL_START  # a taken kickoff keeps its command, as the game controller does
    stop = gc.RefereeState(gc.STOP, None, (2.0, -2.8), 10.0, gc.FREE_KICK, "yellow")
    assert ref.update([], _world(), SCORE, 0.0, False, 5, game=GameView(stop, 1, 290.0))
    msg = ref.message(6)
    assert (msg.command, msg.next_command) == (R.STOP, R.DIRECT_FREE_YELLOW)
    assert (msg.designated_position.x, msg.designated_position.y) == (2000.0, -2800.0)
    assert msg.stage_time_left == 290_000_000
    free = gc.RefereeState(gc.FREE_KICK, "yellow", (2.0, -2.8), 11.0)
    assert ref.update([], _world(ball=(2.0, -2.8)), SCORE, 0.0, False, 7, game=GameView(free, 1, 290.0))
    assert ref.command == R.DIRECT_FREE_YELLOW and ref.next_command is None
    # not taken within the env's timeout: play runs on, the game controller's FORCE_START
    assert ref.update([], _world(ball=(2.0, -2.8)), SCORE, 0.0, False, 8,
                      game=GameView(gc.RefereeState(since=21.0), 1, 280.0))
    assert ref.command == R.FORCE_START
    second = gc.RefereeState(gc.KICKOFF, "yellow", (0.0, 0.0), 300.0)
    assert ref.update([{"type": "half_time"}], _world(), SCORE, 0.0, False, 9, game=GameView(second, 2, 300.0))
    assert (ref.stage, ref.command) == (R.NORMAL_SECOND_HALF_PRE, R.PREPARE_KICKOFF_YELLOW)
    assert ref.update([], _world(), SCORE, 0.0, False, 10, game=GameView(second, 2, 299.98))
    assert (ref.stage, ref.command) == (R.NORMAL_SECOND_HALF, R.NORMAL_START)
    assert ref.update([], _world(), SCORE, 0.0, True, 11, game=GameView(second, 2, 0.0))
    assert (ref.stage, ref.command) == (R.POST_GAME, R.HALT)


def test_a_served_ssl_match_sends_every_command_of_the_env():
    world = BridgeWorld(WorldConfig(robots=3, seconds=20.0, seed=5, blue_team="attack-baseline",
                                    yellow_team="baseline", format="ssl"))
    env_commands, packets, stages = [], [], set()
    while not world.finished:
        events, changed = world.step(int(world.t * 1e6))
        env_commands += [(e["command"], e["team"]) for e in events if e["type"] == "referee"]
        msg = world.referee.message(0)
        stages.add(msg.stage)
        if changed:
            packets.append(msg.command)
        if msg.stage != R.POST_GAME:
            assert 0 <= msg.stage_time_left <= 10_000_000  # each half 10 s on the match clock
    # every STOP and free kick of the env went out as the game controller's command
    expected = [R.STOP if c == gc.STOP else {"blue": R.DIRECT_FREE_BLUE, "yellow": R.DIRECT_FREE_YELLOW}[t]
                for c, t in env_commands if c in (gc.STOP, gc.FREE_KICK)]
    assert [p for p in packets if p in (R.STOP, R.DIRECT_FREE_BLUE, R.DIRECT_FREE_YELLOW)] == expected
    assert packets.count(R.PREPARE_KICKOFF_YELLOW) >= 1  # the second half's kickoff
    assert {R.NORMAL_FIRST_HALF, R.NORMAL_SECOND_HALF, R.POST_GAME} <= stages
    assert packets[-1] == R.HALT


def test_bad_formats_are_refused():
    with pytest.raises(ValueError, match="format"):
        WorldConfig(format="long")


def _packet(command, counter, next_command=None, spot=None):
    msg = R(command=command, command_counter=counter, stage=R.NORMAL_FIRST_HALF, packet_timestamp=0,
            command_timestamp=0)
    if next_command is not None:
        msg.next_command = next_command
    if spot is not None:
        msg.designated_position.x, msg.designated_position.y = spot
    return msg


def test_the_follower_turns_packets_into_the_env_commands():
    f = RefereeFollower()
    assert f.update(np.zeros(2)).command == gc.RUNNING
    f.on_message(_packet(R.STOP, 1, R.DIRECT_FREE_BLUE, (1000.0, -500.0)))
    s = f.update(np.zeros(2))
    assert (s.command, s.next_command, s.next_team, s.position) == (gc.STOP, gc.FREE_KICK, "blue", (1.0, -0.5))
    assert s.must_keep_clear("blue") and s.must_keep_clear("yellow")
    f.on_message(_packet(R.DIRECT_FREE_BLUE, 2, spot=(1000.0, -500.0)))
    assert f.update(np.array([1.0, -0.5])).is_set_piece_for("blue")
    f.on_message(_packet(R.DIRECT_FREE_BLUE, 2))  # repeated: nothing changes
    assert f.update(np.array([1.02, -0.5])).command == gc.FREE_KICK  # moved 2 cm: not yet in play
    assert f.update(np.array([1.1, -0.5])).command == gc.RUNNING  # moved 10 cm: in play
    f.on_message(_packet(R.PREPARE_KICKOFF_YELLOW, 3, R.NORMAL_START))
    f.on_message(_packet(R.NORMAL_START, 4))
    s = f.update(np.zeros(2))
    assert s.is_set_piece_for("yellow") and s.must_keep_clear("blue")
    f.on_message(_packet(R.BALL_PLACEMENT_BLUE, 5, R.FORCE_START, (0.0, 0.0)))
    assert f.update(np.zeros(2)).command == gc.STOP
    f.on_message(_packet(R.FORCE_START, 6))
    assert f.update(np.zeros(2)).command == gc.RUNNING


def _detections(world, t):
    field = FieldGeometry.div_b()
    return merge_frames(detection_frames(replace(world, t=t), camera_regions(field, 1), [int(t * 60)], t, t))


def test_a_client_team_keeps_clear_of_the_ball_at_the_other_teams_free_kick():
    world = _world(ball=(0.5, 0.0), near=True)  # blue 1 stands 0.2 m from the ball, facing it
    actions = {}
    for packet in (None, _packet(R.DIRECT_FREE_YELLOW, 1, spot=(500.0, 0.0))):
        brain = PlayBrain("blue", "baseline", robots=2, tracker=False)
        if packet is not None:
            brain.on_referee(packet)
        for k in range(3):
            out = brain.decide(_detections(world, 1.0 + k / 60))
        actions[packet is None] = out[1]
    free, kept = actions[True], actions[False]
    # body frame, robot facing +x: the ball lies ahead; without a referee it goes for it, at the
    # other team's free kick it backs away and does not kick
    assert free[0] > 0.0 > kept[0]
    assert kept[4] == -1.0


def test_an_ssl_format_match_is_recorded_as_the_match_played(tmp_path, capsys):
    """``ssl-marl match --format ssl --ssl-log``: the bridge replays the same seeded match (same
    score) and the log's referee packets carry SSL's game control (STOP, free kicks, both halves)."""
    from ssl_marl.bridge.ssl_log import MESSAGE_TYPES, read_log
    from ssl_marl.cli import main

    out = tmp_path / "ssl.log"
    assert main(["match", "--blue", "attack-baseline", "--yellow", "baseline", "--robots", "3", "--seconds", "20",
                 "--format", "ssl", "--seed", "4", "--render", "none", "--quiet", "--ssl-log", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "SSL log ->" in printed and "differs" not in printed
    commands, stages = set(), set()
    for msg in read_log(out):
        if msg.message_type == MESSAGE_TYPES["referee_2013"]:
            ref = R.FromString(msg.payload)
            commands.add(ref.command)
            stages.add(ref.stage)
    assert {R.STOP, R.NORMAL_START} <= commands and commands & {R.DIRECT_FREE_BLUE, R.DIRECT_FREE_YELLOW}
    assert {R.NORMAL_FIRST_HALF, R.NORMAL_SECOND_HALF, R.POST_GAME} <= stages
