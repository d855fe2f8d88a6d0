"""The team's pass plan: one :class:`PassCoordinator` per team, shared by the passing plays' roles.

The passing plays (:func:`~ssl_marl.plays.passing_play.passing_plays`) call
:meth:`PassCoordinator.prepare` once per tick (``Play.prepare``) and read the plan in
their roles (:mod:`ssl_marl.plays.passing_roles`). The handshake runs through the roles'
reported :class:`~ssl_marl.plays.tactic_base.TacticStatus` in the
:class:`~ssl_marl.plays.play.PlayContext` (``ctx.role_status``), never through tactic
internals:

1. **Decide** (no plan, a field player of ours holds the ball and runs the
   ``attacker`` role in a settled state, KEEP or AIM_TO_SHOOT): every ``decide_every`` ticks
   the carrier decider rates shoot / pass to teammate k / keep.
   SHOOT and KEEP go to the attacker as ``hold_fire`` (KEEP for at most ``max_keep_s``,
   then it shoots); PASS opens a plan: passer = the carrier, receiver = k, receive point
   = k's position.
2. **Set up** (plan phase SETUP): role ``passer`` (:class:`~ssl_marl.plays.pass_tactic.Pass`)
   goes to the carrier, role ``receiver`` (:class:`~ssl_marl.plays.receive_tactic.Receive`)
   to teammate k (both by cost: 0 for the designated robot, prohibitive for others);
   the attacker role is dropped. The receiver moves to the receive point facing the
   ball; the passer holds the ball and turns; ``receiver_ready`` is passed to the passer
   once the receiver reports READY, and only then does the passer kick.
3. **In flight** (the passer reports DONE): the receiver's RECEIVING state runs the
   receive skill (onto the predicted ball line, cushion); the passer stands.
4. **End**: receiver CONTROLLED, or the ball on the receiver's dribbler for
   ``control_s`` (0.1 s: TIGERs call a reception successful 0.1 s after the ball
   reaches the dribbler; the receive skill's own 0.5 s hold would let the defence
   re-form before the receiver can shoot) -> completed; receiver FAILED, passer FAILED, an
   opponent on the ball (with ``contested_kick``, during setup only once the passer has
   lost it: while both dribblers touch the ball the plan turns *urgent* and the passer
   kicks as soon as it faces the receive point, without waiting for READY), a setup
   longer than ``max_setup_s``, a flight longer than ``max_flight_s``, or (during setup)
   a pass lane that became unsafe -> aborted. The
   attacker role returns; after a completed pass the receiver, now nearest the ball,
   takes it.

**The decider hook.** Step 1's choice is made by the coordinator's
:class:`CarrierDecider` (``PassCoordinator(decider=...)``, ``passing_plays(decider=...)``):
``decide(request: CarrierRequest) -> Decision``. The default, :class:`CostDecider`, is
the cost decision (:func:`~ssl_marl.plays.pass_decision.decide`). Any other decider (the
learned attack decision, :mod:`ssl_marl.decisions.match_decider`) gets the same request
(context, carrier, pass candidates, parameters, restart flag) and answers with a
:class:`~ssl_marl.plays.pass_decision.Decision`; its optional ``dribble_to`` /
``dribble_speed`` steer the attacker's KEEP and ``commit_s`` holds the decision for a
while (module :mod:`~ssl_marl.plays.pass_decision`, ``Decision``). The plays import
nothing of the decider's package: the hook is this protocol.
"""

from __future__ import annotations

import dataclasses
import enum
import math
from dataclasses import dataclass
from typing import Protocol, runtime_checkable

import numpy as np

from ..physics.params import BallParams
from .pass_decision import Choice, Decision, DecisionParams, decide, path_margin, pass_kick_speed
from .pass_tactic import PassState
from .play import PlayContext
from .receive_tactic import ReceiveState
from .set_piece_kick import KEEP_CHOICE_M, SHOT_OPEN_MIN_RAD, set_piece_shot_interval
from .shoot import ShootParams, ShootState

#: attacker states in which the ball is settled on the dribbler and a decision is made
SETTLED = (ShootState.KEEP, ShootState.AIM_TO_SHOOT)
#: what an expired KEEP turns into (``PassingParams.keep_expiry``)
KEEP_EXPIRY = ("shoot", "pass")

