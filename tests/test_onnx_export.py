"""ONNX export of the shipped learned skills: the exported model, run by onnxruntime,
matches the PyTorch actor within 1e-5 on 1,000 observations from the skill's own env,
and carries its observation spec and normalisation in ``metadata_props``.
Skipped cleanly without the ``onnx`` extra (``pip install -e ".[onnx]"``)."""

from __future__ import annotations

import json

import gymnasium as gym
import numpy as np
import pytest
import torch

import ssl_marl  # noqa: F401  (registers the skill envs)
from ssl_marl.cli import main
from ssl_marl.skills.checkpoint import load_actor

onnx = pytest.importorskip("onnx")
ort = pytest.importorskip("onnxruntime")

from ssl_marl.skills.registry import get_skill, learned_skills, task_skills  # noqa: E402

ENV_IDS = {s.name: s.task.env_id for s in task_skills()}  # every skill task, from the registry


def _observations(env_id: str, n: int, seed: int = 10_000, **env_kwargs) -> np.ndarray:
    """n observations from random-action episodes of the skill env (reset on episode end)."""
    env = gym.make(env_id, **env_kwargs)
    env.action_space.seed(seed)
    obs, _ = env.reset(seed=seed)
    out = []
    while len(out) < n:
        out.append(obs)
        obs, _, term, trunc, _ = env.step(env.action_space.sample())
        if term or trunc:
            obs, _ = env.reset()
    env.close()
    return np.asarray(out, dtype=np.float32)


@pytest.mark.parametrize("skill", sorted(s.name for s in learned_skills() if s.actor is not None))
def test_exported_actor_matches_pytorch(skill, tmp_path, capsys):
    out = tmp_path / "models" / f"{skill}.onnx"
    assert main(["export-onnx", str(get_skill(skill).actor), str(out)]) == 0
    assert "->" in capsys.readouterr().out

    actor, meta = load_actor(get_skill(skill).actor)
    task = get_skill(skill).task
    mapping = task.mapping_of(meta["obs_spec"])  # a form with a state of its own: the env option that selects it
    option = {"go_to_ball": "state"}.get(skill, "action_form")
    obs = _observations(ENV_IDS[skill], 1000, **({option: mapping} if mapping in task.form_names else {}))
    with torch.no_grad():
        expected = actor(torch.from_numpy(obs)).numpy()
    sess = ort.InferenceSession(str(out), providers=["CPUExecutionProvider"])
    (got,) = sess.run(["action"], {"obs": obs})
    assert got.shape == (1000, meta["act_dim"])
    np.testing.assert_allclose(got, expected, rtol=0, atol=1e-5)
    (one,) = sess.run(["action"], {"obs": obs[:1]})  # the batch axis is dynamic
    np.testing.assert_allclose(one, expected[:1], rtol=0, atol=1e-5)

    props = {p.key: p.value for p in onnx.load(str(out)).metadata_props}
    assert props["ssl_marl.obs_spec"] == meta["obs_spec"]
    assert int(props["ssl_marl.obs_dim"]) == obs.shape[1]
    assert json.loads(props["ssl_marl.obs_normalisation"])["kind"] == "none"
    assert len(json.loads(props["ssl_marl.obs_names"])) == obs.shape[1]
    assert json.loads(props["ssl_marl.metadata"])["skill"] == skill
    form = json.loads(props["ssl_marl.action_form"])
    residual = meta["obs_spec"] in ("receive/v2", "receive/v3", "redirect/v2")
    assert form["kind"] == ("residual" if residual else "aim" if meta["obs_spec"] == "redirect/v3" else "direct")


def test_the_pressed_receive_form_in_the_metadata_is_the_skill_s_rule():
    """A deployment rebuilds the pressed receive from the metadata alone: its gate, read
    over the named input columns, is ``receive_press_active``; its combination rule is
    ``receive_residual_action``."""
    from ssl_marl.skills.onnx_export import action_form_of
    from ssl_marl.skills.passing_features import (RECEIVE_PRESSED_NAMES, receive_press_active,
                                                  receive_residual_action)

    form = action_form_of("receive/v3")
    obs = _observations(ENV_IDS["receive"], 600, action_form="pressed", interceptors=1, hold_s=0.1)
    gate = [bool(eval(form["gate"]["rule"], {"abs": abs}, dict(zip(RECEIVE_PRESSED_NAMES, map(float, x)))))
            for x in obs]
    assert gate == [receive_press_active(x) for x in obs] and 0 < sum(gate) < len(gate)
    rng = np.random.default_rng(3)
    base, out = rng.uniform(-1, 1, (200, 3)), rng.uniform(-2, 2, (200, 3))
    rebuilt = np.clip(base + form["scale"] * np.clip(out, -1, 1), -1, 1)
    np.testing.assert_allclose(rebuilt, [receive_residual_action(b, o) for b, o in zip(base, out)], atol=1e-12)


def test_export_refuses_a_wrong_suffix_before_loading(tmp_path, capsys):
    assert main(["export-onnx", str(get_skill("go_to_ball").actor), str(tmp_path / "x.pt")]) == 2
    assert "use .onnx" in capsys.readouterr().err


def test_export_of_a_missing_checkpoint_is_a_clear_error(tmp_path, capsys):
    assert main(["export-onnx", str(tmp_path / "nope.pt"), str(tmp_path / "x.onnx")]) == 2
    assert "not found" in capsys.readouterr().err and not (tmp_path / "x.onnx").exists()
