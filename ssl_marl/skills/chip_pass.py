"""The chip pass skill: lift a pass over a robot standing in the lane, hand-coded and
learned.

A chip's ball flies (:mod:`ssl_marl.physics.ball_flight`, no drag): from the ground at
3-D speed ``v`` and elevation ``a`` its height at horizontal distance ``x`` is
``x tan a - g x^2 / (2 v^2 cos^2 a)`` and its first touchdown is at
``2 v^2 sin a cos a / g`` (:func:`~ssl_marl.physics.ball_flight.projectile_reference`).
Robots fit under 0.15 m (``RobotParams.height``): a ball whose lowest point is above
that passes over them (SSL rules; docs/references.md, "Robot and ball figures"). A
chip is for passing, not scoring: a goal does not count if the ball was higher than
0.15 m after the last touch (SSL rules). :func:`chip_kick` picks the shortest-flight
chip that clears a blocker by ``clearance`` over its whole body and touches down
``land_short`` short of the receiver; its ball may still hop above the dribbler bar (the
ball's radius) when it reaches the receiver, and a hop that high bounces off the robot's
body. With ``arrive_speed_max`` it picks, of the chips whose hops are below the bar over
the last ``ground_run`` before the receiver and no faster than that there
(:func:`chip_hops`), the one that reaches the receiver first.

The skill acts in the env's chip layout (``chip_kicks=True``, 6-entry actions: index
5 the chip, the kick's elevation as a fraction of ``RobotParams.chip_angle_max``).

State (spec ``chip_pass/v1``, 12 values, float32; robot frame, m, m/s, rad/s): the
pass's 10 values (:func:`~ssl_marl.skills.passing_features.pass_features`: target
x, y, vx, vy, distance, sin and cos of its bearing, ball x, y, turn rate), then the
lane's blocker x, y (:func:`lane_blocker`).

Action (4 values in [-1, 1]): (omega, kick, speed, elevation): turn rate (fraction of
the limit, dribbler on, no translation); kick when ``kick > 0``; the 3-D kick speed
:func:`~ssl_marl.skills.passing_features.pass_kick_speed` (1 to 6.5 m/s); elevation
``(e + 1) / 2 * chip_angle_max`` (0 to 60 deg).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..envs.actions import make_action
from ..physics.ball_flight import launch
from ..physics.field import FieldGeometry
from ..physics.params import BallParams, RobotParams
from ..physics.state import WorldState
from .features import to_robot_frame
from .navigation import line_frame
from .passing import PassBaseline, PassSkill
from .passing_features import pass_features, pass_kick_speed, pass_speed_action

CHIP_PASS_SPEC = "chip_pass/v1"
CHIP_PASS_NAMES = ("target_x", "target_y", "target_vx", "target_vy", "target_dist", "sin_target", "cos_target",
                   "ball_x", "ball_y", "omega", "blocker_x", "blocker_y")
CHIP_PASS_ACTIONS = ("omega", "kick", "speed", "elevation")
#: an opponent this close (m) to the ball -> target segment counts as standing in the lane
LANE_HALF_WIDTH = 0.5
#: opponents nearer than this (m, along the lane) to the ball or the target are not blockers
LANE_END_MARGIN = 0.2
#: the hand-coded chip's first touchdown is at least this far (m) past the blocker's body
#: and short of the receiver's face
CHIP_LAND_SHORT = 0.6
#: the hand-coded chip's ball passes this far (m) above the blocker's height
CHIP_CLEARANCE = 0.05
#: a receivable chip's ball hops no higher than the dribbler bar over at least this run (m)
#: before the receiver's face (:func:`chip_kick`'s ``arrive_speed_max``)
CHIP_GROUND_RUN = 0.3


@dataclass(frozen=True)
class ChipKick:
    """A chip: 3-D ball speed (m/s), elevation (rad), first touchdown distance (m) and
    the ball's lowest height over the blocker's body (m)."""

    speed: float
    angle: float
    landing: float
    blocker_clearance: float


def chip_hops(speed: np.ndarray, angle: np.ndarray, bp: BallParams, max_hops: int = 16
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Where chips (3-D speed m/s, elevation rad; arrays that broadcast) first hop no
    higher than the ball's radius, the dribbler bar (a higher ball bounces off a robot's
    body; :mod:`ssl_marl.physics.world`): (horizontal distance from the launch (m), time
    (s), horizontal speed (m/s)) at that bounce, by :mod:`~ssl_marl.physics.ball_flight`'s
    drag-free flight and damped bounces (vertical speed x ``bounce_damping_z``, horizontal
    x ``bounce_damping_xy_first`` at the first bounce, ``bounce_damping_xy_later`` after).
    A chip launched no faster upwards than such a hop gives (0, 0, its horizontal speed)."""
    g = bp.gravity
    vh, vz = (np.array(a, float) for a in np.broadcast_arrays(*launch(speed, angle)))
    vz_low = math.sqrt(2.0 * g * bp.radius)  # the vertical speed of a hop as high as the bar
    x, t = np.zeros_like(vh), np.zeros_like(vh)
    low = vz <= vz_low
    for k in range(max_hops):
        if low.all():
            break
        hop = 2.0 * vz / g
        x = np.where(low, x, x + vh * hop)
        t = np.where(low, t, t + hop)
        vh = np.where(low, vh, vh * (bp.bounce_damping_xy_first if k == 0 else bp.bounce_damping_xy_later))
        vz = np.where(low, vz, vz * bp.bounce_damping_z)
        low = vz <= vz_low
    return x, t, vh


