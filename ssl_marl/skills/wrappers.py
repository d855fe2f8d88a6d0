"""The paper's skills as single-robot Gymnasium tasks.

:class:`GoToBallTask` and :class:`AimToShootTask` are the tasks (start, observation,
action mapping, reward, outcome; all in the controlled robot's team frame), so they
run on any robot of any env through :class:`~ssl_marl.skills.robot_env.RobotSkillEnv`.
:class:`GoToBallEnv` / :class:`AimToShootEnv` (``ssl_marl/GoToBall-v0``,
``ssl_marl/AimToShoot-v0``) are those tasks over a one-robot env
(:class:`~ssl_marl.skills.robot_env.OneRobotSkillEnv`): ``blue_0`` and, by default, no
other robot; yellow opponents can be added, ``static`` or driven by the baseline
go-to-ball skill (``chase``). Noise / latency options of the simulator pass through
(``realism=...``): features are computed from what the robot *sees*
(``env.vision_state``), rewards and outcomes from the ground truth.
"""

from __future__ import annotations

import math
from typing import Any

import gymnasium
import numpy as np
from gymnasium.utils import EzPickle

from ..envs.observation import position_extent, speed_caps
from ..physics.field import FieldGeometry
from ..physics.params import RobotParams
from ..physics.state import WorldState
from .base import make_action
from .features import (BALL_LOST_DISTANCE, GO_TO_BALL_SPECS, ORIENTATION_FORMS, aim_to_shoot_env_action,
                       aim_to_shoot_features, aim_to_shoot_reward, aim_to_shoot_spec, check_go_to_ball_state,
                       dribbler_ball_distance, go_to_ball_env_action, go_to_ball_features, go_to_ball_reward)
from .registry import get_task
from .robot_env import Judgement, OneRobotSkillEnv, SkillTask, Start

AGENT = "blue_0"



def skill_observation_bounds(skill: str, field: FieldGeometry, robot: RobotParams,
                             state: str = "default") -> tuple[np.ndarray, np.ndarray]:
    """(low, high) float32 bounds of a skill task's observation (``"go-to-ball"`` or
    ``"aim-to-shoot"``; ``state``: go-to-ball's state form), from the same rules as the
    full-field env (:mod:`ssl_marl.envs.observation`): any robot-frame point lies within
    D, the largest distance between two observable positions; velocities within the
    speed caps x safety factor; distances in [0, D]; sin/cos in [-1, 1]."""
    x, y = position_extent(field)
    d = math.hypot(2 * x, 2 * y)
    v, w, vb = speed_caps(robot)
    if skill == "go-to-ball":  # ball xy, robot v, omega, dist, 4 closest line points (, ball v)
        high = [d, d, v, v, w, d] + [d] * 8
        low = [-d, -d, -v, -v, -w, 0.0] + [-d] * 8
        if check_go_to_ball_state(state) == "ball_velocity":
            high, low = high + [vb, vb], low + [-vb, -vb]
    elif skill == "aim-to-shoot":  # ball xy, ball v, omega, dist to goal, sin/cos of the post angles
        high = [d, d, vb, vb, w, d, 1, 1, 1, 1]
        low = [-d, -d, -vb, -vb, -w, 0.0, -1, -1, -1, -1]
    else:
        raise ValueError(f"unknown skill task {skill!r}; expected 'go-to-ball' or 'aim-to-shoot'")
    return np.array(low, dtype=np.float32), np.array(high, dtype=np.float32)


