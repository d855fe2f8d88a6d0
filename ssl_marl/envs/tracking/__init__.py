"""Vision tracking: Kalman filters per robot and for the ball, latency compensation
through the sent commands, ball-on-dribbler inference and outlier gates, as SSL
teams run between their vision and their AI (docs/references.md, "Vision and tracking").

* :class:`TrackerParams`: every parameter with its source.
* :class:`VisionTracker`: one team's tracker over vision frames and sent commands.
* :class:`TrackedVisionEnv`: the opt-in layer over the env whose
  ``vision_state(team)`` is tracked.
* :func:`resolve_tracker` / :func:`with_tracker`: the ``tracker=`` option
  ("auto" | "on" | "off" | bool) every env factory and runner takes, resolved and
  attached in one place.
"""

from .env import TrackedVisionEnv
from .option import TRACKER_MODES, resolve_tracker, with_tracker
from .params import TrackerParams
from .tracker import VisionTracker

__all__ = ["TRACKER_MODES", "TrackedVisionEnv", "TrackerParams", "VisionTracker", "resolve_tracker", "with_tracker"]
