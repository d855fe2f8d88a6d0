"""K independent Box2D worlds stepped together, with the per-robot logic in numpy.

:class:`BatchedPhysics` holds K :class:`~ssl_marl.physics.world.PhysicsWorld`
objects (they build each world, teleport robots and ball, and run the rare
per-world dribbler update) and does everything else over all worlds at once:
the velocity controller, the kicker, the two-phase ball friction, the "ball on the
dribbler" contact checks and reading the state back. Box2D's ``Step`` stays one
C++ call per world and sub-step.

The maths is the single world's, operation for operation (same order of float
operations, ``sqrt`` of sums of squares, numpy's ``cos``/``sin`` which equal
``math``'s), so world k evolves bit for bit as a :class:`PhysicsWorld` given the
same commands (tested). Bodies are read and written through numpy views of
Box2D's memory (:mod:`ssl_marl.physics.body_memory`) where the layout check
passes, through SWIG otherwise.

Arrays (SI units, field frame), K worlds, n robots (blue first):
``pos`` (K, n, 2) m, ``heading`` (K, n) rad in (-pi, pi], ``vel`` (K, n, 2) m/s,
``omega`` (K, n) rad/s, ``ball_pos``/``ball_vel`` (K, 2), ``on_dribbler`` (K, n)
bool, ``kick_cooldown`` (K, n) s, ``t`` (K,) s; after :meth:`step`,
``kicker`` (K,) index of the robot whose kick fired this step (-1 none) and
``kick_speed`` (K,) m/s (3-D). ``in_flight`` (K,) bool: the ball is in the air. A ball in
the air is rare, so its flight runs per world through the world's own
:meth:`PhysicsWorld._flight_substep` (its height state lives in the world object).
"""

from __future__ import annotations

import math

import numpy as np
from Box2D._Box2D import b2World_Step as Box2D_step

from . import ball_flight
from . import body_memory as bm
from .field import FieldGeometry
from .params import BallParams, RobotParams
from .state import TeamState, WorldState, wrap_angle
from .units import _FACE_PENETRATION_TOL, POS_ITERS, SCALE, VEL_ITERS
from .world import PhysicsWorld, ball_in_robot_frame, cap_velocities


_R19 = np.arange(19)
_R_VW = np.array([16, 17, 18])
_R_V = np.array([16, 17])