class GoToBallTask(SkillTask):
    """go-to-ball: drive to the ball and get it on the dribbler (paper, section 4.3).

    Observation
        ``Box(-inf, inf, (14,), float32)``: the paper's state (``state="default"``, spec
        go_to_ball/v1), or ``(16,)``: the paper's state and the ball's velocity
        (``state="ball_velocity"``, spec go_to_ball/v2); see
        :func:`ssl_marl.skills.features.go_to_ball_features` (robot frame, m, m/s, rad/s).
    Action
        ``Box(-1, 1, (3,), float32)``: (vx, vy, omega) in the robot frame as fractions of
        the robot's max speed and max angular speed. The dribbler is on.
    Reward
        r_contact + r_distance + r_orientation
        (:func:`ssl_marl.skills.features.go_to_ball_reward`; per-term values in
        ``info["reward_terms"]``; ``orientation_form`` "gaussian" (default) or "printed").
    Termination
        Success (terminated, ``info["is_success"] = True``) when the ball is on the
        dribbler. Failure (truncated, ``failure_reason = "timeout"``) at ``max_time_s``
        (10 s).
    Spawn
        The paper's: the ball at rest uniformly on the field (0.1 m inside the lines), the
        robot at a uniformly random position and heading at least 0.3 m from the ball.
        With probability ``rolling`` an episode starts instead with the ball rolling, as
        in a match after a pass, a shot or a rebound: the ball at least 1 m inside the
        lines, moving at ``U(rolling_speed)`` m/s in a uniformly random direction, the
        robot ``U(1, 4)`` m from it in a uniformly random direction (kept 0.2 m inside
        the lines) with a uniformly random heading. Reset options (team frame):
        ``ball_pos``, ``robot_pose``, ``face_ball`` (a paper's spawn with those fixed).
    """

    def __init__(self, max_time_s: float = 10.0, orientation_form: str = "gaussian", state: str = "default",
                 rolling: float = 0.0, rolling_speed: tuple[float, float] = (0.5, 4.0)) -> None:
        if orientation_form not in ORIENTATION_FORMS:
            raise ValueError(f"orientation_form must be one of {ORIENTATION_FORMS}, got {orientation_form!r}")
        if not (math.isfinite(max_time_s) and max_time_s > 0):
            raise ValueError(f"max_time_s must be positive, got {max_time_s!r}")
        if not (isinstance(rolling, (int, float)) and 0.0 <= rolling <= 1.0):
            raise ValueError(f"rolling must be a probability in [0, 1], got {rolling!r}")
        speeds = tuple(rolling_speed) if isinstance(rolling_speed, (tuple, list)) else ()
        if len(speeds) != 2 or not all(isinstance(v, (int, float)) and math.isfinite(v) for v in speeds) \
                or not 0.0 <= speeds[0] <= speeds[1]:
            raise ValueError(f"rolling_speed must be (low, high) m/s with 0 <= low <= high, got {rolling_speed!r}")
        lo, hi = speeds
        self.max_time_s = max_time_s
        self.orientation_form = orientation_form
        self.state = check_go_to_ball_state(state)
        self.spec_version = GO_TO_BALL_SPECS[state]
        self.rolling, self.rolling_speed = float(rolling), (float(lo), float(hi))
        n_obs = len(get_task("go_to_ball").names_of(state)[0])
        self.observation_space = gymnasium.spaces.Box(-np.inf, np.inf, (n_obs,), np.float32)  # bounded in bind()
        self.action_space = gymnasium.spaces.Box(-1.0, 1.0, (3,), np.float32)

    def bind(self, field, robot, ball, dt) -> None:
        super().bind(field, robot, ball, dt)
        self.observation_space = gymnasium.spaces.Box(*skill_observation_bounds("go-to-ball", field, robot, self.state),
                                                      self.observation_space.shape, np.float32)

    def sample_start(self, rng: np.random.Generator, options: dict) -> Start:
        fixed = any(options.get(k) is not None for k in ("ball_pos", "robot_pose")) or options.get("face_ball")
        if not fixed and self.rolling > 0.0 and (self.rolling >= 1.0 or rng.random() < self.rolling):
            return self._rolling_start(rng)
        f = self.field
        ball = options.get("ball_pos")
        if ball is None:
            ball = f.random_free_point(rng, margin=0.1)
        pose = options.get("robot_pose")
        if pose is None:
            xy = f.random_free_point(rng, 0.1, [np.asarray(ball)], 0.3)
            heading = rng.uniform(-math.pi, math.pi)
            if options.get("face_ball"):
                heading = math.atan2(ball[1] - xy[1], ball[0] - xy[0])
            pose = (xy[0], xy[1], heading)
        return Start(np.asarray(pose, float), np.asarray(ball, float))

    def _rolling_start(self, rng: np.random.Generator) -> Start:
        f = self.field
        ball = f.random_free_point(rng, margin=1.0)
        ang = rng.uniform(-math.pi, math.pi)
        robot = ball + rng.uniform(1.0, 4.0) * np.array([math.cos(ang), math.sin(ang)])
        robot = np.clip(robot, [-f.half_length + 0.2, -f.half_width + 0.2], [f.half_length - 0.2, f.half_width - 0.2])
        d = rng.uniform(-math.pi, math.pi)
        vel = rng.uniform(*self.rolling_speed) * np.array([math.cos(d), math.sin(d)])
        return Start(np.array([robot[0], robot[1], rng.uniform(-math.pi, math.pi)]), ball, vel)

    def observe(self, seen: WorldState, robot: int) -> np.ndarray:
        return go_to_ball_features(seen, robot, self.field, self.state)

    def env_action(self, action: np.ndarray) -> np.ndarray:
        return go_to_ball_env_action(action)

    def judge(self, truth: WorldState, robot: int, events: list[dict], t: float) -> Judgement:
        terms = go_to_ball_reward(truth, robot, self.orientation_form)
        success = bool(truth.team(truth.frame).ball_on_dribbler[robot])
        timeout = (not success) and t >= self.max_time_s - 1e-9
        return Judgement(terms, terminated=success, truncated=timeout, success=success,
                         failure_reason=None if success else "timeout")


