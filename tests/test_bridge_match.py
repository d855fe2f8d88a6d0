"""A short real-time match over UDP on loopback: both teams are ``play`` clients of the
server (blue by the simulation protocol, yellow by grSim packets), vision and referee
go to both clients by unicast, a goal is forced by a teleport and play restarts."""

import socket
import time

import pytest

pytest.importorskip("google.protobuf")

from bridge_helpers import LOOP  # noqa: E402

from ssl_marl.bridge.client import ClientConfig, PlayBrain, PlayClient  # noqa: E402
from ssl_marl.bridge.proto import ssl_simulation_pb2 as sim_pb  # noqa: E402
from ssl_marl.bridge.server import BridgeServer, ServerConfig  # noqa: E402
from ssl_marl.bridge.world import WorldConfig  # noqa: E402


def test_udp_match_of_two_play_clients():
    clients = {
        "blue": PlayClient(PlayBrain("blue", "baseline", 2), ClientConfig(vision=f"{LOOP}:0", referee=f"{LOOP}:0",
                                                                         simulator=f"{LOOP}:9")),
        "yellow": PlayClient(PlayBrain("yellow", "baseline", 2, seed=1),
                             ClientConfig(vision=f"{LOOP}:0", referee=f"{LOOP}:0", simulator=f"{LOOP}:9",
                                          protocol="grsim")),
    }
    config = ServerConfig(vision=tuple(f"{LOOP}:{c.vision_in.port}" for c in clients.values()),
                          referee=tuple(f"{LOOP}:{c.referee_in.port}" for c in clients.values()),
                          listen_host=LOOP, control_port=0, blue_port=0, yellow_port=0, grsim_port=0,
                          grsim_status_ports=(9, 9), sync_blue_port=0, sync_yellow_port=0)
    server = BridgeServer(WorldConfig(robots=2, seconds=30.0), config)
    clients["blue"].simulator = (LOOP, server.ports["blue"])
    clients["yellow"].simulator = (LOOP, server.ports["grsim"])
    threads = [server.start(max_wall_s=60)] + [c.start(max_wall_s=60) for c in clients.values()]
    try:
        time.sleep(1.5)
        cmd = sim_pb.SimulatorCommand()
        tb = cmd.control.teleport_ball
        tb.x, tb.y, tb.vx, tb.vy = -4.4, -0.35, -2.0, 0.0  # into blue's goal: yellow scores
        tr = cmd.control.teleport_robot.add(x=-4.0, y=2.0, orientation=0.0)  # the keeper out of the way
        tr.id.id, tr.id.team = 0, sim_pb.BLUE
        sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        sock.settimeout(5.0)
        sock.sendto(cmd.SerializeToString(), (LOOP, server.ports["control"]))
        assert not sim_pb.SimulatorResponse.FromString(sock.recvfrom(65507)[0]).errors
        sock.close()
        deadline = time.monotonic() + 20
        while time.monotonic() < deadline and server.world.env.score["yellow"] < 1:
            time.sleep(0.05)
        deadline = time.monotonic() + 10  # on a loaded machine the clients may need longer to see the score
        while time.monotonic() < deadline and not all(c.brain.decisions > 20 and c.brain.score is not None
                                                      for c in clients.values()):
            time.sleep(0.05)
        time.sleep(1.0)
    finally:
        for c in clients.values():
            c.stop()
        server.stop()
        for t in threads:
            t.join(10)
        server.close()
        for c in clients.values():
            c.close()
    stats = server.world.stats
    assert server.world.env.score["yellow"] >= 1
    assert stats["commands:blue"] > 20 and stats["commands:yellow"] > 20
    assert all(c.brain.decisions > 20 and c.brain.score is not None for c in clients.values())
    assert clients["blue"].brain.score["yellow"] >= 1
    assert server.world.valid()
