"""The attacking plays: shot, flat pass, chip pass, pass into a redirect, or dribble, and
supports on rated spots.

:func:`attack_plays` builds what :func:`~ssl_marl.plays.passing_play.passing_plays`
builds (a shared :class:`~ssl_marl.plays.pass_coordinator.PassCoordinator` with its
pass/receive handshake; restart, offense and defense plays) with three changes:

* the carrier decides with :class:`AttackDecider` (the cost functions of
  :mod:`~ssl_marl.plays.attack_decision`; a chip is an option only where the
  hand-coded chip-pass skill kicks one); a flat, chip or redirect pass opens the
  coordinator's pass plan, the chosen option is remembered for the roles;
* the ``passer`` role runs :class:`~ssl_marl.plays.chip_pass_tactic.ChipPass` (for a
  chosen chip the chip-pass skill, which picks the chip's speed and elevation itself;
  else the pass skill) and the ``receiver`` role
  :class:`~ssl_marl.plays.redirect_tactic.Redirect` (for a pass into a redirect the
  redirect skill takes the incoming ball on to the goal, else an ordinary reception);
* the supports stand on spots rated by :mod:`~ssl_marl.plays.spot_rating` (re-rated
  every ``rate_every`` ticks, one spot per support role, greedy so that no two share a
  spot or a lane) with :class:`~ssl_marl.plays.spot_support_tactic.SpotSupport`;
* the marks (in attack and in the defense play) stand on the marked opponent's line to
  our goal centre (``ball_bias`` 0 instead of 0.25 towards the ball): 0.35 m in front of
  it a marker shadows the whole goal mouth, so it blocks the opponent's one-touch
  redirect and its shot after a reception;
* the attacker waits outside the opponent's defense area while the ball is in it
  (``keep_out_of_opp_area``; touching the ball there is a foul, a free kick for the
  opponents), as it waits outside our own;
* restarts are set pieces under SSL game control (``decide_at_restart``): the kick is
  decided before the kicker reaches the ball and the passer walks up behind the ball on
  the pass line (``approach_behind``) and kicks it from there without the dribbler
  (``strike``: the set piece's kicker may not stay in contact with the ball); a set
  piece with no pass opened the attacker takes with one kick
  (:class:`~ssl_marl.plays.set_piece_kick.SetPieceKick`); a set piece's pass goes to a
  receive point at least 0.6 m inside the field lines (:data:`ATTACK_RESTART_DECISION`).

The coordinator's setup check of the flat lane is off (``abort_margin_s = -inf``): a
chip is chosen exactly when the flat lane is blocked.

The tactics emit the env's 6-entry chip actions (index 5 the chip), the inherited ones
5 entries; the team plays only in an env built with ``chip_kicks=True`` (the match
runner builds one when a team needs it and pads 5-entry actions with a flat chip entry).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from ..physics.params import BallParams
from .assignment import Assignment
from .attack_decision import AttackChoice, AttackDecision, AttackOption, AttackParams, decide_attack
from .chip_pass_tactic import ChipPass
from .pass_coordinator import RESTART_DECISION, CarrierDecider, CarrierRequest, PassCoordinator, PassingParams, PassPlan
from .pass_decision import Choice, Decision, PassOption
from .passing_play import restart_applicable
from .passing_roles import passer_role, passing_attacker_role, receiver_role
from .play import (OPTIONAL_ROLE_UNFILLED_COST, Play, PlayContext, RoleDef, defender_role, defense_play, goalie_role,
                   mark_role, offense_applicable, wall_role)
from .receive_tactic import ReceiveState
from .redirect_tactic import Redirect
from .spot_rating import SpotParams, assign_spots, candidate_grid
from .spot_support_tactic import SpotSupport
from .tactic_base import Tactic

#: the attacking team's pass plan: no setup abort on the flat lane (chips go over it);
#: restarts are set pieces (decided before the kicker reaches the ball); a pass whose
#: ball lies dead after the kick is dropped at once; a pressed passer does not wait for the
#: receiver's READY: an opponent within 0.6 m of the ball or on it turns the setup urgent
#: (``press_urgent_m``, ``contested_kick``; 20 tuning matches against the no-pass baseline,
#: seeds 61500-61519: 23-7 goals and 403 passes tried against 17-11 and 292 without;
#: docs/RESULTS.md, section 12, "What limits scoring")
#: A committed dribble (a learned decider's) is decided again once the carrier has dribbled
#: 0.8 m (``dribble_cut_m``; SSL's limit is 1 m; the cost decision commits to nothing).
#: The attacker waits outside the opponent's defense area while the ball is in it
#: (``keep_out_of_opp_area``: touching it there is a foul; 12 SSL-format tuning matches against the
#: no-pass baseline, seeds 61790-61801: 2.1 such fouls per match against 5.7, the same 17-5 goals;
#: docs/RESULTS.md, section 13, "Fouls in the opponent's defense area").
#: A set piece's pass goes to a receive point at least 0.6 m inside the field lines
#: (``receive_margin_m``; open play keeps 0.15 m): a free kick lies 0.2 m inside the side line after
#: the ball left the field, and the supports' outer spots 0.3 m inside it. Three self-play tuning
#: matches of the clone (seeds 60900-60902): 75.8 % of passes completed against 69.6 % with 0.15 m
#: (23 intercepted against 37); 20 held-out matches: 73.3 % (docs/RESULTS.md, section 15, "Set-piece
#: passes off the side line").
ATTACK_RESTART_DECISION = dataclasses.replace(RESTART_DECISION, receive_margin_m=0.6)
ATTACK_PASSING = PassingParams(abort_margin_s=-math.inf, decide_at_restart=True, set_piece_shot=True, dead_ball_s=0.6,
                               contested_kick=True, press_urgent_m=0.6, dribble_cut_m=0.8, keep_out_of_opp_area=True,
                               restart_decision=ATTACK_RESTART_DECISION)
#: the attacking plays' second defender plays only while at least this many opponents stand in our
#: half (team frame x < 0) or the ball lies there, else its robot takes the next role (a support);
#: None or 0: always (read when the plays are built). With 2: six SSL-format tuning matches against the
#: no-pass baseline (seeds 61884-61889) 18-2 goals against 14-1 with the second defender always on, then
#: 20 held-out matches (108270-108289) 65-7, where the team as it plays scored 67-5 on seeds
#: 108220-108239: no gain shown, so it stays off (docs/RESULTS.md, section 15, "A second defender
#: only against a threat").
ATTACK_DEFENDER_1_OPPONENTS: int | None = None
#: the attacking team's decision parameters (chip, redirect; an :class:`AttackDecider` built
#: without parameters reads them when it is built)
ATTACK_PARAMS = AttackParams()
#: the supports' spot rating (a :class:`SpotPlanner` built without parameters reads it when built)
ATTACK_SPOTS = SpotParams()
#: the marks' turn towards the ball (``MarkParams.ball_bias``; 0: on the marked opponent's line to
#: our goal centre, module docstring), in attack and in the defense play; read when the plays are built
ATTACK_MARK_BIAS = 0.0


def set_piece_value(open_play: float | None, set_piece: float | None, restart: bool) -> float | None:
    """An :class:`AttackParams` value and its set-piece override (``restart_*``, None: unset):
    the override at a restart where set, else the open-play value."""
    return set_piece if restart and set_piece is not None else open_play


@dataclass
class AttackCounters:
    """Decisions taken (for tests, reports and debugging): shots, flat passes, chips,
    redirects, dribbles, and passes into a redirect whose receiver ended CONTROLLED
    (it kicked the ball on, or fetched a ball that stopped short)."""

    shoot: int = 0
    pass_: int = 0
    chip: int = 0
    redirect: int = 0
    dribble: int = 0
    redirected: int = 0

    def count(self, choice: AttackChoice) -> None:
        """One more decision of kind ``choice``."""
        name = "pass_" if choice is AttackChoice.PASS else choice.value
        setattr(self, name, getattr(self, name) + 1)


class AttackDecider:
    """:class:`~ssl_marl.plays.pass_coordinator.CarrierDecider` of the attacking plays:
    :func:`~ssl_marl.plays.attack_decision.decide_attack` on the request, answered as a
    :class:`~ssl_marl.plays.pass_decision.Decision` (any pass kind -> PASS, dribble ->
    KEEP); the chosen pass (or a keep's best eligible pass, which an expired keep may turn
    into: ``PassingParams.keep_expiry``) stays in :attr:`option` for the passer and
    receiver roles."""

    def __init__(self, params: AttackParams | None = None) -> None:
        self.params = params or ATTACK_PARAMS
        self.option: AttackOption | None = None
        self.last: AttackDecision | None = None
        self.counters = AttackCounters()

    def request_params(self, request: CarrierRequest) -> AttackParams:
        """The attack decision's parameters for ``request``: ``params`` with the request's
        decision parameters (open play or restart) and, at a restart, the set pieces'
        redirect weight and chip (``AttackParams.restart_w_redirect``,
        ``restart_chip_arrive_speed``, where set)."""
        p, restart = self.params, request.restart
        return dataclasses.replace(p, decision=request.params,
                                   w_redirect=set_piece_value(p.w_redirect, p.restart_w_redirect, restart),
                                   chip_arrive_speed=set_piece_value(p.chip_arrive_speed, p.restart_chip_arrive_speed,
                                                                     restart))

    def decide(self, request: CarrierRequest) -> Decision:
        ctx = request.ctx
        ours = ctx.world.team(ctx.team)
        d = decide_attack(ctx.ball, request.carrier, ours.pos, ctx.opp_pos, ctx.field, ctx.robot, request.ball,
                          self.request_params(request), candidates=request.candidates, heading=request.heading)
        self.last = d
        self.counters.count(d.choice)
        if d.choice in (AttackChoice.PASS, AttackChoice.CHIP, AttackChoice.REDIRECT) and d.best is not None:
            choice = Choice.PASS
        else:
            choice = Choice.SHOOT if d.choice is AttackChoice.SHOOT else Choice.KEEP
        if choice is Choice.SHOOT or d.best is None:
            return Decision(choice, d.shot, d.keep)
        # a pass, or a keep with its best eligible pass (the pass an expired keep may become)
        self.option = b = d.best
        best = PassOption(b.teammate, b.point, b.kick_speed, 0.0, b.success, 0.0, b.value)
        return Decision(choice, d.shot, d.keep, (best,), best)


class SpotPlanner:
    """The supports' rated spots, re-rated every ``rate_every`` ticks (module docstring)."""

    def __init__(self, n_spots: int = 4, rate_every: int = 6, params: SpotParams | None = None,
                 ball: BallParams | None = None) -> None:
        self.n_spots, self.rate_every, self.params = n_spots, rate_every, params or ATTACK_SPOTS
        self.bp = ball or BallParams()
        self.reset()

    def reset(self) -> None:
        """Forget the spots (a new episode: the next :meth:`update` rates them)."""
        self.spots: np.ndarray | None = None
        self._tick = 0

    def update(self, ctx: PlayContext) -> None:
        self._tick += 1
        if self.spots is not None and self._tick % self.rate_every != 0:
            return
        grid = candidate_grid(ctx.field, ctx.ball, self.params)
        self.spots = assign_spots(self.n_spots, grid, ctx.ball, ctx.opp_pos, ctx.field, ctx.robot, self.bp,
                                  self.params)


