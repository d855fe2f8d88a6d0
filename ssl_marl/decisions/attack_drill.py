"""Attack drill: the attacking plays' carrier decision (shot, flat / chip pass, pass into a redirect, dribble) as a PettingZoo task.

:class:`AttackDrillEnv` is :class:`~ssl_marl.decisions.attack.Attack3v2Env`'s scene, judge,
agents and global state (three attackers ``attacker_0..2`` against a goalie and a defender on
half a Division B field; outcomes, 15 s, +1 for a goal: :mod:`ssl_marl.envs.tasks.attack`) with
the match's attacking plays in place of the passing play:

* **Who plays what.** The attackers run the roles of the attacking plays
  (:mod:`ssl_marl.plays.attack_play`: goalie, the chip passer, the redirect receiver, the
  attacker aiming at the widest open part of the goal mouth, two supports on rated spots) with
  the attacking plays' pass coordinator settings (``ATTACK_PASSING``, asked every tick:
  ``decide_every=1``); the only change from a match is that the carrier's decision comes from
  the agents (:class:`DrillAttackDecider`). The attackers build the attacking team's skills
  (:data:`~ssl_marl.plays.skillset.ATTACK_SKILLS`: with ``skills="learned"`` the shipped chip-pass
  and redirect actors too, as ``attack-learned`` plays in matches). The world is the chip env
  (``chip_kicks=True``); the defence (the project's Goalie and Defender tactics, as in Attack 3v2)
  kicks flat.
* **Options, mask, observation**: :mod:`ssl_marl.decisions.attack_drill_features` (10 options:
  shoot, flat pass / chip / pass into a redirect to teammate slot 1 or 2, three dribbles; 48
  values), the same functions a match's :class:`~ssl_marl.decisions.match_decider.PolicyAttackDecider`
  uses. Decision points as in Attack 3v2: when the play asks for the carrier's decision the
  carrier's agent gets ``infos[agent]["decision"] = True`` with the legal options.
* **Benchmark.** :class:`HandcodedAttackDrillPolicy` is the attacking plays' cost decision
  (:func:`~ssl_marl.plays.attack_decision.decide_attack`, the function the attacking team plays
  in matches) on the same request, mapped to the options (keep -> ``dribble_goal``); a carrier
  that has kept the ball for more than ``max_keep_s`` (0.8 s) shoots, as in the play.
* **Under SSL rules** (:class:`AttackDrillSSLEnv`, task ``attack-drill-ssl``): the attackers'
  SSL fouls end the episode (outcome ``foul``: :class:`~ssl_marl.envs.tasks.attack.AttackRules`
  ``fouls``), the pass coordinator cuts dribbles as in matches (:data:`SSL_DRILL_PASSING`), and
  the dribble options are not offered once the carrier has dribbled
  :data:`~ssl_marl.decisions.dribble_limit.DRIBBLE_MASK_M` (the rule the match's learned decider
  applies, :mod:`~ssl_marl.decisions.dribble_limit`; a masked choice of the hand-coded policy
  is a shot, as its keep clock's). Same observation and options, so its actors play in matches
  as the drill's do.
* **Against the match's defence** (:class:`AttackDrillDefendedEnv`, task ``attack-drill-defended``):
  the drill under SSL rules with the defence a 6v6 attacking team plays when its opponent has the
  ball (:func:`match_defence_plays`: the attacking plays' ``defense_play``, always applicable): a
  goalie, two defenders on the ball-goal line, one robot pressing the ball and marks on the two
  attackers without it (six robots, placed as :class:`~ssl_marl.envs.tasks.attack.AttackSpawn`
  documents); a contested ball plays on (``AttackRules.contested_plays_on``: the attack is lost
  when a defender holds the ball alone). The three attackers are the carrier and the two supports
  of a match's attack. Same observation and options (the observation's opponent slots are the
  goalie and the defender nearest the ball; the others count in its cost features, as in matches).
"""

