"""chip pass: with the ball on the dribbler, turn and chip it over the robot standing
in the lane so that a teammate receives it (the kick's elevation is an action entry:
the env's chip layout)."""

from __future__ import annotations

from ...physics.params import RobotParams
from ..chip_pass import (CHIP_PASS_ACTIONS, CHIP_PASS_NAMES, CHIP_PASS_SPEC, ChipPassBaseline, chip_pass_features,
                         chip_pass_task_action, expand_chip_pass_action)
from ..registry import PRETRAINED_DIR, SkillDef, SkillTaskDef, register

_RP = RobotParams()  # the action mappings' kick-speed and elevation ranges (the task env uses its own)
_ACTOR = PRETRAINED_DIR / "chip_pass.pt"


def _to_task(action6):
    return chip_pass_task_action(action6, _RP)


def _to_env(action4, mapping: str | None = None):
    return expand_chip_pass_action(action4, _RP)


def _drive(env, skill):
    from ..chip_pass_task import chip_pass_skill_action

    return chip_pass_skill_action(env, skill)


SKILL = register(SkillDef(
    name="chip_pass",
    summary="turn with the ball and chip it over a robot in the lane so that a teammate receives it",
    baseline=ChipPassBaseline,
    learned="ssl_marl.skills.chip_pass:LearnedChipPass",
    # shipped only if it is at least as good as the hand-coded chip pass on the validation seed
    actor=_ACTOR if _ACTOR.exists() else None,
    task=SkillTaskDef(
        env_id="ssl_marl/ChipPass-v0",
        entry_point="ssl_marl.skills.chip_pass_task:ChipPassEnv",
        features=chip_pass_features,  # (world, robot, target, target_vel): the target comes from the task
        feature_names=CHIP_PASS_NAMES,
        action_names=CHIP_PASS_ACTIONS,
        to_task_action=_to_task,
        to_env_action=_to_env,
        spec_versions={"default": CHIP_PASS_SPEC},
        demo_fn="ssl_marl.skills.chip_pass_task:chip_pass_baseline_demos",
        train_config="chip_pass",
        drive=_drive,
    ),
    reference={"learned": 0.90},
    reference_source="ssl_marl's target for chip passes over a blocker (completion rate over 1000 episodes); no paper figure",
))
