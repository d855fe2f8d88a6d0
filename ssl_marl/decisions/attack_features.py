"""The attack decision's observation, options and legal-option mask: pure functions of the world.

One set of functions serves the Attack 3v2 drill (:mod:`ssl_marl.decisions.attack`) and
full matches (:mod:`ssl_marl.decisions.match_decider`), so a policy trained in the drill
sees exactly the same features when it plays a match.

Everything is in the attacking team's frame (own goal at -x, opponent goal at +x),
metres, seconds, m/s. ``world`` is a team-frame :class:`~ssl_marl.physics.state.WorldState`
(``world.frame == team``), e.g. ``env.vision_state(team)``.

**Who is who.** ``me`` is the robot whose observation this is (the carrier when it
decides). Its two teammate slots (:func:`teammate_slots`) are the two field players
other than ``me`` (robot 0 is the goalie when the team has >= 2 robots, the project's
convention, and never a slot) with the largest x (most advanced), ordered by y, larger
y (left, seen attacking +x) first. In the 3v2 drill these are simply the two other
attackers; in a 6v6 match the two most advanced field players. The two opponent slots
(:func:`opponent_slots`) are the *goalie* (the opponent nearest the goal we attack) and
the *defender* (of the others, the one nearest the ball). Opponents outside the slots
(matches) still count in the cost features (shot value, pass success, keep value).

**Observation** (:data:`ATTACK_OBS_DIM` = 40 float32 values, clipped to
``[-OBS_BOUND, OBS_BOUND]``; positions / (L/2, W/2), robot velocities / 3 m/s, ball
velocity / 6.5 m/s):

====  =====================================================================
0-5   me: x, y, cos(heading), sin(heading), vx, vy
6-10  ball: x, y, vx, vy, 1 if the ball is on my dribbler else 0
11-15 goal, seen from the ball: distance to the goal centre / (L/2), bearing
      of the goal centre / pi, widest open goal angle / 0.5 rad
      (:func:`~ssl_marl.plays.pass_decision.open_goal_interval`, teammates and
      opponents shadow), shot value from the ball
      (:func:`~ssl_marl.plays.pass_decision.shot_value`), keep value / w_keep
      (pressure, :func:`~ssl_marl.plays.pass_decision.keep_value`)
16-29 two teammate slots x 7: present, x, y, vx, vy, pass success P from the
      ball to its position (:func:`~ssl_marl.plays.pass_decision.evaluate_passes`,
      my heading's turn time included; 0 where the pass is not a candidate), its
      shot value there
30-39 two opponent slots (goalie, defender) x 5: x, y, vx, vy, its reach
      time to the ball / 2 s (:func:`~ssl_marl.plays.pass_decision.opponent_reach_time`)
====  =====================================================================

Absent slots are zeros. Cost-feature parameters are the passing play's open-play
:class:`~ssl_marl.plays.pass_decision.DecisionParams`.

**Options** (:data:`ATTACK_OPTIONS`): ``shoot``; ``pass_1`` / ``pass_2`` (to teammate
slot 1 / 2, at its position); ``dribble_goal`` / ``dribble_left`` / ``dribble_right``
(hold the ball and dribble towards the goal centre / towards a point 1.0 m ahead and
1.2 m to the left / right of the ball, kept 0.3 m inside the field, for
:data:`DRIBBLE_COMMIT_S` at :data:`DRIBBLE_SPEED`). Why these three points: towards
goal is the cost play's KEEP (progress, a better angle); the two diagonals move the
carrier out of the defender's lane (which opens a shot or a pass lane) while still
gaining ground; three keeps the action space small. A committed decision holds until
it is executed (shoot: until the kick, ``SHOOT_COMMIT_S`` at most; a pass runs the
passing play's handshake).

**Mask** (:func:`attack_action_mask`): shoot and the dribbles are always legal; a pass
is legal iff its slot has a robot, that robot is a pass candidate (not during the
passing play's cooldown after a dropped pass) and the pass is a candidate of
:func:`~ssl_marl.plays.pass_decision.evaluate_passes` (length 1-6 m, receive point in
the field and outside both defense areas).
"""