from __future__ import annotations

import dataclasses
import functools
from typing import Any, Mapping

import numpy as np

from ..envs.actions import CHIP_ACTION_DIM, fit_action
from ..envs.tasks.attack import MAX_DEFENCE, AttackRules
from ..physics.params import BallParams
from ..plays.attack_decision import AttackOption, AttackParams, decide_attack
from ..plays.attack_play import (ATTACK_MARK_BIAS, ATTACK_PASSING, AttackDecider, AttackPrepare, SpotPlanner,
                                 chip_passer_role, redirect_receiver_role, spot_support_role)
from ..plays.pass_coordinator import CarrierRequest, PassCoordinator, PassingParams
from ..plays.passing_roles import passing_attacker_role
from ..plays.skillset import ATTACK_SKILLS
from ..plays.play import Play, defense_play, goalie_role
from .attack import Attack3v2Env, CarrierRequestHooks, DrillDecider, HandcodedCarrierPolicy
from .attack_drill_features import (ATTACK_DRILL_OBS_DIM, ATTACK_DRILL_OPTIONS, DRIBBLE_GOAL_OPTION, DRIBBLE_OPTIONS,
                                    SHOOT, SlotPasses,
                                    attack_decision_option, option_play_decision, request_features)
from .attack_features import ATTACK_OBS_DIM, OBS_BOUND, attack_observation
from .dribble_limit import DRIBBLE_MASK_M, check_dribble_mask_m, limit_dribbles
from .long_shot import limit_long_shots

#: the drill's pass coordinator: the attacking plays' settings, asked every tick; the drill
#: calls no fouls and its shipped actors were trained with dribbles that run their time, so
#: the match's dribble cut (``dribble_cut_m``) is off here
DRILL_PASSING = dataclasses.replace(ATTACK_PASSING, decide_every=1, dribble_cut_m=None)
#: the drill under SSL rules: the attacking plays' settings as in matches (dribble cut on), asked every tick
SSL_DRILL_PASSING = dataclasses.replace(ATTACK_PASSING, decide_every=1)


class DrillAttackDecider(DrillDecider, AttackDecider):
    """The attacking plays' decider answered by the drill's agents
    (:class:`~ssl_marl.decisions.attack.DrillDecider`): an answer's payload is the chosen
    pass (:class:`~ssl_marl.plays.attack_decision.AttackOption`, None for a shot or a
    dribble), which the passer and receiver roles read as the cost decision's."""

    def __init__(self, params: AttackParams | None = None) -> None:
        AttackDecider.__init__(self, params)
        DrillDecider.__init__(self)

    def reset(self) -> None:
        DrillDecider.reset(self)
        self.option = None
        self.last = None

    def accept(self, payload: AttackOption | None) -> None:
        if payload is not None:
            self.option = payload


def drill_attacking_plays(passing: PassingParams, *, ball: BallParams | None,
                          decider: AttackDecider | None) -> tuple[Play, ...]:
    """The attackers' one play (a :class:`~ssl_marl.plays.team.PlaysFactory` once ``passing``
    is bound): the attacking plays' offense roles (goalie, chip passer, redirect receiver,
    attacker, two rated-spot supports) with a new coordinator and spot planner."""
    dec = decider if decider is not None else AttackDecider()
    coord = PassCoordinator(passing, ball, dec)
    planner = SpotPlanner(ball=ball)
    roles = (goalie_role(100), chip_passer_role(coord, dec, 95), redirect_receiver_role(coord, dec, 94),
             passing_attacker_role(coord, 90, aim_open_goal=True), spot_support_role(0, planner, 80),
             spot_support_role(1, planner, 70))
    return (Play("attack_drill", lambda ctx: True, roles, prepare=AttackPrepare(coord, planner)),)


