"""Local process pool vs a local Ray instance for the same tactic evaluation, side by side.

    python benchmarks/bench_backends.py [--episodes 1000] [--workers 2] [--skills baseline] [--out results/bench_backends.json]

Runs ``evaluate_tactic`` (the ``eval-tactic`` protocol) twice in one process: first
on the local pool (``--workers`` spawned processes), then on a local Ray instance
started here with ``num_cpus=--workers`` (its start-up time is measured and included
in the Ray wall time, as a user pays it); with ``--bracket`` the local pool runs again
afterwards and Ray is compared with the mean of the two. Checks that all give identical episodes
and prints the wall times and the ratio ray / local as JSON (also written to
``--out``). The machine may be shared: the load average before and after is recorded.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--episodes", type=int, default=1000)
    p.add_argument("--workers", type=int, default=2)
    p.add_argument("--skills", choices=("learned", "baseline"), default="baseline",
                   help="skills inside the tactic (default baseline: ~3x cheaper episodes, so the backend's "
                        "own overhead weighs more)")
    p.add_argument("--seed", type=int, default=20_000)
    p.add_argument("--out", type=Path, default=ROOT / "results" / "bench_backends.json")
    p.add_argument("--bracket", action="store_true", help="run the local pool again after Ray (local, ray, local) "
                   "and compare Ray with the mean of the two local runs")
    args = p.parse_args(argv)

    import ray

    from ssl_marl.io import atomic_write_json
    from ssl_marl.runners.pool import ray_init
    from ssl_marl.runners.tactic_eval import evaluate_tactic

    kw = dict(episodes=args.episodes, seed=args.seed, workers=args.workers, progress=False)
    load0 = os.getloadavg()
    t0 = time.perf_counter()
    local = evaluate_tactic(args.skills, backend="local", **kw)
    t_local = time.perf_counter() - t0
    partial = args.out.with_name(args.out.stem + "_local_only.json")  # in case the Ray half is interrupted
    atomic_write_json(partial, {"local_wall_s": round(t_local, 2), "episodes": args.episodes, "workers": args.workers,
                                "skills": args.skills, "loadavg_1_5_15_before": list(load0),
                                "loadavg_after_local": list(os.getloadavg())})

    t0 = time.perf_counter()
    ray_init(None, num_cpus=args.workers)
    t_init = time.perf_counter() - t0
    ray_res = evaluate_tactic(args.skills, backend="ray", **kw)
    t_ray = time.perf_counter() - t0
    load1 = os.getloadavg()
    ray.shutdown()
    t_local2 = None
    if args.bracket:  # local again after Ray: the machine's load drifts
        atomic_write_json(partial, {"local_wall_s": round(t_local, 2), "ray_wall_s": round(t_ray, 2),
                                    "ray_init_s": round(t_init, 2), "episodes": args.episodes,
                                    "identical": local["episodes_detail"] == ray_res["episodes_detail"]})
        t0 = time.perf_counter()
        local2 = evaluate_tactic(args.skills, backend="local", **kw)
        t_local2 = time.perf_counter() - t0
        assert local2["episodes_detail"] == local["episodes_detail"]

    identical = local["episodes_detail"] == ray_res["episodes_detail"]
    out = {
        "command": "python benchmarks/bench_backends.py " + " ".join(argv if argv is not None else sys.argv[1:]),
        "date": time.strftime("%Y-%m-%d %H:%M:%S %Z"), "machine": f"{platform.machine()}, {os.cpu_count()} cores",
        "python": platform.python_version(), "ray": ray.__version__,
        "episodes": args.episodes, "workers": args.workers, "skills": args.skills, "seed": args.seed,
        "local_wall_s": round(t_local, 2), "local_again_wall_s": None if t_local2 is None else round(t_local2, 2),
        "ray_wall_s": round(t_ray, 2), "ray_init_s": round(t_init, 2),
        "ray_eval_wall_s": round(t_ray - t_init, 2),
        "ratio_ray_over_local": round(t_ray / (t_local if t_local2 is None else 0.5 * (t_local + t_local2)), 3),
        "ratio_ray_over_local_without_init": round(
            (t_ray - t_init) / (t_local if t_local2 is None else 0.5 * (t_local + t_local2)), 3),
        "identical_episodes": identical, "success_rate": local["success_rate"],
        "loadavg_1_5_15_before": [round(x, 2) for x in load0], "loadavg_1_5_15_after": [round(x, 2) for x in load1],
    }
    print(json.dumps(out, indent=2))
    atomic_write_json(args.out, out)
    return 0 if identical else 1


if __name__ == "__main__":
    sys.exit(main())
