"""The bridge server: :class:`BridgeServer` serves a :class:`~.world.BridgeWorld` over
SSL's protocols.

Out (UDP, to every address of each stream): SSL-Vision wrapper packets (one detection
frame per camera and control period; geometry at the start and every
``geometry_every_s``), game-controller referee packets (on every new command and
every ``referee_every_s``), tracker packets (each control period, when tracker
addresses are given). In (UDP): ``SimulatorCommand`` on the control port (reply
``SimulatorResponse``), ``RobotControl`` on the blue / yellow ports (reply
``RobotControlResponse`` with errors and dribbler feedback), legacy ``grSim_Packet``
on the grSim port (robot status to the sender's host on the colour's status port:
light barrier, and a flat or chip kick since the last status).
Replies go to the sender's address and port.

Real-time mode paces the world with the wall clock (times ``speed``); lock-step mode
(:mod:`.lockstep`) steps only on ``SimulationSyncRequest`` s. Timestamps: vision
``t_capture`` = ``time_origin`` + simulated time (s; ``time_origin`` defaults to the
Unix time at the start, so a game controller in vision-time mode can use it).
"""

from __future__ import annotations

import select
import threading
import time
import uuid as uuid_lib
from dataclasses import dataclass
from typing import Any

from google.protobuf.message import DecodeError

from .command_codec import CommandError
from .lockstep import SyncEndpoint, error_response, whole_periods
from .proto import grsim_packet_pb2 as grsim_pb
from .proto import ssl_simulation_pb2 as sim_pb
from .transport import REFEREE_DEFAULT, VISION_DEFAULT, UdpReceiver, UdpSender
from .vision_codec import wrapper
from .world import BridgeWorld, WorldConfig


@dataclass(frozen=True)
class ServerConfig:
    """Addresses and pacing of :class:`BridgeServer` (ports 0 = ephemeral).

    Attributes:
        vision, referee, tracker: destinations "host:port" of each stream (tracker: none
            = no tracker packets).
        listen_host: address the command ports bind.
        control_port, blue_port, yellow_port: SSL simulation protocol ports.
        grsim_port: legacy grSim command port; grsim_status_ports: (blue, yellow) ports
            the robot status goes to.
        lockstep: step on lock-step requests only (TCP ``sync_blue_port`` / ``sync_yellow_port``).
        speed: simulated s per wall s in real-time mode.
        geometry_every_s, referee_every_s: repetition periods (simulated s).
        time_origin: Unix time (s) of simulated time 0; None = the wall clock at start.
    """

    vision: tuple[str, ...] = (VISION_DEFAULT,)
    referee: tuple[str, ...] = (REFEREE_DEFAULT,)
    tracker: tuple[str, ...] = ()
    listen_host: str = "0.0.0.0"
    control_port: int = 10300
    blue_port: int = 10301
    yellow_port: int = 10302
    grsim_port: int = 20011
    grsim_status_ports: tuple[int, int] = (30011, 30012)
    lockstep: bool = False
    sync_blue_port: int = 10310
    sync_yellow_port: int = 10311
    speed: float = 1.0
    geometry_every_s: float = 3.0
    referee_every_s: float = 0.1
    time_origin: float | None = None


