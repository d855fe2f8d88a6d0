"""The 2v0 "pass then score" drill: a continuous-action multi-agent task on the raw engine.

Two blue robots on a Division B field, no opponents, blue attacks +x. ``blue_0`` (the
passer) starts with the ball on its dribbler, at x in [-1.5, 0.5] m, y in [-1.5, 1.5] m,
facing a random direction; ``blue_1`` (the receiver) starts at x in [1.0, 2.5] m,
y in [-2, 2] m, at least 1.5 m from the passer, facing a random direction. Every robot
acts every control tick (60 Hz) with the engine's raw action ``(vx, vy, omega, dribble,
kick)`` in [-1, 1]^5 (:mod:`ssl_marl.envs.actions`): no skills, no options.

Pass: the ball has been at least 0.3 m from the passer's centre and then touches the
receiver (ball centre within robot radius + ball radius + 0.03 m of its centre, or on its
dribbler). Success: a goal for blue after the pass. The episode terminates on a goal
(with or without a pass) or on the ball leaving the field; it is truncated after
``max_time_s`` (default 6 s) of simulated time.

Reward (team-shared, per tick; distances in m, field frame):

* before the pass: ``k_pass * (d_prev - d)`` with d = |ball - receiver| (ball brought to
  the teammate), and ``+pass_bonus`` (default 1) once, at the pass;
* after the pass: ``k_goal * (g_prev - g)`` with g = |ball - centre of the +x goal|;
* ``+goal_bonus`` (default 5) for a goal after the pass; a goal without a pass ends the
  episode with no bonus (it is not the drill).

``k_pass`` = ``k_goal`` = 1 by default, so an ideal episode earns about
d_0 + 1 + g_0 + 5. :class:`PassAndScoreEnv` wraps the engine as a decision env (every agent
decides every tick: ``infos[a]["decision"]`` is True and ``elapsed_s`` is 1/60 s; no action
mask) with the episode's ``success`` (0/1), ``passed`` and ``outcome`` in the final infos.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from pettingzoo import ParallelEnv

from ..referee import judge
from .base import Task
from .engine import Engine
from .scene import Scene


@dataclass(frozen=True)
class PassAndScoreParams:
    """Drill parameters (m, s)."""

    max_time_s: float = 6.0
    k_pass: float = 1.0
    k_goal: float = 1.0
    pass_bonus: float = 1.0
    goal_bonus: float = 5.0
    touch_margin: float = 0.03       # m beyond robot radius + ball radius that counts as touching
    release_distance: float = 0.3    # m from the passer's centre before a touch can count as a pass
    min_separation: float = 1.5      # m between the two robots at the start


class PassAndScoreTask(Task):
    """Scene, judge, rewards and end of the drill (module docstring)."""

    name = "pass_and_score"

    def __init__(self, params: PassAndScoreParams | None = None) -> None:
        super().__init__()
        self.p = params or PassAndScoreParams()
        self.passed = self.released = False
        self.outcome = ""
        self._d = self._g = 0.0
        self._reward = 0.0
        self._goal = np.zeros(2)

    def reset_scene(self, env: Engine, options: dict) -> Scene:
        rng = env.np_random
        p0 = np.array([rng.uniform(-1.5, 0.5), rng.uniform(-1.5, 1.5)])
        while True:
            p1 = np.array([rng.uniform(1.0, 2.5), rng.uniform(-2.0, 2.0)])
            if np.linalg.norm(p1 - p0) >= self.p.min_separation:
                break
        h0, h1 = rng.uniform(-np.pi, np.pi, 2)
        r = env.config.robot.front_distance + env.config.ball.radius + 0.002
        ball = p0 + r * np.array([np.cos(h0), np.sin(h0)])
        return Scene(np.array([[*p0, h0], [*p1, h1]]), ball, np.zeros(2))

    def start(self, env: Engine) -> None:
        ws = env.world_state()
        self._goal = np.array([env.field.half_length, 0.0])
        self.passed = self.released = False
        self.outcome = ""
        self._d = float(np.linalg.norm(ws.ball_pos - ws.blue.pos[1]))
        self._g = float(np.linalg.norm(ws.ball_pos - self._goal))
        self._reward = 0.0

    def begin_step(self, env: Engine) -> None:
        self._reward = 0.0

    def after_tick(self, env: Engine, events: list[dict]) -> bool:
        ws = env.world_state()
        ball = ws.ball_pos
        if not self.released and np.linalg.norm(ball - ws.blue.pos[0]) >= self.p.release_distance:
            self.released = True
        if not self.passed:
            d = float(np.linalg.norm(ball - ws.blue.pos[1]))
            self._reward += self.p.k_pass * (self._d - d)
            self._d = d
            touch = d <= env.config.robot.radius + env.config.ball.radius + self.p.touch_margin \
                or bool(ws.blue.ball_on_dribbler[1])
            if self.released and touch:
                self.passed = True
                self._reward += self.p.pass_bonus
                self._g = float(np.linalg.norm(ball - self._goal))
                events.append({"type": "pass", "t": ws.t})
        else:
            g = float(np.linalg.norm(ball - self._goal))
            self._reward += self.p.k_goal * (self._g - g)
            self._g = g
        call = judge(ws, env.field, env.config.ball.radius)
        if call.goal_for is not None:
            env.award_goal(call.goal_for, events)
            if self.passed and call.goal_for == "blue":
                self._reward += self.p.goal_bonus
                self.outcome = "goal"
            else:
                self.outcome = "goal_without_pass"
            return True
        if call.ball_out:
            self.outcome = "ball_out"
            return True
        return False

    def rewards(self, env: Engine) -> tuple[dict[str, float], dict[str, dict[str, float]]]:
        return {a: self._reward for a in env.agents}, {"blue": {"drill": self._reward}, "yellow": {}}

    def end(self, env: Engine) -> tuple[bool, bool]:
        if self.outcome:
            return True, False
        if env.world_state().t >= self.p.max_time_s - 1e-9:
            self.outcome = "time"
            return False, True
        return False, False


class PassAndScoreEnv(ParallelEnv):
    """The drill as a decision env over the raw engine (every agent decides every 1/60 s tick)."""

    metadata = {"name": "pass_and_score_v0"}

    def __init__(self, params: PassAndScoreParams | None = None, realism: Any = "none") -> None:
        from ..ssl_env import SSLParallelEnv

        self.task = PassAndScoreTask(params)
        self.engine = SSLParallelEnv(n_blue=2, n_yellow=0, field="div_b", task=self.task, realism=realism,
                                     obs_max_teammates=1, obs_max_opponents=0, max_time_s=1e6)
        self.possible_agents = list(self.engine.possible_agents)
        self.agents: list[str] = []
        self.state_space = self.engine.state_space
        self.dt = 1.0 / self.engine.config.control_hz
        self.option_names = None

    def observation_space(self, agent: str) -> Any:
        return self.engine.observation_space(agent)

    def action_space(self, agent: str) -> Any:
        return self.engine.action_space(agent)

    def state(self) -> np.ndarray:
        return self.engine.state()

    def _infos(self, elapsed: float) -> dict[str, dict[str, Any]]:
        return {a: {"decision": True, "elapsed_s": elapsed} for a in self.possible_agents}

    def reset(self, seed: int | None = None, options: dict | None = None):
        obs, _ = self.engine.reset(seed=seed, options=options)
        self.agents = list(self.possible_agents)
        return obs, self._infos(0.0)

    def step(self, actions: dict[str, Any]):
        obs, rew, term, trunc, _ = self.engine.step({a: np.asarray(actions[a], np.float64) for a in self.agents})
        infos = self._infos(self.dt)
        if any(term.values()) or any(trunc.values()):
            for a in self.possible_agents:
                infos[a].update(decision=False, success=float(self.task.outcome == "goal"),
                                passed=float(self.task.passed), outcome=self.task.outcome)
            self.agents = []
        return obs, rew, term, trunc, infos

    def close(self) -> None:
        self.engine.close()


__all__ = ["PassAndScoreEnv", "PassAndScoreParams", "PassAndScoreTask"]
