"""Rollout policy improvement: one step of approximate policy iteration over a benchmark decision policy.

CLI::

    python -m train.mappo_rollout_pi collect --task attack-drill --episodes 600 --seed 120000 --out runs/rpi_drill
    python -m train.mappo_rollout_pi fit --task attack-drill --labels runs/rpi_drill --out runs/rpi_drill/actor.pt
    python -m train.mappo_rollout_pi summarize --task attack-drill --labels runs/rpi_drill --out values.json
    ssl-marl eval-task attack-drill --policy learned --actor runs/rpi_drill/actor.pt --episodes 200 --seed 49000

**collect** plays the benchmark policy (``handcoded`` by default) on seeds ``SEED + i``; at each of
an episode's first ``--max-decisions`` decisions it plays the episode again once per other legal
option: the benchmark everywhere, that option at that decision (the tasks are deterministic under
the seed, so the replay reaches the same decision; a replay that does not raises). Each decision
row keeps the deciding agent's observation, mask and index, the benchmark's option, and the
episode's return after every legal option (NaN for illegal ones): Monte-Carlo values Q(s, o) of
the benchmark policy (Bertsekas's rollout; Lagoudakis and Parr's classification-based policy
iteration). Rows go to ``OUT/labels-<first seed>.npz`` in chunks of ``--chunk`` episodes, written
atomically; a rerun skips the chunks already there, so collection resumes and several processes
can share the seed range (``--episodes`` / ``--seed`` per process). ``--realism realistic`` labels
the task's world under the realistic preset with the tracker on (as ``eval-task --realism
realistic`` plays it; noise and tracker are seeded by the episode, so the replays hold), ``--field``
the other division; each chunk records both, and a folder takes one condition only.

**fit** trains the shared actor of the task's default MAPPO config (sizes, observation scaling,
agent one-hot) to predict each legal option's return from the observation: its logits are the
options' values under a logistic link (binary cross-entropy on the observed returns, which must lie
in [0, 1]: the drills' goal / no goal). A greedy decision actor (``--policy learned``) therefore
picks the option with the highest predicted value: the improved policy. The last ``--holdout``
fraction of the episodes is held out; the printed figures compare, on those decisions, the mean
return of the option the actor picks with the benchmark's (the rollout values of both are known).
The actor is written in the decision-actor format, so it is evaluated like any learned decision,
or warm-starts MAPPO (``--set init_actor=PATH``); ``--first-k`` / ``--margin`` are recorded in the file
(``improve``) as how :class:`~ssl_marl.decisions.learned.ImprovedDecisionPolicy` plays it
(``eval-task --policy improved --actor PATH``). ``collect --policy improved`` labels under the
improved policy: a second iteration, whose first-decision labels value an option followed by the
benchmark, as the first iteration's do.

**summarize** writes the labels' mean value of every option, by decision index and by the option
the benchmark chose (where the benchmark loses against another option), with each chunk's record.

**score** plays the improved policy offline on labels of the benchmark policy (e.g. ``collect
--max-decisions 1`` on tuning seeds): at each episode's first decision the value actor (or the
mean of several: an ensemble) picks as :class:`~ssl_marl.decisions.learned.ImprovedDecisionPolicy`
does, and since the labels hold every legal option's return with the benchmark playing on, the
episode's return under that pick is read, not played. One row per value actor set and margin:
its goal rate, the benchmark's, the best option's (an oracle: the ceiling of any first-decision
departure) and the paired difference with its 95 % interval. Exact for deterministic tasks;
several actors in one ``--actor`` are an ensemble (their logits averaged);
``--units`` says whether the margin compares logits (as the improved policy does) or predicted goals
(the logits' sigmoid).

**merge** writes value actors of one shape as one actor file that outputs their mean logits
(:mod:`train.mappo.ensemble`), with the ``improve`` record of ``fit``.
"""

from __future__ import annotations

import argparse
import io
import json
from pathlib import Path
from typing import Any

import numpy as np
import torch
from tqdm import tqdm

from ssl_marl.decisions.learned import DEFAULT_FIRST_K, DEFAULT_MARGIN
from ssl_marl.decisions.policies import run_episode
from ssl_marl.io import atomic_write_bytes, atomic_write_json

from train.mappo.algorithm import MAPPO
from train.mappo.bc import _task_spec, save_bc_actor
from train.mappo.loop import task_config
from train.mappo.tasks import get_task

LABEL_KEYS = ("obs", "mask", "agent", "seed", "decision", "base_option", "value")


