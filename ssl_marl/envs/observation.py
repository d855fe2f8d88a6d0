"""Per-agent observation vectors, built for a whole team at once with numpy.

Every observation is in the agent's *team frame* (own goal at -x, opponent goal at
+x; yellow's frame is the field frame rotated by pi), so one policy serves both
colours. Layout (float32), with K = ``obs_max_teammates``, M = ``obs_max_opponents``:

======  ====================  ===================================================
index   name                  meaning (team frame; m, m/s, rad/s)
======  ====================  ===================================================
0-1     self_x, self_y        own position
2-3     self_cos, self_sin    cos / sin of own heading
4-5     self_vx, self_vy      own velocity
6       self_omega            own angular velocity
7-8     ball_dx, ball_dy      ball position relative to self
9-10    ball_vx, ball_vy      ball velocity
11      ball_on_dribbler      1 if the ball is on own dribbler, else 0
12      kick_ready            1 if the kicker is charged
13      ball_visible          0 if vision lost the ball this frame (pos = last seen)
14-15   opp_goal_dx, _dy      opponent goal centre relative to self
16-17   own_goal_dx, _dy      own goal centre relative to self
18      field_half_length     L / 2
19      field_half_width      W / 2
20      goal_half_width       goal width / 2
21...   teammates             K slots x 7: mask, dx, dy, vx, vy, cos, sin
...     opponents             M slots x 7: mask, dx, dy, vx, vy, cos, sin
D-2     ball_z                (chip kicks only) ball height above the field (m)
D-1     ball_vz               (chip kicks only) ball vertical velocity (m/s, up +)
======  ====================  ===================================================

With chip kicks (``EnvConfig.chip_kicks``, the env's v1 layout) the two ball-in-air
entries are appended after the slots, so every other index stays where it is; they are
what vision reports (the truth without realism; 0 with realism on, since SSL-Vision
reports a ground ball, see :mod:`ssl_marl.envs.realism`).

Teammate and opponent slots are sorted by distance to self (nearest first); unused
slots are all zero (mask 0).

Bounds (:func:`observation_bounds`, the env's ``observation_space``): finite and
documented, and observations are clipped into them (:func:`clip_to_bounds`), so they
really stay inside. Positions: the outer walls plus :data:`POSITION_MARGIN_M` (room for
vision noise); relative positions: twice that. Velocities: :data:`SPEED_SAFETY` times
the caps (robot ``max_speed`` / ``max_omega``; ball: kick cap + robot top speed, a ball
kicked by a moving robot), since collisions can briefly exceed the commanded caps.
cos/sin in [-1, 1], flags and masks in [0, 1]. Ball height: [0, apex of a vertical
kick at the kick cap] (kick_speed_max^2 / 2g); vertical velocity: +-kick_speed_max. In
normal play clipping never binds.
"""

from __future__ import annotations

import numpy as np

from ..physics.field import FieldGeometry
from ..physics.params import BallParams, RobotParams
from ..physics.state import TeamState, WorldState

SELF_DIM = 21
SLOT_DIM = 7

OBS_NAMES_SELF = ("self_x", "self_y", "self_cos", "self_sin", "self_vx", "self_vy", "self_omega", "ball_dx",
                  "ball_dy", "ball_vx", "ball_vy", "ball_on_dribbler", "kick_ready", "ball_visible", "opp_goal_dx",
                  "opp_goal_dy", "own_goal_dx", "own_goal_dy", "field_half_length", "field_half_width",
                  "goal_half_width")
SLOT_NAMES = ("mask", "dx", "dy", "vx", "vy", "cos", "sin")
#: the ball-in-air entries appended with chip kicks
BALL_AIR_NAMES = ("ball_z", "ball_vz")
BALL_AIR_DIM = len(BALL_AIR_NAMES)

POSITION_MARGIN_M = 0.5  #: m beyond the outer walls allowed in observed positions (vision noise)
SPEED_SAFETY = 2.0  #: factor on the speed caps allowed in observed velocities (collisions)


def position_extent(field: FieldGeometry) -> tuple[float, float]:
    """(x, y) half-extent (m) of any observed position: outer walls + :data:`POSITION_MARGIN_M`."""
    return field.wall_half_length + POSITION_MARGIN_M, field.wall_half_width + POSITION_MARGIN_M


