"""The long-shot rule on a learned attacking decision's options
(:func:`ssl_marl.decisions.long_shot.limit_long_shots`): far from the opponent goal the
shot is offered only when nothing else is."""

import math

import numpy as np
import pytest

from ssl_marl.decisions import long_shot, match_decider
from ssl_marl.decisions.attack_drill_features import N_ATTACK_DRILL_OPTIONS, SHOOT
from ssl_marl.decisions.long_shot import limit_long_shots
from ssl_marl.decisions.match_decider import PolicyAttackDecider
from ssl_marl.physics import FieldGeometry

A, B = FieldGeometry.div_a(), FieldGeometry.div_b()


class _Shooter:
    """A decision policy that shoots whenever it may, else takes the first legal option."""

    def act(self, env, agent, obs, info):
        mask = np.asarray(info["action_mask"])
        return SHOOT if mask[SHOOT] else int(np.flatnonzero(mask)[0])


@pytest.mark.parametrize("field, ball, max_m, masked", [
    (A, (-1.0, 0.0), 6.0, True),     # 7 m out on Division A
    (A, (0.5, 0.0), 6.0, False),     # 5.5 m out
    (A, (2.0, 4.4), 6.0, False),     # near the side line, hypot(4, 4.4) = 5.95 m: just inside
    (A, (2.0, 4.5), 6.0, True),      # on it, hypot(4, 4.5) = 6.02 m: just beyond
    (B, (-1.0, 0.0), 6.0, False),    # 5.5 m out on Division B
    (B, (-2.0, 0.0), 6.0, True),     # 6.5 m out
    (A, (-5.0, 0.0), None, False),   # the rule off
])
def test_the_shot_is_masked_only_beyond_the_distance(field, ball, max_m, masked):
    mask = np.ones(N_ATTACK_DRILL_OPTIONS, np.int8)
    out, did = limit_long_shots(mask, np.array(ball), field, SHOOT, max_m)
    assert did is masked and bool(out[SHOOT]) is not masked
    assert mask.all()  # the caller's mask is not modified
    assert np.array_equal(np.delete(out, SHOOT), np.delete(mask, SHOOT))


def test_the_shot_stays_when_it_is_the_only_legal_option():
    mask = np.zeros(N_ATTACK_DRILL_OPTIONS, np.int8)
    mask[SHOOT] = 1
    out, did = limit_long_shots(mask, np.array([-5.0, 0.0]), A, SHOOT, 6.0)
    assert not did and out[SHOOT] == 1


def test_bad_long_shot_distances_are_refused():
    for bad in (float("nan"), math.inf, 0.0, -1.0, True):
        with pytest.raises(ValueError, match="long_shot_m"):
            PolicyAttackDecider(_Shooter(), long_shot_m=bad)


def test_match_deciders_take_the_module_setting(monkeypatch):
    """:func:`make_match_decider` builds a policy's decider with ``LONG_SHOT_MASK_M`` as it is then
    (default None: off)."""
    assert long_shot.LONG_SHOT_MASK_M is None
    assert match_decider.make_match_decider(_Shooter(), task=match_decider.DRILL_TASK).long_shot_m is None
    monkeypatch.setattr(long_shot, "LONG_SHOT_MASK_M", 6.0)
    assert match_decider.make_match_decider(_Shooter(), task=match_decider.DRILL_TASK).long_shot_m == 6.0


@pytest.mark.parametrize("x, long_shot_m, shoots", [(-2.0, 6.0, False), (-2.0, None, True), (2.5, 6.0, True)])
def test_a_learned_carrier_far_out_passes_instead_of_shooting(x, long_shot_m, shoots):
    """Division A, blue's carrier at (x, 0) with the ball, a free teammate 3 m ahead and to the side:
    a policy that shoots whenever it may shoots from 8 m only without the rule, and from 3.5 m
    with it too."""
    from ssl_marl.physics.params import BallParams, RobotParams
    from ssl_marl.plays.pass_coordinator import CarrierRequest
    from ssl_marl.plays.pass_decision import Choice, DecisionParams
    from ssl_marl.plays.play import make_context
    from ssl_marl.plays.scene import ball_in_front, make_world

    rp, bp = RobotParams(), BallParams()
    world = make_world(blue=[(x, 0.0, 0.0), (x + 2.5, 1.8, np.pi)], yellow=[(5.8, 0.0, np.pi)],
                       ball=ball_in_front(x, 0.0, 0.0), blue_on_dribbler=[True, False], frame="blue")
    ctx = make_context(world, "blue", A, rp)
    dec = PolicyAttackDecider(_Shooter(), long_shot_m=long_shot_m)
    d = dec.decide(CarrierRequest(ctx, 0, (1,), DecisionParams(), False, bp, 1.0))
    assert d.choice is (Choice.SHOOT if shoots else Choice.PASS)
    assert dec.long_shots_masked == int(long_shot_m is not None and not shoots)
