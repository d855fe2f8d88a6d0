"""The full-field match: SSL referee, kickoffs, team rewards (the env's default task).

Start
    Kickoff formation with the ball on the centre mark (``randomize_reset``: robots and
    ball at random); reset options override (see :mod:`ssl_marl.envs.tasks.scene`).
Rules, after every control tick (``referee``, see :mod:`ssl_marl.envs.referee`)
    Goal: the scoring team's score + 1, event ``goal``; the step's remaining ticks are
    skipped. Ball out of play: event ``ball_out``; the ball is placed 0.2 m inside the
    field and robots within 0.5 m of it are moved out. No progress (the ball within
    0.25 m of one spot for ``no_progress_s``, default 10 s, the SSL referee's force
    start): event ``no_progress`` and the same restart at the ball's position.
Reward
    Shared by a team: sum over named terms x ``reward_scales``. ``goal``: +1 when the
    team scores, -1 when it concedes. ``ball_progress``: ball displacement towards the
    opponent goal / (L/2). ``possession``: +dt while a robot of the team holds the ball.
Match clock (:attr:`MatchTask.clock_s`)
    The simulated time, or with ``clock_stops`` the simulated time less the STOPs (SSL
    rules: the clock stops during stop, halt and ball placement). ``max_time_s`` and
    ``half_time_s`` read this clock.
End
    Truncation when the match clock reaches ``max_time_s``; termination after a goal if
    ``after_goal == "terminate"``, otherwise the kickoff formation is placed and play
    goes on.
SSL game control (``ssl_restarts``, ``fouls``; :mod:`ssl_marl.envs.game_control`)
    Referee commands (STOP, KICKOFF(team), FREE_KICK(team), RUNNING) in
    :attr:`MatchTask.referee_state` and as ``referee`` events; free kicks after ball
    out, no progress and fouls; fouls as ``foul`` events.
Restart placement (``restart_jitter_m`` > 0)
    Kickoff formations and the robots cleared from a placed ball are drawn from the
    env's seeded ``np_random``: the same seed gives the same match, but no two restarts
    put the robots in the same poses, so a deterministic kickoff cannot replay itself.
Half-time (``half_time_s``)
    At that time on the match clock: event ``half_time``, the score kept, the kickoff formation
    placed, yellow kicks off. The teams change ends: the field is point-symmetric, so
    the env keeps simulating in its field frame (blue's own goal at -x) and records
    the swap as :attr:`MatchTask.sides_swapped`; the stadium frame of the second half
    is the field frame turned by 180 degrees ((x, y) -> (-x, -y)). Every team frame, and
    so every controller, is the same in both halves.
"""

from __future__ import annotations

import numpy as np

from ..config import MatchRules
from ..game_control import (FREE_KICK, IN_PLAY_DISTANCE, KICKOFF, RUNNING, STOP, RefereeState, TouchWatch,
                            jittered_clearance, jittered_kickoff, kicked_rows, other, too_close_to_kick_point)
from ..referee import (RESTART_CLEARANCE, NoProgressWatch, clear_robots_from, free_kick_spot, judge, kickoff_poses,
                       placement_point)
from .base import Task
from .engine import Engine
from .scene import Scene, scene_from_options

_WORLD = np.zeros(1, np.intp)  # the single env is world 0 of a one-world NoProgressWatch
#: the side (sign of x, field frame) of each team's own goal: the ball out over that goal
#: line gives the team a goal kick (the field frame keeps blue's goal at -x in both halves)
_OWN_GOAL_SIDE = {"blue": -1, "yellow": 1}