def speed_caps(robot: RobotParams) -> tuple[float, float, float]:
    """(robot speed m/s, robot angular speed rad/s, ball speed m/s) bounds, :data:`SPEED_SAFETY`
    times the robot's caps and the kick cap plus the robot's top speed."""
    return (SPEED_SAFETY * robot.max_speed, SPEED_SAFETY * robot.max_omega,
            SPEED_SAFETY * (robot.kick_speed_max + robot.max_speed))


def ball_air_bounds(robot: RobotParams, ball: BallParams) -> tuple[list[float], list[float]]:
    """(low, high) of the ball-in-air entries: height in [0, kick_speed_max^2 / 2g] (m, the
    apex of a vertical kick at the cap), vertical velocity within +-kick_speed_max (m/s)."""
    v = robot.kick_speed_max
    return [0.0, -v], [v * v / (2.0 * ball.gravity), v]


def observation_bounds(field: FieldGeometry, robot: RobotParams, max_teammates: int,
                       max_opponents: int, ball: BallParams | None = None) -> tuple[np.ndarray, np.ndarray]:
    """(low, high) float32 arrays of the observation layout above (see the module docstring);
    with ``ball`` (chip kicks) the ball-in-air entries' bounds are appended."""
    x, y = position_extent(field)
    v, w, vb = speed_caps(robot)
    self_hi = [x, y, 1, 1, v, v, w, 2 * x, 2 * y, vb, vb, 1, 1, 1, 2 * x, 2 * y, 2 * x, 2 * y,
               field.half_length, field.half_width, field.goal_width / 2]
    self_lo = [-x, -y, -1, -1, -v, -v, -w, -2 * x, -2 * y, -vb, -vb, 0, 0, 0, -2 * x, -2 * y, -2 * x, -2 * y,
               0, 0, 0]
    slot_hi, slot_lo = [1, 2 * x, 2 * y, v, v, 1, 1], [0, -2 * x, -2 * y, -v, -v, -1, -1]
    n_slots = max_teammates + max_opponents
    air_lo, air_hi = ball_air_bounds(robot, ball) if ball is not None else ([], [])
    low = np.array(self_lo + slot_lo * n_slots + air_lo, dtype=np.float32)
    high = np.array(self_hi + slot_hi * n_slots + air_hi, dtype=np.float32)
    return low, high


def state_bounds(field: FieldGeometry, robot: RobotParams, n_robots: int) -> tuple[np.ndarray, np.ndarray]:
    """(low, high) float32 arrays of :func:`state_vector` (same rules as :func:`observation_bounds`)."""
    x, y = position_extent(field)
    v, w, vb = speed_caps(robot)
    high = [x, y, vb, vb] + [x, y, 1, 1, v, v, w, 1] * n_robots
    low = [-x, -y, -vb, -vb] + [-x, -y, -1, -1, -v, -v, -w, 0] * n_robots
    return np.array(low, dtype=np.float32), np.array(high, dtype=np.float32)


def clip_to_bounds(obs: np.ndarray, low: np.ndarray, high: np.ndarray) -> np.ndarray:
    """``obs`` clipped into [low, high] in place (float32 observations keep their dtype)."""
    return np.clip(obs, low, high, out=obs)


def obs_dim(max_teammates: int, max_opponents: int, ball_air: bool = False) -> int:
    """Observation length; ``ball_air`` (chip kicks) adds the two ball-in-air entries."""
    return SELF_DIM + SLOT_DIM * (max_teammates + max_opponents) + (BALL_AIR_DIM if ball_air else 0)


def obs_names(max_teammates: int, max_opponents: int, ball_air: bool = False) -> list[str]:
    names = list(OBS_NAMES_SELF)
    for k in range(max_teammates):
        names += [f"mate{k}_{s}" for s in SLOT_NAMES]
    for k in range(max_opponents):
        names += [f"opp{k}_{s}" for s in SLOT_NAMES]
    return names + (list(BALL_AIR_NAMES) if ball_air else [])


