"""One of our teams as a client of an SSL simulator: :class:`PlayClient`.

Each new vision frame: merge the cameras (:func:`~.vision_codec.merge_frames`), update
the world (:class:`~.perception.VisionWorld`), track it with the project's tracker
(:class:`~ssl_marl.envs.tracking.VisionTracker`: Kalman filters fed with the commands
sent, the state predicted to the next control tick, when the command acts; ``tracker=False``
uses the raw detections), let the team controller decide
(:func:`ssl_marl.runners.controllers.make_controller`: STP with learned or hand-coded
skills, its plays and carrier decision), and send the robot commands by the SSL
simulation protocol (``RobotControl`` to the colour's port; the replies carry dribbler
feedback) or as legacy grSim packets. The referee stream is read: ``HALT`` stops the
robots, score changes reach the controller's play selection, and an STP team obeys the game
controller's commands (:class:`~.referee_codec.RefereeFollower`: STOP, kickoffs and free kicks
as it obeys the env's referee).

:class:`PlayBrain` is the part without sockets (also driven by the lock-step runner
:func:`run_lockstep_match`).
"""

from __future__ import annotations

import select
import threading
import time
from dataclasses import dataclass
from typing import Any

import numpy as np
from google.protobuf.message import DecodeError

from ..envs.actions import CHIP_ACTION_DIM
from ..physics.field import FieldGeometry
from ..physics.params import BallParams, RobotParams
from .command_codec import encode_grsim_packet, encode_robot_control
from .perception import VisionWorld
from .proto import ssl_referee_pb2 as ref_pb
from .proto import ssl_simulation_pb2 as sim_pb
from .proto import ssl_vision_wrapper_pb2 as wrap_pb
from .referee_codec import RefereeFollower
from .transport import UdpReceiver, parse_address
from .vision_codec import Detections, merge_frames

PROTOCOLS = ("simulation", "grsim")
#: the stop command: no motion, dribbler off, no kick, flat
STOP = np.array([0, 0, 0, -1, -1, 0], np.float32)


