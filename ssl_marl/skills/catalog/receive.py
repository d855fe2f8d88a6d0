"""receive: intercept a moving ball and bring it under control on the dribbler, held
for 0.5 s (issue 11)."""

from __future__ import annotations

from ..passing import ReceiveBaseline
from ..passing_features import (RECEIVE_NAMES, RECEIVE_SPEC, expand_receive_action, receive_features,
                                receive_task_action)
from ..registry import SkillDef, SkillTaskDef, register


def _to_env(action3, mapping: str | None = None):
    return expand_receive_action(action3)


def _drive(env, skill):
    from ..pass_tasks import skill_task_action

    return skill_task_action("receive", env, skill)


SKILL = register(SkillDef(
    name="receive",
    summary="intercept a moving ball and hold it on the dribbler for 0.5 s",
    baseline=ReceiveBaseline,
    learned="ssl_marl.skills.passing:LearnedReceive",
    # no actor is shipped: the best trained one (0.815 on validation) stays below the
    # hand-coded receive (0.997); a "learned" team uses the hand-coded receive (plays.skillset)
    # and a trained checkpoint can still be evaluated or played (eval-skill --policy PATH)
    actor=None,
    task=SkillTaskDef(
        env_id="ssl_marl/Receive-v0",
        entry_point="ssl_marl.skills.pass_tasks:ReceiveEnv",
        features=receive_features,  # (world, robot, robot_params, ball_params)
        feature_names=RECEIVE_NAMES,
        action_names=("vx", "vy", "omega"),
        to_task_action=receive_task_action,
        to_env_action=_to_env,
        spec_versions={"default": RECEIVE_SPEC},
        demo_fn="ssl_marl.skills.pass_tasks:receive_baseline_demos",
        train_config="receive",
        drive=_drive,
    ),
    reference={"learned": 0.95},
    reference_source="issue 11 target (success rate over 1000 episodes); no paper figure",
))
