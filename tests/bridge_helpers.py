"""Helpers of the bridge tests: every stream on loopback unicast with ephemeral ports."""

from __future__ import annotations

from ssl_marl.bridge.server import BridgeServer, ServerConfig
from ssl_marl.bridge.transport import UdpReceiver
from ssl_marl.bridge.world import WorldConfig

LOOP = "127.0.0.1"


def loopback_server(world: WorldConfig, lockstep: bool = False, **kw) -> tuple[BridgeServer, UdpReceiver, UdpReceiver]:
    """A server whose vision and referee go to two fresh loopback receivers (returned),
    every port ephemeral on 127.0.0.1."""
    vision, referee = UdpReceiver((LOOP, 0)), UdpReceiver((LOOP, 0))
    config = ServerConfig(vision=(f"{LOOP}:{vision.port}",), referee=(f"{LOOP}:{referee.port}",),
                          tracker=tuple(kw.pop("tracker", ())), listen_host=LOOP, control_port=0, blue_port=0,
                          yellow_port=0, grsim_port=0, grsim_status_ports=kw.pop("grsim_status_ports", (9, 9)),
                          sync_blue_port=0, sync_yellow_port=0, lockstep=lockstep, time_origin=0.0, **kw)
    return BridgeServer(world, config), vision, referee


def receive_at_least(receiver: UdpReceiver, n: int, timeout_s: float = 10.0) -> list[tuple[bytes, tuple[str, int]]]:
    """Every datagram ``receiver`` gets until it has ``n`` or ``timeout_s`` wall seconds pass.

    Loopback datagrams are delivered by the kernel's soft interrupts, which a loaded
    machine may run tens of milliseconds late: a test waits for its packets, never a
    fixed sleep."""
    import time

    out = receiver.receive()
    deadline = time.monotonic() + timeout_s
    while len(out) < n and time.monotonic() < deadline:
        time.sleep(0.01)
        out += receiver.receive()
    return out