class PlayBrain:
    """Detections in, robot commands out, for one colour.

    Args:
        team: "blue" or "yellow". kind: a team kind (:data:`~ssl_marl.runners.controllers.TEAM_KINDS`).
        robots: robots per team. field: "div_a" / "div_b". seed: the controller's seed.
        skills, decision: as :func:`~ssl_marl.runners.controllers.make_controller`.
        dt: the simulator's control period (s). tracker: track the detections (see the
            module docstring). latency_steps: control periods between a frame's capture
            and the tick its command acts on (1: the next tick, as on the bridge).
    """

    def __init__(self, team: str, kind: str = "baseline", robots: int = 6, field: str = "div_b", seed: int = 0,
                 skills: Any = None, decision: Any = None, dt: float = 1.0 / 60.0, tracker: bool = True,
                 latency_steps: int = 1) -> None:
        from ..runners.controllers import STP_KINDS, make_controller

        if team not in ("blue", "yellow"):
            raise ValueError(f"team must be 'blue' or 'yellow', got {team!r}")
        self.team, self.n = team, robots
        self.field = FieldGeometry.from_name(field)
        self.robot, self.ball = RobotParams(), BallParams()
        extra = dict(robot=self.robot, ball=self.ball, dt=dt) if kind in STP_KINDS else {}
        self.controller = make_controller(kind, team, robots, self.field, seed=seed, skills=skills,
                                          decision=decision, **extra)
        if hasattr(self.controller, "reset"):
            self.controller.reset()
        self.vision = VisionWorld(robots, self.field, self.robot, self.ball)
        self.dt, self.latency_steps = float(dt), int(latency_steps)
        self.tracker = None
        if tracker:
            from ..envs.tracking import VisionTracker

            self.tracker = VisionTracker(team, self.robot, self.ball, self.dt)
        self.halted = False
        self.score: dict[str, int] | None = None
        self.decisions = 0
        self.referee = RefereeFollower()
        from ..plays.team import TeamController

        self._obeys_referee = isinstance(self.controller, TeamController)

    def on_referee(self, msg: ref_pb.Referee) -> None:
        """Follow HALT and the game controller's commands; tell play selection about goals."""
        self.halted = msg.command == ref_pb.Referee.HALT
        self.referee.on_message(msg)
        score = {"blue": msg.blue.score, "yellow": msg.yellow.score}
        if self.score is not None and hasattr(self.controller, "notify_goal"):
            other = "yellow" if self.team == "blue" else "blue"
            for _ in range(max(score[self.team] - self.score[self.team], 0)):
                self.controller.notify_goal(True)
            for _ in range(max(score[other] - self.score[other], 0)):
                self.controller.notify_goal(False)
        self.score = score

    def on_feedback(self, feedback) -> None:
        """Dribbler contact from a ``RobotControlResponse``'s feedback list."""
        self.vision.set_feedback(self.team, {f.id.id: f.dribbler_ball_contact for f in feedback
                                             if f.HasField("dribbler_ball_contact")})

    def decide(self, det: Detections) -> dict[int, np.ndarray] | None:
        """Normalised actions {robot id: (6,)} (the env's chip layout; a team's five-entry
        actions get a flat chip entry) for a detection set (None: not a new frame)."""
        from ..envs.actions import fit_action

        world = self.vision.update(det)
        if world is None:
            return None
        self.decisions += 1
        extra = {"referee": self.referee.update(world.ball_pos)} if self._obeys_referee else {}
        if self.halted:
            actions = {f"{self.team}_{i}": STOP.copy() for i in range(self.n)}
        elif self.tracker is not None:
            from ..physics.state import to_team_frame

            self.tracker.update(to_team_frame(world, self.team))
            actions = self.controller.act(self.tracker.predict(world.t + self.latency_steps * self.dt), **extra)
        else:
            actions = self.controller.act(world, **extra)
        by_id = {int(name.rsplit("_", 1)[1]): fit_action(a, CHIP_ACTION_DIM) for name, a in actions.items()}
        if self.tracker is not None:
            rows = np.array([by_id.get(i, STOP) for i in range(self.n)])
            self.tracker.record_command(self.tracker.tick_of(world.t) + self.latency_steps, rows)
        return by_id

    def robot_control(self, actions: dict[int, np.ndarray]) -> sim_pb.RobotControl:
        return encode_robot_control(actions, self.robot)


@dataclass(frozen=True)
class ClientConfig:
    """Where a :class:`PlayClient` listens and sends.

    Attributes:
        vision, referee: addresses to listen on ("group:port" joins a multicast group).
        simulator: "host:port" the commands go to (the colour's simulation-protocol port,
            or the grSim command port with ``protocol="grsim"``); None = the SSL
            defaults on 127.0.0.1 (10301 blue / 10302 yellow, grSim 20011).
        protocol: "simulation" or "grsim".
    """

    vision: str = "224.5.23.2:10020"
    referee: str = "224.5.23.1:10003"
    simulator: str | None = None
    protocol: str = "simulation"


