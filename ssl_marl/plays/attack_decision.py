"""The attacking carrier's choice: shot, flat pass, chip pass, pass into a redirect, or dribble.

Team frame (own goal at -x, opponent goal at +x), metres, seconds, m/s, rad. Pure
functions of positions, built on :mod:`ssl_marl.plays.pass_decision` (its interception
times, path margins, shot value and pass value). Every option's value is
*success probability x value of the result*:

* **Shot**: ``shot_value(p)`` of :mod:`~ssl_marl.plays.pass_decision` (the open goal
  interval seen from the ball, the shot path's interception margin, the distance to
  the goal); its success and value are folded into one number in [0, 1].
* **Flat pass** to teammate ``k`` at ``q``: ``P_flat * result(q)`` with ``P_flat`` the
  pass success of :func:`~ssl_marl.plays.pass_decision.evaluate_passes` and
  ``result(q) = w_receiver_shot * shot_value(q) + w_progress * progress + w_possession``
  (:func:`~ssl_marl.plays.pass_decision.receive_value`).
* **Chip pass** to ``k``: ``P_chip * chip_receive_factor * result(q)``, offered only
  where the hand-coded chip-pass skill kicks a chip to ``q``: the chip is the skill's
  (:func:`ssl_marl.skills.chip_pass.lane_chip`: :func:`~ssl_marl.skills.chip_pass.chip_kick`
  over the lane's blocker, the opponent nearest the lane or an imagined robot midway,
  first touchdown past the blocker's body and short of the receiver), so the option's
  speed and elevation are what the play's chip-pass skill kicks; where no chip fits,
  no chip option. Drag-free projectile (:mod:`ssl_marl.physics.ball_flight`: first
  touchdown after ``2 v^2 sin a cos a / g``). ``P_chip`` maps the chip path's margin
  like a flat pass: along the path, the ball's lowest point is at
  ``z(s) = s tan a - g s^2 / (2 v_h^2)`` before the touchdown (the ball passes over a
  robot where ``z > robot height``, 0.15 m; SSL rules, "Robot shape") and rolls and
  hops low after it (horizontal speed ``v_h`` times the first bounce's
  ``bounce_damping_xy_first``). Only samples where the ball is at most ``robot height``
  high can be intercepted; the margin is the smallest ``t_opp - t_ball`` over those
  samples and all opponents, so a chip is safe when it flies over the blockers and
  lands where no opponent reaches first. ``chip_receive_factor`` (< 1) prices the
  harder reception of a hopping ball.
* **Pass into a redirect** (one-touch shot) to ``k``: ``P_redirect * f_redirect(delta) *
  w_redirect * shot_value(q)``. ``P_redirect`` is the flat pass success of a pass kicked
  to arrive at ``redirect_arrive_speed`` (the speed the passer kicks it at: a firmer ball
  than a flat pass, so less time for the opponents to cut the lane). ``delta`` is the
  deflection at ``q``: the angle between
  the direction back to the passer and the direction to the aim point in ``q``'s open
  goal interval (0: the ball goes straight back). ``f_redirect`` is 1 up to 0.9 rad,
  falls linearly to 0 at 1.2 rad (TIGERs' redirect rating, Sumatra
  ``RedirectBallSkill``; docs/references.md, "Passing and pass rating"). A one-touch shot
  gives the goalie no time to set, so ``w_redirect`` (1) exceeds ``w_receiver_shot``.
* **Dribble** (keep): :func:`~ssl_marl.plays.pass_decision.keep_value` (falls to 0 as
  an opponent closes in).

**Decision** (:func:`decide_attack`), the rule of :func:`~ssl_marl.plays.pass_decision.decide`
with more pass kinds: shot value >= ``shoot_threshold`` -> SHOOT; else the best option
among flat, chip and redirect passes with success >= ``min_pass_success`` and value >=
max(shot, keep) + ``pass_gain`` -> that pass; else DRIBBLE while the keep value is at
least ``min_keep`` and the shot is below ``shoot_fallback``, otherwise SHOOT.
"""