class _Branch:
    """The benchmark policy everywhere but at decision ``k`` of the episode, where it answers
    ``option``; the benchmark is asked at every decision (its own state, e.g. the keep clock,
    runs as in the benchmark's episode). Records each decision's observation, mask and agent."""

    def __init__(self, base: Any, k: int = -1, option: int = 0) -> None:
        self.base, self.k, self.option = base, k, option

    def reset(self, env: Any) -> None:
        self.base.reset(env)
        self.i = 0
        self.rows: list[tuple[np.ndarray, np.ndarray, str, int]] = []

    def act(self, env: Any, agent: str, obs: np.ndarray, info: dict) -> int:
        mask = np.asarray(info["action_mask"], np.int8)
        o = int(self.base.act(env, agent, obs, info))
        self.rows.append((np.asarray(obs, np.float32), mask, agent, o))
        i, self.i = self.i, self.i + 1
        return self.option if i == self.k else o


def rollout_labels(env: Any, base: Any, seed: int, max_decisions: int) -> dict[str, np.ndarray] | None:
    """One episode's decision rows (module docstring); None if the benchmark made no decision."""
    root = _Branch(base)
    ret0 = float(run_episode(env, root, seed=seed)["return"])
    rows = root.rows[:max_decisions]
    if not rows:
        return None
    agents = list(env.possible_agents)
    value = np.full((len(rows), env.n_options), np.nan, np.float32)
    for k, (obs_k, mask_k, _, base_o) in enumerate(rows):
        value[k, base_o] = ret0
        for o in np.flatnonzero(mask_k):
            if int(o) == base_o:
                continue
            br = _Branch(base, k, int(o))
            value[k, o] = float(run_episode(env, br, seed=seed)["return"])
            seen = br.rows[k] if len(br.rows) > k else None
            if seen is None or not (np.array_equal(seen[0], obs_k) and np.array_equal(seen[1], mask_k)):
                raise RuntimeError(f"seed {seed}: the replay did not reach decision {k} as the benchmark's episode "
                                   "did; the task is not deterministic under the seed")
    return {"obs": np.stack([r[0] for r in rows]), "mask": np.stack([r[1] for r in rows]),
            "agent": np.array([agents.index(r[2]) for r in rows], np.int64),
            "seed": np.full(len(rows), seed, np.int64),
            "decision": np.arange(len(rows), dtype=np.int64),
            "base_option": np.array([r[3] for r in rows], np.int64), "value": value}


def _concat(parts: list[dict[str, np.ndarray]]) -> dict[str, np.ndarray]:
    return {k: np.concatenate([p[k] for p in parts]) for k in LABEL_KEYS}


def _write_npz(path: Path, data: dict[str, np.ndarray], meta: dict) -> None:
    buf = io.BytesIO()
    np.savez_compressed(buf, meta=np.array(json.dumps(meta)), **data)
    atomic_write_bytes(path, buf.getvalue())


def collect(task: str, out: str | Path, episodes: int, seed: int, policy: str = "handcoded",
            max_decisions: int = 4, chunk: int = 25, progress: bool = True, realism: str | None = None,
            field: str | None = None) -> list[Path]:
    """Label ``episodes`` episodes (seeds ``seed + i``) into ``out``'s chunk files (module
    docstring); returns the chunk files of this range, new and already there.

    ``realism`` ("none" or "realistic", the tracker on with it as in ``eval-task``) and ``field``
    ("div_a" or "div_b") are passed to the task when given (else the task's defaults) and recorded
    in every chunk's record; a folder's chunks must all share them."""
    from ssl_marl.decisions import make_decision_policy
    from ssl_marl.envs.tracking import resolve_tracker
    from ssl_marl.skills.checkpoint import git_commit

    if episodes < 1 or chunk < 1 or max_decisions < 1:
        raise ValueError(f"episodes, chunk and max_decisions must be >= 1, got {episodes}, {chunk}, {max_decisions}")
    if realism not in (None, "none", "realistic"):
        raise ValueError(f"realism must be 'none' or 'realistic', got {realism!r}")
    if field not in (None, "div_a", "div_b"):
        raise ValueError(f"field must be 'div_a' or 'div_b', got {field!r}")
    kwargs = dict(task_config(task).task_kwargs)
    if realism is not None:
        kwargs.update(realism=realism, tracker=resolve_tracker("auto", realism))
    if field is not None:
        kwargs["field"] = field
    conditions = {"realism": kwargs.get("realism", "none"), "field": kwargs.get("field", "div_b")}
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    for f in out.glob("labels-*.npz"):
        with np.load(f, allow_pickle=False) as z:
            there = json.loads(str(z["meta"]))
        got = {k: there.get(k, "none" if k == "realism" else "div_b") for k in conditions}
        if got != conditions:
            raise ValueError(f"{f} was collected with {got}, this run asks for {conditions}; use another --out")
    env = get_task(task).factory(**kwargs)
    base = make_decision_policy(policy, task, seed=seed)
    files = []
    bar = tqdm(total=episodes, disable=not progress, desc=f"rollout labels {task}", unit="ep")
    for c0 in range(seed, seed + episodes, chunk):
        n = min(chunk, seed + episodes - c0)
        path = out / f"labels-{c0}.npz"
        files.append(path)
        if path.exists():
            bar.update(n)
            continue
        parts = []
        for s in range(c0, c0 + n):
            rows = rollout_labels(env, base, s, max_decisions)
            if rows is not None:
                parts.append(rows)
            bar.update(1)
        meta = {"task": task, "policy": policy, "seeds": [c0, c0 + n - 1], "max_decisions": max_decisions,
                **conditions, "commit": git_commit()}
        _write_npz(path, _concat(parts) if parts else {k: np.zeros(0) for k in LABEL_KEYS}, meta)
    bar.close()
    env.close()
    return files


