"""MAPPO (train/algos/mappo.py, train/mappo_loop.py): the pieces against hand-computed values,
masks, shapes, collection on the toy tasks, reproducibility, resume, and a short solve."""

from __future__ import annotations

import csv
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import torch

from train.mappo.algorithm import MAPPO, MAPPOConfig, ValueNorm, gae, smdp_discount
from train.mappo.loop import MAPPOTrainer, task_config
from train.mappo.toy_marl import ToySignal, ToyTempo


def test_smdp_discount_is_gamma_per_tau_seconds() -> None:
    assert smdp_discount(0.5, 0.9, 0.5) == pytest.approx(0.9)
    assert smdp_discount(2.0, 0.9, 1.0) == pytest.approx(0.81)
    assert smdp_discount(0.0, 0.9, 1.0) == pytest.approx(1.0)
    np.testing.assert_allclose(smdp_discount(np.array([1 / 60, 1.0]), 0.99, 1 / 60), [0.99, 0.99 ** 60])
    with pytest.raises(ValueError, match="tau_s"):
        smdp_discount(1.0, 0.9, 0.0)


def test_gae_matches_hand_computed_chain() -> None:
    # agent X: samples 0 -> 2 -> 3 (terminal); agent Y: sample 1, cut at the rollout end (bootstrap 5.0)
    rewards = np.array([1.0, 0.0, 2.0, 3.0])
    values = np.array([0.5, 1.0, 1.5, 2.0])
    next_values = np.array([1.5, 5.0, 2.0, 99.0])   # 99 must be ignored: terminal
    disc = np.array([0.9, 0.8, 0.5, 0.7])
    terminal = np.array([0.0, 0.0, 0.0, 1.0])
    nxt = np.array([2, -1, 3, -1])
    lam = 0.5
    d3 = 3.0 - 2.0
    d2 = 2.0 + 0.5 * 2.0 - 1.5
    d1 = 0.0 + 0.8 * 5.0 - 1.0
    d0 = 1.0 + 0.9 * 1.5 - 0.5
    a3 = d3
    a2 = d2 + 0.5 * lam * a3
    a1 = d1
    a0 = d0 + 0.9 * lam * a2
    adv, ret = gae(rewards, values, next_values, disc, terminal, nxt, lam)
    np.testing.assert_allclose(adv, [a0, a1, a2, a3], rtol=1e-6)
    np.testing.assert_allclose(ret, np.array([a0, a1, a2, a3]) + values, rtol=1e-6)


def test_value_norm_tracks_running_mean_and_std() -> None:
    rng = np.random.default_rng(0)
    vn = ValueNorm()
    chunks = [rng.normal(5.0, 3.0, size=n) for n in (7, 50, 200)]
    for c in chunks:
        vn.update(torch.as_tensor(c))
    allx = np.concatenate(chunks)
    assert float(vn.mean) == pytest.approx(allx.mean(), rel=1e-9)
    assert float(vn.var) == pytest.approx(allx.var(), rel=1e-9)
    x = torch.tensor([1.0, 5.0, 9.0])
    z = vn.normalize(x)
    np.testing.assert_allclose(z.numpy(), (x.numpy() - allx.mean()) / np.sqrt(allx.var() + vn.eps), atol=1e-6)
    np.testing.assert_allclose(vn.denormalize(z).numpy(), x.numpy(), rtol=1e-5)


