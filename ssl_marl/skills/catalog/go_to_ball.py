"""go-to-ball: drive to the ball and get it on the dribbler (paper, section 4.3).

Two state forms (registry action mappings, same action): ``default`` (``go_to_ball/v1``,
the paper's 14 values) and ``ball_velocity`` (``go_to_ball/v2``, the paper's values and
the ball's velocity, for a ball that is rolling)."""

from __future__ import annotations

from ..baseline import GoToBallBaseline
from ..features import (GO_TO_BALL_ACTIONS, GO_TO_BALL_NAMES, GO_TO_BALL_SPECS, GO_TO_BALL_V2_NAMES,
                        go_to_ball_env_action, go_to_ball_features, go_to_ball_task_action)
from ..registry import PRETRAINED_DIR, SkillDef, SkillTaskDef, register

SKILL = register(SkillDef(
    name="go_to_ball",
    summary="drive to the ball and get it on the dribbler",
    baseline=GoToBallBaseline,
    learned="ssl_marl.skills.learned:LearnedGoToBall",
    actor=PRETRAINED_DIR / "go_to_ball.pt",
    task=SkillTaskDef(
        env_id="ssl_marl/GoToBall-v0",
        entry_point="ssl_marl.skills.wrappers:GoToBallEnv",
        features=go_to_ball_features,
        feature_names=GO_TO_BALL_NAMES,
        action_names=GO_TO_BALL_ACTIONS,
        to_task_action=go_to_ball_task_action,
        to_env_action=go_to_ball_env_action,
        # "default": the paper's state (go_to_ball/v1, the task's default); "ball_velocity":
        # with the ball's velocity (go_to_ball/v2, train/configs/go_to_ball_rolling.json)
        spec_versions=GO_TO_BALL_SPECS,
        form_names={"ball_velocity": (GO_TO_BALL_V2_NAMES, GO_TO_BALL_ACTIONS)},
        demo_fn="ssl_marl.skills.demos:go_to_ball_demos",
        train_config="go_to_ball",
    ),
    reference={"baseline": 1.0, "learned": 0.999},
    reference_source="paper section 5.1 (success rate over 1000 episodes)",
))
