"""The env's referee as game-controller ``Referee`` messages.

Our match referee restarts play at once (:mod:`ssl_marl.envs.referee`): after a goal
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
Blue's goal is at -x (``blue_team_on_positive_half`` False).
"""

from __future__ import annotations

import numpy as np

from ..physics.state import WorldState
from .proto import ssl_referee_pb2 as ref_pb

Referee = ref_pb.Referee


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

    def _issue(self, command: int, now_us: int, next_command: int | None = None,
               designated: np.ndarray | None = None) -> None:
        self.command, self.next_command, self.designated = command, next_command, designated
        self.counter = (self.counter + 1) & 0xFFFFFFFF
        self.command_time_us = now_us

    def start(self, now_us: int) -> None:
        """A new match: kickoff for blue."""
        self.stage = Referee.NORMAL_FIRST_HALF
        self.score = {"blue": 0, "yellow": 0}
        self._issue(Referee.PREPARE_KICKOFF_BLUE, now_us, Referee.NORMAL_START)

    def update(self, events: list[dict], truth: WorldState, score: dict[str, int], time_left_s: float,
               finished: bool, now_us: int) -> bool:
        """Advance by one control step's env ``events``; True when a new command was
        issued (send a packet at once). ``truth`` is the field-frame ground truth."""
        self.score = {"blue": int(score.get("blue", 0)), "yellow": int(score.get("yellow", 0))}
        self.time_left_s = float(time_left_s)
        if finished:
            if self.stage == Referee.POST_GAME:
                return False
            self.stage = Referee.POST_GAME
            self._issue(Referee.HALT, now_us)
            return True
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
