"""How far each of our robots has dribbled the ball, measured as the referee measures it.

SSL rules: a robot must not dribble the ball further than 1 m, measured from where its
dribbling began (``envs.game_control.MAX_DRIBBLE_M``; the referee calls excessive dribbling
and gives the opponents a free kick). The referee's :class:`~ssl_marl.envs.game_control.TouchWatch`
starts a dribble when exactly one robot touches the ball
(:func:`~ssl_marl.envs.game_control.touching_robots`: on the dribbler, or a ball at most
0.15 m high within the touch reach), ends it when that robot stops touching, and gives
nobody a dribble while robots of both teams (or two of one) touch the ball.

:class:`DribbleWatch` keeps the same account from the team's own snapshot (team frame,
metres), so team software can stop a dribble before the referee calls it: the plays put
:meth:`DribbleWatch.dribbled` into :attr:`~ssl_marl.plays.play.PlayContext.dribbled_m`.
Under realism the snapshot is the tracked one, so the team's account can differ from the
referee's by the tracker's error; a margin below 1 m is the caller's choice.
"""

from __future__ import annotations

import numpy as np

from ..envs.game_control import touch_reach, touching_robots
from ..physics.params import BallParams, RobotParams
from ..physics.state import WorldState


class DribbleWatch:
    """Where our dribbling robot's current dribble began (module docstring).

    Args:
        team: "blue" or "yellow" (the snapshots' frame).
        robot, ball: physical parameters (the touch reach).
    """

    def __init__(self, team: str, robot: RobotParams | None = None, ball: BallParams | None = None) -> None:
        rp, bp = robot or RobotParams(), ball or BallParams()
        self.team = team
        self.reach = touch_reach(rp.radius, bp.radius)
        self.reset()

    def reset(self) -> None:
        """Forget the dribble (a new episode)."""
        #: our robot index whose dribble is running (None: none of ours dribbles)
        self.dribbler: int | None = None
        #: ball position (m, team frame) where that dribble began
        self.start = np.zeros(2)

    def update(self, world: WorldState) -> np.ndarray:
        """Record this tick's touches (``world`` in this team's frame) and return
        :meth:`dribbled` for it."""
        ours, theirs = world.team(self.team), world.opponents(self.team)
        mine = touching_robots(ours.pos, world.ball_pos, world.ball_height, ours.ball_on_dribbler, self.reach)
        other = touching_robots(theirs.pos, world.ball_pos, world.ball_height, theirs.ball_on_dribbler, self.reach)
        n_touch = int(mine.sum()) + int(other.sum())
        if self.dribbler is not None and not mine[self.dribbler]:
            self.dribbler = None
        if n_touch > 1:
            self.dribbler = None  # a contested ball is nobody's dribble (as the referee counts)
        elif self.dribbler is None and n_touch == 1 and mine.any():
            self.dribbler, self.start = int(np.flatnonzero(mine)[0]), np.array(world.ball_pos, float)
        return self.dribbled(world)

    def dribbled(self, world: WorldState) -> np.ndarray:
        """(n,) metres each of our robots has carried the ball from where its dribble began
        (0 for robots that do not dribble)."""
        out = np.zeros(world.team(self.team).n)
        if self.dribbler is not None:
            out[self.dribbler] = float(np.hypot(*(world.ball_pos - self.start)))
        return out


__all__ = ["DribbleWatch"]