def test_shared_actor_and_central_critic_shapes() -> None:
    ag = MAPPO(obs_dim=7, state_dim=11, n_agents=3, n_out=4, cfg=MAPPOConfig(hidden=(16,), agent_onehot=True))
    assert ag.actor.net[0].in_features == 7 + 3          # one actor for all agents, one-hot appended
    assert ag.critic.net[0].in_features == 11 + 3        # critic on the global state
    obs = np.zeros((5, 7), np.float32)
    act, logp = ag.act(obs, np.array([0, 1, 2, 0, 1]), np.ones((5, 4), np.int8))
    assert act.shape == (5,) and logp.shape == (5,)
    assert ag.value(np.zeros((5, 11), np.float32), np.arange(5) % 3).shape == (5,)
    no_hot = MAPPO(7, 11, 3, 4, MAPPOConfig(hidden=(16,)))
    assert no_hot.actor.net[0].in_features == 7
    cont = MAPPO(7, 11, 2, 5, MAPPOConfig(hidden=(16,), continuous=True))
    a, lp = cont.act(obs, np.zeros(5, int), None, torch.Generator().manual_seed(0))
    assert a.shape == (5, 5) and lp.shape == (5,)


def test_masked_options_are_never_chosen_and_get_zero_probability() -> None:
    ag = MAPPO(3, 3, 1, 4, MAPPOConfig(hidden=(8,)))
    mask = np.tile(np.array([0, 1, 0, 1], np.int8), (500, 1))
    act, logp = ag.act(np.random.default_rng(0).normal(size=(500, 3)).astype(np.float32), np.zeros(500, int), mask,
                       torch.Generator().manual_seed(1))
    assert set(act.tolist()) == {1, 3}
    assert np.all(np.isfinite(logp))
    d = ag.actor.dist(torch.zeros(1, 3), torch.as_tensor(mask[:1]))
    assert d.probs[0, 0] == 0 and d.probs[0, 2] == 0
    greedy, _ = ag.act(np.zeros((1, 3), np.float32), np.zeros(1, int), np.array([[0, 0, 1, 0]], np.int8), greedy=True)
    assert greedy[0] == 2
    batch = {"obs": np.zeros((4, 3), np.float32), "state": np.zeros((4, 3), np.float32), "agent": np.zeros(4, np.int64),
             "act": np.array([1, 3, 1, 3]), "logp": np.log(np.full(4, 0.5, np.float32)), "mask": mask[:4],
             "adv": np.array([1.0, -1.0, 0.5, 0.0], np.float32), "ret": np.ones(4, np.float32)}
    losses = ag.update(batch)
    assert all(np.isfinite(v) for v in losses.values())


def test_collection_accumulates_rewards_and_elapsed_between_an_agents_decisions() -> None:
    cfg = task_config("toy-tempo", num_envs=2, rollout_steps=12, algo={"gamma": 0.9, "tau_s": 1.0, "lam": 1.0})
    import tempfile

    with tempfile.TemporaryDirectory() as d:
        tr = MAPPOTrainer(cfg, 0, d, progress=False)
        batch, stats = tr.collect()
        tr.close()
    # a sample spans one job (reward at its end): with lam = 1 its target is R + d * (target of the next)
    assert set(batch["agent"].tolist()) == {0, 1}
    assert batch["obs"].shape[1] == 3 and batch["state"].shape[1] == 3
    assert stats["ticks"] > 0
    assert np.all(np.isfinite(batch["adv"])) and np.all(np.isfinite(batch["ret"]))


def test_decision_flags_select_the_training_samples() -> None:
    """toy-signal: each episode has exactly one decision per agent (agent 0 then agent 1)."""
    import tempfile

    cfg = task_config("toy-signal", num_envs=3, rollout_steps=10)
    with tempfile.TemporaryDirectory() as d:
        tr = MAPPOTrainer(cfg, 0, d, progress=False)
        batch, stats = tr.collect()
        tr.close()
    assert len(batch["agent"]) == 3 * 10                      # one decider per env step
    assert (batch["agent"] == 0).sum() == (batch["agent"] == 1).sum() == 15
    assert np.all(batch["mask"][:, -1] == 0)                  # the illegal "pass" option is masked
    assert stats["episodes_in_rollout"] == 15


