"""Behaviour cloning of a benchmark decision policy into a MAPPO actor: a warm start.

CLI::

    python -m train.mappo_bc --task attack-3v2 --policy handcoded --episodes 300 --seed 100000 \\
        --out runs/bc_attack_3v2.pt
    python -m train mappo --task attack-3v2 --seed 0 --out runs/mappo_attack_bc_s0 \\
        --set init_actor=runs/bc_attack_3v2.pt --set actor_warmup_rollouts=4

Plays ``--episodes`` episodes of the benchmark policy (``ssl_marl.decisions``' registry:
``handcoded``, ``always-hold``, ``random``) on seeds ``SEED + i`` (keep them away from the
validation and evaluation seeds), records every decision (the deciding agent's observation, its
legal-option mask and the chosen option), and fits the shared actor of the task's default MAPPO
config (same sizes, hidden layers and observation scaling as ``python -m train mappo``) by
masked cross-entropy (Adam). The last ``--holdout`` fraction of the episodes is held out: the
printed accuracy on them says how well the network imitates the policy. The actor is written
(atomically) in the decision-actor format of :mod:`ssl_marl.decisions.learned`, so it can be
evaluated directly (``ssl-marl eval-task ... --policy learned --actor PATH``) or start a MAPPO
run (``init_actor``; ``actor_warmup_rollouts`` lets the critic learn the policy's values first,
so the first PPO steps do not push the cloned actor around with a random critic's advantages).
"""

from __future__ import annotations

import argparse
import functools
import json
from pathlib import Path
from typing import Any

import numpy as np
import torch
from tqdm import tqdm

from ssl_marl.skills.checkpoint import git_commit

from train.mappo.algorithm import MAPPO
from train.mappo.loop import space_scaling, save_decision_actor, task_config
from train.mappo.tasks import get_task


def parse_teachers(task: str, teachers: list[str], seed: int = 0) -> Any:
    """``DRILL=POLICY[:ACTOR]`` strings (one per drill of the mix task) as a
    :class:`~ssl_marl.decisions.attack_drill_mix.PerDrillPolicy`; ValueError naming a malformed entry."""
    from ssl_marl.decisions import make_decision_policy
    from ssl_marl.decisions.attack_drill_mix import PerDrillPolicy

    policies = {}
    for t in teachers:
        drill, sep, rest = t.partition("=")
        if not sep or not drill or not rest:
            raise ValueError(f"--teacher {t!r}: expected DRILL=POLICY[:ACTOR]")
        name, _, actor = rest.partition(":")
        policies[drill] = make_decision_policy(name, task, seed=seed, actor=actor or None)
    return PerDrillPolicy(policies)


def collect_demonstrations(task: str, policy: str | Any, episodes: int, seed: int,
                           progress: bool = True) -> dict[str, np.ndarray]:
    """The policy's decisions on seeds ``seed + i``: raw ``obs``, ``mask``, ``option``, ``agent``
    (index in ``possible_agents``) and ``episode`` (i), one row per decision. ``policy``: a name
    of the decision-policy registry or a policy object."""
    from ssl_marl.decisions import make_decision_policy

    if episodes < 1:
        raise ValueError(f"episodes must be >= 1, got {episodes}")
    cfg = task_config(task)
    env = get_task(task).factory(**cfg.task_kwargs)
    pol = make_decision_policy(policy, task, seed=seed) if isinstance(policy, str) else policy
    label = policy if isinstance(policy, str) else getattr(policy, "name", "policy")
    agents = list(env.possible_agents)
    rows: dict[str, list[Any]] = {k: [] for k in ("obs", "mask", "option", "agent", "episode")}
    for i in tqdm(range(episodes), disable=not progress, desc=f"demos {task}/{label}", unit="ep"):
        obs, infos = env.reset(seed=seed + i)
        pol.reset(env)
        while env.agents:
            act = {}
            for a in env.possible_agents:
                info = infos[a]
                if info.get("decision"):
                    o = int(pol.act(env, a, obs[a], info))
                    act[a] = o
                    rows["obs"].append(np.asarray(obs[a], np.float32))
                    rows["mask"].append(np.asarray(info.get("action_mask", np.ones(env.action_space(a).n)), np.int8))
                    rows["option"].append(o)
                    rows["agent"].append(agents.index(a))
                    rows["episode"].append(i)
                else:
                    act[a] = 0
            obs, _, _, _, infos = env.step(act)
    env.close()
    if not rows["obs"]:
        raise ValueError(f"policy {policy!r} made no decision in {episodes} episodes of {task!r}")
    return {k: np.stack(v) if k in ("obs", "mask") else np.asarray(v, np.int64) for k, v in rows.items()}


@functools.lru_cache(maxsize=None)
def _task_spec(task: str) -> dict[str, Any]:
    """Sizes, observation scaling, option and agent names of the task's default env (built
    once per task; read-only)."""
    cfg = task_config(task)
    env = get_task(task).factory(**cfg.task_kwargs)
    a0 = env.possible_agents[0]
    obs_c, obs_s = space_scaling(env.observation_space(a0))
    spec = {"cfg": cfg, "obs_dim": int(env.observation_space(a0).shape[0]), "state_dim": int(env.state_space.shape[0]),
            "agents": list(env.possible_agents), "n_out": int(env.action_space(a0).n), "obs_c": obs_c, "obs_s": obs_s,
            "option_names": getattr(env, "option_names", None)}
    env.close()
    return spec