from __future__ import annotations

import dataclasses
import enum
import math
from dataclasses import dataclass, field

import numpy as np

from ..physics.ball_flight import flight_height
from ..physics.field import FieldGeometry
from ..physics.params import BallParams, RobotParams
from ..skills.chip_pass import lane_chip
from .shot_lines import best_shot_line
from .pass_decision import (Choice, DecisionParams, choose, evaluate_passes, keep_value, margin_success,
                            open_goal_interval, opponent_reach_time, pass_candidates, receive_value, shot_value,
                            teammates_except)


class AttackChoice(enum.Enum):
    SHOOT = "shoot"
    PASS = "pass"
    CHIP = "chip"
    REDIRECT = "redirect"
    DRIBBLE = "dribble"


@dataclass(frozen=True)
class AttackParams:
    """Parameters of the attack decision (module docstring).

    Attributes:
        decision: the shared shot / pass / keep parameters (thresholds, weights).
        chip_samples: samples along a chip path for its margin.
        chip_receive_factor: value factor of a hopping ball's reception.
        chip_arrive_speed: the chip rated (and kicked by a set piece's passer) is one the
            receiver can take on its dribbler, no faster than this (m/s) at its face
            (:func:`~ssl_marl.skills.chip_pass.chip_kick`'s ``arrive_speed_max``); None: the
            shortest-flight chip, which may still hop above the dribbler bar there.
        restart_chip_arrive_speed: ``chip_arrive_speed`` of set pieces; None:
            ``chip_arrive_speed``. Read by :class:`~ssl_marl.plays.attack_play.AttackDecider`
            for restart requests.
        redirect_full, redirect_zero: deflection (rad) up to which a redirect is fully
            useful / beyond which it is useless (TIGERs: 0.9 / 1.2).
        w_redirect: weight of the receiver's shot value in a pass into a redirect.
        restart_w_redirect: ``w_redirect`` of set pieces (kickoff and free kicks, where the
            defence stands 0.5 m off the ball until the kick); None: ``w_redirect``. Read by
            :class:`~ssl_marl.plays.attack_play.AttackDecider` for restart requests.
        min_redirect_shot: a redirect needs at least this receiver shot value.
        redirect_arrive_speed: a pass into a redirect is kicked, and its success rated, to
            arrive this fast (m/s; a firm ball for the kicker to meet).
        reach_shot_s: SHOOT also when, within ``reach_shot_max_m`` of the goal centre, the
            best shot line (:func:`~ssl_marl.plays.shot_lines.best_shot_line`: the line the
            goalie and defenders reach last) has a margin of at least this (s), whatever the
            open goal interval; None: off (the shot value alone).
        reach_shot_max_m: see ``reach_shot_s`` (m).
    """

    decision: DecisionParams = field(default_factory=DecisionParams)
    chip_samples: int = 24
    chip_receive_factor: float = 0.8
    chip_arrive_speed: float | None = None
    restart_chip_arrive_speed: float | None = None
    redirect_full: float = 0.9
    redirect_zero: float = 1.2
    w_redirect: float = 1.0
    restart_w_redirect: float | None = None
    min_redirect_shot: float = 0.2
    redirect_arrive_speed: float = 2.5
    reach_shot_s: float | None = None
    reach_shot_max_m: float = 3.5

    def __post_init__(self) -> None:
        if not 0.0 <= self.redirect_full < self.redirect_zero:
            raise ValueError("AttackParams.redirect_full must be >= 0 and smaller than redirect_zero")
        if not (isinstance(self.chip_samples, int) and self.chip_samples >= 2):
            raise ValueError(f"AttackParams.chip_samples must be an integer >= 2, got {self.chip_samples!r}")
        weights = {"w_redirect": self.w_redirect}
        if self.restart_w_redirect is not None:
            weights["restart_w_redirect"] = self.restart_w_redirect
        for name, w in weights.items():
            if not (isinstance(w, (int, float)) and math.isfinite(w) and w >= 0):
                raise ValueError(f"AttackParams.{name} must be a finite weight >= 0, got {w!r}")
        for name in ("chip_arrive_speed", "restart_chip_arrive_speed"):
            v = getattr(self, name)
            if v is not None and not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise ValueError(f"AttackParams.{name} must be None or a finite speed > 0 (m/s), got {v!r}")
        r = self.reach_shot_s
        if r is not None and not (isinstance(r, (int, float)) and math.isfinite(r)):
            raise ValueError(f"AttackParams.reach_shot_s must be None or a finite margin (s), got {r!r}")
        m = self.reach_shot_max_m
        if not (isinstance(m, (int, float)) and math.isfinite(m) and m > 0):
            raise ValueError(f"AttackParams.reach_shot_max_m must be a positive finite distance (m), got {m!r}")


