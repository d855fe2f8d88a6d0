"""The learned attack decisions in full matches: a DecisionPolicy as the passing or attacking plays' carrier decider.

:class:`PolicyCarrierDecider` adapts any object with the decision-policy interface
(``act(env, agent, obs, info) -> int``, :mod:`ssl_marl.decisions.policies`; e.g.
``LearnedDecisionPolicy``) into a :class:`~ssl_marl.plays.pass_coordinator.CarrierDecider`:
when the passing play asks the carrier's decision it builds the Attack 3v2 observation
and legal-option mask of the carrier (:mod:`ssl_marl.decisions.attack_features`, the
same functions the drill uses), asks the policy, and turns the option into the play's
:class:`~ssl_marl.plays.pass_decision.Decision` (shoot, pass to a teammate slot with the
play's handshake, or dribble toward a point). Restarts (kickoff, free kicks) stay with
the cost decision (the drill never trains them).

:class:`PolicyAttackDecider` does the same for the attacking plays
(:mod:`ssl_marl.plays.attack_play`) with the attack drill's observation, mask and options
(:mod:`ssl_marl.decisions.attack_drill_features`: shot, flat / chip pass, pass into a
redirect, dribble); it is an :class:`~ssl_marl.plays.attack_play.AttackDecider`, so the
chosen pass reaches the passer and receiver roles as the cost decision's does.

:class:`ImprovedAttackDecider` is the attacking plays' cost decision improved at the first
decision of a possession by a value actor of the attack drill, as
:class:`~ssl_marl.decisions.learned.ImprovedDecisionPolicy` plays the drill.

:func:`make_match_decider` resolves the CLI's ``--blue-decision`` / ``--yellow-decision``
values: ``handcoded`` (None: the play's default cost decision), ``learned`` (the shipped
actor of the team's decision task: ``attack_3v2.pt`` for the passing plays,
``attack_drill.pt`` for the attacking plays, in ``ssl_marl/decisions/pretrained/``),
``improved`` (attacking plays only: :class:`ImprovedAttackDecider` with the shipped value
actor ``attack_drill_value.pt``) or an actor checkpoint path. A missing actor or one built for
another observation size / option count fails here, with the offending field named, before a
match starts.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import gymnasium
import numpy as np

from ..plays.attack_decision import AttackChoice, AttackParams
from ..plays.attack_play import AttackDecider
from ..plays.pass_decision import Choice, Decision
from ..plays.pass_coordinator import CarrierRequest, CostDecider
from .attack_drill_features import (ATTACK_DRILL_OBS_DIM, ATTACK_DRILL_OPTIONS, DRIBBLE_OPTIONS, SHOOT,
                                    attack_decision_option, option_play_decision, request_features)
from .dribble_limit import DRIBBLE_MASK_M, check_dribble_mask_m, limit_dribbles
from . import long_shot
from .long_shot import check_long_shot_m, limit_long_shots
from .attack_features import (ATTACK_OBS_DIM, ATTACK_OPTIONS, DRIBBLE_GOAL, DRIBBLE_LEFT, DRIBBLE_RIGHT, OBS_BOUND,
                              attack_action_mask, attack_observation, option_decision)

TASK = "attack-3v2"
#: the attacking plays' decision task
DRILL_TASK = "attack-drill"
#: task -> (observation size, option names) a match decider feeds its policy
TASK_SPACES: dict[str, tuple[int, tuple[str, ...]]] = {TASK: (ATTACK_OBS_DIM, ATTACK_OPTIONS),
                                                       DRILL_TASK: (ATTACK_DRILL_OBS_DIM, ATTACK_DRILL_OPTIONS)}
DECISION_CHOICES = ("handcoded", "learned", "improved")
AGENT = "attacker_0"


class AttackSpecEnv:
    """The observation / action interface of a carrier-decision task (``task``: a key of
    :data:`TASK_SPACES`) without a simulator: what a policy's ``reset(env)`` checks in a
    match (spaces, option names)."""

    possible_agents = (AGENT,)
    agents = (AGENT,)
    episode_seed = None

    def __init__(self, task: str = TASK) -> None:
        self.name = self.task_name = task
        self.obs_dim, self.option_names = TASK_SPACES[task]
        self.n_options = len(self.option_names)

    def observation_space(self, agent: str) -> gymnasium.spaces.Box:
        return gymnasium.spaces.Box(-OBS_BOUND, OBS_BOUND, (self.obs_dim,), np.float32)

    def action_space(self, agent: str) -> gymnasium.spaces.Discrete:
        return gymnasium.spaces.Discrete(self.n_options)


def ask_policy(policy: Any, spec_env: AttackSpecEnv, obs: np.ndarray, mask: np.ndarray, where: str) -> int:
    """The policy's option for ``obs`` under ``mask``; ValueError for an illegal one."""
    a = int(policy.act(spec_env, AGENT, obs, {"decision": True, "action_mask": mask, "elapsed_s": 0.0}))
    if not (0 <= a < spec_env.n_options) or not mask[a]:
        raise ValueError(f"{where}: the policy chose option {a}, not legal under mask {mask.tolist()} "
                         f"({spec_env.option_names})")
    return a


