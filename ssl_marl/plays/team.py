"""TeamController: one team's STP stack, play -> assignment -> tactics -> skills -> actions.

Works for 1-11 robots of either colour. Everything runs in the team's frame (own
goal at -x): from an env it reads ``env.vision_state(team)`` (what the team sees,
noise and latency included); a field-frame :class:`WorldState` is converted with
:func:`~ssl_marl.physics.state.to_team_frame`. Robot 0 is the goalie when the team
has at least two robots; a single robot plays attacker.

Each tick:

1. :func:`~ssl_marl.plays.play.make_context` derives possession, times to the ball
   and the opponents' danger ranking;
2. the :class:`~ssl_marl.plays.play.PlaySelector` keeps or changes the play;
3. :func:`~ssl_marl.plays.assignment.assign` gives roles to robots (tiers, goalie
   fixed, stickiness for the previous holders);
4. each robot's tactic (kept while its role name and factory stay the same, else
   built fresh) gets its parameters from the role's ``update`` and returns an action;
   robots without a role stop in place;
5. while the referee (an env's ``task.referee_state``, :mod:`ssl_marl.envs.game_control`)
   says STOP, or a kickoff / free kick for the other team, :func:`keep_clear` makes
   every robot keep 0.5 m from the ball (the kicking team's robots play on, so its
   nearest robot takes the kick); during our kickoff or free kick the robots but its
   kicker (the ``takes_ball`` tactic: attacker or passer) keep clear of the ball too. The
   robot that took our set piece gets no role whose tactic goes for the ball
   (``takes_ball``) until another robot has touched the ball
   (:attr:`TeamController.set_piece_guard`; the rules' double touch).

Every team outside unit tests is built by :func:`build_team` from a :class:`TeamSpec`:
its plays (a :class:`PlaysFactory`), its skill set, and its ball carrier's decision
(any :class:`~ssl_marl.plays.pass_coordinator.CarrierDecider`; the learned ones live in
``ssl_marl.decisions`` and are plugged in by the runners, this package imports nothing
from there).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Collection, Protocol, Sequence

import numpy as np

from ..envs.game_control import RUNNING, other, touch_reach, touching_robots
from ..physics.field import FieldGeometry
from ..physics.params import BallParams, RobotParams
from ..physics.state import TEAMS, WorldState, to_team_frame
from ..skills.base import make_action
from .assignment import Assignment, RoleSlot, assign
from .dribble_watch import DribbleWatch
from .pass_coordinator import CarrierDecider
from .play import Play, PlayContext, PlaySelector, RoleDef, make_context, standard_plays, time_to_reach
from .skillset import CORE_SKILLS, SkillsSpec, check_skills, validate_skills
from .tactic_base import Tactic


def required_skills(plays: Sequence[Play]) -> tuple[str, ...]:
    """Skills a team running ``plays`` builds: the core ones (go-to-ball, aim-to-shoot)
    plus every ``uses_skills`` of the plays' tactics (pass, receive for passing plays; also
    chip pass, redirect for the attacking plays)."""
    names = list(CORE_SKILLS)
    for play in plays:
        for role in play.roles:
            for name in getattr(role.tactic, "uses_skills", ()):
                if name not in names:
                    names.append(name)
    return tuple(names)


#: m of slack on the touch reach when the team looks for its set piece's taker: the world
#: it sees lags (vision latency) a robot driving into the ball by a tick or two
TAKER_SLACK_M = 0.04


class TeamController:
    """STP controller for one team.

    Args:
        team: "blue" or "yellow".
        n_robots: robots in the team (1-11); agent names are ``f"{team}_{i}"``.
        field: "div_a", "div_b" or a :class:`FieldGeometry`.
        robot, ball: physical parameters (defaults when None).
        skills: "baseline", "learned" or {skill: kind or actor checkpoint path},
            passed to every tactic (see :mod:`~ssl_marl.plays.skillset`).
        plays: candidate plays (default :func:`~ssl_marl.plays.play.standard_plays`).
        min_hold_s: play hysteresis (s).
        adaptive: CMDragons-style weighted play selection with adapted weights.
        stickiness: assignment bonus (s) for a role's previous holder.
        seed: seed of the play-selection RNG.
        dt: control period (s).
    """

    def __init__(self, team: str, n_robots: int, field: str | FieldGeometry = "div_b",
                 robot: RobotParams | None = None, ball: BallParams | None = None, skills: SkillsSpec = "baseline",
                 plays: Sequence[Play] | None = None, min_hold_s: float = 0.5, adaptive: bool = False,
                 stickiness: float = 0.3, seed: int = 0, dt: float = 1.0 / 60.0) -> None:
        if team not in TEAMS:
            raise ValueError(f"TeamController: team must be 'blue' or 'yellow', got {team!r}")
        if not isinstance(n_robots, int) or isinstance(n_robots, bool) or not 1 <= n_robots <= 11:
            raise ValueError(f"TeamController: n_robots must be an integer in 1..11, got {n_robots!r}")
        validate_skills(skills)
        self.team, self.n = team, n_robots
        self.field = FieldGeometry.from_name(field)
        self.rp, self.bp = robot or RobotParams(), ball or BallParams()
        self.skills, self.dt, self.stickiness = skills, float(dt), float(stickiness)
        self.selector = PlaySelector(plays if plays is not None else standard_plays(), min_hold_s=min_hold_s,
                                     adaptive=adaptive, seed=seed)
        self.agents = [f"{team}_{i}" for i in range(n_robots)]
        check_skills(skills, self.field, self.rp, self.bp,  # fail now (e.g. a bad checkpoint), not mid-match
                     names=required_skills(self.selector.plays))
        self.reset()

    def reset(self) -> None:
        """Forget tactics, assignment history, play history and the score seen."""
        self.selector.reset()
        self._tactics: dict[int, tuple[str, Any, Tactic]] = {}
        self._previous: dict[str, int | None] = {}
        self._score_seen: dict[str, int] | None = None
        self._last_t: float | None = None
        self.assignment: Assignment | None = None
        self.play: Play | None = None
        self.context: PlayContext | None = None
        self._forget_set_piece()
        self.dribble_watch = DribbleWatch(self.team, self.rp, self.bp)
        self._slots: dict[int, tuple[RoleDef, RoleSlot]] = {}

    def _forget_set_piece(self) -> None:
        #: our robot that took our last set piece and may not touch the ball before another
        #: robot has (None: nobody guarded); it takes no ``takes_ball`` role meanwhile
        self.set_piece_guard: int | None = None
        self._set_piece_taker: int | None = None
        self._was_set_piece = False

    def new_episode(self) -> None:
        """The env was reset (detected from simulated time going back): drop tactics,
        role history and the running play, keep the play weights and statistics."""
        self._tactics = {}
        self._previous = {}
        self.assignment = self.play = self.context = None
        self._forget_set_piece()
        self.dribble_watch.reset()
        self.selector.new_episode()

    # ------------------------------------------------------------- queries
    @property
    def roles(self) -> dict[int, str]:
        """robot index -> role name (last tick)."""
        return dict(self.assignment.robots) if self.assignment else {}

    def tactic(self, robot: int) -> Tactic | None:
        """The tactic robot ``robot`` ran last tick (None if it had no role)."""
        entry = self._tactics.get(robot)
        return entry[2] if entry else None

    # ------------------------------------------------------------- outcomes
    def notify_goal(self, for_us: bool) -> None:
        """Tell play selection that a goal was scored (for / against this team)."""
        self.selector.record_goal(for_us)

    def _check_score(self, env: Any) -> None:
        score = getattr(env, "score", None)
        if not isinstance(score, dict):
            return
        if self._score_seen is not None:
            other = "yellow" if self.team == "blue" else "blue"
            for _ in range(max(score.get(self.team, 0) - self._score_seen.get(self.team, 0), 0)):
                self.notify_goal(True)
            for _ in range(max(score.get(other, 0) - self._score_seen.get(other, 0), 0)):
                self.notify_goal(False)
        self._score_seen = dict(score)

    # ------------------------------------------------------- double touch
    def _watch_set_piece_kicker(self, world: WorldState, referee: Any, set_piece: bool) -> None:
        """Keep :attr:`set_piece_guard`: the robot of ours that took our last kickoff or
        free kick (the last of ours within a touch of the ball, plus ``TAKER_SLACK_M``,
        while the set piece lasted), until another robot (either team's) touches the ball
        or the referee gives a new command; the SSL rules call the kicker's second touch
        before that a double touch. Without a referee nothing is guarded."""
        running = referee is not None and referee.command == RUNNING
        ours = world.team(self.team)
        reach = touch_reach(self.rp.radius, self.bp.radius)
        if set_piece:  # the taker: ours nearest the ball, within a touch and the tracker's error
            d = np.hypot(*(ours.pos - world.ball_pos).T)
            i = int(np.argmin(d))
            if d[i] <= reach + TAKER_SLACK_M:
                self._set_piece_taker = i
            self.set_piece_guard = None
        elif self._was_set_piece and running:
            self.set_piece_guard, self._set_piece_taker = self._set_piece_taker, None
        elif not running:
            self.set_piece_guard, self._set_piece_taker = None, None
        self._was_set_piece = set_piece
        g = self.set_piece_guard
        if g is not None:
            theirs = world.opponents(self.team)
            touching = touching_robots(ours.pos, world.ball_pos, world.ball_height, ours.ball_on_dribbler, reach)
            if np.delete(touching, g).any() or touching_robots(
                    theirs.pos, world.ball_pos, world.ball_height, theirs.ball_on_dribbler, reach).any():
                self.set_piece_guard = None

    # ----------------------------------------------------------------- tick
    def team_world(self, env_or_world: Any) -> WorldState:
        """The team-frame snapshot from an env (``vision_state``) or a WorldState."""
        if isinstance(env_or_world, WorldState):
            ws = env_or_world
            if ws.frame == "field":
                return to_team_frame(ws, self.team)
            if ws.frame != self.team:
                raise ValueError(f"TeamController({self.team!r}) got a snapshot in {ws.frame!r}'s frame")
            return ws
        if hasattr(env_or_world, "vision_state"):
            self._check_score(env_or_world)
            return env_or_world.vision_state(self.team)
        raise TypeError(f"TeamController.act expects an SSL env or a WorldState, got {type(env_or_world).__name__}")

    def _active_roles(self, play: Play, ctx: PlayContext) -> list[tuple[RoleDef, np.ndarray]]:
        out = []
        for r in play.roles:
            if ctx.n < r.min_team_size:
                continue
            target = r.target(ctx)
            if target is not None:
                out.append((r, np.asarray(target, float)))
        return out

    def _slot(self, role: RoleDef) -> RoleSlot:
        """The assignment slot of ``role`` (a frozen record: built once per role)."""
        hit = self._slots.get(id(role))
        if hit is None or hit[0] is not role:
            hit = self._slots[id(role)] = (role, RoleSlot(role.name, role.priority, role.unfilled_cost))
        return hit[1]

    def act(self, env_or_world: Any, referee: Any = None) -> dict[str, np.ndarray]:
        """Actions ``{f"{team}_{i}": (5,) float32}`` for all robots of the team.
        ``referee``: the referee's command (a :class:`~ssl_marl.envs.game_control.RefereeState`)
        where ``env_or_world`` carries none (a world seen by a bridge client); None: the
        env's ``task.referee_state`` (none for a bare world: play runs)."""
        world = self.team_world(env_or_world)
        if self._last_t is not None and world.t < self._last_t:
            self.new_episode()
        self._last_t = world.t
        ours = world.team(self.team)
        if ours.n != self.n:
            raise ValueError(f"TeamController({self.team!r}) was built for {self.n} robots, the world has {ours.n}")
        if referee is None:
            referee = getattr(getattr(env_or_world, "task", None), "referee_state", None)
        set_piece = referee is not None and referee.is_set_piece_for(self.team)
        self._watch_set_piece_kicker(world, referee, set_piece)
        dribbled = self.dribble_watch.update(world)
        ctx = make_context(world, self.team, self.field, self.rp,
                           role_status={role: tactic.status for role, _, tactic in self._tactics.values()},
                           role_holders={role: i for i, (role, _, _) in self._tactics.items()}, set_piece=set_piece,
                           their_set_piece=referee is not None and referee.is_set_piece_for(other(self.team)),
                           dribbled_m=dribbled)
        play = self.selector.select(ctx, world.t)
        if play.prepare is not None:
            play.prepare(ctx)
        active = self._active_roles(play, ctx)
        slots = [self._slot(r) for r, _ in active]
        cost = role_costs(active, ctx) if active else np.zeros((0, self.n))
        fixed = {r.name: r.fixed_robot for r, _ in active if r.fixed_robot is not None}
        guard = self.set_piece_guard
        held = self._tactics.get(guard) if guard is not None else None
        kept = held[0] if held is not None and not held[2].wants_ball else None  # e.g. a passer that has kicked
        forbidden = [(r.name, guard) for r, _ in active if guard is not None and r.name != kept
                     and getattr(r.tactic, "takes_ball", False) and r.fixed_robot != guard]
        assignment = assign(range(self.n), slots, cost, fixed=fixed, forbidden=forbidden, previous=self._previous,
                            stickiness=self.stickiness)
        self._previous = dict(assignment.roles)
        self.play, self.context, self.assignment = play, ctx, assignment
        by_name = {r.name: r for r, _ in active}
        actions: dict[str, np.ndarray] = {}
        for i in range(self.n):
            role_name = assignment.robots.get(i)
            if role_name is None:
                self._tactics.pop(i, None)
                actions[self.agents[i]] = make_action()
                continue
            role = by_name[role_name]
            entry = self._tactics.get(i)
            if entry is None or entry[0] != role_name or entry[1] is not role.tactic:
                tactic = role.tactic(self.field, self.rp, self.bp, skills=self.skills, dt=self.dt)
                self._tactics[i] = (role_name, role.tactic, tactic)
            tactic = self._tactics[i][2]
            if role.update is not None:
                role.update(tactic, ctx, assignment)
            actions[self.agents[i]] = tactic.act(world, i)
        if referee is not None and referee.must_keep_clear(self.team):
            keep_clear(actions, self.agents, world, self.team, self.rp.max_speed)
        elif set_piece:  # our set piece: only its kicker goes to the ball
            kickers = [i for i, (_, _, tactic) in self._tactics.items() if tactic.takes_ball]
            keep_clear(actions, self.agents, world, self.team, self.rp.max_speed, exempt=kickers)
        return actions


def role_costs(active: Sequence[tuple[RoleDef, np.ndarray]], ctx: PlayContext) -> np.ndarray:
    """(roles, robots) cost matrix of the active roles (``RoleDef.costs`` row by row): the
    default costs (:func:`~ssl_marl.plays.play.time_to_reach` to each role's target) in one
    array operation, element for element the same numbers."""
    targets = [tgt for r, tgt in active if r.cost is None]
    if not targets or any(t.shape != (2,) for t in targets):
        return np.vstack([r.costs(ctx, tgt) for r, tgt in active])
    default = iter(time_to_reach(ctx.our_pos[None, :, :], np.array(targets)[:, None, :], ctx.robot.max_speed))
    return np.vstack([next(default) if r.cost is None else r.costs(ctx, tgt) for r, tgt in active])


#: m: robots keep this far from the ball when the referee says so (0.5 m, SSL rules,
#: plus a margin for one control period of motion and the tracker's error)
KEEP_CLEAR_M = 0.6


def keep_clear(actions: dict[str, np.ndarray], agents: Sequence[str], world: WorldState, team: str,
               max_speed: float, brake: float = 2.0, clearance: float = KEEP_CLEAR_M,
               exempt: Collection[int] = ()) -> None:
    """Edit ``actions`` in place so that ``team``'s robots obey STOP (SSL rules: 0.5 m
    from the ball). A robot's commanded speed towards the ball is capped at
    sqrt(2 ``brake`` (d - ``clearance``)) (m/s; d its distance to the ball, m), so it
    can stop short of the ``clearance``; a robot already moving towards the ball faster
    than that is commanded its present sideways velocity and the capped speed towards
    the ball (a sideways command would take the acceleration that the braking needs:
    the velocity controller limits the acceleration's norm); within it the robot moves straight away at
    half ``max_speed``; kicking and dribbling are switched off. ``world`` is in the
    team's frame, actions are normalised body-frame (vx, vy, omega, dribble, kick),
    ``max_speed`` (m/s) is the speed of a normalised 1; robots whose indices are in
    ``exempt`` (our set piece's kicker) keep their actions."""
    ours = world.team(team)
    reach = clearance + max_speed ** 2 / (2 * brake)
    for i, name in enumerate(agents):
        if i in exempt:
            continue
        d = ours.pos[i] - world.ball_pos
        dist = float(np.hypot(d[0], d[1]))
        if dist >= reach:
            continue
        u = d / dist if dist > 1e-9 else np.array([-1.0, 0.0])
        a = np.array(actions[name], dtype=np.float32, copy=True)
        c, s_ = np.cos(ours.heading[i]), np.sin(ours.heading[i])
        v = max_speed * np.array([c * a[0] - s_ * a[1], s_ * a[0] + c * a[1]])  # body -> team frame, m/s
        inward = -float(v @ u)
        allowed = float(np.sqrt(2 * brake * max(dist - clearance, 0.0)))
        vel = ours.vel[i]
        inward_now = -float(vel[0] * u[0] + vel[1] * u[1])
        if inward_now > allowed:  # braking: keep the present sideways velocity, so that
            v = vel + (inward_now - allowed) * u  # the robot's acceleration all goes to slowing down
        elif inward > allowed:
            v = v + (inward - allowed) * u
        if dist < clearance:
            v = 0.5 * max_speed * u
        v = v / max_speed
        a[0], a[1] = c * v[0] + s_ * v[1], -s_ * v[0] + c * v[1]  # team -> body frame
        a[3], a[4] = -1.0, -1.0
        actions[name] = np.clip(a, -1.0, 1.0)


class PlaysFactory(Protocol):
    """Builds one team's plays: ``factory(ball=..., decider=...)``, fresh objects on every
    call (plays may hold per-team state, e.g. the passing plays' pass plan).
    ``decider``: the ball carrier's decision for plays that have one (None: theirs)."""

    def __call__(self, *, ball: BallParams | None, decider: CarrierDecider | None) -> Sequence[Play]:
        ...


def standard_team_plays(ball: BallParams | None = None, decider: CarrierDecider | None = None) -> tuple[Play, ...]:
    """:class:`PlaysFactory` of the standard plays (:func:`~ssl_marl.plays.play.standard_plays`);
    they have no carrier decision, so ``decider`` must be None."""
    if decider is not None:
        raise ValueError("a carrier decider needs plays with a carrier decision (the passing plays), "
                         "not the standard plays")
    return standard_plays()


@dataclass(frozen=True)
class TeamSpec:
    """What a team is, apart from its colour, size and the world it plays in.

    Attributes:
        plays: the team's plays (:class:`PlaysFactory`; e.g.
            :func:`~ssl_marl.plays.passing_play.passing_plays`).
        skills: the skill set every tactic uses (:mod:`~ssl_marl.plays.skillset`:
            "baseline", "learned" or {skill: kind or actor checkpoint path}).
        decider: the ball carrier's decision, handed to ``plays``
            (:class:`~ssl_marl.plays.pass_coordinator.CarrierDecider`; None: the plays'
            own). Every team built from this spec shares the object.
        min_hold_s, adaptive, stickiness: play selection and assignment options of
            :class:`TeamController`.
    """

    plays: PlaysFactory = standard_team_plays
    skills: SkillsSpec = "baseline"
    decider: CarrierDecider | None = None
    min_hold_s: float = 0.5
    adaptive: bool = False
    stickiness: float = 0.3


def build_team(spec: TeamSpec, team: str, n_robots: int, field: str | FieldGeometry = "div_b",
               robot: RobotParams | None = None, ball: BallParams | None = None, seed: int = 0,
               dt: float = 1.0 / 60.0) -> TeamController:
    """The :class:`TeamController` of ``spec`` for ``team`` ("blue" / "yellow") with
    ``n_robots`` robots on ``field``; ``robot`` / ``ball``: physical parameters (None:
    defaults), ``seed``: the play-selection RNG's, ``dt``: control period (s)."""
    plays = spec.plays(ball=ball, decider=spec.decider)
    return TeamController(team, n_robots, field=field, robot=robot, ball=ball, skills=spec.skills, plays=plays,
                          min_hold_s=spec.min_hold_s, adaptive=spec.adaptive, stickiness=spec.stickiness,
                          seed=seed, dt=dt)


def stp_traffic(env: Any, skills: SkillsSpec = "baseline") -> list[TeamController]:
    """Drivers for :class:`~ssl_marl.skills.robot_env.RobotSkillEnv`: one STP team per
    colour that has robots in ``env`` (skill-task traffic; name it in a training
    config as ``"traffic": "ssl_marl.plays.team:stp_traffic"``)."""
    cfg = env.config
    spec = TeamSpec(skills=skills)
    return [build_team(spec, team, n, cfg.field, cfg.robot, cfg.ball, dt=cfg.dt)
            for team, n in (("blue", cfg.n_blue), ("yellow", cfg.n_yellow)) if n > 0]


__all__ = ["TeamController", "TeamSpec", "keep_clear", "KEEP_CLEAR_M", "PlaysFactory", "build_team", "standard_team_plays", "stp_traffic",
           "required_skills"]
