"""The passing plays' roles: passer, receiver, attacker and supports, steered by the
team's :class:`~ssl_marl.plays.pass_coordinator.PassCoordinator`.

The passer and receiver roles exist while the coordinator holds a plan; each costs 0 for
the robot the plan names and :data:`PROHIBITIVE_COST` for any other. The attacker role
exists while there is no plan and takes the coordinator's decision (``hold_fire``, KEEP
target and speed). Supports also rate spots by the pass lane to them
(:mod:`ssl_marl.plays.support`, ``pass_lane_weight``).
"""

from __future__ import annotations

from typing import Callable

import numpy as np

from .assignment import Assignment
from .pass_coordinator import PassCoordinator, PassPhase, PassPlan
from .pass_tactic import Pass
from .play import PlayContext, RoleDef, defender_role, goalie_role, mark_role, wall_role, _filled_index, _support_band
from .receive_tactic import Receive, ReceiveState
from .shoot import Attacker
from .support import Support
from .tactic_base import Tactic

PROHIBITIVE_COST = 50.0  # s: a role meant for one robot costs this for any other (unfilled_cost is lower)


def only_robot(robot_of: Callable[[PlayContext], int | None]) -> Callable[[PlayContext, np.ndarray], np.ndarray]:
    """Cost function: 0 for the robot ``robot_of(ctx)`` names, prohibitive for the others."""

    def cost(ctx: PlayContext, target: np.ndarray) -> np.ndarray:
        c = np.full(ctx.n, PROHIBITIVE_COST)
        k = robot_of(ctx)
        if k is not None and 0 <= k < ctx.n:
            c[k] = 0.0
        return c

    return cost


def passer_role(coord: PassCoordinator, priority: int = 95, tactic: type[Tactic] = Pass,
                extra: Callable[[PlayContext, PassPlan], dict] | None = None) -> RoleDef:
    """The plan's passer: ``tactic`` (a :class:`~ssl_marl.plays.pass_tactic.Pass`) told the
    receiver, the receive point and whether the receiver is READY (or the plan urgent), and
    whether it kicks moving (the plan spent: its dribble near SSL's limit);
    ``extra(ctx, plan)`` adds tactic parameters (e.g. a chip's elevation)."""

    def target(ctx: PlayContext) -> np.ndarray | None:
        return np.asarray(ctx.ball, float) if coord.plan is not None else None

    def update(t: Tactic, ctx: PlayContext, a: Assignment) -> None:
        plan = coord.plan
        if plan is None:
            return
        ready = ctx.role_status.get("receiver")
        t.set_params(target_robot=plan.receiver, target_point=(float(plan.point[0]), float(plan.point[1])),
                     receiver_ready=plan.urgent or (ready is not None and ready.state is ReceiveState.READY),
                     kick_moving=plan.spent, **(extra(ctx, plan) if extra is not None else {}))

    return RoleDef("passer", priority, tactic, target, update=update,
                   cost=only_robot(lambda ctx: coord.plan.passer if coord.plan else None), unfilled_cost=20.0)


def receiver_role(coord: PassCoordinator, priority: int = 94, tactic: type[Tactic] = Receive,
                  extra: Callable[[PlayContext, PassPlan], dict] | None = None) -> RoleDef:
    """The plan's receiver: ``tactic`` (a :class:`~ssl_marl.plays.receive_tactic.Receive`)
    told the receive point and where the ball comes from (the ball during the setup, the
    passer in flight); ``extra(ctx, plan)`` adds tactic parameters (e.g. a redirect's aim)."""

    def target(ctx: PlayContext) -> np.ndarray | None:
        return coord.plan.point if coord.plan is not None else None

    def update(t: Tactic, ctx: PlayContext, a: Assignment) -> None:
        plan = coord.plan
        if plan is None:
            return
        src = ctx.ball if plan.phase is PassPhase.SETUP else ctx.our_pos[plan.passer]
        t.set_params(receive_point=(float(plan.point[0]), float(plan.point[1])),
                     ball_from=(float(src[0]), float(src[1])), **(extra(ctx, plan) if extra is not None else {}))

    return RoleDef("receiver", priority, tactic, target, update=update,
                   cost=only_robot(lambda ctx: coord.plan.receiver if coord.plan else None), unfilled_cost=20.0)


def passing_attacker_role(coord: PassCoordinator, priority: int = 90, aim_open_goal: bool = False) -> RoleDef:
    """The carrier: :class:`~ssl_marl.plays.shoot.Attacker` steered by the coordinator's
    decision (hold fire, keep target and speed); ``aim_open_goal``: its shots aim at the
    widest open part of the goal mouth (:class:`~ssl_marl.plays.shoot.ShootParams`). A set
    piece the coordinator opens no pass for it takes with one kick at the open goal
    (``set_piece``, :class:`~ssl_marl.plays.shoot.AttackerParams`)."""

    def target(ctx: PlayContext) -> np.ndarray | None:
        return None if coord.plan is not None else np.asarray(ctx.ball, float)

    def update(t: Tactic, ctx: PlayContext, a: Assignment) -> None:
        t.set_params(hold_fire=coord.hold_fire(), drive_forward_s=coord.params.settle_s,
                     keep_target=coord.keep_target(), keep_speed=coord.keep_speed(),
                     snap_shot=coord.params.snap_shot, aim_open_goal=aim_open_goal,
                     aim_reach=coord.params.aim_reach, keep_tap_m=coord.params.keep_tap_m, set_piece=ctx.set_piece,
                     keep_out_of_opp_defense_area=coord.params.keep_out_of_opp_area)

    return RoleDef("attacker", priority, Attacker, target, update=update)


def passing_support_role(k: int, priority: int) -> RoleDef:
    """A support that also rates spots by how safely the ball can be passed there."""
    name = f"support_{k}"

    def update(t: Tactic, ctx: PlayContext, a: Assignment) -> None:
        i, m = _filled_index(a, "support_", name)
        t.set_params(y_range=_support_band(ctx.field, i, m), pass_lane_weight=1.5)

    def target(ctx: PlayContext) -> np.ndarray:
        f = ctx.field
        lo, hi = _support_band(f, k % 4, 4)
        x = min(max(float(ctx.ball[0]) + 1.0, 0.3), f.half_length - f.defense_depth - 0.35)
        return np.array([x, 0.5 * (lo + hi)])

    return RoleDef(name, priority, Support, target, update=update, unfilled_cost=20.0)


def passing_roles(coord: PassCoordinator) -> tuple[RoleDef, ...]:
    """The roles of the passing plays, in priority order, sharing ``coord``."""
    return (goalie_role(100), passer_role(coord, 95), receiver_role(coord, 94), passing_attacker_role(coord, 90),
            wall_role(0, 85), defender_role(0, 80), passing_support_role(0, 80), wall_role(1, 75),
            passing_support_role(1, 70), defender_role(1, 70), mark_role(0, 60), passing_support_role(2, 60),
            mark_role(1, 50), defender_role(2, 50), passing_support_role(3, 40), mark_role(2, 40))


__all__ = ["PROHIBITIVE_COST", "passer_role", "receiver_role", "passing_attacker_role", "passing_support_role",
           "passing_roles"]
