"""State vectors, action mappings and rewards of the pass and receive skills, as pure
functions shared by the Gymnasium tasks (:mod:`ssl_marl.skills.pass_tasks`,
:mod:`ssl_marl.skills.receive_task`) and the deployed skills (:mod:`ssl_marl.skills.passing`).

Conventions as in :mod:`ssl_marl.skills.features`: a :class:`WorldState` in the robot's
team frame and the robot's index in that team; metres, seconds, radians; *robot
frame* = origin at the robot centre, +x along its heading, +y to its left.

pass state (``pass/v1``, 10 values)
    ===  =================  =====================================================
    idx  name               meaning
    ===  =================  =====================================================
    0-1  target_x, _y       pass target in the robot frame (m)
    2-3  target_vx, _vy     target velocity in the robot frame (m/s; 0 if unknown)
    4    target_dist        distance ball -> target (m)
    5-6  sin/cos_target     sine and cosine of the target's bearing from the heading
    7-8  ball_x, ball_y     ball in the robot frame (m): on the dribbler ~(0.10, 0)
    9    robot_omega        angular velocity (rad/s)
    ===  =================  =====================================================

pass action (3 values in [-1, 1])
    ``(omega, kick, speed)``: angular velocity as a fraction of ``max_omega``; kick when
    ``kick > 0``; kick speed ``PASS_SPEED_MIN + (speed + 1) / 2 * (max - min)`` m/s with
    ``PASS_SPEED_MIN`` 1 m/s and the kicker cap 6.5 m/s. The dribbler is on, the robot
    does not translate.

receive state (``receive/v1``, 11 values)
    ===  ==================  ====================================================
    idx  name                meaning
    ===  ==================  ====================================================
    0-1  ball_x, ball_y      ball in the robot frame (m)
    2-3  ball_vx, ball_vy    ball velocity in the robot frame (m/s)
    4-5  robot_vx, _vy       robot velocity in the robot frame (m/s)
    6    robot_omega         angular velocity (rad/s)
    7    line_offset         signed distance of the robot centre from the ball's
                             line of travel (m; + = left of the ball's direction;
                             0 for a ball slower than 0.1 m/s)
    8    gap                 distance along the ball's direction from the ball to
                             the robot's dribbler face (m; < 0: the ball has passed)
    9    closing_speed       ball speed minus robot speed along the ball's direction
    10   on_dribbler         1 if the ball is on the dribbler, else 0
    ===  ==================  ====================================================

receive action (3 values in [-1, 1]), three forms (the registry's action mappings)
    * ``direct`` (spec ``receive/v1``): ``(vx, vy, omega)`` in the robot frame as
      fractions of the robot's limits, dribbler on (as go-to-ball).
    * ``residual`` (spec ``receive/v2``, same 11 state values): a correction added to the
      hand-coded receive's own ``(vx, vy, omega)`` in the same state,
      ``clip(base + RECEIVE_RESIDUAL_SCALE * a, -1, 1)``
      (:func:`receive_residual_action`); an actor that outputs 0 *is* the hand-coded
      receive.
    * ``pressed`` (spec ``receive/v3``): the residual action on the 11 values above and 7
      about the opponent nearest the ball's path (:func:`receive_pressed_features`):

      ===  ==================  ===============================================
      idx  name                meaning
      ===  ==================  ===============================================
      11-12 opp_x, opp_y       that opponent in the robot frame (m)
      13-14 opp_vx, opp_vy     its velocity in the robot frame (m/s)
      15   opp_line_offset     its signed distance from the ball's line of travel
                               (m, sign as line_offset; 0 for a slow ball)
      16   opp_gap             distance along the ball's direction from the ball
                               to its dribbler face (m; as gap)
      17   opp_present         1 if the robot sees an opponent, else 0 (then
                               values 11-16 are 0)
      ===  ==================  ===============================================

      "Nearest the ball's path": the least distance to the segment from the ball to
      the receiving robot (a robot that can cut the pass off ranks first). The correction
      applies only where :func:`receive_press_active` (that opponent near the ball's line
      and between the ball and the robot, the ball not yet controlled); elsewhere the
      action is the hand-coded receive's.
"""

