"""The served match world without sockets: :class:`BridgeWorld`.

It owns the env (a full-field match, :func:`ssl_marl.envs.parallel_env`, with chip
kicks: the ball can fly), the last command of every robot, the teams of ours that drive
the robots no client commands, the referee stream and the vision cameras. Everything it
takes is a protobuf message (simulation protocol, grSim); everything it gives is a
protobuf message (vision, referee, tracker, replies). Bad input is answered with errors
and counted, never raised.

Frames and units: the env works in metres in the field frame (blue attacks +x); the
simulation protocol and grSim use metres too (grSim's replacement heading is in
degrees); vision is converted to mm by :mod:`.vision_codec`. Commands are the env's
six-entry chip layout (:mod:`.command_codec`); our teams' five-entry actions get a flat
chip entry (:func:`ssl_marl.envs.actions.fit_action`).
"""

from __future__ import annotations

import math
from collections import Counter
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..envs.actions import ACTION_DIM
from .command_codec import CommandError, decode_grsim_command, decode_robot_command
from .proto import grsim_packet_pb2 as grsim_pb
from .proto import ssl_simulation_pb2 as sim_pb
from .referee_codec import GameView, RefereeState
from .tracker_codec import tracker_packet
from .vision_codec import camera_regions, detection_frames, geometry_data

TEAM_OF_PROTO = {sim_pb.BLUE: "blue", sim_pb.YELLOW: "yellow"}
MAX_SPEED_FACTOR = 100.0  # largest simulation speed a client may ask for


@dataclass(frozen=True)
class WorldConfig:
    """What the served match is.

    Attributes:
        robots: robots per team. field: "div_a" / "div_b". seconds: match length (s of
        simulated time). seed: env seed. realism: the env's realism preset (vision
        noise, latency, dropout; radio loss). n_cameras: 1, 2, 4 or 8 cameras.
        blue_team, yellow_team: the team of ours that drives the robots no client
        commands (a :data:`ssl_marl.runners.controllers.TEAM_KINDS` name; "idle" =
        stand still). command_timeout_s: a robot's last command is executed for this
        long (simulated s), then it stops; 0 = commands never expire.
        client_teams: the colours clients may command (a command for another is dropped
        with ``WRONG_TEAM``). tracker: run the project's tracker (its state goes out as
        tracker packets). start_jitter_m, restart_jitter_m: the seeded jitter of the
        kickoff formation at the start and of every restart's placement (as
        :func:`ssl_marl.runners.match.play_match`). chip_kicks: the env's chip-kick
        layout (``parallel_env(chip_kicks=True)``: chips fly, robots kick on contact);
        off, the world is the flat-kick env of :func:`~ssl_marl.runners.match.play_match`
        for teams that do not chip (what :func:`~.log_tools.record_match_log` replays),
        and a client's chip is kicked flat with a ``CHIP_KICK_UNSUPPORTED`` error.
        format: the match format (:func:`ssl_marl.runners.match.format_options`): "plain"
            (restarts at once, one period) or "ssl" (SSL game control: STOP, kickoffs and
            free kicks the teams must obey, fouls, two halves of ``seconds / 2`` on a clock
            that stops during STOP); the referee packets carry its commands
            (:mod:`.referee_codec`).
    """

    robots: int = 6
    field: str = "div_b"
    seconds: float = 300.0
    seed: int = 0
    realism: str = "none"
    n_cameras: int = 1
    blue_team: str = "idle"
    yellow_team: str = "idle"
    command_timeout_s: float = 0.1
    client_teams: tuple[str, ...] = ("blue", "yellow")
    tracker: bool = False
    start_jitter_m: float = 0.05
    restart_jitter_m: float = 0.1
    chip_kicks: bool = True
    format: str = "plain"

    def __post_init__(self) -> None:
        if self.format not in ("plain", "ssl"):
            raise ValueError(f"WorldConfig.format must be 'plain' or 'ssl', got {self.format!r}")


