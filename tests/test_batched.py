"""Batched worlds: each world of the batched physics / env / vector env
behaves exactly as the single env under the same seed and actions."""

from __future__ import annotations

import numpy as np
import pytest

from ssl_marl.envs import SSLParallelEnv
from ssl_marl.envs.actions import scale_actions
from ssl_marl.envs.batched_env import BatchedSSLEnv
from ssl_marl.physics.batched import BatchedPhysics
from ssl_marl.physics.field import FieldGeometry
from ssl_marl.physics.params import BallParams, RobotParams
from ssl_marl.physics.world import PhysicsWorld


def _chase_actions(rng: np.random.Generator, pos, heading, ball_pos, kick_p: float = 0.05,
                   chip: bool = False) -> np.ndarray:
    """(K, n, 5) actions: drive at the ball with the dribbler on, random jitter and kicks
    (so that robots collide, dribble and kick); with ``chip`` (K, n, 6), the chip entry
    random in [-0.5, 1] (a third of the kicks flat)."""
    K, n = heading.shape
    d = ball_pos[:, None, :] - pos
    ang = np.angle(np.exp(1j * (np.arctan2(d[..., 1], d[..., 0]) - heading)))
    a = rng.uniform(-1, 1, (K, n, 5)) * 0.3
    a[..., 0] += np.cos(ang) * 0.7
    a[..., 1] += np.sin(ang) * 0.7
    a[..., 2] += np.clip(ang, -1, 1)
    a[..., 3] = 1.0
    a[..., 4] = np.where(rng.random((K, n)) < kick_p, rng.uniform(0.2, 1.0, (K, n)), -1.0)
    if chip:
        a = np.concatenate([a, rng.uniform(-0.5, 1.0, (K, n, 1))], axis=2)
    return a


@pytest.mark.parametrize("fast_io", [True, False], ids=["memory-views", "swig-fallback"])
def test_batched_physics_bit_equal_to_single_worlds(fast_io, monkeypatch):
    from ssl_marl.physics import body_memory

    assert body_memory.layout_ok()  # the fast path is what runs here; the fallback is forced below
    if not fast_io:
        monkeypatch.setattr("ssl_marl.physics.batched.bm.layout_ok", lambda: False)
    f, rp, bp = FieldGeometry.div_b(), RobotParams(), BallParams()
    K, nb, ny = 3, 2, 2
    n = nb + ny
    singles = [PhysicsWorld(f, rp, bp, nb, ny) for _ in range(K)]
    batch = BatchedPhysics(f, rp, bp, nb, ny, K)
    assert batch._fast == fast_io
    rng = np.random.default_rng(3)
    for k in range(K):
        pose = rng.uniform(-0.6, 0.6, (n, 3))
        pose[0] = (0.0, 0.0, rng.uniform(-3, 3))
        ball = 0.1015 * np.array([np.cos(pose[0, 2]), np.sin(pose[0, 2])])  # on robot 0's dribbler
        singles[k].reset(pose, ball)
        batch.reset_world(k, pose, ball)
    kicks = touches = 0
    for step in range(300):
        a = _chase_actions(rng, batch.pos, batch.heading, batch.ball_pos)
        worlds = np.array([0, 2]) if step % 7 == 3 else np.arange(K)  # sometimes step a subset only
        for k in worlds:
            singles[k].step(*scale_actions(a[k], rp))
            kicks += len(singles[k].kicks_this_step)
            touches += int(singles[k].on_dribbler.sum())
        v, w, d, kk = scale_actions(a[worlds].reshape(-1, 5), rp)
        m = len(worlds)
        batch.step(v.reshape(m, n, 2), w.reshape(m, n), d.reshape(m, n), kk.reshape(m, n),
                   worlds=None if m == K else worlds)
        for k in range(K):
            s = singles[k]
            for name in ("pos", "heading", "vel", "omega", "ball_pos", "ball_vel", "on_dribbler", "kick_cooldown"):
                np.testing.assert_array_equal(getattr(s, name), getattr(batch, name)[k], err_msg=f"{name} step {step}")
            assert s.t == batch.t[k]
    assert kicks >= 5 and touches >= 50  # the run exercised kicks and the dribbler


