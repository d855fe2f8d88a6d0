"""SSL's 1 m dribbling limit on the team side: the team's own account of a dribble
(:class:`~ssl_marl.plays.dribble_watch.DribbleWatch`) and a learned attacking decision that
stops dribbling before the referee calls excessive dribbling."""

import math

import numpy as np
import pytest

from ssl_marl.decisions.attack_drill_features import (ATTACK_DRILL_OPTIONS, DRIBBLE_GOAL_OPTION, DRIBBLE_OPTIONS,
                                                      SHOOT)
from ssl_marl.envs.game_control import TouchWatch
from ssl_marl.physics import FieldGeometry
from ssl_marl.physics.params import BallParams, RobotParams
from ssl_marl.plays.dribble_watch import DribbleWatch
from ssl_marl.plays.pass_coordinator import PassingParams
from ssl_marl.plays.scene import ball_in_front, make_world
from ssl_marl.plays.shoot import Attacker

F = FieldGeometry.div_b()
RP, BP = RobotParams(), BallParams()


def _holding(x, ball_x=None, opp=(), on_yellow=None):
    """Blue robot 0 at (x, 0) facing +x with the ball on its dribbler (field frame = blue's frame)."""
    bx, by = ball_in_front(x, 0.0, 0.0) if ball_x is None else (ball_x, 0.0)
    return make_world(blue=[(x, 0.0, 0.0), (-3.0, 1.0, 0.0)], yellow=[(*o, np.pi) for o in opp], ball=(bx, by),
                      blue_on_dribbler=[True, False], yellow_on_dribbler=on_yellow, frame="blue")


def test_dribble_watch_measures_from_where_the_dribble_began():
    w = DribbleWatch("blue", RP, BP)
    assert w.update(_holding(0.0)).tolist() == [0.0, 0.0]
    d = w.update(_holding(0.7))
    assert d[0] == pytest.approx(0.7) and d[1] == 0.0
    # a contested ball is nobody's dribble; a new dribble starts where the contest ended
    bx = ball_in_front(0.9, 0.0, 0.0)[0]
    contested = _holding(0.9, opp=[(bx + RP.front_distance + BP.radius, 0.0)], on_yellow=[True])
    assert w.update(contested)[0] == 0.0
    w.update(_holding(0.9))
    assert w.update(_holding(1.5))[0] == pytest.approx(0.6)
    # letting go of the ball ends the dribble
    free = make_world(blue=[(1.5, 0.0, 0.0), (-3.0, 1.0, 0.0)], ball=(2.5, 0.0), frame="blue")
    assert w.update(free).tolist() == [0.0, 0.0] and w.dribbler is None
    w.update(_holding(2.0))
    w.reset()
    assert w.dribbler is None and w.dribbled(_holding(2.4)).tolist() == [0.0, 0.0]


def test_dribble_watch_agrees_with_the_referee_on_a_real_dribble():
    """A robot keeping the ball creeps 8 s up the field: the team's account of its dribble is
    the referee's at every tick (the same touches, the same start)."""
    from ssl_marl.envs import parallel_env

    env = parallel_env(n_blue=1, n_yellow=0, field="div_b", max_time_s=10.0, no_progress_s=None)
    pose = (-3.0, 0.0, 0.0)
    env.reset(seed=3, options={"robots": {"blue_0": list(pose)}, "ball": {"pos": list(ball_in_front(*pose))}})
    tac = Attacker(env.field, env.config.robot, env.config.ball, skills="baseline", dt=env.config.dt,
                   hold_fire=True, keep_speed=0.5)
    referee = TouchWatch(1, 0, env.config.robot.radius, env.config.ball.radius)
    team = DribbleWatch("blue", env.config.robot, env.config.ball)
    longest = 0.0
    for _ in range(480):
        env.step({"blue_0": tac.act(env.vision_state("blue"), 0)})
        ws = env.world_state()
        referee.update(ws, referee.touching(ws, []), env.field, False)
        ours = float(team.update(env.vision_state("blue"))[0])
        theirs = 0.0 if referee.dribbler is None else float(np.hypot(*(ws.ball_pos - referee.dribble_start)))
        assert ours == pytest.approx(theirs, abs=1e-9)
        longest = max(longest, ours)
    assert longest > 1.0  # it did dribble past the limit (no fouls called here)


class _Dribbler:
    """A decision policy that dribbles towards the goal (option ``dribble``) whenever it may,
    else shoots (option ``shoot``); the attack drill's options by default."""

    def __init__(self, dribble=DRIBBLE_GOAL_OPTION, shoot=SHOOT):
        self.dribble, self.shoot, self.masks = dribble, shoot, []

    def act(self, env, agent, obs, info):
        mask = np.asarray(info["action_mask"])
        self.masks.append(mask.copy())
        return self.dribble if mask[self.dribble] else self.shoot


