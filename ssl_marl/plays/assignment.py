"""Role assignment: which robot takes which role, as a pure function.

Solver: ``scipy.optimize.linear_sum_assignment`` (the Hungarian-family optimal
solver every scientific Python install has; scipy is the standard, well-tested
implementation, a project dependency). SSL teams solve the role assignment
optimally per priority tier (docs/references.md, "Role assignment").

Rules of :func:`assign`:

1. **Costs** (any unit, e.g. seconds to reach the role's spot) come from a matrix
   ``(n_roles, n_robots)`` or a function ``cost(role_name, robot_id)``. A non-finite
   cost raises ValueError naming the role and the robot: impossible pairs are
   *constraints* (``forbidden``), never infinite costs.
2. **Hard constraints**: ``fixed`` maps a role to a robot id that must take it (e.g.
   the goalie is robot 0); the robot is reserved before anything else. If that robot
   is not among ``robots`` the role is assigned like any other. ``forbidden`` lists
   (role, robot) pairs that must never be matched (the solver sees them as
   disallowed cells; they are not evaluated as costs).
3. **Priority tiers**: roles with a higher ``priority`` are filled first, from all
   robots still free, even where that is costlier overall; within a tier the total
   cost is minimised exactly.
4. **Unfilled cost**: each role may stay empty at its ``unfilled_cost`` (finite). The
   solver leaves a role empty when every free robot costs more than leaving it, or
   when the tier has more roles than free robots (then it drops the roles whose
   emptiness costs least).
5. **Stickiness**: the previous holder of a role (``previous``) gets its cost
   lowered by ``stickiness`` (hysteresis; the CMDragons used ~0.3 s:
   docs/references.md, "Role assignment"), so near-ties do not make roles flap
   between robots.

Surplus robots (more robots than roles) are returned in ``unassigned``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable, Iterable, Mapping, Sequence, Union

import numpy as np
from scipy.optimize import linear_sum_assignment

DEFAULT_UNFILLED_COST = 1.0e3


@dataclass(frozen=True)
class RoleSlot:
    """A role to fill: ``name`` (unique), ``priority`` (higher = filled first),
    ``unfilled_cost`` (cost of leaving it empty; finite)."""

    name: str
    priority: int = 0
    unfilled_cost: float = DEFAULT_UNFILLED_COST


@dataclass(frozen=True)
class Assignment:
    """Result of :func:`assign`.

    Attributes:
        roles: role name -> robot id, or None if the role is unfilled (all roles listed).
        robots: robot id -> role name (assigned robots only).
        unassigned: robot ids that got no role.
        total_cost: sum of the matched costs (without the stickiness bonus) plus the
            unfilled costs of the empty roles.
    """

    roles: dict[str, int | None] = field(default_factory=dict)
    robots: dict[int, str] = field(default_factory=dict)
    unassigned: tuple[int, ...] = ()
    total_cost: float = 0.0

    def __getitem__(self, role: str) -> int | None:
        return self.roles[role]

    @property
    def filled(self) -> tuple[str, ...]:
        return tuple(r for r, k in self.roles.items() if k is not None)

    @property
    def unfilled(self) -> tuple[str, ...]:
        return tuple(r for r, k in self.roles.items() if k is None)


CostSpec = Union[np.ndarray, Sequence[Sequence[float]], Callable[[str, int], float]]


def _slots(roles: Sequence[RoleSlot | str]) -> list[RoleSlot]:
    out = [r if isinstance(r, RoleSlot) else RoleSlot(str(r)) for r in roles]
    names = [r.name for r in out]
    if len(set(names)) != len(names):
        dup = sorted({n for n in names if names.count(n) > 1})
        raise ValueError(f"assign: duplicate role name(s) {dup}")
    for r in out:
        if not (isinstance(r.unfilled_cost, (int, float)) and math.isfinite(r.unfilled_cost)):
            raise ValueError(f"assign: unfilled_cost of role {r.name!r} must be finite, got {r.unfilled_cost!r}")
    return out


def assign(robots: Sequence[int], roles: Sequence[RoleSlot | str], cost: CostSpec, *,
           fixed: Mapping[str, int] | None = None, forbidden: Iterable[tuple[str, int]] = (),
           previous: Mapping[str, int | None] | None = None, stickiness: float = 0.0) -> Assignment:
    """Assign ``robots`` (ids) to ``roles`` (see the module docstring for the rules).

    Args:
        robots: robot ids available.
        roles: :class:`RoleSlot` (or plain names: priority 0, default unfilled cost).
        cost: ``(len(roles), len(robots))`` matrix in the given orders, or a function
            ``cost(role_name, robot_id) -> float``.
        fixed: role name -> robot id that must take it.
        forbidden: (role name, robot id) pairs that must not be matched.
        previous: role name -> robot id that held it last time (stickiness).
        stickiness: cost bonus for the previous holder (>= 0, same unit as costs).

    Raises:
        ValueError: duplicate names/ids, wrong matrix shape, a non-finite cost (naming
            role and robot), a non-finite unfilled cost or stickiness, unknown roles in
            ``fixed``.
    """
    slots = _slots(roles)
    robots = [int(r) for r in robots]
    if len(set(robots)) != len(robots):
        raise ValueError(f"assign: duplicate robot id(s) in {robots}")
    if not (isinstance(stickiness, (int, float)) and math.isfinite(stickiness) and stickiness >= 0):
        raise ValueError(f"assign: stickiness must be a finite number >= 0, got {stickiness!r}")
    names = [s.name for s in slots]
    ridx = {n: i for i, n in enumerate(names)}
    cidx = {k: j for j, k in enumerate(robots)}
    fixed = dict(fixed or {})
    unknown = sorted(set(fixed) - set(names))
    if unknown:
        raise ValueError(f"assign: fixed names unknown role(s) {unknown}; roles are {names}")
    banned = np.zeros((len(slots), len(robots)), dtype=bool)
    for role, robot in forbidden:
        if role in ridx and int(robot) in cidx:
            banned[ridx[role], cidx[int(robot)]] = True

    # ---- cost matrix (forbidden cells are never evaluated / checked)
    if callable(cost):
        C = np.zeros((len(slots), len(robots)))
        for i, s in enumerate(slots):
            for j, k in enumerate(robots):
                if not banned[i, j]:
                    C[i, j] = float(cost(s.name, k))
    else:
        C = np.array(cost, dtype=float, copy=True)
        if C.shape != (len(slots), len(robots)):
            raise ValueError(f"assign: cost matrix has shape {C.shape}, expected (n_roles, n_robots) = "
                             f"({len(slots)}, {len(robots)})")
    bad = ~np.isfinite(C) & ~banned
    if bad.any():
        i, j = map(int, np.argwhere(bad)[0])
        raise ValueError(f"assign: non-finite cost {C[i, j]!r} for role {names[i]!r} and robot {robots[j]}; "
                         "express impossible pairs with forbidden=, not with inf/nan costs")
    raw = np.where(banned, 0.0, C)

    # ---- stickiness bonus for the previous holders
    work = raw.copy()
    for role, robot in (previous or {}).items():
        if robot is not None and role in ridx and int(robot) in cidx and stickiness:
            work[ridx[role], cidx[int(robot)]] -= stickiness

    result: dict[str, int | None] = {n: None for n in names}
    free = list(robots)
    total = 0.0
    # ---- hard constraints first
    for role, robot in fixed.items():
        robot = int(robot)
        if robot in free and not banned[ridx[role], cidx[robot]]:
            result[role] = robot
            free.remove(robot)
            total += raw[ridx[role], cidx[robot]]

    # ---- tiers, highest priority first (small matrices: built from Python lists, which is
    # several times faster than numpy fancy indexing at these sizes)
    work_l, raw_l, banned_l = work.tolist(), raw.tolist(), banned.tolist()
    inf = math.inf
    open_roles = [s for s in slots if result[s.name] is None]
    for prio in sorted({s.priority for s in open_roles}, reverse=True):
        tier = [s for s in open_roles if s.priority == prio]
        if not free:  # nobody left: the whole tier stays empty
            total += sum(s.unfilled_cost for s in tier)
            continue
        nr = len(tier)
        cols = [cidx[k] for k in free]
        rows = []
        for r, s in enumerate(tier):
            i = ridx[s.name]
            wr, br = work_l[i], banned_l[i]
            dummy = [inf] * nr
            dummy[r] = float(s.unfilled_cost)
            rows.append([inf if br[j] else wr[j] for j in cols] + dummy)
        r_ind, c_ind = linear_sum_assignment(np.array(rows))
        nf = len(cols)
        taken = set()
        for r, c in zip(r_ind.tolist(), c_ind.tolist()):
            s = tier[r]
            if c < nf:
                robot = free[c]
                result[s.name] = robot
                taken.add(robot)
                total += raw_l[ridx[s.name]][cidx[robot]]
            else:
                total += s.unfilled_cost
        free = [k for k in free if k not in taken]

    robots_map = {k: r for r, k in result.items() if k is not None}
    return Assignment(roles=result, robots=robots_map, unassigned=tuple(free), total_cost=float(total))
