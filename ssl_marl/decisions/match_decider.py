"""The learned attack decision in full matches: a DecisionPolicy as the passing play's carrier decider.

:class:`PolicyCarrierDecider` adapts any object with the decision-policy interface
(``act(env, agent, obs, info) -> int``, :mod:`ssl_marl.decisions.policies`; e.g.
``LearnedDecisionPolicy``) into a :class:`~ssl_marl.plays.pass_coordinator.CarrierDecider`:
when the passing play asks the carrier's decision it builds the Attack 3v2 observation
and legal-option mask of the carrier (:mod:`ssl_marl.decisions.attack_features`, the
same functions the drill uses), asks the policy, and turns the option into the play's
:class:`~ssl_marl.plays.pass_decision.Decision` (shoot, pass to a teammate slot with the
play's handshake, or dribble toward a point). Restarts (kickoff, free kicks) stay with
the cost decision (the drill never trains them).

:func:`make_match_decider` resolves the CLI's ``--blue-decision`` / ``--yellow-decision``
values: ``handcoded`` (None: the play's default cost decision), ``learned`` (the shipped
actor, ``ssl_marl/decisions/pretrained/attack_3v2.pt``) or an actor checkpoint path. A
missing actor or one built for another observation size / option count fails here, with
the offending field named, before a match starts.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import gymnasium
import numpy as np

from ..plays.pass_decision import Decision
from ..plays.pass_coordinator import CarrierRequest, CostDecider
from .attack_features import (ATTACK_OBS_DIM, ATTACK_OPTIONS, N_ATTACK_OPTIONS, OBS_BOUND, attack_action_mask,
                              attack_observation, option_decision)

TASK = "attack-3v2"
DECISION_CHOICES = ("handcoded", "learned")
AGENT = "attacker_0"


class AttackSpecEnv:
    """The observation / action interface of the Attack 3v2 task without a simulator:
    what a policy's ``reset(env)`` checks in a match (spaces, option names)."""

    name = TASK
    possible_agents = (AGENT,)
    agents = (AGENT,)
    option_names = ATTACK_OPTIONS
    n_options = N_ATTACK_OPTIONS
    task_name = TASK
    episode_seed = None

    def observation_space(self, agent: str) -> gymnasium.spaces.Box:
        return gymnasium.spaces.Box(-OBS_BOUND, OBS_BOUND, (ATTACK_OBS_DIM,), np.float32)

    def action_space(self, agent: str) -> gymnasium.spaces.Discrete:
        return gymnasium.spaces.Discrete(N_ATTACK_OPTIONS)


class PolicyCarrierDecider:
    """CarrierDecider from a decision policy (module docstring).

    Attributes:
        policy: the decision policy; asked only with a legal-option mask.
        fallback: the decider used at restarts (default the cost decision).
        decisions: number of decisions the policy made (for tests and stats).
    """

    def __init__(self, policy: Any, fallback: Any = None) -> None:
        if not callable(getattr(policy, "act", None)):
            raise TypeError(f"PolicyCarrierDecider: policy must have act(env, agent, obs, info), got {policy!r}")
        self.policy = policy
        self.fallback = fallback if fallback is not None else CostDecider()
        self.spec_env = AttackSpecEnv()
        self.decisions = 0
        if callable(getattr(policy, "reset", None)):
            policy.reset(self.spec_env)

    def decide(self, request: CarrierRequest) -> Decision:
        if request.restart:
            return self.fallback.decide(request)
        ctx = request.ctx
        args = (ctx.world, ctx.team, request.carrier, ctx.field, ctx.robot, request.ball, request.params)
        obs = attack_observation(*args, candidates=request.candidates)
        mask = attack_action_mask(*args, candidates=request.candidates)
        a = int(self.policy.act(self.spec_env, AGENT, obs,
                                {"decision": True, "action_mask": mask, "elapsed_s": 0.0}))
        if not (0 <= a < N_ATTACK_OPTIONS) or not mask[a]:
            raise ValueError(f"PolicyCarrierDecider: the policy chose option {a}, not legal under mask "
                             f"{mask.tolist()} ({ATTACK_OPTIONS})")
        self.decisions += 1
        return option_decision(a, *args, candidates=request.candidates)


def default_actor_path() -> Path:
    """The shipped attack actor (``learned.pretrained_path("attack-3v2")`` where the
    learned-decision module exists); FileNotFoundError when absent."""
    try:
        from .learned import pretrained_path
    except ImportError:  # the learned-decision module is not in this checkout
        pretrained_path = None
    if pretrained_path is not None:
        return Path(pretrained_path(TASK))
    here = Path(__file__).resolve().parent / "pretrained"
    for name in ("attack_3v2.pt", "attack-3v2.pt"):
        if (here / name).is_file():
            return here / name
    raise FileNotFoundError(f"no shipped attack decision actor under {here} (attack_3v2.pt); train one with "
                            f"the MAPPO trainer (python -m train ... attack-3v2) or pass an actor path")


def check_actor_file(path: str | Path, where: str = "decision") -> dict:
    """Read an actor checkpoint's header (``torch.load(weights_only=True)``) and check
    it is an attack-3v2 actor: ValueError naming the field (obs_dim, n_options, task)
    that does not fit; FileNotFoundError for a missing file. Returns the header."""
    import torch

    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"{where}: actor file {str(path)!r} does not exist")
    try:
        ck = torch.load(path, map_location="cpu", weights_only=True)
    except Exception as exc:  # noqa: BLE001 - any unreadable file gets one message
        raise ValueError(f"{where}: {path} is not a readable decision actor checkpoint ({exc})") from None
    if not isinstance(ck, dict):
        raise ValueError(f"{where}: {path} is not a decision actor checkpoint (expected a dict)")
    if "obs_dim" in ck and int(ck["obs_dim"]) != ATTACK_OBS_DIM:
        raise ValueError(f"{where}: {path} has obs_dim={int(ck['obs_dim'])}, the attack-3v2 observation has "
                         f"{ATTACK_OBS_DIM} values (an actor for another task?)")
    if "n_options" in ck and int(ck["n_options"]) != N_ATTACK_OPTIONS:
        raise ValueError(f"{where}: {path} has n_options={int(ck['n_options'])}, attack-3v2 has "
                         f"{N_ATTACK_OPTIONS} options {ATTACK_OPTIONS}")
    if "task" in ck and ck["task"] not in (TASK, None):
        raise ValueError(f"{where}: {path} has task={ck['task']!r}, expected {TASK!r}")
    return ck


def make_match_decider(spec: Any, where: str = "decision") -> Any:
    """The carrier decider for a ``--*-decision`` value: None / ``"handcoded"`` -> None
    (the play's default cost decision); ``"learned"`` -> the shipped actor; a path -> that
    actor; a decider object (with ``decide``) or a policy object (with ``act``) as is /
    wrapped."""
    if spec is None or spec == "handcoded":
        return None
    if not isinstance(spec, (str, Path)):
        if callable(getattr(spec, "decide", None)):
            return spec
        return PolicyCarrierDecider(spec)
    path = default_actor_path() if spec == "learned" else Path(spec)
    check_actor_file(path, where)
    try:
        from .learned import LearnedDecisionPolicy
    except ImportError as exc:
        raise ImportError(f"{where}: the learned-decision module (ssl_marl.decisions.learned) is not available "
                          f"({exc})") from None
    return PolicyCarrierDecider(LearnedDecisionPolicy(str(path), task=TASK))


__all__ = ["PolicyCarrierDecider", "AttackSpecEnv", "make_match_decider", "default_actor_path", "check_actor_file",
           "DECISION_CHOICES"]