from __future__ import annotations

import math

import numpy as np

from ..physics.params import BallParams, RobotParams
from ..physics.state import WorldState, wrap_angle
from .base import make_action
from .features import rotate_to_robot, to_robot_frame

PASS_SPEC = "pass/v1"
RECEIVE_SPEC = "receive/v1"
RECEIVE_SPEC_RESIDUAL = "receive/v2"  #: same state as v1; the action is a correction of the hand-coded receive
RECEIVE_SPEC_PRESSED = "receive/v3"  #: v2's residual action on v1's state + the nearest opponent to the ball's path
#: receive action forms (the registry's action-mapping names) -> spec strings
RECEIVE_ACTION_FORMS = {"direct": RECEIVE_SPEC, "residual": RECEIVE_SPEC_RESIDUAL, "pressed": RECEIVE_SPEC_PRESSED}
#: the action forms whose action is a correction of the hand-coded receive's
RECEIVE_RESIDUAL_FORMS = ("residual", "pressed")
#: m: a ``receive/v3`` correction applies while the path's nearest opponent is at most this far
#: from the ball's line (the interceptors of the pressed task start at most 3 m from it)
RECEIVE_PRESS_GATE_M = 3.0
#: m: ... and at least this far ahead of the robot along the ball's path, between the ball and the
#: robot (the pressed task's interceptors start at most 0.9 of the way from the ball to the robot;
#: a marker beside or behind the receiver does not switch the correction on)
RECEIVE_PRESS_AHEAD_M = 0.3
#: :func:`receive_press_active` written over the ``receive/v3`` state names (an exported model's metadata)
RECEIVE_PRESS_RULE = (f"opp_present > 0.5 and on_dribbler < 0.5 and abs(opp_line_offset) <= {RECEIVE_PRESS_GATE_M}"
                      f" and opp_gap <= gap - {RECEIVE_PRESS_AHEAD_M}")
#: largest correction (fraction of each velocity / turn-rate limit) a residual action adds
RECEIVE_RESIDUAL_SCALE = 0.5
PASS_SPEED_MIN = 1.0  #: m/s, the slowest kick the pass action can ask for
SLOW_BALL = 0.1  #: m/s: below this the ball has no usable direction of travel

PASS_NAMES = ("target_x", "target_y", "target_vx", "target_vy", "target_dist", "sin_target", "cos_target",
              "ball_x", "ball_y", "robot_omega")
RECEIVE_NAMES = ("ball_x", "ball_y", "ball_vx", "ball_vy", "robot_vx", "robot_vy", "robot_omega", "line_offset",
                 "gap", "closing_speed", "on_dribbler")
RECEIVE_PRESSED_NAMES = RECEIVE_NAMES + ("opp_x", "opp_y", "opp_vx", "opp_vy", "opp_line_offset", "opp_gap",
                                         "opp_present")


def _team(world: WorldState):
    if world.frame not in ("blue", "yellow"):
        raise ValueError("skill features need a team-frame snapshot (use to_team_frame / env.vision_state(team))")
    return world.team(world.frame)


def check_point(name: str, p) -> np.ndarray:
    """(2,) float array from ``p``; ValueError naming ``name`` if it is not 2 finite numbers."""
    try:
        a = np.asarray(p, dtype=float).reshape(2)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be 2 finite numbers (x, y in m), got {p!r}") from None
    if not np.isfinite(a).all():
        raise ValueError(f"{name} must be 2 finite numbers (x, y in m), got {a.tolist()}")
    return a


def check_options(where: str, options: dict, known: set[str]) -> None:
    """ValueError naming ``where`` (e.g. "PassEnv.reset") and the keys of ``options``
    outside ``known``."""
    unknown = set(options) - known
    if unknown:
        raise ValueError(f"{where}: unknown option(s) {sorted(unknown)}; known: {sorted(known)}")