#: Restarts: keep is worth nothing and shots must be clearly open, so the kicker passes.
RESTART_DECISION = DecisionParams(w_keep=0.0, shoot_threshold=0.6, shoot_fallback=0.6, pass_gain=0.0,
                                  min_pass_success=0.5)


class PassPhase(enum.Enum):
    SETUP = "setup"
    IN_FLIGHT = "in_flight"


@dataclass
class PassPlan:
    """The team's current pass: passer and receiver robot indices, receive point (m),
    phase, start and kick times (s); ``urgent``: an opponent contests the ball, so the
    passer kicks without waiting for the receiver's READY; ``restart``: a set piece
    planned before the passer reached the ball; ``spent``: the passer has dribbled the
    ball ``dribble_cut_m`` (:class:`PassingParams`), so it kicks without the READY and
    however fast it moves (a pressed passer is pushed along with the ball)."""

    passer: int
    receiver: int
    point: np.ndarray
    phase: PassPhase
    t_start: float
    t_kick: float | None = None
    urgent: bool = False
    restart: bool = False
    spent: bool = False


@dataclass(frozen=True)
class PassingParams:
    """Attributes:
        decision: the open-play decision parameters.
        restart_decision: the decision parameters at restarts.
        decide_every: ticks between two decisions (a decision costs ~1-2 ms).
        max_keep_s: KEEP at most this long, then shoot (s; see ``keep_expiry``).
        keep_expiry: what an expired KEEP turns into: "shoot" (a shot whatever its value)
            or "pass" (the decision's best eligible pass, success >= ``min_pass_success``,
            when the shot is worth less than ``shoot_fallback``; else the shot).
        keep_shot_max_m: an expired KEEP turns into a shot (or pass) only with the ball
            within this distance of the opponent goal centre (m); farther out the carrier
            keeps dribbling until the decision itself shoots or passes (a pressed carrier
            still shoots: ``min_keep``); None: at any distance.
        keep_tap_m: the attacker taps the ball ahead during a keep once it lies this far
            from where its touch began (:class:`~ssl_marl.plays.shoot.ShootParams`,
            ``keep_tap_m``: SSL's dribbling limit is 1 m); None: off.
        max_setup_s: a pass not kicked within this is dropped (s).
        max_flight_s: a pass not controlled this long after the kick is dropped (s).
        abort_margin_s: during setup, drop the pass if its path margin falls below this (s).
        cooldown_s: after a dropped pass, no new pass for this long (s).
        settle_s: the attacker's drive-forward duration in the passing plays (s; the
            paper's 1 s lets defenders settle, the passing game moves on faster).
        control_s: the ball on the receiver's dribbler this long completes the pass (s).
        snap_shot: the attacker kicks as soon as its heading lies between the posts
            (:class:`~ssl_marl.plays.shoot.ShootParams`, ``snap_shot``).
        aim_reach: the attacker aims its shots at the line the opponents reach last
            (:class:`~ssl_marl.plays.shoot.ShootParams`, ``aim_reach``).
        decide_at_restart: at the referee's kickoff or free kick for us (``ctx.set_piece``:
            the opponents keep 0.5 m until it is taken; the restart play's
            ``prepare(restart=True)``) decide before anyone holds the ball: the
            kicker is the robot on the ``attacker`` role (else our field robot nearest the
            ball), the request says ``on_ball=False``, a pass plan opens at once and its
            passer walks up behind the ball on the pass line (a set piece). False: decide
            only once a carrier has settled the ball, as in open play.
        max_restart_setup_s: a set piece's pass not kicked within this is dropped (s; it
            includes the walk to the ball).
        set_piece_wait_s: a set piece's passer waits at most this long (s, from the plan)
            for the receiver's READY, then the plan turns urgent (it kicks once it faces
            the receive point).
        set_piece_shot: with ``decide_at_restart``, a set piece whose ball sees the goal
            open for a shot (:func:`~ssl_marl.plays.set_piece_kick.set_piece_shot_interval`
            at least ``SHOT_OPEN_MIN_RAD`` wide, judged until the kicker is within
            ``KEEP_CHOICE_M`` of the ball) is shot: no pass plan opens and the attacker's
            set-piece kick takes it (it shoots at the open goal). False: the decider alone
            chooses (its restart parameters shoot only a shot worth ``shoot_threshold``).
        dead_ball_s: in flight, a ball slower than 0.1 m/s this long (s) after the kick
            while the receiver neither receives nor fetches it drops the plan (the kick
            did not leave, or the pass died on the way); None: wait ``max_flight_s``.
        contested_kick: during setup, an opponent's dribbler on the ball while the passer
            still holds it does not drop the pass: the plan turns urgent and the passer
            kicks as soon as it faces the receive point, without the receiver's READY.
            Off (drop the pass): on 60 tuning matches against the no-pass baseline
            (seeds 45200-45259) it completed fewer passes by the referee's count (52 % vs
            56 %) and scored 11-2 against 17-3 without it (docs/RESULTS.md, "Passing
            game"), although 9 of 11 setups in probe matches were dropped this way.
        press_urgent_m: during an open-play setup, an opponent centre within this of the
            ball (m) turns the plan urgent: the passer kicks as soon as it faces the
            receive point, before the opponent reaches the ball (the receiver meets the
            ball on its line while it runs); None: off.
        dribble_cut_m: a decision committed for a while (a learned decider's dribble,
            ``Decision.commit_s``) is taken again once the carrier has dribbled the ball
            this far (m, :attr:`~ssl_marl.plays.play.PlayContext.dribbled_m`, as the
            referee measures it; SSL's limit is 1 m), so a committed dribble cannot run
            into the excessive-dribbling foul, and an open-play pass setup whose passer has
            dribbled this far is *spent* (:class:`PassPlan`: the passer kicks as soon as it
            faces the receive point, without the receiver's READY and however fast it moves:
            in matches such passers are mostly pushed along by an opponent); None: off.
        keep_out_of_opp_area: the attacker waits outside the opponent's defense area while
            the ball is in it (:class:`~ssl_marl.plays.shoot.ShootParams`,
            ``keep_out_of_opp_defense_area``: touching the ball there is a foul, a free kick
            for the opponents); False: it goes for the ball there too.
    """

    decision: DecisionParams = DecisionParams()
    restart_decision: DecisionParams = RESTART_DECISION
    decide_every: int = 3
    max_keep_s: float = 0.8
    keep_expiry: str = "shoot"
    keep_shot_max_m: float | None = None
    keep_tap_m: float | None = None
    max_setup_s: float = 2.5
    max_flight_s: float = 4.0
    abort_margin_s: float = -0.05
    cooldown_s: float = 0.5
    settle_s: float = 0.5
    control_s: float = 0.1
    snap_shot: bool = True
    aim_reach: bool = False
    contested_kick: bool = False
    decide_at_restart: bool = False
    max_restart_setup_s: float = 5.0
    set_piece_wait_s: float = 2.0
    set_piece_shot: bool = False
    dead_ball_s: float | None = None
    press_urgent_m: float | None = None
    dribble_cut_m: float | None = None
    keep_out_of_opp_area: bool = False

    def __post_init__(self) -> None:
        if self.keep_expiry not in KEEP_EXPIRY:
            raise ValueError(f"PassingParams.keep_expiry must be one of {KEEP_EXPIRY}, got {self.keep_expiry!r}")
        for name in ("press_urgent_m", "keep_shot_max_m", "keep_tap_m", "dribble_cut_m"):
            m = getattr(self, name)
            if m is not None and not (isinstance(m, (int, float)) and math.isfinite(m) and m > 0):
                raise ValueError(f"PassingParams.{name} must be None or a positive finite distance (m), got {m!r}")


