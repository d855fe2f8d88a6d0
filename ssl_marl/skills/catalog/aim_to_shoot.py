"""aim-to-shoot: with the ball on the dribbler, turn towards the goal and score (paper, section 4.3)."""

from __future__ import annotations

from ..baseline import AimToShootBaseline
from ..features import (AIM_TO_SHOOT_ACTIONS, AIM_TO_SHOOT_NAMES, AIM_TO_SHOOT_SPECS, aim_to_shoot_env_action,
                        aim_to_shoot_features, aim_to_shoot_task_action)
from ..registry import PRETRAINED_DIR, SkillDef, SkillTaskDef, register

SKILL = register(SkillDef(
    name="aim_to_shoot",
    summary="with the ball on the dribbler, turn towards the goal and shoot",
    baseline=AimToShootBaseline,
    learned="ssl_marl.skills.learned:LearnedAimToShoot",
    actor=PRETRAINED_DIR / "aim_to_shoot.pt",
    task=SkillTaskDef(
        env_id="ssl_marl/AimToShoot-v0",
        entry_point="ssl_marl.skills.wrappers:AimToShootEnv",
        features=aim_to_shoot_features,
        feature_names=AIM_TO_SHOOT_NAMES,
        action_names=AIM_TO_SHOOT_ACTIONS,
        to_task_action=aim_to_shoot_task_action,
        to_env_action=aim_to_shoot_env_action,
        spec_versions=AIM_TO_SHOOT_SPECS,  # "strength" (v1, the paper's) first: the default
        demo_fn="ssl_marl.skills.demos:aim_to_shoot_baseline_demos",
        train_config="aim_to_shoot",
    ),
    reference={"baseline": 0.71, "learned": 0.772},
    reference_source="paper section 5.1 (success rate over 1000 episodes)",
))