class AimToShootTask(SkillTask):
    """aim-to-shoot: with the ball on the dribbler, turn towards the goal and score
    (paper, section 4.3).

    Observation
        ``Box(-inf, inf, (10,), float32)``: the paper's state, see
        :func:`ssl_marl.skills.features.aim_to_shoot_features`.
    Action
        ``Box(-1, 1, (3,), float32)``: (omega, dribble, kick): angular velocity as a
        fraction of max_omega; dribbler on when > 0; kick when > 0, with strength = value
        (``kick_action="strength"``, the paper's, spec ``aim_to_shoot/v1``) or at full
        strength (``kick_action="full"``, spec ``aim_to_shoot/v2``). With "strength" a
        policy whose kick output rises smoothly through 0 fires a weak kick first that
        stops short of the goal; the paper's demonstrations and reward favour full-speed
        kicks anyway. The robot does not translate.
    Reward
        0.05 (alpha - beta) |V_B| if alpha > beta else (alpha - beta) |V_B|, every step
        (:func:`ssl_marl.skills.features.aim_to_shoot_reward`), ``reward_form="paper"``.
        Because the ball moves with the dribbler while the robot turns, that reward
        charges ~6 * integral(alpha - beta) dtheta for a turn (about -38 for half a turn)
        while a goal earns only ~+0.7, so from a badly oriented start "never turn" is
        optimal. ``reward_form="kick_only"`` applies the same formula only once the
        ball has been kicked (the paper's words: "positive reward when it kicks towards
        the goal and negative when it kicks away"); ``success_bonus`` is added on a goal.
    Termination
        Spawn: robot uniformly in the attacking half (x in [0.5, L/2 - 0.5] m, |y| <=
        W/2 - 0.3 m) with a uniformly random heading, the ball resting on its dribbler.
        Before the kick: failure "ball_lost" (terminated) if the ball leaves the
        dribbler (more than ``lost_distance`` = 0.05 m from the face), failure
        "timeout" (truncated) if no kick within ``max_time_s`` (1.6 s).
        After the kick the robot's actions no longer matter and the episode resolves
        with the ball: success (terminated, ``is_success``) when it has fully crossed
        the goal line inside the goal (or a referee of the surrounding env called a
        goal for the robot's team); failure "missed" (terminated) when it leaves the
        field elsewhere, stops or moves away from the goal line, or after
        ``post_kick_time_s`` (2 s). Time to score = time of the goal.
    """

    def __init__(self, max_time_s: float = 1.6, post_kick_time_s: float = 2.0, lost_distance: float = BALL_LOST_DISTANCE,
                 spawn_x: tuple[float, float] | None = None, reward_form: str = "paper", success_bonus: float = 0.0,
                 kick_action: str = "strength") -> None:
        self.spec_version = aim_to_shoot_spec(kick_action)  # validates kick_action
        if reward_form not in ("paper", "kick_only"):
            raise ValueError(f"reward_form must be 'paper' or 'kick_only', got {reward_form!r}")
        if not math.isfinite(success_bonus):
            raise ValueError(f"success_bonus must be finite, got {success_bonus!r}")
        self.kick_action = kick_action
        self.reward_form, self.success_bonus = reward_form, float(success_bonus)
        self.max_time_s, self.post_kick_time_s, self.lost_distance = max_time_s, post_kick_time_s, lost_distance
        self._spawn_x = spawn_x
        self.observation_space = gymnasium.spaces.Box(-np.inf, np.inf, (10,), np.float32)  # bounded in bind()
        self.action_space = gymnasium.spaces.Box(-1.0, 1.0, (3,), np.float32)
        self.kick_t: float | None = None

    def bind(self, field, robot, ball, dt) -> None:
        super().bind(field, robot, ball, dt)
        self.spawn_x = self._spawn_x or (0.5, field.half_length - 0.5)
        self.observation_space = gymnasium.spaces.Box(*skill_observation_bounds("aim-to-shoot", field, robot),
                                                      (10,), np.float32)

    def sample_start(self, rng: np.random.Generator, options: dict) -> Start:
        f = self.field
        pose = options.get("robot_pose")
        if pose is None:
            x = rng.uniform(*self.spawn_x)
            y = rng.uniform(-f.half_width + 0.3, f.half_width - 0.3)
            pose = (x, y, rng.uniform(-math.pi, math.pi))
        pose = np.asarray(pose, float)
        reach = self.robot_params.front_distance + self.ball_params.radius
        ball = pose[:2] + reach * np.array([math.cos(pose[2]), math.sin(pose[2])])
        return Start(pose, ball)

    def begin(self) -> None:
        self.kick_t = None

    def observe(self, seen: WorldState, robot: int) -> np.ndarray:
        return aim_to_shoot_features(seen, robot, self.field)

    def env_action(self, action: np.ndarray) -> np.ndarray:
        return aim_to_shoot_env_action(action, self.kick_action) if self.kick_t is None else make_action()

    def judge(self, truth: WorldState, robot: int, events: list[dict], t: float) -> Judgement:
        agent = f"{truth.frame}_{robot}"
        if self.kick_t is None and any(ev["type"] == "kick" and ev["agent"] == agent for ev in events):
            self.kick_t = t
        terms = aim_to_shoot_reward(truth, robot, self.field)
        if self.reward_form == "kick_only" and self.kick_t is None:
            terms = {"aim": 0.0}
        terminated, truncated, success, reason = self._outcome(truth, robot, events, t)
        if self.success_bonus:
            terms["success_bonus"] = self.success_bonus if success else 0.0
        return Judgement(terms, terminated, truncated, success, reason, {"kicked": self.kick_t is not None})

    def _outcome(self, truth: WorldState, robot: int, events: list[dict], t: float) -> tuple[bool, bool, bool, str | None]:
        f, br = self.field, self.ball_params.radius
        if self.kick_t is None:
            if dribbler_ball_distance(truth, robot, self.robot_params, self.ball_params) > self.lost_distance:
                return True, False, False, "ball_lost"
            if t >= self.max_time_s - 1e-9:
                return False, True, False, "timeout"
            return False, False, False, None
        goals = [ev["team"] for ev in events if ev["type"] == "goal"]  # a surrounding referee moved the ball
        side = f.in_goal(truth.ball_pos, br)
        if side == 1 or truth.frame in goals:
            return True, False, True, None
        bx, by = truth.ball_pos
        vx = truth.ball_vel[0]
        out = abs(by) >= f.half_width + br or (abs(bx) >= f.half_length + br and side == 0)
        stopped = float(np.hypot(*truth.ball_vel)) < 0.05
        if out or side == -1 or goals or stopped or vx <= 0 or t - self.kick_t >= self.post_kick_time_s:
            return True, False, False, "missed"
        return False, False, False, None