def _slots(pos: np.ndarray, other: TeamState, n_slots: int, exclude_self: bool, sgn: float) -> np.ndarray:
    """(n, n_slots*7) slots of ``other`` robots relative to each row of pos (team frame)."""
    n, m = pos.shape[0], other.n
    out = np.zeros((n, n_slots, SLOT_DIM), dtype=np.float64)
    if m == 0 or n_slots == 0 or n == 0:
        return out.reshape(n, -1)
    opos = other.pos * sgn
    rel = opos[None, :, :] - pos[:, None, :]  # (n, m, 2)
    d2 = (rel ** 2).sum(-1)
    if exclude_self:
        np.fill_diagonal(d2, np.inf)
    order = np.argsort(d2, axis=1, kind="stable")
    k = m - 1 if exclude_self else m
    k = min(k, n_slots)
    order = order[:, :k]
    rows = np.arange(n)[:, None]
    ovel = other.vel * sgn
    oh = other.heading + (0.0 if sgn > 0 else np.pi)
    out[:, :k, 0] = 1.0
    out[:, :k, 1:3] = rel[rows, order]
    out[:, :k, 3:5] = ovel[order]
    out[:, :k, 5] = np.cos(oh)[order]
    out[:, :k, 6] = np.sin(oh)[order]
    return out.reshape(n, -1)


def _fill_self(out: np.ndarray, pos: np.ndarray, cos_h: np.ndarray, sin_h: np.ndarray, vel: np.ndarray,
               omega: np.ndarray, ball_pos: np.ndarray, ball_vel: np.ndarray, on_dribbler: np.ndarray,
               kick_ready: np.ndarray, ball_visible: bool, field: FieldGeometry) -> None:
    """Write the 21 own/ball/goal values (indices 0-20) of every row of ``out``; all
    inputs already in each row's team frame."""
    out[:, 0:2] = pos
    out[:, 2] = cos_h
    out[:, 3] = sin_h
    out[:, 4:6] = vel
    out[:, 6] = omega
    out[:, 7:9] = ball_pos - pos
    out[:, 9:11] = ball_vel
    out[:, 11] = on_dribbler
    out[:, 12] = kick_ready
    out[:, 13] = 1.0 if ball_visible else 0.0
    out[:, 14] = field.half_length - pos[:, 0]
    out[:, 15] = -pos[:, 1]
    out[:, 16] = -field.half_length - pos[:, 0]
    out[:, 17] = -pos[:, 1]
    out[:, 18] = field.half_length
    out[:, 19] = field.half_width
    out[:, 20] = field.goal_width / 2


def team_observations(ws: WorldState, team: str, field: FieldGeometry, max_teammates: int,
                      max_opponents: int, ball_air: bool = False) -> np.ndarray:
    """(n_team, obs_dim) float32 observations for every robot of ``team`` from a
    field-frame snapshot ``ws`` (``ball_air``: with the ball-in-air entries)."""
    sgn = 1.0 if team == "blue" else -1.0
    own = ws.team(team)
    opp = ws.opponents(team)
    n = own.n
    out = np.zeros((n, obs_dim(max_teammates, max_opponents, ball_air)), dtype=np.float64)
    if n == 0:
        return out.astype(np.float32)
    if ball_air:
        out[:, -BALL_AIR_DIM:] = (ws.ball_height, ws.ball_vz)
    pos = own.pos * sgn
    h = own.heading + (0.0 if sgn > 0 else np.pi)
    _fill_self(out, pos, np.cos(h), np.sin(h), own.vel * sgn, own.omega, ws.ball_pos * sgn, ws.ball_vel * sgn,
               own.ball_on_dribbler, own.kick_ready, ws.ball_visible, field)
    a = SELF_DIM
    b = a + SLOT_DIM * max_teammates
    c = b + SLOT_DIM * max_opponents
    out[:, a:b] = _slots(pos, own, max_teammates, True, sgn)
    out[:, b:c] = _slots(pos, opp, max_opponents, False, sgn)
    return out.astype(np.float32)


_OFFSETS: dict[tuple[int, int], np.ndarray] = {}


def _category_offset(nb: int, ny: int) -> np.ndarray:
    """(n, n) sort-key offsets: 0 for teammates, 1e9 for opponents, 2e9 for self."""
    key = (nb, ny)
    if key not in _OFFSETS:
        team = np.concatenate([np.zeros(nb), np.ones(ny)])
        off = np.where(team[:, None] == team[None, :], 0.0, 1e9)
        np.fill_diagonal(off, 2e9)
        _OFFSETS[key] = off
    return _OFFSETS[key]


