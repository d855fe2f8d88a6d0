"""Training across env variants (one go-to-ball actor for both divisions):
the concatenated vector env and the trainer's ``env_variants``."""

from __future__ import annotations

import json

import numpy as np
import pytest
import torch

from ssl_marl.skills.concat_vector import ConcatVectorEnv, _merge_infos
from ssl_marl.skills.vector import SkillVectorEnv
from train.offpolicy.config import DDPGConfig, TrainConfig
from train.offpolicy.loop import Trainer
from train.tools.select import select, training_fields

torch.set_num_threads(1)


def test_concat_vector_env_steps_each_block_as_its_own_vector_env() -> None:
    parts = [SkillVectorEnv("go-to-ball", 2, field="div_a"), SkillVectorEnv("go-to-ball", 2)]
    alone = [SkillVectorEnv("go-to-ball", 2, field="div_a"), SkillVectorEnv("go-to-ball", 2)]
    env = ConcatVectorEnv(parts)
    assert env.num_envs == 4 and env.single_observation_space.shape == (14,)
    for a in alone:  # the union of the fields' bounds holds both fields' observation spaces
        assert np.all(env.single_observation_space.low <= a.single_observation_space.low)
        assert np.all(env.single_observation_space.high >= a.single_observation_space.high)
    obs, _ = env.reset(seed=7)
    ref = np.concatenate([alone[0].reset(seed=7)[0], alone[1].reset(seed=9)[0]])  # sub-env i gets seed + i
    np.testing.assert_array_equal(obs, ref)
    rng = np.random.default_rng(0)
    for _ in range(40):
        act = rng.uniform(-1, 1, (4, 3)).astype(np.float32)
        o, r, te, tr, info = env.step(act)
        ra = [a.step(act[2 * j:2 * j + 2]) for j, a in enumerate(alone)]
        np.testing.assert_array_equal(o, np.concatenate([x[0] for x in ra]))
        np.testing.assert_array_equal(r, np.concatenate([x[1] for x in ra]))
        np.testing.assert_array_equal(info["reward_terms"]["distance"],
                                      np.concatenate([x[4]["reward_terms"]["distance"] for x in ra]))
    assert env.envs[0].field.name != env.envs[1].field.name
    with pytest.raises(ValueError, match="4 rows"):
        env.step(np.zeros((3, 3), np.float32))
    env.close()
    for a in alone:
        a.close()


def test_infos_missing_in_one_block_are_masked() -> None:
    a = {"is_success": np.array([True, False]), "_is_success": np.array([True, False]),
         "failure_reason": np.array([None, None], object), "_failure_reason": np.array([True, False]),
         "terms": {"x": np.array([1.0, 2.0]), "_x": np.array([True, True])}, "_terms": np.array([True, True])}
    out = _merge_infos([a, {}], [2, 3])
    assert out["is_success"].tolist() == [True, False, False, False, False]
    assert out["_is_success"].tolist() == [True, False, False, False, False]
    assert out["failure_reason"].dtype == object and out["failure_reason"][4] is None
    assert out["terms"]["x"].tolist() == [1.0, 2.0, 0.0, 0.0, 0.0]
    assert out["terms"]["_x"].tolist() == [True, True, False, False, False]
    assert out["_terms"].tolist() == [True, True, False, False, False]


def test_env_variants_config_errors_name_the_field() -> None:
    with pytest.raises(ValueError, match="num_envs .3. must be a multiple of the number of env_variants .2."):
        TrainConfig(num_envs=3, env_variants=[{"field": "div_a"}, {"field": "div_b"}])
    with pytest.raises(ValueError, match="env_variants must be a list of dicts"):
        TrainConfig(num_envs=2, env_variants=["div_a", "div_b"])
    cfg = TrainConfig(num_envs=2, env_kwargs={"max_time_s": 5.0}, env_variants=[{"field": "div_a"}, {}])
    assert cfg.variant_kwargs() == [{"max_time_s": 5.0, "field": "div_a"}, {"max_time_s": 5.0}]
    assert TrainConfig(env_kwargs={"field": "div_a"}).variant_kwargs() == [{"field": "div_a"}]


@pytest.mark.parametrize("mode", ["batched", "sync"])
def test_trainer_splits_worlds_demos_and_checks_across_variants(tmp_path, mode) -> None:
    cfg = TrainConfig(skill="go_to_ball", env_id="ssl_marl/GoToBall-v0", demo_fn="ssl_marl.skills.demos:go_to_ball_demos",
                      demo_steps=301, ddpg=DDPGConfig(actor_hidden=(32,), critic_hidden=(32,)), total_samples=400, warmup_samples=100,
                      batch_size=32, buffer_size=5_000, num_envs=4, vector_mode=mode, eval_interval=0, eval_episodes=3,
                      checkpoint_interval=200 if mode == "batched" else 10_000, torch_threads=1, autocast_bf16=False, n_step=3,
                      updates_per_sample=0.25, env_variants=[{"field": "div_a"}, {"field": "div_b"}])
    trainer = Trainer(cfg, seed=0, out=tmp_path, progress=False)
    fields = [e.field.name for e in (trainer.envs.envs if mode == "batched" else
                                     [x.unwrapped for x in trainer.envs.envs])]
    if mode == "batched":  # one batched world set per field
        assert [b.field.name for b in trainer.envs.envs] == ["div_a", "div_b"]
    else:
        assert fields == ["div_a", "div_a", "div_b", "div_b"]
    trainer.run()
    assert trainer.transitions - trainer.samples == 301  # the demo steps, split 151 / 150 across the fields
    result = json.loads((tmp_path / "eval.json").read_text())
    assert result["episodes"] == 3 and [v["episodes"] for v in result["variants"]] == [2, 1]
    rate = sum(v["success_rate"] * v["episodes"] for v in result["variants"]) / 3
    assert result["success_rate"] == pytest.approx(rate)
    if mode == "batched":  # model selection validates each exported actor on both training fields
        sel = select(tmp_path, episodes=2, seed=5000, progress=False)
        assert sel["fields"] is None and len(sel["candidates"]) == 2
        for row in sel["candidates"]:
            assert sorted(row["by_field"]) == ["div_a", "div_b"]
            assert row["success_rate"] == min(f["success_rate"] for f in row["by_field"].values())


def test_training_fields_from_actor_metadata() -> None:
    assert training_fields({}) == ["div_b"]
    assert training_fields({"hyperparameters": {"env_kwargs": {"field": "div_a"}}}) == ["div_a"]
    hp = {"env_kwargs": {}, "env_variants": [{"field": "div_a"}, {"field": "div_b"}, {"field": "div_a"}]}
    assert training_fields({"hyperparameters": hp}) == ["div_a", "div_b"]
