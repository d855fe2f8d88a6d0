"""Lock-step (synchronous) simulation over TCP: ``SimulationSyncRequest`` in,
``SimulationSyncResponse`` out, each message prefixed with its varint length
(:mod:`.wire`).

One TCP port per team colour: a request's ``robot_control`` commands the robots of
the colour whose port it came in on. The server steps once every connected client
has a request waiting (two teams in lock-step advance together); ``sim_step`` (s)
must be a whole number of control periods (within :data:`STEP_TOLERANCE_S`) and the
same in every waiting request, else each gets ``INVALID_STEP`` and nothing moves.
The response holds every camera frame of every control period stepped and the
requesting team's robot feedback; errors of its simulator command and robot
control are in ``robot_control_response.errors``.
"""

from __future__ import annotations

import socket
from collections import Counter

from google.protobuf.message import DecodeError

from .proto import ssl_simulation_pb2 as sim_pb
from .transport import Address, TcpListener, parse_address
from .wire import FrameError, FrameReader, encode_frame

STEP_TOLERANCE_S = 1e-6


def whole_periods(sim_step: float, dt: float) -> int | None:
    """Control periods in ``sim_step`` s, or None unless it is a whole number >= 0 of
    periods ``dt`` within :data:`STEP_TOLERANCE_S`."""
    if not (sim_step == sim_step) or sim_step < 0 or sim_step > 3600:
        return None
    k = round(sim_step / dt)
    return int(k) if abs(k * dt - sim_step) <= STEP_TOLERANCE_S else None


def error_response(code: str, message: str) -> sim_pb.SimulationSyncResponse:
    """A response carrying one error and no detections."""
    resp = sim_pb.SimulationSyncResponse()
    resp.robot_control_response.errors.add(code=code, message=message)
    return resp


class _Conn:
    def __init__(self, sock: socket.socket, team: str) -> None:
        self.sock, self.team, self.reader = sock, team, FrameReader()

    def fileno(self) -> int:
        return self.sock.fileno()


class SyncEndpoint:
    """The server side: TCP listeners per colour and their connections."""

    def __init__(self, host: str, ports: dict[str, int]) -> None:
        self.listeners = {team: TcpListener((host, port)) for team, port in ports.items()}
        self.conns: list[_Conn] = []
        self.pending: dict[str, tuple[_Conn, sim_pb.SimulationSyncRequest]] = {}
        self.stats: Counter = Counter()

    @property
    def ports(self) -> dict[str, int]:
        return {team: lst.port for team, lst in self.listeners.items()}

    def sockets(self) -> list:
        return list(self.listeners.values()) + self.conns

    def handle_readable(self, obj) -> None:
        """Accept a connection or read a connection's frames (requests become pending)."""
        for team, lst in self.listeners.items():
            if obj is lst:
                sock = lst.accept()
                if sock is not None:
                    self.conns.append(_Conn(sock, team))
                return
        conn: _Conn = obj
        try:
            chunk = conn.sock.recv(1 << 16)
        except (BlockingIOError, InterruptedError):
            return
        except OSError:
            chunk = b""
        if not chunk:
            self._drop(conn)
            return
        try:
            frames = conn.reader.feed(chunk)
        except FrameError as exc:
            self.stats["error:FRAME"] += 1
            self.send(conn, error_response("PARSE_ERROR", f"bad frame: {exc}"))
            self._drop(conn)
            return
        for payload in frames:
            req = sim_pb.SimulationSyncRequest()
            try:
                req.ParseFromString(payload)
            except (DecodeError, ValueError, RuntimeError) as exc:
                self.stats["error:PARSE_ERROR"] += 1
                self.send(conn, error_response("PARSE_ERROR", f"not a SimulationSyncRequest: {exc}"))
                continue
            if conn.team in self.pending and self.pending[conn.team][0] is not conn:
                self.stats["error:TEAM_BUSY"] += 1
                self.send(conn, error_response("TEAM_BUSY", f"another client commands {conn.team}"))
                continue
            if conn.team in self.pending:  # a second request before the first was answered
                self.stats["error:PIPELINED"] += 1
                self.send(conn, error_response("PIPELINED", "one request at a time: wait for the response"))
                continue
            self.pending[conn.team] = (conn, req)

    def ready(self) -> bool:
        """Every connected colour has a request waiting (and at least one does)."""
        connected = {c.team for c in self.conns}
        return bool(self.pending) and connected <= set(self.pending)

    def take(self) -> dict[str, tuple[_Conn, sim_pb.SimulationSyncRequest]]:
        out, self.pending = self.pending, {}
        return out

    def send(self, conn: _Conn, response: sim_pb.SimulationSyncResponse) -> None:
        """Send a response (blocking until written; a dead connection is dropped)."""
        try:
            conn.sock.setblocking(True)
            conn.sock.sendall(encode_frame(response.SerializeToString()))
            conn.sock.setblocking(False)
        except OSError:
            self._drop(conn)

    def _drop(self, conn: _Conn) -> None:
        if conn in self.conns:
            self.conns.remove(conn)
        if conn.team in self.pending and self.pending[conn.team][0] is conn:
            del self.pending[conn.team]
        try:
            conn.sock.close()
        except OSError:
            pass

    def close(self) -> None:
        for conn in list(self.conns):
            self._drop(conn)
        for lst in self.listeners.values():
            lst.close()


class LockstepClient:
    """A blocking lock-step client for one colour (``address`` = the server's port for it).

    ``step(sim_step, robot_control, simulator_command)`` sends a request and waits for
    the response; two clients driven by one thread use :meth:`send` then :meth:`receive`.
    """

    def __init__(self, address: str | Address, timeout_s: float = 30.0) -> None:
        self.sock = socket.create_connection(parse_address(address), timeout=timeout_s)
        self.sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        self.reader = FrameReader()
        self._frames: list[bytes] = []

    def send(self, sim_step: float, robot_control: sim_pb.RobotControl | None = None,
             simulator_command: sim_pb.SimulatorCommand | None = None) -> None:
        req = sim_pb.SimulationSyncRequest(sim_step=sim_step)
        if robot_control is not None:
            req.robot_control.CopyFrom(robot_control)
        if simulator_command is not None:
            req.simulator_command.CopyFrom(simulator_command)
        self.send_raw(encode_frame(req.SerializeToString()))

    def send_raw(self, data: bytes) -> None:
        """Bytes as they are (tests of malformed input)."""
        self.sock.sendall(data)

    def receive(self) -> sim_pb.SimulationSyncResponse:
        while not self._frames:
            chunk = self.sock.recv(1 << 16)
            if not chunk:
                raise ConnectionError("lock-step server closed the connection")
            self._frames += self.reader.feed(chunk)
        resp = sim_pb.SimulationSyncResponse()
        resp.ParseFromString(self._frames.pop(0))
        return resp

    def step(self, sim_step: float, robot_control: sim_pb.RobotControl | None = None,
             simulator_command: sim_pb.SimulatorCommand | None = None) -> sim_pb.SimulationSyncResponse:
        self.send(sim_step, robot_control, simulator_command)
        return self.receive()

    def close(self) -> None:
        self.sock.close()