def test_toy_envs_follow_the_decision_interface() -> None:
    env = ToySignal()
    obs, infos = env.reset(seed=3)
    assert infos["agent_0"]["decision"] and not infos["agent_1"]["decision"]
    assert infos["agent_0"]["elapsed_s"] == 0.0
    obs, rew, term, trunc, infos = env.step({"agent_0": 1, "agent_1": 0})
    assert infos["agent_1"]["decision"] and not infos["agent_0"]["decision"]
    obs, rew, term, trunc, infos = env.step({"agent_0": 0, "agent_1": env.signal})
    assert all(term.values()) and rew["agent_0"] == rew["agent_1"] == 1.0 and infos["agent_0"]["success"] == 1.0
    tempo = ToyTempo()
    obs, infos = tempo.reset(seed=0)
    assert infos["agent_0"]["decision"] and not infos["agent_1"]["decision"]
    busy = tempo.remaining[1]
    obs, rew, term, trunc, infos = tempo.step({"agent_0": 1, "agent_1": 0})    # agent_1's action is ignored
    assert infos["agent_1"]["decision"] and not infos["agent_0"]["decision"]
    assert infos["agent_0"]["elapsed_s"] == busy and tempo.job[1] == 0 and tempo.chosen == 1


def _rows(path: Path, drop: tuple[str, ...] = ("decisions_per_s", "agent_steps_per_s", "collect_share", "wall_time")):
    with path.open() as f:
        return [{k: v for k, v in r.items() if k not in drop} for r in csv.DictReader(f)]


def test_resume_after_interruption_continues_identically(tmp_path: Path) -> None:
    cfg = task_config("toy-signal", num_envs=4, rollout_steps=8, total_decisions=10_000, checkpoint_every=2,
                      val_every=2, val_episodes=4)
    full = MAPPOTrainer(cfg, 7, tmp_path / "full", progress=False)
    full.run(stop_after_rollouts=6)
    full.checkpoint()
    full.close()
    part = MAPPOTrainer(cfg, 7, tmp_path / "part", progress=False)
    part.run(stop_after_rollouts=5)        # "killed" after rollout 5: the last checkpoint is rollout 4
    part.close()
    resumed = MAPPOTrainer(cfg, 7, tmp_path / "part", progress=False, resume=True)
    assert resumed.counters["rollout"] == 4
    resumed.run(stop_after_rollouts=2)
    resumed.checkpoint()
    resumed.close()
    a = torch.load(tmp_path / "full" / "checkpoint.pt", weights_only=True)
    b = torch.load(tmp_path / "part" / "checkpoint.pt", weights_only=True)
    for k, v in a["agent"]["actor"].items():
        torch.testing.assert_close(v, b["agent"]["actor"][k], rtol=0, atol=0)
    for k, v in a["agent"]["critic"].items():
        torch.testing.assert_close(v, b["agent"]["critic"][k], rtol=0, atol=0)
    assert a["counters"] == b["counters"]
    assert _rows(tmp_path / "full" / "progress.csv") == _rows(tmp_path / "part" / "progress.csv")
    assert _rows(tmp_path / "full" / "val.csv") == _rows(tmp_path / "part" / "val.csv")


def test_worker_processes_give_the_same_experience_as_the_sequential_vector(tmp_path: Path) -> None:
    batches = []
    for w in (1, 2):
        cfg = task_config("toy-tempo", num_envs=4, rollout_steps=6, workers=w)
        tr = MAPPOTrainer(cfg, 3, tmp_path / f"w{w}", progress=False)
        batches.append(tr.collect()[0])
        tr.close()
    for k in batches[0]:
        np.testing.assert_array_equal(batches[0][k], batches[1][k], err_msg=k)


def test_mappo_solves_the_toy_signalling_game(tmp_path: Path) -> None:
    """Random play scores 1/3; the shared-code optimum 1. Solved in about 5 s of CPU."""
    tr = MAPPOTrainer(task_config("toy-signal", val_every=0), 0, tmp_path, progress=False)
    tr.run()
    val = tr.validate()
    tr.close()
    assert val["val_score"] >= 0.95
    assert (tmp_path / "actors").is_dir() and (tmp_path / "checkpoint.pt").is_file()