def all_observations(ws: WorldState, field: FieldGeometry, max_teammates: int, max_opponents: int,
                     ball_air: bool = False) -> np.ndarray:
    """(n_blue + n_yellow, obs_dim) float32 observations of every robot (blue first),
    in one vectorised pass; row for row equal to :func:`team_observations` (the simpler
    per-team reference that the tests compare against). ``ball_air`` (chip kicks): with
    the ball-in-air entries."""
    nb, ny = ws.blue.n, ws.yellow.n
    n = nb + ny
    d = obs_dim(max_teammates, max_opponents, ball_air)
    out = np.zeros((n, d), dtype=np.float64)
    if n == 0:
        return out.astype(np.float32)
    if ball_air:
        out[:, -BALL_AIR_DIM:] = (ws.ball_height, ws.ball_vz)
    sgn = np.concatenate([np.ones(nb), -np.ones(ny)])
    P = np.concatenate([ws.blue.pos, ws.yellow.pos])
    V = np.concatenate([ws.blue.vel, ws.yellow.vel])
    H = np.concatenate([ws.blue.heading, ws.yellow.heading])
    cos_h, sin_h = np.cos(H), np.sin(H)
    s2 = sgn[:, None]
    pos = P * s2
    _fill_self(out, pos, cos_h * sgn, sin_h * sgn, V * s2, np.concatenate([ws.blue.omega, ws.yellow.omega]),
               ws.ball_pos[None, :] * s2, ws.ball_vel[None, :] * s2,
               np.concatenate([ws.blue.ball_on_dribbler, ws.yellow.ball_on_dribbler]),
               np.concatenate([ws.blue.kick_ready, ws.yellow.kick_ready]), ws.ball_visible, field)
    if n > 1 and (max_teammates or max_opponents):
        # One argsort per step: key = distance^2 + category offset (teammates, then
        # opponents, then self), so each row lists teammates by distance, then opponents.
        rel = (P[None, :, :] - P[:, None, :]) * s2[:, :, None]  # (i, j): robot j seen from i, i's frame
        d2 = np.einsum("ijk,ijk->ij", rel, rel)
        key = d2 + _category_offset(nb, ny)
        order = np.argsort(key, axis=1, kind="stable")
        feat = np.empty((n, n, SLOT_DIM))
        feat[:, :, 0] = 1.0
        feat[:, :, 1:3] = rel
        feat[:, :, 3:5] = V[None, :, :] * s2[:, :, None]
        feat[:, :, 5] = cos_h[None, :] * s2  # heading + pi in yellow's frame
        feat[:, :, 6] = sin_h[None, :] * s2
        g = np.take_along_axis(feat, order[:, :, None], axis=1)  # (n, n, 7) sorted
        t_start, o_start = SELF_DIM, SELF_DIM + SLOT_DIM * max_teammates
        for rows, n_mates, n_opp in ((slice(0, nb), nb - 1, ny), (slice(nb, n), ny - 1, nb)):
            km, ko = min(max(n_mates, 0), max_teammates), min(n_opp, max_opponents)
            if km > 0:
                out[rows, t_start:t_start + SLOT_DIM * km] = g[rows, :km].reshape(-1, SLOT_DIM * km)
            if ko > 0:
                om = max(n_mates, 0)
                out[rows, o_start:o_start + SLOT_DIM * ko] = g[rows, om:om + ko].reshape(-1, SLOT_DIM * ko)
    return out.astype(np.float32)


def state_vector(ws: WorldState) -> np.ndarray:
    """Whole world in the field frame (for centralised critics): ball x, y, vx, vy,
    then per robot (blue 0.., yellow 0..): x, y, cos, sin, vx, vy, omega, on_dribbler."""
    parts = [np.concatenate([ws.ball_pos, ws.ball_vel])]
    for ts in (ws.blue, ws.yellow):
        if ts.n:
            parts.append(np.column_stack([ts.pos, np.cos(ts.heading), np.sin(ts.heading), ts.vel, ts.omega,
                                          ts.ball_on_dribbler]).ravel())
    return np.concatenate(parts).astype(np.float32)


def state_dim(n_robots: int) -> int:
    return 4 + 8 * n_robots
