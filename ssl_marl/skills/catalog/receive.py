"""receive: intercept a moving ball and bring it under control on the dribbler, held
for 0.5 s.

Three forms (registry action mappings): ``direct``
(``receive/v1``: the actor's (vx, vy, omega) is the action) and ``residual``
(``receive/v2``: the actor's output is a bounded correction added to the hand-coded
receive's action, so an untrained actor starts at the hand-coded behaviour), and
``pressed`` (``receive/v3``: the residual action on 18 values, the 11 and the opponent
nearest the ball's path, trained with interceptors pressing the pass). The
shipped actor, when there is one, is the pressed one (docs/RESULTS.md, "Receive under
pressure")."""

from __future__ import annotations

import functools

from ..passing import ReceiveBaseline
from ..passing_features import (RECEIVE_ACTION_FORMS, RECEIVE_NAMES, RECEIVE_PRESSED_NAMES, RECEIVE_RESIDUAL_FORMS,
                                expand_receive_action, receive_features, receive_task_action)
from ..registry import PRETRAINED_DIR, SkillDef, SkillTaskDef, direct_env_action, register

_ACTOR = PRETRAINED_DIR / "receive.pt"
_to_env = functools.partial(direct_env_action, expand_receive_action, "receive",
                            {form: RECEIVE_ACTION_FORMS[form] for form in RECEIVE_RESIDUAL_FORMS},
                            "LearnedReceive", "ReceiveEnv")


def _drive(env, skill):
    from ..pass_tasks import skill_task_action

    return skill_task_action("receive", env, skill)


SKILL = register(SkillDef(
    name="receive",
    summary="intercept a moving ball and hold it on the dribbler for 0.5 s",
    baseline=ReceiveBaseline,
    learned="ssl_marl.skills.passing:LearnedReceive",
    # shipped only if it is at least as good as the hand-coded receive on the held-out seed;
    # without it a "learned" team uses the hand-coded receive (plays.skillset)
    actor=_ACTOR if _ACTOR.exists() else None,
    task=SkillTaskDef(
        env_id="ssl_marl/Receive-v0",
        entry_point="ssl_marl.skills.pass_tasks:ReceiveEnv",
        features=receive_features,  # (world, robot, robot_params, ball_params)
        feature_names=RECEIVE_NAMES,
        action_names=("vx", "vy", "omega"),
        to_task_action=receive_task_action,
        to_env_action=_to_env,
        # "direct" first: the task env's default (what eval-skill drives); training uses
        # action_form="residual" (train/configs/receive.json)
        spec_versions=dict(RECEIVE_ACTION_FORMS),
        form_names={"pressed": (RECEIVE_PRESSED_NAMES, ("vx", "vy", "omega"))},
        demo_fn="ssl_marl.skills.pass_tasks:receive_baseline_demos",
        train_config="receive",
        drive=_drive,
    ),
    reference={"learned": 0.95},
    reference_source="ssl_marl's target for a learned receive (success rate over 1000 episodes, docs/RESULTS.md); the paper has no receive skill",
))