def test_mappo_discounts_by_elapsed_time_on_toy_tempo(tmp_path: Path) -> None:
    """Quick jobs are worth more only under time-based (SMDP) discounting; the learner picks them."""
    tr = MAPPOTrainer(task_config("toy-tempo", val_every=0), 0, tmp_path, progress=False)
    tr.run()
    val = tr.validate()
    tr.close()
    assert val["val_score"] >= 0.9


def test_unknown_task_and_bad_override_are_clear_errors() -> None:
    with pytest.raises(ValueError, match="unknown MAPPO task 'nope'"):
        task_config("nope")
    with pytest.raises(ValueError, match="unknown MAPPO run-config key 'num_env'"):
        task_config("toy-signal", num_env=3)


# --- ssl_marl.decisions.learned and the export ---------------------------------------------------------

def test_exported_actor_plays_greedy_over_legal_options_and_checks_the_env(tmp_path: Path) -> None:
    from ssl_marl.decisions.learned import DecisionActor, LearnedDecisionPolicy, load_decision_actor
    from train.mappo.export import export

    cfg = task_config("toy-signal", num_envs=2, rollout_steps=4, total_decisions=16, val_episodes=3)
    tr = MAPPOTrainer(cfg, 0, tmp_path / "run", progress=False)
    tr.run()
    obs = np.random.default_rng(0).random((6, 5)).astype(np.float32)
    with torch.no_grad():
        want = tr.agent.actor(tr.agent.actor_input(tr._obs(obs), np.zeros(6, int))).numpy()
    tr.close()
    res = export([tmp_path / "run"], tmp_path / "toy.pt")
    assert res["val_seed"] == cfg.val_seed
    actor, meta = load_decision_actor(tmp_path / "toy.pt")
    assert meta["task"] == "toy-signal" and meta["selection"]["candidates"]
    np.testing.assert_allclose(actor(torch.as_tensor(obs)).detach().numpy(), want, rtol=1e-5, atol=1e-6)

    env = ToySignal()
    pol = LearnedDecisionPolicy(tmp_path / "toy.pt", task="toy-signal")
    o, infos = env.reset(seed=0)
    pol.reset(env)
    a = pol.act(env, "agent_0", o["agent_0"], infos["agent_0"])
    assert a != 3                                                   # option 3 is masked
    logits = actor.logits(o["agent_0"])
    only = np.array([0, 0, 1, 0], np.int8)
    assert pol.act(env, "agent_0", o["agent_0"], {"action_mask": only}) == 2
    assert a == int(np.argmax(np.where(infos["agent_0"]["action_mask"] > 0, logits, -np.inf)))
    with pytest.raises(ValueError, match="observations of size 5, the env gives 6"):
        pol.reset(ToySignal(n_signals=4))
    with pytest.raises(ValueError, match="task 'toy-signal', not 'keepaway'"):
        LearnedDecisionPolicy(tmp_path / "toy.pt", task="keepaway")
    bad = LearnedDecisionPolicy(DecisionActor(5, 3, (4,)))
    with pytest.raises(ValueError, match="3 options, the env has 4"):
        bad.reset(env)


def test_pretrained_path_names_the_training_command_when_missing() -> None:
    from ssl_marl.decisions.learned import pretrained_path

    with pytest.raises(FileNotFoundError, match="python -m train mappo --task no-such-task"):
        pretrained_path("no-such-task")


def test_decision_actor_file_is_refused_when_not_one(tmp_path: Path) -> None:
    from ssl_marl.decisions.learned import load_decision_actor

    torch.save({"format": "something else"}, tmp_path / "x.pt")
    with pytest.raises(ValueError, match="not a valid ssl_marl decision actor"):
        load_decision_actor(tmp_path / "x.pt")


