"""The Box2D world: the only module that touches Box2D.

Top-down, zero gravity. Box2D runs in *decimetres* (``SCALE`` = 10 Box2D units per
metre) so that the 43 mm ball is a comfortable size for the solver and Box2D's
fixed restitution velocity threshold (``b2_velocityThreshold`` = 1 unit/s)
becomes 0.1 m/s instead of 1 m/s: a ball that hits a wall at 0.5 m/s still
bounces. Everything outside this module is in metres; conversion happens here
only.

Model (all parameters in :mod:`ssl_marl.physics.params`):

* Robots are dynamic bodies (a circle of radius 0.09 m cut by a flat front face,
  built from three convex polygons). Each control step their velocity is moved
  towards the commanded body-frame (vx, vy, omega), with |dv| limited by the
  acceleration (or braking) limit times dt, and speeds capped. Contacts then act
  on the bodies inside Box2D's step.
* The ball is a bullet (continuous collision) circle with fixed rotation. Rolling
  resistance is not Box2D damping but the two-phase model: it decelerates at
  ``slide_decel`` after a kick until its speed falls to ``slide_to_roll_ratio``
  times the kick speed, then at ``roll_decel``.
* Dribbler: while on, and while the ball touches the front face within its
  width, the bar accelerates the ball towards the velocity of the contact point
  (robot velocity + omega x r) plus a small pull-in and centring, with at most
  ``dribbler_max_accel``. Spinning at 10 rad/s needs ~10 m/s^2 of centripetal
  acceleration at the face, more than the bar can give, so the ball is lost;
  driving forward gently keeps it. Switching the dribbler off releases the ball.
* Kicker: a kick with strength k in (0, 1] sets the ball's 3-D speed to
  k * ``kick_speed_max`` along the robot heading, only when the ball is on the
  kicker face and the kicker has recharged (``kick_recharge_s``). A chip kick
  (elevation angle a in (0, ``chip_angle_max``]) sends k * ``kick_speed_max`` * cos(a)
  along the heading and k * ``kick_speed_max`` * sin(a) upwards.
* Ball in the air (:mod:`ssl_marl.physics.ball_flight`): height and vertical speed
  are integrated in closed form beside Box2D; no ground friction in flight; damped
  bounces; above the robots' height the ball's fixture stops colliding with robots
  (walls and goals still stop it). ``ball_max_height`` is the highest the ball has
  been since a robot last touched it (the goal rule's "at most 0.15 m").
* Contest order: Box2D solves contacts in an order that follows body creation, and
  when two robots squeeze the ball between them the one created later keeps it (in
  1,500 random two-robot contests, 64 were decided by the order, 60 of them for the
  later body). Robots are therefore created in an order drawn from the scene's own
  poses (:func:`creation_order`): the same scene always builds the same world, and
  no robot index, so no colour, is favoured on average. Contested kicks and
  dribbles go to the robot with the ball most centred on its face (``face_offset``).
"""

from __future__ import annotations

import math

import Box2D
import numpy as np

from .field import FieldGeometry
from .params import BallParams, RobotParams
from .state import TeamState, WorldState, wrap_angle

from .units import _FACE_PENETRATION_TOL, CAT_BALL, CAT_ROBOT, POS_ITERS, SCALE, VEL_ITERS
from .world_ball import BallMechanics


def cap_velocities(vel: np.ndarray, omega: np.ndarray | None, v_cap: float, w_cap: float = math.inf):
    """Hard speed caps, applied after every control step (single and batched worlds).

    vel (..., 2) and omega (...) in Box2D units as read from the bodies; v_cap and
    w_cap in the same units. Returns (vel, omega, changed): velocities longer than
    v_cap scaled down to it and angular velocities clipped to +-w_cap, both rounded to
    float32 as Box2D stores them, and the (...) mask of bodies that changed.
    """
    sp = np.sqrt(vel[..., 0] * vel[..., 0] + vel[..., 1] * vel[..., 1])
    over = sp > v_cap
    changed = over.copy()
    if over.any():
        k = np.where(over, v_cap / np.where(over, sp, 1.0), 1.0)
        vel = np.where(over[..., None], (vel * k[..., None]).astype(np.float32), vel)
    if omega is not None:
        spin = np.abs(omega) > w_cap
        if spin.any():
            omega = np.where(spin, np.clip(omega, -w_cap, w_cap).astype(np.float32), omega)
            changed |= spin
    return vel, omega, changed


