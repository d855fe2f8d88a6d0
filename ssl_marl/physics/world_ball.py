"""The ball's mechanics inside one :class:`~ssl_marl.physics.world.PhysicsWorld`:
the kicker (flat and chip kicks, kick on contact), the two-phase ground friction and
the ball in the air (:mod:`ssl_marl.physics.ball_flight` beside Box2D, the collision
filter that lets a high ball pass over robots).

:class:`BallMechanics` is a mixin of :class:`~ssl_marl.physics.world.PhysicsWorld`: it
reads and writes the world's Box2D bodies (``_ball_body``, ``_robot_bodies``,
``_walls_body``, ``world``), parameters (``robot``, ``ball_params``, ``sub_dt``) and ball
state (``ball_z``, ``ball_vz``, ``ball_bounces``, ``ball_max_height``, ``_slide_until``,
``kick_cooldown``, ``kicks_this_step``, ``touchdowns``). Units: metres, seconds, radians
outside Box2D; Box2D values are scaled by :data:`~ssl_marl.physics.units.SCALE`.
"""

from __future__ import annotations

import math

import numpy as np

from . import ball_flight
from .units import _FACE_PENETRATION_TOL, MASK_ALL, MASK_WALLS, POS_ITERS, SCALE, VEL_ITERS


class BallMechanics:
    """Kicker, ground friction and flight of the ball (a mixin of PhysicsWorld)."""

    def _fire_kick(self, i: int, strength: float, heading: float, chip_angle: float) -> None:
        """Robot i kicks: 3-D ball speed strength * kick_speed_max (strength capped at 1)
        along ``heading`` (rad), lifted by ``chip_angle`` (rad, clipped to
        [0, chip_angle_max]; 0 = flat)."""
        rp, S = self.robot, SCALE
        speed = min(strength, 1.0) * rp.kick_speed_max
        h = heading
        angle = min(max(chip_angle, 0.0), rp.chip_angle_max)
        if angle > 0.0:
            vh, vv = ball_flight.launch(np.array([speed]), np.array([angle]))
            self._ball_body.linearVelocity = (float(vh[0]) * math.cos(h) * S, float(vh[0]) * math.sin(h) * S)
            self._slide_until = math.inf
            self._set_flight(0.0, float(vv[0]))
        else:
            self._ball_body.linearVelocity = (speed * math.cos(h) * S, speed * math.sin(h) * S)
            self._launch_ball(speed)
            if self.ball_z > 0.0 or self.ball_vz != 0.0:
                self._set_flight(0.0, 0.0)
        self.ball_max_height = 0.0
        self.kick_cooldown[i] = rp.kick_recharge_s
        self.kicks_this_step.append((i, speed))

    def _armed_contact(self, armed: list[int]) -> int:
        """The armed robot with the ball on its face now (Box2D's current positions, raw
        angles), the ball most centred on the face where several have it (``face_offset``;
        exact ties: the lower index), or -1; never while the ball is above the bar."""
        if self.ball_z > self.ball_params.radius:
            return -1
        S = SCALE
        bp = self._ball_body.position
        ball = np.array((bp[0] / S, bp[1] / S))
        pos = np.array([(b.position[0] / S, b.position[1] / S) for b in (self._robot_bodies[i] for i in armed)])
        hd = np.array([self._robot_bodies[i].angle for i in armed])
        hit = np.flatnonzero(self.ball_on_face(pos, hd, ball))
        if hit.size > 1:
            hit = hit[[int(np.argmin(self.face_offset(pos[hit], hd[hit], ball)))]]
        return armed[int(hit[0])] if hit.size else -1

    # ------------------------------------------------------------ ball in the air
    def _set_flight(self, z: float, vz: float) -> None:
        """Put the ball at height z (m) with vertical speed vz (m/s), a new flight."""
        self.ball_z, self.ball_vz, self.ball_bounces = float(z), float(vz), 0
        self.ball_max_height = max(self.ball_max_height, self.ball_z)
        self._update_ball_filter()

    def _update_ball_filter(self) -> None:
        """The ball's fixture ignores robots exactly while it is above their height."""
        over = self.ball_z > self.robot.height
        if over != self._ball_over_robots and self._ball_body is not None:
            fix = self._ball_body.fixtures[0]
            fd = fix.filterData
            fd.maskBits = MASK_WALLS if over else MASK_ALL
            fix.filterData = fd
        self._ball_over_robots = over

    def _flight_substep(self) -> None:
        """One physics sub-step of a ball in the air: height in closed form, horizontal
        motion by Box2D without ground friction, the bounce's horizontal damping applied
        from the touchdown on."""
        bp, S, dt = self.ball_params, SCALE, self.sub_dt
        fs = ball_flight.advance(np.array([self.ball_z]), np.array([self.ball_vz]), np.array([self.ball_bounces]), dt,
                                 bp.gravity, bp.bounce_damping_z, bp.bounce_damping_xy_first,
                                 bp.bounce_damping_xy_later, bp.min_hop_height)
        self.ball_max_height = max(self.ball_max_height, float(fs.apex[0]))
        self._update_ball_filter()
        if not fs.bounced[0]:
            self.world.Step(dt, VEL_ITERS, POS_ITERS)
            self.ball_z, self.ball_vz = float(fs.z[0]), float(fs.vz[0])
            self._update_ball_filter()
            return
        ball = self._ball_body
        v, p = ball.linearVelocity, ball.position
        vx, vy = v[0], v[1]
        tt = float(fs.t_touch[0])
        self.touchdowns.append(((p[0] + vx * tt) / S, (p[1] + vy * tt) / S))
        eff = float(ball_flight.effective_xy_scale(fs, dt)[0])
        ball.linearVelocity = (vx * eff, vy * eff)
        self.world.Step(dt, VEL_ITERS, POS_ITERS)
        v = ball.linearVelocity
        k = float(fs.xy_factor[0]) / eff
        ball.linearVelocity = (v[0] * k, v[1] * k)
        self.ball_bounces += 1
        self.ball_z, self.ball_vz = float(fs.z[0]), float(fs.vz[0])
        if fs.landed[0]:
            self.ball_bounces = 0
            self._slide_until = math.inf  # after its hops the ball rolls
        self._update_ball_filter()

    def _ball_touches_robot(self) -> bool:
        """A Box2D contact between the ball and a robot body is touching now."""
        for edge in self._ball_body.contacts:
            if edge.other is not self._walls_body and edge.contact.touching:
                return True
        return False

    # ------------------------------------------------------ dribbler and friction
    def _apply_dribblers(self, idx: list[int]) -> None:
        """One dribbler holds the ball at a time: of the robots ``idx`` with the dribbler on
        and the ball on the face, the one with the ball nearest the middle of its face
        (exact ties: the lower index; as a contested kick, ``face_offset``) pulls it in and
        carries it along."""
        rp, S, dt = self.robot, SCALE, self.sub_dt
        ball = self._ball_body
        bp = ball.position
        bx, by = bp[0] / S, bp[1] / S
        hw = rp.dribbler_half_width
        best = None
        for i in idx:
            b = self._robot_bodies[i]
            p = b.position
            rx, ry, h = p[0] / S, p[1] / S, b.angle
            c, s = math.cos(h), math.sin(h)
            dx, dy = bx - rx, by - ry
            lx, ly = c * dx + s * dy, -s * dx + c * dy  # ball in robot frame
            gap = lx - rp.front_distance - self.ball_params.radius
            if -_FACE_PENETRATION_TOL <= gap <= rp.dribbler_tolerance and abs(ly) <= hw \
                    and (best is None or abs(ly) < abs(best[5])):
                best = (b, c, s, dx, dy, ly)
        if best is None:
            return
        b, c, s, dx, dy, ly = best
        bv = ball.linearVelocity
        vbx, vby = bv[0] / S, bv[1] / S
        v = b.linearVelocity
        w = b.angularVelocity
        # velocity of the face point under the ball + pull-in + centring (robot frame -> field)
        tx = v[0] / S - w * dy
        ty = v[1] / S + w * dx
        pull_l = -rp.dribbler_pull_speed
        cent_l = -2.0 * ly
        tx += c * pull_l - s * cent_l
        ty += s * pull_l + c * cent_l
        ddx, ddy = tx - vbx, ty - vby
        dn = math.sqrt(ddx * ddx + ddy * ddy)
        lim = rp.dribbler_max_accel * dt
        if dn > lim:
            ddx, ddy = ddx * lim / dn, ddy * lim / dn
        vbx, vby = vbx + ddx, vby + ddy
        ball.linearVelocity = (vbx * S, vby * S)

    def _launch_ball(self, speed: float) -> None:
        """A ball set moving at ``speed`` (m/s) by a kick or a placement slides until it
        has slowed to ``slide_to_roll_ratio`` of that speed; a ball at rest rolls."""
        self._slide_until = self.ball_params.slide_to_roll_ratio * speed if speed > 0 else math.inf

    def _apply_ball_friction(self) -> None:
        bp, S = self.ball_params, SCALE
        v = self._ball_body.linearVelocity
        vx, vy = v[0] / S, v[1] / S
        sp = math.sqrt(vx * vx + vy * vy)
        if sp <= 0.0:
            return
        if sp > self._slide_until:
            dec = bp.slide_decel
        else:
            dec = bp.roll_decel
            self._slide_until = math.inf
        new = max(sp - dec * self.sub_dt, 0.0)
        k = new / sp * S
        self._ball_body.linearVelocity = (vx * k, vy * k)
