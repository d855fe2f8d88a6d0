"""From merged camera detections to the field-frame world a team controller reads.

:class:`VisionWorld` keeps the last pose of every robot (a robot not seen keeps its
last pose; one never seen stands at its kickoff spot), estimates velocities by
exponentially smoothed finite differences over capture times, and marks the ball on a
dribbler from the robot's own feedback (our robots, simulation protocol) or, for
others, when the ball touches the robot's front face. Output: a
:class:`~ssl_marl.physics.state.WorldState` in the field frame (m, rad, m/s).
"""

from __future__ import annotations

import numpy as np

from ..physics.field import FieldGeometry
from ..physics.params import BallParams, RobotParams
from ..physics.state import WorldState, make_team_state, wrap_angle
from .vision_codec import Detections

SMOOTHING = 0.5  # weight of the newest finite-difference velocity


class VisionWorld:
    """Field-frame world state assembled from SSL-Vision detections (see the module docstring).

    Args:
        n_robots: robots per team (ids 0..n-1; others are ignored).
        field, robot, ball: geometry and parameters (dribbler test).
    """

    def __init__(self, n_robots: int, field: FieldGeometry, robot: RobotParams, ball: BallParams) -> None:
        from ..envs.referee import kickoff_poses

        self.n, self.field, self.robot, self.ball = n_robots, field, robot, ball
        start = kickoff_poses(field, n_robots, n_robots)
        self.pose = {"blue": start[:n_robots].copy(), "yellow": start[n_robots:].copy()}
        self.vel = {t: np.zeros((n_robots, 2)) for t in self.pose}
        self.omega = {t: np.zeros(n_robots) for t in self.pose}
        self.ball_pos = np.zeros(2)
        self.ball_vel = np.zeros(2)
        self.ball_visible = False
        self.t: float | None = None
        self.t0: float | None = None
        self.contact: dict[str, np.ndarray] = {}

    def set_feedback(self, team: str, contact: dict[int, bool]) -> None:
        """Dribbler contact reported by the simulator for ``team``'s robots."""
        arr = np.zeros(self.n, bool)
        for rid, held in contact.items():
            if 0 <= rid < self.n:
                arr[rid] = bool(held)
        self.contact[team] = arr

    def update(self, det: Detections) -> WorldState | None:
        """Fold in one merged detection set; the new world (None for a frame not newer
        than the last one)."""
        if self.t is not None and det.t_capture <= self.t:
            return None
        dt = None if self.t is None else det.t_capture - self.t
        if self.t0 is None:
            self.t0 = det.t_capture
        for team, seen in (("blue", det.blue), ("yellow", det.yellow)):
            for rid, (x, y, h) in seen.items():
                if not 0 <= rid < self.n:
                    continue
                old = self.pose[team][rid].copy()
                if dt is not None and dt > 0:
                    v = (np.array([x, y]) - old[:2]) / dt
                    w = float(wrap_angle(h - old[2])) / dt
                    self.vel[team][rid] = SMOOTHING * v + (1 - SMOOTHING) * self.vel[team][rid]
                    self.omega[team][rid] = SMOOTHING * w + (1 - SMOOTHING) * self.omega[team][rid]
                self.pose[team][rid] = (x, y, h)
        self.ball_visible = det.ball is not None
        if det.ball is not None:
            if dt is not None and dt > 0:
                v = (det.ball - self.ball_pos) / dt
                jump = np.linalg.norm(v) > 12.0  # a teleport, not motion
                self.ball_vel = np.zeros(2) if jump else SMOOTHING * v + (1 - SMOOTHING) * self.ball_vel
            self.ball_pos = np.asarray(det.ball, float)
        self.t = det.t_capture
        return self.world()

    def _on_dribbler(self, team: str) -> np.ndarray:
        if team in self.contact:
            return self.contact[team]
        pose = self.pose[team]
        rel = self.ball_pos - pose[:, :2]
        fwd = rel[:, 0] * np.cos(pose[:, 2]) + rel[:, 1] * np.sin(pose[:, 2])
        side = -rel[:, 0] * np.sin(pose[:, 2]) + rel[:, 1] * np.cos(pose[:, 2])
        reach = self.robot.front_distance + self.ball.radius + 0.015
        return (fwd > 0) & (fwd < reach) & (np.abs(side) < 0.03) & self.ball_visible

    def world(self) -> WorldState:
        """The current field-frame state (``t``: s since the first frame)."""
        teams = {}
        for team in ("blue", "yellow"):
            p = self.pose[team]
            teams[team] = make_team_state(p[:, :2].copy(), wrap_angle(p[:, 2]), self.vel[team].copy(),
                                          self.omega[team].copy(), self._on_dribbler(team).copy(),
                                          np.ones(self.n, bool))
        t = 0.0 if self.t is None else self.t - self.t0
        return WorldState(t=float(t), ball_pos=self.ball_pos.copy(), ball_vel=self.ball_vel.copy(),
                          blue=teams["blue"], yellow=teams["yellow"], ball_visible=bool(self.ball_visible))