def test_warm_start_loads_the_actor_and_warmup_trains_only_the_critic(tmp_path: Path) -> None:
    """``init_actor`` starts the shared actor from an actor file (checked against the run);
    during ``actor_warmup_rollouts`` the actor is held fixed while the critic learns."""
    cfg = task_config("toy-signal", num_envs=2, rollout_steps=4, total_decisions=16, val_episodes=2)
    src = MAPPOTrainer(cfg, 1, tmp_path / "src", progress=False)
    src.run()
    src.save_actor(tmp_path / "init.pt")
    want = {k: v.clone() for k, v in src.agent.actor.state_dict().items()}
    src.close()
    warm = replace(cfg, init_actor=str(tmp_path / "init.pt"), actor_warmup_rollouts=2, total_decisions=10_000)
    tr = MAPPOTrainer(warm, 5, tmp_path / "warm", progress=False)
    critic0 = {k: v.clone() for k, v in tr.agent.critic.state_dict().items()}
    for k, v in tr.agent.actor.state_dict().items():
        torch.testing.assert_close(v, want[k])
    tr.run(stop_after_rollouts=2)
    for k, v in tr.agent.actor.state_dict().items():      # warm-up: actor untouched ...
        torch.testing.assert_close(v, want[k])
    assert any(not torch.equal(v, critic0[k]) for k, v in tr.agent.critic.state_dict().items())  # ... critic learns
    tr.run(stop_after_rollouts=1)
    assert any(not torch.equal(v, want[k]) for k, v in tr.agent.actor.state_dict().items())
    tr.close()
    bad = replace(cfg, init_actor=str(tmp_path / "init.pt"), algo=replace(cfg.algo, hidden=(32,)))
    with pytest.raises(ValueError, match="hidden is \\[64, 64\\], this run needs \\[32\\]"):
        MAPPOTrainer(bad, 0, tmp_path / "bad", progress=False)


def test_behaviour_cloning_imitates_a_benchmark_policy(tmp_path: Path) -> None:
    """train.mappo.bc: demonstrations of keepaway's always-hold keepers are fitted exactly, and
    the written actor plays them back greedily."""
    from ssl_marl.decisions.keepaway.env import KeepawayEnv
    from ssl_marl.decisions.keepaway.params import HOLD
    from ssl_marl.decisions.learned import LearnedDecisionPolicy
    from train.mappo.bc import collect_demonstrations, fit_actor, save_bc_actor

    demos = collect_demonstrations("keepaway", "always-hold", 3, 100000, progress=False)
    assert len(demos["option"]) >= 3 and set(demos["option"].tolist()) == {HOLD}
    assert demos["obs"].shape == (len(demos["option"]), 39) and demos["mask"].shape == (len(demos["option"]), 3)
    agent, stats = fit_actor("keepaway", demos, epochs=30, holdout=0.0)
    assert stats["train_accuracy"] == 1.0 and stats["decisions"] == len(demos["option"])
    save_bc_actor(agent, "keepaway", tmp_path / "bc.pt", bc=stats)
    env = KeepawayEnv()
    pol = LearnedDecisionPolicy(tmp_path / "bc.pt", task="keepaway")
    obs, infos = env.reset(seed=7)
    pol.reset(env)
    assert pol.act(env, "keeper_0", obs["keeper_0"], infos["keeper_0"]) == HOLD
    with pytest.raises(ValueError, match="episodes must be >= 1"):
        collect_demonstrations("keepaway", "always-hold", 0, 0, progress=False)


