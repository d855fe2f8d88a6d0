"""Benchmark policies for the decision-level tasks, and the one episode loop.

:class:`DecisionPolicy` is the protocol every decision policy implements (hand-coded,
random, learned): ``reset(env)`` at the start of an episode, ``act(env, agent, obs,
info) -> int`` for an agent whose ``info["decision"]`` is True (the runner never
calls it otherwise). :func:`run_episode` plays one episode with one policy for all
agents and returns its summary.

Built in here: :class:`RandomPolicy` (uniform over the legal options). The keepaway
benchmarks (:class:`AlwaysHoldPolicy`, :class:`HandcodedKeepawayPolicy`) live in
:mod:`ssl_marl.decisions.keepaway.policies`; the attack benchmark
``HandcodedAttackPolicy`` lives in :mod:`ssl_marl.decisions.attack`.
"""

from __future__ import annotations

from typing import Any, Protocol, runtime_checkable

import numpy as np


@runtime_checkable
class DecisionPolicy(Protocol):
    """What eval-task and the trainers call (see the module docstring)."""

    def reset(self, env: Any) -> None:
        """A new episode of ``env`` starts (after ``env.reset``)."""

    def act(self, env: Any, agent: str, obs: np.ndarray, info: dict) -> int:
        """The option index for ``agent`` (only called where ``info["decision"]``)."""


class RandomPolicy:
    """Uniform over the legal options (``info["action_mask"]``). Its draws depend only on
    its own ``seed`` and the episode's seed (``env.episode_seed``), so evaluations are
    reproducible whatever the worker count."""

    name = "random"

    def __init__(self, seed: int = 0) -> None:
        self.seed = int(seed)
        self.rng = np.random.default_rng(self.seed)

    def reset(self, env: Any) -> None:
        es = getattr(env, "episode_seed", None)
        self.rng = np.random.default_rng(np.random.SeedSequence([self.seed, 0 if es is None else int(es), 7]))

    def act(self, env: Any, agent: str, obs: np.ndarray, info: dict) -> int:
        legal = np.flatnonzero(np.asarray(info["action_mask"]))
        if legal.size == 0:
            raise ValueError(f"RandomPolicy: agent {agent!r} has no legal option (action_mask all zero)")
        return int(legal[self.rng.integers(legal.size)])


def run_episode(env: Any, policy: DecisionPolicy, seed: int | None = None, options: dict | None = None,
                record: bool = False) -> dict:
    """One episode of ``env`` with ``policy`` for every agent.

    Agents without a decision are sent option 0 (ignored by the env).

    Returns: ``{"seed", "outcome", "t_s"`` (simulated duration, s), ``"return"`` (the
    first agent's undiscounted return), ``"decisions"`` (actions read), ``"steps"``,
    ``"options"`` (how often each option was chosen), ``"terminated"``, ``"truncated"``,
    plus the env's score keys (``"duration_s"`` / ``"goal"``)}; with ``record`` also
    ``"trace"``: one (t, agent, option) per decision.
    """
    obs, infos = env.reset(seed=seed, options=options)
    policy.reset(env)
    a0 = env.possible_agents[0]
    ret, steps, decisions = 0.0, 0, 0
    counts = np.zeros(env.n_options, np.int64)
    trace: list[tuple[float, str, int]] = []
    final: dict = {}
    term = trunc = False
    while env.agents:
        actions = {}
        for a in env.possible_agents:
            info = infos[a]
            if info["decision"]:
                o = int(policy.act(env, a, obs[a], info))
                actions[a] = o
                counts[o] += 1
                decisions += 1
                if record:
                    trace.append((float(info["t"]), a, o))
            else:
                actions[a] = 0
        obs, rewards, terms, truncs, infos = env.step(actions)
        ret += float(rewards[a0])
        steps += 1
        if not env.agents:
            final = infos[a0]
            term, trunc = bool(terms[a0]), bool(truncs[a0])
    out = {"seed": seed, "outcome": final.get("outcome"), "t_s": float(env.t), "return": ret,
           "decisions": decisions, "steps": steps,
           "options": {n: int(c) for n, c in zip(env.option_names, counts)},
           "terminated": term, "truncated": trunc}
    for k, v in final.items():
        if k not in ("decision", "action_mask", "elapsed_s", "t", "outcome"):
            out[k] = v
    if record:
        out["trace"] = trace
    return out


__all__ = ["DecisionPolicy", "RandomPolicy", "run_episode"]