def fit_actor(task: str, demos: dict[str, np.ndarray], epochs: int = 200, lr: float = 1e-3,
              batch: int = 256, holdout: float = 0.2, seed: int = 0) -> tuple[MAPPO, dict[str, Any]]:
    """A MAPPO agent (the task's default config) whose actor imitates ``demos``; and the
    fit's figures (samples, train / held-out accuracy and loss)."""
    sp = _task_spec(task)
    obs_c, obs_s = sp["obs_c"], sp["obs_s"]
    agent = MAPPO(sp["obs_dim"], sp["state_dim"], len(sp["agents"]), sp["n_out"], sp["cfg"].algo)
    torch.manual_seed(seed)
    gen = torch.Generator().manual_seed(seed)
    n_ep = int(demos["episode"].max()) + 1
    cut = n_ep - int(round(holdout * n_ep)) if holdout > 0 else n_ep
    train_i = np.flatnonzero(demos["episode"] < cut)
    test_i = np.flatnonzero(demos["episode"] >= cut)
    if len(train_i) == 0:
        raise ValueError("no training decisions left after the holdout; collect more episodes")
    x = agent.actor_input((demos["obs"] - obs_c) / obs_s, demos["agent"])
    mask = torch.as_tensor(demos["mask"])
    y = torch.as_tensor(demos["option"])
    opt = torch.optim.Adam(agent.actor.parameters(), lr=lr)

    def loss_acc(idx: np.ndarray) -> tuple[float, float]:
        with torch.no_grad():
            d = agent.actor.dist(x[idx], mask[idx])
            return float(-d.log_prob(y[idx]).mean()), float((d.probs.argmax(-1) == y[idx]).float().mean())

    ti = torch.as_tensor(train_i)
    for _ in range(epochs):
        perm = ti[torch.randperm(len(ti), generator=gen)]
        for s in range(0, len(perm), batch):
            j = perm[s:s + batch]
            loss = -agent.actor.dist(x[j], mask[j]).log_prob(y[j]).mean()
            opt.zero_grad(set_to_none=True)
            loss.backward()
            opt.step()
    tr_loss, tr_acc = loss_acc(train_i)
    te_loss, te_acc = loss_acc(test_i) if len(test_i) else (float("nan"), float("nan"))
    counts = np.bincount(demos["option"], minlength=agent.n_out)
    stats = {"decisions": int(len(y)), "episodes": n_ep, "train_decisions": int(len(train_i)),
             "holdout_decisions": int(len(test_i)), "train_loss": tr_loss, "train_accuracy": tr_acc,
             "holdout_loss": te_loss, "holdout_accuracy": te_acc,
             "majority_accuracy": float(counts.max() / counts.sum()), "option_counts": counts.tolist(),
             "epochs": epochs, "lr": lr}
    return agent, stats


def save_bc_actor(agent: MAPPO, task: str, path: str | Path, **meta: Any) -> Path:
    """Write the actor (atomically) in the decision-actor format, with the task's scaling."""
    sp = _task_spec(task)
    return save_decision_actor(Path(path), agent, task=task, obs_mean=sp["obs_c"], obs_std=sp["obs_s"],
                               option_names=sp["option_names"], agents=sp["agents"], commit=git_commit(), **meta)


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m train.mappo_bc", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--task", required=True, help="decision task (keepaway, attack-3v2, attack-drill)")
    p.add_argument("--policy", default="handcoded", help="benchmark policy to imitate (default handcoded)")
    p.add_argument("--teacher", action="append", default=[], metavar="DRILL=POLICY[:ACTOR]",
                   help="attack-drill-mix only, once per drill (one-defender, defended): the policy to imitate "
                        "in that drill, with its actor file if it takes one (replaces --policy)")
    p.add_argument("--episodes", type=int, default=300, help="demonstration episodes (default 300)")
    p.add_argument("--seed", type=int, default=100000, help="episode i uses seed SEED+i (default 100000)")
    p.add_argument("--epochs", type=int, default=200, help="passes over the training decisions (default 200)")
    p.add_argument("--lr", type=float, default=1e-3, help="Adam learning rate (default 1e-3)")
    p.add_argument("--holdout", type=float, default=0.2, help="fraction of episodes held out (default 0.2)")
    p.add_argument("--out", type=Path, required=True, help="actor file to write (.pt)")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    args = p.parse_args(argv)
    if not 0 <= args.holdout < 1:
        p.error(f"--holdout must be in [0, 1), got {args.holdout}")
    try:
        policy = parse_teachers(args.task, args.teacher, seed=args.seed) if args.teacher else args.policy
    except (ValueError, FileNotFoundError) as e:
        p.error(str(e))
    name = ", ".join(args.teacher) if args.teacher else args.policy
    demos = collect_demonstrations(args.task, policy, args.episodes, args.seed, progress=not args.no_progress)
    agent, stats = fit_actor(args.task, demos, epochs=args.epochs, lr=args.lr, holdout=args.holdout, seed=args.seed)
    save_bc_actor(agent, args.task, args.out, seed=args.seed, bc={"policy": name, **stats})
    print(json.dumps({"out": str(args.out), "policy": name, **stats}))
    return 0
