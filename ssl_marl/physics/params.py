"""Robot and ball physical parameters (SI units), one frozen dataclass each.

Defaults and their sources (docs/references.md, "SSL rules", "Robot and ball figures",
"Ball motion models"):

* Robot radius 0.09 m with a flat front face 0.08 m from the centre (SSL rules,
  "Robots" > "Shape": fits a 0.18 m cylinder; typical dribbler face ~0.08 m wide
  at ~0.08 m).
* Mass 2.4 kg (rSim 2.4; range 1.5-2.8 across grSim / Sumatra / ER-Force).
* Top speed 3.0 m/s (real teams 2.2-3.2, simulators 3-5); acceleration
  3.0 m/s^2, braking 6.0 m/s^2 (ranges 1.5-4 and up to 6).
* Angular speed 10 rad/s (simulators 10-40: we take the low end, so that the
  dribbler can be lost by spinning at full rate, as the paper reports),
  angular acceleration 50 rad/s^2.
* Kick cap 6.5 m/s (SSL rules, "Ball Speed"); recharge 0.5 s (our choice;
  real kicker capacitors recharge in ~0.5-3 s, grSim has none).
* Ball: radius 0.0215 m, 0.046 kg (golf ball); two-phase deceleration from
  ER-Force's simulator: sliding -3.9 m/s^2 until the speed falls to 0.69 of
  the kick speed, then rolling -0.35 m/s^2.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields


def _check_positive(obj: object, names: tuple[str, ...], allow_zero: tuple[str, ...] = ()) -> None:
    for f in fields(obj):  # type: ignore[arg-type]
        if f.name not in names:
            continue
        v = getattr(obj, f.name)
        ok = isinstance(v, (int, float)) and math.isfinite(v) and (v >= 0 if f.name in allow_zero else v > 0)
        if not ok:
            raise ValueError(f"{type(obj).__name__}.{f.name} must be a {'non-negative' if f.name in allow_zero else 'positive'} "
                             f"finite number, got {v!r}")


@dataclass(frozen=True)
class RobotParams:
    """Omni-directional SSL robot (metres, seconds, kilograms, radians)."""

    radius: float = 0.09
    front_distance: float = 0.08  # centre -> flat front face (dribbler/kicker)
    mass: float = 2.4
    max_speed: float = 3.0  # m/s, cap on |v|
    max_accel: float = 3.0  # m/s^2 when speeding up / turning the velocity
    max_brake: float = 6.0  # m/s^2 when slowing down
    max_omega: float = 10.0  # rad/s
    max_alpha: float = 50.0  # rad/s^2
    kick_speed_max: float = 6.5  # m/s, ball speed at kick strength 1
    kick_recharge_s: float = 0.5  # s between two kicks
    # Dribbler model: the bar accelerates the ball towards the velocity of the
    # contact point (plus a small pull-in) with at most this acceleration.
    dribbler_max_accel: float = 5.0  # m/s^2 on the ball (bounded holding force / ball mass)
    dribbler_pull_speed: float = 0.05  # m/s towards the face (backspin pull-in)
    dribbler_tolerance: float = 0.01  # m: ball-face gap still counted as "on the dribbler"
    friction: float = 0.3
    restitution_ball: float = 0.3  # ball-robot coefficient
    height: float = 0.15  # m; a ball higher than this passes over the robot (SSL rules: robots fit under 0.15 m)
    chip_angle_max: float = math.radians(60.0)  # rad, the steepest chip the kicker can lift (3-D speed capped as a flat kick)
    # Kick on contact: a kick command arms the kicker for the control step and it fires at the
    # first physics sub-step with the ball on the face (a light barrier, as SSL robots and the
    # SSL simulation protocol's kick_speed work); off: only a ball already on the face is kicked.
    kick_on_contact: bool = False

    def __post_init__(self) -> None:
        _check_positive(self, ("radius", "front_distance", "mass", "max_speed", "max_accel", "max_brake",
                               "max_omega", "max_alpha", "kick_speed_max", "kick_recharge_s",
                               "dribbler_max_accel", "dribbler_pull_speed", "dribbler_tolerance",
                               "friction", "restitution_ball", "height", "chip_angle_max"),
                        allow_zero=("kick_recharge_s", "dribbler_pull_speed", "friction", "restitution_ball"))
        if self.front_distance >= self.radius:
            raise ValueError("RobotParams.front_distance must be smaller than RobotParams.radius")
        if self.chip_angle_max >= math.pi / 2:
            raise ValueError(f"RobotParams.chip_angle_max must be below pi/2 rad, got {self.chip_angle_max!r}")

    @property
    def dribbler_half_width(self) -> float:
        """Half the width of the flat front face (chord of the body circle)."""
        return math.sqrt(self.radius ** 2 - self.front_distance ** 2)


@dataclass(frozen=True)
class BallParams:
    """SSL golf ball with a two-phase (slide, then roll) deceleration model."""

    radius: float = 0.0215
    mass: float = 0.046
    slide_decel: float = 3.9  # m/s^2 while sliding (ER-Force)
    roll_decel: float = 0.35  # m/s^2 while rolling (ER-Force)
    slide_to_roll_ratio: float = 0.69  # sliding until speed <= ratio * kick speed (ER-Force)
    restitution_wall: float = 0.6  # ball-wall / ball-goal coefficient
    # In the air (physics/ball_flight.py): gravity and TIGERs' analytic chip bounce model
    gravity: float = 9.81  # m/s^2
    bounce_damping_z: float = 0.47  # vertical speed kept at a bounce
    bounce_damping_xy_first: float = 0.8  # horizontal speed kept at the first bounce
    bounce_damping_xy_later: float = 0.85  # ... at every later bounce
    min_hop_height: float = 0.01  # m: a lower hop ends the flight (the ball then rolls)

    def __post_init__(self) -> None:
        _check_positive(self, ("radius", "mass", "slide_decel", "roll_decel", "slide_to_roll_ratio",
                               "restitution_wall", "gravity", "bounce_damping_z", "bounce_damping_xy_first",
                               "bounce_damping_xy_later", "min_hop_height"), allow_zero=("restitution_wall",))
        for name in ("bounce_damping_z", "bounce_damping_xy_first", "bounce_damping_xy_later"):
            if getattr(self, name) >= 1.0:
                raise ValueError(f"BallParams.{name} must lie in (0, 1), got {getattr(self, name)!r}")
        if self.slide_to_roll_ratio > 1.0:
            raise ValueError("BallParams.slide_to_roll_ratio must lie in (0, 1]")
