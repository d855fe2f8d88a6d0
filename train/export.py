"""Export the actor of a run's latest resumable checkpoint, without resuming the run.

    python -m train.export RUN_DIR [--out RUN_DIR/actor-<samples>.pt]

For model selection while a run goes on (each checkpoint replaces the previous one):
the actor file carries the same metadata as the run's final ``actor.pt``.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from ssl_marl.skills.checkpoint import safe_torch_load, save_actor
from ssl_marl.skills.networks import Actor

from .config import config_from_dict
from .loop import CHECKPOINT


def export_checkpoint_actor(run: str | Path, out: str | Path | None = None) -> Path:
    run = Path(run)
    state = safe_torch_load(run / CHECKPOINT, "ssl_marl training checkpoint")
    if not isinstance(state, dict) or state.get("format") != "ssl_marl.train_state":
        raise ValueError(f"{run / CHECKPOINT} is not an ssl_marl training checkpoint")
    cfg = config_from_dict(state["config"])
    sd = state["agent"]["actor"]
    obs_dim = sd["trunk.0.weight"].shape[1]
    act_dim = sd["head.weight"].shape[0]
    actor = Actor(obs_dim, act_dim, cfg.actor_hidden, cfg.layer_norm)
    actor.load_state_dict(sd)
    c = state["counters"]
    import gymnasium as gym

    import ssl_marl  # noqa: F401  (registers the skill envs)

    env = gym.make(cfg.env_id, **cfg.env_kwargs)
    spec = getattr(env.unwrapped, "spec_version", "") or cfg.env_id
    low, high = env.action_space.low.tolist(), env.action_space.high.tolist()
    env.close()
    meta = {"skill": cfg.skill, "obs_spec": spec, "env_id": cfg.env_id, "hyperparameters": cfg.to_dict(),
            "seed": state["seed"], "samples": int(c["samples"]),
            "demo_transitions": int(c["transitions"]) - int(c["samples"]), "updates": int(state["agent"]["updates"]),
            "action_low": low, "action_high": high, "exported_from": str(run / CHECKPOINT)}
    path = Path(out) if out else run / f"actor-{int(c['samples']):09d}.pt"
    return save_actor(path, actor, meta)


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("run", help="run folder holding checkpoint.pt")
    p.add_argument("--out", default=None, help="actor file (default RUN/actor-<samples>.pt)")
    a = p.parse_args(argv)
    print(export_checkpoint_actor(a.run, a.out))


if __name__ == "__main__":
    main()
