"""redirect: meet a moving ball and kick it on into the open part of the goal past the
defending goalie, without stopping it (one touch).

Three action forms (registry action mappings): ``direct`` (``redirect/v1``: the actor's
(vx, vy, omega) is the action), ``residual`` (``redirect/v2``: a bounded correction
added to the hand-coded redirect's action), both on the 14-value state, and ``aim``
(``redirect/v3``: the actor picks the aim point along the goal mouth from a 21-value
state and the hand-coded contact planner executes it). The kicker is always armed;
robots kick on contact."""

from __future__ import annotations

import functools

from ..redirect import (REDIRECT_ACTION_FORMS, REDIRECT_ACTIONS, REDIRECT_AIM_ACTIONS, REDIRECT_AIM_NAMES,
                        REDIRECT_NAMES, RedirectBaseline, expand_redirect_action, redirect_features,
                        redirect_task_action)
from ..registry import PRETRAINED_DIR, SkillDef, SkillTaskDef, direct_env_action, register

_ACTOR = PRETRAINED_DIR / "redirect.pt"
_direct_or_residual = functools.partial(direct_env_action, expand_redirect_action,
                                        "redirect", {"residual": "redirect/v2"}, "LearnedRedirect", "RedirectEnv")


def _to_env(action3, mapping: str | None = None):
    """``to_env_action``: a direct action expanded; a residual or aim action needs the
    world state (ValueError naming LearnedRedirect and RedirectEnv, which apply it)."""
    if mapping == "aim":
        raise ValueError("a redirect aim action (redirect/v3) is an aim point the hand-coded contact planner "
                         "executes and needs the world state: use LearnedRedirect or RedirectEnv(action_form='aim')")
    return _direct_or_residual(action3, mapping)


def _drive(env, skill):
    from ..redirect_task import redirect_skill_action

    return redirect_skill_action(env, skill)


SKILL = register(SkillDef(
    name="redirect",
    summary="meet a moving ball and kick it on into the open part of the goal (one touch)",
    baseline=RedirectBaseline,
    learned="ssl_marl.skills.redirect:LearnedRedirect",
    # shipped only if it is at least as good as the hand-coded redirect on the held-out seed
    actor=_ACTOR if _ACTOR.exists() else None,
    task=SkillTaskDef(
        env_id="ssl_marl/Redirect-v0",
        entry_point="ssl_marl.skills.redirect_task:RedirectEnv",
        features=redirect_features,  # (world, robot, field, robot_params, ball_params)
        feature_names=REDIRECT_NAMES,
        action_names=REDIRECT_ACTIONS,
        to_task_action=redirect_task_action,
        to_env_action=_to_env,
        # "direct" first: the task env's default (what eval-skill drives); training uses
        # action_form="aim" (train/configs/redirect.json)
        spec_versions=dict(REDIRECT_ACTION_FORMS),
        form_names={"aim": (REDIRECT_AIM_NAMES, REDIRECT_AIM_ACTIONS)},
        demo_fn="ssl_marl.skills.redirect_task:redirect_baseline_demos",
        train_config="redirect",
        drive=_drive,
    ),
    reference={"learned": 0.85},
    reference_source="the project's target (success rate against the goalie over 1000 episodes); no paper figure",
))
