"""Single-robot Gymnasium tasks for the paper's skills, over the full-field env.

Both wrap :class:`ssl_marl.envs.ssl_env.SSLParallelEnv` with one controlled robot
(``blue_0``, whose team frame is the field frame) and, by default, no other robot.
Other robots can be added as yellow opponents, ``static`` or driven by the
baseline go-to-ball skill (``chase``). The full-field referee is off: the task
judges its own episodes. Noise / latency options of the simulator pass through
(``realism=...``): features are computed from what the robot *sees*
(``env.vision_state``), rewards and outcomes from the ground truth.
"""

from __future__ import annotations

import math
from typing import Any

import gymnasium
import numpy as np
from gymnasium.utils import EzPickle

from ..envs.observation import clip_to_bounds, position_extent, speed_caps
from ..envs.ssl_env import SSLParallelEnv
from ..physics.field import FieldGeometry
from ..physics.params import RobotParams
from ..physics.state import WorldState, to_team_frame
from .base import make_action
from .features import (AIM_TO_SHOOT_SPEC, BALL_LOST_DISTANCE, GO_TO_BALL_SPEC, ORIENTATION_FORMS,
                       aim_to_shoot_features, aim_to_shoot_reward, aim_to_shoot_spec, dribbler_ball_distance,
                       go_to_ball_features, go_to_ball_reward)

AGENT = "blue_0"


def skill_observation_bounds(skill: str, field: FieldGeometry, robot: RobotParams) -> tuple[np.ndarray, np.ndarray]:
    """(low, high) float32 bounds of a skill task's observation (``"go-to-ball"`` or
    ``"aim-to-shoot"``), from the same rules as the full-field env
    (:mod:`ssl_marl.envs.observation`): any robot-frame point lies within D, the
    largest distance between two observable positions; velocities within the speed
    caps x safety factor; distances in [0, D]; sin/cos in [-1, 1]."""
    x, y = position_extent(field)
    d = math.hypot(2 * x, 2 * y)
    v, w, vb = speed_caps(robot)
    if skill == "go-to-ball":  # ball xy, robot v, omega, dist, 4 closest line points
        high = [d, d, v, v, w, d] + [d] * 8
        low = [-d, -d, -v, -v, -w, 0.0] + [-d] * 8
    elif skill == "aim-to-shoot":  # ball xy, ball v, omega, dist to goal, sin/cos of the post angles
        high = [d, d, vb, vb, w, d, 1, 1, 1, 1]
        low = [-d, -d, -vb, -vb, -w, 0.0, -1, -1, -1, -1]
    else:
        raise ValueError(f"unknown skill task {skill!r}; expected 'go-to-ball' or 'aim-to-shoot'")
    return np.array(low, dtype=np.float32), np.array(high, dtype=np.float32)