class PlayClient:
    """A team of ours playing through SSL's network protocols (module docstring)."""

    def __init__(self, brain: PlayBrain, config: ClientConfig = ClientConfig()) -> None:
        if config.protocol not in PROTOCOLS:
            raise ValueError(f"protocol must be one of {PROTOCOLS}, got {config.protocol!r}")
        self.brain, self.config = brain, config
        default = 20011 if config.protocol == "grsim" else (10301 if brain.team == "blue" else 10302)
        self.simulator = parse_address(config.simulator or f"127.0.0.1:{default}")
        self.vision_in = UdpReceiver(config.vision)
        self.referee_in = UdpReceiver(config.referee)
        self.command_sock = UdpReceiver(("0.0.0.0" if self.simulator[0] != "127.0.0.1" else "127.0.0.1", 0))
        self.stop_event = threading.Event()
        self._frames: dict[float, list] = {}
        self.sent = 0
        self.post_game = False

    def _read_vision(self) -> None:
        for data, _ in self.vision_in.receive():
            packet = wrap_pb.SSL_WrapperPacket()
            try:
                packet.ParseFromString(data)
            except (DecodeError, ValueError, RuntimeError):
                continue
            if packet.HasField("detection"):
                self._frames.setdefault(packet.detection.t_capture, []).append(packet.detection)

    def _read_referee(self) -> None:
        for data, _ in self.referee_in.receive():
            msg = ref_pb.Referee()
            try:
                msg.ParseFromString(data)
            except (DecodeError, ValueError, RuntimeError):
                continue
            self.brain.on_referee(msg)
            self.post_game = msg.stage == ref_pb.Referee.POST_GAME

    def _read_replies(self) -> None:
        for data, _ in self.command_sock.receive():
            resp = sim_pb.RobotControlResponse()
            try:
                resp.ParseFromString(data)
            except (DecodeError, ValueError, RuntimeError):
                continue
            self.brain.on_feedback(resp.feedback)

    def send(self, actions: dict[int, np.ndarray]) -> None:
        """Send ``actions`` by the configured protocol."""
        if self.config.protocol == "grsim":
            payload = encode_grsim_packet(actions, self.brain.team == "yellow", time.time(),
                                          self.brain.robot).SerializeToString()
        else:
            payload = self.brain.robot_control(actions).SerializeToString()
        if self.command_sock.reply(payload, self.simulator):
            self.sent += 1

    def tick(self, timeout: float = 0.05) -> bool:
        """Wait for input up to ``timeout`` s, handle it, act on the newest frame; True if commands went out."""
        socks = [self.vision_in, self.referee_in, self.command_sock]
        readable, _, _ = select.select(socks, [], [], timeout)
        if self.referee_in in readable:
            self._read_referee()
        if self.command_sock in readable:
            self._read_replies()
        if self.vision_in not in readable:
            return False
        self._read_vision()
        if not self._frames:
            return False
        newest = max(self._frames)
        det = merge_frames(self._frames.pop(newest))
        self._frames = {t: f for t, f in self._frames.items() if t > newest}
        actions = self.brain.decide(det)
        if actions is None:
            return False
        self.send(actions)
        return True

    def run(self, max_wall_s: float | None = None, stop_at_post_game: bool = True) -> int:
        """Play until :meth:`stop`, the referee's POST_GAME or ``max_wall_s``; commands sent."""
        start = time.monotonic()
        while not self.stop_event.is_set():
            if max_wall_s is not None and time.monotonic() - start >= max_wall_s:
                break
            if stop_at_post_game and self.post_game:
                break
            self.tick()
        return self.sent

    def start(self, max_wall_s: float | None = None) -> threading.Thread:
        thread = threading.Thread(target=self.run, kwargs={"max_wall_s": max_wall_s}, daemon=True)
        thread.start()
        return thread

    def stop(self) -> None:
        self.stop_event.set()

    def close(self) -> None:
        for s in (self.vision_in, self.referee_in, self.command_sock):
            s.close()


def run_lockstep_match(sync_ports: dict[str, Any], brains: dict[str, PlayBrain], dt: float = 1.0 / 60.0,
                       max_steps: int | None = None) -> int:
    """Drive the brains (one or both colours) through a lock-step server
    (``sync_ports``: {team: "host:port"}) until the match ends (no detections come
    back) or ``max_steps``; returns the control periods stepped."""
    from .lockstep import LockstepClient

    clients = {team: LockstepClient(sync_ports[team], timeout_s=5.0) for team in brains}
    try:
        actions: dict[str, dict[int, np.ndarray]] = {team: {} for team in brains}
        steps = 0
        while max_steps is None or steps < max_steps:
            for team, client in clients.items():
                control = brains[team].robot_control(actions[team]) if actions[team] else None
                client.send(dt if steps else 0.0, control)
            responses = {team: client.receive() for team, client in clients.items()}
            if steps and not any(len(r.detection) for r in responses.values()):
                break
            for team, resp in responses.items():
                brains[team].on_feedback(resp.robot_control_response.feedback)
                if resp.detection:
                    t_last = max(f.t_capture for f in resp.detection)
                    det = merge_frames([f for f in resp.detection if f.t_capture == t_last])
                    acts = brains[team].decide(det)
                    if acts is not None:
                        actions[team] = acts
            steps += 1
        return steps - 1
    finally:
        for client in clients.values():
            client.close()
