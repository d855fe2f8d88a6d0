"""pass: with the ball on the dribbler, turn and kick so that a teammate at a given
point receives it. Module named ``pass_ball`` because ``pass`` is a keyword."""

from __future__ import annotations

from ...physics.params import RobotParams
from ..passing import PassBaseline
from ..passing_features import PASS_NAMES, PASS_SPEC, expand_pass_action, pass_features, pass_task_action
from ..registry import PRETRAINED_DIR, SkillDef, SkillTaskDef, register

_RP = RobotParams()  # the action mappings' kick-speed range (the task env uses its own robot params)


def _to_task(action5):
    return pass_task_action(action5, _RP)


def _to_env(action3, mapping: str | None = None):
    return expand_pass_action(action3, _RP)


def _drive(env, skill):
    from ..pass_tasks import skill_task_action

    return skill_task_action("pass", env, skill)


SKILL = register(SkillDef(
    name="pass",
    summary="turn with the ball and kick it so that a teammate at a given point receives it",
    baseline=PassBaseline,
    learned="ssl_marl.skills.passing:LearnedPass",
    actor=PRETRAINED_DIR / "pass.pt",
    task=SkillTaskDef(
        env_id="ssl_marl/Pass-v0",
        entry_point="ssl_marl.skills.pass_tasks:PassEnv",
        features=pass_features,  # (world, robot, target, target_vel): the target comes from the task
        feature_names=PASS_NAMES,
        action_names=("omega", "kick", "speed"),
        to_task_action=_to_task,
        to_env_action=_to_env,
        spec_versions={"default": PASS_SPEC},
        demo_fn="ssl_marl.skills.pass_tasks:pass_baseline_demos",
        train_config="pass",
        drive=_drive,
    ),
    reference={"learned": 0.95},
    reference_source="ssl_marl's target for a learned pass (success rate over 1000 episodes, docs/RESULTS.md); the paper has no pass skill",
))
