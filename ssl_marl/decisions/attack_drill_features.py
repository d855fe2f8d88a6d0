"""The attacking plays' carrier decision as options: observation, legal-option mask, execution.

Pure functions of the world shared by the attack drill (:mod:`ssl_marl.decisions.attack_drill`)
and full matches (:class:`ssl_marl.decisions.match_decider.PolicyAttackDecider`), so a policy
trained in the drill sees the same features and plays the same options in a match.

Team frame (own goal at -x, opponent goal at +x), metres, seconds, m/s, rad. ``world`` is a
team-frame :class:`~ssl_marl.physics.state.WorldState`. Teammate and opponent slots are those of
:mod:`ssl_marl.decisions.attack_features` (the two most advanced field players other than the
carrier, larger y first; the goalie and the defender nearest the ball).

**Options** (:data:`ATTACK_DRILL_OPTIONS`, the carrier's choices of the attacking plays,
:mod:`ssl_marl.plays.attack_decision`): ``shoot``; ``pass_1`` / ``pass_2`` (flat pass to teammate
slot 1 / 2); ``chip_1`` / ``chip_2`` (chip pass over the lane, the decision's chip to that
slot); ``redirect_1`` / ``redirect_2`` (pass into a one-touch redirect at that slot, aimed at the
centre of its widest open goal interval); ``dribble_goal`` / ``dribble_left`` /
``dribble_right`` (as in :mod:`~ssl_marl.decisions.attack_features`: hold the ball and dribble
for 0.6 s at 0.5 m/s towards the goal centre or a point 1.0 m ahead and 1.2 m to the side).

**Mask** (:func:`attack_drill_mask`): shoot and the dribbles are always legal; a pass of a kind
to a slot is legal iff the attack decision's evaluation
(:func:`~ssl_marl.plays.attack_decision.evaluate_attack_passes`) has that kind of pass to that
slot's teammate: a flat pass needs a candidate lane (1-6 m, receive point in the field, outside
both defense areas, not during the cooldown after a dropped pass); a chip needs a chip that fits
the kicker cap and is at least ``min_chip_m`` long; a redirect needs a deflection below
``redirect_zero`` and a receiver shot value of at least ``min_redirect_shot``.

**Observation** (:data:`ATTACK_DRILL_OBS_DIM` = 48 float32 values in ``[-OBS_BOUND, OBS_BOUND]``):
the 40 values of :func:`~ssl_marl.decisions.attack_features.attack_observation`, then per teammate
slot (4 values x 2): the flat pass's value, the chip's success and value, the redirect's value
(the attack decision's ``success x value of the result``; 0 where that pass is not legal).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from ..physics.field import FieldGeometry
from ..physics.params import BallParams, RobotParams
from ..physics.state import WorldState
from ..plays.attack_decision import AttackChoice, AttackDecision, AttackOption, AttackParams, evaluate_attack_passes
from ..plays.pass_coordinator import CarrierRequest
from ..plays.pass_decision import Choice, Decision, PassOption
from .attack_features import (ATTACK_OBS_DIM, DRIBBLE_COMMIT_S, DRIBBLE_GOAL, DRIBBLE_LEFT, DRIBBLE_RIGHT,
                              DRIBBLE_SPEED, OBS_BOUND, SHOOT_COMMIT_S, attack_observation, check_option,
                              dribble_point, teammate_slots)

#: option names, in action-index order
ATTACK_DRILL_OPTIONS: tuple[str, ...] = ("shoot", "pass_1", "pass_2", "chip_1", "chip_2", "redirect_1",
                                         "redirect_2", "dribble_goal", "dribble_left", "dribble_right")
N_ATTACK_DRILL_OPTIONS = len(ATTACK_DRILL_OPTIONS)
SHOOT = 0
DRIBBLE_GOAL_OPTION = 7
#: option index -> (pass kind, teammate slot) for the six pass options
PASS_OPTIONS: dict[int, tuple[AttackChoice, int]] = {
    1: (AttackChoice.PASS, 0), 2: (AttackChoice.PASS, 1), 3: (AttackChoice.CHIP, 0), 4: (AttackChoice.CHIP, 1),
    5: (AttackChoice.REDIRECT, 0), 6: (AttackChoice.REDIRECT, 1)}
#: option index -> the dribble option of :mod:`~ssl_marl.decisions.attack_features` it runs
DRIBBLE_OPTIONS: dict[int, int] = {DRIBBLE_GOAL_OPTION: DRIBBLE_GOAL, 8: DRIBBLE_LEFT, 9: DRIBBLE_RIGHT}
SLOT_FEATURES = 4
ATTACK_DRILL_OBS_DIM = ATTACK_OBS_DIM + 2 * SLOT_FEATURES

SlotPasses = dict[tuple[AttackChoice, int], AttackOption]


def slot_passes(world: WorldState, team: str, me: int, field: FieldGeometry, rp: RobotParams, bp: BallParams,
                params: AttackParams, candidates: Sequence[int] | None = None) -> SlotPasses:
    """{(kind, slot): option} of every pass the attack decision evaluates from the ball to
    the teammates in carrier ``me``'s two slots (module docstring). ``candidates``:
    teammates a pass may go to (None: all)."""
    ours = world.team(team)
    slots = teammate_slots(world, team, me)
    allowed = set(range(ours.n)) if candidates is None else set(candidates)
    targets = tuple(k for k in slots if k is not None and k in allowed and k != me)
    if not targets:
        return {}
    opts = evaluate_attack_passes(world.ball_pos, me, ours.pos, world.opponents(team).pos, field, rp, bp, params,
                                  targets, heading=float(ours.heading[me]))
    return {(o.kind, slots.index(o.teammate)): o for o in opts}


def attack_drill_observation(world: WorldState, team: str, me: int, field: FieldGeometry, rp: RobotParams,
                             bp: BallParams, params: AttackParams, candidates: Sequence[int] | None = None,
                             passes: SlotPasses | None = None) -> np.ndarray:
    """(ATTACK_DRILL_OBS_DIM,) float32 observation of robot ``me`` (module docstring);
    ``passes``: :func:`slot_passes` when already computed."""
    base = attack_observation(world, team, me, field, rp, bp, params.decision, candidates=candidates)
    passes = slot_passes(world, team, me, field, rp, bp, params, candidates) if passes is None else passes
    extra = np.zeros(2 * SLOT_FEATURES, np.float64)
    for j in range(2):
        flat, chip = passes.get((AttackChoice.PASS, j)), passes.get((AttackChoice.CHIP, j))
        redirect = passes.get((AttackChoice.REDIRECT, j))
        extra[SLOT_FEATURES * j:SLOT_FEATURES * (j + 1)] = (
            flat.value if flat else 0.0, chip.success if chip else 0.0, chip.value if chip else 0.0,
            redirect.value if redirect else 0.0)
    return np.clip(np.concatenate([base, extra]), -OBS_BOUND, OBS_BOUND).astype(np.float32)


def request_features(request: CarrierRequest, params: AttackParams) -> tuple[SlotPasses, np.ndarray, np.ndarray]:
    """(:func:`slot_passes`, :func:`attack_drill_observation`, :func:`attack_drill_mask`) of
    the carrier of a play's decision ``request`` (its world, team, field, robot and ball
    parameters and candidates), with the attack decision's ``params``."""
    ctx = request.ctx
    args = (ctx.world, ctx.team, request.carrier, ctx.field, ctx.robot, request.ball, params)
    passes = slot_passes(*args, candidates=request.candidates)
    obs = attack_drill_observation(*args, candidates=request.candidates, passes=passes)
    return passes, obs, attack_drill_mask(passes)