from __future__ import annotations

import math
from typing import Sequence

import numpy as np

from ..physics.field import FieldGeometry
from ..physics.params import BallParams, RobotParams
from ..physics.state import WorldState
from ..plays.pass_decision import (Choice, Decision, DecisionParams, evaluate_passes, keep_value,
                                   open_goal_interval, opponent_reach_time, shot_value)

#: option names, in action-index order
ATTACK_OPTIONS: tuple[str, ...] = ("shoot", "pass_1", "pass_2", "dribble_goal", "dribble_left", "dribble_right")
N_ATTACK_OPTIONS = len(ATTACK_OPTIONS)
SHOOT, PASS_1, PASS_2, DRIBBLE_GOAL, DRIBBLE_LEFT, DRIBBLE_RIGHT = range(N_ATTACK_OPTIONS)
ATTACK_OBS_DIM = 40
OBS_BOUND = 5.0
N_MATE_SLOTS = 2
MATE_FEATURES = 7
OPP_FEATURES = 5

DRIBBLE_AHEAD_M = 1.0  # m: the side dribble points lie this far ahead of the ball ...
DRIBBLE_SIDE_M = 1.2  # m: ... and this far to the side
DRIBBLE_MARGIN_M = 0.3  # m: dribble points stay this far inside the field
DRIBBLE_SPEED = 0.5  # m/s: forward speed of a dribble option (the attacker's KEEP creeps at 0.3)
DRIBBLE_COMMIT_S = 0.6  # s: a dribble option runs this long before the next decision
SHOOT_COMMIT_S = 2.0  # s: a shot decision is held (the attacker aims and kicks) for at most this long
REACH_SCALE_S = 2.0


def teammate_slots(world: WorldState, team: str, me: int) -> tuple[int | None, int | None]:
    """The two teammate slots of robot ``me`` (module docstring): robot indices or None."""
    ours = world.team(team)
    field_players = [k for k in range(ours.n) if k != me and not (ours.n >= 2 and k == 0)]
    ahead = sorted(field_players, key=lambda k: (-float(ours.pos[k, 0]), k))[:N_MATE_SLOTS]
    ordered = sorted(ahead, key=lambda k: (-float(ours.pos[k, 1]), k))
    out = ordered + [None] * (N_MATE_SLOTS - len(ordered))
    return out[0], out[1]


def opponent_slots(world: WorldState, team: str, field: FieldGeometry) -> tuple[int | None, int | None]:
    """(goalie, defender) opponent indices (module docstring) or None."""
    opp = world.opponents(team)
    if opp.n == 0:
        return None, None
    d_goal = np.hypot(*(opp.pos - field.goal_center(+1)).T)
    goalie = int(np.argmin(d_goal))
    others = [k for k in range(opp.n) if k != goalie]
    if not others:
        return goalie, None
    d_ball = np.hypot(*(opp.pos[others] - world.ball_pos).T)
    return goalie, int(others[int(np.argmin(d_ball))])


def dribble_point(option: int, ball: np.ndarray, field: FieldGeometry) -> np.ndarray:
    """Target point (m) of a dribble option (module docstring)."""
    b = np.asarray(ball, float)
    if option == DRIBBLE_GOAL:
        return field.goal_center(+1).astype(float)
    if option not in (DRIBBLE_LEFT, DRIBBLE_RIGHT):
        raise ValueError(f"dribble_point: option {option} is not a dribble option")
    side = 1.0 if option == DRIBBLE_LEFT else -1.0
    q = b + np.array([DRIBBLE_AHEAD_M, side * DRIBBLE_SIDE_M])
    lim_x, lim_y = field.half_length - DRIBBLE_MARGIN_M, field.half_width - DRIBBLE_MARGIN_M
    return np.array([min(max(q[0], -lim_x), lim_x), min(max(q[1], -lim_y), lim_y)])


