"""The env's referee as game-controller ``Referee`` messages.

**Plain format** (no SSL game control: :meth:`RefereeState.update` gets no ``game``). Our
match referee restarts play at once (:mod:`ssl_marl.envs.referee`): after a goal
the kickoff formation is placed and play goes on; after the ball left the field (or
no progress) the ball is placed and play goes on. :class:`RefereeState` turns those
events into the commands a game controller would send, each held for one control
step before the restart command:

* start and after a goal: ``PREPARE_KICKOFF_<team>`` (the team that kicks off: blue
  at the start, the conceding team after a goal) -> ``NORMAL_START``;
* ball out / no progress: ``BALL_PLACEMENT_<team>`` with the designated position (the
  restart spot, mm, field frame; the team with the robot nearest to it) -> ``FORCE_START``;
* the end of the match: stage ``POST_GAME``, command ``HALT``.

Stage: ``NORMAL_FIRST_HALF`` for the whole match (``stage_time_left`` = time left, µs).

**SSL format** (the env's SSL game control, :mod:`ssl_marl.envs.game_control`; ``update``
gets the match's :class:`GameView`). The packets carry the env's own commands, as the SSL
game controller would send them:

* ``STOP`` -> ``STOP`` with ``next_command`` (the set piece it announces) and
  ``designated_position`` (the ball's spot, the env's automatic placement);
* ``KICKOFF(team)`` -> ``PREPARE_KICKOFF_<team>``, one control step later ``NORMAL_START``;
* ``FREE_KICK(team)`` -> ``DIRECT_FREE_<team>`` with the spot;
* ``RUNNING`` after a kickoff or free kick that was taken (the ball moved
  ``IN_PLAY_DISTANCE`` from its spot): no new command (the game controller's command
  stays, as in SSL); after one that was not taken in time (the env's free-kick timeout):
  ``FORCE_START``.

Stages: ``NORMAL_FIRST_HALF_PRE`` until the first kickoff's ``NORMAL_START``, then
``NORMAL_FIRST_HALF``; at half-time ``NORMAL_SECOND_HALF_PRE`` (the env has no break: the
second half's kickoff is placed at once), ``NORMAL_SECOND_HALF`` from its ``NORMAL_START``;
``POST_GAME`` with ``HALT`` at the end. ``stage_time_left``: the half's time left on the
match clock (which stops during STOP with ``clock_stops``), µs. Fouls reach the teams as
the free kicks they give; no ``game_events`` are sent.

Frames: the served field frame keeps blue's goal at -x in both halves (the env's field
frame: the field is point-symmetric, so the teams' change of ends at half-time changes
nothing a client sees but the stage), so ``blue_team_on_positive_half`` is False
throughout.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..envs import game_control as gc
from ..physics.state import WorldState
from .proto import ssl_referee_pb2 as ref_pb

Referee = ref_pb.Referee

#: the env's set pieces (command, team) as the served stream sends them
_SENT_SET_PIECES = {(gc.KICKOFF, "blue"): Referee.PREPARE_KICKOFF_BLUE, (gc.KICKOFF, "yellow"): Referee.PREPARE_KICKOFF_YELLOW,
                    (gc.FREE_KICK, "blue"): Referee.DIRECT_FREE_BLUE, (gc.FREE_KICK, "yellow"): Referee.DIRECT_FREE_YELLOW}
#: the game controller's set-piece commands as the env's (command, team) when read: those sent, and the
#: indirect free kicks (read as free kicks, never sent)
_SET_PIECES = {**{cmd: pair for pair, cmd in _SENT_SET_PIECES.items()},
               Referee.INDIRECT_FREE_BLUE: (gc.FREE_KICK, "blue"), Referee.INDIRECT_FREE_YELLOW: (gc.FREE_KICK, "yellow")}


@dataclass(frozen=True)
class GameView:
    """What the referee stream reads of a match under SSL game control.

    Attributes:
        referee: the match task's command (:class:`ssl_marl.envs.game_control.RefereeState`,
            field frame, m).
        half: 1 or 2.
        time_left_s: the half's time left on the match clock (s).
    """

    referee: gc.RefereeState
    half: int
    time_left_s: float


def set_piece_command(command: str, team: str | None) -> int | None:
    """The game controller's command for the env's ``KICKOFF`` / ``FREE_KICK`` of ``team``
    (``PREPARE_KICKOFF_<team>`` / ``DIRECT_FREE_<team>``); None for other commands."""
    return _SENT_SET_PIECES.get((command, team))


class RefereeState:
    """Command, counter and timestamps of the referee stream for one match.

    Args:
        team_names: {"blue": name, "yellow": name} sent in the team infos.
        goalkeepers: {"blue": id, "yellow": id} (robot 0 keeps goal in our teams).
    """

    def __init__(self, team_names: dict[str, str] | None = None, goalkeepers: dict[str, int] | None = None) -> None:
        self.names = dict(team_names or {"blue": "blue", "yellow": "yellow"})
        self.goalkeepers = dict(goalkeepers or {"blue": 0, "yellow": 0})
        self.stage = Referee.NORMAL_FIRST_HALF
        self.command = Referee.PREPARE_KICKOFF_BLUE
        self.next_command: int | None = Referee.NORMAL_START
        self.counter = 0
        self.command_time_us = 0
        self.designated: np.ndarray | None = None
        self.score = {"blue": 0, "yellow": 0}
        self.time_left_s = 0.0
        self._game_seen: gc.RefereeState | None = None  #: the env command last turned into packets

    def _issue(self, command: int, now_us: int, next_command: int | None = None,
               designated: np.ndarray | None = None) -> None:
        self.command, self.next_command, self.designated = command, next_command, designated
        self.counter = (self.counter + 1) & 0xFFFFFFFF
        self.command_time_us = now_us

    def start(self, now_us: int, game: GameView | None = None) -> None:
        """A new match: kickoff for blue (with ``game``: the match's first command, the
        stage ``NORMAL_FIRST_HALF_PRE`` until its ``NORMAL_START``)."""
        self.score = {"blue": 0, "yellow": 0}
        self._game_seen = None
        if game is None:
            self.stage = Referee.NORMAL_FIRST_HALF
            self._issue(Referee.PREPARE_KICKOFF_BLUE, now_us, Referee.NORMAL_START)
            return
        self.stage = Referee.NORMAL_FIRST_HALF_PRE
        self.time_left_s = float(game.time_left_s)
        self._follow(game, None, now_us)

    def update(self, events: list[dict], truth: WorldState, score: dict[str, int], time_left_s: float,
               finished: bool, now_us: int, game: GameView | None = None) -> bool:
        """Advance by one control step's env ``events``; True when a new command was
        issued (send a packet at once). ``truth`` is the field-frame ground truth;
        ``game``: the match under SSL game control (module docstring; None: plain format,
        the commands follow ``events``); ``time_left_s``: without ``game``, the match's."""
        self.score = {"blue": int(score.get("blue", 0)), "yellow": int(score.get("yellow", 0))}
        self.time_left_s = float(time_left_s if game is None else game.time_left_s)
        if finished:
            if self.stage == Referee.POST_GAME:
                return False
            self.stage = Referee.POST_GAME
            self._issue(Referee.HALT, now_us)
            return True
        if game is not None:
            return self._follow(game, truth, now_us)
        goals = [e for e in events if e.get("type") == "goal"]
        restarts = [e for e in events if e.get("type") in ("ball_out", "no_progress")]
        if goals:
            kicker = "yellow" if goals[-1]["team"] == "blue" else "blue"
            self._issue(Referee.PREPARE_KICKOFF_BLUE if kicker == "blue" else Referee.PREPARE_KICKOFF_YELLOW,
                        now_us, Referee.NORMAL_START)
            return True
        if restarts:
            spot = np.asarray(restarts[-1].get("placement", truth.ball_pos), float)
            team = self._nearest_team(truth, spot)
            self._issue(Referee.BALL_PLACEMENT_BLUE if team == "blue" else Referee.BALL_PLACEMENT_YELLOW,
                        now_us, Referee.FORCE_START, designated=spot)
            return True
        if self.next_command is not None and self.command != self.next_command:
            self._issue(self.next_command, now_us)
            return True
        return False

    def _follow(self, game: GameView, truth: WorldState | None, now_us: int) -> bool:
        """The SSL format's packets (module docstring); True when a command was issued."""
        half_pre = Referee.NORMAL_FIRST_HALF_PRE if game.half == 1 else Referee.NORMAL_SECOND_HALF_PRE
        if game.half == 2 and self.stage in (Referee.NORMAL_FIRST_HALF_PRE, Referee.NORMAL_FIRST_HALF):
            self.stage = half_pre
        ref, seen = game.referee, self._game_seen
        if ref != seen:
            self._game_seen = ref
            spot = None if ref.position is None else np.asarray(ref.position, float)
            if ref.command == gc.STOP:
                nxt = set_piece_command(ref.next_command or "", ref.next_team)
                self._issue(Referee.STOP, now_us, nxt, designated=spot)
                return True
            command = set_piece_command(ref.command, ref.team)
            if command is not None:
                self._issue(command, now_us, Referee.NORMAL_START if ref.command == gc.KICKOFF else None,
                            designated=spot)
                return True
            # RUNNING: a set piece that was taken keeps its command, one that timed out is forced
            timed_out = (seen is not None and seen.command in (gc.KICKOFF, gc.FREE_KICK) and seen.position is not None
                         and truth is not None and float(np.hypot(*(truth.ball_pos - np.asarray(seen.position, float))))
                         < gc.IN_PLAY_DISTANCE - 1e-9)
            if seen is None or timed_out:
                self._issue(Referee.FORCE_START, now_us)
                return True
            return False
        if self.next_command == Referee.NORMAL_START and self.command != Referee.NORMAL_START \
                and self.command in (Referee.PREPARE_KICKOFF_BLUE, Referee.PREPARE_KICKOFF_YELLOW):
            self._issue(Referee.NORMAL_START, now_us, designated=self.designated)
            if self.stage == half_pre:
                self.stage = Referee.NORMAL_FIRST_HALF if game.half == 1 else Referee.NORMAL_SECOND_HALF
            return True
        return False

    @staticmethod
    def _nearest_team(truth: WorldState, spot: np.ndarray) -> str:
        best, team = np.inf, "blue"
        for name in ("blue", "yellow"):
            pos = truth.team(name).pos
            if len(pos):
                d = float(np.min(np.linalg.norm(pos - spot, axis=1)))
                if d < best:
                    best, team = d, name
        return team

    def message(self, now_us: int, source_identifier: str = "ssl_marl") -> ref_pb.Referee:
        """The current ``Referee`` packet stamped ``now_us`` (Unix µs)."""
        msg = Referee(source_identifier=source_identifier, packet_timestamp=int(now_us), stage=self.stage,
                      command=self.command, command_counter=self.counter,
                      command_timestamp=int(self.command_time_us), blue_team_on_positive_half=False)
        if self.stage != Referee.POST_GAME:
            msg.stage_time_left = int(np.clip(self.time_left_s * 1e6, -2 ** 31, 2 ** 31 - 1))
        for team, info in (("yellow", msg.yellow), ("blue", msg.blue)):
            info.name = self.names.get(team, team)
            info.score = self.score[team]
            info.red_cards = 0
            info.yellow_cards = 0
            info.timeouts = 4
            info.timeout_time = 300_000_000
            info.goalkeeper = int(self.goalkeepers.get(team, 0))
        if self.designated is not None:
            msg.designated_position.x = float(self.designated[0] * 1000.0)
            msg.designated_position.y = float(self.designated[1] * 1000.0)
        if self.next_command is not None:
            msg.next_command = self.next_command
        return msg


