"""The attack drill with its defence drawn per episode (task ``attack-drill-mix``).

A decision trained only against one defence fits that defence: fine-tuned against the match's
six-robot defence, the attacking decision shoots at almost every request and loses what it knew
against a goalie and one defender, where a pass to the free attacker scores (``docs/RESULTS.md``,
section 15). :class:`AttackDrillMixEnv` plays both drills of the attacking plays' decision under
SSL rules, one per episode:

* ``one-defender``: :class:`~ssl_marl.decisions.attack_drill.AttackDrillSSLEnv` (a goalie and
  one defender, the Attack 3v2 scene);
* ``defended``: :class:`~ssl_marl.decisions.attack_drill.AttackDrillDefendedEnv` (the match's
  defence: goalie, two defenders, a presser, two marks).

Episode seed ``s`` draws the drill from ``SeedSequence([s, 2])`` (probability ``p_defended`` for
the defended one) and then resets that drill with ``s``, so an episode of the mix is the same
episode as the drill's own task on that seed. Agents, observation (48 values) and options (10)
are the drills' own, so an actor trained here plays in both drills and in matches. The global
state (the centralised critic's input) is the drill's state padded with zeros to the defended
drill's length, then one value: 1 in the defended drill, 0 in the other. A finished episode's
infos carry ``"drill"`` (its name) beside the drill's outcome. Everything else (the open carrier
request, the decider, the engine) is the active drill's, so the drills' hand-coded and learned
policies play the mix unchanged.
"""

from __future__ import annotations

import math
from typing import Any, Mapping

import gymnasium
import numpy as np
from pettingzoo import ParallelEnv

from .attack_drill import AttackDrillDefendedEnv, AttackDrillSSLEnv

#: the mix's drills, in the order of the state's flag value (0, 1)
MIX_DRILLS: tuple[str, ...] = ("one-defender", "defended")


def check_p_defended(p: Any, where: str) -> float:
    """``p`` as a probability in [0, 1]; ValueError naming ``where`` otherwise."""
    if isinstance(p, bool) or not isinstance(p, (int, float, np.integer, np.floating)) or not math.isfinite(p) \
            or not 0.0 <= float(p) <= 1.0:
        raise ValueError(f"{where}: p_defended must be a probability in [0, 1], got {p!r}")
    return float(p)


def drill_of_seed(seed: int, p_defended: float) -> int:
    """Index into :data:`MIX_DRILLS` of episode seed ``seed`` (1: defended, with probability ``p_defended``)."""
    u = np.random.default_rng(np.random.SeedSequence([int(seed), 2])).random()
    return int(u < p_defended)


class AttackDrillMixEnv(ParallelEnv):
    """The two drills of the module docstring, one per episode. ``p_defended``: probability of
    the defended drill (default 0.5); the other keyword arguments (``skills``, ``render_mode``,
    ...) go to both drills."""

    task_name = "attack-drill-mix"
    metadata = {"name": "ssl_marl_attack_drill_mix_v0", "render_modes": ["rgb_array"], "is_parallelizable": True}

    def __init__(self, p_defended: float = 0.5, **kwargs: Any) -> None:
        self.p_defended = check_p_defended(p_defended, type(self).__name__)
        self.drills = (AttackDrillSSLEnv(**kwargs), AttackDrillDefendedEnv(**kwargs))
        one, defended = self.drills
        if one.possible_agents != defended.possible_agents or one.option_names != defended.option_names:
            raise RuntimeError("the mix's drills must share agents and options")
        self.possible_agents = list(one.possible_agents)
        self.option_names = one.option_names
        self.render_mode = one.render_mode
        self._pad = defended.state_space.shape[0]
        low = np.concatenate([np.minimum(defended.state_space.low, 0.0), [0.0]]).astype(np.float32)
        high = np.concatenate([np.maximum(defended.state_space.high, 0.0), [1.0]]).astype(np.float32)
        self.state_space = gymnasium.spaces.Box(low, high, low.shape, np.float32)
        self._rng = np.random.default_rng()
        self.active = 0

    # ------------------------------------------------------------------ the drill
    @property
    def drill(self) -> Any:
        """The drill of the current episode."""
        return self.drills[self.active]

    @property
    def drill_name(self) -> str:
        return MIX_DRILLS[self.active]

    def __getattr__(self, name: str) -> Any:
        # the active drill's decider, engine, field, ...: only reached for names the mix lacks
        if name in ("drills", "active") or name.startswith("__"):
            raise AttributeError(name)
        return getattr(self.drills[self.active], name)

    # ------------------------------------------------------------------ API
    @property
    def agents(self) -> list[str]:
        return self.drill.agents

    def observation_space(self, agent: str) -> gymnasium.spaces.Box:
        return self.drills[0].observation_space(agent)

    def action_space(self, agent: str) -> gymnasium.spaces.Discrete:
        return self.drills[0].action_space(agent)

    def reset(self, seed: int | None = None, options: dict | None = None):
        if seed is None:
            seed = int(self._rng.integers(2 ** 31))
        self.active = drill_of_seed(seed, self.p_defended)
        return self.drill.reset(seed=seed, options=options)

    def step(self, actions: Mapping[str, Any]):
        obs, rewards, terms, truncs, infos = self.drill.step(actions)
        if not self.drill.agents:
            for info in infos.values():
                info["drill"] = self.drill_name
        return obs, rewards, terms, truncs, infos

    def state(self) -> np.ndarray:
        s = np.zeros(self._pad + 1, np.float32)
        d = self.drill.state()
        s[:len(d)] = d
        s[-1] = float(self.active)
        return s

    def render(self):
        return self.drill.render()

    def close(self) -> None:
        for d in self.drills:
            d.close()


class PerDrillPolicy:
    """A decision policy of the mix that plays ``policies[drill name]`` in each drill (e.g. to
    clone two teachers into one actor: ``python -m train.mappo_bc --teacher``). Every drill of
    :data:`MIX_DRILLS` needs a policy."""

    name = "per-drill"

    def __init__(self, policies: Mapping[str, Any]) -> None:
        missing = [d for d in MIX_DRILLS if d not in policies]
        unknown = [d for d in policies if d not in MIX_DRILLS]
        if missing or unknown:
            raise ValueError(f"PerDrillPolicy needs a policy for each drill of {MIX_DRILLS}; "
                             f"missing {missing}, unknown {unknown}")
        self.policies = dict(policies)

    def reset(self, env: Any) -> None:
        self.policies[env.drill_name].reset(env)

    def act(self, env: Any, agent: str, obs: np.ndarray, info: dict) -> int:
        return int(self.policies[env.drill_name].act(env, agent, obs, info))


__all__ = ["AttackDrillMixEnv", "PerDrillPolicy", "MIX_DRILLS", "drill_of_seed", "check_p_defended"]
