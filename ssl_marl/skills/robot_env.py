"""One robot of any full-field env as a single-agent Gymnasium skill task.

:class:`RobotSkillEnv` wraps any :class:`~ssl_marl.envs.ssl_env.SSLParallelEnv`
(any team sizes, either division, any engine task) and turns one of its robots
(``agent``, e.g. ``"yellow_3"``) into the robot of a :class:`SkillTask`. Everything
the task sees and decides is in that robot's *team frame* (own goal at -x), so the
task is the same for a blue and a yellow robot: features from what its team sees
(``env.vision_state(team)``), rewards and outcomes from the ground truth. The other
robots are driven by the *drivers* handed to the wrapper: objects with ``reset()``
and ``act(env) -> {agent: (5,) action}`` (:class:`StaticDriver`,
:class:`SkillDriver` for scripted or learned skills, or an STP
:class:`~ssl_marl.plays.team.TeamController`); actions they give the controlled
robot are ignored, robots nobody drives stand still.

``ssl_marl/GoToBall-v0`` and ``ssl_marl/AimToShoot-v0`` are this wrapper over a
one-robot env (:mod:`ssl_marl.skills.wrappers`); ``ssl_marl/Pass-v0`` and
``ssl_marl/Receive-v0`` over the passing tasks' env, the pass's receiver a driver
(:mod:`ssl_marl.skills.pass_tasks`, :mod:`ssl_marl.skills.receive_task`). The vision
tracker comes with the env (``tracker=``, :func:`~ssl_marl.envs.tracking.with_tracker`).

A :class:`SkillTask` says where an episode starts (robot pose and ball, team frame),
what the robot observes, how the task's action becomes an env action, and judges
every step (reward terms, success, failure). Its time limit is in *simulated* time
(a real-time step can span several control ticks, so a step-count limit such as
Gymnasium's ``TimeLimit`` would be wrong there); ``gym.make(..., max_episode_steps=N)``
still adds Gymnasium's ``TimeLimit`` on top when asked.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Callable, Iterable, Protocol, Sequence

import gymnasium
import numpy as np
from gymnasium.utils import EzPickle

from ..envs.observation import clip_to_bounds
from ..envs.ssl_env import SSLParallelEnv
from ..envs.tracking import with_tracker
from ..physics.field import FieldGeometry
from ..physics.params import BallParams, RobotParams
from ..physics.state import WorldState, to_team_frame, wrap_angle


# ----------------------------------------------------------------- frames
def team_to_field_pose(pose: np.ndarray, team: str) -> np.ndarray:
    """A (3,) pose (x, y, heading) in ``team``'s frame -> the field frame."""
    p = np.asarray(pose, dtype=float)
    if team == "blue":
        return p.copy()
    return np.array([-p[0], -p[1], float(wrap_angle(p[2] + math.pi))])


def team_to_field_vec(v: np.ndarray, team: str) -> np.ndarray:
    """A (2,) point or velocity in ``team``'s frame -> the field frame."""
    v = np.asarray(v, dtype=float)
    return v.copy() if team == "blue" else -v


# ---------------------------------------------------------------- drivers
class RobotDriver(Protocol):
    """Drives some robots of an env (the controlled robot's traffic)."""

    def reset(self) -> None:
        """A new episode starts (the env has been reset)."""

    def act(self, env: SSLParallelEnv) -> dict[str, np.ndarray]:
        """Actions for the robots it drives, from what their team sees."""


class StaticDriver:
    """Robots stand still (no actions)."""

    def reset(self) -> None:
        pass

    def act(self, env: SSLParallelEnv) -> dict[str, np.ndarray]:
        return {}