class GoToBallEnv(OneRobotSkillEnv):
    """``ssl_marl/GoToBall-v0``: :class:`GoToBallTask` over a one-robot env (see
    :class:`~ssl_marl.skills.robot_env.OneRobotSkillEnv` for the env options)."""

    def __init__(self, max_time_s: float = 10.0, orientation_form: str = "gaussian", state: str = "default",
                 rolling: float = 0.0, rolling_speed: tuple[float, float] = (0.5, 4.0), **kwargs: Any) -> None:
        task = GoToBallTask(max_time_s, orientation_form, state, rolling, rolling_speed)
        super().__init__(task, **kwargs)
        EzPickle.__init__(self, max_time_s=max_time_s, orientation_form=orientation_form, state=state,
                          rolling=rolling, rolling_speed=rolling_speed, **kwargs)


class AimToShootEnv(OneRobotSkillEnv):
    """``ssl_marl/AimToShoot-v0``: :class:`AimToShootTask` over a one-robot env (see
    :class:`~ssl_marl.skills.robot_env.OneRobotSkillEnv` for the env options)."""

    def __init__(self, max_time_s: float = 1.6, post_kick_time_s: float = 2.0, lost_distance: float = BALL_LOST_DISTANCE,
                 spawn_x: tuple[float, float] | None = None, reward_form: str = "paper", success_bonus: float = 0.0,
                 kick_action: str = "strength", **kwargs: Any) -> None:
        task = AimToShootTask(max_time_s, post_kick_time_s, lost_distance, spawn_x, reward_form, success_bonus,
                              kick_action)  # validates before the world is built
        super().__init__(task, **kwargs)
        EzPickle.__init__(self, max_time_s=max_time_s, post_kick_time_s=post_kick_time_s,
                          lost_distance=lost_distance, spawn_x=spawn_x, reward_form=reward_form,
                          success_bonus=success_bonus, kick_action=kick_action, **kwargs)


def task_action(task: str, action5: np.ndarray) -> np.ndarray:
    """Project a skill's full (5,) action onto skill ``task``'s action space (the
    registry's mapping: go-to-ball keeps (vx, vy, omega); aim-to-shoot keeps
    (omega, dribble, kick))."""
    return get_task(task).to_task_action(action5)


def expand_task_action(task: str, action3: np.ndarray, mapping: str | None = None) -> np.ndarray:
    """Inverse of :func:`task_action` as the wrappers apply it: a task's action as a
    full (5,) env action under action mapping ``mapping`` (aim-to-shoot: the kick
    action, "strength" or "full"; None = the task's default)."""
    return get_task(task).to_env_action(action3, mapping)