class PolicyCarrierDecider:
    """CarrierDecider from a decision policy (module docstring).

    SSL's dribbling limit as in :class:`PolicyAttackDecider`: from ``dribble_mask_m`` of the
    carrier's current dribble the Attack 3v2 dribble options are not offered
    (:func:`limit_dribbles`).

    Attributes:
        policy: the decision policy; asked only with a legal-option mask.
        fallback: the decider used at restarts (default the cost decision).
        dribble_mask_m: the dribble distance (m) from which dribbling is not offered;
            None: always offered (as in the Attack 3v2 task).
        decisions: number of decisions the policy made (for tests and stats).
        dribbles_masked: decisions taken with the dribbles masked.
    """

    def __init__(self, policy: Any, fallback: Any = None, dribble_mask_m: float | None = DRIBBLE_MASK_M) -> None:
        if not callable(getattr(policy, "act", None)):
            raise TypeError(f"PolicyCarrierDecider: policy must have act(env, agent, obs, info), got {policy!r}")
        self.policy = policy
        self.fallback = fallback if fallback is not None else CostDecider()
        self.dribble_mask_m = check_dribble_mask_m(dribble_mask_m, "PolicyCarrierDecider")
        self.spec_env = AttackSpecEnv()
        self.decisions = 0
        self.dribbles_masked = 0
        if callable(getattr(policy, "reset", None)):
            policy.reset(self.spec_env)

    def decide(self, request: CarrierRequest) -> Decision:
        if request.restart:
            return self.fallback.decide(request)
        ctx = request.ctx
        args = (ctx.world, ctx.team, request.carrier, ctx.field, ctx.robot, request.ball, request.params)
        obs = attack_observation(*args, candidates=request.candidates)
        mask, masked = limit_dribbles(attack_action_mask(*args, candidates=request.candidates), request,
                                      (DRIBBLE_GOAL, DRIBBLE_LEFT, DRIBBLE_RIGHT), self.dribble_mask_m)
        self.dribbles_masked += masked
        a = ask_policy(self.policy, self.spec_env, obs, mask, "PolicyCarrierDecider")
        self.decisions += 1
        return option_decision(a, *args, candidates=request.candidates)


