"""Hand-built world snapshots for tests, examples and debugging of tactics.

:func:`make_world` builds a field-frame :class:`~ssl_marl.physics.state.WorldState`
from a few poses (metres, radians) and, with ``frame=``, returns it in that team's
frame (own goal at -x) via :func:`~ssl_marl.physics.state.to_team_frame`.
"""

from __future__ import annotations

from typing import Sequence

import numpy as np

from ..physics.params import BallParams, RobotParams
from ..physics.state import WorldState, make_team_state, to_team_frame


def _team(poses: Sequence[Sequence[float]], vels, on_dribbler, kick_ready):
    n = len(poses)
    p = np.asarray(poses, float).reshape(n, 3) if n else np.zeros((0, 3))
    v = np.zeros((n, 2)) if vels is None else np.asarray(vels, float).reshape(n, 2)
    od = np.zeros(n, bool) if on_dribbler is None else np.asarray(on_dribbler, bool).reshape(n)
    kr = np.ones(n, bool) if kick_ready is None else np.asarray(kick_ready, bool).reshape(n)
    return make_team_state(p[:, :2], p[:, 2], v, np.zeros(n), od, kr)


def make_world(blue: Sequence[Sequence[float]] = (), yellow: Sequence[Sequence[float]] = (),
               ball: Sequence[float] = (0.0, 0.0), ball_vel: Sequence[float] = (0.0, 0.0), t: float = 0.0,
               blue_vel=None, yellow_vel=None, blue_on_dribbler=None, yellow_on_dribbler=None,
               blue_kick_ready=None, yellow_kick_ready=None, frame: str = "field") -> WorldState:
    """A snapshot with robots at ``blue`` / ``yellow`` poses ``(x, y, heading)`` and the
    ball at ``ball`` (all in the *field* frame); converted to ``frame`` ("blue" or
    "yellow") if given. Kickers are charged unless ``*_kick_ready`` says otherwise."""
    ws = WorldState(t=float(t), ball_pos=np.asarray(ball, float), ball_vel=np.asarray(ball_vel, float),
                    blue=_team(blue, blue_vel, blue_on_dribbler, blue_kick_ready),
                    yellow=_team(yellow, yellow_vel, yellow_on_dribbler, yellow_kick_ready))
    return ws if frame == "field" else to_team_frame(ws, frame)


def ball_in_front(x: float, y: float, heading: float, gap: float = 0.0, robot: RobotParams | None = None,
                  ball: BallParams | None = None) -> tuple[float, float]:
    """Ball centre ``gap`` metres in front of the dribbler of a robot at (x, y, heading)."""
    rp, bp = robot or RobotParams(), ball or BallParams()
    r = rp.front_distance + bp.radius + gap
    return (x + r * np.cos(heading), y + r * np.sin(heading))