def test_rollout_policy_improvement_labels_fit_and_resume(tmp_path: Path) -> None:
    """train.mappo.rollout_pi: every legal option of the drill's first decision is played out
    (the benchmark's own option carries the benchmark episode's return, illegal ones NaN); a
    rerun resumes without replaying; the fitted actor's greedy pick is the best-valued option."""
    import numpy as np

    from ssl_marl.decisions import make_decision_policy
    from ssl_marl.decisions.attack_drill import AttackDrillEnv
    from ssl_marl.decisions.policies import run_episode
    from train.mappo.rollout_pi import collect, fit_value_actor, load_labels, summarize

    files = collect("attack-drill", tmp_path, 1, 46004, max_decisions=1, chunk=1, progress=False)
    lab = load_labels(tmp_path)
    assert lab["obs"].shape == (1, 48) and lab["decision"].tolist() == [0]
    legal = lab["mask"][0].astype(bool)
    assert np.all(np.isnan(lab["value"][0][~legal])) and not np.any(np.isnan(lab["value"][0][legal]))
    base = run_episode(AttackDrillEnv(), make_decision_policy("handcoded", "attack-drill"), seed=46004)
    assert lab["value"][0][lab["base_option"][0]] == base["return"]
    stamp = files[0].stat().st_mtime_ns
    collect("attack-drill", tmp_path, 1, 46004, max_decisions=1, chunk=1, progress=False)
    assert files[0].stat().st_mtime_ns == stamp
    summary = summarize("attack-drill", [tmp_path])
    assert summary["episodes"] == 1 and summary["by_decision"][0]["benchmark"] == base["return"]
    assert summary["chunks"][0]["seeds"] == [46004, 46004] and summary["chunks"][0]["policy"] == "handcoded"
    assert (summary["chunks"][0]["realism"], summary["chunks"][0]["field"]) == ("none", "div_b")
    with pytest.raises(ValueError, match="collected with .*'realism': 'none'.* asks for .*'realistic'"):
        collect("attack-drill", tmp_path, 1, 46005, max_decisions=1, chunk=1, progress=False, realism="realistic")
    with pytest.raises(ValueError, match="realism must be"):
        collect("attack-drill", tmp_path / "other", 1, 46005, progress=False, realism="noisy")
    lab["value"][0][legal] = 0.0
    best = int(np.flatnonzero(legal)[-1])
    lab["value"][0][best] = 1.0
    agent, stats = fit_value_actor("attack-drill", lab, epochs=200, holdout=0.0)
    assert stats["train"]["picked_value"] == 1.0 and stats["picked_options"][best] == 1
    lab["value"][0][best] = 2.0
    with pytest.raises(ValueError, match=r"\[0, 1\]"):
        fit_value_actor("attack-drill", lab, epochs=1, holdout=0.0)


def test_rollout_labels_under_the_realistic_preset_replay_the_same_decision(tmp_path: Path) -> None:
    """collect --realism realistic: the noisy world and the tracker are seeded by the episode, so
    every branch replays the benchmark's episode up to its first decision (collect raises if not);
    the chunk records the preset."""
    import numpy as np

    from train.mappo.rollout_pi import collect, load_labels, summarize

    collect("attack-drill", tmp_path, 1, 46004, max_decisions=1, chunk=1, progress=False, realism="realistic")
    lab = load_labels(tmp_path)
    assert lab["obs"].shape == (1, 48) and np.isfinite(lab["value"][0][lab["mask"][0].astype(bool)]).all()
    assert summarize("attack-drill", [tmp_path])["chunks"][0]["realism"] == "realistic"