class PolicyAttackDecider(AttackDecider):
    """The attacking plays' carrier decision from a decision policy of the attack drill
    (module docstring); restarts (set pieces) stay with the cost decision.

    SSL's dribbling limit: once the carrier has dribbled the ball ``dribble_mask_m`` or more
    in its current dribble (:attr:`~ssl_marl.plays.play.PlayContext.dribbled_m`, as the
    referee measures it), the dribble options are masked, so the policy shoots or passes
    (a dribble option carries the ball about 0.3 m: 0.6 s at 0.5 m/s). With the attacking
    plays' ``dribble_cut_m`` (0.8 m) a committed dribble is decided again before the
    referee's 1 m. The drill calls no fouls, so its actors never learned the limit.

    Long shots (``long_shot_m``): with the ball farther than that from the opponent goal
    centre the shot is offered only when nothing else is (:func:`limit_long_shots`).

    Attributes:
        policy: the decision policy; asked only with a legal-option mask.
        dribble_mask_m: the dribble distance (m) from which dribbling is not offered;
            None: always offered (as in the drill).
        long_shot_m: the ball's distance from the opponent goal centre (m) beyond which the
            shot is not offered while another option is; None: always offered.
        decisions: number of decisions the policy made.
        dribbles_masked: decisions taken with the dribbles masked.
        long_shots_masked: decisions taken with the shot masked as a long shot.
    """

    def __init__(self, policy: Any, params: AttackParams | None = None,
                 dribble_mask_m: float | None = DRIBBLE_MASK_M, long_shot_m: float | None = None) -> None:
        if not callable(getattr(policy, "act", None)):
            raise TypeError(f"PolicyAttackDecider: policy must have act(env, agent, obs, info), got {policy!r}")
        self.dribble_mask_m = check_dribble_mask_m(dribble_mask_m, "PolicyAttackDecider")
        self.long_shot_m = check_long_shot_m(long_shot_m, "PolicyAttackDecider")
        self.long_shots_masked = 0
        super().__init__(params)
        self.policy = policy
        self.spec_env = AttackSpecEnv(DRILL_TASK)
        self.decisions = 0
        self.dribbles_masked = 0
        if callable(getattr(policy, "reset", None)):
            policy.reset(self.spec_env)

    def decide(self, request: CarrierRequest) -> Decision:
        if request.restart or not request.on_ball:
            return super().decide(request)
        passes, obs, mask = request_features(request, self.request_params(request))
        mask, masked = limit_dribbles(mask, request, DRIBBLE_OPTIONS, self.dribble_mask_m)
        self.dribbles_masked += masked
        mask, masked = limit_long_shots(mask, request.ctx.ball, request.ctx.field, SHOOT, self.long_shot_m)
        self.long_shots_masked += masked
        a = ask_policy(self.policy, self.spec_env, obs, mask, "PolicyAttackDecider")
        self.decisions += 1
        d, option = option_play_decision(a, request.ctx.ball, request.ctx.field, passes)
        if option is not None:
            self.option = option
        self.counters.count(option.kind if option is not None else
                            AttackChoice.SHOOT if d.choice is Choice.SHOOT else AttackChoice.DRIBBLE)
        return d


class ImprovedAttackDecider(AttackDecider):
    """The attacking plays' cost decision, improved at the first decision of a possession by a
    value actor of the attack drill (the drill's :class:`~ssl_marl.decisions.learned.ImprovedDecisionPolicy`
    in a match).

    The cost decision is taken at every request. At the first open-play request of a possession
    with the ball in the half the drill is played in (x >= ``min_x_m``, team frame; the drill's
    carrier starts at 0.5-2.5 m), the value actor rates the drill's legal options; where the best
    has a logit (predicted log-odds of a goal) more than ``margin`` above the cost decision's option's, it is played
    instead (``margin`` None: the one the value actor file records,
    :func:`~ssl_marl.decisions.learned.improve_settings`). A possession starts with a request after none for ``gap_s`` (the coordinator asks every
    few ticks while a robot holds the ball), unless that carrier is the receiver of the team's last
    planned pass (in the drill, too, only the episode's first decision is the actor's).

    Attributes:
        value: the value actor's policy wrapper (:class:`~ssl_marl.decisions.learned.LearnedDecisionPolicy`).
        deviations: possessions at which the value actor's option was played.
    """

    def __init__(self, value_actor: str | Path, params: AttackParams | None = None, margin: float | None = None,
                 gap_s: float = 0.5, min_x_m: float = 0.0) -> None:
        from .learned import LearnedDecisionPolicy, improve_settings

        super().__init__(params)
        self.value = LearnedDecisionPolicy(str(value_actor), task=DRILL_TASK)
        self.spec_env = AttackSpecEnv(DRILL_TASK)
        self.value.reset(self.spec_env)
        margin = improve_settings(self.value.meta)[1] if margin is None else margin
        self.margin, self.gap_s, self.min_x_m = float(margin), float(gap_s), float(min_x_m)
        self.deviations = 0
        self._last_t: float | None = None
        self._passed_to: int | None = None

    def _first_of_possession(self, request: CarrierRequest) -> bool:
        t, gap = float(request.t), self._last_t is None or float(request.t) - self._last_t > self.gap_s
        self._last_t = t
        if not gap:
            return False
        own_pass, self._passed_to = self._passed_to == request.carrier, None
        return not own_pass

    def decide(self, request: CarrierRequest) -> Decision:
        from .learned import better_option

        d = super().decide(request)
        if request.restart or not request.on_ball:
            return d
        first = self._first_of_possession(request)
        if first and float(request.ctx.ball[0]) >= self.min_x_m and self.last is not None:
            passes, obs, mask = request_features(request, self.request_params(request))
            base = attack_decision_option(self.last, request.ctx.world, request.ctx.team, request.carrier)
            best = better_option(self.value.actor.logits(obs, None), mask, base, self.margin) if mask[base] else None
            if best is not None:
                self.deviations += 1
                d, option = option_play_decision(best, request.ctx.ball, request.ctx.field, passes)
                self.option = option
        if d.choice is Choice.PASS and self.option is not None:
            self._passed_to = self.option.teammate
        return d


