"""Export the actor of a run's latest resumable checkpoint, without resuming the run.

    python -m train.export RUN_DIR [--out RUN_DIR/actor-<samples>.pt]

For model selection while a run goes on (each checkpoint replaces the previous one):
the actor file carries the same metadata as the run's final ``actor.pt``
(:func:`train.offpolicy.checkpoints.actor_metadata`), whatever the algorithm.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from ssl_marl.skills.checkpoint import save_actor
from ssl_marl.skills.networks import Actor

from train.offpolicy.checkpoints import CHECKPOINT, actor_metadata, read_train_state
from train.offpolicy.config import config_from_dict


def export_checkpoint_actor(run: str | Path, out: str | Path | None = None) -> Path:
    run = Path(run)
    state = read_train_state(run / CHECKPOINT)
    cfg = config_from_dict(state["config"])
    sd = state["agent"]["actor"]  # every algorithm keeps its deployable Actor under "actor"
    obs_dim = sd["trunk.0.weight"].shape[1]
    act_dim = sd["head.weight"].shape[0]
    actor = Actor(obs_dim, act_dim, cfg.ddpg.actor_hidden, cfg.ddpg.layer_norm)
    actor.load_state_dict(sd)
    c = state["counters"]
    from train.offpolicy.evaluate import make_env  # imports ssl_marl, which registers the skill envs
    from train.offpolicy.loop import spec_version

    env = make_env(cfg.env_id, cfg.env_kwargs, cfg.max_episode_steps)
    spec = spec_version(env, cfg.env_id)
    low, high = env.action_space.low.tolist(), env.action_space.high.tolist()
    env.close()
    meta = actor_metadata(cfg, obs_spec=spec, seed=state["seed"], samples=int(c["samples"]),
                          transitions=int(c["transitions"]), updates=int(state["agent"]["updates"]),
                          action_low=low, action_high=high, exported_from=str(run / CHECKPOINT))
    path = Path(out) if out else run / f"actor-{int(c['samples']):09d}.pt"
    return save_actor(path, actor, meta)


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(prog="python -m train.export", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("run", help="run folder holding checkpoint.pt")
    p.add_argument("--out", default=None, help="actor file (default RUN/actor-<samples>.pt)")
    a = p.parse_args(argv)
    print(export_checkpoint_actor(a.run, a.out))
