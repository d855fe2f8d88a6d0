"""Robot commands <-> our normalised actions.

Our action per robot is the env's chip layout (:mod:`ssl_marl.envs.actions`, six
entries): body-frame vx, vy (fractions of ``RobotParams.max_speed``), omega (fraction of
``max_omega``), dribbler (on when > 0), kick strength (3-D ball speed ``kick *
kick_speed_max`` when > 0) and chip (kick elevation ``chip * chip_angle_max`` when > 0,
else flat). The SSL simulation protocol's ``RobotCommand`` and grSim's
``grSim_Robot_Command`` carry SI values: m/s forward / left in the robot frame (or x / y
in the field frame for a global velocity), rad/s; the simulation protocol's kick is a
3-D ball speed ``kick_speed`` (m/s) at the elevation ``kick_angle`` (degrees, 0 =
flat), grSim's the ball velocity's parts along the heading ``kickspeedx`` and upwards
``kickspeedz`` (m/s); either is a chip when it lifts the ball
(docs/references.md, "SSL network protocols").

Decoding never raises on bad input: a command with a non-finite value or a value
beyond :data:`SANE_SPEED` / :data:`SANE_OMEGA` / :data:`SANE_KICK` is dropped with a
:class:`CommandError`. A kick beyond the kicker (3-D speed above
``RobotParams.kick_speed_max``, elevation above ``RobotParams.chip_angle_max`` or below
0) is executed at the nearest value the kicker can do and answered with a
``VALUE_CLIPPED`` error naming the field; what the physics cannot do (wheel
velocities) is answered with an error too.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..envs.actions import ACTION_DIM, CHIP_ACTION_DIM
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
                    robot: RobotParams, elevation: float = 0.0) -> np.ndarray:
    """The normalised (6,) action (the env's chip layout) of SI body-frame velocities
    (m/s, rad/s), the dribbler, a 3-D kick speed (m/s, 0 = no kick) and its elevation
    (rad, 0 = flat); entries clipped to [-1, 1]. The chip entry is 0 (flat) without a
    kick or lift."""
    kick = min(kick_speed / robot.kick_speed_max, 1.0) if kick_speed > 0 else -1.0
    chip = elevation / robot.chip_angle_max if kick_speed > 0 and elevation > 0 else 0.0
    a = np.array([forward / robot.max_speed, left / robot.max_speed, angular / robot.max_omega,
                  1.0 if dribble else -1.0, kick, chip], dtype=np.float32)
    return np.clip(a, -1.0, 1.0)


def _sane(forward: float, left: float, angular: float, kick: float, what: str) -> CommandError | None:
    if not _finite(forward, left, angular, kick):
        return CommandError("INVALID_VALUE", f"{what}: non-finite velocity or kick speed")
    if math.hypot(forward, left) > SANE_SPEED or abs(angular) > SANE_OMEGA or abs(kick) > SANE_KICK:
        return CommandError("VALUE_OUT_OF_RANGE", f"{what}: velocity {math.hypot(forward, left):.3g} m/s, "
                                                  f"angular {angular:.3g} rad/s or kick {kick:.3g} m/s is out of range")
    return None


def fit_kick(speed: float, elevation: float, robot: RobotParams, what: str, speed_field: str,
             angle_field: str) -> tuple[float, float, list[CommandError]]:
    """(3-D speed m/s, elevation rad, errors) of a requested kick, within what the kicker
    can do: speed at most ``robot.kick_speed_max``, elevation in [0,
    ``robot.chip_angle_max``]. Each clipped value is answered with a ``VALUE_CLIPPED``
    error naming ``speed_field`` / ``angle_field`` (the command's fields). No kick
    (``speed`` <= 0): (0, 0, no errors)."""
    if speed <= 0.0:
        return 0.0, 0.0, []
    errors = []
    cap_speed, cap_angle = robot.kick_speed_max, robot.chip_angle_max
    if speed > cap_speed * (1.0 + 1e-6):
        errors.append(CommandError("VALUE_CLIPPED", f"{what}: {speed_field} {speed:.4g} m/s is above the kicker's "
                                                    f"{cap_speed:.4g} m/s; kicked at {cap_speed:.4g} m/s"))
    if elevation > cap_angle + 1e-6:
        errors.append(CommandError("VALUE_CLIPPED", f"{what}: {angle_field} {math.degrees(elevation):.4g} deg is "
                                                    f"above the kicker's {math.degrees(cap_angle):.4g} deg; chipped "
                                                    f"at {math.degrees(cap_angle):.4g} deg"))
    elif elevation < -1e-6:
        errors.append(CommandError("VALUE_CLIPPED", f"{what}: {angle_field} {math.degrees(elevation):.4g} deg is "
                                                    "below 0 deg; kicked flat"))
    return min(speed, cap_speed), min(max(elevation, 0.0), cap_angle), errors


def decode_robot_command(cmd: sim_pb.RobotCommand, heading: float,
                         robot: RobotParams) -> tuple[np.ndarray | None, list[CommandError]]:
    """(action or None when dropped, errors) of a simulation-protocol command for a robot
    whose field-frame heading is ``heading`` (rad; turns a global velocity into the body
    frame). A command without a move command keeps the robot still; ``kick_speed`` is the
    ball's 3-D speed, ``kick_angle`` its elevation (degrees)."""
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
    speed, elevation, kick_errors = fit_kick(kick_speed, math.radians(angle), robot, what, "kick_speed", "kick_angle")
    dribble = cmd.HasField("dribbler_speed") and cmd.dribbler_speed > 0
    return velocity_action(forward, left, angular, dribble, speed, robot, elevation), errors + kick_errors


def decode_grsim_command(cmd: grsim_pb.grSim_Robot_Command,
                         robot: RobotParams) -> tuple[np.ndarray | None, list[CommandError]]:
    """(action or None when dropped, errors) of a legacy grSim robot command: the kick is
    the ball velocity ``kickspeedx`` along the heading and ``kickspeedz`` up (m/s; a
    negative part counts as 0), i.e. 3-D speed hypot(x, z) at elevation atan2(z, x)."""
    what = f"robot {cmd.id}"
    if not math.isfinite(cmd.kickspeedz):
        return None, [CommandError("INVALID_VALUE", f"{what}: non-finite kickspeedz")]
    horizontal, vertical = max(cmd.kickspeedx, 0.0), max(cmd.kickspeedz, 0.0)
    speed = math.hypot(horizontal, vertical) if math.isfinite(cmd.kickspeedx) else cmd.kickspeedx
    bad = _sane(cmd.veltangent, cmd.velnormal, cmd.velangular, speed, what)
    if bad is not None:
        return None, [bad]
    errors = []
    if cmd.wheelsspeed:
        errors.append(CommandError("WHEEL_VELOCITY_UNSUPPORTED", f"{what}: wheel speeds are not simulated"))
    speed, elevation, kick_errors = fit_kick(speed, math.atan2(vertical, horizontal), robot, what,
                                             "kick speed hypot(kickspeedx, kickspeedz)",
                                             "kick elevation atan2(kickspeedz, kickspeedx)")
    return velocity_action(cmd.veltangent, cmd.velnormal, cmd.velangular, cmd.spinner, speed, robot,
                           elevation), errors + kick_errors


def action_velocities(action: np.ndarray, robot: RobotParams) -> tuple[float, float, float, bool, float, float]:
    """(forward m/s, left m/s, angular rad/s, dribbler on, 3-D kick speed m/s, kick
    elevation rad) of a normalised (5,) or (6,) action (a (5,) action kicks flat)."""
    a = np.clip(np.nan_to_num(np.asarray(action, float), nan=0.0), -1.0, 1.0)
    kick = float(a[4]) * robot.kick_speed_max if a[4] > 0 else 0.0
    elevation = float(a[ACTION_DIM]) * robot.chip_angle_max if a.shape[-1] >= CHIP_ACTION_DIM and kick > 0 \
        and a[ACTION_DIM] > 0 else 0.0
    return (float(a[0]) * robot.max_speed, float(a[1]) * robot.max_speed, float(a[2]) * robot.max_omega,
            bool(a[3] > 0), kick, elevation)


def encode_robot_control(actions: dict[int, np.ndarray], robot: RobotParams) -> sim_pb.RobotControl:
    """A simulation-protocol ``RobotControl`` of {robot id: normalised action} (local
    velocities; a chip as ``kick_angle`` in degrees)."""
    msg = sim_pb.RobotControl()
    for rid, action in sorted(actions.items()):
        fwd, left, ang, drib, kick, elevation = action_velocities(action, robot)
        cmd = msg.robot_commands.add(id=int(rid), kick_speed=kick, kick_angle=math.degrees(elevation),
                                     dribbler_speed=DRIBBLER_RPM if drib else 0.0)
        cmd.move_command.local_velocity.forward = fwd
        cmd.move_command.local_velocity.left = left
        cmd.move_command.local_velocity.angular = ang
    return msg


def encode_grsim_packet(actions: dict[int, np.ndarray], yellow: bool, timestamp: float,
                        robot: RobotParams) -> grsim_pb.grSim_Packet:
    """A legacy ``grSim_Packet`` of {robot id: normalised action} for one team (a chip as
    the kick's parts along the heading and up)."""
    packet = grsim_pb.grSim_Packet()
    packet.commands.timestamp = float(timestamp)
    packet.commands.isteamyellow = bool(yellow)
    for rid, action in sorted(actions.items()):
        fwd, left, ang, drib, kick, elevation = action_velocities(action, robot)
        packet.commands.robot_commands.add(id=int(rid), kickspeedx=kick * math.cos(elevation),
                                           kickspeedz=kick * math.sin(elevation), veltangent=fwd, velnormal=left,
                                           velangular=ang, spinner=drib, wheelsspeed=False)
    return packet
