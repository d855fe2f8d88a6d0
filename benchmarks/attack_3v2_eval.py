"""Attack 3v2 benchmark policies over many episodes (resumable), until ``ssl-marl eval-task`` covers it.

Episode i uses seed ``--seed + i`` (independent of ``--workers``). Each finished
episode is appended to ``OUT/episodes.jsonl`` as it comes, so an interrupted run resumes
where it stopped (episodes already in the file are skipped); ``OUT/results.json`` is
rewritten (atomically) after every chunk with the goal rate, its 95 % Wilson interval
and the outcome counts over the episodes done so far.

    python benchmarks/attack_3v2_eval.py --policy handcoded --episodes 1000 --seed 41000 \
        --workers 2 --out results/attack_3v2_handcoded
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import sys
import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from pathlib import Path

_ENV = None
_POLICY = None


def _init(policy: str, skills: str) -> None:
    global _ENV, _POLICY
    import torch

    torch.set_num_threads(1)
    from ssl_marl.decisions import make_decision_policy
    from ssl_marl.decisions.attack import Attack3v2Env

    _ENV = Attack3v2Env(skills=skills)
    # the registry's policies, as eval-task builds them (random: RandomPolicy(0); learned: the shipped actor)
    _POLICY = make_decision_policy(policy, "attack-3v2", seed=0)


def _run(seeds: list[int]) -> list[dict]:
    from ssl_marl.decisions.policies import run_episode

    out = []
    for s in seeds:
        t0 = time.perf_counter()
        r = run_episode(_ENV, _POLICY, seed=s)
        r["wall_s"] = time.perf_counter() - t0
        out.append(r)
    return out


def summarize(rows: list[dict], args: argparse.Namespace, wall: float) -> dict:
    """Figures over the longest run of consecutive seeds from ``--seed`` that is complete
    (an interrupted run reports a prefix of the seeds, not a selection of fast episodes)."""
    by_seed = {r["seed"]: r for r in rows}
    prefix = []
    while args.seed + len(prefix) in by_seed:
        prefix.append(by_seed[args.seed + len(prefix)])
    rows = prefix
    n = len(rows)
    goals = sum(int(r["goal"]) for r in rows)
    outcomes: dict[str, int] = {}
    for r in rows:
        outcomes[r["outcome"]] = outcomes.get(r["outcome"], 0) + 1
    sim = sum(r["t_s"] for r in rows)
    dec = sum(r["decisions"] for r in rows)
    ep_wall = sum(r["wall_s"] for r in rows)
    opts: dict[str, int] = {}
    for r in rows:
        for k, v in r["options"].items():
            opts[k] = opts.get(k, 0) + v
    from ssl_marl.runners.statistics import wilson_interval

    lo, hi = wilson_interval(goals, n)
    return {"task": "attack-3v2", "policy": args.policy, "skills": args.skills, "episodes": n,
            "episodes_requested": args.episodes, "seeds": [args.seed, args.seed + n - 1], "seed": args.seed, "goal_rate": goals / n if n else None,
            "goal_rate_ci95": [lo, hi], "goals": goals, "outcomes": dict(sorted(outcomes.items())),
            "mean_duration_s": sim / n if n else None, "decisions": dec, "options": opts,
            "decisions_per_s": dec / ep_wall if ep_wall else None, "sim_s_per_s": sim / ep_wall if ep_wall else None,
            "episode_wall_s_total": ep_wall, "wall_s_this_run": wall, "machine": platform.processor() or platform.machine(),
            "command": "python benchmarks/attack_3v2_eval.py " + " ".join(sys.argv[1:])}


def export(src: Path, dst: Path, policy: str, seed: int, episodes: int | None) -> dict:
    """Write ``dst/results.json`` (+ ``duration_hist.png``) in ``ssl-marl eval-task``'s format
    from the longest complete prefix of seeds in ``src/episodes.jsonl`` (at most ``episodes``).
    The episodes are the ones eval-task plays (same env, same seeds, ``RandomPolicy(0)``),
    so the figures equal ``ssl-marl eval-task attack-3v2 --policy POLICY --episodes N --seed SEED``."""
    from ssl_marl.runners.task_eval import task_results, write_task_results

    rows = {}
    for line in (src / "episodes.jsonl").read_text().splitlines():
        if line.strip():
            r = json.loads(line)
            rows[r["seed"]] = r
    eps = []
    while seed + len(eps) in rows and (episodes is None or len(eps) < episodes):
        r = rows[seed + len(eps)]
        eps.append({"index": len(eps), "seed": r["seed"], "outcome": r["outcome"], "duration_s": float(r["t_s"]),
                    "decisions": int(r["decisions"]), "steps": int(r["steps"]), "options": r["options"],
                    "goal": int(r["goal"])})
    wall = sum(rows[e["seed"]]["wall_s"] for e in eps)
    dec = sum(e["decisions"] for e in eps)
    throughput = {"episode_wall_s_sum": wall, "decisions_per_s": dec / wall,
                  "sim_s_per_s": sum(e["duration_s"] for e in eps) / wall,
                  "note": "per worker process (episode wall time summed); not deterministic"}
    config = {"realism": "none", "field": "div_b", "workers": None, "backend": "local",
              "runner": "benchmarks/attack_3v2_eval.py (same episodes as ssl-marl eval-task)"}
    res = task_results("attack-3v2", policy, eps, seed=seed, actor=None, config=config, throughput=throughput)
    write_task_results(res, dst)
    return res


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--policy", choices=("handcoded", "random", "learned"), required=True,
                   help="benchmark policy, or learned (the shipped pretrained/attack_3v2.pt)")
    p.add_argument("--episodes", type=int, default=1000, help="episodes (default 1000)")
    p.add_argument("--seed", type=int, default=41000, help="episode i uses seed + i (default 41000)")
    p.add_argument("--workers", type=int, default=1, help="worker processes (default 1)")
    p.add_argument("--skills", choices=("learned", "baseline"), default="learned", help="both teams' skills")
    p.add_argument("--chunk", type=int, default=5, help="episodes per job (default 5)")
    p.add_argument("--out", required=True, help="output folder")
    p.add_argument("--export", default=None, metavar="DIR",
                   help="do not run: write DIR/results.json in eval-task's format from OUT/episodes.jsonl "
                        "(the complete prefix of seeds, at most --episodes)")
    args = p.parse_args()
    if args.export:
        r = export(Path(args.out), Path(args.export), args.policy, args.seed, args.episodes)
        print(f"{args.policy}: goal rate {r['goal_rate']:.3f} {r['goal_rate_ci95']} over {r['episodes']} episodes; "
              f"outcomes {r['outcomes']} -> {args.export}/results.json")
        return 0
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    log = out / "episodes.jsonl"
    rows = [json.loads(line) for line in log.read_text().splitlines() if line.strip()] if log.exists() else []
    rows = [r for r in rows if args.seed <= r["seed"] < args.seed + args.episodes]
    done = {r["seed"] for r in rows}
    todo = [args.seed + i for i in range(args.episodes) if args.seed + i not in done]
    chunks = [todo[i:i + args.chunk] for i in range(0, len(todo), args.chunk)]
    t0 = time.perf_counter()
    from tqdm import tqdm

    def write() -> None:
        rows.sort(key=lambda r: r["seed"])
        tmp = out / "results.json.tmp"
        tmp.write_text(json.dumps(summarize(rows, args, time.perf_counter() - t0), indent=1))
        os.replace(tmp, out / "results.json")

    with ProcessPoolExecutor(args.workers, initializer=_init, initargs=(args.policy, args.skills)) as ex, \
            open(log, "a") as f, tqdm(total=len(todo), desc=f"attack-3v2 {args.policy}", unit="ep") as bar:
        futs = [ex.submit(_run, c) for c in chunks]
        for fut in as_completed(futs):
            for r in fut.result():
                f.write(json.dumps(r) + "\n")
                rows.append(r)
            f.flush()
            bar.update(len(fut.result()))
            write()
    write()
    s = json.loads((out / "results.json").read_text())
    print(f"{args.policy}: goal rate {s['goal_rate']:.3f} [{s['goal_rate_ci95'][0]:.3f}, {s['goal_rate_ci95'][1]:.3f}] "
          f"over {s['episodes']} episodes; outcomes {s['outcomes']}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