@dataclass(frozen=True)
class AttackPrepare:
    """``Play.prepare`` of the attacking plays: the coordinator's tick, then the spots."""

    coordinator: PassCoordinator
    planner: SpotPlanner
    restart: bool = False

    def reset(self) -> None:
        """A new episode: the coordinator's plan and the spots are forgotten."""
        self.coordinator.reset()
        self.planner.reset()

    def __call__(self, ctx: PlayContext) -> None:
        dec, recv = self.coordinator.decider, ctx.role_status.get("receiver")
        o = _plan_option(self.coordinator, dec) if isinstance(dec, AttackDecider) else None
        if o is not None and o.kind is AttackChoice.REDIRECT and recv is not None \
                and recv.state is ReceiveState.CONTROLLED:
            dec.counters.redirected += 1  # the receiver kicked the ball on (its last tick's state)
        self.coordinator.prepare(ctx, restart=self.restart)
        self.planner.update(ctx)


def _plan_option(coord: PassCoordinator, decider: AttackDecider) -> AttackOption | None:
    plan, o = coord.plan, decider.option
    return o if plan is not None and o is not None and o.teammate == plan.receiver else None


def chip_passer_role(coord: PassCoordinator, decider: AttackDecider, priority: int = 95) -> RoleDef:
    """:func:`~ssl_marl.plays.passing_roles.passer_role` with
    :class:`~ssl_marl.plays.chip_pass_tactic.ChipPass`: a chosen chip runs the chip-pass
    skill (which picks the chip's speed and elevation); a flat pass arrives at the
    decision's ``pass_arrive_speed`` (the speed its success was rated at), a pass into a
    redirect at ``redirect_arrive_speed``."""

    def extra(ctx: PlayContext, plan: PassPlan) -> dict:
        o = _plan_option(coord, decider)
        redirect = o is not None and o.kind is AttackChoice.REDIRECT
        decision = coord.params.restart_decision if plan.restart else coord.params.decision
        arrival = decider.params.redirect_arrive_speed if redirect else decision.pass_arrive_speed
        return dict(chip=o is not None and o.kind is AttackChoice.CHIP, approach_behind=plan.restart,
                    strike=plan.restart, arrival_speed=arrival,
                    chip_arrive_speed=set_piece_value(decider.params.chip_arrive_speed,
                                                      decider.params.restart_chip_arrive_speed, plan.restart))

    return passer_role(coord, priority, ChipPass, extra)


