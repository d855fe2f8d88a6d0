"""Tracker parameters: one frozen dataclass, every number with its source.

Sources (docs/references.md, "Vision and tracking", which names each repository and file):
[S] TIGERs Mannheim's Sumatra vision filter, [E] ER-Force's ``amun`` tracking,
[R] RoboTeam Twente's observer, [U] UBC Thunderbots' ball filter. "(env)" marks a
number taken from this project's simulator so that the tracker's models match it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace
from typing import Any


@dataclass(frozen=True)
class TrackerParams:
    """Attributes (SI units; "measurement" = one vision frame):

    Robot filter ([x, y, vx, vy] and [theta, omega], one per robot):
        robot_pos_sigma: position measurement noise (m). [E] 4 mm (primary camera);
            :meth:`for_realism` uses the env preset's figure (ER-Force's realistic
            preset: 1.3 mm).
        robot_angle_sigma: heading measurement noise (rad). [E] 0.01.
        vel_sigma: velocity measurement noise (m/s). The env's vision reports
            velocities (real SSL vision does not); :meth:`for_realism` uses the preset's.
        omega_sigma: angular-velocity measurement noise (rad/s); our choice (the env
            reports omega unperturbed; a floor keeps the filter well conditioned).
        own_accel_sigma: white-noise acceleration of own robots around the motion the
            sent commands imply (m/s^2). Our choice, below [E]'s 4 m/s^2 because the
            command model here is the simulator's own controller (collisions and 3 %
            lost commands are what is left).
        opp_accel_sigma: white-noise acceleration of opponents, whose commands are not
            known (m/s^2). [E] 4 m/s^2, [R] 4 m/s^2.
        own_alpha_sigma, opp_alpha_sigma: the same for the heading (rad/s^2).
            [R] 4 rad/s^2, [E] 10 rad/s^2.
        use_commands: predict own robots with the acceleration the sent commands imply
            ([E]'s control input, clamped to the robot limits) instead of constant velocity.

    Ball filter ([x, y, vx, vy], constant deceleration in two phases as the env):
        ball_pos_sigma: position measurement noise (m). [E] 3 mm; preset 1.4 mm.
        ball_accel_sigma: white-noise acceleration around the deceleration model (m/s^2);
            our choice.
        kick_speed_jump: a measured ball speed this much above the prediction (m/s) is a
            kick: the filter restarts at the measurement in the sliding phase.
            [E] flags a shot above 1 m/s.
        vel_reset_jump: a measured velocity this far from the prediction (m/s) (a
            bounce) restarts the velocity estimate; our choice (~10 sigma of vel noise).

    Outliers:
        robot_gate_speed: a robot detection farther from the prediction than
            ``robot_gate_base + robot_gate_speed * age`` is an outlier. [S] 6 m/s.
        robot_gate_turn: the same for the heading (rad/s); [S] 30 rad/s.
        robot_gate_base, robot_gate_turn_base: noise allowance at age 0 (m, rad):
            ~10 sigma of the preset's noise.
        ball_gate_speed: ball gate speed (m/s); [S] 15 m/s.
        ball_gate_cap: hard cap on the ball gate (m); [S] 0.5 m.
        ball_gate_base: ball noise allowance at age 0 (m).
        max_outliers: consecutive outliers after which the filter restarts at the
            measurement. [U] resets after more than 3.

    Ball on the dribbler:
        dribbler_gate: a ball measured within this distance (m) of a robot's dribbler
            point (ball centre touching the front face) is on that dribbler. Our choice:
            the env's face tolerance (0.01 m) plus ~7 sigma of vision noise.
        release_gate: a held ball measured farther than this from the dribbler point (m)
            is released: the skills' "ball lost" distance (0.05 m).
        occlusion_gate: an unseen ball whose last estimate lay within this distance (m)
            of a dribbler point is pinned to it. [S] places a virtual ball at the
            dribbler after 50 ms unseen; [E] pins an unseen ball near a robot after 80 ms.
            Here the pin is immediate (the env drops single frames at random).
        lost_after_s: an unseen ball that is not held is extrapolated for this long (s),
            then kept where it was predicted to stop. [S] drops balls unseen for 1 s.

    Latency:
        radio_delay_s: time between sending a command and the robot executing it (s):
            the prediction target is now + this. [E] budgets ~11 ms; the env preset
            uses one control step. :meth:`for_env` reads it from the env.
        command_stale_s: a command older than this is no longer applied in prediction
            (the robot may have lost it); [E] 20 ms at 100 Hz. Here the robots keep
            executing the last command received, so the default is long (0.5 s).
    """

    robot_pos_sigma: float = 0.004
    robot_angle_sigma: float = 0.01
    vel_sigma: float = 0.05
    omega_sigma: float = 0.05
    own_accel_sigma: float = 1.0
    opp_accel_sigma: float = 4.0
    own_alpha_sigma: float = 4.0
    opp_alpha_sigma: float = 10.0
    use_commands: bool = True
    ball_pos_sigma: float = 0.003
    ball_accel_sigma: float = 1.0
    kick_speed_jump: float = 1.0
    vel_reset_jump: float = 0.3
    robot_gate_speed: float = 6.0
    robot_gate_turn: float = 30.0
    robot_gate_base: float = 0.02
    robot_gate_turn_base: float = 0.15
    ball_gate_speed: float = 15.0
    ball_gate_cap: float = 0.5
    ball_gate_base: float = 0.02
    max_outliers: int = 3
    dribbler_gate: float = 0.02
    release_gate: float = 0.05
    occlusion_gate: float = 0.05
    lost_after_s: float = 1.0
    radio_delay_s: float = 0.0
    command_stale_s: float = 0.5

    def __post_init__(self) -> None:
        for f in fields(self):
            v = getattr(self, f.name)
            if f.name == "use_commands":
                if not isinstance(v, bool):
                    raise ValueError(f"TrackerParams.use_commands must be a bool, got {v!r}")
                continue
            if f.name == "max_outliers":
                if not isinstance(v, int) or isinstance(v, bool) or v < 1:
                    raise ValueError(f"TrackerParams.max_outliers must be an integer >= 1, got {v!r}")
                continue
            ok = isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
            zero_ok = f.name in ("radio_delay_s",)
            if not ok or v < 0 or (v == 0 and not zero_ok):
                kind = "non-negative" if zero_ok else "positive"
                raise ValueError(f"TrackerParams.{f.name} must be a {kind} finite number, got {v!r}")
        if self.release_gate < self.dribbler_gate:
            raise ValueError("TrackerParams.release_gate must be >= dribbler_gate (hysteresis)")

    @staticmethod
    def for_realism(realism: Any, dt: float, **overrides: Any) -> TrackerParams:
        """Parameters for an env realism config: measurement noise = the preset's
        documented sigmas (teams calibrate theirs; floors keep the filter conditioned
        when realism is off), radio delay = ``cmd_latency_steps * dt``."""
        from ..config import RealismConfig

        cfg = realism if isinstance(realism, RealismConfig) else (
            RealismConfig.preset(realism) if isinstance(realism, str) else RealismConfig(**dict(realism)))
        base = TrackerParams(
            robot_pos_sigma=max(cfg.robot_pos_sigma, 5e-4), robot_angle_sigma=max(cfg.robot_angle_sigma, 2e-3),
            vel_sigma=max(cfg.vel_sigma, 5e-3), ball_pos_sigma=max(cfg.ball_pos_sigma, 5e-4),
            radio_delay_s=cfg.cmd_latency_steps * float(dt))
        return replace(base, **overrides) if overrides else base