def chip_kick(blocker_distance: float, receiver_distance: float, rp: RobotParams, bp: BallParams,
              clearance: float = CHIP_CLEARANCE, land_short: float = CHIP_LAND_SHORT,
              body: float | None = None, arrive_speed_max: float | None = None,
              ground_run: float = CHIP_GROUND_RUN) -> ChipKick:
    """The chip (speed <= ``rp.kick_speed_max``, elevation <= ``rp.chip_angle_max``)
    whose ball's lowest point stays ``clearance`` (m) above ``rp.height`` over the
    blocker's body (``blocker_distance`` +- ``body``, default robot radius + ball radius,
    m from the kicker's face) and whose first touchdown is at most ``receiver_distance
    - land_short`` (m); of those, the one with the shortest flight (the fastest ball to
    the receiver). Candidates: a 46 x 56 grid of elevations (15 deg to the limit) and
    speeds (1 m/s to the cap). ValueError when no chip does both.

    With ``arrive_speed_max`` (m/s) the chip is one the receiver can take on its dribbler:
    its hops are no higher than the ball's radius (:func:`chip_hops`) from at least
    ``ground_run`` (m) before ``receiver_distance`` on, at a horizontal speed of at most
    ``arrive_speed_max`` there; of those, the one that reaches ``receiver_distance``
    first (no roll deceleration counted: 0.35 m/s^2 over the last metres)."""
    g = bp.gravity
    body = rp.radius + bp.radius if body is None else body
    xs = np.array([blocker_distance - body, blocker_distance, blocker_distance + body])
    angles = np.linspace(math.radians(15.0), rp.chip_angle_max, 46)[:, None]
    speeds = np.linspace(1.0, rp.kick_speed_max, 56)[None, :]
    landing = 2.0 * speeds ** 2 * np.sin(angles) * np.cos(angles) / g
    vh, vv = launch(speeds, angles)
    t = xs[:, None, None] / vh[None]
    low = np.min(vv[None] * t - 0.5 * g * t * t, axis=0)  # the ball's lowest point over the body
    ok = (landing <= receiver_distance - land_short) & (landing > xs[-1] + land_short) & (low >= rp.height + clearance)
    if arrive_speed_max is None:
        cost = 2.0 * vv / g  # the flight
    else:
        x_low, t_low, v_low = chip_hops(speeds, angles, bp)
        ok &= (x_low <= receiver_distance - ground_run) & (v_low <= arrive_speed_max)
        cost = t_low + (receiver_distance - x_low) / np.maximum(v_low, 1e-6)
    if not ok.any():
        raise ValueError(f"no chip clears a blocker {blocker_distance:.2f} m away and lands "
                         f"{land_short:.2f} m short of a receiver {receiver_distance:.2f} m away"
                         + ("" if arrive_speed_max is None else f" at most {arrive_speed_max:.2f} m/s fast"))
    i, j = np.unravel_index(int(np.argmin(np.where(ok, cost, np.inf))), ok.shape)
    speed, angle = float(speeds[0, j]), float(angles[i, 0])
    return ChipKick(speed, angle, float(landing[i, j]), float(low[i, j]))