@dataclass(frozen=True)
class AttackOption:
    """One evaluated pass of any kind.

    kind: PASS, CHIP or REDIRECT; teammate: receiver index; point: receive point (m);
    kick_speed: 3-D kick speed (m/s); chip_angle: elevation (rad, 0 flat); success: P
    in [0, 1]; value: success x value of the result; aim: redirect aim point on the goal
    line (m) or None; deflection: the redirect's deflection (rad, 0 for other kinds).
    """

    kind: AttackChoice
    teammate: int
    point: np.ndarray
    kick_speed: float
    chip_angle: float
    success: float
    value: float
    aim: np.ndarray | None = None
    deflection: float = 0.0


@dataclass(frozen=True)
class AttackDecision:
    """The carrier's choice with its evidence: shot and keep values, all options, the chosen one."""

    choice: AttackChoice
    shot: float
    keep: float
    options: tuple[AttackOption, ...] = ()
    best: AttackOption | None = None


# ------------------------------------------------------------------ chip
def chip_margin(start: np.ndarray, end: np.ndarray, speed: float, angle: float, opponents: np.ndarray,
                rp: RobotParams, bp: BallParams, params: DecisionParams, samples: int = 24) -> float:
    """Smallest ``t_opp - t_ball`` (s) over the samples of the chip path ``start -> end``
    where the ball is no higher than the robots (module docstring); inf without such
    opponents."""
    start, end = np.asarray(start, float), np.asarray(end, float)
    opp = np.asarray(opponents, float).reshape(-1, 2)
    length = float(np.hypot(*(end - start)))
    if opp.shape[0] == 0 or length < 1e-6:
        return math.inf
    vh, vv = speed * math.cos(angle), speed * math.sin(angle)
    t_land = 2.0 * vv / bp.gravity
    d_land = vh * t_land
    s = np.linspace(params.skip_near_m, length, samples)
    in_air = s < d_land
    t_air = s / vh
    z = flight_height(s, speed, angle, bp.gravity)
    v_after = vh * bp.bounce_damping_xy_first
    t_ball = np.where(in_air, t_air, t_land + (s - d_land) / max(v_after, 1e-6))
    reachable = ~in_air | (z <= rp.height)
    if not reachable.any():
        return math.inf
    u = (end - start) / length
    pts = start[None, :] + s[reachable, None] * u[None, :]
    t_opp = opponent_reach_time(opp, pts, rp, bp, params)
    return float((t_opp - t_ball[reachable][None, :]).min())


