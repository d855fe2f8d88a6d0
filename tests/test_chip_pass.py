"""Chip passes: the kick from the flight model clears a blocker midway and lands short
of the receiver; a chipped pass over a blocker is completed, a flat one is not."""

import math

import pytest

from ssl_marl.physics.ball_flight import projectile_reference
from ssl_marl.physics.params import BallParams, RobotParams
from ssl_marl.physics.ball_flight import flight_height
from ssl_marl.skills.chip_pass import chip_kick, chip_pass_episode

RP, BP = RobotParams(), BallParams()


@pytest.mark.parametrize("receiver", [3.0, 4.0, 4.5])
def test_chip_kick_clears_the_blocker_and_lands_short(receiver):
    k = chip_kick(receiver / 2, receiver, RP, BP)
    body = RP.radius + BP.radius
    for x in (receiver / 2 - body, receiver / 2, receiver / 2 + body):
        assert flight_height(x, k.speed, k.angle, BP.gravity) > RP.height
    landing, _ = projectile_reference(k.speed, k.angle, BP.gravity)
    assert math.isclose(landing, k.landing) and receiver / 2 + body < landing <= receiver - 0.6
    assert k.speed <= RP.kick_speed_max and k.angle <= RP.chip_angle_max


def test_no_chip_raises():
    with pytest.raises(ValueError, match="no chip"):
        chip_kick(0.3, 0.6, RP, BP)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_chip_clears_a_blocker_a_flat_pass_does_not(seed):
    chip = chip_pass_episode(seed, chip=True)
    flat = chip_pass_episode(seed, chip=False)
    assert chip["completed"] and not chip["blocked"] and chip["max_height"] > RP.height
    assert flat["blocked"] and not flat["completed"]