def load_labels(folder: str | Path) -> dict[str, np.ndarray]:
    """Every chunk file of ``folder``, concatenated (rows ordered by seed)."""
    files = sorted(Path(folder).glob("labels-*.npz"), key=lambda p: int(p.stem.split("-")[1]))
    if not files:
        raise ValueError(f"no labels-*.npz in {folder}")
    parts = []
    for f in files:
        with np.load(f, allow_pickle=False) as z:
            if z["obs"].size:
                parts.append({k: z[k] for k in LABEL_KEYS})
    if not parts:
        raise ValueError(f"the chunk files in {folder} hold no decision")
    return _concat(parts)


def fit_value_actor(task: str, labels: dict[str, np.ndarray], epochs: int = 300, lr: float = 1e-3,
                    batch: int = 256, holdout: float = 0.2, weight_decay: float = 1e-4,
                    seed: int = 0) -> tuple[MAPPO, dict[str, Any]]:
    """A MAPPO agent (the task's default config) whose actor logits predict each legal option's
    return (binary cross-entropy; module docstring); and the fit's figures."""
    val = labels["value"]
    seen = ~np.isnan(val)
    if np.any((val[seen] < 0) | (val[seen] > 1)):
        raise ValueError("rollout returns must lie in [0, 1] (goal / no goal) to be fitted as values")
    sp = _task_spec(task)
    agent = MAPPO(sp["obs_dim"], sp["state_dim"], len(sp["agents"]), sp["n_out"], sp["cfg"].algo)
    torch.manual_seed(seed)
    gen = torch.Generator().manual_seed(seed)
    eps = np.unique(labels["seed"])
    n_hold = min(int(round(holdout * len(eps))), len(eps) - 1)
    cut = eps[len(eps) - n_hold] if n_hold > 0 else eps[-1] + 1
    train_i, test_i = np.flatnonzero(labels["seed"] < cut), np.flatnonzero(labels["seed"] >= cut)
    if len(train_i) == 0:
        raise ValueError("no training decisions left after the holdout; collect more episodes")
    x = agent.actor_input((labels["obs"] - sp["obs_c"]) / sp["obs_s"], labels["agent"])
    y = torch.as_tensor(np.nan_to_num(val, nan=0.0))
    w = torch.as_tensor(seen.astype(np.float32))
    opt = torch.optim.Adam(agent.actor.parameters(), lr=lr, weight_decay=weight_decay)
    bce = torch.nn.BCEWithLogitsLoss(reduction="none")

    def loss_of(idx: torch.Tensor) -> torch.Tensor:
        return (bce(agent.actor.net(x[idx]), y[idx]) * w[idx]).sum() / w[idx].sum().clamp(min=1.0)

    def figures(idx: np.ndarray) -> dict[str, float]:
        if len(idx) == 0:
            return {}
        with torch.no_grad():
            logits = agent.actor.net(x[idx]).numpy()
            loss = float(loss_of(torch.as_tensor(idx)))
        pick = np.argmax(np.where(seen[idx], logits, -np.inf), axis=1)
        v = val[idx]
        return {"decisions": int(len(idx)), "loss": loss,
                "picked_value": float(v[np.arange(len(idx)), pick].mean()),
                "benchmark_value": float(v[np.arange(len(idx)), labels["base_option"][idx]].mean()),
                "best_value": float(np.nanmax(v, axis=1).mean()),
                "agrees_with_benchmark": float((pick == labels["base_option"][idx]).mean())}

    ti = torch.as_tensor(train_i)
    for _ in range(epochs):
        perm = ti[torch.randperm(len(ti), generator=gen)]
        for s in range(0, len(perm), batch):
            loss = loss_of(perm[s:s + batch])
            opt.zero_grad(set_to_none=True)
            loss.backward()
            opt.step()
    picks = np.argmax(np.where(seen, agent.actor.net(x).detach().numpy(), -np.inf), axis=1)
    stats = {"episodes": int(len(eps)), "train": figures(train_i), "holdout": figures(test_i),
             "picked_options": np.bincount(picks, minlength=agent.n_out).tolist(),
             "benchmark_options": np.bincount(labels["base_option"], minlength=agent.n_out).tolist(),
             "epochs": epochs, "lr": lr, "weight_decay": weight_decay}
    return agent, stats