class BridgeWorld:
    """The match world the bridge serves (see the module docstring)."""

    def __init__(self, config: WorldConfig) -> None:
        from ..envs import parallel_env
        from ..envs.tracking import with_tracker
        from ..runners.controllers import CHIP_KINDS, STP_KINDS, make_controller
        from ..runners.match import format_options

        self.config = config
        if not config.chip_kicks:
            for team, kind in (("blue", config.blue_team), ("yellow", config.yellow_team)):
                if kind in CHIP_KINDS:
                    raise ValueError(f"{team}_team {kind!r} chips; it needs WorldConfig(chip_kicks=True)")
        options = {**format_options(config.format, float(config.seconds)), "restart_jitter_m": config.restart_jitter_m}
        env = parallel_env(n_blue=config.robots, n_yellow=config.robots, field=config.field,
                           max_time_s=float(config.seconds), realism=config.realism, after_goal="kickoff",
                           chip_kicks=bool(config.chip_kicks), **options)
        self.env = with_tracker(env, "on" if config.tracker else "auto")
        cfg = self.env.config
        self.robot, self.ball, self.field, self.dt = cfg.robot, cfg.ball, self.env.field, cfg.dt
        self.n = config.robots
        #: entries of an env action (6 with chip kicks)
        self.action_dim = int(self.env.action_dim)
        self.controllers: dict[str, Any] = {}
        for k, (team, kind) in enumerate((("blue", config.blue_team), ("yellow", config.yellow_team))):
            if kind != "idle" and self.n > 0:
                extra = dict(robot=self.robot, ball=self.ball, dt=self.dt) if kind in STP_KINDS else {}
                self.controllers[team] = make_controller(kind, team, self.n, self.field, seed=config.seed + k, **extra)
        self.regions = camera_regions(self.field, config.n_cameras)
        self.geometry = geometry_data(self.field, self.robot, self.ball)
        self.referee = RefereeState()
        self.stats: Counter = Counter()
        self.frame_numbers = [0] * len(self.regions)
        self.tracker_frame = 0
        self.events: list[dict] = []
        self.finished = False
        self.speed = 1.0
        self.reset()

    # ------------------------------------------------------------ lifecycle
    def reset(self) -> None:
        """Start the match (seeded kickoff formation) and forget all commands."""
        from ..envs.referee import match_start_options

        self.env.reset(seed=self.config.seed, options=match_start_options(self.env, self.config.seed,
                                                                    self.config.start_jitter_m))
        for ctrl in self.controllers.values():
            if hasattr(ctrl, "reset"):
                ctrl.reset()
        self.commands = {t: np.zeros((self.n, self.action_dim), np.float32) for t in ("blue", "yellow")}
        for cmd in self.commands.values():
            cmd[:, 3:5] = -1.0  # dribbler off, no kick (a chip entry stays 0: flat)
        self.kicks: dict[str, dict[int, str]] = {"blue": {}, "yellow": {}}
        self.command_time = {t: np.full(self.n, -np.inf) for t in ("blue", "yellow")}
        self.finished = False
        self.referee.start(0, self.game_view())

    @property
    def t(self) -> float:
        """Simulated time since the match start (s)."""
        return float(self.env.world_state().t)

    def game_view(self) -> GameView | None:
        """The match's SSL game control for the referee stream (None in the plain format):
        the env's command, the half and the half's time left on the match clock (s)."""
        task = getattr(self.env, "task", None)
        rules = getattr(task, "rules", None)
        if task is None or rules is None or not rules.ssl_restarts:
            return None
        clock = float(task.clock_s(self.env))
        half_end = rules.half_time_s if task.half == 1 and rules.half_time_s is not None else self.config.seconds
        return GameView(task.referee_state, int(task.half), float(half_end) - clock)

    def step(self, now_us: int) -> tuple[list[dict], bool]:
        """Advance one control period; (env events, referee command changed). ``now_us``
        stamps a new referee command (Unix µs). No-op once the match is over."""
        from ..envs.actions import fit_action

        if self.finished:
            return [], False
        actions: dict[str, np.ndarray] = {}
        for team in ("blue", "yellow"):
            ctrl = self.controllers.get(team)
            if ctrl is not None:
                acted = ctrl.act(self.env)  # as play_match: fitted in a chip env, as they are in a flat one
                actions.update(acted if self.action_dim == ACTION_DIM
                               else {k: fit_action(v, self.action_dim) for k, v in acted.items()})
            fresh = (self.t - self.command_time[team] <= self.config.command_timeout_s + 1e-9
                     if self.config.command_timeout_s > 0 else np.isfinite(self.command_time[team]))
            for i in np.flatnonzero(fresh):
                actions[f"{team}_{i}"] = self.commands[team][i]
        _, _, term, trunc, infos = self.env.step(actions)
        events = next(iter(infos.values()))["events"] if infos else []
        self.finished = not self.env.agents
        time_left = self.config.seconds - self.t
        changed = self.referee.update(events, self.env.world_state(), self.env.score, time_left, self.finished, now_us,
                                      game=self.game_view())
        self.events = events
        self.stats["steps"] += 1
        self._note_kicks(events)
        return events, changed

    def _note_kicks(self, events: list[dict]) -> None:
        """Remember this step's kicks for :meth:`take_kicks`: a chip when the ball left
        the ground after it (ground truth), else flat."""
        kicks = [e["agent"] for e in events if e["type"] == "kick"]
        if not kicks:
            return
        ws = self.env.world_state()
        kind = "chip" if ws.ball_height > 0.0 or ws.ball_vz > 0.0 or ws.ball_max_height > 0.0 else "flat"
        for agent in kicks:
            team, rid = agent.rsplit("_", 1)
            self.kicks[team][int(rid)] = kind

    # --------------------------------------------------------------- output
    def detections(self, t_capture: float, t_sent: float) -> list:
        """This step's detection frames, one per camera (what the teams see: the
        realism preset's noise, dropout and latency applied)."""
        frames = detection_frames(self._raw_vision(), self.regions, self.frame_numbers, t_capture, t_sent)
        self.frame_numbers = [n + 1 for n in self.frame_numbers]
        return frames

    def _raw_vision(self):
        env = self.env
        return env.raw_vision_state() if hasattr(env, "raw_vision_state") else env.vision_state()

    def tracker(self, timestamp: float, uuid: str):
        """A tracker packet of the project's tracker (blue's tracked view: the field frame)."""
        self.tracker_frame += 1
        tracked = hasattr(self.env, "raw_vision_state")  # vision_state(): blue's tracked view, field frame
        return tracker_packet(self.env.vision_state() if tracked else self.env.world_state(), self.tracker_frame,
                              timestamp, uuid)

    def feedback(self, team: str) -> list[sim_pb.RobotFeedback]:
        """Per robot of ``team``: dribbler contact (ground truth, as a light barrier reports)."""
        held = self.env.world_state().team(team).ball_on_dribbler
        colour = sim_pb.BLUE if team == "blue" else sim_pb.YELLOW
        return [sim_pb.RobotFeedback(id=sim_pb.RobotId(id=i, team=colour), dribbler_ball_contact=bool(held[i]))
                for i in range(self.n)]

    def take_kicks(self, team: str) -> dict[int, str]:
        """{robot id: "flat" or "chip"} of ``team``'s kicks since the last call (grSim's
        robot status reports them), forgotten once taken."""
        kicks, self.kicks[team] = self.kicks[team], {}
        return kicks

    # ---------------------------------------------------------------- input
    def _error(self, errors: list, code: str, message: str) -> None:
        self.stats[f"error:{code}"] += 1
        errors.append(CommandError(code, message))

    def robot_control(self, team: str, control: sim_pb.RobotControl) -> list[CommandError]:
        """Apply a simulation-protocol ``RobotControl`` for ``team``; its errors."""
        errors: list[CommandError] = []
        if team not in self.config.client_teams:
            self._error(errors, "WRONG_TEAM", f"{team} is not commanded by clients on this server")
            return errors
        heading = self.env.world_state().team(team).heading
        for cmd in control.robot_commands:
            if not 0 <= cmd.id < self.n:
                self._error(errors, "UNKNOWN_ROBOT", f"{team} robot {cmd.id} does not exist (0..{self.n - 1})")
                continue
            action, errs = decode_robot_command(cmd, float(heading[cmd.id]), self.robot)
            for e in errs:
                self._error(errors, e.code, e.message)
            if action is not None:
                self._set_command(team, cmd.id, action, errors)
        return errors

    def grsim_packet(self, packet: grsim_pb.grSim_Packet) -> tuple[str | None, list[CommandError]]:
        """Apply a legacy grSim packet (commands and replacement); (commanded team, errors)."""
        errors: list[CommandError] = []
        team = None
        if packet.HasField("commands"):
            team = "yellow" if packet.commands.isteamyellow else "blue"
            if team not in self.config.client_teams:
                self._error(errors, "WRONG_TEAM", f"{team} is not commanded by clients on this server")
            else:
                for cmd in packet.commands.robot_commands:
                    if not 0 <= cmd.id < self.n:
                        self._error(errors, "UNKNOWN_ROBOT", f"{team} robot {cmd.id} does not exist")
                        continue
                    action, errs = decode_grsim_command(cmd, self.robot)
                    for e in errs:
                        self._error(errors, e.code, e.message)
                    if action is not None:
                        self._set_command(team, cmd.id, action, errors)
        if packet.HasField("replacement"):
            rep = packet.replacement
            control = sim_pb.SimulatorControl()
            if rep.HasField("ball"):
                b = rep.ball
                tb = control.teleport_ball
                for name in ("x", "y", "vx", "vy"):
                    if b.HasField(name):
                        setattr(tb, name, getattr(b, name))
            for r in rep.robots:
                tr = control.teleport_robot.add(x=r.x, y=r.y, orientation=math.radians(r.dir))
                tr.id.id, tr.id.team = r.id, sim_pb.YELLOW if r.yellowteam else sim_pb.BLUE
                if r.HasField("turnon") and not r.turnon:
                    tr.present = False
            errors += self.simulator_control(control)
        return team, errors

    def _set_command(self, team: str, rid: int, action: np.ndarray, errors: list) -> None:
        """Store a decoded (6,) command; in a world without chip kicks a chip is kicked
        flat (its chip entry dropped) with an error."""
        if self.action_dim < action.shape[-1] and action[self.action_dim:].max() > 0 and action[4] > 0:
            self._error(errors, "CHIP_KICK_UNSUPPORTED", f"{team} robot {rid}: this world has chip kicks off "
                                                         "(WorldConfig.chip_kicks); kicked flat")
        self.commands[team][rid] = action[:self.action_dim]
        self.command_time[team][rid] = self.t
        self.stats["commands"] += 1
        self.stats[f"commands:{team}"] += 1

    def simulator_command(self, command: sim_pb.SimulatorCommand, vision_port_setter=None) -> list[CommandError]:
        """Apply a ``SimulatorCommand`` (control, and of the config only ``vision_port``
        through ``vision_port_setter(port)``); its errors."""
        errors: list[CommandError] = []
        if command.HasField("control"):
            errors += self.simulator_control(command.control)
        if command.HasField("config"):
            cfg = command.config
            for name, code in (("geometry", "GEOMETRY_UNSUPPORTED"), ("realism_config", "REALISM_UNSUPPORTED")):
                if cfg.HasField(name):
                    self._error(errors, code, f"config.{name} cannot be changed on this simulator")
            if len(cfg.robot_specs):
                self._error(errors, "ROBOT_SPECS_UNSUPPORTED", "robot specs cannot be changed on this simulator")
            if cfg.HasField("vision_port"):
                if vision_port_setter is None or not 0 < cfg.vision_port < 65536:
                    self._error(errors, "VISION_PORT_UNSUPPORTED", f"vision port {cfg.vision_port} not applied")
                else:
                    vision_port_setter(int(cfg.vision_port))
        return errors

    def simulator_control(self, control: sim_pb.SimulatorControl) -> list[CommandError]:
        """Teleport the ball and robots, set the simulation speed; errors for what the
        planar simulation cannot do (height, spin, robot velocities, removal)."""
        errors: list[CommandError] = []
        wx, wy = self.field.wall_half_length - 0.05, self.field.wall_half_width - 0.05
        if control.HasField("teleport_ball"):
            tb = control.teleport_ball
            truth = self.env.world_state()
            x = tb.x if tb.HasField("x") else float(truth.ball_pos[0])
            y = tb.y if tb.HasField("y") else float(truth.ball_pos[1])
            vx, vy = (tb.vx if tb.HasField("vx") else 0.0), (tb.vy if tb.HasField("vy") else 0.0)
            if not all(math.isfinite(v) for v in (x, y, vx, vy)) or math.hypot(vx, vy) > 20.0:
                self._error(errors, "INVALID_VALUE", "teleport_ball: non-finite or out-of-range value")
            else:
                if tb.z or tb.vz:
                    self._error(errors, "BALL_HEIGHT_UNSUPPORTED", "teleport_ball: the ball stays on the ground")
                if tb.roll or tb.teleport_safely:
                    self._error(errors, "TELEPORT_OPTION_UNSUPPORTED", "teleport_ball: roll / teleport_safely ignored")
                self.env.place_ball(np.array([np.clip(x, -wx, wx), np.clip(y, -wy, wy)]), np.array([vx, vy]))
                self._expect_jump()
                self.stats["teleports"] += 1
        if len(control.teleport_robot):
            pose = self.env.robot_poses()
            rows = []
            for tr in control.teleport_robot:
                team = TEAM_OF_PROTO.get(tr.id.team)
                if team is None or not 0 <= tr.id.id < self.n:
                    self._error(errors, "UNKNOWN_ROBOT", f"teleport_robot: no robot {tr.id.id} of team {tr.id.team}")
                    continue
                row = tr.id.id + (0 if team == "blue" else self.n)
                values = [tr.x if tr.HasField("x") else pose[row, 0], tr.y if tr.HasField("y") else pose[row, 1],
                          tr.orientation if tr.HasField("orientation") else pose[row, 2]]
                if not all(math.isfinite(v) for v in values):
                    self._error(errors, "INVALID_VALUE", f"teleport_robot {team} {tr.id.id}: non-finite value")
                    continue
                if tr.HasField("present") and not tr.present:
                    self._error(errors, "ROBOT_PRESENCE_UNSUPPORTED", "robots cannot be taken off the field")
                    continue
                if tr.v_x or tr.v_y or tr.v_angular:
                    self._error(errors, "ROBOT_VELOCITY_UNSUPPORTED", "teleported robots start at rest")
                pose[row] = [np.clip(values[0], -wx, wx), np.clip(values[1], -wy, wy), values[2]]
                rows.append(row)
            if rows:
                self.env.place_robots(pose, only=np.array(rows))
                self._expect_jump()
                self.stats["teleports"] += 1
        if control.HasField("simulation_speed"):
            s = control.simulation_speed
            if not (math.isfinite(s) and 0 < s <= MAX_SPEED_FACTOR):
                self._error(errors, "INVALID_VALUE", f"simulation_speed must be in (0, {MAX_SPEED_FACTOR}], got {s}")
            else:
                self.speed = float(s)
        return errors

    def _expect_jump(self) -> None:
        for tr in getattr(self.env, "trackers", {}).values():
            tr.expect_jump(8)

    def valid(self) -> bool:
        """The world is sane: every position and velocity finite and inside the walls."""
        ws = self.env.world_state()
        arrays = [ws.ball_pos, ws.ball_vel, ws.blue.pos, ws.yellow.pos, ws.blue.vel, ws.yellow.vel]
        if not all(np.isfinite(a).all() for a in arrays):
            return False
        lim = np.array([self.field.wall_half_length, self.field.wall_half_width]) + 0.1
        return all((np.abs(p) <= lim).all() for p in (ws.ball_pos.reshape(1, 2), ws.blue.pos, ws.yellow.pos))
