"""Toy cooperative decision tasks (pure numpy, microseconds per step) for testing MAPPO.

Both implement the decision-env interface of ``ssl_marl/decisions`` (PettingZoo
``ParallelEnv``; ``infos[agent]`` carries ``decision``, ``action_mask`` and ``elapsed_s``;
``state()`` for the centralised critic; episode score in the final infos):

* :class:`ToySignal` ("toy-signal"): agent 0 sees a random signal in {0..K-1} and sends one
  of K messages; then agent 1, who sees only the message, guesses the signal. Both get +1
  when the guess is right (score ``success``). Option K ("pass") is always illegal (masked),
  so the mask path is exercised. Random play succeeds 1/K of the time; solving it needs a
  shared code, i.e. cooperation across the two decision points.
* :class:`ToyTempo` ("toy-tempo"): two agents choose, each at its own asynchronous decision
  points, a *quick* job (1 s, reward 1) or a *slow* one (5 s, reward 3) until 20 s have
  passed. With gamma = 0.9 per second the quick job is worth more (about 10 vs 7.4 per
  agent), but if time were ignored (discounting per decision) the slow job would look
  better (30 vs 10): the task checks the SMDP discount. Score ``success`` = fraction of
  quick jobs chosen.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from gymnasium import spaces
from pettingzoo import ParallelEnv


class ToySignal(ParallelEnv):
    """Two-agent signalling game; see the module docstring."""

    metadata = {"name": "toy_signal_v0"}

    def __init__(self, n_signals: int = 3) -> None:
        self.k = int(n_signals)
        self.possible_agents = ["agent_0", "agent_1"]
        self.agents = list(self.possible_agents)
        self.option_names = tuple(f"say_{i}" for i in range(self.k)) + ("pass",)
        self._obs_space = spaces.Box(0.0, 1.0, (self.k + 2,), np.float32)
        self.state_space = spaces.Box(0.0, 1.0, (2 * self.k + 2,), np.float32)
        self._rng = np.random.default_rng()
        self.signal, self.message, self.phase = 0, -1, 0

    def observation_space(self, agent: str) -> spaces.Box:
        return self._obs_space

    def action_space(self, agent: str) -> spaces.Discrete:
        return spaces.Discrete(self.k + 1)

    def _obs(self) -> dict[str, np.ndarray]:
        o0 = np.zeros(self.k + 2, np.float32)
        o1 = np.zeros(self.k + 2, np.float32)
        o0[self.signal] = 1.0
        o0[self.k] = o1[self.k] = float(self.phase == 0)
        o0[self.k + 1] = o1[self.k + 1] = float(self.phase == 1)
        if self.message >= 0:
            o1[self.message] = 1.0
        return {"agent_0": o0, "agent_1": o1}

    def state(self) -> np.ndarray:
        s = np.zeros(2 * self.k + 2, np.float32)
        s[self.signal] = 1.0
        if self.message >= 0:
            s[self.k + self.message] = 1.0
        s[2 * self.k + self.phase] = 1.0
        return s

    def _infos(self, elapsed: float) -> dict[str, dict[str, Any]]:
        mask = np.ones(self.k + 1, np.int8)
        mask[self.k] = 0
        return {a: {"decision": i == self.phase, "action_mask": mask.copy() if i == self.phase
                    else np.ones(self.k + 1, np.int8), "elapsed_s": elapsed}
                for i, a in enumerate(self.possible_agents)}

    def reset(self, seed: int | None = None, options: dict | None = None):
        if seed is not None:
            self._rng = np.random.default_rng(seed)
        self.agents = list(self.possible_agents)
        self.signal, self.message, self.phase = int(self._rng.integers(self.k)), -1, 0
        return self._obs(), self._infos(0.0)

    def step(self, actions: dict[str, Any]):
        act = int(actions[self.possible_agents[self.phase]])
        if act >= self.k:  # the illegal "pass" option maps to option 0 (documented default)
            act = 0
        zero = {a: 0.0 for a in self.possible_agents}
        if self.phase == 0:
            self.message, self.phase = act, 1
            f = {a: False for a in self.possible_agents}
            return self._obs(), zero, f, dict(f), self._infos(0.5)
        success = float(act == self.signal)
        infos = self._infos(0.5)
        for a in self.possible_agents:
            infos[a].update(decision=False, success=success, outcome="right" if success else "wrong")
        obs = self._obs()
        self.agents = []
        t = {a: True for a in self.possible_agents}
        return obs, {a: success for a in self.possible_agents}, t, {a: False for a in t}, infos


class ToyTempo(ParallelEnv):
    """Two agents with asynchronous variable-duration jobs; see the module docstring."""

    metadata = {"name": "toy_tempo_v0"}
    DURATION_S = (1.0, 5.0)
    REWARD = (1.0, 3.0)
    HORIZON_S = 20.0

    def __init__(self) -> None:
        self.possible_agents = ["agent_0", "agent_1"]
        self.agents = list(self.possible_agents)
        self.option_names = ("quick", "slow")
        self._obs_space = spaces.Box(0.0, 1.0, (3,), np.float32)
        self.state_space = spaces.Box(0.0, 1.0, (3,), np.float32)
        self.t, self.remaining, self.job = 0.0, np.zeros(2), np.zeros(2, int)
        self.quick, self.chosen = 0, 0
        self._rng = np.random.default_rng()

    def observation_space(self, agent: str) -> spaces.Box:
        return self._obs_space

    def action_space(self, agent: str) -> spaces.Discrete:
        return spaces.Discrete(2)

    def state(self) -> np.ndarray:
        return np.array([self.t / self.HORIZON_S, *(self.remaining / 5.0)], np.float32)

    def _obs(self) -> dict[str, np.ndarray]:
        return {a: np.array([self.t / self.HORIZON_S, self.remaining[i] / 5.0, self.remaining[1 - i] / 5.0],
                            np.float32) for i, a in enumerate(self.possible_agents)}

    def _infos(self, elapsed: float) -> dict[str, dict[str, Any]]:
        return {a: {"decision": bool(self.remaining[i] <= 0.0), "action_mask": np.ones(2, np.int8),
                    "elapsed_s": elapsed} for i, a in enumerate(self.possible_agents)}

    def reset(self, seed: int | None = None, options: dict | None = None):
        if seed is not None:
            self._rng = np.random.default_rng(seed)
        self.agents = list(self.possible_agents)
        self.t = 0.0
        self.remaining = np.array([0.0, float(self._rng.integers(1, 4))])  # agent 1 starts busy: asynchronous
        self.job = np.zeros(2, int)
        self.quick, self.chosen = 0, 0
        return self._obs(), self._infos(0.0)

    def step(self, actions: dict[str, Any]):
        for i, a in enumerate(self.possible_agents):
            if self.remaining[i] <= 0.0:
                self.job[i] = int(actions[a])
                self.remaining[i] = self.DURATION_S[self.job[i]]
                self.quick += int(self.job[i] == 0)
                self.chosen += 1
        dt = float(min(self.remaining.min(), self.HORIZON_S - self.t))
        self.t += dt
        self.remaining -= dt
        rewards = {a: (self.REWARD[self.job[i]] if self.remaining[i] <= 1e-9 else 0.0)
                   for i, a in enumerate(self.possible_agents)}
        self.remaining[self.remaining <= 1e-9] = 0.0
        done = self.t >= self.HORIZON_S - 1e-9
        infos = self._infos(dt)
        if done:
            for a in self.possible_agents:
                infos[a].update(decision=False, success=self.quick / max(self.chosen, 1), outcome="time")
            self.agents = []
        return self._obs(), rewards, {a: False for a in rewards}, {a: done for a in rewards}, infos


TOY_TASKS = {"toy-signal": ToySignal, "toy-tempo": ToyTempo}