def _passes(world: WorldState, team: str, me: int, slots: Sequence[int | None], candidates: Sequence[int] | None,
            field: FieldGeometry, rp: RobotParams, bp: BallParams, params: DecisionParams) -> dict:
    ours = world.team(team)
    cands = set(range(ours.n)) if candidates is None else set(candidates)
    points = {k: ours.pos[k] for k in slots if k is not None and k in cands and k != me}
    if not points:
        return {}
    opts = evaluate_passes(world.ball_pos, points, ours.pos, world.opponents(team).pos, field, rp, bp, params,
                           heading=float(ours.heading[me]))
    return {o.teammate: o for o in opts}


def attack_observation(world: WorldState, team: str, me: int, field: FieldGeometry, rp: RobotParams | None = None,
                       bp: BallParams | None = None, params: DecisionParams | None = None,
                       candidates: Sequence[int] | None = None) -> np.ndarray:
    """(ATTACK_OBS_DIM,) float32 observation of robot ``me`` (module docstring).
    ``candidates``: teammates a pass may go to (None: all)."""
    if world.frame != team:
        raise ValueError(f"attack_observation: expected a snapshot in {team!r}'s frame, got {world.frame!r}")
    rp, bp, params = rp or RobotParams(), bp or BallParams(), params or DecisionParams()
    ours, opp = world.team(team), world.opponents(team)
    if not 0 <= me < ours.n:
        raise ValueError(f"attack_observation: robot {me} outside the team's {ours.n} robots")
    L2, W2 = field.half_length, field.half_width
    sv, bv = rp.max_speed, rp.kick_speed_max
    ball = np.asarray(world.ball_pos, float)
    o = np.zeros(ATTACK_OBS_DIM, np.float64)
    h = float(ours.heading[me])
    o[0:6] = (ours.pos[me, 0] / L2, ours.pos[me, 1] / W2, math.cos(h), math.sin(h),
              ours.vel[me, 0] / sv, ours.vel[me, 1] / sv)
    o[6:11] = (ball[0] / L2, ball[1] / W2, world.ball_vel[0] / bv, world.ball_vel[1] / bv,
               float(bool(ours.ball_on_dribbler[me])))
    others = np.delete(ours.pos, me, axis=0)
    g = field.goal_center(+1)
    open_angle, _ = open_goal_interval(ball, np.concatenate([opp.pos, others], axis=0), field, rp, bp)
    o[11] = float(np.hypot(*(g - ball))) / L2
    o[12] = math.atan2(g[1] - ball[1], g[0] - ball[0]) / math.pi
    o[13] = open_angle / 0.5
    o[14] = shot_value(ball, opp.pos, others, field, rp, bp, params)
    o[15] = keep_value(ball, opp.pos, rp, bp, params) / params.w_keep if params.w_keep > 0 else 0.0
    slots = teammate_slots(world, team, me)
    passes = _passes(world, team, me, slots, candidates, field, rp, bp, params)
    for j, k in enumerate(slots):
        if k is None:
            continue
        base = 16 + MATE_FEATURES * j
        p = passes.get(k)
        if p is not None:
            success, recv = p.success, p.receiver_shot
        else:
            success = 0.0
            recv = shot_value(ours.pos[k], opp.pos, np.delete(ours.pos, k, axis=0), field, rp, bp, params)
        o[base:base + MATE_FEATURES] = (1.0, ours.pos[k, 0] / L2, ours.pos[k, 1] / W2, ours.vel[k, 0] / sv,
                                        ours.vel[k, 1] / sv, success, recv)
    reach = opponent_reach_time(opp.pos, ball[None, :], rp, bp, params)[:, 0] if opp.n else np.zeros(0)
    for j, k in enumerate(opponent_slots(world, team, field)):
        if k is None:
            continue
        base = 16 + MATE_FEATURES * N_MATE_SLOTS + OPP_FEATURES * j
        o[base:base + OPP_FEATURES] = (opp.pos[k, 0] / L2, opp.pos[k, 1] / W2, opp.vel[k, 0] / sv,
                                       opp.vel[k, 1] / sv, float(reach[k]) / REACH_SCALE_S)
    return np.clip(np.nan_to_num(o, nan=0.0, posinf=OBS_BOUND, neginf=-OBS_BOUND), -OBS_BOUND,
                   OBS_BOUND).astype(np.float32)