# ---------------------------------------------------------------------- pass
def pass_features(world: WorldState, robot: int, target: np.ndarray, target_vel: np.ndarray | None = None
                  ) -> np.ndarray:
    """The 10 pass state values (float32), see the module table. ``target`` and
    ``target_vel`` in the team frame (m, m/s)."""
    ts = _team(world)
    pos, h = ts.pos[robot], float(ts.heading[robot])
    tgt = to_robot_frame(target, pos, h)
    tv = rotate_to_robot(np.zeros(2) if target_vel is None else np.asarray(target_vel, float), h)
    ball = to_robot_frame(world.ball_pos, pos, h)
    dist = float(np.hypot(*(np.asarray(target, float) - world.ball_pos)))
    bearing = math.atan2(tgt[1], tgt[0])
    return np.array([tgt[0], tgt[1], tv[0], tv[1], dist, math.sin(bearing), math.cos(bearing), ball[0], ball[1],
                     ts.omega[robot]], dtype=np.float32)


def pass_kick_speed(a_speed: float, robot_params: RobotParams) -> float:
    """Kick speed (m/s) of the pass action's speed entry in [-1, 1]."""
    frac = (float(np.clip(a_speed, -1.0, 1.0)) + 1.0) / 2.0
    return PASS_SPEED_MIN + frac * (robot_params.kick_speed_max - PASS_SPEED_MIN)


def pass_speed_action(speed: float, robot_params: RobotParams) -> float:
    """Inverse of :func:`pass_kick_speed` (clipped to [-1, 1])."""
    frac = (float(speed) - PASS_SPEED_MIN) / (robot_params.kick_speed_max - PASS_SPEED_MIN)
    return float(np.clip(2.0 * frac - 1.0, -1.0, 1.0))


def expand_pass_action(action3: np.ndarray, robot_params: RobotParams) -> np.ndarray:
    """The pass task's (omega, kick, speed) as a full (5,) env action: dribbler on, no
    translation, kick strength = kick speed / cap when ``kick > 0``."""
    a = np.clip(np.asarray(action3, dtype=np.float64).reshape(3), -1.0, 1.0)
    strength = pass_kick_speed(a[2], robot_params) / robot_params.kick_speed_max if a[1] > 0 else 0.0
    return make_action(0.0, 0.0, a[0], dribble=True, kick=strength)


def pass_task_action(action5: np.ndarray, robot_params: RobotParams) -> np.ndarray:
    """Project a pass skill's (5,) action onto the task's (omega, kick, speed)."""
    a = np.asarray(action5, dtype=np.float64)
    kick = a[4] > 0
    speed = pass_speed_action(a[4] * robot_params.kick_speed_max, robot_params) if kick else 0.0
    return np.array([a[2], 1.0 if kick else -1.0, speed], dtype=np.float32)


def pass_aim_error(world: WorldState, robot: int, target: np.ndarray) -> float:
    """Signed angle (rad) from the robot's heading to the direction ball -> target."""
    ts = _team(world)
    d = np.asarray(target, float) - world.ball_pos
    return float(wrap_angle(math.atan2(d[1], d[0]) - float(ts.heading[robot])))


def pass_reward(aim_error: float, kicked_now: bool, outcome: str | None) -> dict[str, float]:
    """Pass reward terms for one step.

    * ``aim``: -0.1 |aim error| (rad) per step before the kick (turn towards the target);
    * ``kick``: +1 on the step of the kick, scaled by cos(aim error) (a kick at the target);
    * ``outcome``: +10 when the receiver controls the ball, -5 on a failure (ball lost,
      timeout, ball stopped short, out, not received), 0 while running.
    """
    return {"aim": -0.1 * abs(aim_error) if not kicked_now else 0.0,
            "kick": math.cos(aim_error) if kicked_now else 0.0,
            "outcome": 10.0 if outcome == "success" else (-5.0 if outcome else 0.0)}


# ------------------------------------------------------------------- receive
def ball_line_geometry(world: WorldState, robot: int, robot_params: RobotParams, ball_params: BallParams
                       ) -> tuple[float, float, float, np.ndarray]:
    """(line_offset, gap, closing_speed, u) of a receiving robot, team frame.

    ``u`` is the ball's unit direction of travel (zeros for a ball slower than
    :data:`SLOW_BALL`, then offset = 0 and gap = the distance to the face along the
    robot-ball line). See the module table for the meaning of the three numbers."""
    ts = _team(world)
    offset, gap, u = line_offset_gap(ts.pos[robot], world, robot_params.front_distance + ball_params.radius)
    closing = float(np.hypot(*world.ball_vel)) - float(ts.vel[robot] @ u) if np.any(u) else 0.0
    return offset, gap, closing, u


