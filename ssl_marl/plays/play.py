"""Plays as data, the standard plays, and play selection.

A :class:`Play` is a record: a name, an applicability predicate over the
:class:`PlayContext` (the team-frame world plus a few derived facts), a tuple of
:class:`RoleDef` (priority tier, tactic factory, the role's target point for the
assignment cost, a per-tick parameter update, constraints), a timeout and an
initial weight. Nothing in a play runs by itself: the
:class:`~ssl_marl.plays.team.TeamController` evaluates it each tick
(play -> assignment -> tactics -> skills -> actions).

Cost of a role for a robot (default, :func:`time_to_reach`): the time (s) to reach
the role's target at the robot's top speed. The goalie is a hard constraint
(``fixed_robot=0``) whenever the team has at least two robots.

Selection (:class:`PlaySelector`), CMDragons-style:

* the current play is kept for at least ``min_hold_s`` (hysteresis);
* after that it is kept while it stays applicable and has not timed out, unless an
  applicable play of higher ``priority`` exists (preemption, e.g. a kickoff);
* otherwise a play is picked among the applicable ones of the highest priority:
  the largest weight (ties: list order), or, with ``adaptive=True``, at random in
  proportion to the weights (seeded); the weights adapt to outcomes: a goal for us
  while a play runs multiplies its weight by ``1 + learning_rate``, a goal against
  divides it by that factor (clipped to [w_min, w_max]).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Callable, Mapping, Sequence

import numpy as np

from ..physics.field import FieldGeometry
from ..physics.params import RobotParams
from ..physics.state import WorldState
from ..skills.navigation import NavParams, sanitize_target
from .assignment import DEFAULT_UNFILLED_COST, Assignment
from .defense import Defender, Goalie, Mark, MarkParams, block_position, goalie_guard_position, mark_position
from .shoot import Attacker
from .support import Support, SupportParams
from .wall import Wall, wall_spot
from .tactic_base import Tactic, TacticStatus

HAS_BALL_MARGIN_S = 0.25  # overlap band of the offense/defense predicates (s of time-to-ball)


# ------------------------------------------------------------------ context
@dataclass(frozen=True)
class PlayContext:
    """What plays look at each tick (team frame: own goal at -x).

    Attributes:
        team: "blue" or "yellow".
        world: the team-frame snapshot.
        field, robot: geometry and robot parameters.
        n: number of own robots; n_opp: number of opponents.
        we_have_ball / they_have_ball: a robot of that team holds the ball on its dribbler.
        our_time / their_time: least estimated time (s) for a field player (robot 0
            excluded when n >= 2: the goalie) / an opponent to reach the ball at top
            speed (inf without robots).
        threats: opponent indices sorted by danger (closest to our goal first),
            leaving out the opponent nearest the ball (the attacker presses it).
        role_status: role name -> the :class:`~ssl_marl.plays.tactic_base.TacticStatus`
            its tactic reported on the previous tick (how tactics report to plays,
            e.g. the pass handshake); filled by the team controller.
        role_holders: role name -> robot index that held it on the previous tick.
        set_piece: the referee gave us a kickoff or free kick that is not taken yet (the
            opponents keep 0.5 m from the ball until it is; SSL game control, filled by
            the team controller from the env's referee state; False without one).
        their_set_piece: the opponents have a kickoff or free kick not taken yet (we keep
            0.5 m; the wall roles exist).
        dribbled_m: (n,) metres each of our robots has dribbled the ball in its current
            dribble, as the referee measures it (:class:`~ssl_marl.plays.dribble_watch.DribbleWatch`;
            SSL's limit is 1 m); filled by the team controller, None without one.
    """

    team: str
    world: WorldState
    field: FieldGeometry
    robot: RobotParams
    n: int
    n_opp: int
    we_have_ball: bool
    they_have_ball: bool
    our_time: float
    their_time: float
    threats: tuple[int, ...]
    role_status: Mapping[str, TacticStatus] = field(default_factory=dict)
    role_holders: Mapping[str, int] = field(default_factory=dict)
    set_piece: bool = False
    their_set_piece: bool = False
    dribbled_m: np.ndarray | None = None

    @property
    def ball(self) -> np.ndarray:
        return self.world.ball_pos

    @property
    def field_robots(self) -> tuple[int, ...]:
        """Our robot indices but the goalie (robot 0 when the team has two or more)."""
        return tuple(range(1, self.n)) if self.n >= 2 else tuple(range(self.n))

    @property
    def our_pos(self) -> np.ndarray:
        return self.world.team(self.team).pos

    @property
    def opp_pos(self) -> np.ndarray:
        return self.world.opponents(self.team).pos


def time_to_reach(pos: np.ndarray, target: np.ndarray, max_speed: float) -> np.ndarray:
    """Estimated time (s) for robots at ``pos`` (n, 2) to reach ``target`` at ``max_speed`` (m/s)."""
    d = np.asarray(pos, float) - np.asarray(target, float)
    return np.hypot(d[..., 0], d[..., 1]) / max(max_speed, 1e-9)


def make_context(world: WorldState, team: str, field: FieldGeometry, robot: RobotParams, **extra: Any
                 ) -> PlayContext:
    """Build the :class:`PlayContext` from a team-frame snapshot; ``extra``: the fields the
    team controller fills (``role_status``, ``role_holders``, ``set_piece``, ...)."""
    if world.frame != team:
        raise ValueError(f"make_context: expected a snapshot in {team!r}'s frame, got frame={world.frame!r}")
    ours, theirs = world.team(team), world.opponents(team)
    field_players = ours.pos[1:] if ours.n >= 2 else ours.pos
    our_t = (float(time_to_reach(field_players, world.ball_pos, robot.max_speed).min()) if len(field_players)
             else math.inf)
    their_all = time_to_reach(theirs.pos, world.ball_pos, robot.max_speed) if theirs.n else np.zeros(0)
    their_t = float(their_all.min()) if theirs.n else math.inf
    threats: tuple[int, ...] = ()
    if theirs.n:
        presser_target = int(np.argmin(their_all))
        danger = time_to_reach(theirs.pos, field.goal_center(-1), 1.0)
        order = [int(k) for k in np.argsort(danger, kind="stable") if int(k) != presser_target]
        threats = tuple(order)
    return PlayContext(team=team, world=world, field=field, robot=robot, n=ours.n, n_opp=theirs.n,
                       we_have_ball=bool(ours.ball_on_dribbler.any()),
                       they_have_ball=bool(theirs.ball_on_dribbler.any()),
                       our_time=our_t, their_time=their_t, threats=threats, **extra)


# -------------------------------------------------------------------- roles
TacticFactory = Callable[..., Tactic]  # called as factory(field, robot, ball, skills=..., dt=...)


@dataclass(frozen=True)
class RoleDef:
    """One role of a play.

    Attributes:
        name: unique within the play (e.g. "defender_0"); tactics are kept across
            ticks (and plays) while a robot keeps the same role name and factory.
        priority: assignment tier (higher = filled first).
        tactic: factory ``(field, robot, ball, skills=, dt=) -> Tactic`` (a Tactic class works).
        target: ``ctx -> (2,) point`` the role will go to (for the cost), or None when
            the role is not needed this tick (e.g. nobody to mark).
        update: ``(tactic, ctx, assignment) -> None``, sets the tactic's parameters each tick.
        cost: ``(ctx, target) -> (n,)`` per-robot cost; default :func:`time_to_reach`.
        unfilled_cost: cost of leaving the role empty (s).
        min_team_size: the role exists only when the team has at least this many robots.
        fixed_robot: hard constraint: this robot id takes the role (goalie: 0).
    """

    name: str
    priority: int
    tactic: TacticFactory
    target: Callable[[PlayContext], np.ndarray | None]
    update: Callable[[Tactic, PlayContext, Assignment], None] | None = None
    cost: Callable[[PlayContext, np.ndarray], np.ndarray] | None = None
    unfilled_cost: float = DEFAULT_UNFILLED_COST
    min_team_size: int = 1
    fixed_robot: int | None = None

    def costs(self, ctx: PlayContext, target: np.ndarray) -> np.ndarray:
        if self.cost is not None:
            return np.asarray(self.cost(ctx, target), dtype=float)
        return time_to_reach(ctx.our_pos, target, ctx.robot.max_speed)


@dataclass(frozen=True)
class Play:
    """A play: see the module docstring. ``priority`` lets an applicable play preempt
    the current one after the hold time (kickoff > open play). ``prepare`` (optional)
    runs once per tick while the play is selected, before its roles' targets are
    evaluated: team-level decisions that several roles share (the passing plays'
    pass coordinator) are made there; a ``prepare`` with a ``reset()`` method is reset
    whenever the team's play selector is (a new episode)."""

    name: str
    applicable: Callable[[PlayContext], bool]
    roles: tuple[RoleDef, ...]
    timeout_s: float = 25.0
    weight: float = 1.0
    priority: int = 0
    prepare: Callable[[PlayContext], None] | None = None

    def __post_init__(self) -> None:
        names = [r.name for r in self.roles]
        dup = sorted({n for n in names if names.count(n) > 1})
        if dup:
            raise ValueError(f"play {self.name!r}: duplicate role name(s) {dup}")
        if not (self.timeout_s > 0 and self.weight > 0):
            raise ValueError(f"play {self.name!r}: timeout_s and weight must be positive")


# ------------------------------------------------------- standard role defs
def _filled_index(assignment: Assignment, prefix: str, name: str) -> tuple[int, int]:
    """(index of role ``name`` among the filled roles starting with ``prefix``, how many)."""
    same = sorted(r for r in assignment.filled if r.startswith(prefix))
    return (same.index(name) if name in same else 0), max(len(same), 1)


def goalie_role(priority: int = 100) -> RoleDef:
    def target(ctx: PlayContext) -> np.ndarray:
        w = ctx.world
        return goalie_guard_position(w.ball_pos, w.ball_vel, ctx.field, ctx.robot)

    return RoleDef("goalie", priority, Goalie, target, min_team_size=2, fixed_robot=0)


def attacker_role(priority: int = 90) -> RoleDef:
    """Go for the ball and shoot (:class:`~ssl_marl.plays.shoot.Attacker`); our set piece
    it takes with one kick (``ctx.set_piece``)."""

    def update(t: Tactic, ctx: PlayContext, a: Assignment) -> None:
        t.set_params(set_piece=ctx.set_piece)

    return RoleDef("attacker", priority, Attacker, lambda ctx: np.asarray(ctx.ball, float), update=update)


# Cost (s of travel time) of leaving a mark or support role empty: far below the
# default (assignment.DEFAULT_UNFILLED_COST, "must fill"), so these optional roles
# are the first left empty when robots are short; hand-tuned.
OPTIONAL_ROLE_UNFILLED_COST = 20.0
DEFENDER_SPACING = 0.22  # m between neighbouring defenders' lanes (robot diameter + 4 cm)


def defender_role(k: int, priority: int) -> RoleDef:
    name = f"defender_{k}"

    def update(t: Tactic, ctx: PlayContext, a: Assignment) -> None:
        i, m = _filled_index(a, "defender_", name)
        t.set_params(lane_offset=(i - (m - 1) / 2.0) * DEFENDER_SPACING)

    def target(ctx: PlayContext) -> np.ndarray:
        return block_position(ctx.ball, ctx.field)

    return RoleDef(name, priority, Defender, target, update=update)


def mark_role(k: int, priority: int, ball_bias: float = MarkParams.ball_bias) -> RoleDef:
    """Mark the k-th most dangerous opponent (:class:`~ssl_marl.plays.defense.Mark`)
    0.35 m from it towards our goal centre, turned by ``ball_bias`` (0..1) towards the
    ball: 0 stands on its line to our goal and blocks its shot, one-touch or after a
    reception; the default 0.25 also leans into the lane of a pass to it."""
    name = f"mark_{k}"

    def target(ctx: PlayContext) -> np.ndarray | None:
        if k >= len(ctx.threats):
            return None
        opp = ctx.opp_pos[ctx.threats[k]]
        return sanitize_target(mark_position(opp, ctx.ball, ctx.field, ball_bias=ball_bias), ctx.field, NavParams())

    def update(t: Tactic, ctx: PlayContext, a: Assignment) -> None:
        t.set_params(opponent=ctx.threats[k] if k < len(ctx.threats) else None, ball_bias=ball_bias)

    return RoleDef(name, priority, Mark, target, update=update, unfilled_cost=OPTIONAL_ROLE_UNFILLED_COST)


#: a second wall robot stands while the ball is this close to our goal centre (m): from
#: farther out one robot shadows the whole Division B goal (plays/wall.py)
SECOND_WALL_M = 3.5


def wall_role(k: int, priority: int) -> RoleDef:
    """The ``k``-th robot (0 or 1) of the wall against the opponents' set piece
    (:class:`~ssl_marl.plays.wall.Wall`), only while ``ctx.their_set_piece``; the second
    only while the ball lies within :data:`SECOND_WALL_M` of our goal, the two side by side
    (a robot diameter plus 1 cm apart)."""
    name = f"wall_{k}"

    def robots(ctx: PlayContext) -> int:
        if not ctx.their_set_piece:
            return 0
        return 2 if float(np.hypot(*(ctx.ball - ctx.field.goal_center(-1)))) < SECOND_WALL_M else 1

    def offset(ctx: PlayContext) -> float:
        return (k - 0.5) * (2 * ctx.robot.radius + 0.01) if robots(ctx) == 2 else 0.0

    def target(ctx: PlayContext) -> np.ndarray | None:
        return wall_spot(ctx.ball, ctx.field, offset(ctx)) if k < robots(ctx) else None

    def update(t: Tactic, ctx: PlayContext, a: Assignment) -> None:
        if k < robots(ctx):
            spot = ctx.field.clamp_to_field(wall_spot(ctx.ball, ctx.field, offset(ctx)))
            t.set_params(spot=(float(spot[0]), float(spot[1])))

    return RoleDef(name, priority, Wall, target, update=update, unfilled_cost=OPTIONAL_ROLE_UNFILLED_COST)


def _support_band(field: FieldGeometry, i: int, m: int) -> tuple[float, float]:
    w = field.width / m
    lo = -field.half_width + i * w
    return (lo, lo + w)


def support_role(k: int, priority: int) -> RoleDef:
    name = f"support_{k}"

    def update(t: Tactic, ctx: PlayContext, a: Assignment) -> None:
        i, m = _filled_index(a, "support_", name)
        t.set_params(y_range=_support_band(ctx.field, i, m))

    def target(ctx: PlayContext) -> np.ndarray:
        f = ctx.field
        # k-th of up to 4 bands, by role index: a rough spot for the cost only
        lo, hi = _support_band(f, k % 4, 4)
        sp = SupportParams()  # the tactic's own defaults: ``ahead`` of the ball, within its x range
        x = min(max(float(ctx.ball[0]) + sp.ahead, sp.x_min_m), f.half_length - f.defense_depth - sp.defense_gap_m)
        return np.array([x, 0.5 * (lo + hi)])

    return RoleDef(name, priority, Support, target, update=update, unfilled_cost=OPTIONAL_ROLE_UNFILLED_COST)


# ------------------------------------------------------------ standard plays
def offense_applicable(ctx: PlayContext) -> bool:
    """We hold the ball, or nobody holds it and we are (about) closer to it."""
    return not ctx.they_have_ball and (ctx.we_have_ball or ctx.our_time <= ctx.their_time + HAS_BALL_MARGIN_S)


def defense_applicable(ctx: PlayContext) -> bool:
    """They hold the ball, or nobody holds it and they are (about) closer to it."""
    return not ctx.we_have_ball and (ctx.they_have_ball or ctx.their_time <= ctx.our_time + HAS_BALL_MARGIN_S)


def kickoff_applicable(ctx: PlayContext) -> bool:
    """Neutral restart: ball still near the centre mark, nobody within 0.3 m of it."""
    ball_still = float(np.hypot(*ctx.world.ball_vel)) < 0.1 and float(np.hypot(*ctx.ball)) < 0.15
    near = min(ctx.our_time, ctx.their_time) * ctx.robot.max_speed
    return ball_still and near > 0.3 and not (ctx.we_have_ball or ctx.they_have_ball)


def offense_play() -> Play:
    """Attacker, supports in the opponent half, defenders, goalie."""
    roles = (goalie_role(100), attacker_role(90), wall_role(0, 85), defender_role(0, 80), support_role(0, 80),
             wall_role(1, 75), support_role(1, 70), defender_role(1, 70), mark_role(0, 60), support_role(2, 60),
             mark_role(1, 50), defender_role(2, 50), support_role(3, 40), mark_role(2, 40))
    return Play("offense", offense_applicable, roles)


def defense_play(mark_ball_bias: float = MarkParams.ball_bias) -> Play:
    """Goalie, two defenders on the shot lane, marks on the most dangerous opponents
    (``mark_ball_bias``: :func:`mark_role`), an attacker pressing the ball."""
    b = mark_ball_bias
    roles = (goalie_role(100), attacker_role(90), wall_role(0, 85), defender_role(0, 80), defender_role(1, 80),
             wall_role(1, 75), mark_role(0, 70, b), mark_role(1, 70, b), mark_role(2, 60, b), defender_role(2, 60),
             mark_role(3, 50, b), support_role(0, 50), mark_role(4, 40, b), support_role(1, 40))
    return Play("defense", defense_applicable, roles)


def kickoff_play() -> Play:
    """Neutral restart: attacker goes for the ball, a balanced shape behind it."""
    roles = (goalie_role(100), attacker_role(90), wall_role(0, 85), defender_role(0, 80), support_role(0, 80),
             wall_role(1, 75), defender_role(1, 70), support_role(1, 70), mark_role(0, 60), support_role(2, 60),
             mark_role(1, 50), defender_role(2, 50), support_role(3, 40), mark_role(2, 40))
    return Play("kickoff", kickoff_applicable, roles, priority=1)


def standard_plays() -> tuple[Play, ...]:
    """(kickoff, offense, defense)."""
    return (kickoff_play(), offense_play(), defense_play())


# ---------------------------------------------------------------- selection
@dataclass
class PlayStats:
    """Per-play bookkeeping: selections, goals for / against while running, seconds run."""

    selections: int = 0
    goals_for: int = 0
    goals_against: int = 0
    time_s: float = 0.0


class PlaySelector:
    """Chooses the play each tick (see the module docstring for the rules).

    Args:
        plays: candidate plays (order breaks weight ties).
        min_hold_s: minimum time a selected play is kept (s).
        adaptive: weighted random selection with outcome-adapted weights.
        learning_rate: weight factor step for adaptation.
        w_min, w_max: weight bounds.
        seed: seed of the selection RNG (adaptive mode).
    """

    def __init__(self, plays: Sequence[Play], min_hold_s: float = 0.5, adaptive: bool = False,
                 learning_rate: float = 0.2, w_min: float = 0.05, w_max: float = 20.0, seed: int = 0) -> None:
        if not plays:
            raise ValueError("PlaySelector needs at least one play")
        names = [p.name for p in plays]
        if len(set(names)) != len(names):
            raise ValueError(f"PlaySelector: duplicate play names in {names}")
        self.plays = tuple(plays)
        self.min_hold_s, self.adaptive = float(min_hold_s), bool(adaptive)
        self.learning_rate, self.w_min, self.w_max = float(learning_rate), float(w_min), float(w_max)
        self.seed = seed
        self.reset()

    def reset(self) -> None:
        self.weights: dict[str, float] = {p.name: float(p.weight) for p in self.plays}
        self.stats: dict[str, PlayStats] = {p.name: PlayStats() for p in self.plays}
        self.current: Play | None = None
        self.since = 0.0
        self._last_t: float | None = None
        self.rng = np.random.default_rng(self.seed)
        self._reset_prepares()

    def new_episode(self) -> None:
        """Drop the running play (the env was reset); keep weights and statistics."""
        self.current, self.since, self._last_t = None, 0.0, None
        self._reset_prepares()

    def _reset_prepares(self) -> None:
        """Reset every play's ``prepare`` that keeps state between ticks (it has a
        ``reset()``: the pass coordinator's plan, the supports' spots), so that an episode
        does not depend on the one before."""
        for p in self.plays:
            reset = getattr(p.prepare, "reset", None)
            if callable(reset):
                reset()

    def _pick(self, candidates: list[Play]) -> Play:
        top = max(p.priority for p in candidates)
        cands = [p for p in candidates if p.priority == top]
        w = np.array([self.weights[p.name] for p in cands])
        if self.adaptive and len(cands) > 1:
            return cands[int(self.rng.choice(len(cands), p=w / w.sum()))]
        return cands[int(np.argmax(w))]

    def select(self, ctx: PlayContext, t: float) -> Play:
        """The play to run at time ``t`` (s)."""
        if self.current is not None and self._last_t is not None:
            self.stats[self.current.name].time_s += max(t - self._last_t, 0.0)
        self._last_t = t
        cur = self.current
        if cur is not None and t - self.since < self.min_hold_s:
            return cur
        applicable = [p for p in self.plays if p.applicable(ctx)]
        if cur is not None:
            ok = cur in applicable and t - self.since < cur.timeout_s
            preempt = any(p.priority > cur.priority for p in applicable)
            if ok and not preempt:
                return cur
        if not applicable:
            if cur is not None:
                return cur
            applicable = list(self.plays)
        new = self._pick(applicable)
        self.current, self.since = new, t
        self.stats[new.name].selections += 1
        return new

    def record_goal(self, for_us: bool) -> None:
        """Credit (or blame) the running play for a goal; adapts its weight if adaptive."""
        if self.current is None:
            return
        name = self.current.name
        st = self.stats[name]
        if for_us:
            st.goals_for += 1
        else:
            st.goals_against += 1
        if self.adaptive:
            f = 1.0 + self.learning_rate
            w = self.weights[name] * (f if for_us else 1.0 / f)
            self.weights[name] = float(np.clip(w, self.w_min, self.w_max))

    def summary(self) -> dict[str, Any]:
        return {p.name: {"weight": self.weights[p.name], **self.stats[p.name].__dict__} for p in self.plays}


__all__ = ["PlayContext", "make_context", "time_to_reach", "RoleDef", "Play", "PlaySelector", "PlayStats",
           "goalie_role", "attacker_role", "wall_role", "SECOND_WALL_M", "defender_role", "mark_role", "support_role", "offense_play",
           "defense_play", "kickoff_play", "standard_plays", "offense_applicable", "defense_applicable",
           "kickoff_applicable"]
