"""The long-shot rule on a learned attacking decision's options
(:func:`ssl_marl.decisions.match_decider.limit_long_shots`): far from the opponent goal the
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
