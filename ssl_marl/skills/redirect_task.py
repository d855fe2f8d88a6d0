"""The redirect skill's Gymnasium task (``ssl_marl/Redirect-v0``): :class:`RedirectTask`
on the per-robot wrapper (:class:`~ssl_marl.skills.robot_env.RobotSkillEnv`) over a
full-field env with the redirecting robot ``blue_0`` and a defending goalie
``yellow_0`` (the project's STP goalie, ``ssl_marl.plays.defense:Goalie``, resolved by
name so that ``skills`` does not import ``plays``); no referee, no time limit. Robots
kick on contact (``RobotParams.kick_on_contact``). ``realism=...`` and ``tracker=...``
pass through; features from what the robot sees, outcomes from the ground truth.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any

import gymnasium
import numpy as np
from gymnasium.utils import EzPickle

from ..envs.observation import position_extent, speed_caps
from ..envs.ssl_env import SSLParallelEnv
from ..envs.tracking import with_tracker
from ..physics import ball_model
from ..physics.field import FieldGeometry
from ..physics.params import BallParams, RobotParams
from ..physics.state import WorldState
from .passing_features import check_options, check_point
from .receive_task import ball_out, positive
from .redirect import (REDIRECT_ACTION_FORMS, RedirectBaseline, check_redirect_action_form, expand_redirect_action,
                       redirect_aim_features, redirect_aim_point, redirect_features, redirect_residual_action,
                       redirect_residual_of)
from .registry import resolve_ref
from .robot_env import Judgement, RobotSkillEnv, SkillDriver, SkillTask, Start

REDIRECTOR, KEEPER = "blue_0", "yellow_0"
#: the defending goalie's class ("module:Class", a Skill-protocol tactic)
GOALIE_REF = "ssl_marl.plays.defense:Goalie"


def redirect_observation_bounds(field: FieldGeometry, robot: RobotParams) -> tuple[np.ndarray, np.ndarray]:
    """(low, high) float32 bounds of the 14 redirect values (as the receive's: points
    within the largest distance between two observable positions, speeds within the
    caps x safety factor); wide enough that they never bind in play."""
    x, y = position_extent(field)
    d = math.hypot(2 * x, 2 * y)
    v, w, vb = speed_caps(robot)
    high = [d, d, vb, vb, v, v, w, d, d, d, d, d, d, vb + v]
    low = [-d, -d, -vb, -vb, -v, -v, -w, -d, -d, -d, -d, -d, -d, -(vb + v)]
    return np.array(low, dtype=np.float32), np.array(high, dtype=np.float32)


def redirect_aim_observation_bounds(field: FieldGeometry, robot: RobotParams) -> tuple[np.ndarray, np.ndarray]:
    """(low, high) float32 bounds of the 21 ``redirect/v3`` values: the 14 of
    :func:`redirect_observation_bounds`, positions within the observable extent, the
    keeper's velocity within the robot speed cap, the aim's y within the goal mouth."""
    low, high = redirect_observation_bounds(field, robot)
    x, y = position_extent(field)
    v = speed_caps(robot)[0]
    g = field.goal_width / 2.0
    extra_high = np.array([x, y, x, y, v, v, g], dtype=np.float32)
    return np.concatenate([low, -extra_high]), np.concatenate([high, extra_high])


class RedirectTask(SkillTask):
    """redirect: meet a moving ball and kick it on into the opponent goal (+x, team
    frame) past the defending goalie, without stopping it.

    Observation
        ``Box(-inf, inf, (14,), float32)`` (bounded in ``bind``), spec ``redirect/v1``:
        :func:`ssl_marl.skills.redirect.redirect_features`; ``action_form="aim"``: 21
        values, :func:`ssl_marl.skills.redirect.redirect_aim_features`.
    Action
        ``Box(-1, 1, (3,), float32)``, kicker always armed at full strength, dribbler
        off; ``action_form``: ``"direct"`` (spec ``redirect/v1``, default): (vx, vy,
        omega), robot frame, fractions of the robot's limits; ``"residual"`` (spec
        ``redirect/v2``): a correction added to :class:`RedirectBaseline`'s action in the
        state the robot sees (0 = the hand-coded redirect); ``"aim"`` (spec
        ``redirect/v3``): ``Box(-1, 1, (1,))``, the aim point's y along the goal mouth
        (:func:`ssl_marl.skills.redirect.redirect_aim_point`), executed by
        :class:`RedirectBaseline`'s contact planner (which stops once it has kicked).
    Reward
        Sparse: +1 on success, -1 on failure, else 0 (``info["reward_terms"]``).
    Spawn
        The robot at rest, x ~ U(L/2 - 2.5, L/2 - D - 0.2) m (D the defense area's
        depth: outside the opponent's area), |y| <= 1.5 m, facing the
        ball's start +- U(0.5) rad. The deflection (angle between the robot -> ball-start
        and robot -> goal-centre directions) ~ U(0, ``max_deflection``) (1.2 rad) with a
        random side; the ball ``U(2, 6)`` m from the robot along it (inside the field,
        0.2 m margin), kicked (sliding first) at ``U(2, 5)`` m/s towards a point
        ``U(-0.3, 0.3)`` m to the side of the robot's centre; a ball that would stop
        before reaching the robot is redrawn. The goalie (``yellow_0``) at rest on its
        goal line's centre, 0.2 m in front, facing the field; driven by
        ``goalie`` (default the project's STP goalie; None: it stands still).
    Termination
        Success (terminated, ``is_success``): the ball wholly crosses the goal line
        between the posts (or a surrounding referee calls a goal for the robot's team)
        after the robot has kicked it. Failure (terminated): "no_touch" when the ball
        reaches the goal or leaves the field untouched by the robot, "missed" when the
        kicked ball leaves the field elsewhere, moves away from the goal line or stops,
        "saved" when the goalie touches the kicked ball; (truncated) "timeout" at
        ``max_time_s`` (5 s).
    Reset options
        ``robot_pose`` (x, y, heading), ``ball_pos`` (x, y), ``ball_vel`` (vx, vy),
        ``keeper_pose`` (x, y, heading): override the spawn.
    """

    REWARD_FORMS = ("outcome",)

    def __init__(self, max_time_s: float = 5.0, speed_range: tuple[float, float] = (2.0, 5.0),
                 distance_range: tuple[float, float] = (2.0, 6.0), max_deflection: float = 1.2,
                 max_side_offset: float = 0.3, heading_noise: float = 0.5, action_form: str = "direct") -> None:
        self.action_form = check_redirect_action_form(action_form)
        self.spec_version = REDIRECT_ACTION_FORMS[self.action_form]
        self.max_time_s = positive("max_time_s", max_time_s)
        self.speed_range = tuple(float(v) for v in speed_range)
        self.distance_range = tuple(float(v) for v in distance_range)
        if not 0 < self.distance_range[0] <= self.distance_range[1]:
            raise ValueError(f"distance_range must satisfy 0 < lo <= hi (m), got {distance_range!r}")
        if not (math.isfinite(max_deflection) and 0 <= max_deflection <= math.pi):
            raise ValueError(f"max_deflection must lie in [0, pi] rad, got {max_deflection!r}")
        self.max_deflection = float(max_deflection)
        self.max_side_offset, self.heading_noise = float(max_side_offset), float(heading_noise)
        aim = self.action_form == "aim"
        self.observation_space = gymnasium.spaces.Box(-np.inf, np.inf, (21 if aim else 14,), np.float32)
        self.action_space = gymnasium.spaces.Box(-1.0, 1.0, (1 if aim else 3,), np.float32)
        self._seen: WorldState | None = None
        self.kick_t: float | None = None

    def bind(self, field: FieldGeometry, robot: RobotParams, ball: BallParams, dt: float) -> None:
        super().bind(field, robot, ball, dt)
        if not 0 < self.speed_range[0] <= self.speed_range[1] <= robot.kick_speed_max:
            raise ValueError(f"speed_range must satisfy 0 < lo <= hi <= {robot.kick_speed_max} m/s, "
                             f"got {self.speed_range!r}")
        bounds = redirect_aim_observation_bounds if self.action_form == "aim" else redirect_observation_bounds
        self.observation_space = gymnasium.spaces.Box(*bounds(field, robot), self.observation_space.shape, np.float32)
        self._base = RedirectBaseline(field, robot, ball)
        self._planner = RedirectBaseline(field, robot, ball)  # executes the aim form's aim points
        # in front of the goal, outside the opponent defense area (0.2 m margin)
        self.spawn_x = (field.half_length - 2.5, field.half_length - field.defense_depth - 0.2)
        self.spawn_half_y = 1.5

    def _sample_spawn(self, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        f, bp = self.field, self.ball_params
        goal = np.array([f.half_length, 0.0])
        for _ in range(10_000):
            robot = np.array([rng.uniform(*self.spawn_x), rng.uniform(-self.spawn_half_y, self.spawn_half_y)])
            to_goal = math.atan2(goal[1] - robot[1], goal[0] - robot[0])
            ang = to_goal + rng.choice([-1.0, 1.0]) * rng.uniform(0.0, self.max_deflection)
            dist = rng.uniform(*self.distance_range)
            ball = robot + dist * np.array([math.cos(ang), math.sin(ang)])
            if not bool(f.in_field(ball, 0.2)):
                continue
            to_robot = (robot - ball) / dist
            aim = robot + rng.uniform(-self.max_side_offset, self.max_side_offset) * np.array([-to_robot[1],
                                                                                              to_robot[0]])
            d_aim = aim - ball
            speed = rng.uniform(*self.speed_range)
            if ball_model.stop_distance(speed, bp) < float(np.hypot(*d_aim)) + 0.3:
                continue
            heading = ang + rng.uniform(-self.heading_noise, self.heading_noise)
            return np.array([robot[0], robot[1], heading]), ball, speed * d_aim / float(np.hypot(*d_aim))
        raise RuntimeError("RedirectEnv: no spawn in 10,000 draws; check the spawn ranges")

    def sample_start(self, rng: np.random.Generator, options: dict) -> Start:
        check_options("RedirectEnv.reset", options, {"robot_pose", "ball_pos", "ball_vel", "keeper_pose"})
        pose, ball, vel = self._sample_spawn(rng)
        if "ball_vel" in options:
            vel = check_point("ball_vel", options["ball_vel"])
        if "ball_pos" in options:
            ball = check_point("ball_pos", options["ball_pos"])
        if "robot_pose" in options:
            pose = np.asarray(options["robot_pose"], float).reshape(3)
        keeper = np.asarray(options.get("keeper_pose", (self.field.half_length - 0.2, 0.0, math.pi)),
                            float).reshape(3)
        for name, p in (("ball_pos", ball), ("robot_pose", pose[:2]), ("keeper_pose", keeper[:2])):
            if not bool(self.field.in_field(p)):
                raise ValueError(f"RedirectEnv.reset: {name} {np.asarray(p).tolist()} lies outside the field")
        return Start(pose, ball, vel, others={KEEPER: keeper})

    def begin(self) -> None:
        self.kick_t = None
        self._planner.reset()

    def begin_step(self, seen: WorldState, robot: int) -> None:
        self._seen = seen

    def base_action(self, seen: WorldState, robot: int = 0) -> np.ndarray:
        """The hand-coded redirect's (vx, vy, omega) in the state ``seen``."""
        return self._base.task_action(seen, robot)

    def observe(self, seen: WorldState, robot: int) -> np.ndarray:
        if self.action_form == "aim":
            return redirect_aim_features(seen, robot, self.field, self.robot_params, self.ball_params)
        return redirect_features(seen, robot, self.field, self.robot_params, self.ball_params)

    def env_action(self, action: np.ndarray) -> np.ndarray:
        if self.action_form == "aim":
            self._planner.aim = redirect_aim_point(action, self.field)
            return self._planner.act(self._seen, 0)
        a = np.clip(action, -1.0, 1.0)
        if self.action_form == "residual":
            a = redirect_residual_action(self.base_action(self._seen), a)
        return expand_redirect_action(a)

    def judge(self, truth: WorldState, robot: int, events: list[dict], t: float) -> Judgement:
        outcome = self._outcome(truth, robot, events, t)
        success = outcome == "success"
        timeout = outcome == "timeout"
        reward = 0.0 if outcome is None else (1.0 if success else -1.0)
        return Judgement({"outcome": reward}, terminated=outcome is not None and not timeout, truncated=timeout,
                         success=success, failure_reason=None if success else outcome,
                         info={"kicked": self.kick_t is not None})

    def _outcome(self, truth: WorldState, robot: int, events: list[dict], t: float) -> str | None:
        f, br = self.field, self.ball_params.radius
        me = f"{truth.frame}_{robot}"
        for ev in events:
            if ev["type"] == "kick" and self.kick_t is None and ev.get("agent") == me:
                self.kick_t = t
            elif ev["type"] == "kick" and self.kick_t is not None and ev.get("agent") != me:
                return "saved"
        goals = [ev["team"] for ev in events if ev["type"] == "goal"]
        side = f.in_goal(truth.ball_pos, br)
        if self.kick_t is None:
            if side != 0 or goals or ball_out(truth, f, self.ball_params):
                return "no_touch"
        else:
            if side == 1 or truth.frame in goals:
                return "success"
            opp = truth.opponents(truth.frame)
            if len(opp.pos) and bool(opp.ball_on_dribbler.any()):
                return "saved"
            if side == -1 or goals or ball_out(truth, f, self.ball_params) or truth.ball_vel[0] <= 0 \
                    or float(np.hypot(*truth.ball_vel)) < 0.05:
                return "missed"
        if t >= self.max_time_s - 1e-9:
            return "timeout"
        return None


class RedirectEnv(RobotSkillEnv, EzPickle):
    """``ssl_marl/Redirect-v0``: :class:`RedirectTask` for ``blue_0`` against the goalie
    ``yellow_0`` (``goalie``: "module:Class" of its controller, None = standing still).
    ``field``, ``realism``, ``realtime``, ``render_mode``, ``tracker`` and further env
    options pass through; ``robot`` (a :class:`RobotParams`, default the standard one)
    always gets ``kick_on_contact=True``."""

    def __init__(self, max_time_s: float = 5.0, speed_range: tuple[float, float] = (2.0, 5.0),
                 distance_range: tuple[float, float] = (2.0, 6.0), max_deflection: float = 1.2,
                 max_side_offset: float = 0.3, heading_noise: float = 0.5, action_form: str = "direct",
                 goalie: str | None = GOALIE_REF, field: str = "div_b", realism: Any = "none", realtime: bool = False,
                 render_mode: str | None = None, tracker: Any = False, robot: RobotParams | None = None,
                 **env_kwargs: Any) -> None:
        task = RedirectTask(max_time_s, speed_range, distance_range, max_deflection, max_side_offset, heading_noise,
                            action_form)
        rp = replace(robot or RobotParams(), kick_on_contact=True)
        env = SSLParallelEnv(n_blue=1, n_yellow=1, field=field, realism=realism, realtime=realtime, referee=False,
                             max_time_s=1e9, render_mode=render_mode, obs_max_teammates=0, obs_max_opponents=0,
                             robot=rp, **env_kwargs)
        env = with_tracker(env, tracker)
        drivers = [] if goalie is None else [SkillDriver([KEEPER], resolve_ref(goalie), env.field, env.config.robot,
                                                         env.config.ball)]
        super().__init__(env, REDIRECTOR, task, drivers)
        EzPickle.__init__(self, max_time_s=max_time_s, speed_range=speed_range, distance_range=distance_range,
                          max_deflection=max_deflection, max_side_offset=max_side_offset, heading_noise=heading_noise,
                          action_form=action_form, goalie=goalie, field=field, realism=realism, realtime=realtime,
                          render_mode=render_mode, tracker=tracker, robot=robot, **env_kwargs)

    def base_action(self) -> np.ndarray:
        """The hand-coded redirect's (vx, vy, omega) in the state the robot sees now."""
        return self.task.base_action(self.seen(), self.robot)

    def from_direct(self, action3: np.ndarray) -> np.ndarray:
        """This env's action for a direct (vx, vy, omega) action: itself, or the residual
        correction from the hand-coded redirect's action; ValueError for the ``aim`` form
        (an aim point is not a function of a motion: :func:`redirect_skill_action` takes
        it from the skill)."""
        if self.task.action_form == "aim":
            raise ValueError("an aim action is not a function of a (vx, vy, omega) action; "
                             "use redirect_skill_action with a skill that has aim_action()")
        if self.task.action_form == "direct":
            return np.asarray(action3, dtype=np.float32)
        return redirect_residual_of(self.base_action(), action3)


def redirect_skill_action(env: RedirectEnv, skill: Any) -> np.ndarray:
    """One step of a redirect skill (hand-coded or learned) in its task env: its (5,)
    action's (vx, vy, omega), as a correction when the env takes residual actions; with
    ``action_form="aim"`` the aim point the skill planned this step (its ``aim_action()``)."""
    if env.task.action_form == "aim":
        skill.act(env.seen(), 0)
        return np.asarray(skill.aim_action(), dtype=np.float32)
    return env.from_direct(np.asarray(skill.act(env.seen(), 0), dtype=np.float32)[:3])


def redirect_baseline_demos(n_steps: int, seed: int = 0, **env_kwargs: Any):
    """``n_steps`` redirect transitions (obs (14,), action (3,)) from
    :class:`RedirectBaseline` on the task's own spawns; successful episodes only (with
    ``action_form="residual"`` the actions are zero corrections; with ``"aim"`` obs (21,)
    and the hand-coded aim points as actions (1,))."""
    from .demos import skill_demos

    env = RedirectEnv(**env_kwargs)
    skill = RedirectBaseline(env.field, env.robot_params, env.ball_params)
    return skill_demos(env, skill, redirect_skill_action, n_steps, seed)


def redirect_baseline_all_demos(n_steps: int, seed: int = 0, **env_kwargs: Any):
    """As :func:`redirect_baseline_demos`, but every episode, failures too: the critic
    sees what the hand-coded choices lead to (with ``action_form="aim"``: where the
    hand-coded aim point lets the goalie save)."""
    from .demos import skill_demos

    env = RedirectEnv(**env_kwargs)
    skill = RedirectBaseline(env.field, env.robot_params, env.ball_params)
    return skill_demos(env, skill, redirect_skill_action, n_steps, seed, successful_only=False)


__all__ = ["GOALIE_REF", "KEEPER", "REDIRECTOR", "RedirectEnv", "RedirectTask", "redirect_aim_observation_bounds",
           "redirect_baseline_all_demos", "redirect_baseline_demos", "redirect_observation_bounds",
           "redirect_skill_action"]