def summarize(task: str, folders: list[str | Path]) -> dict[str, Any]:
    """The labels' mean rollout value of every option (by decision index, and by the option the
    benchmark chose), with each chunk's collection record (commit, seeds, policy)."""
    labels = _concat([load_labels(d) for d in folders])
    names = list(_task_spec(task)["option_names"] or range(labels["value"].shape[1]))
    val, base, dec = labels["value"], labels["base_option"], labels["decision"]

    def options(rows: np.ndarray) -> dict[str, list[float]]:
        v = val[rows]
        return {str(n): [int((~np.isnan(v[:, j])).sum()), float(np.nanmean(v[:, j]))]
                for j, n in enumerate(names) if (~np.isnan(v[:, j])).any()}

    by_decision = []
    for k in np.unique(dec):
        rows = np.flatnonzero(dec == k)
        by_decision.append({"decision": int(k), "decisions": int(len(rows)),
                            "benchmark": float(val[rows, base[rows]].mean()), "options": options(rows)})
    by_choice = []
    for o in np.unique(base):
        rows = np.flatnonzero(base == o)
        by_choice.append({"option": str(names[o]), "decisions": int(len(rows)),
                          "value": float(val[rows, o].mean()), "options": options(rows)})
    chunks = []
    for d in folders:
        for f in sorted(Path(d).glob("labels-*.npz"), key=lambda p: int(p.stem.split("-")[1])):
            with np.load(f, allow_pickle=False) as z:
                chunks.append({"file": f.name, **json.loads(str(z["meta"]))})
    seeds = sorted({int(x) for x in labels["seed"]})
    return {"task": task, "episodes": len(seeds), "decisions": int(len(base)), "seeds": [seeds[0], seeds[-1]],
            "by_decision": by_decision, "by_benchmark_option": by_choice, "chunks": chunks}