def redirect_receiver_role(coord: PassCoordinator, decider: AttackDecider, priority: int = 94) -> RoleDef:
    """:func:`~ssl_marl.plays.passing_roles.receiver_role` with
    :class:`~ssl_marl.plays.redirect_tactic.Redirect`: for a pass into a redirect, the aim
    point of the one-touch shot; otherwise an ordinary reception."""

    def extra(ctx: PlayContext, plan: PassPlan) -> dict:
        o = _plan_option(coord, decider)
        aim = o.aim if o is not None and o.kind is AttackChoice.REDIRECT else None
        return dict(redirect_target=None if aim is None else (float(aim[0]), float(aim[1])))

    return receiver_role(coord, priority, Redirect, extra)


def spot_support_role(k: int, planner: SpotPlanner, priority: int) -> RoleDef:
    def target(ctx: PlayContext) -> np.ndarray | None:
        if planner.spots is None or k >= len(planner.spots):
            return None
        return planner.spots[k]

    def update(t: Tactic, ctx: PlayContext, a: Assignment) -> None:
        if planner.spots is not None and k < len(planner.spots):
            s = planner.spots[k]
            t.set_params(spot=(float(s[0]), float(s[1])))

    return RoleDef(f"support_{k}", priority, SpotSupport, target, update=update,
                   unfilled_cost=OPTIONAL_ROLE_UNFILLED_COST)