def test_offline_score_plays_the_improved_policys_first_decision_from_the_labels() -> None:
    """train.mappo.rollout_pi.score_first_decision: the pick of ImprovedDecisionPolicy's rule
    (margin in predicted goals or in logits; an ensemble averages) reads its return from the
    labels; the benchmark's and the best option's returns come beside it."""
    import numpy as np
    import torch

    from ssl_marl.decisions.learned import DecisionActor
    from train.mappo.rollout_pi import score_first_decision

    def actor(logits):
        a = DecisionActor(4, 3, [])
        with torch.no_grad():
            a.net[0].weight.zero_()
            a.net[0].bias.copy_(torch.tensor(logits, dtype=torch.float32))
        return a

    nan = np.nan
    lab = {"obs": np.zeros((3, 4), np.float32), "mask": np.array([[1, 1, 1], [1, 1, 0], [1, 1, 1]], np.int8),
           "agent": np.zeros(3, np.int64), "seed": np.array([1, 2, 2]), "decision": np.array([0, 0, 1]),
           "base_option": np.array([0, 0, 0]), "value": np.array([[0, 0, 1], [1, 0, nan], [0, 0, 1]], np.float32)}
    prefers_1 = actor([0.0, 0.3, 2.0])  # option 2 is best but illegal in row 1
    r = score_first_decision(lab, [prefers_1], margin=0.05, units="goal")
    assert r["episodes"] == 2 and r["deviations"] == 2
    assert r["goal_rate"] == 0.5 and r["benchmark_goal_rate"] == 0.5 and r["oracle_goal_rate"] == 1.0
    assert r["paired_diff"] == 0.0  # row 0: option 2 (1) instead of 0; row 1: option 1 (0) instead of 1
    keeps = score_first_decision(lab, [actor([0.0, 0.3, 0.2])], margin=0.1, units="goal")
    assert keeps["deviations"] == 0 and keeps["goal_rate"] == 0.5  # sigmoid gap 0.074 < 0.1
    moves = score_first_decision(lab, [actor([0.0, 0.3, 0.2])], margin=0.1, units="logit")
    assert moves["deviations"] == 2 and moves["goal_rate"] == 0.0  # option 1 in both rows
    both = score_first_decision(lab, [actor([0.0, 4.0, -4.0]), actor([0.0, -4.0, 4.0])], margin=0.05)
    assert both["deviations"] == 0  # the members' means are level with the benchmark's option
    with pytest.raises(ValueError, match="units"):
        score_first_decision(lab, [prefers_1], margin=0.1, units="odds")


def test_merged_value_actors_output_the_members_mean_logits(tmp_path: Path) -> None:
    """train.mappo.ensemble: the merged file is a plain decision actor whose logits are the
    members' mean; members of another shape are refused, naming the difference."""
    import numpy as np
    import torch

    from ssl_marl.decisions.learned import DecisionActor, load_decision_actor
    from ssl_marl.skills.checkpoint import save_actor_file
    from train.mappo.rollout_pi import main as rpi_main

    def member(seed, hidden=(5, 3)):
        torch.manual_seed(seed)
        a = DecisionActor(4, 3, list(hidden), n_agents=2)
        a.obs_mean.fill_(0.5)
        a.obs_std.fill_(2.0)
        path = tmp_path / f"m{seed}_{len(hidden)}.pt"
        meta = {"task": "toy", "obs_dim": 4, "n_options": 3, "hidden": list(hidden), "agent_ids": ["a", "b"],
                "option_names": None, "continuous": False}
        save_actor_file(path, "decision", {**{f"net.{k}": v for k, v in a.net.state_dict().items()},
                                           "obs_mean": a.obs_mean, "obs_std": a.obs_std}, meta)
        return path, a

    (p1, a1), (p2, a2), (p3, a3) = member(1), member(2), member(3)
    out = tmp_path / "ens.pt"
    assert rpi_main(["merge", "--actor", str(p1), str(p2), str(p3), "--margin", "0.05", "--out", str(out)]) == 0
    merged, meta = load_decision_actor(out)
    assert meta["hidden"] == [15, 9] and meta["improve"] == {"first_k": 1, "margin": 0.05}
    assert [m["file"] for m in meta["ensemble"]["members"]] == [p1.name, p2.name, p3.name]
    rng = np.random.default_rng(0)
    for _ in range(5):
        obs, who = rng.normal(size=4).astype(np.float32), int(rng.integers(2))
        mean = np.mean([a.logits(obs, who) for a in (a1, a2, a3)], axis=0)
        np.testing.assert_allclose(merged.logits(obs, who), mean, rtol=1e-5, atol=1e-6)
    other, _ = member(4, hidden=(5,))
    with pytest.raises(SystemExit):
        rpi_main(["merge", "--actor", str(p1), str(other), "--out", str(tmp_path / "bad.pt")])