def score_first_decision(labels: dict[str, np.ndarray], actors: list[Any], margin: float,
                         units: str = "logit") -> dict[str, Any]:
    """The improved policy's figures at the labels' first decisions (module docstring, **score**).

    ``actors``: :class:`~ssl_marl.decisions.learned.DecisionActor` s whose logits are averaged (an
    ensemble, as one merged network computes it); ``margin`` in ``units``: "goal" (the sigmoid of
    the mean logit) or "logit"."""
    from ssl_marl.decisions.learned import better_option

    if units not in ("goal", "logit"):
        raise ValueError(f"units must be 'goal' or 'logit', got {units!r}")
    rows = np.flatnonzero(labels["decision"] == 0)
    if len(rows) == 0:
        raise ValueError("the labels hold no first decision")
    val = labels["value"]
    got, base, best, dev = [], [], [], 0
    for r in rows:
        idx = int(labels["agent"][r])
        v = np.mean([a.logits(labels["obs"][r], idx if a.n_agents else None) for a in actors], axis=0)
        if units == "goal":
            v = 1.0 / (1.0 + np.exp(-v))
        b = int(labels["base_option"][r])
        o = better_option(v, labels["mask"][r].astype(bool), b, margin)
        dev += o is not None
        got.append(val[r, b if o is None else o])
        base.append(val[r, b])
        best.append(np.nanmax(val[r]))
    got, base, best = np.asarray(got, float), np.asarray(base, float), np.asarray(best, float)
    d = got - base
    half = 1.96 * float(d.std(ddof=1)) / np.sqrt(len(d)) if len(d) > 1 else float("nan")
    return {"episodes": int(len(rows)), "goal_rate": float(got.mean()), "benchmark_goal_rate": float(base.mean()),
            "oracle_goal_rate": float(best.mean()), "deviations": int(dev),
            "paired_diff": float(d.mean()), "paired_diff_ci95": [float(d.mean()) - half, float(d.mean()) + half],
            "outcomes": {"goal": int(got.sum()), "no goal": int(len(got) - got.sum())}}


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m train.mappo_rollout_pi", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="cmd", required=True)
    c = sub.add_parser("collect", help="label decisions with the rollout values of every legal option")
    c.add_argument("--task", required=True, help="decision task (attack-3v2, attack-drill)")
    c.add_argument("--policy", default="handcoded", help="benchmark policy (default handcoded)")
    c.add_argument("--episodes", type=int, required=True, help="episodes to label")
    c.add_argument("--seed", type=int, required=True, help="episode i uses seed SEED+i")
    c.add_argument("--max-decisions", type=int, default=4, help="label an episode's first N decisions (default 4)")
    c.add_argument("--chunk", type=int, default=25, help="episodes per chunk file (default 25)")
    c.add_argument("--out", type=Path, required=True, help="folder of the chunk files (resumed if there)")
    c.add_argument("--realism", choices=("none", "realistic"), default=None,
                   help="realism preset of the task's world, the tracker on with realistic (default: the task's, none)")
    c.add_argument("--field", choices=("div_a", "div_b"), default=None,
                   help="field and team size of the task (default: the task's, div_b)")
    c.add_argument("--no-progress", action="store_true", help="no progress bar")
    f = sub.add_parser("fit", help="fit a value actor to the labels and write it")
    f.add_argument("--task", required=True, help="decision task the labels come from")
    f.add_argument("--labels", type=Path, nargs="+", required=True, help="folders of chunk files")
    f.add_argument("--epochs", type=int, default=300, help="passes over the training decisions (default 300)")
    f.add_argument("--lr", type=float, default=1e-3, help="Adam learning rate (default 1e-3)")
    f.add_argument("--weight-decay", type=float, default=1e-4, help="Adam weight decay (default 1e-4)")
    f.add_argument("--holdout", type=float, default=0.2, help="fraction of episodes held out (default 0.2)")
    f.add_argument("--seed", type=int, default=0, help="torch seed (default 0)")
    f.add_argument("--first-k", type=int, default=DEFAULT_FIRST_K,
                   help="recorded in the file: the improved policy may deviate at an episode's first K decisions "
                        f"(default {DEFAULT_FIRST_K})")
    f.add_argument("--margin", type=float, default=DEFAULT_MARGIN,
                   help="recorded in the file: the gain in logits (predicted log-odds of a goal) a deviation needs "
                        f"(default {DEFAULT_MARGIN})")
    f.add_argument("--out", type=Path, required=True, help="actor file to write (.pt)")
    m = sub.add_parser("summarize", help="write the labels' mean option values (JSON with a manifest)")
    m.add_argument("--task", required=True, help="decision task the labels come from")
    m.add_argument("--labels", type=Path, nargs="+", required=True, help="folders of chunk files")
    m.add_argument("--out", type=Path, required=True, help="JSON file to write")
    sc = sub.add_parser("score", help="play first-decision departures offline on labels (JSON with a manifest)")
    sc.add_argument("--task", required=True, help="decision task the labels come from")
    sc.add_argument("--labels", type=Path, nargs="+", required=True, help="folders of chunk files")
    sc.add_argument("--actor", type=Path, nargs="+", action="append", required=True,
                    help="value actor file(s) whose logits are averaged; repeat --actor for another row")
    sc.add_argument("--margin", type=float, nargs="+", default=[DEFAULT_MARGIN],
                    help=f"margins to score, one row each (default {DEFAULT_MARGIN})")
    sc.add_argument("--units", choices=("goal", "logit"), default="logit",
                    help="the margin compares logits, as ImprovedDecisionPolicy does, or predicted goals (the "
                         "sigmoid of the logits) (default logit)")
    sc.add_argument("--out", type=Path, required=True, help="JSON file to write")
    mg = sub.add_parser("merge", help="write value actors as one actor of their mean logits (an ensemble)")
    mg.add_argument("--actor", type=Path, nargs="+", required=True, help="two or more value actor files of one shape")
    mg.add_argument("--first-k", type=int, default=DEFAULT_FIRST_K,
                    help=f"recorded in the file, as for fit (default {DEFAULT_FIRST_K})")
    mg.add_argument("--margin", type=float, default=DEFAULT_MARGIN,
                    help=f"recorded in the file, as for fit (default {DEFAULT_MARGIN})")
    mg.add_argument("--out", type=Path, required=True, help="actor file to write (.pt)")
    args = p.parse_args(argv)
    if args.cmd == "merge":
        from ssl_marl.skills.checkpoint import git_commit

        from train.mappo.ensemble import write_merged

        if args.first_k < 1 or not np.isfinite(args.margin):
            p.error(f"--first-k must be >= 1 and --margin finite, got {args.first_k}, {args.margin}")
        try:
            write_merged(args.actor, args.out, improve={"first_k": args.first_k, "margin": args.margin},
                         commit=git_commit())
        except ValueError as e:
            p.error(str(e))
        print(json.dumps({"out": str(args.out), "members": [str(a) for a in args.actor]}))
        return 0
    if args.cmd == "score":
        from ssl_marl.decisions.learned import load_decision_actor
        from ssl_marl.runners.provenance import build_manifest

        if not all(np.isfinite(m) for m in args.margin):
            p.error(f"--margin must be finite, got {args.margin}")
        labels = _concat([load_labels(d) for d in args.labels])
        rows = []
        for files in args.actor:
            actors = [load_decision_actor(f)[0] for f in files]
            for m in args.margin:
                name = " + ".join(f.name for f in files) + f", margin {m:g} {args.units}"
                rows.append({"policy": name, "actors": [str(f) for f in files], "margin": m, "units": args.units,
                             **score_first_decision(labels, actors, m, args.units)})
        seeds = sorted({int(x) for x in labels["seed"]})
        out = {"task": args.task, "seeds": [seeds[0], seeds[-1]], "rows": rows,
               "manifest": build_manifest(rules={"probe": "rollout_pi_score", "task": args.task, "units": args.units},
                                          seeds={"seeds": [seeds[0], seeds[-1]]})}
        atomic_write_json(args.out, out)
        for r in rows:
            print(f"{r['policy']}: {r['goal_rate']:.3f} (benchmark {r['benchmark_goal_rate']:.3f}, oracle "
                  f"{r['oracle_goal_rate']:.3f}; {r['paired_diff']:+.3f} [{r['paired_diff_ci95'][0]:+.3f}, "
                  f"{r['paired_diff_ci95'][1]:+.3f}]; {r['deviations']} departures of {r['episodes']})")
        return 0
    if args.cmd == "summarize":
        from ssl_marl.runners.provenance import build_manifest

        out = summarize(args.task, args.labels)
        out["manifest"] = build_manifest(rules={"probe": "rollout_values", "task": args.task},
                                         seeds={"seeds": out["seeds"]})
        atomic_write_json(args.out, out)
        print(json.dumps({k: out[k] for k in ("task", "episodes", "decisions", "seeds")}))
        return 0
    if args.cmd == "collect":
        try:
            files = collect(args.task, args.out, args.episodes, args.seed, args.policy, args.max_decisions,
                            args.chunk, progress=not args.no_progress, realism=args.realism, field=args.field)
        except ValueError as e:
            p.error(str(e))
        print(json.dumps({"out": str(args.out), "chunks": [f.name for f in files]}))
        return 0
    if not 0 <= args.holdout < 1:
        p.error(f"--holdout must be in [0, 1), got {args.holdout}")
    if args.first_k < 1 or not np.isfinite(args.margin):
        p.error(f"--first-k must be >= 1 and --margin finite, got {args.first_k}, {args.margin}")
    labels = _concat([load_labels(d) for d in args.labels])
    agent, stats = fit_value_actor(args.task, labels, epochs=args.epochs, lr=args.lr, holdout=args.holdout,
                                   weight_decay=args.weight_decay, seed=args.seed)
    seeds = sorted({int(s) for s in labels["seed"]})
    save_bc_actor(agent, args.task, args.out, seed=args.seed,
                  improve={"first_k": args.first_k, "margin": args.margin},
                  rollout_pi={"labels": [str(d) for d in args.labels], "seeds": [seeds[0], seeds[-1]], **stats})
    print(json.dumps({"out": str(args.out), **stats}))
    return 0
