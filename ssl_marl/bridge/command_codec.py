"""Robot commands <-> our normalised actions.

Our action per robot (:mod:`ssl_marl.envs.actions`): body-frame vx, vy (fractions of
``RobotParams.max_speed``), omega (fraction of ``max_omega``), dribbler (on when > 0),
kick strength (ball speed ``kick * kick_speed_max`` when > 0). The SSL simulation
protocol's ``RobotCommand`` and grSim's ``grSim_Robot_Command`` carry SI values: m/s
forward / left in the robot frame (or x / y in the field frame for a global
velocity), rad/s, kick speed m/s.

Decoding never raises on bad input: a command with a non-finite value or a value
beyond :data:`SANE_SPEED` / :data:`SANE_OMEGA` / :data:`SANE_KICK` is dropped with a
:class:`CommandError`; what the physics cannot do (wheel velocities, chip kicks) is
answered with an error too, a chip being executed as a flat kick of its horizontal speed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..physics.params import RobotParams
from .proto import grsim_packet_pb2 as grsim_pb
from .proto import ssl_simulation_pb2 as sim_pb

SANE_SPEED = 100.0  # m/s: a larger commanded speed is garbage, not a fast robot
SANE_OMEGA = 1000.0  # rad/s
SANE_KICK = 100.0  # m/s
DRIBBLER_RPM = 1000.0  # dribbler speed the client sends for "dribbler on"


@dataclass(frozen=True)
class CommandError:
    """An error code (SSL simulation protocol ``SimulatorError.code``) and message."""

    code: str
    message: str

    def to_proto(self) -> sim_pb.SimulatorError:
        err = sim_pb.SimulatorError(code=self.code, message=self.message)
        if self.code == "WHEEL_VELOCITY_UNSUPPORTED":
            err.unsupported_capability = sim_pb.SIMULATOR_CAPABILITY_MOVE_WHEEL_VELOCITY
        return err


def _finite(*values: float) -> bool:
    return all(math.isfinite(v) for v in values)


def velocity_action(forward: float, left: float, angular: float, dribble: bool, kick_speed: float,
                    robot: RobotParams) -> np.ndarray:
    """The normalised (5,) action of SI body-frame velocities (m/s, rad/s), the
    dribbler and a kick speed (m/s, 0 = no kick); entries clipped to [-1, 1]."""
    kick = min(kick_speed / robot.kick_speed_max, 1.0) if kick_speed > 0 else -1.0
    a = np.array([forward / robot.max_speed, left / robot.max_speed, angular / robot.max_omega,
                  1.0 if dribble else -1.0, kick], dtype=np.float32)
    return np.clip(a, -1.0, 1.0)


def _sane(forward: float, left: float, angular: float, kick: float, what: str) -> CommandError | None:
    if not _finite(forward, left, angular, kick):
        return CommandError("INVALID_VALUE", f"{what}: non-finite velocity or kick speed")
    if math.hypot(forward, left) > SANE_SPEED or abs(angular) > SANE_OMEGA or abs(kick) > SANE_KICK:
        return CommandError("VALUE_OUT_OF_RANGE", f"{what}: velocity {math.hypot(forward, left):.3g} m/s, "
                                                  f"angular {angular:.3g} rad/s or kick {kick:.3g} m/s is out of range")
    return None


def decode_robot_command(cmd: sim_pb.RobotCommand, heading: float,
                         robot: RobotParams) -> tuple[np.ndarray | None, list[CommandError]]:
    """(action or None when dropped, errors) of a simulation-protocol command for a robot
    whose field-frame heading is ``heading`` (rad; turns a global velocity into the body
    frame). A command without a move command keeps the robot still."""
    what = f"robot {cmd.id}"
    errors: list[CommandError] = []
    forward = left = angular = 0.0
    move = cmd.move_command.WhichOneof("command") if cmd.HasField("move_command") else None
    if move == "local_velocity":
        lv = cmd.move_command.local_velocity
        forward, left, angular = lv.forward, lv.left, lv.angular
    elif move == "global_velocity":
        gv = cmd.move_command.global_velocity
        if not _finite(gv.x, gv.y, gv.angular):
            return None, [CommandError("INVALID_VALUE", f"{what}: non-finite global velocity")]
        c, s = math.cos(heading), math.sin(heading)
        forward, left, angular = c * gv.x + s * gv.y, -s * gv.x + c * gv.y, gv.angular
    elif move == "wheel_velocity":
        errors.append(CommandError("WHEEL_VELOCITY_UNSUPPORTED",
                                   f"{what}: wheel velocities are not simulated; send a local or global velocity"))
    kick_speed = cmd.kick_speed if cmd.HasField("kick_speed") else 0.0
    angle = cmd.kick_angle if cmd.HasField("kick_angle") else 0.0
    bad = _sane(forward, left, angular, kick_speed, what) or (
        None if _finite(angle, cmd.dribbler_speed) else CommandError("INVALID_VALUE", f"{what}: non-finite field"))
    if bad is not None:
        return None, [bad]
    if kick_speed > 0 and angle != 0:
        errors.append(CommandError("CHIP_KICK_UNSUPPORTED",
                                   f"{what}: chip kicks are not simulated; kicked flat at the horizontal speed"))
        kick_speed *= max(math.cos(math.radians(angle)), 0.0)
    dribble = cmd.HasField("dribbler_speed") and cmd.dribbler_speed > 0
    return velocity_action(forward, left, angular, dribble, max(kick_speed, 0.0), robot), errors


def decode_grsim_command(cmd: grsim_pb.grSim_Robot_Command,
                         robot: RobotParams) -> tuple[np.ndarray | None, list[CommandError]]:
    """(action or None when dropped, errors) of a legacy grSim robot command."""
    what = f"robot {cmd.id}"
    bad = _sane(cmd.veltangent, cmd.velnormal, cmd.velangular, cmd.kickspeedx, what)
    if bad is None and not math.isfinite(cmd.kickspeedz):
        bad = CommandError("INVALID_VALUE", f"{what}: non-finite kickspeedz")
    if bad is not None:
        return None, [bad]
    errors = []
    if cmd.wheelsspeed:
        errors.append(CommandError("WHEEL_VELOCITY_UNSUPPORTED", f"{what}: wheel speeds are not simulated"))
    if cmd.kickspeedz > 0:
        errors.append(CommandError("CHIP_KICK_UNSUPPORTED", f"{what}: chip kicks are not simulated; kicked flat"))
    return velocity_action(cmd.veltangent, cmd.velnormal, cmd.velangular, cmd.spinner,
                           max(cmd.kickspeedx, 0.0), robot), errors


def action_velocities(action: np.ndarray, robot: RobotParams) -> tuple[float, float, float, bool, float]:
    """(forward m/s, left m/s, angular rad/s, dribbler on, kick speed m/s) of a normalised action."""
    a = np.clip(np.nan_to_num(np.asarray(action, float), nan=0.0), -1.0, 1.0)
    kick = float(a[4]) * robot.kick_speed_max if a[4] > 0 else 0.0
    return (float(a[0]) * robot.max_speed, float(a[1]) * robot.max_speed, float(a[2]) * robot.max_omega,
            bool(a[3] > 0), kick)


def encode_robot_control(actions: dict[int, np.ndarray], robot: RobotParams) -> sim_pb.RobotControl:
    """A simulation-protocol ``RobotControl`` of {robot id: normalised action} (local velocities)."""
    msg = sim_pb.RobotControl()
    for rid, action in sorted(actions.items()):
        fwd, left, ang, drib, kick = action_velocities(action, robot)
        cmd = msg.robot_commands.add(id=int(rid), kick_speed=kick, kick_angle=0.0,
                                     dribbler_speed=DRIBBLER_RPM if drib else 0.0)
        cmd.move_command.local_velocity.forward = fwd
        cmd.move_command.local_velocity.left = left
        cmd.move_command.local_velocity.angular = ang
    return msg


def encode_grsim_packet(actions: dict[int, np.ndarray], yellow: bool, timestamp: float,
                        robot: RobotParams) -> grsim_pb.grSim_Packet:
    """A legacy ``grSim_Packet`` of {robot id: normalised action} for one team."""
    packet = grsim_pb.grSim_Packet()
    packet.commands.timestamp = float(timestamp)
    packet.commands.isteamyellow = bool(yellow)
    for rid, action in sorted(actions.items()):
        fwd, left, ang, drib, kick = action_velocities(action, robot)
        packet.commands.robot_commands.add(id=int(rid), kickspeedx=kick, kickspeedz=0.0, veltangent=fwd,
                                           velnormal=left, velangular=ang, spinner=drib, wheelsspeed=False)
    return packet
