"""Chip passes over a robot in the lane: the kick's speed and elevation from the
ball-flight model, and a small scene that measures completions.

A chip's ball flies (:mod:`ssl_marl.physics.ball_flight`, no drag): from the ground at
3-D speed ``v`` and elevation ``a`` its height at horizontal distance ``x`` is
``x tan a - g x^2 / (2 v^2 cos^2 a)`` and its first touchdown is at
``2 v^2 sin a cos a / g`` (:func:`~ssl_marl.physics.ball_flight.projectile_reference`).
Robots fit under 0.15 m (``RobotParams.height``): a ball whose lowest point is above
that passes over them (SSL rules; docs/references.md, "Robot and ball figures"). A
chip is for passing, not scoring: a goal does not count if the ball was higher than
0.15 m after the last touch (SSL rules). :func:`chip_kick` picks the flattest-landing
chip that clears a blocker by ``clearance`` over its whole body and touches down
``land_short`` short of the receiver, so the receiver meets a ball that has stopped
hopping high.

:func:`chip_pass_episode` plays one pass in a full-field env: the passer ``blue_0``
with the ball on its dribbler, a blocker ``yellow_0`` standing midway in the lane, the
receiver ``blue_1`` running the hand-coded receive. The env's action has no chip
entry, so the episode drives the chip through the physics (``PhysicsWorld.step(...,
chip=...)``) on the kick's control step.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..envs.ssl_env import SSLParallelEnv
from ..envs.tracking import with_tracker
from ..physics.ball_flight import flight_height, projectile_reference
from ..physics.params import BallParams, RobotParams
from ..physics.world import PhysicsWorld
from .base import make_action
from .passing import ReceiveBaseline


@dataclass(frozen=True)
class ChipKick:
    """A chip: 3-D ball speed (m/s), elevation (rad), first touchdown distance (m) and
    the ball's lowest height over the blocker's body (m)."""

    speed: float
    angle: float
    landing: float
    blocker_clearance: float


def chip_kick(blocker_distance: float, receiver_distance: float, rp: RobotParams, bp: BallParams,
              clearance: float = 0.05, land_short: float = 0.6, body: float | None = None) -> ChipKick:
    """The chip (speed <= ``rp.kick_speed_max``, elevation <= ``rp.chip_angle_max``)
    whose ball's lowest point stays ``clearance`` (m) above ``rp.height`` over the
    blocker's body (``blocker_distance`` +- ``body``, default robot radius + ball radius,
    m from the kicker's face) and whose first touchdown is at most ``receiver_distance
    - land_short`` (m); of those, the one that lands farthest (the fastest ball to the
    receiver). ValueError when no chip does both."""
    g = bp.gravity
    body = rp.radius + bp.radius if body is None else body
    xs = np.array([blocker_distance - body, blocker_distance, blocker_distance + body])
    best: ChipKick | None = None
    best_flight = math.inf
    for angle in np.linspace(math.radians(15.0), rp.chip_angle_max, 46):
        for speed in np.linspace(1.0, rp.kick_speed_max, 56):
            landing, _ = projectile_reference(speed, angle, g)
            if landing > receiver_distance - land_short or landing <= xs[-1] + land_short:
                continue
            low = float(np.min(flight_height(xs, speed, angle, g)))  # the ball's lowest point is its height
            if low < rp.height + clearance:
                continue
            flight = 2.0 * speed * math.sin(angle) / g
            if best is None or flight < best_flight:
                best, best_flight = ChipKick(float(speed), float(angle), float(landing), low), flight
    if best is None:
        raise ValueError(f"no chip clears a blocker {blocker_distance:.2f} m away and lands "
                         f"{land_short:.2f} m short of a receiver {receiver_distance:.2f} m away")
    return best


def chip_pass_episode(seed: int, chip: bool = True, realism: Any = "none", tracker: Any = False,
                      distance_range: tuple[float, float] = (3.0, 4.5), max_time_s: float = 6.0,
                      hold_s: float = 0.5, flat_speed: float = 3.5) -> dict[str, Any]:
    """One pass over a blocker (see the module docstring): the passer at a random spot
    of the own half, the receiver ``U(distance_range)`` m away in a random direction
    (inside the field, 0.5 m margin), the blocker on the lane's midpoint (+- 0.05 m to
    the side) facing the passer. ``chip``: a :func:`chip_kick`; otherwise a flat kick at
    ``flat_speed`` m/s. Completed when the receiver holds the ball on its dribbler for
    ``hold_s`` within ``max_time_s`` and the blocker never touched it (the ball's lowest
    point at most ``rp.height`` within its body radius + ball radius + 1 cm: in a game
    that is an interception). Returns {"completed", "blocked", "time_s", "chip": the
    ChipKick or None, "max_height" (m)}."""
    rng = np.random.default_rng(seed)
    env = with_tracker(SSLParallelEnv(n_blue=2, n_yellow=1, field="div_b", realism=realism, referee=False,
                                      max_time_s=1e9, obs_max_teammates=0, obs_max_opponents=0), tracker)
    f, rp, bp = env.field, env.config.robot, env.config.ball
    reach = rp.front_distance + bp.radius
    while True:
        passer = f.random_free_point(rng, margin=0.5)
        ang = rng.uniform(-math.pi, math.pi)
        dist = rng.uniform(*distance_range)
        u = np.array([math.cos(ang), math.sin(ang)])
        receiver = passer + dist * u
        if bool(f.in_field(receiver, 0.5)):
            break
    mid = passer + 0.5 * dist * u + rng.uniform(-0.05, 0.05) * np.array([-u[1], u[0]])
    ball = passer + reach * u
    env.reset(seed=int(rng.integers(2 ** 31)), options={
        "robots": {"blue_0": (*passer, ang), "blue_1": (*receiver, ang + math.pi), "yellow_0": (*mid, ang + math.pi)},
        "ball": {"pos": tuple(ball), "vel": (0.0, 0.0)}})
    kick = chip_kick(float(np.hypot(*(mid - ball))), float(np.hypot(*(receiver - ball))) - reach, rp, bp) \
        if chip else None
    strength = (kick.speed if kick else flat_speed) / rp.kick_speed_max
    receive = ReceiveBaseline(f, rp, bp, hold_s=hold_s)
    physics: PhysicsWorld = env.unwrapped.physics if hasattr(env, "unwrapped") else env.physics
    held_since, max_h, t, blocked, kicked = None, 0.0, 0.0, False, False
    if kick is not None:  # the chip rides on the physics step until the passer's kick fires (radio delays, losses)
        chip_angles = np.zeros(env.n)
        chip_angles[0] = kick.angle
        physics.step = functools.partial(PhysicsWorld.step, physics, chip=chip_angles)
    for step in range(int(max_time_s / env.config.dt)):
        acts = {"yellow_0": make_action(), "blue_0": make_action() if kicked else make_action(kick=strength)}
        if step > 0:
            acts["blue_1"] = receive.act(env.vision_state("blue"), 1)
        _, _, _, _, infos = env.step(acts)
        if not kicked and any(ev["type"] == "kick" and ev["agent"] == "blue_0" for ev in infos["blue_0"]["events"]):
            kicked = True
            if kick is not None:
                del physics.step
        truth = env.world_state()
        max_h = max(max_h, float(truth.ball_height))
        if float(truth.ball_height) <= rp.height and \
                float(np.hypot(*(truth.ball_pos - truth.yellow.pos[0]))) <= rp.radius + bp.radius + 0.01:
            blocked = True
        t = (step + 1) * env.config.dt
        if bool(truth.blue.ball_on_dribbler[1]):
            held_since = t if held_since is None else held_since
            if t - held_since >= hold_s - 1e-9:
                if not kicked and kick is not None:
                    del physics.step
                env.close()
                return {"completed": not blocked, "blocked": blocked, "time_s": t, "chip": kick, "max_height": max_h}
        else:
            held_since = None
        if not bool(f.in_field(truth.ball_pos, -bp.radius)):
            break
    if not kicked and kick is not None:
        del physics.step
    env.close()
    return {"completed": False, "blocked": blocked, "time_s": t, "chip": kick, "max_height": max_h}


def chip_pass_completion(episodes: int, seed: int = 0, chip: bool = True, realism: Any = "none",
                         tracker: Any = "auto") -> dict[str, Any]:
    """Completed fraction of ``episodes`` passes over a blocker (episode ``i`` seeded
    ``seed * 100_003 + i``); ``tracker="auto"``: the receiver reads tracked vision
    when realism is on."""
    from ..envs.tracking import resolve_tracker

    use = resolve_tracker(tracker, realism)
    done = [chip_pass_episode(seed * 100_003 + i, chip=chip, realism=realism, tracker=use)["completed"]
            for i in range(episodes)]
    return {"episodes": episodes, "completed": int(sum(done)), "completion_rate": float(np.mean(done)),
            "chip": chip, "realism": realism, "tracker": use, "seed": seed}


__all__ = ["ChipKick", "chip_kick", "chip_pass_completion", "chip_pass_episode"]