def lane_blocker_at(ball: np.ndarray, target: np.ndarray, opponents: np.ndarray,
                    half_width: float = LANE_HALF_WIDTH) -> np.ndarray:
    """Position (m, the frame of the inputs) of the opponent standing in the lane from
    ``ball`` to ``target``: of the ``opponents`` ((k, 2), m) within ``half_width`` of the
    segment and more than :data:`LANE_END_MARGIN` from either end along it, the one
    nearest the line; the lane's midpoint when none stands there (a chip then clears an
    imagined robot midway)."""
    ball = np.asarray(ball, float)
    opp = np.asarray(opponents, float).reshape(-1, 2)
    frame = line_frame(ball, target, opp)
    if frame is None:
        return ball.copy()
    _, length, along, cross = frame
    cross = np.abs(cross)
    inside = (along > LANE_END_MARGIN) & (along < length - LANE_END_MARGIN) & (cross < half_width)
    if inside.any():
        return opp[int(np.flatnonzero(inside)[np.argmin(cross[inside])])].copy()
    return ball + 0.5 * (np.asarray(target, float) - ball)


def lane_blocker(world: WorldState, target: np.ndarray, half_width: float = LANE_HALF_WIDTH) -> np.ndarray:
    """Team-frame position (m) of the opponent standing in the lane from the ball to
    ``target`` (team frame, m): :func:`lane_blocker_at` over the world's opponents."""
    return lane_blocker_at(world.ball_pos, target, world.opponents(world.frame).pos, half_width)


def lane_chip(ball: np.ndarray, target: np.ndarray, opponents: np.ndarray, rp: RobotParams, bp: BallParams,
              clearance: float = CHIP_CLEARANCE, land_short: float = CHIP_LAND_SHORT,
              arrive_speed_max: float | None = None) -> ChipKick | None:
    """The hand-coded chip from ``ball`` to a receiver at ``target`` (m, the frame of the
    inputs): :func:`chip_kick` over the lane's blocker
    (:func:`lane_blocker_at` of ``opponents`` (k, 2), its distance along the lane from
    the ball) landing ``land_short`` (m) short of the receiver's face (``rp.front_distance
    + bp.radius`` before ``target``), with ``arrive_speed_max`` (m/s) one the receiver
    can take on its dribbler; None where no chip fits (a short pass, a blocker too near
    either end)."""
    reach = rp.front_distance + bp.radius
    frame = line_frame(ball, target, lane_blocker_at(ball, target, opponents))
    if frame is None:
        return None
    _, length, blocker, _ = frame
    try:
        return chip_kick(float(blocker), length - reach, rp, bp, clearance, land_short,
                         arrive_speed_max=arrive_speed_max)
    except ValueError:
        return None


def chip_pass_features(world: WorldState, robot: int, target: np.ndarray, target_vel: np.ndarray | None = None
                       ) -> np.ndarray:
    """The 12 chip-pass state values (float32), see the module docstring; ``target`` and
    ``target_vel`` in the team frame (m, m/s)."""
    ts = world.team(world.frame)
    blocker = to_robot_frame(lane_blocker(world, target), ts.pos[robot], float(ts.heading[robot]))
    return np.concatenate([pass_features(world, robot, target, target_vel), blocker]).astype(np.float32)