class SkillDriver:
    """Each of ``agents`` runs its own skill built by ``make(field, robot, ball)`` (a
    hand-coded or learned :class:`~ssl_marl.skills.base.Skill`), rebuilt every episode,
    e.g. ``SkillDriver(["yellow_0"], GoToBallBaseline)`` chases the ball."""

    def __init__(self, agents: Sequence[str], make: Callable[..., Any], field: FieldGeometry,
                 robot: RobotParams | None = None, ball: BallParams | None = None) -> None:
        self.agents = list(agents)
        self.make, self.field, self.robot, self.ball = make, field, robot, ball
        self.skills: dict[str, Any] = {}

    def reset(self) -> None:
        self.skills = {a: self.make(self.field, self.robot, self.ball) for a in self.agents}

    def act(self, env: SSLParallelEnv) -> dict[str, np.ndarray]:
        out, seen = {}, {}
        for agent, skill in self.skills.items():
            team, idx = agent.rsplit("_", 1)
            if team not in seen:
                seen[team] = env.vision_state(team)
            out[agent] = skill.act(seen[team], int(idx))
        return out


# ------------------------------------------------------------------- task
@dataclass(frozen=True)
class Start:
    """An episode's start in the controlled robot's team frame: pose (x, y m, heading
    rad), ball position (m) and velocity (m/s), and the poses of other robots the task
    places itself (agent name -> (x, y, heading), team frame; the wrapper places the
    rest)."""

    robot_pose: np.ndarray
    ball_pos: np.ndarray
    ball_vel: np.ndarray = field(default_factory=lambda: np.zeros(2))
    others: dict[str, np.ndarray] = field(default_factory=dict)


@dataclass
class Judgement:
    """One step's verdict: named reward terms, episode end and outcome, extra info.

    ``run_on``: the step is not over yet: the wrapper advances the env once more (the
    drivers' actions and the task's ``env_action`` of the same task action) and judges
    again, until a judgement without ``run_on`` or an episode end; the step returns the
    last judgement (e.g. a pass resolved within its kick step)."""

    terms: dict[str, float]
    terminated: bool = False
    truncated: bool = False
    success: bool = False
    failure_reason: str | None = None
    info: dict[str, Any] = field(default_factory=dict)
    run_on: bool = False


class SkillTask:
    """A single-robot skill task in the robot's team frame (subclass per skill).

    Attributes set by subclasses: ``spec_version`` (the observation/action spec a
    learned actor trained here records), ``observation_space``, ``action_space``.
    """

    spec_version = ""
    observation_space: gymnasium.spaces.Box
    action_space: gymnasium.spaces.Box

    def bind(self, field: FieldGeometry, robot: RobotParams, ball: BallParams, dt: float) -> None:
        """The world the task runs in (called once by the wrapper)."""
        self.field, self.robot_params, self.ball_params, self.dt = field, robot, ball, dt

    def sample_start(self, rng: np.random.Generator, options: dict) -> Start:
        raise NotImplementedError

    def begin(self) -> None:
        """A new episode starts (clear per-episode state)."""

    def begin_step(self, seen: WorldState, robot: int) -> None:
        """A step starts: what the robot sees before its action is applied (team frame)."""

    def observe(self, seen: WorldState, robot: int) -> np.ndarray:
        raise NotImplementedError

    def env_action(self, action: np.ndarray) -> np.ndarray:
        """The task's (validated) action -> the robot's full (5,) env action."""
        raise NotImplementedError

    def judge(self, truth: WorldState, robot: int, events: list[dict], t: float) -> Judgement:
        """Judge the step: ``truth`` in the robot's team frame, ``events`` of the env
        step (kicks, goals, ...), ``t`` the episode's simulated time (s)."""
        raise NotImplementedError


def check_action(action: Any, dim: int) -> np.ndarray:
    """``action`` as a (dim,) float array; ValueError for a wrong shape or NaN/inf.
    (Clipping to [-1, 1] is the action mapping's job.)"""
    a = np.asarray(action, dtype=np.float64)
    if a.shape != (dim,):
        raise ValueError(f"action must have shape ({dim},), got {a.shape}")
    if not np.isfinite(a).all():
        raise ValueError(f"action contains NaN or inf: {a.tolist()}")
    return a