def _run_pair(config: dict, K: int, steps: int, seed: int, options=None, kick_p=0.05):
    """Step a batched env and K single envs side by side; assert equal results; return counters."""
    batched = BatchedSSLEnv(K, **config)
    singles = [SSLParallelEnv(**config) for _ in range(K)]
    opts = options if isinstance(options, list) else [options] * K
    obs_b, _ = batched.reset(seed=seed, options=options)
    for k, env in enumerate(singles):
        obs, _ = env.reset(seed=seed + k, options=opts[k])
        np.testing.assert_array_equal(np.stack([obs[a] for a in env.possible_agents]), obs_b[k])
    rng = np.random.default_rng(seed)
    chip = bool(config.get("chip_kicks", False))
    stats = {"kicks": 0, "goals": 0, "outs": 0, "ends": 0, "autoresets": 0, "airborne": 0}
    for step in range(steps):
        ph = batched.physics
        a = _chase_actions(rng, ph.pos, ph.heading, ph.ball_pos, kick_p, chip).astype(np.float32)
        obs_b, rew_b, term_b, trunc_b, info = batched.step(a)
        for k, env in enumerate(singles):
            if info["autoreset"][k]:
                obs, _ = env.reset()
                stats["autoresets"] += 1
                rew = {ag: 0.0 for ag in env.possible_agents}
                term = trunc = {ag: False for ag in env.possible_agents}
            else:
                obs, rew, term, trunc, infos = env.step(dict(zip(env.possible_agents, a[k])))
                ev = infos[env.possible_agents[0]]["events"]
                stats["kicks"] += sum(e["type"] == "kick" for e in ev)
                stats["goals"] += sum(e["type"] == "goal" for e in ev)
                stats["outs"] += sum(e["type"] == "ball_out" for e in ev)
                assert info["goal"][k] == sum((1 if e["team"] == "blue" else -1) for e in ev if e["type"] == "goal")
            msg = f"world {k} step {step}"
            np.testing.assert_array_equal(np.stack([obs[ag] for ag in env.possible_agents]), obs_b[k], err_msg=msg)
            np.testing.assert_array_equal([rew[ag] for ag in env.possible_agents], rew_b[k], err_msg=msg)
            assert term[env.possible_agents[0]] == term_b[k], msg
            assert trunc[env.possible_agents[0]] == trunc_b[k], msg
            ws = env.world_state()
            np.testing.assert_array_equal(ws.blue.pos, batched.physics.pos[k, :env.config.n_blue], err_msg=msg)
            np.testing.assert_array_equal(ws.ball_pos, batched.physics.ball_pos[k], err_msg=msg)
            wb = batched.world_state(k)
            assert (ws.ball_height, ws.ball_vz, ws.ball_max_height) == \
                (wb.ball_height, wb.ball_vz, wb.ball_max_height), msg
            stats["airborne"] += int(ws.ball_height > 0.0)
            stats["ends"] += int(term_b[k] or trunc_b[k])
    return stats


def test_batched_env_matches_single_env_with_kicks_goals_and_autoreset():
    config = dict(n_blue=3, n_yellow=3, field="div_b", max_time_s=1.5, randomize_reset=True,
                  reward_scales={"goal": 1.0, "ball_progress": 1.0, "possession": 0.5})
    # world 1 starts with blue_0 behind the ball in front of the yellow goal: it scores
    shot = {"robots": {"blue_0": (3.9, 0.0, 0.0)}, "ball": {"pos": (4.0015, 0.0)}}
    # world 2: blue_0 on the touch line facing out, ball on its dribbler: ball out, placement
    out = {"robots": {"blue_0": (0.0, 2.7, np.pi / 2)}, "ball": {"pos": (0.0, 2.8015)}}
    stats = _run_pair(config, 3, 250, seed=11, options=[None, shot, out], kick_p=0.15)
    assert stats["kicks"] >= 3 and stats["ends"] >= 3 and stats["autoresets"] >= 3
    assert stats["goals"] >= 1 and stats["outs"] >= 1


def test_batched_env_matches_single_env_terminate_after_goal_and_realism():
    config = dict(n_blue=2, n_yellow=1, field="div_b", max_time_s=1.0, randomize_reset=True, after_goal="terminate",
                  realism="realistic")
    shot = {"robots": {"blue_0": (3.9, 0.0, 0.0)}, "ball": {"pos": (4.0015, 0.0)}}
    _run_pair(config, 2, 150, seed=5, options=[shot, None], kick_p=0.3)


