"""The skill registry: one record per skill, and every consumer covers every skill."""

import subprocess
import sys

import gymnasium
import numpy as np
import pytest

import ssl_marl  # noqa: F401  (registers the gym ids)
from ssl_marl.physics.field import FieldGeometry
from ssl_marl.skills import make_skill, registry
from ssl_marl.skills.registry import (SKILL_KINDS, SkillDef, all_skills, cli_choices, get_skill, get_task,
                                      learned_skills, register, task_skills)

F = FieldGeometry.div_b()


def test_names_and_spellings():
    names = [s.name for s in all_skills()]
    assert names[:2] == ["go_to_ball", "aim_to_shoot"] and {"drive_forward", "move_to_point"} <= set(names)
    assert len(set(names)) == len(names)
    for s in all_skills():
        assert get_skill(s.name) is s and get_skill(s.cli_name) is s
        assert s.cli_name == s.name.replace("_", "-")
    with pytest.raises(ValueError, match="unknown skill 'juggle'"):
        get_skill("juggle")
    with pytest.raises(ValueError, match="no learning task"):
        get_task("drive_forward")
    with pytest.raises(ValueError, match="already registered"):
        register(SkillDef(name="go_to_ball", summary="again", baseline=object))


def test_every_consumer_covers_every_registered_skill():
    from ssl_marl.cli import build_parser
    from ssl_marl.plays.skillset import make_tactic_skill, swappable_skills
    from ssl_marl.runners.skill_eval import _make_env, resolve_policy
    from train.offpolicy.config import CONFIG_DIR, SKILL_CONFIGS, default_config

    sub = next(a for a in build_parser()._subparsers._group_actions)  # noqa: SLF001 (argparse has no API)
    eval_choices = tuple(sub.choices["eval-skill"]._positionals._group_actions[0].choices)  # noqa: SLF001
    assert eval_choices == cli_choices() == tuple(s.cli_name for s in task_skills())
    assert swappable_skills() == tuple(s.name for s in learned_skills())
    for s in all_skills():
        for kind in SKILL_KINDS:  # make_skill: every skill, every kind (learned: where an actor is shipped)
            if kind == "learned" and s.has_learned and s.actor is None:
                with pytest.raises(FileNotFoundError, match="ships no learned actor"):
                    make_skill(s.name, kind, F)
                continue
            skill = make_skill(s.name, kind, F)
            expected = s.learned_class() if (kind == "learned" and s.has_learned) else s.baseline
            assert type(skill) is expected and hasattr(skill, "act") and hasattr(skill, "reset")
        if s.has_learned:  # STP skill sets
            assert type(make_tactic_skill(s.name, "baseline", F)) is s.baseline
        if s.task is None:
            continue
        t = s.task
        assert t.env_id in gymnasium.registry  # gym registration
        env = gymnasium.make(t.env_id)
        assert env.observation_space.shape == (t.obs_dim,) and env.action_space.shape == (t.act_dim,)
        assert env.unwrapped.spec_version in t.specs
        env.close()
        assert resolve_policy(s.cli_name, "baseline") == ("baseline", None)  # evaluation
        assert _make_env(s.cli_name, {}).spec_version == t.spec_of()
        a5 = np.array([0.1, -0.2, 0.3, 0.9, 0.5], np.float32)  # action mapping round trip
        assert t.to_task_action(a5).shape == (t.act_dim,)
        assert t.to_env_action(t.to_task_action(a5)).shape in ((5,), (6,))  # (6,): the env's chip layout
        if s.has_learned and s.actor is not None:  # shipped actor keeps loading (spec versions)
            from ssl_marl.skills.learned import load_policy

            _, meta = load_policy(s.name)
            assert meta["skill"] == s.name and meta["obs_spec"] in t.specs
        # trainer configs: the registry names it, train/ resolves it, and it agrees
        assert SKILL_CONFIGS[s.cli_name] == f"{t.train_config}.json" and (CONFIG_DIR / SKILL_CONFIGS[s.cli_name]).exists()
        cfg = default_config(s.cli_name)
        assert cfg.skill == s.name and cfg.env_id == t.env_id
        if t.demo_fn:
            registry.resolve_ref(t.demo_fn)
        assert set(s.reference) <= set(SKILL_KINDS)


def test_adding_a_skill_is_one_record(monkeypatch):
    """A new record shows up in every lookup without touching any consumer."""
    from ssl_marl.plays.skillset import swappable_skills, validate_skills
    from ssl_marl.skills.baseline import GoToBallBaseline

    monkeypatch.setattr(registry, "_REGISTRY", dict(registry._REGISTRY))  # noqa: SLF001 (test isolation)
    base = get_skill("go_to_ball")
    register(SkillDef(name="chip_to_goal", summary="test skill", baseline=GoToBallBaseline,
                      learned=base.learned, actor=base.actor, task=base.task))
    assert "chip-to-goal" in cli_choices() and "chip_to_goal" in swappable_skills()
    assert type(make_skill("chip-to-goal", "baseline", F)) is GoToBallBaseline
    validate_skills({"chip_to_goal": "learned"})


def test_ssl_marl_never_imports_train():
    code = ("import sys, ssl_marl, ssl_marl.cli, ssl_marl.skills.registry, ssl_marl.skills.catalog, "
            "ssl_marl.runners.skill_eval, ssl_marl.plays.skillset; "
            "ssl_marl.cli.build_parser(); assert not any(m == 'train' or m.startswith('train.') for m in sys.modules)")
    subprocess.run([sys.executable, "-c", code], check=True)


def test_one_skill_kinds_tuple():
    from ssl_marl import skills
    from ssl_marl.plays import skillset

    assert skills.SKILL_KINDS is registry.SKILL_KINDS and skillset.SKILL_KINDS is registry.SKILL_KINDS