def line_offset_gap(point: np.ndarray, world: WorldState, reach: float) -> tuple[float, float, np.ndarray]:
    """(line offset, gap, u) of a robot centred at ``point`` whose dribbler face is
    ``reach`` (m) from its centre, against the ball's line of travel (module table, state
    7-8; ``u`` the ball's unit direction, zeros for a ball slower than :data:`SLOW_BALL`,
    then the offset is 0 and the gap the distance to the face along the robot-ball line)."""
    d = np.asarray(point, float) - world.ball_pos
    sp = float(np.hypot(*world.ball_vel))
    if sp < SLOW_BALL:
        return 0.0, float(np.hypot(*d)) - reach, np.zeros(2)
    u = world.ball_vel / sp
    return float(u[0] * d[1] - u[1] * d[0]), float(d @ u) - reach, u


def receive_features(world: WorldState, robot: int, robot_params: RobotParams, ball_params: BallParams
                     ) -> np.ndarray:
    """The 11 receive state values (float32), see the module table."""
    ts = _team(world)
    pos, h = ts.pos[robot], float(ts.heading[robot])
    ball = to_robot_frame(world.ball_pos, pos, h)
    bvel = rotate_to_robot(world.ball_vel, h)
    rvel = rotate_to_robot(ts.vel[robot], h)
    offset, gap, closing, _ = ball_line_geometry(world, robot, robot_params, ball_params)
    return np.array([ball[0], ball[1], bvel[0], bvel[1], rvel[0], rvel[1], ts.omega[robot], offset, gap, closing,
                     1.0 if bool(ts.ball_on_dribbler[robot]) else 0.0], dtype=np.float32)


def path_threat(world: WorldState, robot: int) -> int | None:
    """Index of the opponent nearest the segment from the ball to robot ``robot`` (team
    frame; the one best placed to cut a pass to it off), or None without opponents."""
    ts = _team(world)
    opp = world.opponents(world.frame)
    if len(opp.pos) == 0:
        return None
    a, b = world.ball_pos, ts.pos[robot]
    ab = b - a
    t = np.clip(((opp.pos - a) @ ab) / max(float(ab @ ab), 1e-12), 0.0, 1.0)
    d = np.hypot(*(opp.pos - (a + t[:, None] * ab)).T)
    return int(np.argmin(d))


def receive_pressed_features(world: WorldState, robot: int, robot_params: RobotParams, ball_params: BallParams
                             ) -> np.ndarray:
    """The 18 ``receive/v3`` state values (float32): :func:`receive_features` and the
    opponent of :func:`path_threat` (module table)."""
    base = receive_features(world, robot, robot_params, ball_params)
    k = path_threat(world, robot)
    if k is None:
        return np.concatenate([base, np.zeros(7, np.float32)])
    ts, opp = _team(world), world.opponents(world.frame)
    pos, h = ts.pos[robot], float(ts.heading[robot])
    rel = to_robot_frame(opp.pos[k], pos, h)
    vel = rotate_to_robot(opp.vel[k], h)
    offset, gap, _ = line_offset_gap(opp.pos[k], world, robot_params.front_distance + ball_params.radius)
    extra = np.array([rel[0], rel[1], vel[0], vel[1], offset, gap, 1.0], dtype=np.float32)
    return np.concatenate([base, extra])


def receive_press_active(features: np.ndarray) -> bool:
    """True where a ``receive/v3`` correction applies, from its 18 state values: an
    opponent is seen, at most :data:`RECEIVE_PRESS_GATE_M` from the ball's line and at
    least :data:`RECEIVE_PRESS_AHEAD_M` closer to the ball along it than the robot (a
    robot that can cut the pass off), and the ball is not on the dribbler. Elsewhere the
    pressed receive is the hand-coded one (the plain task, a ball already under control,
    a marker beside or behind the receiver). :data:`RECEIVE_PRESS_RULE` is the same rule
    over the state names."""
    f = np.asarray(features, dtype=np.float64)
    return bool(f[17] > 0.5 and f[10] < 0.5 and abs(f[15]) <= RECEIVE_PRESS_GATE_M
                and f[16] <= f[8] - RECEIVE_PRESS_AHEAD_M)


