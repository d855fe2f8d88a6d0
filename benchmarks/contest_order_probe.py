"""Does the robot order decide contested balls? The same two-robot contest, robot A first
or second in the robot order.

Each scene: a ball at rest at the centre, two robots 0.2-0.6 m from it on roughly
opposite sides, both chasing it with their dribblers on (turn to the ball, drive at it),
each kicking from a random step in half the scenes; 120 control steps. The scene is played
twice, with robot A at index 0 (blue) and at index 1 (yellow). Where the ball's track
differs by more than 1 mm the robot order decided something; the scene counts as "first
helped" (or "first hurt") where robot A had the ball on its face more (less) of the time
as index 0 than as index 1, by more than 2 % of the steps.

``--index-order`` creates Box2D bodies in the robot order (the physics before
``creation_order``) to show what the order did.

    python benchmarks/contest_order_probe.py --scenes 1500 --seed 1 --out results/tuning/contest_order.json
    python benchmarks/contest_order_probe.py --scenes 1500 --seed 1 --index-order --out results/tuning/contest_order_index.json
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))


def contest(pose: np.ndarray, kick_at: np.ndarray, swap: bool, steps: int = 120) -> np.ndarray:
    """(steps, 4): ball x, y (m) and robot A's, robot B's ball-on-face flag per step."""
    from ssl_marl.physics import BallParams, FieldGeometry, PhysicsWorld, RobotParams

    order = [1, 0] if swap else [0, 1]
    w = PhysicsWorld(FieldGeometry.div_b(), RobotParams(), BallParams(), 1, 1)
    w.reset(pose[order], np.zeros(2))
    track = []
    for t in range(steps):
        d = w.ball_pos[None] - w.pos
        err = (np.arctan2(d[:, 1], d[:, 0]) - w.heading + np.pi) % (2 * np.pi) - np.pi
        dist = np.hypot(d[:, 0], d[:, 1])
        v = np.stack([np.clip(2.0 * dist, 0.3, 1.5) * np.cos(err), 0.3 * np.sin(err)], 1)
        k = kick_at[order]
        w.step(v, np.clip(6 * err, -8, 8), np.ones(2, bool), np.where((k >= 0) & (t >= k), 0.6, 0.0))
        track.append((*w.ball_pos, *w.on_dribbler[order]))
    return np.array(track)


def probe(scenes: int, seed: int) -> dict:
    rng = np.random.default_rng(seed)
    decided = helped = hurt = 0
    for _ in range(scenes):
        a1 = rng.uniform(-np.pi, np.pi)
        a2 = a1 + np.pi + rng.uniform(-1.0, 1.0)
        r1, r2 = rng.uniform(0.2, 0.6, 2)
        pose = np.array([[r1 * np.cos(a1), r1 * np.sin(a1), a1 + np.pi + rng.normal(0, 0.2)],
                         [r2 * np.cos(a2), r2 * np.sin(a2), a2 + np.pi + rng.normal(0, 0.2)]])
        kick_at = np.where(rng.random(2) < 0.5, rng.integers(20, 80, 2), -1)
        first, second = contest(pose, kick_at, False), contest(pose, kick_at, True)
        if np.abs(first[:, :2] - second[:, :2]).max() <= 1e-3:
            continue
        decided += 1
        gain = (first[:, 2].mean() - first[:, 3].mean()) - (second[:, 2].mean() - second[:, 3].mean())
        helped += int(gain > 0.02)
        hurt += int(gain < -0.02)
    return {"scenes": scenes, "tracks_differ": decided, "first_helped": helped, "first_hurt": hurt}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scenes", type=int, default=1500, help="contests to play (each twice)")
    ap.add_argument("--seed", type=int, default=1, help="seed of the scenes")
    ap.add_argument("--index-order", action="store_true", help="create Box2D bodies in the robot order")
    ap.add_argument("--out", type=Path, default=None, help="JSON summary path")
    args = ap.parse_args(argv)
    if args.index_order:
        import ssl_marl.physics.world as world

        world.creation_order = lambda pose: np.arange(np.asarray(pose).shape[0])
    record = {**probe(args.scenes, args.seed), "index_order": bool(args.index_order)}
    print(json.dumps(record))
    if args.out is not None:
        from ssl_marl.io import atomic_write_json
        from ssl_marl.runners.provenance import build_manifest

        args.out.parent.mkdir(parents=True, exist_ok=True)
        atomic_write_json(args.out, {**record, "manifest": build_manifest(
            rules={"probe": "contest_order", "index_order": bool(args.index_order)},
            seeds={"seed": args.seed, "scenes": args.scenes})})
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