def test_batched_env_matches_single_env_with_chip_kicks():
    """The v1 layout (chip kicks): world k bit-equal to a single env through chips,
    flights, bounces, the goal rule (a chip into the goal is ball out) and autoresets."""
    config = dict(n_blue=3, n_yellow=3, field="div_b", max_time_s=1.5, randomize_reset=True, chip_kicks=True,
                  reward_scales={"goal": 1.0, "ball_progress": 1.0, "possession": 0.5})
    shot = {"robots": {"blue_0": (3.9, 0.0, 0.0)}, "ball": {"pos": (4.0015, 0.0)}}
    chip_shot = {"robots": {"blue_0": (3.0, 0.0, 0.0)}, "ball": {"pos": (3.1015, 0.0)}}
    stats = _run_pair(config, 3, 250, seed=11, options=[None, shot, chip_shot], kick_p=0.15)
    assert stats["kicks"] >= 3 and stats["airborne"] >= 20 and stats["autoresets"] >= 3
    assert stats["goals"] + stats["outs"] >= 1


def test_batched_env_chip_kicks_with_realism_matches_single_env():
    config = dict(n_blue=2, n_yellow=1, field="div_b", max_time_s=1.0, randomize_reset=True, chip_kicks=True,
                  realism="realistic")
    _run_pair(config, 2, 120, seed=5, kick_p=0.3)


def test_batched_env_11v11_div_a_matches_single_env():
    _run_pair(dict(n_blue=11, n_yellow=11, field="div_a", max_time_s=2.0, randomize_reset=True), 2, 60, seed=2)


def test_batched_env_rejects_bad_actions_naming_world_and_agent():
    env = BatchedSSLEnv(2, n_blue=1, n_yellow=1)
    with pytest.raises(RuntimeError, match="before reset"):
        env.step(np.zeros((2, 2, 5)))
    env.reset(seed=0)
    with pytest.raises(ValueError, match=r"shape \(worlds, agents, 5\)"):
        env.step(np.zeros((2, 5)))
    with pytest.raises(ValueError, match=r"shape"):
        env.step(np.zeros((3, 2, 5)))
    a = np.zeros((2, 2, 5))
    a[1, 1, 2] = np.nan
    with pytest.raises(ValueError, match=r"world 1: action for agent 'yellow_0' contains NaN"):
        env.step(a)
    a[1, 1, 2] = np.inf
    with pytest.raises(ValueError, match="yellow_0"):
        env.step(a)
    with pytest.raises(ValueError, match="n_worlds"):
        BatchedSSLEnv(0)
    with pytest.raises(ValueError, match="realtime"):
        BatchedSSLEnv(2, realtime=True)
    with pytest.raises(ValueError, match="unknown env option"):
        BatchedSSLEnv(2, bogus=1)


@pytest.mark.filterwarnings("ignore:.*reset options. ignoring unknown key.*:UserWarning")  # api_test's junk option
def test_world_view_passes_pettingzoo_parallel_api_test():
    from pettingzoo.test import parallel_api_test

    env = BatchedSSLEnv(3, n_blue=2, n_yellow=2, max_time_s=2.0)
    env.reset(seed=0)
    view = env.world_view(1)
    parallel_api_test(view, num_cycles=200)
    before = env.physics.pos[0].copy()
    view.reset(seed=1)
    view.step({a: np.ones(5, np.float32) for a in view.agents})
    np.testing.assert_array_equal(env.physics.pos[0], before)  # other worlds untouched
    with pytest.raises(ValueError, match="blue_0"):
        view.step({"blue_0": np.full(5, np.nan)})


# ------------------------------------------------------------------ skill vector env
def _skill_pair(task: str, K: int, steps: int, seed: int, kwargs: dict, policy):
    """SkillVectorEnv vs Gymnasium's SyncVectorEnv of the single task env (next-step
    autoreset both): equal observations and terminations, rewards to the last bit of exp/atan2."""
    import gymnasium

    from ssl_marl.skills.vector import TASKS, SkillVectorEnv

    ours = SkillVectorEnv(task, K, **kwargs)
    ref = gymnasium.vector.SyncVectorEnv([lambda: TASKS[task](**kwargs)] * K,
                                         autoreset_mode=gymnasium.vector.AutoresetMode.NEXT_STEP)
    o1, _ = ours.reset(seed=seed)
    o2, _ = ref.reset(seed=seed)
    np.testing.assert_array_equal(o1, o2)
    rng = np.random.default_rng(seed)
    ends = successes = 0
    for step in range(steps):
        a = policy(rng, o1).astype(np.float32)
        o1, r1, te1, tr1, i1 = ours.step(a)
        o2, r2, te2, tr2, i2 = ref.step(a)
        msg = f"step {step}"
        np.testing.assert_allclose(o1, o2, rtol=0, atol=2e-6, err_msg=msg)  # float32 of atan2-based values
        np.testing.assert_allclose(r1, r2, rtol=1e-12, atol=1e-12, err_msg=msg)
        np.testing.assert_array_equal(te1, te2, err_msg=msg)
        np.testing.assert_array_equal(tr1, tr2, err_msg=msg)
        if "is_success" in i2:
            np.testing.assert_array_equal(i1["_is_success"], i2["_is_success"], err_msg=msg)
            np.testing.assert_array_equal(i1["is_success"][i1["_is_success"]], i2["is_success"][i2["_is_success"]])
            np.testing.assert_array_equal(i1["failure_reason"][i1["_is_success"]],
                                          i2["failure_reason"][i2["_failure_reason"]])
            successes += int(i1["is_success"][i1["_is_success"]].sum())
        ends += int((te1 | tr1).sum())
        assert ours.observation_space.contains(o1)
    return ends, successes