def expand_receive_action(action3: np.ndarray) -> np.ndarray:
    """The receive task's (vx, vy, omega) as a full (5,) env action, dribbler on."""
    a = np.clip(np.asarray(action3, dtype=np.float64).reshape(3), -1.0, 1.0)
    return make_action(a[0], a[1], a[2], dribble=True)


def receive_task_action(action5: np.ndarray) -> np.ndarray:
    """Project a receive skill's (5,) action onto the task's (vx, vy, omega)."""
    return np.asarray(action5, dtype=np.float32)[[0, 1, 2]]


def check_receive_action_form(action_form: str) -> str:
    """``action_form`` if it is a receive action form, else ValueError naming the known ones."""
    if action_form not in RECEIVE_ACTION_FORMS:
        raise ValueError(f"receive action_form must be one of {tuple(RECEIVE_ACTION_FORMS)}, got {action_form!r}")
    return action_form


def receive_residual_action(base3: np.ndarray, correction3: np.ndarray,
                            scale: float = RECEIVE_RESIDUAL_SCALE) -> np.ndarray:
    """The ``residual`` receive action: ``clip(base3 + scale * clip(correction3), -1, 1)``
    (float32, 3 values; ``base3`` = the hand-coded receive's (vx, vy, omega) fractions)."""
    c = np.clip(np.asarray(correction3, dtype=np.float64).reshape(3), -1.0, 1.0)
    return np.clip(np.asarray(base3, dtype=np.float64).reshape(3) + scale * c, -1.0, 1.0).astype(np.float32)


def receive_residual_of(base3: np.ndarray, action3: np.ndarray, scale: float = RECEIVE_RESIDUAL_SCALE
                        ) -> np.ndarray:
    """Inverse of :func:`receive_residual_action`: the correction (clipped to [-1, 1])
    that turns ``base3`` into ``action3`` (0 when they are equal)."""
    d = (np.asarray(action3, dtype=np.float64).reshape(3) - np.asarray(base3, dtype=np.float64).reshape(3)) / scale
    return np.clip(d, -1.0, 1.0).astype(np.float32)


def receive_outcome_reward(outcome: str | None) -> dict[str, float]:
    """The sparse receive reward (``reward_form="outcome"``): ``outcome`` = +1 on success
    (control held 0.5 s), -1 on a failure (out, timeout), else 0. Small returns keep the
    critic's Q of the same order as a behaviour-cloning term (docs/RESULTS.md)."""
    return {"outcome": 1.0 if outcome == "success" else (-1.0 if outcome else 0.0)}


def receive_reward(world: WorldState, robot: int, robot_params: RobotParams, ball_params: BallParams,
                   outcome: str | None) -> dict[str, float]:
    """Receive reward terms for one step (ground truth).

    * ``line``: -|line offset| (m) while the ball moves towards the robot (gap > 0),
      else -0.5 x the robot-ball distance (go and get a ball that has passed or stopped);
    * ``facing``: -0.2 x |angle between the heading and the direction to the ball| / pi;
    * ``contact``: +1 per step with the ball on the dribbler;
    * ``outcome``: +10 on success (control held 0.5 s), -5 on a failure, else 0.
    """
    ts = _team(world)
    pos, h = ts.pos[robot], float(ts.heading[robot])
    offset, gap, _, u = ball_line_geometry(world, robot, robot_params, ball_params)
    d = world.ball_pos - pos
    if gap > 0 and np.any(u):
        line = -abs(offset)
    else:
        line = -0.5 * float(np.hypot(*d))
    face = abs(float(wrap_angle(math.atan2(d[1], d[0]) - h)))
    return {"line": line, "facing": -0.2 * face / math.pi,
            "contact": 1.0 if bool(ts.ball_on_dribbler[robot]) else 0.0,
            "outcome": 10.0 if outcome == "success" else (-5.0 if outcome else 0.0)}
