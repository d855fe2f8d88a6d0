"""Runners: everything that runs experiments on top of the STP stack.

Layers: physics -> envs -> skills -> plays -> **runners** (``plays`` imports nothing
from here). One module per job:

==========================  ========================================================
:mod:`.controllers`         team kinds (:data:`TEAM_KINDS`) resolved to a TeamSpec
                            (:func:`team_spec`) and built (:func:`make_controller`),
                            random / idle teams, per-skill sources, JSON team files
:mod:`.match`               one match: :func:`play_match`
:mod:`.series`              K matches over a pool: :func:`play_series`
:mod:`.result`              :class:`MatchResult`, :func:`summarize`
:mod:`.skill_eval`          the paper's skill protocol: :func:`evaluate_skill`
:mod:`.tactic_eval`         the paper's tactic protocol: :func:`evaluate_tactic`
:mod:`.pool`                the one worker pool (local processes or Ray): :func:`run_pool`
:mod:`.plots`               the one histogram writer: :func:`write_time_histogram`
==========================  ========================================================

The real-time deadline object is :class:`ssl_marl.envs.deadline.ControlDeadline`
and the one video sink (GIF/MP4 streamed to disk, constant memory) is
:class:`ssl_marl.envs.animation.VideoSink`: the env and its renderer use them too, so
they live below the runners. Names are imported lazily.
"""

from __future__ import annotations

from typing import Any

_LAZY = {"TEAM_KINDS": "controllers", "make_controller": "controllers", "team_spec": "controllers",
         "team_skills": "controllers", "resolve_team_option": "controllers",
         "load_team_file": "controllers", "parse_skill_source": "controllers",
         "play_match": "match", "play_series": "series", "MatchResult": "result", "summarize": "result",
         "evaluate_skill": "skill_eval", "evaluate_tactic": "tactic_eval", "run_pool": "pool", "BACKENDS": "pool",
         "write_time_histogram": "plots"}


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        import importlib

        return getattr(importlib.import_module(f".{_LAZY[name]}", __name__), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = list(_LAZY)