def _go_to_ball_policy(rng, obs):
    """Turn to the ball and drive at it (robot-frame ball position = obs[:, 0:2]) with noise."""
    ang = np.arctan2(obs[:, 1], obs[:, 0])
    a = np.stack([np.cos(ang) * 0.8, np.sin(ang) * 0.8, np.clip(ang, -1, 1)], axis=1)
    return np.clip(a + rng.normal(0, 0.3, a.shape), -1, 1)


def test_skill_vector_env_go_to_ball_matches_sync_vector_env():
    ends, successes = _skill_pair("go-to-ball", 4, 400, 3, {"max_time_s": 2.0}, _go_to_ball_policy)
    assert ends >= 4 and successes >= 1
    _skill_pair("go-to-ball", 2, 150, 4, {"max_time_s": 1.0, "n_opponents": 2}, _go_to_ball_policy)  # static opponents


def test_skill_vector_env_aim_to_shoot_matches_sync_vector_env():
    def policy(rng, obs):
        a = rng.uniform(-1, 1, (obs.shape[0], 3))
        a[:, 1] = 1.0  # dribble
        a[:, 2] = np.where(rng.random(obs.shape[0]) < 0.1, 1.0, -1.0)
        return a

    for kw in ({}, {"kick_action": "full", "reward_form": "kick_only", "success_bonus": 2.0}):
        ends, _ = _skill_pair("aim-to-shoot", 4, 200, 7, kw, policy)
        assert ends >= 8


def test_skill_vector_env_realism_matches_sync_vector_env():
    _skill_pair("go-to-ball", 2, 200, 1, {"max_time_s": 1.5, "realism": "realistic"}, _go_to_ball_policy)


@pytest.mark.parametrize("task", ["go-to-ball", "aim-to-shoot"])
def test_skill_vector_env_passes_gymnasium_checks(task):
    """Gymnasium 1.4 has no checker for vector envs; these are the env checker's checks
    that apply to one (spaces, return types, seeded reset determinism), plus its step-
    determinism and returned-data checks redone with array-valued terminations."""
    from gymnasium.utils import env_checker as ec

    from ssl_marl.skills.vector import SkillVectorEnv

    env = SkillVectorEnv(task, 3)
    for check in (ec.check_reset_return_type, ec.check_reset_options, ec.check_reset_seed_determinism,
                  ec.check_reset_return_info_deprecation):
        check(env)
    acts = np.random.default_rng(0).uniform(-1, 1, (20,) + env.action_space.shape)
    runs = []
    for _ in range(2):
        out = [env.reset(seed=123)[0]]
        out += [np.concatenate([o.ravel(), r, te, tr]) for o, r, te, tr, _ in (env.step(a) for a in acts)]
        runs.append(out)
    for x, y in zip(*runs):
        assert ec.data_equivalence(x, y, exact=True)
    o1, _ = env.reset(seed=1)
    # seeded actions: with unseeded ones an aim-to-shoot kick could end every world in the first
    # step, and a step in which every world autoresets has no live world and so no reward terms
    env.action_space.seed(1)
    o2, _, _, _, i2 = env.step(env.action_space.sample())
    o3, _, _, _, i3 = env.step(env.action_space.sample())
    assert not np.shares_memory(o1, o2) and not np.shares_memory(o2, o3)
    assert i2["reward_terms"] is not i3["reward_terms"]