class _SkillEnv(gymnasium.Env, EzPickle):
    """Shared plumbing: the inner parallel env, other robots, info bookkeeping."""

    metadata = {"render_modes": ["rgb_array", "human"], "render_fps": 60}
    spec_version = ""

    def __init__(self, field: str = "div_b", n_opponents: int = 0, opponent_policy: str = "static",
                 realism: Any = "none", realtime: bool = False, render_mode: str | None = None,
                 **env_kwargs: Any) -> None:
        EzPickle.__init__(self, field=field, n_opponents=n_opponents, opponent_policy=opponent_policy,
                          realism=realism, realtime=realtime, render_mode=render_mode, **env_kwargs)
        if opponent_policy not in ("static", "chase"):
            raise ValueError(f"opponent_policy must be 'static' or 'chase', got {opponent_policy!r}")
        self.render_mode = render_mode
        self.env = SSLParallelEnv(n_blue=1, n_yellow=n_opponents, field=field, realism=realism, realtime=realtime,
                                  referee=False, max_time_s=1e9, render_mode=render_mode,
                                  obs_max_teammates=0, obs_max_opponents=max(n_opponents, 0), **env_kwargs)
        self.field: FieldGeometry = self.env.field
        self.robot_params = self.env.config.robot
        self.ball_params = self.env.config.ball
        self.dt = self.env.config.dt
        self.n_opponents = n_opponents
        self.opponent_policy = opponent_policy
        self._opponent_skills: list = []

    # --- helpers --------------------------------------------------------------
    def _bounded(self, obs: np.ndarray) -> np.ndarray:
        """``obs`` clipped into ``observation_space`` (bounds wide enough that it never binds in play)."""
        return clip_to_bounds(obs, self.observation_space.low, self.observation_space.high)

    @property
    def t(self) -> float:
        """Simulated time since the episode started (s), from the world itself (in real-time
        mode one step can cover several control ticks)."""
        return self.env.world_state().t

    def seen(self) -> WorldState:
        """What the controlled robot sees, in its team frame."""
        return self.env.vision_state("blue")

    def truth(self) -> WorldState:
        return to_team_frame(self.env.world_state(), "blue")

    def _opponent_actions(self) -> dict[str, np.ndarray]:
        if self.n_opponents == 0 or self.opponent_policy == "static":
            return {}
        ws = self.env.vision_state("yellow")
        return {f"yellow_{k}": sk.act(ws, k) for k, sk in enumerate(self._opponent_skills)}

    def _reset_inner(self, seed: int | None, robot_pose: np.ndarray, ball_pos: np.ndarray,
                     ball_vel: np.ndarray | None = None) -> None:
        robots = {AGENT: tuple(robot_pose)}
        taken = [np.asarray(robot_pose[:2]), np.asarray(ball_pos)]
        for k in range(self.n_opponents):
            p = self._free_spot(taken, 0.3)
            taken.append(p)
            robots[f"yellow_{k}"] = (p[0], p[1], self.np_random.uniform(-math.pi, math.pi))
        opts = {"robots": robots, "ball": {"pos": tuple(ball_pos),
                                           "vel": tuple(np.zeros(2) if ball_vel is None else ball_vel)}}
        self.env.reset(seed=None if seed is None else int(self.np_random.integers(2 ** 31)), options=opts)
        if self.n_opponents and self.opponent_policy == "chase":
            from .baseline import GoToBallBaseline

            self._opponent_skills = [GoToBallBaseline(self.field, self.robot_params, self.ball_params)
                                     for _ in range(self.n_opponents)]

    def _free_spot(self, taken: list[np.ndarray], min_dist: float, margin: float = 0.2) -> np.ndarray:
        return self.field.random_free_point(self.np_random, margin, taken, min_dist)

    def _step_inner(self, action5: np.ndarray) -> dict:
        acts = {AGENT: action5}
        acts.update(self._opponent_actions())
        _, _, _, _, infos = self.env.step(acts)
        return infos[AGENT]

    @staticmethod
    def _check_action(action: Any, dim: int) -> np.ndarray:
        a = np.asarray(action, dtype=np.float64)
        if a.shape != (dim,):
            raise ValueError(f"action must have shape ({dim},), got {a.shape}")
        if not np.isfinite(a).all():
            raise ValueError(f"action contains NaN or inf: {a.tolist()}")
        return np.clip(a, -1.0, 1.0)

    def render(self):
        return self.env.render()

    def close(self) -> None:
        self.env.close()


