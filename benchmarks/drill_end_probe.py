"""How a drill's attacks end: who wins the ball, and the carrier's last option before the end.

For each episode of an attack drill (``ssl_marl.decisions``, e.g. ``attack-drill-defended``) played
by one decision policy (as ``ssl-marl eval-task``), this records the outcome, the time (s), the
number of decisions, the carrier's last option and when it was chosen, and, for a ball lost to a
defender, the defence's role (its play's role name: ``attacker`` is the defense play's robot that
presses the ball) of the robot(s) holding it. The summary counts them.

    python benchmarks/drill_end_probe.py --task attack-drill-defended --policy handcoded \\
        --seeds 155000-155199 --out results/tuning/drill_end_probe/handcoded_155000.json
"""

from __future__ import annotations

import argparse
import collections
import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from benchmarks.ball_out_probe import seed_range  # noqa: E402


def probe_episode(env, policy, seed: int) -> dict:
    """One episode's end (module docstring): :func:`~ssl_marl.decisions.policies.run_episode`'s
    record, then the env's last tick (its world and the defence's roles)."""
    from ssl_marl.decisions.policies import run_episode

    r = run_episode(env, policy, seed=seed, record=True)
    last = r["trace"][-1] if r["trace"] else None  # (t, agent, option)
    roles = dict(env.yellow.roles)
    holders = [roles.get(int(k), "unassigned") for k in np.flatnonzero(env.engine.world_state().yellow.ball_on_dribbler)]
    return {"seed": seed, "outcome": r["outcome"], "t_s": round(r["t_s"], 2), "decisions": r["decisions"],
            "last_option": env.option_names[last[2]] if last else None,
            "last_option_t_s": round(last[0], 2) if last else None, "defence_holders": holders}


def summarize(rows: list[dict]) -> dict:
    lost = [r for r in rows if r["outcome"] == "lost_defender"]
    return {"episodes": len(rows), "outcomes": dict(collections.Counter(r["outcome"] for r in rows)),
            "goals": sum(r["outcome"] == "goal" for r in rows),
            "lost_defender_by_role": dict(collections.Counter("+".join(r["defence_holders"]) for r in lost)),
            "lost_defender_before_a_decision": sum(r["decisions"] == 0 for r in lost),
            "last_option_before": {o: dict(collections.Counter(r["last_option"] for r in rows if r["outcome"] == o))
                                   for o in ("lost_defender", "out", "goal")},
            "median_t_s": {o: float(np.median([r["t_s"] for r in rows if r["outcome"] == o]))
                           for o in ("lost_defender", "out", "goal") if any(r["outcome"] == o for r in rows)}}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--task", default="attack-drill-defended", help="attack drill task (default attack-drill-defended)")
    ap.add_argument("--policy", default="handcoded", help="decision policy: handcoded or learned (default handcoded)")
    ap.add_argument("--actor", default=None, help="decision actor file for --policy learned (default: the shipped one)")
    ap.add_argument("--seeds", type=seed_range, default=seed_range("155000-155199"),
                    help="seed range A-B (tuning seeds; default 155000-155199)")
    ap.add_argument("--out", default=None, help="JSON output (summary and every episode)")
    args = ap.parse_args(argv)

    from ssl_marl.decisions import make_decision_env, make_decision_policy
    from ssl_marl.io import atomic_write_json
    from ssl_marl.runners.provenance import build_manifest

    env = make_decision_env(args.task)
    policy = make_decision_policy(args.policy, args.task, actor=args.actor)
    rows = [probe_episode(env, policy, s) for s in args.seeds]
    summary = summarize(rows)
    print(json.dumps(summary, indent=1))
    if args.out:
        from ssl_marl.decisions.learned import pretrained_path

        actor = (args.actor or pretrained_path(args.task)) if args.policy == "learned" else args.actor
        atomic_write_json(args.out, {"summary": summary, "episodes": rows, "manifest": build_manifest(
            rules={"task": args.task, "policy": args.policy, "actor": args.actor}, seeds={"seeds": args.seeds},
            actor_files=[actor])})
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
