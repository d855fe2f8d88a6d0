"""Bad input never stops the server: random and mutated packets on every input port
(garbage, truncated messages, unknown robot ids, NaN and huge values, the wrong team)
are dropped or answered with an error and counted; the world stays valid. The full
soak (100,000 packets) is slow-marked; a small variant runs in the suite."""

import math

import numpy as np
import pytest

pytest.importorskip("google.protobuf")

from ssl_marl.bridge.proto import grsim_packet_pb2 as grsim_pb  # noqa: E402
from ssl_marl.bridge.proto import ssl_simulation_pb2 as sim_pb  # noqa: E402
from ssl_marl.bridge.world import BridgeWorld, WorldConfig  # noqa: E402

WILD = (float("nan"), float("inf"), -float("inf"), 1e30, -1e30, 0.0, 1.0, -3.0, 1e6)


def _valid_messages(rng: np.random.Generator) -> list[tuple[str, bytes]]:
    ctl = sim_pb.RobotControl()
    for _ in range(int(rng.integers(1, 4))):
        cmd = ctl.robot_commands.add(id=int(rng.integers(0, 12)))
        kind = rng.integers(0, 4)
        if kind == 0:
            lv = cmd.move_command.local_velocity
            lv.forward, lv.left, lv.angular = (float(rng.choice(WILD)) for _ in range(3))
        elif kind == 1:
            gv = cmd.move_command.global_velocity
            gv.x, gv.y, gv.angular = (float(rng.choice(WILD)) for _ in range(3))
        elif kind == 2:
            wv = cmd.move_command.wheel_velocity
            wv.front_right = wv.back_right = wv.back_left = wv.front_left = 1.0
        cmd.kick_speed = float(rng.choice(WILD))
        cmd.kick_angle = float(rng.choice((0.0, 45.0, float("nan"))))
        cmd.dribbler_speed = float(rng.choice(WILD))
    sc = sim_pb.SimulatorCommand()
    tb = sc.control.teleport_ball
    tb.x, tb.y, tb.vx, tb.vy = (float(rng.choice(WILD)) for _ in range(4))
    tr = sc.control.teleport_robot.add(x=float(rng.choice(WILD)), y=float(rng.choice(WILD)),
                                       orientation=float(rng.choice(WILD)))
    tr.id.id, tr.id.team = int(rng.integers(0, 12)), int(rng.integers(0, 3))
    sc.control.simulation_speed = float(rng.choice(WILD))
    gp = grsim_pb.grSim_Packet()
    gp.commands.timestamp = 0.0
    gp.commands.isteamyellow = bool(rng.integers(0, 2))
    gp.commands.robot_commands.add(id=int(rng.integers(0, 12)), kickspeedx=float(rng.choice(WILD)),
                                   kickspeedz=float(rng.choice(WILD)), veltangent=float(rng.choice(WILD)),
                                   velnormal=float(rng.choice(WILD)), velangular=float(rng.choice(WILD)),
                                   spinner=True, wheelsspeed=bool(rng.integers(0, 2)))
    return [("blue", ctl.SerializeToString()), ("yellow", ctl.SerializeToString()),
            ("control", sc.SerializeToString()), ("grsim", gp.SerializeToString())]


def _mutate(data: bytes, rng: np.random.Generator) -> bytes:
    kind = rng.integers(0, 4)
    if kind == 0:
        return bytes(rng.integers(0, 256, int(rng.integers(0, 64)), dtype=np.uint8))
    if kind == 1:
        return data[:int(rng.integers(0, max(len(data), 1)))]
    if kind == 2 and data:
        b = bytearray(data)
        for _ in range(int(rng.integers(1, 4))):
            b[int(rng.integers(0, len(b)))] = int(rng.integers(0, 256))
        return bytes(b)
    return data


def soak(n_packets: int, seed: int = 0) -> BridgeWorld:
    """Feed ``n_packets`` random / mutated packets straight into the server's handlers,
    stepping the world every 50; returns the world."""
    from bridge_helpers import loopback_server

    server, vision, referee = loopback_server(WorldConfig(robots=3, seconds=1e6, client_teams=("blue",),
                                                          blue_team="baseline", yellow_team="random"))
    rng = np.random.default_rng(seed)
    handlers = {"blue": lambda d, a: server._on_robot_control("blue", d, a),
                "yellow": lambda d, a: server._on_robot_control("yellow", d, a),
                "control": server._on_control, "grsim": server._on_grsim}
    sink = ("127.0.0.1", 9)  # discard port: replies go nowhere
    try:
        sent = 0
        while sent < n_packets:
            for port, data in _valid_messages(rng):
                handlers[port](_mutate(data, rng), sink)
                sent += 1
            if sent % 50 < 4:
                server.advance()
                assert server.world.valid()
                vision.receive()
                referee.receive()
    finally:
        server.close()
        vision.close()
        referee.close()
    return server.world


def _check(world: BridgeWorld) -> None:
    stats = world.stats
    assert stats["steps"] > 0 and world.valid()
    assert stats["error:PARSE_ERROR"] > 0 and stats["error:UNKNOWN_ROBOT"] > 0
    assert stats["error:WRONG_TEAM"] > 0 and stats["error:INVALID_VALUE"] > 0
    assert world.speed > 0 and math.isfinite(world.speed)
    assert np.isfinite(world.commands["blue"]).all()


def test_fuzz_small():
    _check(soak(2000, seed=1))


@pytest.mark.slow
def test_fuzz_soak_100k():
    _check(soak(100_000, seed=2))

