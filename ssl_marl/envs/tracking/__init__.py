"""Vision tracking: Kalman filters per robot and for the ball, latency compensation
through the sent commands, ball-on-dribbler inference and outlier gates, as SSL
teams run between their vision and their AI (docs/references.md, "Vision and tracking").

* :class:`TrackerParams`: every parameter with its source.
* :class:`VisionTracker`: one team's tracker over vision frames and sent commands.
* :class:`TrackedVisionEnv` / :func:`with_tracker`: the opt-in layer over the env
  whose ``vision_state(team)`` is tracked; :func:`resolve_tracker` for the CLI's
  ``--tracker auto|on|off``.
"""

from .env import TRACKER_MODES, TrackedVisionEnv, resolve_tracker, with_tracker
from .params import TrackerParams
from .tracker import VisionTracker

__all__ = ["TRACKER_MODES", "TrackedVisionEnv", "TrackerParams", "VisionTracker", "resolve_tracker", "with_tracker"]