def default_actor_path(task: str = TASK) -> Path:
    """The shipped actor of decision task ``task`` (``learned.pretrained_path``);
    FileNotFoundError saying how to train one when it is absent."""
    from .learned import pretrained_path

    return Path(pretrained_path(task))


def check_actor_file(path: str | Path, where: str = "decision", task: str = TASK) -> dict:
    """Read an actor checkpoint's header (``torch.load(weights_only=True)``) and check
    it is an actor of ``task`` (a key of :data:`TASK_SPACES`): ValueError naming the
    field (obs_dim, n_options, task) that does not fit; FileNotFoundError for a missing
    file. Returns the header."""
    import torch

    obs_dim, options = TASK_SPACES[task]
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"{where}: actor file {str(path)!r} does not exist")
    try:
        ck = torch.load(path, map_location="cpu", weights_only=True)
    except Exception as exc:  # noqa: BLE001 - any unreadable file gets one message
        raise ValueError(f"{where}: {path} is not a readable decision actor checkpoint ({exc})") from None
    if not isinstance(ck, dict):
        raise ValueError(f"{where}: {path} is not a decision actor checkpoint (expected a dict)")
    ck = ck.get("metadata", ck) if isinstance(ck.get("metadata"), dict) else ck  # the actor file's header
    if "obs_dim" in ck and int(ck["obs_dim"]) != obs_dim:
        raise ValueError(f"{where}: {path} has obs_dim={int(ck['obs_dim'])}, the {task} observation has "
                         f"{obs_dim} values (an actor for another task?)")
    if "n_options" in ck and int(ck["n_options"]) != len(options):
        raise ValueError(f"{where}: {path} has n_options={int(ck['n_options'])}, {task} has "
                         f"{len(options)} options {options}")
    from .learned import decision_family

    if ck.get("task") is not None and decision_family(ck["task"]) != decision_family(task):
        raise ValueError(f"{where}: {path} has task={ck['task']!r}, expected {task!r}")
    return ck


def make_match_decider(spec: Any, where: str = "decision", task: str = TASK) -> Any:
    """The carrier decider for a ``--*-decision`` value of a team whose decision task is
    ``task`` (:data:`TASK`: the passing plays; :data:`DRILL_TASK`: the attacking plays):
    None / ``"handcoded"`` -> None (the play's default cost decision); ``"learned"`` ->
    the task's shipped actor; a path -> that actor; a decider object (with ``decide``) as
    is; a policy object (with ``act``) wrapped."""
    if task not in TASK_SPACES:
        raise ValueError(f"{where}: unknown decision task {task!r}; expected one of {tuple(TASK_SPACES)}")
    if spec is None or spec == "handcoded":
        return None
    if spec == "improved":
        if task != DRILL_TASK:
            raise ValueError(f"{where}: 'improved' is the attacking plays' decision (attack-drill value actor); "
                             f"this team plays the {task} decision")
        from .learned import pretrained_value_path

        path = pretrained_value_path(task)
        check_actor_file(path, where, task)
        return ImprovedAttackDecider(path)
    if not isinstance(spec, (str, Path)):
        if callable(getattr(spec, "decide", None)):
            return spec
        return _policy_decider(spec, task)
    path = default_actor_path(task) if spec == "learned" else Path(spec)
    check_actor_file(path, where, task)
    from .learned import LearnedDecisionPolicy

    policy = LearnedDecisionPolicy(str(path), task=task)
    return _policy_decider(policy, task)


def _policy_decider(policy: Any, task: str) -> Any:
    """The match decider of decision policy ``policy`` for ``task``: the attacking plays' with the
    long-shot rule as set now (:data:`~ssl_marl.decisions.long_shot.LONG_SHOT_MASK_M`), else the
    passing plays'."""
    if task == DRILL_TASK:
        return PolicyAttackDecider(policy, long_shot_m=long_shot.LONG_SHOT_MASK_M)
    return PolicyCarrierDecider(policy)


__all__ = ["PolicyCarrierDecider", "PolicyAttackDecider", "ImprovedAttackDecider", "AttackSpecEnv", "ask_policy",
           "make_match_decider", "default_actor_path", "check_actor_file", "DECISION_CHOICES", "TASK", "DRILL_TASK", "TASK_SPACES"]