def attack_action_mask(world: WorldState, team: str, me: int, field: FieldGeometry, rp: RobotParams | None = None,
                       bp: BallParams | None = None, params: DecisionParams | None = None,
                       candidates: Sequence[int] | None = None) -> np.ndarray:
    """(N_ATTACK_OPTIONS,) int8 legal options of carrier ``me`` (module docstring)."""
    rp, bp, params = rp or RobotParams(), bp or BallParams(), params or DecisionParams()
    mask = np.ones(N_ATTACK_OPTIONS, np.int8)
    slots = teammate_slots(world, team, me)
    passes = _passes(world, team, me, slots, candidates, field, rp, bp, params)
    for j, k in enumerate(slots):
        mask[PASS_1 + j] = int(k is not None and k in passes)
    return mask


def check_option(option: object, names: Sequence[str]) -> int:
    """``option`` as an int index into the option ``names``; ValueError naming it otherwise
    (bools, floats, NaN and out-of-range values included)."""
    if isinstance(option, (bool, np.bool_)) or not isinstance(option, (int, np.integer)) \
            or not 0 <= int(option) < len(names):
        raise ValueError(f"option must be an integer in 0..{len(names) - 1} {tuple(names)}, got {option!r}")
    return int(option)


def option_decision(option: int, world: WorldState, team: str, me: int, field: FieldGeometry,
                    rp: RobotParams | None = None, bp: BallParams | None = None,
                    params: DecisionParams | None = None, candidates: Sequence[int] | None = None) -> Decision:
    """The passing play's :class:`~ssl_marl.plays.pass_decision.Decision` for option
    ``option`` of carrier ``me`` (what the coordinator executes). ValueError for an
    option outside ``range(N_ATTACK_OPTIONS)`` or an illegal pass (check the mask first)."""
    rp, bp, params = rp or RobotParams(), bp or BallParams(), params or DecisionParams()
    option = check_option(option, ATTACK_OPTIONS)
    if option == SHOOT:
        return Decision(Choice.SHOOT, 0.0, 0.0, commit_s=SHOOT_COMMIT_S)
    if option in (PASS_1, PASS_2):
        k = teammate_slots(world, team, me)[option - PASS_1]
        passes = _passes(world, team, me, (k,), candidates, field, rp, bp, params)
        if k is None or k not in passes:
            raise ValueError(f"option {ATTACK_OPTIONS[option]!r} is not legal here (no such teammate, or the pass "
                             f"is not a candidate); check attack_action_mask first")
        best = passes[k]
        return Decision(Choice.PASS, 0.0, 0.0, (best,), best)
    return Decision(Choice.KEEP, 0.0, 0.0, dribble_to=dribble_point(option, world.ball_pos, field),
                    dribble_speed=DRIBBLE_SPEED, commit_s=DRIBBLE_COMMIT_S)


def decision_option(decision: Decision, world: WorldState, team: str, me: int) -> int:
    """The option index of a cost decision (the hand-coded policy): SHOOT -> shoot,
    PASS to teammate k -> the slot holding k (shoot if k holds no slot), KEEP ->
    dribble_goal (the attacker's KEEP turns and creeps towards the goal centre)."""
    if decision.choice is Choice.SHOOT:
        return SHOOT
    if decision.choice is Choice.PASS and decision.best_pass is not None:
        slots = teammate_slots(world, team, me)
        k = decision.best_pass.teammate
        return PASS_1 + slots.index(k) if k in slots else SHOOT
    return DRIBBLE_GOAL


__all__ = ["ATTACK_OPTIONS", "N_ATTACK_OPTIONS", "ATTACK_OBS_DIM", "OBS_BOUND", "SHOOT", "PASS_1", "PASS_2",
           "DRIBBLE_GOAL", "DRIBBLE_LEFT", "DRIBBLE_RIGHT", "DRIBBLE_SPEED", "DRIBBLE_COMMIT_S", "SHOOT_COMMIT_S",
           "teammate_slots", "opponent_slots", "dribble_point", "check_option", "attack_observation",
           "attack_action_mask", "option_decision", "decision_option"]
