"""SSL log files of bridge matches: ``serve --log`` writes vision and referee packets in
SSL's log format; a recorded log replays out of loopback ports and renders to a GIF."""

import argparse

import pytest

pytest.importorskip("google.protobuf")

from bridge_helpers import LOOP, receive_at_least  # noqa: E402

from ssl_marl.bridge.proto import ssl_referee_pb2 as ref_pb  # noqa: E402
from ssl_marl.bridge.proto import ssl_vision_wrapper_pb2 as wrap_pb  # noqa: E402
from ssl_marl.bridge.ssl_log import MESSAGE_TYPES, read_log, replay  # noqa: E402
from ssl_marl.bridge.transport import UdpReceiver, UdpSender  # noqa: E402


def _serve_args(*extra: str) -> argparse.Namespace:
    from ssl_marl.bridge.commands import serve

    parser = argparse.ArgumentParser()
    serve.register(parser.add_subparsers())
    loop = ["--listen-host", LOOP, "--control-port", "0", "--blue-port", "0", "--yellow-port", "0",
            "--grsim-port", "0", "--sync-blue-port", "0", "--sync-yellow-port", "0", "--grsim-status-ports", "9,9"]
    return parser.parse_args(["serve", *loop, *extra])


def test_serve_writes_an_ssl_log_that_replays_and_renders(tmp_path):
    sink = UdpReceiver((LOOP, 0))
    log = tmp_path / "match.log"
    args = _serve_args("--vision", f"{LOOP}:{sink.port}", "--referee", f"{LOOP}:{sink.port}", "--robots", "2",
                       "--seconds", "1.0", "--speed", "10", "--cameras", "2", "--blue-team", "baseline",
                       "--log", str(log), "--max-wall-s", "30")
    assert args.handler(args) == 0
    sink.receive()
    messages = list(read_log(log))
    kinds = {m.message_type for m in messages}
    assert kinds == {MESSAGE_TYPES["vision_2014"], MESSAGE_TYPES["referee_2013"]}
    vision = [wrap_pb.SSL_WrapperPacket.FromString(m.payload) for m in messages
              if m.message_type == MESSAGE_TYPES["vision_2014"]]
    assert vision[0].HasField("geometry") and {p.detection.camera_id for p in vision[1:]} == {0, 1}
    assert ref_pb.Referee.FromString(messages[-1].payload).stage == ref_pb.Referee.POST_GAME
    assert all(a.timestamp_ns <= b.timestamp_ns for a, b in zip(messages, messages[1:]))

    sender = UdpSender([f"{LOOP}:{sink.port}"])
    assert replay(log, sender, sender, speed=0) == len(messages)
    sender.close()
    assert len(receive_at_least(sink, 1)) > 0
    sink.close()

    gif = tmp_path / "replay.gif"
    args = _serve_args("--replay", str(log), "--replay-video", str(gif), "--robots", "2")
    assert args.handler(args) == 0 and gif.stat().st_size > 0


def test_match_command_writes_an_ssl_log(tmp_path, capsys):
    from ssl_marl.cli import main

    out = tmp_path / "m.log"
    assert main(["match", "--seconds", "2", "--robots", "2", "--render", "none", "--quiet",
                 "--ssl-log", str(out)]) == 0
    assert out.read_bytes()[:12] == b"SSL_LOG_FILE"
    assert "SSL log ->" in capsys.readouterr().out
    assert main(["match", "--seconds", "2", "--matches", "2", "--render", "none", "--quiet",
                 "--ssl-log", str(tmp_path / "x.log")]) == 2  # series are not recorded
