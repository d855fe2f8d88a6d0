"""Go-to-ball-and-shoot: the paper's tactic (section 4.4, Fig. 2), and the Attacker.

State machine (d_{d-b}: dribbler-ball distance, :func:`~ssl_marl.skills.features.dribbler_ball_distance`)::

    GO_TO_BALL ----(d_db <= 35 mm)----> DRIVE_FORWARD (dribbler on, forward, 1 s)
    DRIVE_FORWARD --(1 s done, d_db <= 35 mm)--> AIM_TO_SHOOT
    DRIVE_FORWARD --(1 s done, d_db >  35 mm)--> GO_TO_BALL
    AIM_TO_SHOOT --(kick commanded / skill SUCCEEDED)--> GO_TO_BALL   (status.kicks += 1)
    AIM_TO_SHOOT --(skill FAILED or d_db > 35 mm before the kick)--> GO_TO_BALL

With ``hold_fire`` (set each tick by a play that decides when to shoot, default False:
never) the machine holds the ball instead of aiming (state ``KEEP``: dribbler on, turn
towards the goal at ``keep_turn_rate``, creep forward at ``keep_speed`` while facing it
and the field ahead is free)::

    DRIVE_FORWARD --(done, near, hold_fire)--> KEEP
    AIM_TO_SHOOT --(hold_fire, no kick yet)--> KEEP
    KEEP --(not hold_fire)--> AIM_TO_SHOOT;  KEEP --(d_db > lost_ball_m)--> GO_TO_BALL

The go-to-ball and aim-to-shoot skills are learned or baseline (``skills=``); drive
forward is the paper's fixed skill. The tactic does not know about goals: the env's
referee counts them and the runner reads them.

:class:`Attacker` is the same machine with one guard for team play
(``keep_out_of_own_defense_area=True``): while the ball lies inside the own defense
area (the goalie's), it waits just outside the area, facing the ball
(state ``WAIT_OUTSIDE_DEFENSE_AREA``); with the default False the machine is exactly
the paper's. ``keep_out_of_opp_defense_area`` does the same at the opponent's defense
area, where touching the ball is a foul (SSL rules: "attacker touches ball in opponent
defense area", a free kick for the opponents): the opponent's goalie clears it.
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass

import numpy as np

from ..envs.game_control import touch_reach, touching_robots
from ..physics.state import WorldState, wrap_angle
from ..skills.base import SkillStatus, make_action
from ..skills.baseline import DriveForward
from ..skills.features import BALL_LOST_DISTANCE, dribbler_ball_distance, heading_between_posts
from ..skills.navigation import NavigateToPoint, NavParams, defense_rect, facing_towards, push_out_of_rect
from .pass_decision import DecisionParams, open_goal_interval
from .set_piece_kick import SetPieceKick, SetPieceState
from .shot_lines import SHOT_REACTION_S, goal_line_targets, heading_goal_point, shot_line_margins
from .tactic_base import NEAR_BALL_M, Tactic, skill_status


#: the interception model of :attr:`ShootParams.aim_reach`'s shot lines (a shot at the kicker's cap)
_SHOT_RATING = DecisionParams()


class ShootState(enum.Enum):
    GO_TO_BALL = "go_to_ball"
    DRIVE_FORWARD = "drive_forward"
    AIM_TO_SHOOT = "aim_to_shoot"
    WAIT_OUTSIDE_DEFENSE_AREA = "wait_outside_defense_area"
    KEEP = "keep"


@dataclass(frozen=True)
class ShootParams:
    """Attributes:
        near_ball_m: "ball near the dribbler" threshold on d_{d-b} (m); paper: 0.035.
        drive_forward_s: duration of the drive-forward skill (s); paper: 1.0.
        drive_forward_speed: its forward speed (m/s).
        keep_out_of_own_defense_area: wait outside the own defense area while the ball
            is in it (team play); False = the paper's machine.
        keep_out_of_opp_defense_area: wait outside the opponent's defense area while
            the ball is in it (touching it there is a foul); False = go for it.
        wait_margin: how far outside the defense area to wait (m, robot centre).
        wait_hysteresis_m: keep waiting until the ball is this far outside the own
            defense area (m), so a ball on the line does not flip the state every
            tick; hand-tuned.
        safe_drive_forward: scale the drive-forward speed down to 0 as the free space
            ahead of the ball (to the field lines, along the heading) shrinks from
            ``safe_free_full_m`` (full speed) to ``safe_free_stop_m`` (stop), so the
            robot does not push the ball out of play; False = paper. The band
            0.1-0.5 m is hand-tuned: at 0.5 m/s and the ball's rolling friction the ball
            stops within ~0.1 m after contact.
        approach_speed: speed governor on the go-to-ball skill (m/s at contact, None =
            off): the commanded speed is capped at sqrt(v^2 + 2 a gap) (a =
            ``approach_decel``, gap = ball distance - reach), so a skill that drives into
            the ball at full speed (the learned one does: it was rewarded for contact, not
            for control) touches it gently enough to keep it. Not in the paper's Fig. 2;
            applied to learned and hand-coded skills alike (the baseline already
            approaches at ~0.7 m/s).
        approach_decel: deceleration used by the governor (m/s^2).
        hold_fire: hold the ball (KEEP) instead of aiming to shoot; plays that decide
            between shooting, passing and keeping set it every tick (False = paper).
        lost_ball_m: KEEP -> GO_TO_BALL when d_{d-b} exceeds this (m).
        keep_turn_rate: KEEP's turn rate towards the goal (rad/s, below aim-to-shoot's 5).
        keep_speed: KEEP's forward creep (m/s; scaled to 0 as free space ahead shrinks).
        keep_target: (x, y) point (m, team frame) KEEP turns and creeps towards; None =
            the opponent goal centre (a decider's "dribble toward a point" sets it).
        keep_tap_m: KEEP taps the ball ahead (dribbler off, a kick of strength
            ``keep_tap_kick``) once it lies this far (m) from where this robot's touch of
            it began, facing the keep target with at least ``keep_tap_free_m`` of field
            ahead, and stops creeping while it may not; the robot then goes to the ball
            again, which starts a new touch. SSL calls excessive dribbling beyond 1 m
            (:data:`~ssl_marl.envs.game_control.MAX_DRIBBLE_M`, measured the same way);
            None = off (KEEP dribbles as far as it is kept).
        keep_tap_kick, keep_tap_free_m: see ``keep_tap_m`` (kick strength in (0, 1]: a
            ball speed of that fraction of ``kick_speed_max``; m).
        snap_shot: in AIM_TO_SHOOT, kick at full strength as soon as the heading lies
            between the posts (the hand-coded skill's first-opportunity rule, applied by
            the tactic whatever the skill; False = the skill alone decides when to kick).
            The passing plays set it: a carrier in a match is pressed within a few tenths
            of a second, and a learned aim-to-shoot trained without opponents waits for a
            centred aim that rarely comes (docs/RESULTS.md, "Passing game").
        aim_open_goal: in AIM_TO_SHOOT, the tactic aims itself at the centre of the widest
            part of the goal mouth that no other robot shadows (seen from the ball;
            :func:`~ssl_marl.plays.pass_decision.open_goal_interval`) and kicks at full
            strength once the heading lies within ``open_aim_window`` x half that part's
            width of its centre (shots at the goalie are wasted: SSL teams aim at the
            largest gap, e.g. TIGERs' and Thunderbots' shot rating; docs/references.md,
            "Passing and pass rating"); with no part at least ``open_aim_min`` (rad) wide,
            or after ``open_aim_timeout_s`` (s) in AIM_TO_SHOOT, the ``snap_shot`` rule (or
            the skill) decides. A narrower gap closes while the carrier turns (the goalie
            moves): in the attack drill (3 attackers, goalie and defender; 200 episodes)
            aiming at gaps from 0.06 rad scored 0.27-0.32 of episodes against 0.56 for the
            snap shot alone, from 0.15 rad 0.59 (docs/RESULTS.md, "Attack drill").
            False = the skill (and ``snap_shot``) alone.
        open_aim_window, open_aim_min, open_aim_timeout_s: see ``aim_open_goal``.
        open_aim_turn_rate: turn rate while aiming with the ball (rad/s).
        aim_reach: in AIM_TO_SHOOT, aim at the shot line the opponents reach last
            (:mod:`~ssl_marl.plays.shot_lines`: ``reach_targets`` points across the goal
            mouth rated by their path margin, opponents reacting after
            ``reach_reaction_s``; teammates in the line block it) and kick at full
            strength once the line along the heading is rated within
            ``reach_tolerance_s`` of the best one, or at least ``reach_good_s``; turns
            towards the best line otherwise; after ``open_aim_timeout_s`` the
            ``snap_shot`` rule (or the skill) decides. Takes precedence over
            ``aim_open_goal``. False = off.
        reach_reaction_s, reach_tolerance_s, reach_good_s, reach_targets: see ``aim_reach``.
    """

    near_ball_m: float = NEAR_BALL_M
    drive_forward_s: float = 1.0
    drive_forward_speed: float = 0.5
    keep_out_of_own_defense_area: bool = False
    keep_out_of_opp_defense_area: bool = False
    wait_margin: float = 0.2
    wait_hysteresis_m: float = 0.1
    safe_drive_forward: bool = False
    safe_free_stop_m: float = 0.1
    safe_free_full_m: float = 0.5
    approach_speed: float | None = 0.8
    approach_decel: float = 3.0
    hold_fire: bool = False
    lost_ball_m: float = BALL_LOST_DISTANCE
    keep_turn_rate: float = 3.0
    keep_speed: float = 0.3
    keep_target: tuple[float, float] | None = None
    keep_tap_m: float | None = None
    keep_tap_kick: float = 0.15
    keep_tap_free_m: float = 1.0
    snap_shot: bool = False
    aim_open_goal: bool = False
    open_aim_window: float = 0.3
    open_aim_min: float = 0.15
    open_aim_timeout_s: float = 0.8
    open_aim_turn_rate: float = 4.0
    aim_reach: bool = False
    reach_reaction_s: float = SHOT_REACTION_S
    reach_tolerance_s: float = 0.03
    reach_good_s: float = 0.15
    reach_targets: int = 21


@dataclass(frozen=True)
class ShootInputs:
    """Attributes:
        d_db: dribbler-ball distance (m).
        skill_status: status of the current state's skill after its last tick.
        kicked: a kick was commanded on the previous tick.
        ball_in_own_defense: ball inside the own defense area.
        ball_near_own_defense: ball inside the own defense area grown by
            ``wait_hysteresis_m``
            (hysteresis for leaving the wait state).
        ball_in_opp_defense, ball_near_opp_defense: the same at the opponent's defense area.
    """

    d_db: float
    skill_status: SkillStatus = SkillStatus.RUNNING
    kicked: bool = False
    ball_in_own_defense: bool = False
    ball_near_own_defense: bool = False
    ball_in_opp_defense: bool = False
    ball_near_opp_defense: bool = False


class GoToBallAndShoot(Tactic):
    """The paper's go-to-ball-and-shoot tactic (see the module docstring)."""

    name = "go_to_ball_and_shoot"
    uses_skills = ("go_to_ball", "aim_to_shoot")
    State = ShootState
    Params = ShootParams
    Inputs = ShootInputs
    initial_state = ShootState.GO_TO_BALL

    def __init__(self, field, robot=None, ball=None, skills="baseline", dt: float = 1.0 / 60.0, **params) -> None:
        self.go_to_ball = None
        self._touch_from: np.ndarray | None = None
        super().__init__(field, robot, ball, skills, dt, **params)
        self.go_to_ball = self._skill("go_to_ball")
        self.aim_to_shoot = self._skill("aim_to_shoot")
        self.drive_forward = DriveForward(field, self.rp, self.bp, duration_s=self.params.drive_forward_s,
                                          speed=self.params.drive_forward_speed, dt=self.dt)
        self.nav = NavigateToPoint(field, self.rp, self.bp, NavParams(avoid_opp_defense=False))
        self.on_enter(self.state)

    def _current_skill(self):
        return {ShootState.GO_TO_BALL: self.go_to_ball, ShootState.DRIVE_FORWARD: self.drive_forward,
                ShootState.AIM_TO_SHOOT: self.aim_to_shoot,
                ShootState.WAIT_OUTSIDE_DEFENSE_AREA: self.nav, ShootState.KEEP: None}[self.state]

    def observe(self, world: WorldState, robot: int) -> ShootInputs:
        ball = world.ball_pos
        self._track_touch(world, robot)
        return ShootInputs(d_db=dribbler_ball_distance(world, robot, self.rp, self.bp),
                           skill_status=(skill_status(self._current_skill()) if self.state is not ShootState.KEEP
                                         else SkillStatus.RUNNING), kicked=self._kicked,
                           ball_in_own_defense=bool(self.field.in_defense_area(ball, -1)),
                           ball_near_own_defense=bool(self.field.in_defense_area(
                               ball, -1, margin=self.params.wait_hysteresis_m)),
                           ball_in_opp_defense=bool(self.field.in_defense_area(ball, +1)),
                           ball_near_opp_defense=bool(self.field.in_defense_area(
                               ball, +1, margin=self.params.wait_hysteresis_m)))

    @staticmethod
    def transition(state: ShootState, inputs: ShootInputs, params: ShootParams) -> ShootState:
        """Fig. 2 of the paper (plus the optional defense-area waits)."""
        S = ShootState
        near = inputs.d_db <= params.near_ball_m
        own, opp = params.keep_out_of_own_defense_area, params.keep_out_of_opp_defense_area
        if own or opp:
            inside = (own and inputs.ball_in_own_defense) or (opp and inputs.ball_in_opp_defense)
            if inside and state is not S.WAIT_OUTSIDE_DEFENSE_AREA:
                return S.WAIT_OUTSIDE_DEFENSE_AREA
            if state is S.WAIT_OUTSIDE_DEFENSE_AREA:
                near_area = (own and inputs.ball_near_own_defense) or (opp and inputs.ball_near_opp_defense)
                return S.WAIT_OUTSIDE_DEFENSE_AREA if near_area else S.GO_TO_BALL
        elif state is S.WAIT_OUTSIDE_DEFENSE_AREA:
            return S.GO_TO_BALL
        if state is S.GO_TO_BALL:
            return S.DRIVE_FORWARD if near else S.GO_TO_BALL
        if state is S.DRIVE_FORWARD:
            if inputs.skill_status is SkillStatus.SUCCEEDED:
                if not near:
                    return S.GO_TO_BALL
                return S.KEEP if params.hold_fire else S.AIM_TO_SHOOT
            return S.DRIVE_FORWARD
        if state is S.AIM_TO_SHOOT:
            if inputs.kicked or inputs.skill_status is not SkillStatus.RUNNING or not near:
                return S.GO_TO_BALL
            return S.KEEP if params.hold_fire else S.AIM_TO_SHOOT
        if state is S.KEEP:
            if inputs.d_db > params.lost_ball_m:
                return S.GO_TO_BALL
            return S.KEEP if params.hold_fire else S.AIM_TO_SHOOT
        raise ValueError(f"unknown state {state!r}")

    def on_enter(self, state: ShootState) -> None:
        if self.go_to_ball is None:  # called from the base constructor before the skills exist
            return
        if state is ShootState.DRIVE_FORWARD:
            self.drive_forward.duration_s = self.params.drive_forward_s
            self.drive_forward.speed = self.params.drive_forward_speed
        skill = self._current_skill()
        if skill is not None:
            skill.reset()

    def execute(self, world: WorldState, robot: int, inputs: ShootInputs) -> np.ndarray:
        if self.state is ShootState.DRIVE_FORWARD and self.params.safe_drive_forward:
            heading = float(world.team(world.frame).heading[robot])
            free = free_distance_ahead(world.ball_pos, heading, self.field)
            p = self.params
            scale = (free - p.safe_free_stop_m) / (p.safe_free_full_m - p.safe_free_stop_m)
            self.drive_forward.speed = p.drive_forward_speed * min(max(scale, 0.0), 1.0)
        if self.state is ShootState.WAIT_OUTSIDE_DEFENSE_AREA:
            pos = world.team(world.frame).pos[robot]
            side = -1 if float(world.ball_pos[0]) < 0.0 else +1  # the area the ball is in (or near)
            rect = defense_rect(self.field, side, self.nav.params.defense_margin + self.params.wait_margin)
            self.nav.target = push_out_of_rect(world.ball_pos, rect)
            self.nav.facing = facing_towards(pos, world.ball_pos)
        if self.state is ShootState.KEEP:
            return self.keep_action(world, robot)
        if self.state is ShootState.AIM_TO_SHOOT and self.params.aim_reach \
                and self._time_in_state < self.params.open_aim_timeout_s:
            return self.reach_aim_action(world, robot)
        if self.state is ShootState.AIM_TO_SHOOT and self.params.aim_open_goal \
                and self._time_in_state < self.params.open_aim_timeout_s:
            action = self.open_goal_action(world, robot)
            if action is not None:
                return action
        if (self.state is ShootState.AIM_TO_SHOOT and self.params.snap_shot
                and bool(world.team(world.frame).kick_ready[robot]) and heading_between_posts(world, robot, self.field)):
            return make_action(dribble=True, kick=1.0)
        action = self._current_skill().act(world, robot)
        if self.state is ShootState.GO_TO_BALL and self.params.approach_speed is not None:
            action = govern_approach(action, world, robot, self.rp, self.bp, self.params.approach_speed,
                                     self.params.approach_decel)
        return action

    def open_goal_action(self, world: WorldState, robot: int) -> np.ndarray | None:
        """``aim_open_goal`` (see :class:`ShootParams`): a full-strength kick when the
        heading lies near the centre of the widest open part of the goal mouth, else a
        turn towards that centre with the dribbler on; None when no part is
        ``open_aim_min`` wide."""
        p = self.params
        ts = world.team(world.frame)
        others = np.concatenate([np.delete(ts.pos, robot, axis=0), world.opponents(world.frame).pos])
        open_angle, aim = open_goal_interval(world.ball_pos, others, self.field, self.rp, self.bp)
        if open_angle < p.open_aim_min:
            return None
        err = float(wrap_angle(aim - float(ts.heading[robot])))
        if abs(err) <= p.open_aim_window * open_angle / 2.0 and bool(ts.kick_ready[robot]):
            return make_action(dribble=True, kick=1.0)
        return self.aim_turn(err)

    def reach_aim_action(self, world: WorldState, robot: int) -> np.ndarray:
        """``aim_reach`` (see :class:`ShootParams`): a full-strength kick when the line along
        the heading is rated (nearly) as well as the best shot line, else a turn towards
        the best line with the dribbler on."""
        p = self.params
        ts = world.team(world.frame)
        ball = world.ball_pos
        heading = float(ts.heading[robot])
        targets = goal_line_targets(self.field, p.reach_targets)
        own = heading_goal_point(ball, heading, self.field)
        if own is not None:
            targets = np.concatenate([targets, own[None, :]])
        mates = np.delete(ts.pos, robot, axis=0)
        margins = shot_line_margins(ball, targets, world.opponents(world.frame).pos, mates, self.rp, self.bp,
                                    _SHOT_RATING, p.reach_reaction_s)
        best = int(np.argmax(margins[:p.reach_targets]))
        m_best = float(margins[best])
        if own is not None and bool(ts.kick_ready[robot]):
            m_own = float(margins[-1])
            if m_own >= p.reach_good_s or (np.isfinite(m_own) and m_own >= m_best - p.reach_tolerance_s):
                return make_action(dribble=True, kick=1.0)
        aim = math.atan2(float(targets[best, 1] - ball[1]), float(targets[best, 0] - ball[0]))
        return self.aim_turn(float(wrap_angle(aim - heading)))

    def aim_turn(self, err: float) -> np.ndarray:
        """Turn with the ball (dribbler on) to close a heading error ``err`` (rad), at most
        ``open_aim_turn_rate``."""
        p = self.params
        omega = float(np.clip(6.0 * err, -p.open_aim_turn_rate, p.open_aim_turn_rate))
        return make_action(omega=omega / self.rp.max_omega, dribble=True)

    def _track_touch(self, world: WorldState, robot: int) -> None:
        """Where this robot's current touch of the ball began, while ``keep_tap_m`` needs it
        (the referee's touch, :func:`~ssl_marl.envs.game_control.touching_robots`; None while
        it does not touch the ball)."""
        if self.params.keep_tap_m is None:
            self._touch_from = None
            return
        ts = world.team(world.frame)
        touching = bool(touching_robots(ts.pos[robot:robot + 1], world.ball_pos, world.ball_height,
                                        ts.ball_on_dribbler[robot:robot + 1],
                                        touch_reach(self.rp.radius, self.bp.radius))[0])
        if not touching:
            self._touch_from = None
        elif self._touch_from is None:
            self._touch_from = np.array(world.ball_pos, float)

    def dribbled_m(self, world: WorldState) -> float:
        """How far (m) the ball lies from where this robot's current touch began (0 without one)."""
        start = self._touch_from
        return 0.0 if start is None else float(np.hypot(*(world.ball_pos - start)))

    def keep_action(self, world: WorldState, robot: int) -> np.ndarray:
        """KEEP: dribbler on, turn towards ``keep_target`` (default the opponent goal
        centre), creep forward when facing it (within 0.4 rad) and the field ahead is free;
        with ``keep_tap_m``, tap the ball ahead before the dribble grows too long."""
        p = self.params
        ts = world.team(world.frame)
        pos, heading = ts.pos[robot], float(ts.heading[robot])
        target = self.field.goal_center(+1) if p.keep_target is None else np.asarray(p.keep_target, float)
        err = float(wrap_angle(facing_towards(pos, target) - heading))
        omega = float(np.clip(6.0 * err, -p.keep_turn_rate, p.keep_turn_rate))
        free = free_distance_ahead(world.ball_pos, heading, self.field)
        speed = p.keep_speed * min(max((free - 0.3) / 0.5, 0.0), 1.0) if abs(err) < 0.4 else 0.0
        tap = False
        if p.keep_tap_m is not None and self.dribbled_m(world) >= p.keep_tap_m:
            tap = abs(err) < 0.4 and free >= p.keep_tap_free_m and bool(ts.kick_ready[robot])
            speed = speed if tap else 0.0  # at the limit: tap, or hold still until a tap fits
        return make_action(vx=speed / self.rp.max_speed, omega=omega / self.rp.max_omega, dribble=not tap,
                           kick=p.keep_tap_kick if tap else 0.0)


def govern_approach(action: np.ndarray, world: WorldState, robot: int, rp, bp, v_touch: float,
                    decel: float) -> np.ndarray:
    """Cap the commanded translational speed of a (5,) action at sqrt(v_touch^2 + 2 decel gap),
    gap = distance from the robot centre to the ball minus the face reach (m)."""
    pos = world.team(world.frame).pos[robot]
    gap = float(np.hypot(*(world.ball_pos - pos))) - rp.front_distance - bp.radius
    v_lim = float(np.sqrt(v_touch ** 2 + 2.0 * decel * max(gap, 0.0)))
    a = np.array(action, dtype=np.float32, copy=True)
    speed = float(np.hypot(a[0], a[1])) * rp.max_speed
    if speed > v_lim:
        a[0:2] *= v_lim / speed
    return a


@dataclass(frozen=True)
class AttackerParams(ShootParams):
    """:class:`ShootParams` and:

    Attributes:
        set_piece: the referee gave our team a kickoff or free kick not taken yet; the
            attacker takes it with one kick
            (:class:`~ssl_marl.plays.set_piece_kick.SetPieceKick`: a shot at the open goal
            or a pass, :func:`~ssl_marl.plays.set_piece_kick.set_piece_choice`) instead of
            its machine, which would carry the ball off on the dribbler (a
            double touch by the rules). Plays set it every tick from ``ctx.set_piece``.
    """

    set_piece: bool = False


class Attacker(GoToBallAndShoot):
    """Attacker role: :class:`GoToBallAndShoot` that waits outside the own defense area
    while the ball is in it (the goalie clears it), does not drive the ball over the
    lines in DRIVE_FORWARD (``safe_drive_forward``) and takes our set pieces with one
    kick (``set_piece``); when the set piece ends the machine starts again from
    GO_TO_BALL. The team controller keeps a set piece's kicker off the ball-taking roles
    until another robot has touched the ball (the double-touch rule)."""

    name = "attacker"
    Params = AttackerParams
    takes_ball = True

    def __init__(self, field, robot=None, ball=None, skills="baseline", dt: float = 1.0 / 60.0, **params) -> None:
        params.setdefault("keep_out_of_own_defense_area", True)
        params.setdefault("safe_drive_forward", True)
        self._in_set_piece = False
        super().__init__(field, robot, ball, skills, dt, **params)
        self.set_piece_kick = SetPieceKick(self.field, self.rp, self.bp, dt=self.dt)

    def act(self, world: WorldState, robot: int) -> np.ndarray:
        if not self.params.set_piece:
            if self._in_set_piece:
                self._in_set_piece = False
                self.set_piece_kick.reset()
                self.reset()
            return super().act(world, robot)
        self._in_set_piece = True
        before = self.set_piece_kick.state
        a = self.set_piece_kick.act(world, robot)
        self._kicked = before is not SetPieceState.DONE and self.set_piece_kick.state is SetPieceState.DONE
        self._kicks += int(self._kicked)
        return a


def free_distance_ahead(point: np.ndarray, heading: float, field) -> float:
    """Distance (m) from ``point`` along ``heading`` to the playing-area boundary (the
    goal lines and touch lines); 0 if the point is outside."""
    x, y = float(point[0]), float(point[1])
    c, s = math.cos(heading), math.sin(heading)
    L2, W2 = field.half_length, field.half_width
    if abs(x) > L2 or abs(y) > W2:
        return 0.0
    t = math.inf
    if c > 1e-9:
        t = min(t, (L2 - x) / c)
    elif c < -1e-9:
        t = min(t, (-L2 - x) / c)
    if s > 1e-9:
        t = min(t, (W2 - y) / s)
    elif s < -1e-9:
        t = min(t, (-W2 - y) / s)
    return float(t)


__all__ = ["ShootState", "ShootParams", "ShootInputs", "GoToBallAndShoot", "AttackerParams", "Attacker",
           "free_distance_ahead"]