@dataclass
class PassCounters:
    """What the coordinator saw (for tests and debugging): plans opened, kicked,
    completed, aborted."""

    planned: int = 0
    kicked: int = 0
    completed: int = 0
    aborted: int = 0


@dataclass(frozen=True)
class CarrierRequest:
    """What a :class:`CarrierDecider` is asked, once the carrier has settled the ball.

    Attributes:
        ctx: the tick's play context (team frame: own goal at -x).
        carrier: the carrier's robot index.
        candidates: teammates a pass may go to (empty during the cooldown after a dropped pass).
        params: the decision parameters of the moment (open play or restart).
        restart: the ball is at a restart (kickoff, free kick).
        ball: ball parameters (for the ball model).
        t: simulated time (s).
        on_ball: the carrier holds the ball (False: a set piece decided before the
            kicker reached it, so its heading says nothing about the kick).
    """

    ctx: PlayContext
    carrier: int
    candidates: tuple[int, ...]
    params: DecisionParams
    restart: bool
    ball: BallParams
    t: float
    on_ball: bool = True

    @property
    def heading(self) -> float | None:
        """The carrier's heading (rad, team frame) while it holds the ball, else None."""
        return float(self.ctx.world.team(self.ctx.team).heading[self.carrier]) if self.on_ball else None


