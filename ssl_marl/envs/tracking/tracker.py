"""The vision tracker of one team: Kalman filters, latency compensation, ball on the
dribbler, outlier gates.

What it consumes: the team's vision frames (``env.vision_state(team)``: team frame,
noisy, ``obs_latency`` old, the ball sometimes missing; ``frame.t`` is the capture
time) and the commands the team sent (normalised (n, 5) actions, or (n, 6) with chip
kicks, see :mod:`ssl_marl.envs.actions`, each with the control tick from which the
robots execute it). What it produces: a :class:`~ssl_marl.physics.state.WorldState` of the
same type and frame, predicted to the time the next command will start to act.

How (docs/references.md, "Vision and tracking"; parameters in :class:`.TrackerParams`):

* one filter per robot, [x, y, vx, vy] and [theta, omega] (TIGERs' split), with the
  acceleration implied by the sent commands as control input for the team's own
  robots (ER-Force) and white-noise acceleration for the opponents; measurements
  are position, heading and the velocities the env's vision reports;
* one ball filter [x, y, vx, vy] with the simulator's two-phase deceleration as
  control input; a measured speed jump above the prediction is a kick (restart in
  the sliding phase), a velocity jump a bounce (restart of the velocity);
* ball on the dribbler: a ball touching a robot's front face (measured within
  ``dribbler_gate``), reported on the dribbler by the robot itself (the env's
  per-robot contact flag, like a light barrier) or unseen near a dribbler is pinned
  at its offset to that robot (ER-Force) and moves with it; it is released when
  measured more than ``release_gate`` from the face or kicked by a sent kick command;
* outliers: a detection outside a gate that grows with the time since the last
  accepted one (TIGERs' 6 m/s, 30 rad/s, ball 15 m/s capped at 0.5 m) is ignored;
  after ``max_outliers`` consecutive ones the filter restarts at the detection
  (Thunderbots), at once after a referee teleport (:meth:`expect_jump`);
* latency: the filter state lives at the capture time of the last frame ("past"
  filter); :meth:`predict` copies it and rolls the copy forward tick by tick through
  the commands already sent (ER-Force's "future" copy), including kicks of a held
  ball and the dribbler catching a ball the robot drives onto.

Everything is deterministic (no random numbers).

A ground ball only: the tracker does not model a ball in the air. Vision reports a chip
as SSL-Vision does (:mod:`ssl_marl.envs.camera`: no height, the position projected onto
the ground-ball plane, displaced away from the camera's foot point by up to
z / (H - r - z) of the offset, 0.14 at a 0.5 m apex under 4 m cameras), and the filter
treats it as a ground ball: the estimate follows that projected position (error up to
the projection's displacement, plus the ground deceleration wrongly applied between
measurements), each bounce's drop in speed restarts the velocity, and a chip kick's
speed jump restarts the filter like a flat kick. The chip entry of a command is
ignored: the prediction of a sent chip kick of a held ball is a flat kick at the full
3-D speed until vision shows the ball. ER-Force's tracker fits chips over the camera
rays instead. Measured figures: docs/DESIGN.md, "Ball in the air".
"""

from __future__ import annotations

import bisect
import math
from dataclasses import dataclass

import numpy as np

from ...physics.params import BallParams, RobotParams
from ...physics.state import TEAMS, WorldState, make_team_state, wrap_angle
from ..actions import ACTION_DIM, CHIP_ACTION_DIM, scale_actions
from .kalman import PVFilter
from .motion import (
    ball_deceleration,
    ball_position_factor,
    face_geometry,
    pinned_ball,
    robot_response,
)
from .params import TrackerParams

OWN, OPP = 0, 1


@dataclass
class _Robots:
    xy: PVFilter
    th: PVFilter
    misses: np.ndarray
    last_tick: np.ndarray

    @staticmethod
    def new(n: int) -> _Robots:
        return _Robots(PVFilter(n, 2), PVFilter(n, 1, angular=True), np.zeros(n, int), np.zeros(n, int))

    def copy(self) -> _Robots:
        return _Robots(self.xy.copy(), self.th.copy(), self.misses.copy(), self.last_tick.copy())


