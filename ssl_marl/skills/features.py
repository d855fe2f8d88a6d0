"""The paper's skill state vectors and rewards as pure functions.

The paper: D. Schwab, Y. Zhu and M. Veloso, *Learning Skills for Small Size League
RoboCup*, RoboCup 2018 (LNCS 11374), section 4.3 (states, actions, rewards,
terminations of go-to-ball and aim-to-shoot).

Shared by the Gymnasium training wrappers and the deployed skills, so training
and deployment can never disagree. Every function takes a :class:`WorldState`
in the robot's *team frame* (``world.frame`` is the team; opponent goal at +x)
and the robot's index in that team. Lengths in metres, angles in radians.
*Robot frame*: origin at the robot centre, +x along its heading (through the
dribbler), +y to its left.
"""

from __future__ import annotations

import math

import numpy as np

from ..envs.actions import make_action
from ..physics.field import FieldGeometry
from ..physics.params import BallParams, RobotParams
from ..physics.state import WorldState, wrap_angle

GO_TO_BALL_SPEC = "go_to_ball/v1"  #: the paper's 14-value state
#: go-to-ball spec per state form (same action): "default" = the paper's state (v1);
#: "ball_velocity" = the paper's state and the ball's velocity in the robot frame (v2),
#: which lets a policy lead a rolling ball. A learned actor stores the spec it was trained on.
GO_TO_BALL_SPECS = {"default": GO_TO_BALL_SPEC, "ball_velocity": "go_to_ball/v2"}
GO_TO_BALL_STATES = tuple(GO_TO_BALL_SPECS)
BALL_LOST_DISTANCE = 0.05  # m: d_{d-b} beyond which a held ball counts as lost (aim-to-shoot, clearing)
#: aim-to-shoot spec per kick-action mapping (same observation, different meaning of the kick
#: action): v1 = the paper's "kick strength" (kick at strength a_k when a_k > 0), v2 = any
#: a_k > 0 kicks at full strength. A learned actor stores the spec it was trained on.
AIM_TO_SHOOT_SPECS = {"strength": "aim_to_shoot/v1", "full": "aim_to_shoot/v2"}
KICK_ACTIONS = tuple(AIM_TO_SHOOT_SPECS)
AIM_TO_SHOOT_SPEC = AIM_TO_SHOOT_SPECS["strength"]  #: the default (the paper's) mapping


def aim_to_shoot_spec(kick_action: str) -> str:
    """The aim-to-shoot spec string of a kick-action mapping; ValueError for an unknown one."""
    try:
        return AIM_TO_SHOOT_SPECS[kick_action]
    except (KeyError, TypeError):
        raise ValueError(f"kick_action must be one of {KICK_ACTIONS}, got {kick_action!r}") from None


def kick_action_of_spec(spec: str) -> str:
    """Inverse of :func:`aim_to_shoot_spec`: the kick-action mapping a spec string names."""
    for kick_action, s in AIM_TO_SHOOT_SPECS.items():
        if s == spec:
            return kick_action
    raise ValueError(f"unknown aim-to-shoot spec {spec!r}; expected one of {tuple(AIM_TO_SHOOT_SPECS.values())}")

GO_TO_BALL_ACTIONS = ("vx", "vy", "omega")
AIM_TO_SHOOT_ACTIONS = ("omega", "dribble", "kick")
GO_TO_BALL_NAMES = ("ball_x", "ball_y", "robot_vx", "robot_vy", "robot_omega", "dist_robot_ball",
                    "top_x", "top_y", "bottom_x", "bottom_y", "left_x", "left_y", "right_x", "right_y")
#: the ``ball_velocity`` state (go_to_ball/v2): the paper's 14 values, then the ball's velocity
GO_TO_BALL_V2_NAMES = GO_TO_BALL_NAMES + ("ball_vx", "ball_vy")
AIM_TO_SHOOT_NAMES = ("ball_x", "ball_y", "ball_vx", "ball_vy", "robot_omega", "dist_robot_goal",
                      "sin_left_post", "cos_left_post", "sin_right_post", "cos_right_post")


def _team(world: WorldState):
    if world.frame not in ("blue", "yellow"):
        raise ValueError("skill features need a team-frame snapshot (use to_team_frame / env.vision_state(team))")
    return world.team(world.frame)


def to_robot_frame(points: np.ndarray, pos: np.ndarray, heading: float) -> np.ndarray:
    """Express point(s) (..., 2) given in the team frame in the robot frame."""
    c, s = math.cos(heading), math.sin(heading)
    d = np.asarray(points, dtype=float) - pos
    return np.stack([c * d[..., 0] + s * d[..., 1], -s * d[..., 0] + c * d[..., 1]], axis=-1)