# ---------------------------------------------------------------- wrapper
class RobotSkillEnv(gymnasium.Env):
    """Robot ``agent`` of ``env`` as the robot of ``task`` (see the module docstring).

    Args:
        env: any full-field parallel env (it is reset at every episode start).
        agent: the controlled robot, e.g. "blue_0" or "yellow_3".
        task: the :class:`SkillTask`.
        drivers: drivers of the other robots (default: none, they stand still).
        others_placement: "free": every other robot at a uniformly random free spot
            (0.2 m inside the lines, 0.3 m from the robot, the ball and each other) with a
            random heading, drawn after the task's start; "env": where the env's own task
            puts them on reset (e.g. the match's kickoff formation). Robots in the
            start's ``others`` stand where the task puts them either way.
    """

    metadata = {"render_modes": ["rgb_array", "human"], "render_fps": 60}

    def __init__(self, env: SSLParallelEnv, agent: str, task: SkillTask, drivers: Iterable[RobotDriver] = (),
                 others_placement: str = "free") -> None:
        if others_placement not in ("free", "env"):
            raise ValueError(f"others_placement must be 'free' or 'env', got {others_placement!r}")
        self.env = env
        self.agent_index_in_env = env.agent_index(agent)
        self.agent = agent
        self.team, idx = agent.rsplit("_", 1)
        self.robot = int(idx)
        self.task = task
        self.drivers = list(drivers)
        self.others_placement = others_placement
        self.others = [a for a in env.possible_agents if a != agent]
        self.field: FieldGeometry = env.field
        self.robot_params = env.config.robot
        self.ball_params = env.config.ball
        self.dt = env.config.dt
        self.render_mode = env.render_mode
        task.bind(self.field, self.robot_params, self.ball_params, self.dt)
        self.observation_space = task.observation_space
        self.action_space = task.action_space
        self.spec_version = task.spec_version
        self._t0 = 0.0

    def __getattr__(self, name: str) -> Any:
        """Public attributes of the task read through the env (``env.max_time_s``, ``env.kick_action``)."""
        task = self.__dict__.get("task")
        if not name.startswith("_") and task is not None and hasattr(task, name):
            return getattr(task, name)
        raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")

    # --- views ----------------------------------------------------------------
    @property
    def t(self) -> float:
        """Simulated time since the episode started (s), from the world itself (in
        real-time mode one step can cover several control ticks)."""
        return self.env.world_state().t - self._t0

    def seen(self) -> WorldState:
        """What the controlled robot's team sees, in its team frame."""
        return self.env.vision_state(self.team)

    def truth(self) -> WorldState:
        """The ground truth in the controlled robot's team frame."""
        return to_team_frame(self.env.world_state(), self.team)

    # --- episode --------------------------------------------------------------
    def reset(self, *, seed: int | None = None, options: dict | None = None):
        super().reset(seed=seed)
        start = self.task.sample_start(self.np_random, dict(options or {}))
        robots = {self.agent: tuple(team_to_field_pose(start.robot_pose, self.team))}
        for other, pose in start.others.items():
            if other not in self.others:
                raise ValueError(f"start: {other!r} is not another robot of the env (others: {self.others})")
            robots[other] = tuple(team_to_field_pose(pose, self.team))
        if self.others_placement == "free":
            taken = [np.asarray(start.robot_pose[:2]), np.asarray(start.ball_pos)]
            taken += [np.asarray(pose[:2]) for pose in start.others.values()]
            for other in (o for o in self.others if o not in start.others):
                p = self.field.random_free_point(self.np_random, 0.2, taken, 0.3)
                taken.append(p)
                pose = (p[0], p[1], self.np_random.uniform(-math.pi, math.pi))
                robots[other] = tuple(team_to_field_pose(pose, self.team))
        opts = {"robots": robots, "ball": {"pos": tuple(team_to_field_vec(start.ball_pos, self.team)),
                                           "vel": tuple(team_to_field_vec(start.ball_vel, self.team))}}
        self.env.reset(seed=None if seed is None else int(self.np_random.integers(2 ** 31)), options=opts)
        self._t0 = self.env.world_state().t
        for d in self.drivers:
            d.reset()
        self.task.begin()
        return self._observe(), {"reward_terms": {}}

    def step(self, action):
        a = check_action(action, self.action_space.shape[0])
        self.task.begin_step(self.seen(), self.robot)
        while True:
            acts = {}
            for d in self.drivers:
                acts.update(d.act(self.env))
            acts[self.agent] = self.task.env_action(a)
            acts = {k: v for k, v in acts.items() if k in self.env.agents}
            _, _, term, trunc, infos = self.env.step(acts)
            events = infos[self.agent]["events"]
            j = self.task.judge(self.truth(), self.robot, events, self.t)
            env_ended = term[self.agent] or trunc[self.agent]
            if not j.run_on or j.terminated or j.truncated or env_ended:
                break
        terminated, truncated, success, reason = j.terminated, j.truncated, j.success, j.failure_reason
        if not (terminated or truncated) and env_ended:
            truncated, reason = True, "env_ended"  # the surrounding env's episode ended first
        info: dict[str, Any] = {"reward_terms": j.terms, "t": self.t, **j.info}
        if terminated or truncated:
            info.update(is_success=success, failure_reason=None if success else reason, time_s=self.t)
        return self._observe(), float(sum(j.terms.values())), terminated, truncated, info

    def _observe(self) -> np.ndarray:
        """The task's features of what the robot sees, clipped into ``observation_space``
        (finite bounds wide enough that they never bind in play)."""
        obs = np.asarray(self.task.observe(self.seen(), self.robot), dtype=np.float32)
        return clip_to_bounds(obs, self.observation_space.low, self.observation_space.high)

    def render(self):
        return self.env.render()

    def close(self) -> None:
        self.env.close()