class BridgeServer:
    """Serve one match world (see the module docstring). ``log``: an optional
    :class:`~.ssl_log.LogWriter` that records every vision and referee packet sent."""

    def __init__(self, world: BridgeWorld | WorldConfig, config: ServerConfig = ServerConfig(),
                 log: Any = None) -> None:
        self.world = world if isinstance(world, BridgeWorld) else BridgeWorld(world)
        if config.lockstep and self.world.config.command_timeout_s > 0:
            from dataclasses import replace

            self.world.config = replace(self.world.config, command_timeout_s=0.0)  # requests replace commands
        self.config = config
        self.log = log
        self.uuid = str(uuid_lib.UUID(int=self.world.config.seed & ((1 << 128) - 1)))
        self.vision_out = UdpSender(config.vision)
        self.referee_out = UdpSender(config.referee)
        self.tracker_out = UdpSender(config.tracker) if config.tracker else None
        h = config.listen_host
        self.control_in = UdpReceiver((h, config.control_port))
        self.team_in = {"blue": UdpReceiver((h, config.blue_port)), "yellow": UdpReceiver((h, config.yellow_port))}
        self.grsim_in = UdpReceiver((h, config.grsim_port))
        self.sync = SyncEndpoint(h, {"blue": config.sync_blue_port, "yellow": config.sync_yellow_port}) \
            if config.lockstep else None
        self.time_origin = time.time() if config.time_origin is None else float(config.time_origin)
        self.world.speed = float(config.speed)
        self._last_geometry = -float("inf")
        self._last_referee = -float("inf")
        self.stop_event = threading.Event()
        self.stats = self.world.stats
        self._publish(referee_changed=True)

    # ------------------------------------------------------------ ports
    @property
    def ports(self) -> dict[str, int]:
        """Bound ports by name (ephemeral ones resolved)."""
        out = {"control": self.control_in.port, "blue": self.team_in["blue"].port,
               "yellow": self.team_in["yellow"].port, "grsim": self.grsim_in.port}
        if self.sync is not None:
            out.update({f"sync_{t}": p for t, p in self.sync.ports.items()})
        return out

    def _now_us(self) -> int:
        return int(round((self.time_origin + self.world.t) * 1e6))

    # ---------------------------------------------------------- publish
    def _publish(self, referee_changed: bool, frames: list | None = None) -> list:
        t = self.world.t
        t_capture = self.time_origin + t
        t_sent = t_capture if self.config.lockstep else time.time()
        if t - self._last_geometry >= self.config.geometry_every_s - 1e-9:
            self._send_vision(wrapper(geometry=self.world.geometry).SerializeToString())
            self._last_geometry = t
        frames = self.world.detections(t_capture, t_sent) if frames is None else frames
        for f in frames:
            self._send_vision(wrapper(detection=f).SerializeToString())
        if referee_changed or t - self._last_referee >= self.config.referee_every_s - 1e-9:
            payload = self.world.referee.message(self._now_us()).SerializeToString()
            self.referee_out.send(payload)
            if self.log is not None:
                self.log.write_referee(int(t_capture * 1e9), payload)
            self._last_referee = t
        if self.tracker_out is not None:
            self.tracker_out.send(self.world.tracker(t_capture, self.uuid).SerializeToString())
        return frames

    def _send_vision(self, payload: bytes) -> None:
        self.vision_out.send(payload)
        if self.log is not None:
            self.log.write_vision(int((self.time_origin + self.world.t) * 1e9), payload)

    def advance(self) -> list:
        """One control period: step the world and publish; the detection frames sent."""
        _, changed = self.world.step(self._now_us())
        return self._publish(changed)

    # ------------------------------------------------------------- input
    def _sockets(self) -> list:
        socks: list = [self.control_in, self.grsim_in, *self.team_in.values()]
        if self.sync is not None:
            socks += self.sync.sockets()
        return socks

    def poll(self, timeout: float) -> None:
        """Wait up to ``timeout`` s for input and handle all of it (never raises on bad input)."""
        try:
            readable, _, _ = select.select(self._sockets(), [], [], max(timeout, 0.0))
        except (OSError, ValueError):
            return
        for sock in readable:
            if sock is self.control_in:
                for data, addr in sock.receive():
                    self._on_control(data, addr)
            elif sock is self.grsim_in:
                for data, addr in sock.receive():
                    self._on_grsim(data, addr)
            elif sock in self.team_in.values():
                team = "blue" if sock is self.team_in["blue"] else "yellow"
                for data, addr in sock.receive():
                    self._on_robot_control(team, data, addr)
            elif self.sync is not None:
                self.sync.handle_readable(sock)
        if self.sync is not None and self.sync.ready():
            self._lockstep_round()

    def _parse(self, message: Any, data: bytes) -> bool:
        self.stats["packets"] += 1
        try:
            message.ParseFromString(data)
            return True
        except (DecodeError, ValueError, RuntimeError):
            self.stats["error:PARSE_ERROR"] += 1
            return False

    def _on_control(self, data: bytes, addr) -> None:
        cmd = sim_pb.SimulatorCommand()
        resp = sim_pb.SimulatorResponse()
        if not self._parse(cmd, data):
            resp.errors.add(code="PARSE_ERROR", message="not a SimulatorCommand")
        else:
            for e in self.world.simulator_command(cmd, self.vision_out.set_port):
                resp.errors.append(e.to_proto())
        self.control_in.reply(resp.SerializeToString(), addr)

    def _on_robot_control(self, team: str, data: bytes, addr) -> None:
        control = sim_pb.RobotControl()
        resp = sim_pb.RobotControlResponse()
        if not self._parse(control, data):
            resp.errors.add(code="PARSE_ERROR", message="not a RobotControl")
        else:
            errors: list[CommandError] = self.world.robot_control(team, control)
            resp.errors.extend(e.to_proto() for e in errors)
            resp.feedback.extend(self.world.feedback(team))
        self.team_in[team].reply(resp.SerializeToString(), addr)

    def _on_grsim(self, data: bytes, addr) -> None:
        packet = grsim_pb.grSim_Packet()
        if not self._parse(packet, data):
            return
        team, _ = self.world.grsim_packet(packet)
        if team is not None:
            held = self.world.env.world_state().team(team).ball_on_dribbler
            kicks = self.world.take_kicks(team)
            status = grsim_pb.grSim_Robots_Status()
            for i in range(self.world.n):
                status.robots_status.add(robot_id=i, infrared=bool(held[i]), flat_kick=kicks.get(i) == "flat",
                                         chip_kick=kicks.get(i) == "chip")
            port = self.config.grsim_status_ports[0 if team == "blue" else 1]
            self.grsim_in.reply(status.SerializeToString(), (addr[0], port))

    def _lockstep_round(self) -> None:
        batch = self.sync.take()
        dt = self.world.dt
        steps = {team: whole_periods(req.sim_step, dt) for team, (_, req) in batch.items()}
        if any(k is None for k in steps.values()) or len(set(steps.values())) > 1:
            self.stats["error:INVALID_STEP"] += 1
            for team, (conn, req) in batch.items():
                self.sync.send(conn, error_response(
                    "INVALID_STEP", f"sim_step {req.sim_step!r} s must be a whole number of control periods "
                                    f"({dt!r} s) and the same for every lock-step client"))
            return
        errors: dict[str, list] = {}
        for team, (_, req) in batch.items():
            errs: list[CommandError] = []
            if req.HasField("simulator_command"):
                errs += self.world.simulator_command(req.simulator_command, self.vision_out.set_port)
            if req.HasField("robot_control"):
                errs += self.world.robot_control(team, req.robot_control)
            errors[team] = errs
        k = next(iter(steps.values()))
        frames = [] if k else self.world.detections(self.time_origin + self.world.t, self.time_origin + self.world.t)
        for _ in range(k):
            if self.world.finished:
                break
            frames += self.advance()
        for team, (conn, _) in batch.items():
            resp = sim_pb.SimulationSyncResponse()
            resp.detection.extend(frames)
            resp.robot_control_response.errors.extend(e.to_proto() for e in errors[team])
            resp.robot_control_response.feedback.extend(self.world.feedback(team))
            self.sync.send(conn, resp)

    # -------------------------------------------------------------- loops
    def run(self, max_wall_s: float | None = None) -> dict:
        """Serve until the match ends (lock-step: and every client has hung up),
        :meth:`stop` is called or ``max_wall_s`` passes;
        the counters (packets, errors by code, steps)."""
        start = time.monotonic()
        next_tick = start
        while not self.stop_event.is_set():
            now = time.monotonic()
            if max_wall_s is not None and now - start >= max_wall_s:
                break
            if self.config.lockstep:  # after the end, answer until the clients hang up
                if self.world.finished and not self.sync.conns:
                    break
                self.poll(0.05)
                continue
            if self.world.finished:
                break
            if now < next_tick:
                self.poll(next_tick - now)
                continue
            self.advance()
            next_tick += self.world.dt / self.world.speed
            if time.monotonic() - next_tick > 5 * self.world.dt:  # fell behind: do not race to catch up
                self.stats["late_ticks"] += 1
                next_tick = time.monotonic()
        if self.world.finished:
            self.referee_out.send(self.world.referee.message(self._now_us()).SerializeToString())
        return dict(self.stats)

    def start(self, max_wall_s: float | None = None) -> threading.Thread:
        """:meth:`run` in a daemon thread."""
        thread = threading.Thread(target=self.run, kwargs={"max_wall_s": max_wall_s}, daemon=True)
        thread.start()
        return thread

    def stop(self) -> None:
        self.stop_event.set()

    def close(self) -> None:
        """Close every socket (and the log)."""
        for s in (self.control_in, self.grsim_in, *self.team_in.values(), self.vision_out, self.referee_out):
            s.close()
        if self.tracker_out is not None:
            self.tracker_out.close()
        if self.sync is not None:
            self.sync.close()
        if self.log is not None:
            self.log.close()