def match_defence_plays(*, ball: BallParams | None, decider: Any) -> tuple[Play, ...]:
    """The defence of :class:`AttackDrillDefendedEnv` (a :class:`~ssl_marl.plays.team.PlaysFactory`):
    the attacking plays' defense play (goalie, presser, two defenders, marks; marks with
    :data:`~ssl_marl.plays.attack_play.ATTACK_MARK_BIAS`), applicable throughout."""
    play = defense_play(mark_ball_bias=ATTACK_MARK_BIAS)
    return (dataclasses.replace(play, name="match_defence", applicable=lambda ctx: True),)


class AttackOptionsMixin(CarrierRequestHooks):
    """The carrier's attacking options as :class:`~ssl_marl.decisions.base.DecisionEnv` hooks,
    shared by the drill and the full-match task: the :class:`DrillAttackDecider`'s open request
    is the decision point of the carrier's agent (robot k is ``agent_of(k)``, field robots
    1..``n_agents``), the mask and observation are the drill's features, the chosen option
    answers the request. Non-deciding agents observe Attack 3v2's 40 values and zeros for the
    pass values (only a deciding agent's observation is acted on). The env provides
    ``decider``, ``attack``, ``blue``, ``yellow``, ``engine``, ``field``, ``rp``, ``bp``,
    ``n_agents`` and ``agent_of``."""

    _passes: SlotPasses
    #: m: dribble distance from which the dribble options are masked (None: never;
    #: :func:`~ssl_marl.decisions.dribble_limit.limit_dribbles`)
    dribble_mask_m: float | None = None
    #: m: the ball's distance from the opponent goal centre beyond which the shot is offered only
    #: when nothing else is (None: always; :func:`~ssl_marl.decisions.long_shot.limit_long_shots`)
    long_shot_m: float | None = None

    def request_features(self, req: CarrierRequest) -> tuple[np.ndarray, np.ndarray]:
        self._passes, obs, mask = request_features(req, self.decider.request_params(req))
        mask = limit_dribbles(mask, req, DRIBBLE_OPTIONS, self.dribble_mask_m)[0]
        return obs, limit_long_shots(mask, req.ctx.ball, req.ctx.field, SHOOT, self.long_shot_m)[0]

    def start_options(self, chosen: Mapping[str, int]) -> None:
        req = self.decider.request
        for agent, option in chosen.items():
            d, o = option_play_decision(option, req.ctx.world.ball_pos, self.field, self._passes)
            self.decider.answer_with(d, o)

    def tick_actions(self) -> dict[str, np.ndarray]:
        actions = self.blue.act(self.engine)
        actions.update(self.yellow.act(self.engine))
        return {k: fit_action(v, CHIP_ACTION_DIM) for k, v in actions.items()}

    def observe(self) -> dict[str, np.ndarray]:
        world = self.engine.vision_state("blue")
        pad = np.zeros(ATTACK_DRILL_OBS_DIM - ATTACK_OBS_DIM, np.float32)
        out = {}
        for a in self.possible_agents:
            if a in self._deciding and self._request_obs is not None:
                out[a] = self._request_obs
            else:
                k = int(a.rsplit("_", 1)[1]) + 1
                out[a] = np.concatenate([attack_observation(world, "blue", k, self.field, self.rp, self.bp,
                                                            self.attack.decision), pad])
        return out

    def observation_bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return (np.full(ATTACK_DRILL_OBS_DIM, -OBS_BOUND, np.float32),
                np.full(ATTACK_DRILL_OBS_DIM, OBS_BOUND, np.float32))