def threat_defender_role(k: int, priority: int, min_opponents: int | None) -> RoleDef:
    """:func:`~ssl_marl.plays.play.defender_role` that plays only while at least
    ``min_opponents`` opponents stand in our half (team frame x < 0) or the ball lies there
    (an optional role otherwise unfilled); None or 0: always, the defender role itself."""
    base = defender_role(k, priority)
    if not min_opponents:
        return base

    def target(ctx: PlayContext) -> np.ndarray | None:
        if float(ctx.ball[0]) < 0.0 or int(np.count_nonzero(ctx.opp_pos[:, 0] < 0.0)) >= min_opponents:
            return base.target(ctx)
        return None

    return dataclasses.replace(base, target=target, unfilled_cost=OPTIONAL_ROLE_UNFILLED_COST)


def attack_roles(coord: PassCoordinator, decider: AttackDecider, planner: SpotPlanner,
                 mark_bias: float | None = None) -> tuple[RoleDef, ...]:
    """The roles of the attacking plays, in priority order (as the passing plays');
    ``mark_bias``: the marks' ``ball_bias`` (None: :data:`ATTACK_MARK_BIAS`); the second
    defender per :data:`ATTACK_DEFENDER_1_OPPONENTS`."""
    b = ATTACK_MARK_BIAS if mark_bias is None else mark_bias
    return (goalie_role(100), chip_passer_role(coord, decider, 95), redirect_receiver_role(coord, decider, 94),
            passing_attacker_role(coord, 90, aim_open_goal=True), wall_role(0, 85), defender_role(0, 80),
            spot_support_role(0, planner, 80), wall_role(1, 75), spot_support_role(1, planner, 70),
            threat_defender_role(1, 70, ATTACK_DEFENDER_1_OPPONENTS),
            mark_role(0, 60, ball_bias=b), spot_support_role(2, planner, 60), mark_role(1, 50, ball_bias=b),
            defender_role(2, 50), spot_support_role(3, planner, 40), mark_role(2, 40, ball_bias=b))