def rotate_to_robot(vec: np.ndarray, heading: float) -> np.ndarray:
    """Rotate a free vector (velocity) from the team frame into the robot frame."""
    c, s = math.cos(heading), math.sin(heading)
    return np.array([c * vec[0] + s * vec[1], -s * vec[0] + c * vec[1]])


def check_go_to_ball_state(state: str) -> str:
    """``state`` if it names a go-to-ball state form, else ValueError."""
    if state not in GO_TO_BALL_SPECS:
        raise ValueError(f"go-to-ball state must be one of {GO_TO_BALL_STATES}, got {state!r}")
    return state


def go_to_ball_features(world: WorldState, robot: int, field: FieldGeometry, state: str = "default") -> np.ndarray:
    """The go-to-ball state values (float32): 14 (``state="default"``, the paper's,
    spec go_to_ball/v1) or 16 (``"ball_velocity"``, spec go_to_ball/v2).

    ``(P_x^B, P_y^B, V_x^R, V_y^R, omega^R, d_{r-b}, x_top, y_top, x_bottom, y_bottom,
    x_left, y_left, x_right, y_right)``: ball position, robot velocity (both in the
    robot frame, m and m/s), angular velocity (rad/s), robot-ball distance (m), and the
    closest points of the top (+y), bottom (-y), left (-x) and right (+x) field lines
    to the robot, in the robot frame (m). Top/bottom/left/right refer to the team frame.
    ``"ball_velocity"`` appends ``(V_x^B, V_y^B)``, the ball's velocity in the robot
    frame (m/s).
    """
    check_go_to_ball_state(state)
    ts = _team(world)
    pos, h = ts.pos[robot], float(ts.heading[robot])
    ball = to_robot_frame(world.ball_pos, pos, h)
    vel = rotate_to_robot(ts.vel[robot], h)
    edges = to_robot_frame(field.edge_closest_points(pos), pos, h)
    dist = float(np.hypot(*(world.ball_pos - pos)))
    parts = [ball, vel, [ts.omega[robot], dist], edges.ravel()]
    if state == "ball_velocity":
        parts.append(rotate_to_robot(world.ball_vel, h))
    return np.concatenate(parts).astype(np.float32)


def goal_post_angles(world: WorldState, robot: int, field: FieldGeometry) -> tuple[float, float]:
    """Angles (rad, in (-pi, pi]) of the left and right posts of the opponent goal
    relative to the robot's heading (positive = to the robot's left)."""
    ts = _team(world)
    pos, h = ts.pos[robot], float(ts.heading[robot])
    left, right = field.goal_posts(+1)
    al = math.atan2(left[1] - pos[1], left[0] - pos[0]) - h
    ar = math.atan2(right[1] - pos[1], right[0] - pos[0]) - h
    return float(wrap_angle(al)), float(wrap_angle(ar))


def aim_to_shoot_features(world: WorldState, robot: int, field: FieldGeometry) -> np.ndarray:
    """The paper's 10 aim-to-shoot state values (float32).

    ``(P_x^B, P_y^B, V_x^B, V_y^B, omega^R, d_{r-g}, sin th_l, cos th_l, sin th_r, cos th_r)``:
    ball position and velocity in the robot frame (m, m/s), robot angular velocity
    (rad/s), distance from the robot to the opponent goal centre (m), and sine and
    cosine of the left and right post angles relative to the robot heading.
    """
    ts = _team(world)
    pos, h = ts.pos[robot], float(ts.heading[robot])
    ball = to_robot_frame(world.ball_pos, pos, h)
    bvel = rotate_to_robot(world.ball_vel, h)
    d_goal = float(np.hypot(*(field.goal_center(+1) - pos)))
    al, ar = goal_post_angles(world, robot, field)
    return np.array([ball[0], ball[1], bvel[0], bvel[1], ts.omega[robot], d_goal,
                     math.sin(al), math.cos(al), math.sin(ar), math.cos(ar)], dtype=np.float32)


# ------------------------------------------------------------------ geometry
def ball_angle_from_heading(world: WorldState, robot: int) -> float:
    """theta_{r-b}: unsigned angle (rad, [0, pi]) between the robot heading and the
    direction from the robot to the ball."""
    ts = _team(world)
    pos, h = ts.pos[robot], float(ts.heading[robot])
    d = world.ball_pos - pos
    return abs(float(wrap_angle(math.atan2(d[1], d[0]) - h)))


def dribbler_ball_distance(world: WorldState, robot: int, robot_params: RobotParams,
                           ball_params: BallParams) -> float:
    """d_{d-b} (m): distance from the centre of the dribbler (front-face midpoint) to
    the ball's surface, 0 when touching. The tactic's 35 mm test uses this."""
    ts = _team(world)
    pos, h = ts.pos[robot], float(ts.heading[robot])
    face = pos + robot_params.front_distance * np.array([math.cos(h), math.sin(h)])
    return max(float(np.hypot(*(world.ball_pos - face))) - ball_params.radius, 0.0)


