"""Probe: how much of the goal a defence of a goalie and 0-3 defenders on the ball-goal line leaves open.

No simulation: for every ball position on a grid of the attacking half (team frame, the
opponent goal at +x), the defence stands where its tactics put it for that ball
(:func:`~ssl_marl.plays.defense.goalie_guard_position` for a ball at rest and
:func:`~ssl_marl.plays.defense.block_position` with the standard plays' lane offsets,
``DEFENDER_SPACING``), and each of 21 shot lines across the goal mouth is rated by
:func:`~ssl_marl.plays.shot_lines.shot_line_margins` (the ball at the kicker's 6.5 m/s
against the opponents' reach times, reacting after ``--reaction`` s). Per defence it
reports, over the scoring zone (x from 1 m to 3.8 m, |y| <= 1.5 m: section 12's shot
probe) and the whole half, the share of ball positions whose best line has a margin of at
least 0 s / 0.05 s / 0.1 s, the median best margin and the median open goal angle
(:func:`~ssl_marl.plays.pass_decision.open_goal_interval`, the geometric shadows).

    python benchmarks/wall_probe.py --out results/tuning/wall_probe.json
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))


def defence_positions(ball: np.ndarray, defenders: int, field, rp) -> np.ndarray:
    """(1 + defenders, 2) goalie and defenders for ``ball`` (attacker's frame: they defend +x)."""
    from ssl_marl.plays.defense import block_position, goalie_guard_position
    from ssl_marl.plays.play import DEFENDER_SPACING

    b = -np.asarray(ball, float)  # the defence's own frame: its goal at -x
    pts = [goalie_guard_position(b, np.zeros(2), field, rp)]
    for i in range(defenders):
        pts.append(block_position(b, field, lane_offset=(i - (defenders - 1) / 2.0) * DEFENDER_SPACING))
    return -np.asarray(pts)


def probe(field_name: str, defenders: int, reaction_s: float, step_m: float) -> dict:
    from ssl_marl.physics.field import FieldGeometry
    from ssl_marl.physics.params import BallParams, RobotParams
    from ssl_marl.plays.pass_decision import DecisionParams, open_goal_interval
    from ssl_marl.plays.shot_lines import goal_line_targets, shot_line_margins

    field = FieldGeometry.from_name(field_name)
    rp, bp, dp = RobotParams(), BallParams(), DecisionParams()
    targets = goal_line_targets(field, 21)
    xs = np.arange(step_m / 2, field.half_length - field.defense_depth - 0.1, step_m)
    ys = np.arange(-field.half_width + step_m / 2, field.half_width, step_m)
    best, angle, zone = [], [], []
    for x in xs:
        for y in ys:
            p = np.array([x, y])
            opp = defence_positions(p, defenders, field, rp)
            best.append(float(shot_line_margins(p, targets, opp, np.zeros((0, 2)), rp, bp, dp, reaction_s).max()))
            angle.append(open_goal_interval(p, opp, field, rp, bp)[0])
            zone.append(1.0 <= x <= 3.8 and abs(y) <= 1.5)
    best, angle, zone = np.array(best), np.array(angle), np.array(zone)

    def summary(mask: np.ndarray) -> dict:
        b, a = best[mask], angle[mask]
        return {"positions": int(mask.sum()), "median_best_margin_s": float(np.median(b)),
                **{f"share_margin_ge_{t:g}s": float(np.mean(b >= t)) for t in (0.0, 0.05, 0.1)},
                "median_open_angle_rad": float(np.median(a)), "share_open_ge_0.05rad": float(np.mean(a >= 0.05))}

    return {"field": field.name, "defenders": defenders, "reaction_s": reaction_s, "grid_step_m": step_m,
            "scoring_zone": summary(zone), "half": summary(np.ones_like(zone))}


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--defenders", type=int, nargs="+", default=[0, 1, 2, 3], help="defenders beside the goalie")
    ap.add_argument("--field", choices=("div_a", "div_b"), nargs="+", default=["div_b", "div_a"])
    ap.add_argument("--reaction", type=float, default=None,
                    help="the defence's reaction time, s (default shot_lines.SHOT_REACTION_S)")
    ap.add_argument("--step", type=float, default=0.1, help="grid step, m (default 0.1)")
    ap.add_argument("--out", required=True, help="JSON output")
    args = ap.parse_args(argv)
    from ssl_marl.io import atomic_write_json
    from ssl_marl.plays.shot_lines import SHOT_REACTION_S
    from ssl_marl.runners.provenance import build_manifest

    reaction = SHOT_REACTION_S if args.reaction is None else float(args.reaction)
    rows = [probe(f, n, reaction, args.step) for f in args.field for n in args.defenders]
    for r in rows:
        z = r["scoring_zone"]
        print(f"{r['field']} goalie + {r['defenders']}: zone median best margin "
              f"{z['median_best_margin_s']:+.3f} s, >= 0.05 s {100 * z['share_margin_ge_0.05s']:.0f} %, open >= 0.05 rad {100 * z['share_open_ge_0.05rad']:.0f} %")
    manifest = build_manifest({"probe": "wall", "reaction_s": reaction, "grid_step_m": args.step},
                              {"seed": None})
    atomic_write_json(args.out, {"rows": rows, "manifest": manifest})


if __name__ == "__main__":
    main()
