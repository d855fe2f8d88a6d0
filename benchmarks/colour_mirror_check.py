"""Is the control stack colour-blind? The same scene played from both colours, mirrored.

Env A holds a random 6v6 Division B scene (chip env, no realism); env B holds its mirror
image with the colours swapped: every robot of A's blue team is B's yellow robot of the same
index at (-x, -y, heading + pi), and the other way round; the ball at (-x, -y). Team
``--team`` plays blue in A and yellow in B, ``--opponent`` the other side, each controller
built fresh with the same seed in both. Both envs are stepped with their own controllers'
commands. Body-frame commands do not change under the mirror, so a colour-blind stack gives
the same commands in A and B, and mirrored worlds, up to float rounding. For each scene this
reports the first control step at which a command differs by more than ``--command-tol`` or
the worlds by more than ``--world-tol`` (m), the world difference then, and the robot and
both commands. A colour rule shows as a difference while the worlds still agree; float
rounding grows until the worlds part by about a millimetre, then decisions flip.

    python benchmarks/colour_mirror_check.py --team attack-baseline --seeds 0-3 --steps 900 --out results/tuning/colour_mirror_attack_baseline.json
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

ROBOTS = 6


def _other(team: str) -> str:
    return "yellow" if team == "blue" else "blue"


def check_scene(team: str, opponent: str, seed: int, steps: int, command_tol: float, world_tol: float) -> dict:
    """The first step at which the mirrored plays part (module docstring), or None."""
    from ssl_marl.envs import parallel_env
    from ssl_marl.envs.actions import fit_action
    from ssl_marl.runners.controllers import make_controller

    rng = np.random.default_rng(seed)
    opts = dict(n_blue=ROBOTS, n_yellow=ROBOTS, field="div_b", max_time_s=600.0, after_goal="kickoff",
                realtime=False, chip_kicks=True, restart_jitter_m=0.0)
    env_a, env_b = parallel_env(**opts), parallel_env(**opts)
    poses = {f"{t}_{i}": (float(sx * rng.uniform(0.3, 4.0)), float(rng.uniform(-2.8, 2.8)), float(rng.uniform(-3, 3)))
             for t, sx in (("blue", -1), ("yellow", 1)) for i in range(ROBOTS)}
    ball = (float(rng.uniform(-3, 3)), float(rng.uniform(-2, 2)))
    mirror = {}
    for name, (x, y, h) in poses.items():
        t, i = name.split("_")
        mirror[f"{_other(t)}_{i}"] = (-x, -y, float(np.arctan2(-np.sin(h), -np.cos(h))))
    env_a.reset(seed=seed, options={"robots": poses, "ball": {"pos": ball}})
    env_b.reset(seed=seed, options={"robots": mirror, "ball": {"pos": (-ball[0], -ball[1])}})
    cfg = env_a.config
    kw = dict(robot=cfg.robot, ball=cfg.ball, dt=cfg.dt)
    ctrl_a = [make_controller(team, "blue", ROBOTS, env_a.field, seed=1, **kw),
              make_controller(opponent, "yellow", ROBOTS, env_a.field, seed=2, **kw)]
    ctrl_b = [make_controller(team, "yellow", ROBOTS, env_b.field, seed=1, **kw),
              make_controller(opponent, "blue", ROBOTS, env_b.field, seed=2, **kw)]
    for c in ctrl_a + ctrl_b:
        if hasattr(c, "reset"):
            c.reset()
    for k in range(steps):
        act_a = {n: fit_action(v, 6) for c in ctrl_a for n, v in c.act(env_a).items()}
        act_b = {n: fit_action(v, 6) for c in ctrl_b for n, v in c.act(env_b).items()}
        wa, wb = env_a.world_state(), env_b.world_state()
        world = max(float(np.abs(wa.blue.pos + wb.yellow.pos).max()), float(np.abs(wa.yellow.pos + wb.blue.pos).max()),
                    float(np.abs(wa.ball_pos + wb.ball_pos).max()))
        diffs = {n: float(np.abs(a - act_b[f"{_other(n.split('_')[0])}_{n.split('_')[1]}"]).max())
                 for n, a in act_a.items()}
        worst = max(diffs, key=diffs.get)
        if diffs[worst] > command_tol or world > world_tol:
            mate = f"{_other(worst.split('_')[0])}_{worst.split('_')[1]}"
            return {"seed": seed, "step": k, "world_diff_m": world, "command_diff": diffs[worst], "robot": worst,
                    "command_a": act_a[worst].round(4).tolist(), "command_b": act_b[mate].round(4).tolist()}
        env_a.step(act_a)
        env_b.step(act_b)
    return {"seed": seed, "step": None}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--team", default="attack-baseline", help="team kind on blue in A and yellow in B")
    ap.add_argument("--opponent", default=None, help="team kind on the other side (default: --team)")
    ap.add_argument("--seeds", default="0-3", help="scene seeds, e.g. 0-3")
    ap.add_argument("--steps", type=int, default=900, help="control steps per scene (60 per second)")
    ap.add_argument("--command-tol", type=float, default=0.05, help="largest command difference tolerated")
    ap.add_argument("--world-tol", type=float, default=0.01, help="largest world difference tolerated (m)")
    ap.add_argument("--out", type=Path, default=None, help="JSON summary path")
    args = ap.parse_args(argv)
    lo, _, hi = args.seeds.partition("-")
    scenes = [check_scene(args.team, args.opponent or args.team, s, args.steps, args.command_tol, args.world_tol)
              for s in range(int(lo), int(hi or lo) + 1)]
    for sc in scenes:
        print(json.dumps(sc))
    if args.out is not None:
        from ssl_marl.io import atomic_write_json
        from ssl_marl.runners.provenance import build_manifest

        opponent = args.opponent or args.team
        args.out.parent.mkdir(parents=True, exist_ok=True)
        atomic_write_json(args.out, {"team": args.team, "opponent": opponent, "scenes": scenes, "manifest": build_manifest(
            rules={"probe": "colour_mirror", "team": args.team, "opponent": opponent, "steps": args.steps,
                   "command_tol": args.command_tol, "world_tol": args.world_tol},
            seeds={"seeds": [sc["seed"] for sc in scenes]})})
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