def heading_between_posts(world: WorldState, robot: int, field: FieldGeometry, margin: float = 0.0) -> bool:
    """True if the robot's heading points between the opponent goal posts, keeping
    ``margin`` (rad) away from each post."""
    al, ar = goal_post_angles(world, robot, field)
    return al - margin > 0.0 > ar + margin


# ------------------------------------------------------------------- rewards
ORIENTATION_FORMS = ("gaussian", "printed")


def go_to_ball_reward(world: WorldState, robot: int, orientation_form: str = "gaussian") -> dict[str, float]:
    """The paper's go-to-ball reward terms (per control step).

    r_contact = 100 if the ball is on the dribbler else 0;
    r_distance = 5 / sqrt(2 pi) * exp(-d^2 / 2) - 2  (d: robot-ball distance, m);
    r_orientation = 1 / sqrt(2 pi) * exp(-2 theta^2 / pi^2) ("gaussian", default), or
    exp(-2 theta / pi^2) as printed in the paper ("printed"); theta = theta_{r-b}.
    The printed form reads like a typo (a Gaussian in the angle is the likely intent);
    both are selectable.
    """
    ts = _team(world)
    d = float(np.hypot(*(world.ball_pos - ts.pos[robot])))
    theta = ball_angle_from_heading(world, robot)
    if orientation_form == "gaussian":
        r_or = math.exp(-2.0 * theta ** 2 / math.pi ** 2) / math.sqrt(2 * math.pi)
    elif orientation_form == "printed":
        r_or = math.exp(-2.0 * theta / math.pi ** 2) / math.sqrt(2 * math.pi)
    else:
        raise ValueError(f"orientation_form must be one of {ORIENTATION_FORMS}, got {orientation_form!r}")
    return {"contact": 100.0 if bool(ts.ball_on_dribbler[robot]) else 0.0,
            "distance": 5.0 / math.sqrt(2 * math.pi) * math.exp(-d * d / 2.0) - 2.0,
            "orientation": r_or}


def aim_to_shoot_reward(world: WorldState, robot: int, field: FieldGeometry) -> dict[str, float]:
    """The paper's aim-to-shoot reward: with alpha the angle between the posts seen
    from the robot and beta the larger of the two post angles relative to the heading,
    r = 0.05 (alpha - beta) |V_B| if alpha > beta else (alpha - beta) |V_B|  (V_B: ball
    velocity, m/s). Positive only while the heading lies between the posts."""
    al, ar = goal_post_angles(world, robot, field)
    alpha = abs(float(wrap_angle(al - ar)))
    beta = max(abs(al), abs(ar))
    speed = float(np.hypot(*world.ball_vel))
    diff = alpha - beta
    return {"aim": (0.05 * diff if diff > 0 else diff) * speed}


# ------------------------------------------------------------ action mappings
def go_to_ball_task_action(action5: np.ndarray) -> np.ndarray:
    """A skill's full (5,) env action -> go-to-ball's (3,) task action (vx, vy, omega)."""
    return np.asarray(action5, dtype=np.float32)[[0, 1, 2]]


def go_to_ball_env_action(action3: np.ndarray, mapping: str | None = None) -> np.ndarray:
    """go-to-ball's (3,) task action (clipped to [-1, 1]) -> the full (5,) env action,
    dribbler on. ``mapping``: a state form (:data:`GO_TO_BALL_STATES`) or None; every
    form has this one action."""
    if mapping is not None:
        check_go_to_ball_state(mapping)
    a = np.clip(np.asarray(action3, dtype=np.float64), -1.0, 1.0)
    return make_action(a[0], a[1], a[2], dribble=True)


def aim_to_shoot_task_action(action5: np.ndarray) -> np.ndarray:
    """A skill's full (5,) env action -> aim-to-shoot's (3,) task action (omega, dribble, kick)."""
    return np.asarray(action5, dtype=np.float32)[[2, 3, 4]]


def aim_to_shoot_env_action(action3: np.ndarray, kick_action: str | None = "strength") -> np.ndarray:
    """aim-to-shoot's (3,) task action (clipped to [-1, 1]) -> the full (5,) env action,
    no translation. Kick: none when a_k <= 0; otherwise strength a_k (``kick_action``
    "strength", the paper's, spec v1) or full strength ("full", spec v2)."""
    kick_action = "strength" if kick_action is None else kick_action
    aim_to_shoot_spec(kick_action)  # validates
    a = np.clip(np.asarray(action3, dtype=np.float64), -1.0, 1.0)
    kick = float(a[2]) if kick_action == "strength" or a[2] <= 0 else 1.0
    return make_action(0.0, 0.0, a[0], dribble=a[1] > 0, kick=kick)