class GoToBallEnv(_SkillEnv):
    """go-to-ball: drive to the ball and get it on the dribbler (paper, section 4.3).

    Observation
        ``Box(low, high, (14,), float32)`` (finite: :func:`skill_observation_bounds`): the paper's state, see
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
        (10 s). Spawn: ball uniformly on the field (0.1 m inside the lines), robot at a
        uniformly random position and heading at least 0.3 m from the ball.
    """

    spec_version = GO_TO_BALL_SPEC

    def __init__(self, max_time_s: float = 10.0, orientation_form: str = "gaussian", **kwargs: Any) -> None:
        super().__init__(**kwargs)
        EzPickle.__init__(self, max_time_s=max_time_s, orientation_form=orientation_form, **kwargs)
        if orientation_form not in ORIENTATION_FORMS:
            raise ValueError(f"orientation_form must be one of {ORIENTATION_FORMS}, got {orientation_form!r}")
        if not (math.isfinite(max_time_s) and max_time_s > 0):
            raise ValueError(f"max_time_s must be positive, got {max_time_s!r}")
        self.max_time_s = max_time_s
        self.orientation_form = orientation_form
        self.observation_space = gymnasium.spaces.Box(*skill_observation_bounds("go-to-ball", self.field,
                                                                                 self.robot_params), (14,), np.float32)
        self.action_space = gymnasium.spaces.Box(-1.0, 1.0, (3,), np.float32)

    def reset(self, *, seed: int | None = None, options: dict | None = None):
        super().reset(seed=seed)
        options = options or {}
        f = self.field
        ball = options.get("ball_pos")
        if ball is None:
            ball = f.random_free_point(self.np_random, margin=0.1)
        pose = options.get("robot_pose")
        if pose is None:
            xy = self._free_spot([np.asarray(ball)], 0.3, margin=0.1)
            heading = self.np_random.uniform(-math.pi, math.pi)
            if options.get("face_ball"):
                heading = math.atan2(ball[1] - xy[1], ball[0] - xy[0])
            pose = (xy[0], xy[1], heading)
        self._reset_inner(seed, np.asarray(pose, float), np.asarray(ball, float))
        return self._bounded(go_to_ball_features(self.seen(), 0, f)), {"reward_terms": {}}

    def step(self, action):
        self._step_inner(expand_task_action("go-to-ball", self._check_action(action, 3)))
        truth = self.truth()
        terms = go_to_ball_reward(truth, 0, self.orientation_form)
        success = bool(truth.blue.ball_on_dribbler[0])
        timeout = (not success) and self.t >= self.max_time_s - 1e-9
        info: dict[str, Any] = {"reward_terms": terms, "t": self.t}
        if success or timeout:
            info["is_success"] = success
            info["failure_reason"] = None if success else "timeout"
            info["time_s"] = self.t
        obs = self._bounded(go_to_ball_features(self.seen(), 0, self.field))
        return obs, float(sum(terms.values())), success, timeout, info