class OneRobotSkillEnv(RobotSkillEnv, EzPickle):
    """A skill task over its own small env: the controlled robot ``blue_0`` (whose team
    frame is the field frame), ``n_teammates`` more blue robots and ``n_opponents``
    yellow robots, all placed at random free spots. The env's task is free play (no
    referee, no time limit): the skill task judges its episodes. Realism and real-time
    options pass through (``realism=...``, ``realtime=...``).

    Traffic (what a training config names in ``env_kwargs``): other robots stand still,
    except that ``opponent_policy="chase"`` drives the opponents with the hand-coded
    go-to-ball, and ``traffic="module:function"`` adds drivers built by
    ``function(env)`` (e.g. ``"ssl_marl.plays.team:stp_traffic"``: STP teams).

    ``tracker``: "on" / True: the robot reads tracked, latency-compensated vision
    (:class:`~ssl_marl.envs.tracking.TrackedVisionEnv` around the env), as deployed skills
    do under realism; so a skill can be trained through the tracker it will run behind
    (with ``realism="randomized"``: through its estimates under randomised conditions).
    "off" / False (default): raw vision; "auto": on unless realism is "none"
    (:func:`~ssl_marl.envs.tracking.resolve_tracker`)."""

    def __init__(self, task: SkillTask, field: str = "div_b", n_opponents: int = 0, opponent_policy: str = "static",
                 n_teammates: int = 0, traffic: str | None = None, realism: Any = "none", realtime: bool = False,
                 render_mode: str | None = None, tracker: Any = False, **env_kwargs: Any) -> None:
        if opponent_policy not in ("static", "chase"):
            raise ValueError(f"opponent_policy must be 'static' or 'chase', got {opponent_policy!r}")
        env = SSLParallelEnv(n_blue=1 + n_teammates, n_yellow=n_opponents, field=field, realism=realism,
                             realtime=realtime, task="free_play", render_mode=render_mode,
                             obs_max_teammates=max(n_teammates, 0), obs_max_opponents=max(n_opponents, 0),
                             **env_kwargs)
        env = with_tracker(env, tracker)
        drivers: list[RobotDriver] = []
        if n_opponents and opponent_policy == "chase":
            from .baseline import GoToBallBaseline

            drivers.append(SkillDriver([f"yellow_{k}" for k in range(n_opponents)], GoToBallBaseline, env.field,
                                       env.config.robot, env.config.ball))
        if traffic is not None:
            from .registry import resolve_ref

            drivers.extend(resolve_ref(traffic)(env))
        super().__init__(env, "blue_0", task, drivers, others_placement="free")
        self.n_opponents, self.opponent_policy, self.n_teammates = n_opponents, opponent_policy, n_teammates


__all__ = ["RobotSkillEnv", "OneRobotSkillEnv", "SkillTask", "Start", "Judgement", "RobotDriver", "StaticDriver",
           "SkillDriver", "check_action", "team_to_field_pose", "team_to_field_vec"]
