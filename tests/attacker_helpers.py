"""Shared by the attacker tests: an aim-to-shoot stand-in and a run up to AIM_TO_SHOOT."""

from ssl_marl.plays.shoot import ShootState
from ssl_marl.skills.base import SkillStatus, make_action

DT = 1.0 / 60.0


class NeverKicks:
    """An aim-to-shoot stand-in that turns nowhere and never kicks."""

    status = SkillStatus.RUNNING

    def reset(self):
        pass

    def act(self, world, robot):
        return make_action(dribble=True)


def act_at_aim(tac, world, robot: int = 0, ticks: int = 70):
    """(action, world) of ``tac`` (its aim-to-shoot replaced by :class:`NeverKicks`) on the first
    tick it spends in AIM_TO_SHOOT; ``world(t)`` builds the scene at time t (s)."""
    tac.aim_to_shoot = NeverKicks()
    tac.act(world(0.0), robot)
    for k in range(1, ticks):
        w = world(k * DT)
        a = tac.act(w, robot)
        if tac.state is ShootState.AIM_TO_SHOOT:
            return a, w
    raise AssertionError("never reached AIM_TO_SHOOT")