def attack_drill_mask(passes: SlotPasses) -> np.ndarray:
    """(N_ATTACK_DRILL_OPTIONS,) int8 legal options given :func:`slot_passes` (module docstring)."""
    mask = np.ones(N_ATTACK_DRILL_OPTIONS, np.int8)
    for option, key in PASS_OPTIONS.items():
        mask[option] = int(key in passes)
    return mask


def option_play_decision(option: int, ball: np.ndarray, field: FieldGeometry,
                         passes: Mapping[tuple[AttackChoice, int], AttackOption]
                         ) -> tuple[Decision, AttackOption | None]:
    """(the pass coordinator's :class:`~ssl_marl.plays.pass_decision.Decision`, the chosen
    pass for the attacking plays' passer and receiver roles, or None) of ``option``.
    ValueError for an option outside the range or a pass that is not legal."""
    option = check_option(option, ATTACK_DRILL_OPTIONS)
    if option == SHOOT:
        return Decision(Choice.SHOOT, 0.0, 0.0, commit_s=SHOOT_COMMIT_S), None
    if option in PASS_OPTIONS:
        o = passes.get(PASS_OPTIONS[option])
        if o is None:
            raise ValueError(f"option {ATTACK_DRILL_OPTIONS[option]!r} is not legal here (no such pass); check "
                             f"attack_drill_mask first")
        best = PassOption(o.teammate, o.point, o.kick_speed, 0.0, o.success, 0.0, o.value)
        return Decision(Choice.PASS, 0.0, 0.0, (best,), best), o
    return Decision(Choice.KEEP, 0.0, 0.0, dribble_to=dribble_point(DRIBBLE_OPTIONS[option], ball, field),
                    dribble_speed=DRIBBLE_SPEED, commit_s=DRIBBLE_COMMIT_S), None


def attack_decision_option(decision: AttackDecision, world: WorldState, team: str, me: int) -> int:
    """The option index of a cost decision (:func:`~ssl_marl.plays.attack_decision.decide_attack`):
    SHOOT -> shoot; a pass of a kind to teammate k -> that kind's option for k's slot (shoot
    when k holds no slot); DRIBBLE -> dribble_goal."""
    if decision.choice is AttackChoice.SHOOT:
        return SHOOT
    if decision.choice is AttackChoice.DRIBBLE or decision.best is None:
        return DRIBBLE_GOAL_OPTION
    slots = teammate_slots(world, team, me)
    if decision.best.teammate not in slots:
        return SHOOT
    key = (decision.best.kind, slots.index(decision.best.teammate))
    return next(i for i, k in PASS_OPTIONS.items() if k == key)


__all__ = ["request_features", "ATTACK_DRILL_OPTIONS", "N_ATTACK_DRILL_OPTIONS", "ATTACK_DRILL_OBS_DIM", "PASS_OPTIONS",
           "DRIBBLE_OPTIONS", "SHOOT", "DRIBBLE_GOAL_OPTION", "slot_passes", "attack_drill_observation",
           "attack_drill_mask",
           "option_play_decision", "attack_decision_option"]
