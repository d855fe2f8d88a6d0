"""The ``tracker=`` option of every env factory and runner: :func:`resolve_tracker` says
whether the vision tracker runs, :func:`with_tracker` puts it around an env.

Accepted values everywhere (skill task envs, decision task envs, the match, the
evaluation runners, the CLI's ``--tracker``): ``"on"`` / ``True``, ``"off"`` /
``False``, and ``"auto"`` / ``None`` = on unless the realism preset is "none" (the
tracker then sees perfect, undelayed vision and is left out).
"""

from __future__ import annotations

from typing import Any

from ..config import RealismConfig
from .env import TrackedVisionEnv
from .params import TrackerParams

TRACKER_MODES = ("auto", "on", "off")


def resolve_tracker(mode: Any, realism: Any) -> bool:
    """Whether to run the tracker: ``mode`` "on" / True, "off" / False, or "auto" / None
    = on whenever ``realism`` (a preset name, a :class:`RealismConfig` or its fields as a
    dict) is enabled. ValueError for any other ``mode``."""
    if isinstance(mode, bool):
        return mode
    if mode is None or mode == "auto":
        if isinstance(realism, RealismConfig):
            return realism.enabled
        if isinstance(realism, str):
            return RealismConfig.preset(realism).enabled
        return RealismConfig(**dict(realism)).enabled
    if mode == "on":
        return True
    if mode == "off":
        return False
    raise ValueError(f"tracker: expected one of {TRACKER_MODES} or a bool, got {mode!r}")


def with_tracker(env: Any, mode: Any = "auto", params: TrackerParams | None = None) -> Any:
    """``env`` (an :class:`~ssl_marl.envs.ssl_env.SSLParallelEnv`) inside a
    :class:`TrackedVisionEnv` when :func:`resolve_tracker` says so for ``mode`` and the
    env's realism config, else ``env`` itself."""
    return TrackedVisionEnv(env, params) if resolve_tracker(mode, env.config.realism) else env


__all__ = ["TRACKER_MODES", "resolve_tracker", "with_tracker"]