class AimToShootEnv(_SkillEnv):
    """aim-to-shoot: with the ball on the dribbler, turn towards the goal and score
    (paper, section 4.3).

    Observation
        ``Box(low, high, (10,), float32)`` (finite: :func:`skill_observation_bounds`): the paper's state, see
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
        the goal line inside the goal; failure "missed" (terminated) when it leaves
        the field elsewhere, stops or moves away from the goal line, or after
        ``post_kick_time_s`` (2 s). Time to score = time of the goal.
    """

    spec_version = AIM_TO_SHOOT_SPEC

    def __init__(self, max_time_s: float = 1.6, post_kick_time_s: float = 2.0, lost_distance: float = BALL_LOST_DISTANCE,
                 spawn_x: tuple[float, float] | None = None, reward_form: str = "paper", success_bonus: float = 0.0,
                 kick_action: str = "strength", **kwargs: Any) -> None:
        spec = aim_to_shoot_spec(kick_action)  # validates kick_action before the world is built
        super().__init__(**kwargs)
        EzPickle.__init__(self, max_time_s=max_time_s, post_kick_time_s=post_kick_time_s,
                          lost_distance=lost_distance, spawn_x=spawn_x, reward_form=reward_form,
                          success_bonus=success_bonus, kick_action=kick_action, **kwargs)
        if reward_form not in ("paper", "kick_only"):
            raise ValueError(f"reward_form must be 'paper' or 'kick_only', got {reward_form!r}")
        self.kick_action, self.spec_version = kick_action, spec
        if not math.isfinite(success_bonus):
            raise ValueError(f"success_bonus must be finite, got {success_bonus!r}")
        self.reward_form, self.success_bonus = reward_form, float(success_bonus)
        self.max_time_s, self.post_kick_time_s, self.lost_distance = max_time_s, post_kick_time_s, lost_distance
        f = self.field
        self.spawn_x = spawn_x or (0.5, f.half_length - 0.5)
        self.observation_space = gymnasium.spaces.Box(*skill_observation_bounds("aim-to-shoot", self.field,
                                                                                 self.robot_params), (10,), np.float32)
        self.action_space = gymnasium.spaces.Box(-1.0, 1.0, (3,), np.float32)
        self._kick_t: float | None = None

    def reset(self, *, seed: int | None = None, options: dict | None = None):
        super().reset(seed=seed)
        options = options or {}
        f = self.field
        pose = options.get("robot_pose")
        if pose is None:
            x = self.np_random.uniform(*self.spawn_x)
            y = self.np_random.uniform(-f.half_width + 0.3, f.half_width - 0.3)
            pose = (x, y, self.np_random.uniform(-math.pi, math.pi))
        pose = np.asarray(pose, float)
        reach = self.robot_params.front_distance + self.ball_params.radius
        ball = pose[:2] + reach * np.array([math.cos(pose[2]), math.sin(pose[2])])
        self._reset_inner(seed, pose, ball)
        self._kick_t = None
        return self._bounded(aim_to_shoot_features(self.seen(), 0, f)), {"reward_terms": {}}

    def step(self, action):
        a = self._check_action(action, 3)
        action5 = expand_task_action("aim-to-shoot", a, self.kick_action) if self._kick_t is None else make_action()
        info = self._step_inner(action5)
        truth = self.truth()
        if self._kick_t is None and any(ev["type"] == "kick" and ev["agent"] == AGENT for ev in info["events"]):
            self._kick_t = self.t
        terms = aim_to_shoot_reward(truth, 0, self.field)
        if self.reward_form == "kick_only" and self._kick_t is None:
            terms = {"aim": 0.0}
        terminated, truncated, success, reason = self._outcome(truth)
        if self.success_bonus:
            terms["success_bonus"] = self.success_bonus if success else 0.0
        out: dict[str, Any] = {"reward_terms": terms, "t": self.t, "kicked": self._kick_t is not None}
        if terminated or truncated:
            out.update(is_success=success, failure_reason=reason, time_s=self.t)
        obs = self._bounded(aim_to_shoot_features(self.seen(), 0, self.field))
        return obs, float(sum(terms.values())), terminated, truncated, out

    def _outcome(self, truth: WorldState) -> tuple[bool, bool, bool, str | None]:
        f, br = self.field, self.ball_params.radius
        if self._kick_t is None:
            if dribbler_ball_distance(truth, 0, self.robot_params, self.ball_params) > self.lost_distance:
                return True, False, False, "ball_lost"
            if self.t >= self.max_time_s - 1e-9:
                return False, True, False, "timeout"
            return False, False, False, None
        side = f.in_goal(truth.ball_pos, br)
        if side == 1:
            return True, False, True, None
        bx, by = truth.ball_pos
        vx = truth.ball_vel[0]
        out = abs(by) >= f.half_width + br or (abs(bx) >= f.half_length + br and side == 0)
        stopped = float(np.hypot(*truth.ball_vel)) < 0.05
        if out or side == -1 or stopped or vx <= 0 or self.t - self._kick_t >= self.post_kick_time_s:
            return True, False, False, "missed"
        return False, False, False, None


def task_action(task: str, action5: np.ndarray) -> np.ndarray:
    """Project a skill's full (5,) action onto a task's (3,) action space:
    go-to-ball keeps (vx, vy, omega); aim-to-shoot keeps (omega, dribble, kick)."""
    a = np.asarray(action5, dtype=np.float32)
    if task == "go-to-ball":
        return a[[0, 1, 2]]
    if task == "aim-to-shoot":
        return a[[2, 3, 4]]
    raise ValueError(f"unknown skill task {task!r}; expected 'go-to-ball' or 'aim-to-shoot'")


def expand_task_action(task: str, action3: np.ndarray, kick_action: str = "strength") -> np.ndarray:
    """Inverse of :func:`task_action` as the wrappers apply it: a task's (3,) action
    as a full (5,) env action (go-to-ball: dribbler on; aim-to-shoot: no translation).
    aim-to-shoot's kick: no kick when a_k <= 0; otherwise strength a_k (``kick_action``
    "strength", the paper's) or full strength ("full")."""
    a = np.clip(np.asarray(action3, dtype=np.float64), -1.0, 1.0)
    if task == "go-to-ball":
        return make_action(a[0], a[1], a[2], dribble=True)
    if task == "aim-to-shoot":
        aim_to_shoot_spec(kick_action)  # validates
        kick = float(a[2]) if kick_action == "strength" or a[2] <= 0 else 1.0
        return make_action(0.0, 0.0, a[0], dribble=a[1] > 0, kick=kick)
    raise ValueError(f"unknown skill task {task!r}; expected 'go-to-ball' or 'aim-to-shoot'")