def test_skill_vector_env_api_and_bad_inputs():
    import gymnasium

    from ssl_marl.skills.vector import SkillVectorEnv

    env = SkillVectorEnv("ssl_marl/GoToBall-v0", 3)
    assert isinstance(env, gymnasium.vector.VectorEnv)
    assert env.observation_space.shape == (3, 14) and env.action_space.shape == (3, 3)
    assert env.metadata["autoreset_mode"] == gymnasium.vector.AutoresetMode.NEXT_STEP
    o, info = env.reset(seed=0)
    o_again, _ = SkillVectorEnv("go-to-ball", 3).reset(seed=0)
    np.testing.assert_array_equal(o, o_again)  # seeded resets are reproducible
    assert o.dtype == np.float32 and env.observation_space.contains(o)
    obs, rew, term, trunc, info = env.step(env.action_space.sample())
    assert obs.shape == (3, 14) and rew.shape == (3,) and term.dtype == bool and trunc.dtype == bool
    assert set(info["reward_terms"]) >= {"contact", "distance", "orientation", "_contact"}
    with pytest.raises(ValueError, match=r"shape \(3, 3\)"):
        env.step(np.zeros((3, 5)))
    bad = np.zeros((3, 3))
    bad[2, 1] = np.nan
    with pytest.raises(ValueError, match="sub-env 2: action contains NaN"):
        env.step(bad)
    with pytest.raises(ValueError, match="num_envs"):
        SkillVectorEnv("go-to-ball", 0)
    with pytest.raises(ValueError, match="task must be"):
        SkillVectorEnv("dance", 2)
    with pytest.raises(ValueError, match="opponent_policy"):
        SkillVectorEnv("go-to-ball", 2, n_opponents=1, opponent_policy="chase")
    env.close()


@pytest.mark.parametrize("chip_kicks", [False, True], ids=["v0", "chip-kicks"])
def test_sharded_env_matches_one_batched_env(chip_kicks):
    from ssl_marl.envs.sharded import ShardedBatchedEnv

    config = dict(n_blue=2, n_yellow=2, max_time_s=0.5, randomize_reset=True, chip_kicks=chip_kicks)
    dim = 6 if chip_kicks else 5
    sharded = ShardedBatchedEnv(2, 2, **config)
    try:
        ref = BatchedSSLEnv(4, **config)
        o1, _ = sharded.reset(seed=4)
        o2, _ = ref.reset(seed=4)
        np.testing.assert_array_equal(o1, o2)
        rng = np.random.default_rng(0)
        for _ in range(80):  # 30 steps per episode: autoresets included
            a = rng.uniform(-1, 1, (4, 4, dim))
            r1, r2 = sharded.step(a), ref.step(a)
            for x, y in zip(r1[:4], r2[:4]):
                np.testing.assert_array_equal(x, y)
            for k in ("goal", "kicker", "t", "autoreset", "score"):
                np.testing.assert_array_equal(r1[4][k], r2[4][k])
        a[3, 1, 0] = np.nan
        with pytest.raises(ValueError, match="world 3: action for agent 'blue_1'"):
            sharded.step(a)
        with pytest.raises(ValueError, match="shape"):
            sharded.step(a[:2])
    finally:
        sharded.close()


def test_trainer_collects_the_same_data_through_the_batched_vector_env(tmp_path):
    """train's vector_mode="batched" (SkillVectorEnv) stores the same transitions as "sync"."""
    from train.offpolicy.config import config_from_dict, default_config
    from train.offpolicy.loop import Trainer

    buffers = []
    for mode in ("sync", "batched"):
        cfg = config_from_dict({"demo_steps": 0, "eval_interval": 0, "num_envs": 3, "vector_mode": mode,
                                "warmup_samples": 10**9, "buffer_size": 1000, "total_samples": 10**6,
                                "env_kwargs": {"max_time_s": 0.5}, "max_episode_steps": None},
                               base=default_config("go-to-ball"))
        tr = Trainer(cfg, seed=2, out=tmp_path / mode, progress=False)
        tr._reset_envs()
        for _ in range(60):  # 30 steps per episode: autoresets included
            tr.collect_step()
        tr.envs.close()
        b = tr.buffer
        buffers.append((b.obs[: b.size].copy(), b.act[: b.size].copy(), b.terminated[: b.size].copy(), tr.episodes))
    np.testing.assert_array_equal(buffers[0][0], buffers[1][0])
    np.testing.assert_array_equal(buffers[0][1], buffers[1][1])
    np.testing.assert_array_equal(buffers[0][2], buffers[1][2])
    assert buffers[0][3] == buffers[1][3] > 0