def chip_elevation(a_elev: float, rp: RobotParams) -> float:
    """Kick elevation (rad) of the action's elevation entry in [-1, 1]."""
    return (float(np.clip(a_elev, -1.0, 1.0)) + 1.0) / 2.0 * rp.chip_angle_max


def expand_chip_pass_action(action4: np.ndarray, rp: RobotParams) -> np.ndarray:
    """The task's (omega, kick, speed, elevation) as a (6,) env action (chip layout):
    dribbler on, no translation; when ``kick > 0`` the kick strength = speed / cap and
    the chip entry = elevation / ``chip_angle_max``."""
    a = np.clip(np.asarray(action4, dtype=np.float64).reshape(4), -1.0, 1.0)
    if a[1] <= 0:
        return make_action(0.0, 0.0, a[0], dribble=True, chip=0.0)
    return make_action(0.0, 0.0, a[0], dribble=True, kick=pass_kick_speed(a[2], rp) / rp.kick_speed_max,
                       chip=chip_elevation(a[3], rp) / rp.chip_angle_max)


def chip_pass_task_values(omega: float, kicks: bool, speed_action: float, chip: float) -> np.ndarray:
    """The task's (omega, kick, speed, elevation) (float32) from the turn rate entry, whether
    it kicks, the speed entry and the chip entry (elevation / ``chip_angle_max``, [0, 1])."""
    return np.array([omega, 1.0 if kicks else -1.0, speed_action, 2.0 * chip - 1.0], dtype=np.float32)


def chip_pass_task_action(action6: np.ndarray, rp: RobotParams) -> np.ndarray:
    """A chip-pass skill's (6,) action projected onto the task's (omega, kick, speed,
    elevation) (a 5-entry action is a flat one)."""
    a = np.asarray(action6, dtype=np.float64)
    if a[4] <= 0:
        return chip_pass_task_values(a[2], False, 0.0, 0.0)
    chip = float(np.clip(a[5], 0.0, 1.0)) if len(a) > 5 else 0.0
    return chip_pass_task_values(a[2], True, pass_speed_action(a[4] * rp.kick_speed_max, rp), chip)


class ChipPassSkill(PassSkill):
    """chip pass, hand-coded or learned: a :class:`~ssl_marl.skills.passing.PassSkill`
    (target, kick bookkeeping, ball-lost and time-out failures) whose actions have the
    chip entry (6 values; 0 while it does not kick).

    :attr:`task_action` is the task's (omega, kick, speed, elevation) of the last
    :meth:`act`: for the hand-coded skill the speed and elevation of the kick it plans
    on every step, also while it still turns (an env action carries them only on the
    kick), so demonstrations map every state to the kick it leads to.

    The kick command goes out on one step; a radio that loses commands (the realistic
    preset drops 3 %) can lose it, and the robot then keeps the ball. When the world still
    shows the ball on the dribbler and the kicker charged :attr:`kick_confirm_s` after the
    command, the skill aims and kicks again."""

    name = "chip_pass"
    task_action: np.ndarray | None = None
    #: seconds after a kick command from which a ball still held with the kicker charged
    #: means the command never fired (lost on the radio): the skill aims and kicks again
    #: (more than the vision and radio delays of the realistic preset, 4 control steps)
    kick_confirm_s: float = 0.1
    _kick_sent_t: float | None = None

    def reset(self) -> None:
        super().reset()
        self._kick_sent_t = None

    def act(self, world: WorldState, robot: int) -> np.ndarray:
        self.task_action = None
        if self._kicked and self._kick_not_fired(world, robot):
            self._kicked = False
        a = super().act(world, robot)
        if self._kicked and self._kick_sent_t is None:
            self._kick_sent_t = float(world.t)
        elif not self._kicked:
            self._kick_sent_t = None
        a = a if len(a) == 6 else np.append(a, np.float32(0.0))
        if self.task_action is None:
            self.task_action = chip_pass_task_action(a, self.rp)
        return a

    def _kick_not_fired(self, world: WorldState, robot: int) -> bool:
        """Whether ``world`` shows the ball still on the dribbler and the kicker charged
        :attr:`kick_confirm_s` after the kick command (a fired kicker recharges)."""
        team = world.team(world.frame)
        waited = self._kick_sent_t is not None and world.t - self._kick_sent_t >= self.kick_confirm_s - 1e-9
        return waited and bool(team.kick_ready[robot]) and bool(team.ball_on_dribbler[robot])