class MatchTask(Task):
    """The full-field match (see the module docstring); ``rules`` default to the env's
    ``config.match`` (:class:`~ssl_marl.envs.config.MatchRules`)."""

    name = "match"

    def __init__(self, rules: MatchRules | None = None) -> None:
        super().__init__()
        self.rules = rules
        self.goal_for: str | None = None  #: team that scored in the current step
        self._prev_ball_x = 0.0
        self._watch: NoProgressWatch | None = None
        #: the referee's command to the teams (RUNNING throughout without ``ssl_restarts``)
        self.referee_state = RefereeState()
        self.half = 1  #: 1 or 2 (``half_time_s``)
        self.sides_swapped = False  #: True in the second half (module docstring)
        self._touch: TouchWatch | None = None
        self._half_time_now = False
        self._stopped_s = 0.0  #: s of simulated time the match clock stood still (``clock_stops``)
        self._pending_free_kick: str | None = None
        self._pending_command = FREE_KICK  #: what follows the STOP (a repeated kickoff stays one)
        self._spot = np.zeros(2)
        self._event_mark = 0
        #: the referee events of commands given outside a tick go out with a step's events: the
        #: match's first kickoff with the first step's, a kickoff after a goal or at half-time
        #: with the events of the step that placed it (the current step's list, from after_tick)
        self._pending_events: list[dict] = []
        self._step_events: list[dict] | None = None  #: set by every after_tick, before after_step

    def bind(self, env: Engine) -> None:
        super().bind(env)
        if self.rules is None:
            self.rules = env.config.match

    def reset_scene(self, env: Engine, options: dict) -> Scene:
        return scene_from_options(env, options, "random" if self.rules.randomize_reset else "kickoff")

    def start(self, env: Engine) -> None:
        self.goal_for = None
        self._prev_ball_x = float(env.world_state().ball_pos[0])
        self._watch = NoProgressWatch(1, self.rules.no_progress_s)
        self._restart_watch(env)
        r = self.rules
        self.half, self.sides_swapped, self._half_time_now = 1, False, False
        self._stopped_s = 0.0
        self.referee_state = RefereeState(since=float(env.world_state().t))
        self._game = r.ssl_restarts or r.fouls or r.half_time_s is not None
        self._touch = (TouchWatch(env.config.n_blue, env.config.n_yellow, env.config.robot.radius,
                                  env.config.ball.radius) if self._game else None)
        self._pending_events, self._step_events = [], None
        if r.ssl_restarts:
            w = env.world_state()
            self._command(KICKOFF, "blue", w.ball_pos, w.t, self._pending_events)

    def _restart_watch(self, env: Engine) -> None:
        w = env.world_state()
        self._watch.restart(_WORLD, w.ball_pos[None, :], np.array([w.t]))

    def begin_step(self, env: Engine) -> None:
        self.goal_for = None
        self._event_mark = 0

    def clock_s(self, env: Engine) -> float:
        """The match clock (s): the simulated time, less the STOPs with ``clock_stops``."""
        return float(env.world_state().t) - self._stopped_s

    def after_tick(self, env: Engine, events: list[dict]) -> bool:
        if self.rules.clock_stops and self.referee_state.command == STOP:  # the tick just simulated was a STOP
            self._stopped_s += env.config.dt
        if self._pending_events:
            events.extend(self._pending_events)
            self._pending_events = []
        self._step_events = events
        if not self.rules.referee:
            return False
        truth, f = env.world_state(), env.field
        call = judge(truth, f, env.config.ball.radius)
        if call.goal_for is not None:
            env.award_goal(call.goal_for, events)
            self.goal_for = call.goal_for
            return True
        if self._game:
            return self._game_tick(env, truth, call, events)
        if call.ball_out:
            events.append({"type": "ball_out", "t": truth.t, "placement": call.placement.tolist()})
            self._restart_play(env, call.placement)
        elif self._watch.update(_WORLD, truth.ball_pos[None, :], np.array([truth.t]))[0]:
            place = placement_point(truth.ball_pos, f)
            events.append({"type": "no_progress", "t": truth.t, "placement": place.tolist()})
            self._restart_play(env, place)
        return False

    def _restart_play(self, env: Engine, place: np.ndarray) -> None:
        """Ball at ``place`` (m, at rest), robots within 0.5 m of it moved out."""
        pose = env.robot_poses()
        if self.rules.restart_jitter_m > 0:
            new_pos = jittered_clearance(place, pose[:, 0:2], env.field, RESTART_CLEARANCE,
                                         self.rules.restart_jitter_m, env.np_random, env.config.robot.radius)
        else:
            new_pos = clear_robots_from(place, pose[:, 0:2], env.field, robot_radius=env.config.robot.radius)
        moved = np.flatnonzero(np.any(new_pos != pose[:, 0:2], axis=1))
        if moved.size:
            pose[moved, 0:2] = new_pos[moved]
            env.place_robots(pose, only=moved)
        env.place_ball(place)
        self._prev_ball_x = float(env.world_state().ball_pos[0])
        self._restart_watch(env)

    def rewards(self, env: Engine) -> tuple[dict[str, float], dict[str, dict[str, float]]]:
        scales = self.rules.reward_scales
        truth = env.world_state()
        bx = float(truth.ball_pos[0])
        progress = (bx - self._prev_ball_x) / env.field.half_length
        self._prev_ball_x = bx
        possess = {"blue": bool(truth.blue.ball_on_dribbler.any()), "yellow": bool(truth.yellow.ball_on_dribbler.any())}
        terms = {}
        for team, sgn in (("blue", 1.0), ("yellow", -1.0)):
            goal = 0.0 if self.goal_for is None else (1.0 if self.goal_for == team else -1.0)
            terms[team] = {"goal": scales["goal"] * goal,
                           "ball_progress": scales["ball_progress"] * sgn * progress,
                           "possession": scales["possession"] * (env.config.dt if possess[team] else 0.0)}
        team_reward = {team: float(sum(t.values())) for team, t in terms.items()}
        return {a: team_reward[env.team_of(a)] for a in env.agents}, terms

    def end(self, env: Engine) -> tuple[bool, bool]:
        terminated = self.goal_for is not None and self.rules.after_goal == "terminate"
        truncated = (self.clock_s(env) >= self.rules.max_time_s - 1e-9) and not terminated
        return terminated, truncated

    def after_step(self, env: Engine, terminated: bool, truncated: bool) -> None:
        half_time, self._half_time_now = self._half_time_now, False
        if (self.goal_for is not None or half_time) and not (terminated or truncated and half_time):  # kickoff
            poses = kickoff_poses(env.field, env.config.n_blue, env.config.n_yellow)
            if self.rules.restart_jitter_m > 0:
                poses = jittered_kickoff(poses, env.config.n_blue, env.field, self.rules.restart_jitter_m,
                                         env.np_random, env.config.robot.radius)
            env.place_robots(poses)
            env.place_ball(np.zeros(2))
            self._prev_ball_x = 0.0
            self._restart_watch(env)
            if self._touch is not None:
                self._touch.reset()
            if self.rules.ssl_restarts:
                team = "yellow" if half_time else other(self.goal_for)
                self._command(KICKOFF, team, np.zeros(2), env.world_state().t, self._step_events)

    # ------------------------------------------------------------ SSL game control
    def _command(self, command: str, team: str | None, position: np.ndarray | None, t: float,
                 events: list[dict] | None, next_command: str | None = None, next_team: str | None = None) -> None:
        pos = None if position is None else (float(position[0]), float(position[1]))
        self.referee_state = RefereeState(command, team, pos, float(t), next_command, next_team)
        if position is not None:
            self._spot = np.array(pos)
        if events is not None:
            events.append({"type": "referee", **self.referee_state.to_dict(), "t": float(t)})

    def _game_tick(self, env: Engine, truth, call, events: list[dict]) -> bool:
        """One tick of :mod:`~ssl_marl.envs.game_control` (goals are judged before)."""
        r, f = self.rules, env.field
        kicked = kicked_rows(events[self._event_mark:], env.agent_index)
        self._event_mark = len(events)
        touch = self._touch.touching(truth, kicked)
        if r.half_time_s is not None and self.half == 1 and self.clock_s(env) >= r.half_time_s - 1e-9:
            self.half, self.sides_swapped, self._half_time_now = 2, True, True
            events.append({"type": "half_time", "t": truth.t, "score": dict(getattr(env, "score", {}))})
            return True  # after_step places the second half's kickoff
        st = self.referee_state
        if call.ball_out:
            team = self._free_kick_team(truth)
            place = call.placement
            if r.ssl_restarts:
                over = int(np.sign(truth.ball_pos[0])) if abs(truth.ball_pos[0]) >= f.half_length else 0
                place = free_kick_spot(truth.ball_pos, f, goal_line=over, goal_kick=over == _OWN_GOAL_SIDE[team])
            events.append({"type": "ball_out", "t": truth.t, "placement": place.tolist(),
                           **({"free_kick_for": team} if r.ssl_restarts else {})})
            self._restart(env, place, team, truth.t, events)
            return False
        if st.command == RUNNING:
            foul = self._touch.update(truth, touch, f, r.fouls, kicked)
            if foul is not None:
                self._call_foul(env, *foul, truth, events)
            elif self._watch.update(_WORLD, truth.ball_pos[None, :], np.array([truth.t]))[0]:
                place = self._free_kick_point(truth.ball_pos, f)
                team = self._free_kick_team(truth)
                events.append({"type": "no_progress", "t": truth.t, "placement": place.tolist()})
                self._restart(env, place, team, truth.t, events)
            return False
        if st.command == STOP:
            if np.hypot(*(truth.ball_pos - self._spot)) > 0.01:
                env.place_ball(self._spot)
            if truth.t - st.since >= r.stop_s - 1e-9:
                self._command(self._pending_command, self._pending_free_kick, self._spot, truth.t, events)
            return False
        self._touch.update(truth, touch, f, False, kicked)  # KICKOFF / FREE_KICK: who touches, no fouls
        taken = np.hypot(*(truth.ball_pos - self._spot)) > IN_PLAY_DISTANCE
        if not taken and r.fouls:
            defending = other(st.team)
            near = too_close_to_kick_point(truth.team(defending).pos, self._spot)
            if near is not None:  # the same set piece again after a STOP (module docstring of game_control)
                row = near + (env.config.n_blue if defending == "yellow" else 0)  # blue's rows come first
                events.append({"type": "foul", "foul": "defender_too_close", "team": defending,
                               "agent": env.possible_agents[row], "t": truth.t,
                               "placement": self._spot.tolist()})
                self._restart(env, self._spot.copy(), st.team, truth.t, events, command=st.command)
                return False
        if taken or truth.t - st.since >= r.free_kick_timeout_s - 1e-9:
            taker = self._touch.last_robot if taken else None
            self._command(RUNNING, None, None, truth.t, events)
            self._touch.taken_by(taker)
            self._restart_watch(env)
            if r.fouls and taker is not None and self._touch.carries(truth, taker, kicked):
                self._call_foul(env, "double_touch", taker, truth, events)  # in contact over the 0.05 m
        return False

    def _call_foul(self, env: Engine, name: str, row: int, truth, events: list[dict]) -> None:
        """Foul ``name`` by the robot in engine row ``row``: the event, and the other team's
        free kick where the ball is (placed by the rules)."""
        offender = str(self._touch.teams[row])
        place = self._free_kick_point(truth.ball_pos, env.field)
        events.append({"type": "foul", "foul": name, "team": offender, "agent": env.possible_agents[row],
                       "t": truth.t, "placement": place.tolist()})
        self._restart(env, place, other(offender), truth.t, events)

    def _free_kick_point(self, ball_pos: np.ndarray, field) -> np.ndarray:
        """Where a free kick after a foul or no progress is placed: the SSL spot
        (:func:`~ssl_marl.envs.referee.free_kick_spot`) with ``ssl_restarts``, else
        :func:`~ssl_marl.envs.referee.placement_point`."""
        return free_kick_spot(ball_pos, field) if self.rules.ssl_restarts else placement_point(ball_pos, field)

    def _free_kick_team(self, truth) -> str:
        """The team that did not touch the ball last (no touch yet: the team defending
        the half the ball is in)."""
        last = self._touch.last_team()
        if last is not None:
            return other(last)
        return "blue" if truth.ball_pos[0] < 0 else "yellow"

    def _restart(self, env: Engine, place: np.ndarray, team: str, t: float, events: list[dict],
                 command: str = FREE_KICK) -> None:
        """Ball placed at ``place``; with ``ssl_restarts`` a STOP, then ``command`` (a free
        kick, or the kickoff that is taken again) for ``team``."""
        self._restart_play(env, place)
        self._touch.reset()
        if not self.rules.ssl_restarts:
            return
        self._pending_free_kick, self._pending_command = team, command
        if self.rules.stop_s > 0:
            self._command(STOP, None, place, t, events, next_command=command, next_team=team)
        else:
            self._command(command, team, place, t, events)