def attack_plays(params: PassingParams | None = None, ball: BallParams | None = None,
                 decider: CarrierDecider | None = None, attack: AttackParams | None = None) -> tuple[Play, ...]:
    """(restart, offense_attack, defense) sharing one coordinator (module docstring).
    ``decider``: an :class:`AttackDecider` (default: a new one with ``attack``); the
    coordinator runs with ``params`` (default :data:`ATTACK_PASSING`)."""
    if decider is not None and not isinstance(decider, AttackDecider):
        raise ValueError(f"attack_plays: the carrier decision must be an AttackDecider, got {type(decider).__name__}")
    dec = decider or AttackDecider(attack)
    coord = PassCoordinator(params or ATTACK_PASSING, ball, dec)
    planner = SpotPlanner(ball=ball)
    roles = attack_roles(coord, dec, planner)

    def offense_attack_applicable(ctx: PlayContext) -> bool:
        return coord.active or offense_applicable(ctx)

    restart = Play("restart", restart_applicable, roles, priority=1, prepare=AttackPrepare(coord, planner, True))
    offense = Play("offense_attack", offense_attack_applicable, roles, prepare=AttackPrepare(coord, planner))
    return (restart, offense, defense_play(mark_ball_bias=ATTACK_MARK_BIAS))


def attack_decider_of(plays) -> AttackDecider | None:
    """The :class:`AttackDecider` of an :func:`attack_plays` tuple (None for other plays)."""
    for p in plays:
        c = getattr(p.prepare, "coordinator", None)
        if c is not None and isinstance(c.decider, AttackDecider):
            return c.decider
    return None


__all__ = ["ATTACK_PASSING", "ATTACK_RESTART_DECISION", "ATTACK_PARAMS", "ATTACK_SPOTS", "ATTACK_MARK_BIAS", "AttackCounters", "AttackDecider", "SpotPlanner",
           "AttackPrepare", "chip_passer_role", "threat_defender_role", "ATTACK_DEFENDER_1_OPPONENTS",
           "redirect_receiver_role", "spot_support_role", "attack_roles", "attack_plays", "attack_decider_of"]