def evaluate_chips(p: np.ndarray, receive_points: dict[int, np.ndarray], teammates: np.ndarray,
                   opponents: np.ndarray, field_geom: FieldGeometry, rp: RobotParams, bp: BallParams,
                   params: AttackParams) -> tuple[AttackOption, ...]:
    """Chip passes from ``p`` to each ``{teammate: point}`` where the hand-coded chip-pass
    skill kicks one (module docstring)."""
    dp = params.decision
    p = np.asarray(p, float)
    opp = np.asarray(opponents, float).reshape(-1, 2)
    mates = np.asarray(teammates, float).reshape(-1, 2)
    out = []
    for k, q, _ in pass_candidates(p, receive_points, 0.0, dp.max_pass_m, field_geom, dp.receive_margin_m):
        kick = lane_chip(p, q, opp, rp, bp, arrive_speed_max=params.chip_arrive_speed)
        if kick is None:
            continue
        margin = chip_margin(p, q, kick.speed, kick.angle, opp, rp, bp, dp, params.chip_samples)
        success = margin_success(margin, dp)
        result = receive_value(p, q, shot_value(q, opp, teammates_except(mates, k), field_geom, rp, bp, dp), dp)
        out.append(AttackOption(AttackChoice.CHIP, int(k), q, kick.speed, kick.angle, success,
                                float(success * params.chip_receive_factor * result)))
    return tuple(out)


# -------------------------------------------------------------- redirect
def redirect_factor(deflection: float, full: float = 0.9, zero: float = 1.2) -> float:
    """1 up to ``full`` rad of deflection, linearly to 0 at ``zero`` rad, 0 beyond."""
    return float(min(max((zero - abs(deflection)) / (zero - full), 0.0), 1.0))


def redirect_geometry(q: np.ndarray, ball_from: np.ndarray, obstacles: np.ndarray, field_geom: FieldGeometry,
                      rp: RobotParams, bp: BallParams) -> tuple[np.ndarray, float, float]:
    """(aim point on the goal line (m), deflection (rad), open angle (rad)) of a redirect
    at ``q`` of a ball coming from ``ball_from``: the aim is the centre of ``q``'s widest
    open goal interval."""
    q, src = np.asarray(q, float), np.asarray(ball_from, float)
    open_angle, aim_dir = open_goal_interval(q, obstacles, field_geom, rp, bp)
    dx = field_geom.half_length - float(q[0])
    aim = q + np.array([dx, dx * math.tan(aim_dir)])
    back = math.atan2(src[1] - q[1], src[0] - q[0])
    return aim, abs(math.remainder(aim_dir - back, 2.0 * math.pi)), open_angle


def evaluate_redirects(p: np.ndarray, flat: tuple, teammates: np.ndarray, opponents: np.ndarray,
                       field_geom: FieldGeometry, rp: RobotParams, bp: BallParams,
                       params: AttackParams) -> tuple[AttackOption, ...]:
    """Passes into a redirect from the flat passes ``flat``
    (:class:`~ssl_marl.plays.pass_decision.PassOption`, rated at ``redirect_arrive_speed``:
    their kick speed and success, module docstring)."""
    opp = np.asarray(opponents, float).reshape(-1, 2)
    mates = np.asarray(teammates, float).reshape(-1, 2)
    out = []
    for o in flat:
        others = teammates_except(mates, o.teammate)
        aim, deflection, _ = redirect_geometry(o.point, p, np.concatenate([opp, others]), field_geom, rp, bp)
        f = redirect_factor(deflection, params.redirect_full, params.redirect_zero)
        if f <= 0.0 or o.receiver_shot < params.min_redirect_shot:
            continue
        out.append(AttackOption(AttackChoice.REDIRECT, o.teammate, o.point, o.kick_speed, 0.0, o.success,
                                float(o.success * f * params.w_redirect * o.receiver_shot), aim, deflection))
    return tuple(out)