class ChipPassBaseline(ChipPassSkill, PassBaseline):
    """Hand-coded chip pass: turn with the ball towards the target as the hand-coded
    pass does (:class:`~ssl_marl.skills.passing.PassBaseline`), then kick the
    :func:`lane_chip` (:func:`chip_kick` over the lane's blocker, landing ``land_short``
    (m) short of the receiver's face); where no chip fits (a short pass, a blocker too
    near) the flat pass."""

    def __init__(self, field: FieldGeometry, robot: RobotParams | None = None, ball: BallParams | None = None,
                 target=None, target_vel=None, max_time_s=None, land_short: float = CHIP_LAND_SHORT,
                 clearance: float = CHIP_CLEARANCE, **pass_kwargs) -> None:
        super().__init__(field, robot, ball, target, target_vel, max_time_s, **pass_kwargs)
        self.land_short, self.clearance = land_short, clearance

    def chip(self, world: WorldState) -> ChipKick | None:
        """The chip over the lane's blocker to the current target (:func:`lane_chip`), or
        None when none fits."""
        return lane_chip(world.ball_pos, self.target, world.opponents(world.frame).pos, self.rp, self.bp,
                         self.clearance, self.land_short)

    def aim(self, world: WorldState, robot: int) -> tuple[np.ndarray, bool]:
        action, kicks = super().aim(world, robot)
        kick = self.chip(world)
        speed, angle = (self.plan(world)[1], 0.0) if kick is None else (kick.speed, kick.angle)
        self.task_action = chip_pass_task_values(action[2], kicks, pass_speed_action(speed, self.rp),
                                                 angle / self.rp.chip_angle_max)
        if not kicks:
            return np.append(action, np.float32(0.0)), False
        return make_action(omega=float(action[2]), dribble=True, kick=speed / self.rp.kick_speed_max,
                           chip=angle / self.rp.chip_angle_max), True


class LearnedChipPass(ChipPassSkill):
    """Learned chip pass: the trained actor maps :func:`chip_pass_features` to (omega,
    kick, speed, elevation)."""

    def __init__(self, field: FieldGeometry, robot: RobotParams | None = None, ball: BallParams | None = None,
                 target=None, target_vel=None, max_time_s=None, checkpoint: str | Path | None = None,
                 policy=None) -> None:
        super().__init__(field, robot, ball, target, target_vel, max_time_s)
        if policy is None:
            from .learned import load_policy

            policy = load_policy("chip_pass", checkpoint)[0]
        self.policy = policy

    def aim(self, world: WorldState, robot: int) -> tuple[np.ndarray, bool]:
        a4 = np.clip(self.policy(chip_pass_features(world, robot, self.target, self.target_vel)), -1.0, 1.0)
        self.task_action = a4.astype(np.float32)
        a = expand_chip_pass_action(a4, self.rp)
        return a, bool(a[4] > 0)


__all__ = ["CHIP_CLEARANCE", "CHIP_GROUND_RUN", "CHIP_LAND_SHORT", "CHIP_PASS_ACTIONS", "CHIP_PASS_NAMES", "CHIP_PASS_SPEC", "ChipKick",
           "ChipPassBaseline", "ChipPassSkill", "LearnedChipPass", "chip_elevation", "chip_hops", "chip_kick", "chip_pass_features",
           "chip_pass_task_action", "chip_pass_task_values", "expand_chip_pass_action", "lane_blocker",
           "lane_blocker_at", "lane_chip"]