class AttackDrillEnv(AttackOptionsMixin, Attack3v2Env):
    """The attack drill (module docstring). Arguments as :class:`~ssl_marl.decisions.attack.Attack3v2Env`
    (``passing`` default :data:`DRILL_PASSING`) plus ``attack``: the attacking plays'
    :class:`~ssl_marl.plays.attack_decision.AttackParams` (default: the match's)."""

    task_name = "attack-drill"
    option_names = ATTACK_DRILL_OPTIONS
    default_option = SHOOT
    #: the attacking team's skills (with the chip pass and the redirect), as in matches
    attacker_skills = ATTACK_SKILLS

    def __init__(self, skills: str = "learned", attack: AttackParams | None = None, **kwargs: Any) -> None:
        self.attack = attack or AttackParams()
        kwargs.setdefault("passing", DRILL_PASSING)
        self._passes: SlotPasses = {}
        super().__init__(skills=skills, **kwargs)

    def make_decider(self) -> DrillAttackDecider:
        return DrillAttackDecider(self.attack)

    def attack_plays_factory(self) -> Any:
        return functools.partial(drill_attacking_plays, self.passing)

    def engine_kwargs(self) -> dict:
        return {**super().engine_kwargs(), "chip_kicks": True}


class AttackDrillSSLEnv(AttackDrillEnv):
    """The attack drill under SSL rules (module docstring): fouls called, the match's dribble cut
    and the learned decider's dribble mask. Arguments as :class:`AttackDrillEnv` plus
    ``dribble_mask_m`` (m, default :data:`~ssl_marl.decisions.dribble_limit.DRIBBLE_MASK_M`;
    None: dribbles always offered); ``rules`` must call fouls."""

    task_name = "attack-drill-ssl"

    def __init__(self, dribble_mask_m: float | None = DRIBBLE_MASK_M, **kwargs: Any) -> None:
        self.dribble_mask_m = check_dribble_mask_m(dribble_mask_m, type(self).__name__)
        rules = kwargs.setdefault("rules", AttackRules(fouls=True))
        if not rules.fouls:
            raise ValueError(f"{type(self).__name__}: rules must call fouls (AttackRules(fouls=True)), got {rules!r}")
        kwargs.setdefault("passing", SSL_DRILL_PASSING)
        super().__init__(**kwargs)


class AttackDrillDefendedEnv(AttackDrillSSLEnv):
    """The attack drill under SSL rules against the match's defence (module docstring). Arguments
    as :class:`AttackDrillSSLEnv` (``rules`` default: fouls called, a contested ball plays on) plus
    ``n_defence``: the defence's robots, goalie included (3-6, default 6: a 6v6 team's defence; the
    defense play fills goalie, presser, the two defenders, then the marks)."""

    task_name = "attack-drill-defended"

    def __init__(self, n_defence: int = MAX_DEFENCE, **kwargs: Any) -> None:
        if isinstance(n_defence, bool) or not isinstance(n_defence, (int, np.integer)) or not 3 <= n_defence <= MAX_DEFENCE:
            raise ValueError(f"{type(self).__name__}: n_defence must be an integer 3-{MAX_DEFENCE} (goalie "
                             f"included), got {n_defence!r}")
        self.n_defence = int(n_defence)
        kwargs.setdefault("rules", AttackRules(fouls=True, contested_plays_on=True))
        super().__init__(**kwargs)

    def defence_plays_factory(self) -> Any:
        return match_defence_plays


class HandcodedAttackDrillPolicy(HandcodedCarrierPolicy):
    """The attacking plays' cost decision as an attack-drill policy (module docstring)."""

    def choose(self, env: Any, request: CarrierRequest) -> tuple[int, bool]:
        ctx = request.ctx
        ours = ctx.world.team(ctx.team)
        d = decide_attack(ctx.ball, request.carrier, ours.pos, ctx.opp_pos, ctx.field, ctx.robot, request.ball,
                          env.decider.request_params(request), candidates=request.candidates,
                          heading=request.heading)
        option = attack_decision_option(d, ctx.world, ctx.team, request.carrier)
        return option, option == DRIBBLE_GOAL_OPTION


__all__ = ["AttackDrillEnv", "AttackDrillSSLEnv", "AttackDrillDefendedEnv", "match_defence_plays", "AttackOptionsMixin",
           "SSL_DRILL_PASSING", "HandcodedAttackDrillPolicy", "DrillAttackDecider", "drill_attacking_plays", "DRILL_PASSING"]