@dataclass
class _State:
    """Everything that is rolled forward: filters at ``tick``, ball holder (side, index)."""

    tick: int
    robots: tuple[_Robots, _Robots]
    ball: PVFilter
    slide_until: float
    holder: tuple[int, int] | None
    offset: np.ndarray
    ball_misses: int
    ball_tick: int
    kick_ready: np.ndarray

    def copy(self) -> _State:
        return _State(self.tick, (self.robots[0].copy(), self.robots[1].copy()), self.ball.copy(), self.slide_until,
                      self.holder, self.offset.copy(), self.ball_misses, self.ball_tick, self.kick_ready.copy())


class VisionTracker:
    """Tracker for one team's view of the world (see the module docstring).

    Args:
        team: "blue" or "yellow"; frames must be in this team's frame.
        robot, ball: physical parameters (the team knows its robots and the ball).
        dt: control period (s); frames and commands are on this tick grid.
        substeps: physics sub-steps per control step (the ball's integration).
        params: :class:`TrackerParams` (defaults when None).

    Use: :meth:`record_command` after sending, :meth:`update` with each new vision
    frame, :meth:`predict` for the state at a time (or :meth:`track`: both).
    """

    def __init__(self, team: str, robot: RobotParams | None = None, ball: BallParams | None = None,
                 dt: float = 1.0 / 60.0, substeps: int = 2, params: TrackerParams | None = None) -> None:
        if team not in TEAMS:
            raise ValueError(f"VisionTracker: team must be 'blue' or 'yellow', got {team!r}")
        if not (isinstance(dt, (int, float)) and math.isfinite(dt) and dt > 0):
            raise ValueError(f"VisionTracker: dt must be a positive number of seconds, got {dt!r}")
        if not isinstance(substeps, int) or substeps < 1:
            raise ValueError(f"VisionTracker: substeps must be an integer >= 1, got {substeps!r}")
        if params is not None and not isinstance(params, TrackerParams):
            raise ValueError(f"VisionTracker: params must be a TrackerParams, got {type(params).__name__}")
        self.team = team
        self.other = "yellow" if team == "blue" else "blue"
        self.rp, self.bp = robot or RobotParams(), ball or BallParams()
        self.dt, self.substeps = float(dt), substeps
        self.params = params or TrackerParams()
        self._ball_factor = ball_position_factor(substeps)
        self._reach = self.rp.front_distance + self.bp.radius
        self.reset()

    # ------------------------------------------------------------ bookkeeping
    def reset(self) -> None:
        """Forget everything (new episode)."""
        self._state: _State | None = None
        self._n: tuple[int, int] | None = None
        self._cmd_ticks: list[int] = []
        self._cmds: list[np.ndarray] = []
        self._jump_frames = 0
        self._last_visible = True

    @property
    def initialised(self) -> bool:
        return self._state is not None

    @property
    def capture_time(self) -> float | None:
        """Capture time (s) of the last frame incorporated, None before the first."""
        return None if self._state is None else self._state.tick * self.dt

    def tick_of(self, t: float) -> int:
        """Control tick index of time ``t`` (s)."""
        return int(round(float(t) / self.dt))

    def expect_jump(self, frames: int) -> None:
        """The referee teleported robots / the ball: during the next ``frames`` frames a
        detection outside the gate restarts its filter at once."""
        self._jump_frames = max(self._jump_frames, int(frames))

    def record_command(self, tick: int, actions: np.ndarray) -> None:
        """The team's robots execute ``actions`` ((n, 5) normalised, robot order; (n, 6)
        with chip kicks, the chip entry ignored: the tracker models a ground ball) from
        control tick ``tick`` on (tick = (time the command is executed from) / dt)."""
        a = np.asarray(actions, dtype=float)
        if a.ndim != 2 or a.shape[1] not in (ACTION_DIM, CHIP_ACTION_DIM):
            raise ValueError(f"VisionTracker.record_command: actions must have shape (n, {ACTION_DIM}) or "
                             f"(n, {CHIP_ACTION_DIM}), got {a.shape}")
        a = a[:, :ACTION_DIM]
        if self._n is not None and a.shape[0] != self._n[OWN]:
            raise ValueError(f"VisionTracker.record_command: {a.shape[0]} command rows for a team of "
                             f"{self._n[OWN]} robots")
        if not np.isfinite(a).all():
            raise ValueError("VisionTracker.record_command: actions contain NaN or inf")
        tick = int(tick)
        k = bisect.bisect_left(self._cmd_ticks, tick)
        if k < len(self._cmd_ticks) and self._cmd_ticks[k] == tick:
            self._cmds[k] = a.copy()
        else:
            self._cmd_ticks.insert(k, tick)
            self._cmds.insert(k, a.copy())

    def _cmd_at(self, j: int) -> np.ndarray | None:
        k = bisect.bisect_right(self._cmd_ticks, j) - 1
        if k < 0 or (j - self._cmd_ticks[k]) * self.dt > self.params.command_stale_s:
            return None
        return self._cmds[k]

    def _prune_commands(self, tick: int) -> None:
        k = bisect.bisect_right(self._cmd_ticks, tick) - 1
        if k > 0:
            del self._cmd_ticks[:k]
            del self._cmds[:k]

    # ---------------------------------------------------------------- checks
    def _check_frame(self, frame: WorldState) -> None:
        if not isinstance(frame, WorldState):
            raise ValueError(f"VisionTracker.update: expected a WorldState vision frame, got {type(frame).__name__}")
        if frame.frame != self.team:
            raise ValueError(f"VisionTracker({self.team!r}).update: the frame is in {frame.frame!r}'s frame; pass "
                             f"env.vision_state({self.team!r})")
        if not math.isfinite(frame.t):
            raise ValueError(f"VisionTracker.update: frame.t must be finite, got {frame.t!r}")
        for name in ("ball_pos", "ball_vel"):
            if not np.isfinite(getattr(frame, name)).all():
                raise ValueError(f"VisionTracker.update: frame.{name} is not finite: {getattr(frame, name)}")
        for team in TEAMS:
            ts = frame.team(team)
            for name in ("pos", "heading", "vel", "omega"):
                if not np.isfinite(getattr(ts, name)).all():
                    raise ValueError(f"VisionTracker.update: frame.{team}.{name} is not finite")
        n = (frame.team(self.team).n, frame.team(self.other).n)
        if self._n is not None and n != self._n and self._state is not None:
            raise ValueError(f"VisionTracker.update: the frame has {n[0]} own / {n[1]} opponent robots, the tracker "
                             f"tracks {self._n[0]} / {self._n[1]} (call reset() for a new setup)")

    # ---------------------------------------------------------------- update
    def update(self, frame: WorldState) -> None:
        """Incorporate one vision frame (team frame; ``frame.t`` = capture time). A frame
        already incorporated is ignored; a frame older than the state restarts the
        tracker (the env was reset)."""
        self._check_frame(frame)
        c = self.tick_of(frame.t)
        st = self._state
        if st is not None and c == st.tick:
            return
        if st is None or c < st.tick:
            self._init(frame, c)
            return
        for j in range(st.tick, c):
            self._advance(st, j, covariance=True)
        jump = self._jump_frames > 0
        self._jump_frames = max(self._jump_frames - 1, 0)
        own, opp = frame.team(self.team), frame.team(self.other)
        for side, ts in ((OWN, own), (OPP, opp)):
            self._measure_robots(st.robots[side], ts, c, jump)
        st.kick_ready = np.array(own.kick_ready, bool)
        self._opp_ready = np.array(opp.kick_ready, bool)
        self._measure_ball(st, frame, c, jump)
        self._last_visible = bool(frame.ball_visible)
        self._prune_commands(c)

    def _init(self, frame: WorldState, c: int) -> None:
        P = self.params
        own, opp = frame.team(self.team), frame.team(self.other)
        self._n = (own.n, opp.n)
        robots = (_Robots.new(own.n), _Robots.new(opp.n))
        for R, ts in zip(robots, (own, opp)):
            R.xy.set(slice(None), ts.pos, ts.vel, P.robot_pos_sigma ** 2, P.vel_sigma ** 2)
            R.th.set(slice(None), ts.heading[:, None], ts.omega[:, None], P.robot_angle_sigma ** 2, P.omega_sigma ** 2)
            R.last_tick[:] = c
        ball = PVFilter(1, 2)
        ball.set(0, frame.ball_pos, frame.ball_vel, P.ball_pos_sigma ** 2, P.vel_sigma ** 2)
        sp = float(np.hypot(*frame.ball_vel))
        slide = self.bp.slide_to_roll_ratio * sp if sp > P.kick_speed_jump else math.inf
        self._opp_ready = np.array(opp.kick_ready, bool)
        self._state = _State(c, robots, ball, slide, None, np.array([self._reach, 0.0]), 0, c,
                             np.array(own.kick_ready, bool))
        self._jump_frames = 0
        self._take_ball(self._state, frame, c)
        self._last_visible = bool(frame.ball_visible)

    def _measure_robots(self, R: _Robots, ts, c: int, jump: bool) -> None:
        if ts.n == 0:
            return
        P = self.params
        age = (c - R.last_tick) * self.dt
        d = np.hypot(*(ts.pos - R.xy.p).T)
        dh = np.abs(wrap_angle(ts.heading - R.th.p[:, 0]))
        ok = (d <= P.robot_gate_base + P.robot_gate_speed * age) & (dh <= P.robot_gate_turn_base + P.robot_gate_turn * age)
        R.misses = np.where(ok, 0, R.misses + 1)
        restart = ~ok & ((R.misses > P.max_outliers) | jump)
        if restart.any():
            R.xy.set(restart, ts.pos[restart], ts.vel[restart], P.robot_pos_sigma ** 2, P.vel_sigma ** 2)
            R.th.set(restart, ts.heading[restart, None], ts.omega[restart, None], P.robot_angle_sigma ** 2,
                     P.omega_sigma ** 2)
            R.misses[restart] = 0
        R.xy.update(ok, ts.pos, P.robot_pos_sigma, ts.vel, P.vel_sigma)
        R.th.update(ok, ts.heading[:, None], P.robot_angle_sigma, ts.omega[:, None], P.omega_sigma)
        R.last_tick[ok | restart] = c

    # ------------------------------------------------------------------ ball
    def _robot_pose(self, st: _State, side: int, i: int) -> tuple[np.ndarray, float, np.ndarray, float]:
        R = st.robots[side]
        return R.xy.p[i], float(R.th.p[i, 0]), R.xy.v[i], float(R.th.v[i, 0])

    def _pin(self, st: _State) -> None:
        side, i = st.holder
        pos, h, v, w = self._robot_pose(st, side, i)
        bp, bv = pinned_ball(pos, h, v, w, st.offset)
        st.ball.p[0], st.ball.v[0] = bp, bv

    def _clip_offset(self, local: np.ndarray) -> np.ndarray:
        hw = self.rp.dribbler_half_width
        return np.array([min(max(local[0], self._reach - 0.01), self._reach + self.rp.dribbler_tolerance),
                         min(max(local[1], -hw), hw)])

    def _local(self, st: _State, side: int, i: int, point: np.ndarray) -> np.ndarray:
        pos, h, _, _ = self._robot_pose(st, side, i)
        d = np.asarray(point, float) - pos
        c, s = math.cos(h), math.sin(h)
        return np.array([c * d[0] + s * d[1], -s * d[0] + c * d[1]])

    def _take_ball(self, st: _State, frame: WorldState, c: int) -> bool:
        """Ball-on-dribbler inference for a free ball: pin it to the robot whose face it
        touches (measured), that reports it (own robots' contact flag) or, unseen, whose
        dribbler its estimate lies near. Returns True if pinned."""
        P = self.params
        vis = bool(frame.ball_visible)
        point = frame.ball_pos if vis else st.ball.p[0]
        best: tuple[float, int, int] | None = None
        feedback = frame.team(self.team).ball_on_dribbler
        for side in (OWN, OPP):
            R = st.robots[side]
            if R.xy.n == 0:
                continue
            gap, ly, d_db = face_geometry(R.xy.p, R.th.p[:, 0], point, self.rp, self.bp)
            if vis:
                cand = (np.abs(gap) <= P.dribbler_gate) & (np.abs(ly) <= self.rp.dribbler_half_width)
            else:
                cand = d_db <= P.occlusion_gate
            if side == OWN:
                cand |= np.asarray(feedback, bool) & (d_db <= P.release_gate)
            for i in np.flatnonzero(cand):
                if best is None or d_db[i] < best[0]:
                    best = (float(d_db[i]), side, int(i))
        if best is None:
            return False
        _, side, i = best
        st.holder = (side, i)
        st.offset = self._clip_offset(self._local(st, side, i, point))
        if vis:  # the estimate at capture time is the (mm-accurate) measurement
            st.ball.p[0], st.ball.v[0] = frame.ball_pos, frame.ball_vel
        else:
            self._pin(st)
        st.ball.P[:] = 0.0
        st.ball.P[0, :, 0, 0] = P.ball_pos_sigma ** 2
        st.ball.P[0, :, 1, 1] = P.vel_sigma ** 2
        st.ball_misses, st.ball_tick = 0, c
        return True

    def _restart_ball(self, st: _State, pos: np.ndarray, vel: np.ndarray, kicked: bool, c: int) -> None:
        P = self.params
        st.ball.set(0, pos, vel, P.ball_pos_sigma ** 2, P.vel_sigma ** 2)
        if kicked:
            st.slide_until = self.bp.slide_to_roll_ratio * float(np.hypot(*vel))
        st.ball_misses, st.ball_tick = 0, c

    def _measure_ball(self, st: _State, frame: WorldState, c: int, jump: bool) -> None:
        P = self.params
        vis = bool(frame.ball_visible)
        zp, zv = np.asarray(frame.ball_pos, float), np.asarray(frame.ball_vel, float)
        if st.holder is not None:
            side, i = st.holder
            if vis:
                pos, h, v, w = self._robot_pose(st, side, i)
                _, _, d_db = face_geometry(pos[None], np.array([h]), zp, self.rp, self.bp)
                feedback = bool(frame.team(self.team).ball_on_dribbler[i]) if side == OWN else True
                if d_db[0] > P.release_gate or (not feedback and d_db[0] > P.dribbler_gate):
                    st.holder = None
                    kicked = float(np.hypot(*zv)) > float(np.hypot(*v)) + P.kick_speed_jump
                    self._restart_ball(st, zp, zv, kicked, c)
                    return
                # seen on the dribbler: the measurement is the estimate at capture time (its
                # noise is mm); the offset carries it forward with the robot
                st.offset = self._clip_offset(self._local(st, side, i, zp))
                st.ball.p[0], st.ball.v[0] = zp, zv
            else:
                self._pin(st)
            st.ball_tick = c
            return
        if self._take_ball(st, frame, c):
            return
        if not vis:
            if (c - st.ball_tick) * self.dt > P.lost_after_s:
                st.ball.v[:] = 0.0
            return
        age = (c - st.ball_tick) * self.dt
        gate = min(P.ball_gate_base + P.ball_gate_speed * age, P.ball_gate_cap)
        if float(np.hypot(*(zp - st.ball.p[0]))) > gate:
            st.ball_misses += 1
            if st.ball_misses > P.max_outliers or jump:
                self._restart_ball(st, zp, zv, float(np.hypot(*zv)) > P.kick_speed_jump, c)
                st.slide_until = math.inf if float(np.hypot(*zv)) <= P.kick_speed_jump else st.slide_until
            return
        st.ball_misses, st.ball_tick = 0, c
        sp_meas, sp_pred = float(np.hypot(*zv)), float(np.hypot(*st.ball.v[0]))
        if sp_meas - sp_pred > P.kick_speed_jump:
            self._restart_ball(st, zp, zv, True, c)
        elif float(np.hypot(*(zv - st.ball.v[0]))) > P.vel_reset_jump:
            slide = st.slide_until
            self._restart_ball(st, zp, zv, False, c)
            st.slide_until = slide
        else:
            st.ball.update(np.array([True]), zp[None], P.ball_pos_sigma, zv[None], P.vel_sigma)

    # --------------------------------------------------------------- predict
    def _advance(self, st: _State, j: int, covariance: bool) -> None:
        """Roll ``st`` one control tick forward, from tick j to j + 1."""
        P, dt, rp = self.params, self.dt, self.rp
        st.tick = j + 1
        own, opp = st.robots
        cmd = self._cmd_at(j) if own.xy.n else None
        kick = drib = None
        h0 = own.th.p[:, 0].copy()
        if cmd is not None and P.use_commands:
            vb, wc, drib, kick = scale_actions(cmd, rp)
            a, al = robot_response(own.th.p[:, 0], own.xy.v, own.th.v[:, 0], vb, wc, rp, dt)
        else:
            a, al = 0.0, np.zeros(own.xy.n)
        if st.holder is not None and st.holder[0] == OWN and kick is not None:
            i = st.holder[1]
            if kick[i] > 0 and st.kick_ready[i]:  # the kick fires with the robot's pose at the start of the tick
                speed = float(min(kick[i], 1.0)) * rp.kick_speed_max
                self._pin(st)
                st.ball.v[0] = speed * np.array([math.cos(h0[i]), math.sin(h0[i])])
                st.slide_until = self.bp.slide_to_roll_ratio * speed
                st.holder = None
                st.kick_ready = st.kick_ready.copy()
                st.kick_ready[i] = False
        own.xy.predict(dt, a, P.own_accel_sigma, 1.0, covariance)
        own.th.predict(dt, np.asarray(al)[:, None], P.own_alpha_sigma, 1.0, covariance)
        opp.xy.predict(dt, 0.0, P.opp_accel_sigma, 1.0, covariance)
        opp.th.predict(dt, 0.0, P.opp_alpha_sigma, 1.0, covariance)
        if st.holder is not None:
            self._pin(st)
            return
        acc, st.slide_until = ball_deceleration(st.ball.v[0], st.slide_until, self.bp, dt)
        st.ball.predict(dt, acc[None], P.ball_accel_sigma, self._ball_factor, covariance)
        if not covariance:  # prediction: the dribbler catches a ball the robot drives onto
            self._predict_catch(st, drib)

    def _predict_catch(self, st: _State, drib: np.ndarray | None) -> None:
        best = None
        for side in (OWN, OPP):
            R = st.robots[side]
            if R.xy.n == 0:
                continue
            gap, ly, d_db = face_geometry(R.xy.p, R.th.p[:, 0], st.ball.p[0], self.rp, self.bp)
            touch = (gap <= self.rp.dribbler_tolerance) & (gap >= -self.rp.radius) & \
                (np.abs(ly) <= self.rp.dribbler_half_width)
            if side == OWN:
                touch &= np.zeros(R.xy.n, bool) if drib is None else np.asarray(drib, bool)
            for i in np.flatnonzero(touch):
                if best is None or d_db[i] < best[0]:
                    best = (float(d_db[i]), side, int(i), float(ly[i]))
        if best is not None:
            _, side, i, ly = best
            st.holder = (side, i)
            st.offset = np.array([self._reach, ly])
            self._pin(st)

    def predict(self, t: float) -> WorldState:
        """The tracked state at time ``t`` (s, >= the last capture time), in the team
        frame: the past filter rolled forward through the commands sent."""
        st0 = self._state
        if st0 is None:
            raise RuntimeError("VisionTracker.predict: no vision frame yet (call update first)")
        if not math.isfinite(t):
            raise ValueError(f"VisionTracker.predict: t must be finite, got {t!r}")
        target = self.tick_of(t)
        if target < st0.tick:
            raise ValueError(f"VisionTracker.predict: t={t} s lies before the last capture time "
                             f"{st0.tick * self.dt} s")
        st = st0.copy()
        for j in range(st0.tick, target):
            self._advance(st, j, covariance=False)
        return self._world(st, target * self.dt)

    def track(self, frame: WorldState, now: float) -> WorldState:
        """:meth:`update` with ``frame``, then :meth:`predict` for ``now`` + the radio delay."""
        self.update(frame)
        return self.predict(now + self.params.radio_delay_s)

    def _world(self, st: _State, t: float) -> WorldState:
        teams = {}
        gate = self.params.dribbler_gate
        for side, name in ((OWN, self.team), (OPP, self.other)):
            R = st.robots[side]
            # on the dribbler: the holder, and any robot whose face touches the ball (two
            # robots can press on one ball)
            gap, ly, _ = face_geometry(R.xy.p, R.th.p[:, 0], st.ball.p[0], self.rp, self.bp)
            held = (np.abs(gap) <= gate) & (np.abs(ly) <= self.rp.dribbler_half_width)
            if st.holder is not None and st.holder[0] == side:
                held[st.holder[1]] = True
            ready = st.kick_ready if side == OWN else self._opp_ready
            teams[name] = make_team_state(R.xy.p, wrap_angle(R.th.p[:, 0]), R.xy.v, R.th.v[:, 0], held, ready)
        bp, bv = st.ball.p[0].copy(), st.ball.v[0].copy()
        for a in (bp, bv):
            a.setflags(write=False)
        return WorldState(t=float(t), ball_pos=bp, ball_vel=bv, blue=teams["blue"], yellow=teams["yellow"],
                          ball_visible=self._last_visible, frame=self.team)
