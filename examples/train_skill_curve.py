"""Train the go-to-ball skill briefly with DDPG and draw its learning curve.

    python examples/train_skill_curve.py [--out runs/example_gtb] [--samples 3000]

A deliberately tiny run (small networks, a few thousand samples: under a minute on
one CPU core) to show the workflow; the shipped actor took 380,006 samples
(``ssl-marl train go-to-ball --config train/configs/go_to_ball_both.json --seed 0``,
see ``ssl_marl/skills/pretrained/MANIFEST.md``). The
same run from the command line::

    ssl-marl train go-to-ball --seed 0 --out runs/example_gtb --samples 3000 \\
        --set demo_steps=2000 --set ddpg.actor_hidden=[64,64] --set ddpg.critic_hidden=[64,64] \\
        --set 'env_kwargs={"max_time_s": 4.0}' ...

Writes ``OUT/progress.csv`` (one row per episode), ``OUT/eval.csv``,
``OUT/actor.pt`` (loadable by ``make_skill("go_to_ball", "learned", field,
checkpoint=...)``) and ``OUT/learning_curve.png``. Rerunning with the same OUT
resumes (and finishes at once when the run is complete).
"""

from __future__ import annotations

import argparse
from pathlib import Path

from train.offpolicy.config import apply_overrides, default_config
from train.offpolicy.loop import train
from train.tools.plots import plot_run


def main(argv: list[str] | None = None) -> dict:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--out", type=Path, default=Path("runs/example_gtb"), help="run folder")
    p.add_argument("--samples", type=int, default=3000, help="env samples after the demonstrations (default 3000)")
    p.add_argument("--seed", type=int, default=0, help="training seed (default 0)")
    args = p.parse_args(argv)

    cfg = apply_overrides(default_config("go-to-ball"), [
        f"total_samples={args.samples}", "demo_steps=2000", "warmup_samples=500",
        "ddpg.actor_hidden=[64,64]", "ddpg.critic_hidden=[64,64]", "batch_size=64",
        'env_kwargs={"max_time_s": 4.0}',  # shorter episodes than the paper's 10 s: more of them
        f"eval_interval={max(args.samples // 2, 1)}", "eval_episodes=2", f"checkpoint_interval={args.samples}",
    ])
    resume = (args.out / "checkpoint.pt").is_file()
    result = train(cfg, args.seed, args.out, resume=resume, progress=False)
    png = plot_run(args.out)
    print(f"{cfg.skill}: {args.samples} samples after 2000 demonstration steps, "
          f"success rate {result['success_rate']:.2f}, mean return {result['mean_return']:.1f}; "
          f"actor -> {args.out / 'actor.pt'}, curve -> {png}")
    return result


if __name__ == "__main__":
    main()