def _dribble_run(mask_m, cut_m, seconds=10.0):
    """The attacking team (goalie + one field robot, the ball at its dribbler in its own
    half, no opponents) with :class:`_Dribbler` as its carrier decision; the referee's touch
    watch counts the fouls it would call. Returns (fouls, decider)."""
    from ssl_marl.decisions.match_decider import PolicyAttackDecider
    from ssl_marl.envs import parallel_env
    from ssl_marl.envs.actions import fit_action
    from ssl_marl.plays import attack_play
    from ssl_marl.runners.controllers import make_controller

    env = parallel_env(n_blue=2, n_yellow=0, field="div_b", max_time_s=seconds + 1.0, no_progress_s=None,
                       chip_kicks=True)
    pose = (-3.0, 0.0, 0.0)
    env.reset(seed=5, options={"robots": {"blue_0": [-4.3, 0.0, 0.0], "blue_1": list(pose)},
                               "ball": {"pos": list(ball_in_front(*pose))}})
    dec = PolicyAttackDecider(_Dribbler(), dribble_mask_m=mask_m)
    old = attack_play.ATTACK_PASSING
    attack_play.ATTACK_PASSING = PassingParams(**{**old.__dict__, "dribble_cut_m": cut_m})
    try:
        team = make_controller("attack-baseline", "blue", 2, env.field, decision=dec, robot=env.config.robot,
                               ball=env.config.ball, dt=env.config.dt)
    finally:
        attack_play.ATTACK_PASSING = old
    referee = TouchWatch(2, 0, env.config.robot.radius, env.config.ball.radius)
    fouls = []
    for _ in range(int(seconds * 60)):
        actions = {k: fit_action(a, 6) for k, a in team.act(env).items()}
        env.step(actions)
        ws = env.world_state()
        kicked = [i for i, a in enumerate(actions[f"blue_{k}"] for k in range(2)) if a[4] > 0]
        foul = referee.update(ws, referee.touching(ws, kicked), env.field, True)
        fouls += [foul[0]] if foul else []
    return fouls, dec


@pytest.mark.parametrize("limit", [False, True])
def test_learned_attacking_decision_stops_dribbling_before_the_limit(limit):
    """A policy that always dribbles: with the dribble mask (0.5 m) and the plays' dribble
    cut (0.8 m) the referee would call no excessive dribbling and the policy is made to
    shoot (its dribbles masked); without them it runs into the foul."""
    fouls, dec = _dribble_run(0.5 if limit else None, 0.8 if limit else None)
    masked = [m for m in dec.policy.masks if not m[list(DRIBBLE_OPTIONS)].any()]
    assert dec.decisions >= 3
    if limit:
        assert "excessive_dribbling" not in fouls
        assert masked and dec.dribbles_masked == len(masked) and all(m[SHOOT] for m in masked)
    else:
        assert "excessive_dribbling" in fouls and not masked and dec.dribbles_masked == 0


def _dribbler_3v2():
    """:class:`_Dribbler` over the Attack 3v2 options."""
    from ssl_marl.decisions.attack_features import DRIBBLE_GOAL, SHOOT as SHOOT_3V2

    return _Dribbler(DRIBBLE_GOAL, SHOOT_3V2)


@pytest.mark.parametrize("dribbled, masked", [(0.3, False), (0.6, True)])
def test_passing_plays_learned_decider_masks_dribbles_past_the_limit(dribbled, masked):
    """The passing plays' learned decider (Attack 3v2 options) offers no dribble once the
    carrier has dribbled ``DRIBBLE_MASK_M`` (0.5 m): an always-dribble policy shoots."""
    from dataclasses import replace

    from ssl_marl.decisions.attack_features import DRIBBLE_GOAL, DRIBBLE_LEFT, DRIBBLE_RIGHT
    from ssl_marl.decisions.dribble_limit import DRIBBLE_MASK_M
    from ssl_marl.decisions.match_decider import PolicyCarrierDecider
    from ssl_marl.plays.pass_coordinator import CarrierRequest
    from ssl_marl.plays.pass_decision import Choice, DecisionParams
    from ssl_marl.plays.play import make_context

    ctx = replace(make_context(_holding(0.0), "blue", F, RP), dribbled_m=np.array([dribbled, 0.0]))
    pol = _dribbler_3v2()
    dec = PolicyCarrierDecider(pol)
    assert dec.dribble_mask_m == DRIBBLE_MASK_M == 0.5
    d = dec.decide(CarrierRequest(ctx, 0, (1,), DecisionParams(), False, BP, 1.0))
    assert dec.dribbles_masked == int(masked) and dec.decisions == 1
    assert bool(pol.masks[0][[DRIBBLE_GOAL, DRIBBLE_LEFT, DRIBBLE_RIGHT]].any()) is not masked
    assert d.choice is (Choice.SHOOT if masked else Choice.KEEP)
    # without the limit the policy dribbles on
    d = PolicyCarrierDecider(_dribbler_3v2(), dribble_mask_m=None).decide(
        CarrierRequest(ctx, 0, (1,), DecisionParams(), False, BP, 1.0))
    assert d.choice is Choice.KEEP


def test_dribble_limit_parameters_are_checked():
    from ssl_marl.decisions.match_decider import PolicyAttackDecider

    with pytest.raises(ValueError, match="dribble_mask_m"):
        PolicyAttackDecider(_Dribbler(), dribble_mask_m=float("nan"))
    with pytest.raises(ValueError, match="dribble_mask_m"):
        PolicyAttackDecider(_Dribbler(), dribble_mask_m=-0.1)
    from ssl_marl.decisions.match_decider import PolicyCarrierDecider
    with pytest.raises(ValueError, match="PolicyCarrierDecider: dribble_mask_m"):
        PolicyCarrierDecider(_dribbler_3v2(), dribble_mask_m=math.inf)
    with pytest.raises(ValueError, match="dribble_cut_m"):
        PassingParams(dribble_cut_m=0.0)
    assert len(ATTACK_DRILL_OPTIONS) == 10 and set(DRIBBLE_OPTIONS) == {7, 8, 9}