def creation_order(robot_pose: np.ndarray) -> np.ndarray:
    """(n,) the order in which a world's robot bodies are created: a permutation drawn
    from the bits of ``robot_pose`` ((n, 3) m, m, rad), so it is the same for the same
    scene and independent of the robots' indices (module docstring, "Contest order")."""
    pose = np.ascontiguousarray(robot_pose, dtype=np.float64)
    entropy = np.frombuffer(pose.tobytes(), dtype=np.uint32)
    return np.random.default_rng(entropy.tolist() or [0]).permutation(pose.shape[0])


def ball_in_robot_frame(pos: np.ndarray, heading: np.ndarray, ball_pos: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(lx, ly) in m: the ball's centre in each robot's body frame (+x forward).
    ``pos`` (..., 2) m, ``heading`` (...) rad, ``ball_pos`` broadcastable to ``pos``. The
    one formula of the single and the batched worlds' face checks (bit-equal results)."""
    d0 = ball_pos[..., 0] - pos[..., 0]
    d1 = ball_pos[..., 1] - pos[..., 1]
    c, s = np.cos(heading), np.sin(heading)
    return c * d0 + s * d1, -s * d0 + c * d1


class PhysicsWorld(BallMechanics):
    """Box2D simulation of one SSL field with robots and one ball.

    Robots are indexed 0..n_blue-1 (blue) then n_blue..n_blue+n_yellow-1 (yellow).

    Args:
        field: field geometry.
        robot: robot parameters (shared by all robots).
        ball: ball parameters.
        n_blue, n_yellow: robots per team.
        control_dt: control period (s); one call of :meth:`step` advances this much.
        substeps: Box2D steps per control step.
    """

    def __init__(self, field: FieldGeometry, robot: RobotParams, ball: BallParams, n_blue: int, n_yellow: int,
                 control_dt: float = 1.0 / 60.0, substeps: int = 2) -> None:
        self.field, self.robot, self.ball_params = field, robot, ball
        self.n_blue, self.n_yellow = n_blue, n_yellow
        self.n = n_blue + n_yellow
        self.control_dt = float(control_dt)
        self.substeps = int(substeps)
        self.sub_dt = self.control_dt / self.substeps
        self.world: Box2D.b2World | None = None
        self.t = 0.0
        self._robot_bodies: list = []
        self._ball_body = None
        # cached state (metres)
        self.pos = np.zeros((self.n, 2))
        self.heading = np.zeros(self.n)
        self.vel = np.zeros((self.n, 2))
        self.omega = np.zeros(self.n)
        self.on_dribbler = np.zeros(self.n, bool)  # ball touched the face during the last step
        self._on_face_now = np.zeros(self.n, bool)  # ball touching the face now
        self.kick_cooldown = np.zeros(self.n)
        self.ball_pos = np.zeros(2)
        self.ball_vel = np.zeros(2)
        self._slide_until = math.inf  # ball slides while speed > this (m/s)
        self.kicks_this_step: list[tuple[int, float]] = []  # (robot index, ball speed)
        self.ball_z = 0.0  # m, height of the ball's lowest point above the field
        self.ball_vz = 0.0  # m/s, up positive
        self.ball_bounces = 0  # bounces of the current flight
        self.ball_max_height = 0.0  # m, highest since a robot last touched the ball
        self._ball_over_robots = False  # the ball's fixture ignores robots
        self.touchdowns: list[tuple[float, float]] = []  # (x, y) m of this step's bounces

    def set_params(self, robot: RobotParams | None = None, ball: BallParams | None = None) -> None:
        """Replace the robot and/or ball parameters (e.g. one episode's domain-randomised
        draw); they take effect at the next :meth:`reset`, which builds a fresh world
        (the cached fixture definitions carry the restitution coefficients and are
        rebuilt). Radius and front distance must not change: observations and tactics
        assume the nominal shape."""
        for new, old_p, name in ((robot, self.robot, "robot"), (ball, self.ball_params, "ball")):
            if new is None:
                continue
            if new.radius != old_p.radius or getattr(new, "front_distance", 0) != getattr(old_p, "front_distance", 0):
                raise ValueError(f"set_params: the {name}'s shape (radius / front_distance) cannot change")
        if robot is not None:
            self.robot = robot
        if ball is not None:
            self.ball_params = ball
        if hasattr(self, "_robot_fixdefs"):
            del self._robot_fixdefs  # rebuilt at the next reset with the new coefficients

    # ---------------------------------------------------------------- building
    def _make_fixture_defs(self) -> None:
        """Shapes are built once; every reset reuses them (creating SWIG shapes is slow)."""
        S, rp = SCALE, self.robot
        r, fd, hw = rp.radius, rp.front_distance, rp.dribbler_half_width
        a0 = math.acos(fd / r)  # half-angle of the front cut
        # The robot (a circle cut by a chord: convex) as two 8-vertex polygons, top and
        # bottom half: max radial error 2 mm, plus Box2D's 1 mm polygon skin.
        arc = np.linspace(a0, math.pi, 7)
        top = [(fd * S, 0.0)] + [(r * S * math.cos(a), r * S * math.sin(a)) for a in arc]
        top[1] = (fd * S, hw * S)
        polys = [top, [(x, -y) for (x, y) in reversed(top)]]
        area = 0.0
        for p in polys:
            xs, ys = np.array(p).T
            area += 0.5 * abs(np.dot(xs, np.roll(ys, 1)) - np.dot(ys, np.roll(xs, 1)))
        self._robot_fixdefs = [Box2D.b2FixtureDef(shape=Box2D.b2PolygonShape(vertices=p), density=rp.mass / area,
                                                  friction=rp.friction, restitution=rp.restitution_ball,
                                                  categoryBits=CAT_ROBOT)
                               for p in polys]
        br = self.ball_params.radius * S
        # Box2D mixes restitution as max(a, b): the ball's own coefficient is 0 so that
        # ball-robot contacts use the robot's and ball-wall contacts the wall's.
        self._ball_fixdef = Box2D.b2FixtureDef(shape=Box2D.b2CircleShape(radius=br),
                                               density=self.ball_params.mass / (math.pi * br * br),
                                               friction=0.1, restitution=0.0, categoryBits=CAT_BALL)
        f = self.field
        boxes = []
        t = 0.5  # outer wall thickness (m), generous so nothing tunnels
        hx, hy = f.wall_half_length, f.wall_half_width
        boxes += [(hx + t, t / 2, 0, hy + t / 2), (hx + t, t / 2, 0, -hy - t / 2),
                  (t / 2, hy + t, hx + t / 2, 0), (t / 2, hy + t, -hx - t / 2, 0)]
        # goals: back wall and two side walls, behind each goal line
        gd, gt, ghw, L2 = f.goal_depth, f.goal_wall_thickness, f.goal_width / 2, f.half_length
        for side in (1, -1):
            boxes += [(gt / 2, ghw + gt, side * (L2 + gd + gt / 2), 0.0),
                      (gd / 2, gt / 2, side * (L2 + gd / 2), ghw + gt / 2),
                      (gd / 2, gt / 2, side * (L2 + gd / 2), -ghw - gt / 2)]
        self._wall_fixdefs = [Box2D.b2FixtureDef(shape=Box2D.b2PolygonShape(box=(bw * S, bh * S, (cx * S, cy * S), 0.0)),
                                                 friction=0.1, restitution=self.ball_params.restitution_wall)
                              for bw, bh, cx, cy in boxes]

    def _build(self, robot_pose: np.ndarray, robot_vel: np.ndarray, ball_pos: np.ndarray, ball_vel: np.ndarray) -> None:
        """Create a fresh b2World with every body at its initial state (no SetTransform: slow)."""
        if not hasattr(self, "_robot_fixdefs"):
            self._make_fixture_defs()
        S = SCALE
        w = Box2D.b2World(gravity=(0.0, 0.0), doSleep=False)
        walls = w.CreateStaticBody(position=(0, 0))
        self._walls_body = walls
        for fd in self._wall_fixdefs:
            walls.CreateFixture(fd)
        bodies: list = [None] * self.n  # by robot index, created in creation_order
        poses, vels = robot_pose.tolist(), robot_vel.tolist()
        for i in creation_order(robot_pose).tolist():
            (x, y, h), (vx, vy, om) = poses[i], vels[i]
            b = w.CreateDynamicBody(position=(x * S, y * S), angle=h, linearVelocity=(vx * S, vy * S),
                                    angularVelocity=om)
            for fd in self._robot_fixdefs:
                b.CreateFixture(fd)
            bodies[i] = b
        self._robot_bodies = bodies
        ball = w.CreateDynamicBody(position=(float(ball_pos[0]) * S, float(ball_pos[1]) * S), bullet=True,
                                   fixedRotation=True,
                                   linearVelocity=(float(ball_vel[0]) * S, float(ball_vel[1]) * S))
        ball.CreateFixture(self._ball_fixdef)
        self._ball_body = ball
        self.world = w

    # ----------------------------------------------------------------- control
    def reset(self, robot_pose: np.ndarray, ball_pos: np.ndarray, ball_vel: np.ndarray | None = None,
              robot_vel: np.ndarray | None = None) -> None:
        """Build a fresh Box2D world (for exact determinism) and place everything.

        Args:
            robot_pose: (n, 3) x, y (m), heading (rad), field frame.
            ball_pos: (2,) m.  ball_vel: (2,) m/s; a moving ball starts in the sliding phase.
            robot_vel: optional (n, 3) vx, vy (m/s, field frame), omega (rad/s).
        """
        robot_pose = np.asarray(robot_pose, float).reshape(self.n, 3)
        rv = np.zeros((self.n, 3)) if robot_vel is None else np.asarray(robot_vel, float).reshape(self.n, 3)
        bv = np.zeros(2) if ball_vel is None else np.asarray(ball_vel, float)
        self._build(robot_pose, rv, np.asarray(ball_pos, float), bv)
        self._launch_ball(float(np.hypot(*bv)))
        self._ball_over_robots = False  # a fresh fixture collides with everything
        self.ball_max_height = 0.0
        self._set_flight(0.0, 0.0)
        self.t = 0.0
        self.kick_cooldown = np.zeros(self.n)
        self.kicks_this_step = []
        self._read_state()

    def step(self, v_body: np.ndarray, omega: np.ndarray, dribble: np.ndarray, kick: np.ndarray,
             chip: np.ndarray | None = None) -> None:
        """Advance one control period.

        Args:
            v_body: (n, 2) commanded velocity in each robot's body frame (m/s, +x forward).
            omega: (n,) commanded angular velocity (rad/s).
            dribble: (n,) bool, dribbler on.
            kick: (n,) kick strength in [0, 1]; 0 = no kick.
            chip: optional (n,) elevation of the kick (rad, clipped to [0, chip_angle_max]);
                0 or None = a flat kick.
        """
        rp, S, dt = self.robot, SCALE, self.control_dt
        # --- robot velocity tracking ------------------------------------------------
        # A plain per-robot loop: the bodies must be touched one by one anyway, and for
        # 1-22 robots float maths beats ~20 numpy calls on tiny arrays (measured).
        vmax, acc, brk = rp.max_speed, rp.max_accel * dt, rp.max_brake * dt
        wmax, alpha = rp.max_omega, rp.max_alpha * dt
        bx, by = float(self.ball_pos[0]), float(self.ball_pos[1])
        bvx, bvy = float(self.ball_vel[0]), float(self.ball_vel[1])
        ball_sp = math.sqrt(bvx * bvx + bvy * bvy)
        near_base = rp.radius + rp.front_distance + self.ball_params.radius + 0.05 + (ball_sp + 2 * rp.max_accel * dt) * dt
        near: list[int] = []
        cmd_v, cmd_w = v_body.tolist(), omega.tolist()
        for i, (b, (ux, uy), w_cmd, (px, py), h, (vx, vy), w) in enumerate(zip(
                self._robot_bodies, cmd_v, cmd_w, self.pos.tolist(), self.heading.tolist(), self.vel.tolist(),
                self.omega.tolist())):
            c, sn = math.cos(h), math.sin(h)
            dx, dy = c * ux - sn * uy, sn * ux + c * uy  # desired field-frame velocity
            sp = math.sqrt(dx * dx + dy * dy)  # sqrt, not hypot: bit-equal to the batched numpy path
            if sp > vmax:
                dx, dy, sp = dx * vmax / sp, dy * vmax / sp, vmax
            ex, ey = dx - vx, dy - vy
            en = math.sqrt(ex * ex + ey * ey)
            cur = math.sqrt(vx * vx + vy * vy)
            lim = brk if sp < cur else acc
            if en > lim:
                ex, ey = ex * lim / en, ey * lim / en
            b.linearVelocity = ((vx + ex) * S, (vy + ey) * S)
            w_des = wmax if w_cmd > wmax else (-wmax if w_cmd < -wmax else w_cmd)
            dw = w_des - w
            dw = alpha if dw > alpha else (-alpha if dw < -alpha else dw)
            b.angularVelocity = w + dw
            qx, qy = px - bx, py - by
            if math.sqrt(qx * qx + qy * qy) < near_base + cur * dt:
                near.append(i)
        # --- kicker -------------------------------------------------------------
        self.kick_cooldown = np.maximum(self.kick_cooldown - dt, 0.0)  # new array: snapshots stay intact
        self.kicks_this_step = []
        kickers = np.flatnonzero((kick > 0) & self._on_face_now & (self.kick_cooldown <= 0)) if near else ()
        kicked = len(kickers) > 0
        if kicked:  # of several kicks firing at once, the robot with the ball most centred on its face
            i = int(kickers[int(np.argmin(self.face_offset(self.pos[kickers], self.heading[kickers],
                                                             self.ball_pos)))])
            self._fire_kick(i, float(kick[i]), self.heading[i], 0.0 if chip is None else float(chip[i]))
        # kick on contact: an armed kicker fires when the ball reaches its face during the step
        armed = [i for i in near if kick[i] > 0 and self.kick_cooldown[i] <= 0] \
            if rp.kick_on_contact and not kicked else []
        # --- sub-steps: dribbler, ball friction, Box2D -------------------------
        dribblers = [] if kicked else [i for i in near if dribble[i]]
        # robots near the ball are checked after every sub-step, so a fast robot whose
        # face hits the ball is seen even if the ball bounces away within the step
        touched = np.zeros(self.n, bool)
        self.touchdowns = []
        for k in range(self.substeps):
            if dribblers:
                self._apply_dribblers(dribblers)
            if self.ball_z > 0.0 or self.ball_vz > 0.0:
                self._flight_substep()
            else:
                self._apply_ball_friction()
                self.world.Step(self.sub_dt, VEL_ITERS, POS_ITERS)
            if near and k < self.substeps - 1:
                self._mark_touches(near, touched)
            if armed:
                i = self._armed_contact(armed)
                if i >= 0:
                    b = self._robot_bodies[i]
                    self._fire_kick(i, float(kick[i]), b.angle, 0.0 if chip is None else float(chip[i]))
                    armed = dribblers = []
        self.t += dt
        self._read_state(caps=True)
        self.on_dribbler = self._on_face_now if self.ball_z > self.ball_params.radius else self._on_face_now | touched
        if self.ball_max_height > 0.0 and (self.on_dribbler.any() or self._ball_touches_robot()):
            self.ball_max_height = self.ball_z

    def _mark_touches(self, idx: list[int], touched: np.ndarray) -> None:
        S = SCALE
        bp = self._ball_body.position
        ball = np.array((bp[0] / S, bp[1] / S))
        pos = np.array([(b.position[0] / S, b.position[1] / S) for b in (self._robot_bodies[i] for i in idx)])
        hd = np.array([self._robot_bodies[i].angle for i in idx])
        touched[idx] |= self.ball_on_face(pos, hd, ball)

    def _read_state(self, caps: bool = False) -> None:
        """Read every body into the cached arrays; with ``caps``, first enforce the hard
        speed caps (:func:`cap_velocities`): robot speed <= max_speed, |omega| <=
        max_omega, ball speed <= kick_speed_max. Contacts can otherwise push a robot or
        squeeze the ball past them (the soak test saw 3.3 m/s, 27 rad/s, 7.3 m/s)."""
        S = SCALE
        n = self.n
        buf = np.empty((n, 6))
        rows = []
        for b in self._robot_bodies:
            p, v = b.position, b.linearVelocity
            rows.append((p[0], p[1], b.angle, v[0], v[1], b.angularVelocity))
        if n:
            buf[:] = rows
        bp, bv = self._ball_body.position, self._ball_body.linearVelocity
        ball_v = np.array(((bv[0], bv[1]),))
        rp = self.robot
        if caps:  # cheap float pre-check (slightly conservative); cap_velocities decides exactly
            v2 = (rp.max_speed * S) ** 2 * (1 - 1e-9)
            b2 = (rp.kick_speed_max * S) ** 2 * (1 - 1e-9)
            bvx, bvy = ball_v[0]
            caps = bvx * bvx + bvy * bvy > b2 or any(
                r[3] * r[3] + r[4] * r[4] > v2 or abs(r[5]) > rp.max_omega for r in rows)
        if caps:
            vel, om, changed = cap_velocities(buf[:, 3:5], buf[:, 5], rp.max_speed * S, rp.max_omega)
            for i in np.flatnonzero(changed).tolist():
                b = self._robot_bodies[i]
                b.linearVelocity = (float(vel[i, 0]), float(vel[i, 1]))
                b.angularVelocity = float(om[i])
                buf[i, 3:5], buf[i, 5] = vel[i], om[i]
            ball_v, _, bch = cap_velocities(ball_v, None, rp.kick_speed_max * S)
            if bch[0]:
                self._ball_body.linearVelocity = (float(ball_v[0, 0]), float(ball_v[0, 1]))
        if n:
            self.pos = buf[:, 0:2] / S
            self.heading = wrap_angle(buf[:, 2])
            self.vel = buf[:, 3:5] / S
            self.omega = buf[:, 5].copy()
        self.ball_pos = np.array((bp[0] / S, bp[1] / S))
        self.ball_vel = np.array((ball_v[0, 0] / S, ball_v[0, 1] / S))
        self._on_face_now = self.ball_on_face(self.pos, self.heading, self.ball_pos)
        if self.ball_z > self.ball_params.radius:  # in the air: above the dribbler bar
            self._on_face_now = np.zeros(self.n, bool)
        self.on_dribbler = self._on_face_now

    def ball_on_face(self, pos: np.ndarray, heading: np.ndarray, ball_pos: np.ndarray) -> np.ndarray:
        """(n,) bool: ball touching the flat front face within its width (the paper's
        "ball on the dribbler" contact condition)."""
        if pos.shape[0] == 0:
            return np.zeros(0, bool)
        rp = self.robot
        lx, ly = ball_in_robot_frame(pos, heading, ball_pos)
        gap = lx - rp.front_distance - self.ball_params.radius
        return (gap >= -_FACE_PENETRATION_TOL) & (gap <= rp.dribbler_tolerance) & (np.abs(ly) <= rp.dribbler_half_width)

    def face_offset(self, pos: np.ndarray, heading: np.ndarray, ball_pos: np.ndarray) -> np.ndarray:
        """(n,) lateral offset (m) of the ball's centre from the middle of each robot's front
        face (the ``ly`` of :meth:`ball_on_face`). When several robots' kicks fire in one
        step, or several robots dribble the ball, the smallest offset gets the ball (exact
        ties: the lower index), so neither team wins contested balls by its place in the
        robot order."""
        return np.abs(ball_in_robot_frame(pos, heading, ball_pos)[1])

    def snapshot(self) -> WorldState:
        """Ground-truth :class:`WorldState` (field frame). Arrays are read-only views of
        arrays the physics never writes in place (it rebinds them every step)."""
        nb = self.n_blue
        ready = self.kick_cooldown <= 0
        arrays = (self.pos, self.heading, self.vel, self.omega, self.on_dribbler, ready)
        for a in arrays:
            a.setflags(write=False)
        bp, bv = self.ball_pos, self.ball_vel
        bp.setflags(write=False)
        bv.setflags(write=False)
        blue = TeamState(*(a[:nb] for a in arrays))
        yellow = TeamState(*(a[nb:] for a in arrays))
        return WorldState(t=self.t, ball_pos=bp, ball_vel=bv, blue=blue, yellow=yellow, ball_height=self.ball_z,
                          ball_vz=self.ball_vz, ball_max_height=self.ball_max_height)

    def set_ball(self, pos: np.ndarray, vel: np.ndarray | None = None, z: float = 0.0, vz: float = 0.0) -> None:
        """Teleport the ball (referee ball placement): position (m), horizontal velocity
        (m/s), height z >= 0 (m) and vertical velocity vz (m/s; a ball above the ground
        or rising flies). Counts as a touch for the goal rule."""
        S = SCALE
        v = np.zeros(2) if vel is None else np.asarray(vel, float)
        if not (math.isfinite(z) and math.isfinite(vz) and z >= 0.0):
            raise ValueError(f"set_ball: z must be finite and >= 0 and vz finite, got z={z!r}, vz={vz!r}")
        self._ball_body.position = (float(pos[0]) * S, float(pos[1]) * S)
        self._ball_body.linearVelocity = (float(v[0]) * S, float(v[1]) * S)
        self._launch_ball(float(np.hypot(*v)))
        self.ball_max_height = 0.0
        self._set_flight(z, vz)
        if z > 0.0 or vz > 0.0:
            self._slide_until = math.inf
        self._read_state()

    def set_robots(self, pose: np.ndarray, only: np.ndarray | None = None) -> None:
        """Teleport robots to pose (n, 3) and stop them (referee formations and
        placements). With ``only`` (indices), move just those robots."""
        S = SCALE
        pose = np.asarray(pose, float).reshape(self.n, 3)
        idx = range(self.n) if only is None else [int(i) for i in only]
        for i in idx:
            b = self._robot_bodies[i]
            b.position = (pose[i, 0] * S, pose[i, 1] * S)
            b.angle = float(pose[i, 2])
            b.linearVelocity = (0.0, 0.0)
            b.angularVelocity = 0.0
        self._read_state()
