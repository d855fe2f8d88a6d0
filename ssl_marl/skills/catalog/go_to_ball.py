"""go-to-ball: drive to the ball and get it on the dribbler (paper, section 4.3)."""

from __future__ import annotations

from ..baseline import GoToBallBaseline
from ..features import (GO_TO_BALL_ACTIONS, GO_TO_BALL_NAMES, GO_TO_BALL_SPEC, go_to_ball_env_action,
                        go_to_ball_features, go_to_ball_task_action)
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
        spec_versions={"default": GO_TO_BALL_SPEC},
        demo_fn="ssl_marl.skills.demos:go_to_ball_demos",
        train_config="go_to_ball",
    ),
    reference={"baseline": 1.0, "learned": 0.999},
    reference_source="paper section 5.1 (success rate over 1000 episodes)",
))