#: game-controller commands under which our robots keep 0.5 m from the ball (the env's STOP):
#: stop, halt, ball placement (we place no ball), timeouts and penalties (not played here)
_KEEP_CLEAR_COMMANDS = (Referee.HALT, Referee.STOP, Referee.BALL_PLACEMENT_BLUE, Referee.BALL_PLACEMENT_YELLOW,
                        Referee.TIMEOUT_BLUE, Referee.TIMEOUT_YELLOW, Referee.PREPARE_PENALTY_BLUE,
                        Referee.PREPARE_PENALTY_YELLOW)


class RefereeFollower:
    """A client's view of the game controller: ``Referee`` packets in, the env's command
    (:class:`ssl_marl.envs.game_control.RefereeState`, field frame, m) out, for a team
    controller that obeys it as it obeys the env's referee
    (:meth:`ssl_marl.plays.team.TeamController.act`, ``referee=``).

    ``STOP``, ``HALT``, ball placement, timeouts and penalties -> ``STOP`` (keep 0.5 m);
    ``PREPARE_KICKOFF_<team>`` and the ``NORMAL_START`` after it -> ``KICKOFF(team)``;
    ``DIRECT_FREE_<team>`` / ``INDIRECT_FREE_<team>`` -> ``FREE_KICK(team)``; a kickoff or
    free kick turns ``RUNNING`` once the ball has moved ``IN_PLAY_DISTANCE`` from where it
    lay when the set piece began (as the rules put the ball in play); ``NORMAL_START``
    otherwise and ``FORCE_START`` -> ``RUNNING``. Before any packet: ``RUNNING``.
    """

    def __init__(self) -> None:
        self.state = gc.RefereeState()
        self._counter: int | None = None
        self._spot: np.ndarray | None = None

    def on_message(self, msg: ref_pb.Referee) -> None:
        """Take a referee packet (a repeated one, same ``command_counter``, changes nothing)."""
        if self._counter is not None and msg.command_counter == self._counter:
            return
        self._counter = int(msg.command_counter)
        command = msg.command
        spot = (float(msg.designated_position.x) / 1000.0, float(msg.designated_position.y) / 1000.0) \
            if msg.HasField("designated_position") else None
        prev = self.state
        if command in _KEEP_CLEAR_COMMANDS:
            nxt = _SET_PIECES.get(msg.next_command) if msg.HasField("next_command") else None
            self.state = gc.RefereeState(gc.STOP, None, spot, 0.0, nxt[0] if nxt else None, nxt[1] if nxt else None)
        elif command in _SET_PIECES:
            kind, team = _SET_PIECES[command]
            self.state = gc.RefereeState(kind, team, spot)
            self._spot = None  # the ball's first seen position (a detection, not the designated spot)
        elif command == Referee.NORMAL_START and prev.command == gc.KICKOFF:
            pass  # the kickoff may now be taken: the set piece holds until the ball moves
        else:
            self.state = gc.RefereeState()

    def update(self, ball_pos: np.ndarray) -> gc.RefereeState:
        """The command for a frame whose ball (field frame, m) lies at ``ball_pos``."""
        if self.state.command in (gc.KICKOFF, gc.FREE_KICK):
            ball = np.asarray(ball_pos, float)
            if self._spot is None:
                self._spot = ball.copy()
            elif float(np.hypot(*(ball - self._spot))) >= gc.IN_PLAY_DISTANCE:
                self.state, self._spot = gc.RefereeState(), None
        return self.state
