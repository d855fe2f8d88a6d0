"""Domain randomisation: per-episode draws of the conditions a team meets.

``realism="randomized"`` (``EnvConfig``) draws, at every ``reset``, one
:class:`EpisodeConditions` from :class:`RandomizationRanges`: vision latency, vision
noise, ball dropout, radio latency, command loss, robot top speed and acceleration,
ball sliding and rolling deceleration, and the ball's restitution off walls and robots.
The env then runs that episode with those conditions (its vision, radio and physics
are rebuilt from them); ``env.conditions`` holds the draw and the reset ``infos`` list it
under ``"conditions"``. Teams are told only the nominal conditions: the config's
``realism`` is the "realistic" preset (what the vision tracker is tuned to), ``robot`` /
``ball`` stay the nominal parameters (what actions are scaled by and what tactics plan
with).

Reproducible: the draw comes from a generator seeded from the env's ``np_random``, so
``reset(seed=s)`` gives the same conditions for the same ``s``, and successive resets
without a seed give new ones.

Ranges and their sources, in ``docs/references.md``: [V] "Vision and tracking", [R]
"Robot and ball figures", [B] "Ball motion models", [D] "Domain randomisation"; "our
choice" where no source gives a range; the nominal value of this project in brackets:

=========================  ==================  =====================================================
quantity                   range               source
=========================  ==================  =====================================================
vision latency             1-4 steps (17-67    [V] ER-Force budget ~26 ms + processing, realistic
                           ms) [3 = 50 ms]     preset 35 + 10 = 45 ms, ZJU predicts ~63 ms ahead;
                                               [D] Haarnoja et al. observation delay 10-50 ms
radio latency              0-2 steps (0-33     [V] ER-Force ~11 ms out (one 60 Hz step rounds
                           ms) [1]             it up); 2 steps for a slow radio: our choice
robot position noise       0.5-4 mm [1.3]      [V] ER-Force realistic 1.3 mm; ER-Force tracker
                                               assumes 4 mm (primary camera); real cameras ~3 mm
robot heading noise        0.002-0.03 rad      [V] ER-Force 0.01 (primary) / 0.03 rad (other
                           [0.01]              cameras)
ball position noise        0.5-4 mm [1.4]      [V] ER-Force realistic 1.4 mm, tracker 3 mm, real ~3 mm
velocity noise             0-0.05 m/s [0.02]   our choice (the env reports velocities; SSL vision
                                               does not)
ball dropout               0-10 % [5 %]        [V] realistic preset 5 %; up to 2x: our choice
command loss               0-10 % [3 %]        [V] realistic preset 3 %, plus 10 % response loss
robot top speed            2.2-3.2 m/s [3.0]   [R] real teams 2.2-3.2 m/s
robot acceleration         1.5-4.0 m/s^2 [3]   [R] 1.5-4 m/s^2
ball sliding decel         2.5-4.0 m/s^2       [B] TIGERs sim 2.46, ER-Force real field 2.79,
                           [3.9]               TIGERs 3.0, ER-Force sim 3.9, ZJU 4.0
ball rolling decel         0.25-0.45 m/s^2     [B] TIGERs 0.26 (0.4 in an earlier model), ER-Force
                           [0.35]              0.33 (real) / 0.35 (sim), ZJU 0.325
ball-wall restitution      0.4-0.8 [0.6]       our choice around the nominal (no source)
ball-robot restitution     0.15-0.45 [0.3]     our choice around the nominal (no source)
=========================  ==================  =====================================================

Latencies are drawn as whole control steps (uniform over the integers), everything
else uniform over the interval. The robot's braking limit and the kick speed stay
nominal.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, fields, replace
from typing import Any

import numpy as np

from ..physics.params import BallParams, RobotParams
from .config import RealismConfig

#: the nominal conditions a randomised env tells its teams (the tracker is tuned to them)
NOMINAL_PRESET = "realistic"


@dataclass(frozen=True)
class RandomizationRanges:
    """Closed intervals ``(low, high)`` of the per-episode draws (see the module docstring
    for units and sources). Step counts are integers, the rest floats."""

    obs_latency_steps: tuple[int, int] = (1, 4)
    cmd_latency_steps: tuple[int, int] = (0, 2)
    robot_pos_sigma: tuple[float, float] = (0.0005, 0.004)
    robot_angle_sigma: tuple[float, float] = (0.002, 0.03)
    ball_pos_sigma: tuple[float, float] = (0.0005, 0.004)
    vel_sigma: tuple[float, float] = (0.0, 0.05)
    ball_dropout: tuple[float, float] = (0.0, 0.10)
    cmd_loss: tuple[float, float] = (0.0, 0.10)
    max_speed: tuple[float, float] = (2.2, 3.2)
    max_accel: tuple[float, float] = (1.5, 4.0)
    slide_decel: tuple[float, float] = (2.5, 4.0)
    roll_decel: tuple[float, float] = (0.25, 0.45)
    restitution_wall: tuple[float, float] = (0.4, 0.8)
    restitution_ball: tuple[float, float] = (0.15, 0.45)

    def __post_init__(self) -> None:
        for f in fields(self):
            v = getattr(self, f.name)
            ok = isinstance(v, (tuple, list)) and len(v) == 2 and all(
                isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x) for x in v)
            if not ok:
                raise ValueError(f"RandomizationRanges.{f.name} must be a (low, high) pair of finite numbers, "
                                 f"got {v!r}")
            lo, hi = v
            if lo > hi or lo < 0:
                raise ValueError(f"RandomizationRanges.{f.name} must satisfy 0 <= low <= high, got {v!r}")
            if f.name.endswith("_steps") and not all(isinstance(x, int) for x in v):
                raise ValueError(f"RandomizationRanges.{f.name} must be whole control steps, got {v!r}")
            if f.name in ("ball_dropout", "cmd_loss") and hi > 1:
                raise ValueError(f"RandomizationRanges.{f.name} is a probability: high must be <= 1, got {v!r}")
            if f.name in ("max_speed", "max_accel", "slide_decel", "roll_decel") and lo <= 0:
                raise ValueError(f"RandomizationRanges.{f.name} must be positive, got {v!r}")
            object.__setattr__(self, f.name, tuple(v))


@dataclass(frozen=True)
class EpisodeConditions:
    """One episode's draw: the realism the env applies and the physical parameters it
    simulates with."""

    realism: RealismConfig
    robot: RobotParams
    ball: BallParams

    def as_dict(self) -> dict[str, Any]:
        """Flat dict of the drawn values (for logs and ``infos``)."""
        r = asdict(self.realism)
        return {**{k: r[k] for k in ("obs_latency_steps", "cmd_latency_steps", "robot_pos_sigma",
                                     "robot_angle_sigma", "ball_pos_sigma", "vel_sigma", "ball_dropout",
                                     "cmd_loss")},
                "max_speed": self.robot.max_speed, "max_accel": self.robot.max_accel,
                "restitution_ball": self.robot.restitution_ball, "slide_decel": self.ball.slide_decel,
                "roll_decel": self.ball.roll_decel, "restitution_wall": self.ball.restitution_wall}


@dataclass(frozen=True)
class DomainRandomization:
    """Draws :class:`EpisodeConditions` from ``ranges`` (a :class:`RandomizationRanges`)."""

    ranges: RandomizationRanges = RandomizationRanges()

    def draw(self, rng: np.random.Generator, robot: RobotParams | None = None,
             ball: BallParams | None = None) -> EpisodeConditions:
        """One episode's conditions; ``robot`` / ``ball`` are the nominal parameters whose
        other fields are kept. The order of the draws is fixed (changing it changes every
        randomised run)."""
        rg = self.ranges
        robot = robot or RobotParams()
        ball = ball or BallParams()

        def u(name: str) -> float:
            lo, hi = getattr(rg, name)
            return float(rng.uniform(lo, hi)) if hi > lo else float(lo)

        def steps(name: str) -> int:
            lo, hi = getattr(rg, name)
            return int(rng.integers(lo, hi + 1))

        realism = RealismConfig(obs_latency_steps=steps("obs_latency_steps"),
                                cmd_latency_steps=steps("cmd_latency_steps"),
                                robot_pos_sigma=u("robot_pos_sigma"), robot_angle_sigma=u("robot_angle_sigma"),
                                ball_pos_sigma=u("ball_pos_sigma"), vel_sigma=u("vel_sigma"),
                                ball_dropout=u("ball_dropout"), cmd_loss=u("cmd_loss"))
        max_speed, max_accel = u("max_speed"), u("max_accel")
        slide, roll = u("slide_decel"), u("roll_decel")
        rest_wall, rest_ball = u("restitution_wall"), u("restitution_ball")
        return EpisodeConditions(
            realism=realism,
            robot=replace(robot, max_speed=max_speed, max_accel=max_accel, restitution_ball=rest_ball),
            ball=replace(ball, slide_decel=slide, roll_decel=roll, restitution_wall=rest_wall))


def resolve_randomization(value: Any) -> DomainRandomization | None:
    """None/False -> None; True -> the default ranges; a :class:`DomainRandomization` or
    :class:`RandomizationRanges` as is; a dict -> ranges with those fields. ValueError otherwise."""
    if value is None or value is False:
        return None
    if value is True:
        return DomainRandomization()
    if isinstance(value, DomainRandomization):
        return value
    if isinstance(value, RandomizationRanges):
        return DomainRandomization(value)
    if isinstance(value, dict):
        known = {f.name for f in fields(RandomizationRanges)}
        unknown = sorted(set(value) - known)
        if unknown:
            raise ValueError(f"randomization: unknown range(s) {unknown}; known: {sorted(known)}")
        return DomainRandomization(RandomizationRanges(**value))
    raise ValueError(f"randomization: expected None, True, a dict of ranges, RandomizationRanges or "
                     f"DomainRandomization, got {value!r}")


__all__ = ["NOMINAL_PRESET", "RandomizationRanges", "EpisodeConditions", "DomainRandomization",
           "resolve_randomization"]
