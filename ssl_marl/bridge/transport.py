"""UDP and TCP sockets of the bridge: addresses, senders, receivers.

Addresses are ``"host:port"`` strings or (host, port) tuples. A multicast group as a
destination gets TTL 1 (the local network); as a listening address the socket binds
the port on all interfaces and joins the group. Every socket is non-blocking: the
server's loop polls them with ``select``.
"""

from __future__ import annotations

import ipaddress
import socket
import struct
from typing import Iterable, Sequence

Address = tuple[str, int]
MAX_DATAGRAM = 65507  # bytes, the largest UDP payload over IPv4
#: SSL's default addresses (docs/references.md, "SSL network protocols")
VISION_DEFAULT = "224.5.23.2:10020"
REFEREE_DEFAULT = "224.5.23.1:10003"
TRACKER_DEFAULT = "224.5.23.2:10010"


def parse_address(text: str | Address) -> Address:
    """(host, port) of ``"host:port"`` (or of a tuple). ValueError for a bad address."""
    if isinstance(text, tuple):
        host, port = text
    else:
        host, sep, port_text = str(text).rpartition(":")
        if not sep or not host:
            raise ValueError(f"address must be HOST:PORT, got {text!r}")
        try:
            port = int(port_text)
        except ValueError:
            raise ValueError(f"address {text!r}: port {port_text!r} is not a number") from None
    if not 0 <= int(port) <= 65535:
        raise ValueError(f"address {text!r}: port must be in 0..65535")
    return str(host), int(port)


def is_multicast(host: str) -> bool:
    """True for an IPv4 multicast group (224.0.0.0/4)."""
    try:
        return ipaddress.ip_address(host).is_multicast
    except ValueError:
        return False


class UdpSender:
    """One UDP socket that sends each payload to every destination of a stream."""

    def __init__(self, destinations: Iterable[str | Address]) -> None:
        self.destinations: list[Address] = [parse_address(d) for d in destinations]
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        if any(is_multicast(h) for h, _ in self.destinations):
            self.sock.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_TTL, 1)
            self.sock.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_LOOP, 1)
        self.sock.setblocking(False)
        self.sent = 0
        self.failed = 0

    def send(self, payload: bytes) -> None:
        """Send ``payload`` to every destination; a failed send is counted, never raised."""
        for dest in self.destinations:
            try:
                self.sock.sendto(payload, dest)
                self.sent += 1
            except OSError:
                self.failed += 1

    def set_port(self, port: int) -> None:
        """Send to ``port`` on every destination host (the simulator config's vision_port)."""
        self.destinations = [(h, int(port)) for h, _ in self.destinations]

    def close(self) -> None:
        self.sock.close()


class UdpReceiver:
    """A bound, non-blocking UDP socket (joins the group for a multicast address).
    ``port`` 0 binds an ephemeral port: :attr:`port` tells which."""

    def __init__(self, address: str | Address) -> None:
        host, port = parse_address(address)
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        if is_multicast(host):
            self.sock.bind(("", port))
            mreq = struct.pack("4s4s", socket.inet_aton(host), socket.inet_aton("0.0.0.0"))
            self.sock.setsockopt(socket.IPPROTO_IP, socket.IP_ADD_MEMBERSHIP, mreq)
        else:
            self.sock.bind((host, port))
        self.sock.setblocking(False)
        self.host = host
        self.port = self.sock.getsockname()[1]

    def fileno(self) -> int:
        return self.sock.fileno()

    def receive(self, limit: int = 10_000) -> list[tuple[bytes, Address]]:
        """Every datagram waiting (at most ``limit``), with its sender."""
        out = []
        while len(out) < limit:
            try:
                out.append(self.sock.recvfrom(MAX_DATAGRAM))
            except (BlockingIOError, InterruptedError):
                break
            except OSError:  # e.g. ICMP port unreachable reported on the socket
                continue
        return out

    def reply(self, payload: bytes, dest: Address) -> bool:
        """Send ``payload`` from this socket to ``dest``; False when it failed."""
        try:
            self.sock.sendto(payload, dest)
            return True
        except OSError:
            return False

    def close(self) -> None:
        self.sock.close()


class TcpListener:
    """A listening, non-blocking TCP socket (``port`` 0: ephemeral, see :attr:`port`)."""

    def __init__(self, address: str | Address) -> None:
        host, port = parse_address(address)
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        self.sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        self.sock.bind((host, port))
        self.sock.listen(4)
        self.sock.setblocking(False)
        self.port = self.sock.getsockname()[1]

    def fileno(self) -> int:
        return self.sock.fileno()

    def accept(self) -> socket.socket | None:
        try:
            conn, _ = self.sock.accept()
        except (BlockingIOError, InterruptedError):
            return None
        conn.setblocking(False)
        conn.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        return conn

    def close(self) -> None:
        self.sock.close()


def loopback(ports: Sequence[int]) -> list[str]:
    """``["127.0.0.1:PORT", ...]`` (test helpers use nothing else)."""
    return [f"127.0.0.1:{p}" for p in ports]
