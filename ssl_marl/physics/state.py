"""The world-state snapshot: the one thing physics produces and everything else reads.

All arrays are read-only numpy arrays in SI units. Frame: the field frame of
:mod:`ssl_marl.physics.field` (blue attacks +x), unless a snapshot was
converted with :func:`to_team_frame`, in which case ``frame`` names the team
whose own goal lies at -x.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

TEAMS = ("blue", "yellow")


def _ro(a: np.ndarray) -> np.ndarray:
    a = np.ascontiguousarray(a, dtype=np.float64) if a.dtype != bool else np.ascontiguousarray(a)
    a.setflags(write=False)
    return a


@dataclass(frozen=True)
class TeamState:
    """Robots of one team (n robots, n may be 0).

    pos: (n, 2) m; heading: (n,) rad in (-pi, pi]; vel: (n, 2) m/s (field/team frame,
    not robot frame); omega: (n,) rad/s; ball_on_dribbler: (n,) bool;
    kick_ready: (n,) bool (kicker charged).
    """

    pos: np.ndarray
    heading: np.ndarray
    vel: np.ndarray
    omega: np.ndarray
    ball_on_dribbler: np.ndarray
    kick_ready: np.ndarray

    @property
    def n(self) -> int:
        return int(self.pos.shape[0])

    @staticmethod
    def empty() -> "TeamState":
        z2, z1 = np.zeros((0, 2)), np.zeros(0)
        return TeamState(_ro(z2), _ro(z1), _ro(z2.copy()), _ro(z1.copy()), _ro(np.zeros(0, bool)),
                         _ro(np.zeros(0, bool)))


@dataclass(frozen=True)
class WorldState:
    """Frozen snapshot of the world.

    Attributes:
        t: simulated time since reset (s).
        ball_pos: (2,) m.  ball_vel: (2,) m/s.
        ball_visible: False when vision dropped the ball this frame (then ball_pos is
            the last seen position). Always True for ground truth.
        blue, yellow: :class:`TeamState`.
        frame: "field" or the team name whose own goal is at -x.
        ball_height: height of the ball's lowest point above the field (m; 0 on the
            ground). ball_vz: its vertical velocity (m/s, up positive). Both are the
            same in every frame.
        ball_max_height: the highest the ball has been since a robot last touched it
            (m; the goal rule's "at most 0.15 m", SSL rules).
    """

    t: float
    ball_pos: np.ndarray
    ball_vel: np.ndarray
    blue: TeamState
    yellow: TeamState
    ball_visible: bool = True
    frame: str = "field"
    ball_height: float = 0.0
    ball_vz: float = 0.0
    ball_max_height: float = 0.0

    def team(self, name: str) -> TeamState:
        if name == "blue":
            return self.blue
        if name == "yellow":
            return self.yellow
        raise ValueError(f"team: unknown team {name!r}; expected 'blue' or 'yellow'")

    def opponents(self, name: str) -> TeamState:
        return self.yellow if name == "blue" else self.blue

    def robot_pose(self, team: str, idx: int) -> tuple[np.ndarray, float]:
        ts = self.team(team)
        return ts.pos[idx], float(ts.heading[idx])


def make_team_state(pos, heading, vel, omega, on_dribbler, kick_ready) -> TeamState:
    return TeamState(_ro(np.asarray(pos, float).reshape(-1, 2)), _ro(np.asarray(heading, float)),
                     _ro(np.asarray(vel, float).reshape(-1, 2)), _ro(np.asarray(omega, float)),
                     _ro(np.asarray(on_dribbler, bool)), _ro(np.asarray(kick_ready, bool)))


def wrap_angle(a):
    """Wrap angle(s) to (-pi, pi]."""
    return np.pi - np.mod(np.pi - np.asarray(a, dtype=float), 2 * np.pi)


def _flip_team(ts: TeamState) -> TeamState:
    return TeamState(_ro(-ts.pos), _ro(wrap_angle(ts.heading + np.pi)), _ro(-ts.vel), ts.omega,
                     ts.ball_on_dribbler, ts.kick_ready)


def to_team_frame(ws: WorldState, team: str) -> WorldState:
    """Express a field-frame snapshot in ``team``'s frame (own goal at -x).

    Blue's frame is the field frame; yellow's is the field frame rotated by pi.
    Team contents are unchanged (``blue`` is still the blue team).
    """
    if team not in TEAMS:
        raise ValueError(f"team: unknown team {team!r}; expected 'blue' or 'yellow'")
    if ws.frame != "field":
        raise ValueError(f"to_team_frame expects a field-frame snapshot, got frame={ws.frame!r}")
    if team == "blue":
        return replace(ws, frame="blue")
    return replace(ws, ball_pos=_ro(-ws.ball_pos), ball_vel=_ro(-ws.ball_vel), blue=_flip_team(ws.blue),
                   yellow=_flip_team(ws.yellow), frame="yellow")


def team_sign(team: str) -> float:
    """+1 for blue (attacks +x in the field frame), -1 for yellow."""
    return 1.0 if team == "blue" else -1.0