# -------------------------------------------------------------- decision
def evaluate_attack_passes(p: np.ndarray, carrier: int, teammates: np.ndarray, opponents: np.ndarray,
                           field_geom: FieldGeometry, rp: RobotParams, bp: BallParams, params: AttackParams,
                           candidates: tuple[int, ...], heading: float | None = None) -> tuple[AttackOption, ...]:
    """Every pass of every kind from ``p`` to the ``candidates`` (teammate indices;
    the carrier is skipped): the flat passes, then the chips, then the passes into a
    redirect (module docstring; ``heading`` as in :func:`decide_attack`)."""
    p = np.asarray(p, float)
    mates = np.asarray(teammates, float).reshape(-1, 2)
    opp = np.asarray(opponents, float).reshape(-1, 2)
    points = {k: mates[k] for k in candidates if k != carrier}
    dp = params.decision
    flat = evaluate_passes(p, points, mates, opp, field_geom, rp, bp, dp, heading)
    options = tuple(AttackOption(AttackChoice.PASS, o.teammate, o.point, o.kick_speed, 0.0, o.success, o.value)
                    for o in flat)
    options += evaluate_chips(p, points, mates, opp, field_geom, rp, bp, params)
    if params.redirect_arrive_speed != dp.pass_arrive_speed:  # a redirect's pass is kicked to arrive firmer
        flat = evaluate_passes(p, points, mates, opp, field_geom, rp, bp,
                               dataclasses.replace(dp, pass_arrive_speed=params.redirect_arrive_speed), heading)
    return options + evaluate_redirects(p, flat, mates, opp, field_geom, rp, bp, params)


def reach_shot(p: np.ndarray, mates: np.ndarray, carrier: int, opp: np.ndarray, field_geom: FieldGeometry,
               rp: RobotParams, bp: BallParams, params: AttackParams) -> bool:
    """``params.reach_shot_s``'s rule: the best shot line from ``p`` has at least that margin (s)."""
    if params.reach_shot_s is None or float(np.hypot(*(field_geom.goal_center(+1) - p))) > params.reach_shot_max_m:
        return False
    _, margin = best_shot_line(p, opp, np.delete(mates, carrier, axis=0), field_geom, rp, bp, params.decision)
    return margin >= params.reach_shot_s


def decide_attack(p: np.ndarray, carrier: int, teammates: np.ndarray, opponents: np.ndarray,
                  field_geom: FieldGeometry, rp: RobotParams | None = None, bp: BallParams | None = None,
                  params: AttackParams | None = None, candidates: tuple[int, ...] | None = None,
                  heading: float | None = None) -> AttackDecision:
    """The carrier's choice (module docstring). ``p``: ball (2,); ``teammates`` (n, 2)
    own robots (the carrier at index ``carrier``); ``opponents`` (O, 2); ``candidates``:
    teammates a pass may go to (default all but the carrier); ``heading``: the carrier's
    heading (rad; flat passes needing a long turn lose margin)."""
    rp, bp, params = rp or RobotParams(), bp or BallParams(), params or AttackParams()
    dp = params.decision
    p = np.asarray(p, float)
    mates = np.asarray(teammates, float).reshape(-1, 2)
    opp = np.asarray(opponents, float).reshape(-1, 2)
    if not 0 <= carrier < len(mates):
        raise ValueError(f"decide_attack: carrier index {carrier} outside the {len(mates)} teammates")
    shot = shot_value(p, opp, np.delete(mates, carrier, axis=0), field_geom, rp, bp, dp)
    keep = keep_value(p, opp, rp, bp, dp)
    if shot >= dp.shoot_threshold or reach_shot(p, mates, carrier, opp, field_geom, rp, bp, params):
        return AttackDecision(AttackChoice.SHOOT, shot, keep)
    cands = candidates if candidates is not None else tuple(k for k in range(len(mates)) if k != carrier)
    options = evaluate_attack_passes(p, carrier, mates, opp, field_geom, rp, bp, params, cands, heading)
    choice, best = choose(shot, keep, options, dp)
    kind = {Choice.PASS: best.kind if best else None, Choice.SHOOT: AttackChoice.SHOOT,
            Choice.KEEP: AttackChoice.DRIBBLE}[choice]
    return AttackDecision(kind, shot, keep, options, best)


__all__ = ["AttackChoice", "AttackParams", "AttackOption", "AttackDecision", "chip_margin",
           "evaluate_chips", "redirect_factor", "redirect_geometry", "evaluate_redirects",
           "evaluate_attack_passes", "reach_shot", "decide_attack"]