@runtime_checkable
class CarrierDecider(Protocol):
    """The carrier's shoot / pass / keep (dribble) decision (module docstring, "the decider hook")."""

    def decide(self, request: CarrierRequest) -> Decision:
        ...


class CostDecider:
    """The default decider: the documented cost decision
    (:func:`~ssl_marl.plays.pass_decision.decide`) on the request."""

    def decide(self, request: CarrierRequest) -> Decision:
        ctx = request.ctx
        ours = ctx.world.team(ctx.team)
        return decide(ctx.ball, request.carrier, ours.pos, ctx.opp_pos, ctx.field, ctx.robot, request.ball,
                      request.params, candidates=request.candidates, heading=request.heading)


class PassCoordinator:
    """Team-level pass plan shared by the passing plays' roles (module docstring).
    ``decider``: the carrier's decision (default :class:`CostDecider`)."""

    def __init__(self, params: PassingParams | None = None, ball: BallParams | None = None,
                 decider: CarrierDecider | None = None) -> None:
        self.params = params or PassingParams()
        self.bp = ball or BallParams()
        if decider is not None and not callable(getattr(decider, "decide", None)):
            raise TypeError(f"PassCoordinator: decider must have a decide(request) method, got {decider!r}")
        self.decider: CarrierDecider = decider if decider is not None else CostDecider()
        self.reset()

    def reset(self) -> None:
        self.plan: PassPlan | None = None
        self.decision: Decision | None = None
        self.counters = PassCounters()
        self._tick = 0
        self._last_t: float | None = None
        self._cooldown_until = -math.inf
        self._keep_since: float | None = None
        self._carrier: int | None = None
        self._recv_on_since: float | None = None
        self._commit_until = -math.inf
        self._set_piece_shot = False

    @property
    def active(self) -> bool:
        return self.plan is not None

    def hold_fire(self) -> bool:
        """The attacker holds the ball (KEEP) unless the current decision is SHOOT (so
        that it never shoots before a decision was made)."""
        d = self.decision
        return d is None or d.choice is not Choice.SHOOT

    def keep_target(self) -> tuple[float, float] | None:
        """Where a KEEP decision dribbles to (None: the opponent goal centre)."""
        d = self.decision
        if d is None or d.choice is not Choice.KEEP or d.dribble_to is None:
            return None
        return (float(d.dribble_to[0]), float(d.dribble_to[1]))

    def keep_speed(self) -> float:
        """KEEP's forward speed (m/s): the decision's ``dribble_speed``, else the attacker's default."""
        d = self.decision
        if d is None or d.choice is not Choice.KEEP or d.dribble_speed is None:
            return ShootParams.keep_speed
        return float(d.dribble_speed)

    # ----------------------------------------------------------------- tick
    def prepare(self, ctx: PlayContext, restart: bool = False) -> None:
        t = float(ctx.world.t)
        if self._last_t is not None and t < self._last_t:  # new episode
            self.reset()
        self._last_t = t
        self._tick += 1
        if not ctx.set_piece:
            self._set_piece_shot = False
        if self.plan is not None:
            self._follow(ctx, t)
        if self.plan is None:
            self._decide(ctx, t, restart)

    def _drop(self, t: float, completed: bool = False) -> None:
        if completed:
            self.counters.completed += 1
        else:
            self.counters.aborted += 1
            self._cooldown_until = t + self.params.cooldown_s
        self.plan = None
        self.decision = None
        self._keep_since = None
        self._recv_on_since = None
        self._commit_until = -math.inf

    def _follow(self, ctx: PlayContext, t: float) -> None:
        plan, p = self.plan, self.params
        passer = ctx.role_status.get("passer")
        receiver = ctx.role_status.get("receiver")
        on = plan.phase is PassPhase.IN_FLIGHT and bool(ctx.world.team(ctx.team).ball_on_dribbler[plan.receiver])
        self._recv_on_since = (self._recv_on_since if self._recv_on_since is not None else t) if on else None
        if (receiver is not None and receiver.state is ReceiveState.CONTROLLED) or (
                self._recv_on_since is not None and t - self._recv_on_since >= p.control_s - 1e-9):
            self._drop(t, completed=True)
            return
        if receiver is not None and receiver.state is ReceiveState.FAILED:
            self._drop(t)
            return
        if ctx.they_have_ball:
            ours = ctx.world.team(ctx.team).ball_on_dribbler
            if not (plan.phase is PassPhase.SETUP and p.contested_kick and bool(ours[plan.passer])):
                self._drop(t)
                return
            plan.urgent = True  # contested: both dribblers on the ball, the passer kicks once it faces the lane
        if plan.phase is PassPhase.SETUP:
            if passer is not None and passer.state is PassState.DONE:
                plan.phase, plan.t_kick = PassPhase.IN_FLIGHT, t
                self.counters.kicked += 1
                return
            if plan.restart and t - plan.t_start > p.set_piece_wait_s:
                plan.urgent = True
            if not plan.restart and p.press_urgent_m is not None and len(ctx.opp_pos) and float(
                    np.min(np.hypot(*(ctx.opp_pos - ctx.ball).T))) < p.press_urgent_m:
                plan.urgent = True
            if not plan.restart and self._dribble_spent(ctx, plan.passer):
                plan.urgent = plan.spent = True  # the passer kicks before SSL's 1 m limit
            max_setup = p.max_restart_setup_s if plan.restart else p.max_setup_s
            if (passer is not None and passer.state is PassState.FAILED) or t - plan.t_start > max_setup:
                self._drop(t)
                return
            if self._tick % p.decide_every == 0 and not (passer is not None and passer.state is PassState.KICK):
                length = float(np.hypot(*(plan.point - ctx.ball)))
                v0 = pass_kick_speed(length, self.bp, ctx.robot, p.decision)
                if path_margin(ctx.ball, plan.point, v0, ctx.opp_pos, ctx.robot, self.bp, p.decision,
                               receiver=ctx.our_pos[plan.receiver]) < p.abort_margin_s:
                    self._drop(t)
            return
        if t - (plan.t_kick or t) > p.max_flight_s:
            self._drop(t)
            return
        if p.dead_ball_s is not None and t - (plan.t_kick or t) > p.dead_ball_s \
                and float(np.hypot(*ctx.world.ball_vel)) < 0.1 \
                and not (receiver is not None and receiver.state in (ReceiveState.RECEIVING, ReceiveState.FETCH)):
            self._drop(t)

    def _decide(self, ctx: PlayContext, t: float, restart: bool) -> None:
        p = self.params
        ours = ctx.world.team(ctx.team)
        holders = [int(i) for i in np.flatnonzero(ours.ball_on_dribbler) if i in ctx.field_robots]
        if not holders and restart and p.decide_at_restart and ctx.set_piece:
            kicker = self._restart_kicker(ctx)
            if kicker is not None:
                if self.decision is None or self._tick % p.decide_every == 0:
                    if p.set_piece_shot and self._set_piece_shot_open(ctx, kicker):
                        self.decision = None
                        return  # the attacker's set-piece kick shoots
                    self._request(ctx, t, kicker, restart=True, on_ball=False)
                return
        if not holders:
            self.decision = None
            self._keep_since = None
            self._carrier = None
            self._commit_until = -math.inf
            return
        carrier = int(holders[0])
        attacker = ctx.role_status.get("attacker")
        if ctx.role_holders.get("attacker") != carrier or attacker is None or attacker.state not in SETTLED:
            if attacker is None or attacker.state not in SETTLED + (ShootState.DRIVE_FORWARD,):
                self.decision, self._keep_since = None, None  # a new possession: decide afresh
                self._commit_until = -math.inf
            return  # decide once the carrier has settled the ball (not while it drives or fetches)
        if carrier != self._carrier:
            self._carrier, self._keep_since, self.decision = carrier, None, None
            self._commit_until = -math.inf
        committed = t < self._commit_until - 1e-9 and not self._dribble_spent(ctx, carrier)
        if self.decision is not None and (self._tick % p.decide_every != 0 or committed):
            return
        self._request(ctx, t, carrier, restart)

    def _dribble_spent(self, ctx: PlayContext, carrier: int) -> bool:
        """``dribble_cut_m``'s rule: the carrier has dribbled the ball at least that far."""
        m, dribbled = self.params.dribble_cut_m, ctx.dribbled_m
        return m is not None and dribbled is not None and float(dribbled[carrier]) >= m

    def _keep_may_expire(self, ctx: PlayContext) -> bool:
        """``keep_shot_max_m``'s rule: the ball is near enough to the opponent goal (team frame)."""
        m = self.params.keep_shot_max_m
        return m is None or float(np.hypot(*(ctx.ball - ctx.field.goal_center(+1)))) <= m

    def _set_piece_shot_open(self, ctx: PlayContext, kicker: int) -> bool:
        """``set_piece_shot``'s rule: the goal is open for a shot from the ball, as judged
        while the kicker is farther than ``KEEP_CHOICE_M`` from the ball; nearer, the
        judgement stands (the set-piece kick keeps its choice there too)."""
        near = float(np.hypot(*(ctx.our_pos[kicker] - ctx.ball))) < KEEP_CHOICE_M
        if not near:
            open_angle, _ = set_piece_shot_interval(ctx.ball, kicker, ctx.our_pos, ctx.opp_pos, ctx.field,
                                                    ctx.robot, self.bp)
            self._set_piece_shot = open_angle >= SHOT_OPEN_MIN_RAD
        return self._set_piece_shot

    def _restart_kicker(self, ctx: PlayContext) -> int | None:
        """The set piece's kicker: the ``attacker`` role's robot, else our field robot
        nearest the ball (None without field robots)."""
        k = ctx.role_holders.get("attacker")
        if k in ctx.field_robots:
            return int(k)
        field_robots = list(ctx.field_robots)
        if not field_robots:
            return None
        d = np.hypot(*(ctx.our_pos[field_robots] - ctx.ball).T)
        return field_robots[int(np.argmin(d))]

    def _request(self, ctx: PlayContext, t: float, carrier: int, restart: bool, on_ball: bool = True) -> None:
        """Ask the decider and act on its answer (keep clock, plan)."""
        p = self.params
        params = p.restart_decision if restart else p.decision
        cands = tuple(k for k in ctx.field_robots if k != carrier)
        if t < self._cooldown_until:
            cands = ()
        d = self.decider.decide(CarrierRequest(ctx, carrier, cands, params, restart, self.bp, t, on_ball))
        if not isinstance(d, Decision):
            raise TypeError(f"PassCoordinator: the decider {type(self.decider).__name__} returned "
                            f"{type(d).__name__}, expected a Decision")
        self._commit_until = t + float(d.commit_s) if d.commit_s > 0 else -math.inf
        if not on_ball:  # a set piece: only a pass opens; shot and keep wait for the carrier
            self._keep_since = None
        elif d.choice is Choice.KEEP and d.commit_s > 0:
            self._keep_since = None
        elif d.choice is Choice.KEEP:
            if self._keep_since is None:
                self._keep_since = t
            if t - self._keep_since > p.max_keep_s and self._keep_may_expire(ctx):
                to_pass = (p.keep_expiry == "pass" and d.best_pass is not None
                           and d.shot < params.shoot_fallback)
                d = dataclasses.replace(d, choice=Choice.PASS if to_pass else Choice.SHOOT)
        else:
            self._keep_since = None
        self.decision = d
        if d.choice is Choice.PASS and d.best_pass is not None:
            self.plan = PassPlan(carrier, d.best_pass.teammate, np.asarray(d.best_pass.point, float),
                                 PassPhase.SETUP, t, restart=not on_ball)
            self.counters.planned += 1


__all__ = ["CarrierRequest", "CarrierDecider", "CostDecider", "PassPhase", "PassPlan", "PassingParams",
           "PassCoordinator", "PassCounters", "RESTART_DECISION", "SETTLED"]
