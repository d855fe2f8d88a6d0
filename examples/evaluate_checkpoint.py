"""Evaluate a learned-skill checkpoint with the paper's protocol, from Python.

    python examples/evaluate_checkpoint.py [CHECKPOINT] [--episodes 20] [--out DIR]

CHECKPOINT defaults to the shipped go-to-ball actor
(``ssl_marl/skills/pretrained/go_to_ball.pt``); any ``actor.pt`` written by
``ssl-marl train`` works. The checkpoint is loaded with ``weights_only=True`` and
its metadata (skill, observation spec, training seed and samples) is printed; then
it runs from random spawns on the held-out evaluation seed 10000, as
``ssl-marl eval-skill`` does, and compares with the hand-coded baseline on the same
episodes.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from ssl_marl.skills.checkpoint import load_actor
from ssl_marl.runners.skill_eval import evaluate_skill
from ssl_marl.skills.registry import get_skill


def main(argv: list[str] | None = None) -> dict:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("checkpoint", nargs="?", default=str(get_skill("go_to_ball").actor), help="actor checkpoint (.pt)")
    p.add_argument("--episodes", type=int, default=20, help="episodes per policy (default 20; the paper uses 1000)")
    p.add_argument("--out", type=Path, default=None, help="folder for results.json and time_hist.png")
    args = p.parse_args(argv)

    actor, meta = load_actor(args.checkpoint)  # never runs code from the file
    skill = meta["skill"].replace("_", "-")
    print(f"{args.checkpoint}: {meta['skill']} ({meta['obs_spec']}), obs {actor.obs_dim} -> act {actor.act_dim}, "
          f"trained with seed {meta.get('seed')} on {meta.get('samples')} samples")
    results = {}
    for policy in (args.checkpoint, "baseline"):
        out = None if args.out is None else args.out / ("learned" if policy != "baseline" else "baseline")
        s = evaluate_skill(skill, policy, episodes=args.episodes, seed=10_000, workers=1, out=out, progress=False)
        lo, hi = s["success_ci95"]
        t = s["time_to_success_s"]["mean"]
        name = "learned" if policy != "baseline" else "baseline"
        print(f"{name:>8}: success {s['success_rate']:.2f} [95% CI {lo:.2f}-{hi:.2f}] over {s['episodes']} episodes, "
              f"mean time to success {t:.2f} s" if t is not None else f"{name:>8}: no success")
        results[name] = s
    return results


if __name__ == "__main__":
    main()