class BatchedPhysics:
    """K independent SSL worlds (same field, robots and parameters).

    Args:
        field, robot, ball, n_blue, n_yellow, control_dt, substeps: as
            :class:`PhysicsWorld`.
        n_worlds: K >= 1.
        worlds: optional existing :class:`PhysicsWorld` objects to drive (K of them,
            same configuration); built here otherwise.
    """

    def __init__(self, field: FieldGeometry, robot: RobotParams, ball: BallParams, n_blue: int, n_yellow: int,
                 n_worlds: int, control_dt: float = 1.0 / 60.0, substeps: int = 2,
                 worlds: list[PhysicsWorld] | None = None) -> None:
        if not isinstance(n_worlds, int) or n_worlds < 1:
            raise ValueError(f"n_worlds must be a positive integer, got {n_worlds!r}")
        self.field, self.robot, self.ball_params = field, robot, ball
        self.n_blue, self.n_yellow, self.n = n_blue, n_yellow, n_blue + n_yellow
        self.K = n_worlds
        self.control_dt, self.substeps = float(control_dt), int(substeps)
        self.sub_dt = self.control_dt / self.substeps
        if worlds is None:
            worlds = [PhysicsWorld(field, robot, ball, n_blue, n_yellow, control_dt, substeps) for _ in range(n_worlds)]
        if len(worlds) != n_worlds:
            raise ValueError(f"got {len(worlds)} worlds for n_worlds={n_worlds}")
        self.worlds = worlds
        K, n = self.K, self.n
        self.pos = np.zeros((K, n, 2))
        self.heading = np.zeros((K, n))
        self.vel = np.zeros((K, n, 2))
        self.omega = np.zeros((K, n))
        self.ball_pos = np.zeros((K, 2))
        self.ball_vel = np.zeros((K, 2))
        self.on_face_now = np.zeros((K, n), bool)
        self.on_dribbler = np.zeros((K, n), bool)
        self.kick_cooldown = np.zeros((K, n))
        self.slide_until = np.full(K, math.inf)
        self.t = np.zeros(K)
        self.kicker = np.full(K, -1)
        self.kick_speed = np.zeros(K)
        self.in_flight = np.zeros(K, bool)
        self._flew: set[int] = set()  # worlds whose touchdowns list may be non-empty
        self._lifted: set[int] = set()  # worlds whose ball_max_height may be > 0
        self._fast = bm.layout_ok()
        self._b2: list = [w.world for w in worlds]
        self._addr = np.zeros((K, n + 1), np.int64)
        self._span_dirty = True
        self._mem = self._slot = None

    # ------------------------------------------------------------------ syncing
    def pull(self, k: int) -> None:
        """Copy world k's state from its :class:`PhysicsWorld` (after a reset or a
        teleport done through it) and refresh its memory view."""
        w = self.worlds[k]
        self._b2[k] = w.world
        if self._fast:
            self._addr[k] = [bm.address(b) for b in w._robot_bodies + [w._ball_body]]
            self._span_dirty = True
        self.pos[k], self.heading[k], self.vel[k], self.omega[k] = w.pos, w.heading, w.vel, w.omega
        self.ball_pos[k], self.ball_vel[k] = w.ball_pos, w.ball_vel
        self.on_face_now[k] = w._on_face_now
        self.on_dribbler[k] = w.on_dribbler
        self.slide_until[k] = w._slide_until
        self.t[k] = w.t
        self.kick_cooldown[k] = w.kick_cooldown
        self.in_flight[k] = w.ball_z > 0.0 or w.ball_vz > 0.0
        if w.ball_max_height > 0.0:
            self._lifted.add(k)

    def push(self, k: int) -> None:
        """Hand world k's cached state to its :class:`PhysicsWorld` (before using it to
        teleport, so that its own bookkeeping is current)."""
        w = self.worlds[k]
        w.pos, w.heading, w.vel, w.omega = self.pos[k].copy(), self.heading[k].copy(), self.vel[k].copy(), \
            self.omega[k].copy()
        w.ball_pos, w.ball_vel = self.ball_pos[k].copy(), self.ball_vel[k].copy()
        w._on_face_now, w.on_dribbler = self.on_face_now[k].copy(), self.on_dribbler[k].copy()
        w._slide_until, w.t, w.kick_cooldown = float(self.slide_until[k]), float(self.t[k]), self.kick_cooldown[k].copy()

    def reset_world(self, k: int, robot_pose: np.ndarray, ball_pos: np.ndarray, ball_vel: np.ndarray | None = None,
                    robot_vel: np.ndarray | None = None) -> None:
        """:meth:`PhysicsWorld.reset` of world k."""
        self.worlds[k].reset(robot_pose, ball_pos, ball_vel, robot_vel)
        self.pull(k)

    def set_ball(self, k: int, pos: np.ndarray, vel: np.ndarray | None = None, z: float = 0.0,
                 vz: float = 0.0) -> None:
        self.push(k)
        self.worlds[k].set_ball(pos, vel, z, vz)
        self.pull(k)

    def set_robots(self, k: int, pose: np.ndarray, only: np.ndarray | None = None) -> None:
        self.push(k)
        self.worlds[k].set_robots(pose, only)
        self.pull(k)

    # --------------------------------------------------------------- body I/O
    # Fast path: one flat float32 view spanning every body of every world
    # (body_memory.span_view) and the index of each body's first slot, so that reading
    # all bodies or writing all velocities is one numpy gather / scatter. Fallback
    # (layout check failed): SWIG, body by body.
    def _span(self) -> tuple[np.ndarray, np.ndarray]:
        if self._span_dirty:
            self._mem, self._slot = bm.span_view(self._addr)
            self._span_dirty = False
        return self._mem, self._slot

    def _raw_state(self, idx: np.ndarray, full: bool) -> np.ndarray:
        """(len(idx), n + 1, 19) Box2D state (float32 values as float64) of worlds idx."""
        if self._fast:
            mem, slot = self._span()
            s = slot if full else slot[idx]
            return mem[s[..., None] + _R19].astype(np.float64)
        out = np.zeros((len(idx), self.n + 1, 19))
        for j, k in enumerate(idx):
            w = self.worlds[k]
            for i, b in enumerate(w._robot_bodies + [w._ball_body]):
                p, lv = b.position, b.linearVelocity
                out[j, i, 3:5] = p[0], p[1]
                out[j, i, bm.ANGLE] = b.angle
                out[j, i, 16:18] = lv[0], lv[1]
                out[j, i, bm.OMEGA] = b.angularVelocity
        return out

    def _write_robot_vel(self, idx: np.ndarray, full: bool, vals: np.ndarray) -> None:
        """vals (len(idx), n, 3): linear velocity (Box2D units) and angular velocity."""
        n = self.n
        if self._fast:
            mem, slot = self._span()
            s = slot[:, :n] if full else slot[idx, :n]
            mem[s[..., None] + _R_VW] = vals
            return
        for j, k in enumerate(idx):
            for b, (vx, vy, w) in zip(self.worlds[k]._robot_bodies, vals[j].tolist()):
                b.linearVelocity = (vx, vy)
                b.angularVelocity = w

    def _ball_vel_raw(self, idx: np.ndarray, full: bool) -> np.ndarray:
        """(len(idx), 2) ball velocities (Box2D units)."""
        if self._fast:
            mem, slot = self._span()
            s = slot[:, self.n] if full else slot[idx, self.n]
            return mem[s[:, None] + _R_V].astype(np.float64)
        out = np.empty((len(idx), 2))
        for j, k in enumerate(idx):
            lv = self.worlds[k]._ball_body.linearVelocity
            out[j] = lv[0], lv[1]
        return out

    def _set_ball_vel_raw(self, worlds: np.ndarray, vals: np.ndarray) -> None:
        """Set the ball velocity (Box2D units) of ``worlds`` (world indices) to vals (m, 2)."""
        if self._fast:
            mem, slot = self._span()
            mem[slot[worlds, self.n][:, None] + _R_V] = vals
            return
        for k, (vx, vy) in zip(worlds.tolist(), vals.tolist()):
            self.worlds[k]._ball_body.linearVelocity = (vx, vy)

    # ------------------------------------------------------------------ step
    def step(self, v_body: np.ndarray, omega: np.ndarray, dribble: np.ndarray, kick: np.ndarray,
             worlds: np.ndarray | None = None, chip: np.ndarray | None = None) -> None:
        """Advance worlds ``worlds`` (indices; default all) by one control period.

        Args: as :meth:`PhysicsWorld.step` with a leading world axis of len(worlds):
        v_body (k, n, 2) m/s body frame, omega (k, n) rad/s, dribble (k, n) bool,
        kick (k, n) strength in [0, 1], chip (k, n) kick elevation in rad or None (flat).
        """
        idx = np.arange(self.K) if worlds is None else np.asarray(worlds, dtype=np.int64)
        full = worlds is None
        rp, S, dt = self.robot, SCALE, self.control_dt
        n = self.n

        def get(a):
            return a if full else a[idx]

        pos, heading, vel, om = get(self.pos), get(self.heading), get(self.vel), get(self.omega)
        ball_pos, ball_vel = get(self.ball_pos), get(self.ball_vel)
        # --- robot velocity tracking (PhysicsWorld.step, vectorised) -------------------
        vmax, acc, brk = rp.max_speed, rp.max_accel * dt, rp.max_brake * dt
        wmax, alpha = rp.max_omega, rp.max_alpha * dt
        bvx, bvy = ball_vel[:, 0], ball_vel[:, 1]
        ball_sp = np.sqrt(bvx * bvx + bvy * bvy)
        near_base = rp.radius + rp.front_distance + self.ball_params.radius + 0.05 + (ball_sp + 2 * rp.max_accel * dt) * dt
        ux, uy = v_body[..., 0], v_body[..., 1]
        c, sn = np.cos(heading), np.sin(heading)
        dx, dy = c * ux - sn * uy, sn * ux + c * uy
        sp = np.sqrt(dx * dx + dy * dy)
        over = sp > vmax
        if over.any():
            d = np.where(over, sp, 1.0)
            dx, dy = np.where(over, dx * vmax / d, dx), np.where(over, dy * vmax / d, dy)
            sp = np.where(over, vmax, sp)
        vx, vy = vel[..., 0], vel[..., 1]
        ex, ey = dx - vx, dy - vy
        en = np.sqrt(ex * ex + ey * ey)
        cur = np.sqrt(vx * vx + vy * vy)
        lim = np.where(sp < cur, brk, acc)
        big = en > lim
        if big.any():
            e = np.where(big, en, 1.0)
            ex, ey = np.where(big, ex * lim / e, ex), np.where(big, ey * lim / e, ey)
        w_des = np.clip(omega, -wmax, wmax)
        dw = np.clip(w_des - om, -alpha, alpha)
        cmd = np.empty(vel.shape[:2] + (3,))
        cmd[..., 0] = (vx + ex) * S
        cmd[..., 1] = (vy + ey) * S
        cmd[..., 2] = om + dw
        self._write_robot_vel(idx, full, cmd)
        qx, qy = pos[..., 0] - ball_pos[:, None, 0], pos[..., 1] - ball_pos[:, None, 1]
        near = np.sqrt(qx * qx + qy * qy) < near_base[:, None] + cur * dt  # (k, n)
        any_near = near.any(axis=1)
        # --- kicker -----------------------------------------------------------------
        cool = np.maximum(get(self.kick_cooldown) - dt, 0.0)
        fire = (kick > 0) & get(self.on_face_now) & (cool <= 0) & any_near[:, None]
        kicked = fire.any(axis=1)
        kicker = np.where(kicked, np.argmax(fire, axis=1), -1)
        for j in np.flatnonzero(fire.sum(axis=1) > 1).tolist():  # contested: PhysicsWorld.step's rule
            offset = np.where(fire[j], self.face_offset(pos[j], heading[j], ball_pos[j]), np.inf)
            kicker[j] = int(np.argmin(offset))
        kick_speed = np.zeros(len(idx))
        slide_until = get(self.slide_until).copy()
        kj = np.flatnonzero(kicked)
        if kj.size:
            ki = kicker[kj]
            speed = np.minimum(kick[kj, ki], 1.0) * rp.kick_speed_max
            h = heading[kj, ki]
            angle = np.zeros(kj.size) if chip is None else np.minimum(np.maximum(chip[kj, ki], 0.0), rp.chip_angle_max)
            lifted = angle > 0.0
            vh, vv = ball_flight.launch(speed, angle)
            vh = np.where(lifted, vh, speed)
            self._set_ball_vel_raw(idx[kj], np.stack([vh * np.cos(h) * S, vh * np.sin(h) * S], axis=1))
            slide_until[kj] = np.where(lifted, math.inf,
                                       np.where(speed > 0, self.ball_params.slide_to_roll_ratio * speed, math.inf))
            for j in np.flatnonzero(lifted | self.in_flight[idx[kj]]).tolist():
                w = self.worlds[int(idx[kj[j]])]
                w._set_flight(0.0, float(vv[j]) if lifted[j] else 0.0)
            for k in idx[kj].tolist():
                self.worlds[k].ball_max_height = 0.0
            self.in_flight[idx[kj]] = lifted
            cool[kj, ki] = rp.kick_recharge_s
            kick_speed[kj] = speed
        armed = near & (kick > 0) & (cool <= 0) & ~kicked[:, None] if rp.kick_on_contact else None
        if armed is not None and not armed.any():
            armed = None
        # --- sub-steps: dribbler, ball friction, Box2D ------------------------------
        drib = near & dribble & ~kicked[:, None]
        drib_worlds = np.flatnonzero(drib.any(axis=1))
        drib_lists = [(int(idx[j]), np.flatnonzero(drib[j]).tolist()) for j in drib_worlds]
        touched = np.zeros(near.shape, bool)
        near_pairs = np.nonzero(near)
        b2worlds = self._b2 if full else [self._b2[k] for k in idx.tolist()]
        b2step = Box2D_step
        bp = self.ball_params
        for k in self._flew:
            self.worlds[k].touchdowns = []
        self._flew = set()
        for sub in range(self.substeps):
            for k, lst in drib_lists:
                self.worlds[k]._apply_dribblers(lst)
            flying = get(self.in_flight)
            any_flying = bool(flying.any())
            if any_flying:
                flying = flying.copy()  # worlds land during the sub-step
            # two-phase ball friction (PhysicsWorld._apply_ball_friction, vectorised)
            raw = self._ball_vel_raw(idx, full)
            bx_, by_ = raw[:, 0] / S, raw[:, 1] / S
            bsp = np.sqrt(bx_ * bx_ + by_ * by_)
            moving = (bsp > 0.0) & ~flying if any_flying else bsp > 0.0
            sliding = bsp > slide_until
            dec = np.where(sliding, bp.slide_decel, bp.roll_decel)
            slide_until = np.where(moving & ~sliding, math.inf, slide_until)
            new = np.maximum(bsp - dec * self.sub_dt, 0.0)
            kf = new / np.where(moving, bsp, 1.0) * S
            mv = np.flatnonzero(moving)
            if mv.size:
                self._set_ball_vel_raw(idx[mv], np.stack([bx_[mv] * kf[mv], by_[mv] * kf[mv]], axis=1))
            if any_flying:
                fly = set(np.flatnonzero(flying).tolist())
                for j, w in enumerate(b2worlds):
                    if j not in fly:
                        b2step(w, self.sub_dt, VEL_ITERS, POS_ITERS)
                for j in fly:
                    k = int(idx[j])
                    pw = self.worlds[k]
                    pw._flight_substep()
                    self._flew.add(k)
                    self.in_flight[k] = pw.ball_z > 0.0 or pw.ball_vz > 0.0
                    if pw._slide_until == math.inf:
                        slide_until[j] = math.inf
            else:
                for w in b2worlds:
                    b2step(w, self.sub_dt, VEL_ITERS, POS_ITERS)
            if near_pairs[0].size and sub < self.substeps - 1:
                self._mark_touches(idx, near_pairs, touched)
            if armed is not None:
                fired = self._fire_armed(idx, armed, kick, chip, cool, slide_until, kicker, kick_speed)
                if fired:
                    drib_lists = [(k, lst) for k, lst in drib_lists if k not in fired]
                    if not armed.any():
                        armed = None
        # --- read back --------------------------------------------------------------
        raw = self._raw_state(idx, full)
        self._enforce_caps(idx, full, raw)
        new_pos = raw[:, :n, 3:5] / S
        new_heading = wrap_angle(raw[:, :n, bm.ANGLE])
        on_face = self.ball_on_face(new_pos, new_heading, raw[:, n, 3:5] / S)
        if self._lifted or self._flew:
            self._after_flight(idx, on_face, touched)
        vals = {"pos": new_pos, "heading": new_heading, "vel": raw[:, :n, 16:18] / S,
                "omega": raw[:, :n, bm.OMEGA], "ball_pos": raw[:, n, 3:5] / S, "ball_vel": raw[:, n, 16:18] / S,
                "on_face_now": on_face, "on_dribbler": on_face | touched, "kick_cooldown": cool,
                "slide_until": slide_until, "kicker": kicker, "kick_speed": kick_speed}
        t = get(self.t) + dt
        if full:
            for name, v in vals.items():
                setattr(self, name, v)
            self.t = t
        else:
            for name, v in vals.items():
                getattr(self, name)[idx] = v
            self.t[idx] = t

    def _fire_armed(self, idx: np.ndarray, armed: np.ndarray, kick: np.ndarray, chip: np.ndarray | None,
                    cool: np.ndarray, slide_until: np.ndarray, kicker: np.ndarray, kick_speed: np.ndarray) -> set[int]:
        """Kick on contact (PhysicsWorld.step's armed kickers): in each world with an armed
        robot touching the ball now, that robot (the ball most centred on its face where
        several have it: ``face_offset``, exact ties the lower index) fires through the
        world's own ``_fire_kick``; the batch's arrays take its result. Returns the worlds
        that fired."""
        wj, ri = np.nonzero(armed)
        rows = self._pair_rows(idx, wj, ri)
        pos, hd, ball = rows[:, 0:2] / SCALE, rows[:, 2], rows[:, 3:5] / SCALE
        hit = np.flatnonzero(self.ball_on_face(pos, hd, ball))
        if hit.size > 1:  # most centred first; a stable sort keeps the index order on exact ties
            hit = hit[np.argsort(self.face_offset(pos[hit], hd[hit], ball[hit]), kind="stable")]
        fired: set[int] = set()
        for m in hit.tolist():
            j, i = int(wj[m]), int(ri[m])
            k = int(idx[j])
            w = self.worlds[k]
            if k in fired or w.ball_z > self.ball_params.radius:
                continue
            w.kicks_this_step = []
            w._fire_kick(i, float(kick[j, i]), float(rows[m, 2]), 0.0 if chip is None else float(chip[j, i]))
            fired.add(k)
            cool[j, i] = self.robot.kick_recharge_s
            slide_until[j] = w._slide_until
            kicker[j] = i
            kick_speed[j] = w.kicks_this_step[-1][1]
            self.in_flight[k] = w.ball_z > 0.0 or w.ball_vz > 0.0
            armed[j] = False
        return fired

    def _after_flight(self, idx: np.ndarray, on_face: np.ndarray, touched: np.ndarray) -> None:
        """PhysicsWorld.step's end for worlds whose ball flew this step: no dribbler
        contact while the ball is above the bar; a touch restarts the goal rule's height."""
        pos_of = {int(k): j for j, k in enumerate(idx.tolist())}
        self._lifted |= {k for k in self._flew if self.worlds[k].ball_max_height > 0.0}
        for k in sorted(self._lifted | self._flew):
            j = pos_of.get(k)
            if j is None:
                continue
            w = self.worlds[k]
            if w.ball_z > self.ball_params.radius:
                on_face[j] = False
                touched[j] = False
            if w.ball_max_height > 0.0 and ((on_face[j] | touched[j]).any() or w._ball_touches_robot()):
                w.ball_max_height = w.ball_z
            if w.ball_max_height <= 0.0:
                self._lifted.discard(k)

    def _enforce_caps(self, idx: np.ndarray, full: bool, raw: np.ndarray) -> None:
        """PhysicsWorld's hard speed caps (world.cap_velocities) on worlds idx; raw is
        patched to what the bodies now hold."""
        rp, S, n = self.robot, SCALE, self.n
        vel, om, changed = cap_velocities(raw[:, :n, 16:18], raw[:, :n, bm.OMEGA], rp.max_speed * S, rp.max_omega)
        bvel, _, bch = cap_velocities(raw[:, n, 16:18], None, rp.kick_speed_max * S)
        if not (changed.any() or bch.any()):
            return
        raw[:, :n, 16:18], raw[:, :n, bm.OMEGA], raw[:, n, 16:18] = vel, om, bvel
        wj, ri = np.nonzero(changed)
        bj = np.flatnonzero(bch)
        if self._fast:
            mem, slot = self._span()
            if wj.size:
                mem[slot[idx[wj], ri][:, None] + _R_VW] = raw[wj, ri, 16:19]
            if bj.size:
                mem[slot[idx[bj], n][:, None] + _R_V] = raw[bj, n, 16:18]
            return
        for j, i in zip(wj.tolist(), ri.tolist()):
            b = self.worlds[int(idx[j])]._robot_bodies[i]
            b.linearVelocity = (float(raw[j, i, 16]), float(raw[j, i, 17]))
            b.angularVelocity = float(raw[j, i, bm.OMEGA])
        for j in bj.tolist():
            self.worlds[int(idx[j])]._ball_body.linearVelocity = (float(raw[j, n, 16]), float(raw[j, n, 17]))

    def _pair_rows(self, idx: np.ndarray, wj: np.ndarray, ri: np.ndarray) -> np.ndarray:
        """(len(wj), 5) Box2D x, y, raw angle of robot ri[m] and the ball's x, y, in world
        idx[wj[m]] (Box2D units, float32 values as float64)."""
        n = self.n
        if self._fast:
            mem, slot = self._span()
            ks = idx[wj]
            r = mem[slot[ks, ri][:, None] + _R19[[3, 4, bm.ANGLE]]].astype(np.float64)
            q = mem[slot[ks, n][:, None] + _R19[[3, 4]]].astype(np.float64)
            return np.concatenate([r, q], axis=1)
        rows = np.empty((wj.size, 5))
        for m, (j, i) in enumerate(zip(wj.tolist(), ri.tolist())):
            w = self.worlds[int(idx[j])]
            b, ball = w._robot_bodies[i], w._ball_body
            p, q = b.position, ball.position
            rows[m] = p[0], p[1], b.angle, q[0], q[1]
        return rows

    def _mark_touches(self, idx: np.ndarray, near_pairs: tuple[np.ndarray, np.ndarray], touched: np.ndarray) -> None:
        """touched[j, i] |= ball on robot i's face now, for the near (j, i) pairs
        (PhysicsWorld._mark_touches: the raw, unwrapped Box2D angle)."""
        wj, ri = near_pairs
        rows = self._pair_rows(idx, wj, ri)
        hit = self.ball_on_face(rows[:, 0:2] / SCALE, rows[:, 2], rows[:, 3:5] / SCALE)
        touched[wj, ri] |= hit

    def ball_on_face(self, pos: np.ndarray, heading: np.ndarray, ball_pos: np.ndarray) -> np.ndarray:
        """Vectorised :meth:`PhysicsWorld.ball_on_face`: pos (..., 2), heading (...),
        ball_pos broadcastable to pos (a (k, 2) ball is applied to every robot of its world)."""
        rp = self.robot
        lx, ly = self._ball_local(pos, heading, ball_pos)
        gap = lx - rp.front_distance - self.ball_params.radius
        return (gap >= -_FACE_PENETRATION_TOL) & (gap <= rp.dribbler_tolerance) & (np.abs(ly) <= rp.dribbler_half_width)

    def face_offset(self, pos: np.ndarray, heading: np.ndarray, ball_pos: np.ndarray) -> np.ndarray:
        """Vectorised :meth:`PhysicsWorld.face_offset` (shapes as :meth:`ball_on_face`)."""
        return np.abs(self._ball_local(pos, heading, ball_pos)[1])

    @staticmethod
    def _ball_local(pos: np.ndarray, heading: np.ndarray, ball_pos: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """:func:`ball_in_robot_frame` with one ball per world ((K, 2)) spread over (K, n, 2) robots."""
        if ball_pos.ndim == pos.ndim - 1 and pos.ndim == 3:
            ball_pos = ball_pos[:, None, :]
        return ball_in_robot_frame(pos, heading, ball_pos)

    # --------------------------------------------------------------- snapshots
    def snapshot(self, k: int) -> WorldState:
        """World k as a read-only :class:`WorldState` (copies)."""
        nb = self.n_blue
        arrays = [a[k].copy() for a in (self.pos, self.heading, self.vel, self.omega, self.on_dribbler)]
        arrays.append(self.kick_cooldown[k] <= 0)
        for a in arrays:
            a.setflags(write=False)
        bp, bv = self.ball_pos[k].copy(), self.ball_vel[k].copy()
        bp.setflags(write=False)
        bv.setflags(write=False)
        w = self.worlds[k]
        return WorldState(t=float(self.t[k]), ball_pos=bp, ball_vel=bv, blue=TeamState(*(a[:nb] for a in arrays)),
                          yellow=TeamState(*(a[nb:] for a in arrays)), ball_height=w.ball_z, ball_vz=w.ball_vz,
                          ball_max_height=w.ball_max_height)
