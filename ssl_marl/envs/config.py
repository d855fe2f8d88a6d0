"""Env configuration: frozen dataclasses that fail loudly, naming the offending field.

:class:`EnvConfig` holds the engine's options, :class:`RealismConfig` the vision and radio
effects and :class:`MatchRules` the parameters of the match task. This module imports
nothing else from :mod:`ssl_marl.envs`: task names are checked where the task is built
(:func:`ssl_marl.envs.tasks.make_task`) and randomisation ranges where the env is built
(:func:`ssl_marl.envs.randomization.resolve_randomization`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace
from dataclasses import field as dc_field
from typing import Any, Mapping

from ..physics.field import FieldGeometry
from ..physics.params import BallParams, RobotParams

REWARD_TERMS = ("goal", "ball_progress", "possession")
AFTER_GOAL = ("kickoff", "terminate")
#: reward scales of the match task when none are given
DEFAULT_REWARD_SCALES = {"goal": 1.0, "ball_progress": 0.0, "possession": 0.0}


@dataclass(frozen=True)
class RealismConfig:
    """Vision noise, dropout, latency and radio loss. All zero (off) by default.

    Attributes:
        robot_pos_sigma: Gaussian noise on observed robot positions (m).
        robot_angle_sigma: Gaussian noise on observed robot headings (rad).
        ball_pos_sigma: Gaussian noise on the observed ball position (m).
        vel_sigma: Gaussian noise on observed linear velocities (m/s).
        ball_dropout: probability that the ball is not detected in a frame; the
            observation then holds the last seen ball and ``ball_visible`` = 0.
        obs_latency_steps: vision delay in control steps (observations are this old).
        cmd_latency_steps: radio delay in control steps (commands act this late).
        cmd_loss: probability that a robot's command is lost; it keeps the previous one.
    """

    robot_pos_sigma: float = 0.0
    robot_angle_sigma: float = 0.0
    ball_pos_sigma: float = 0.0
    vel_sigma: float = 0.0
    ball_dropout: float = 0.0
    obs_latency_steps: int = 0
    cmd_latency_steps: int = 0
    cmd_loss: float = 0.0

    def __post_init__(self) -> None:
        for f in fields(self):
            v = getattr(self, f.name)
            if f.name.endswith("_steps"):
                if not isinstance(v, int) or isinstance(v, bool) or v < 0:
                    raise ValueError(f"realism.{f.name} must be a non-negative integer, got {v!r}")
            else:
                if not (isinstance(v, (int, float)) and math.isfinite(v) and v >= 0):
                    raise ValueError(f"realism.{f.name} must be a non-negative finite number, got {v!r}")
        for name in ("ball_dropout", "cmd_loss"):
            if getattr(self, name) > 1:
                raise ValueError(f"realism.{name} is a probability and must be <= 1, got {getattr(self, name)!r}")

        object.__setattr__(self, "_enabled", any(getattr(self, f.name) for f in fields(self)))

    @property
    def enabled(self) -> bool:
        """True if any realism effect is switched on (cached: read every step)."""
        return self._enabled  # type: ignore[attr-defined]

    @staticmethod
    def preset(name: str) -> "RealismConfig":
        """"none" or "realistic" (ER-Force's realistic preset at 60 Hz: ball sigma 1.4 mm,
        robot 1.3 mm / 0.01 rad, ~45 ms vision delay -> 3 steps, 5 % ball dropout,
        3 % commands lost, one step of radio delay). "randomized" gives the same nominal
        config: an env built with ``realism="randomized"`` draws each episode's conditions
        around it (:mod:`ssl_marl.envs.randomization`); teams are told the nominal ones."""
        if name == "none":
            return RealismConfig()
        if name in ("realistic", "randomized"):
            return RealismConfig(robot_pos_sigma=0.0013, robot_angle_sigma=0.01, ball_pos_sigma=0.0014,
                                 vel_sigma=0.02, ball_dropout=0.05, obs_latency_steps=3, cmd_latency_steps=1,
                                 cmd_loss=0.03)
        raise ValueError(f"realism: unknown preset {name!r}; expected 'none', 'realistic' or 'randomized'")


def check_no_progress_s(v: Any) -> None:
    """ValueError unless ``v`` (``no_progress_s``) is None or a positive finite number of seconds."""
    if v is not None and not (isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) and v > 0):
        raise ValueError(f"no_progress_s must be None (off) or a positive finite number of seconds, got {v!r}")


@dataclass(frozen=True)
class MatchRules:
    """Parameters of the match task (:class:`ssl_marl.envs.tasks.match.MatchTask`), the one
    place they live: an env reads them from ``config.match`` (or its match task's ``rules``).

    Attributes:
        referee: goals, out-of-play and no progress are called (False: the walls hold
            everything in).
        after_goal: "kickoff" (place the kickoff formation and play on) or "terminate".
        max_time_s: truncation time (s on the match clock, the simulated time unless
            ``clock_stops``; ``math.inf``: no limit).
        reward_scales: scale per named reward term ("goal", "ball_progress",
            "possession"); terms not named keep their defaults (goal 1, the others 0).
        randomize_reset: True: robots and ball at random on reset; False: kickoff formation.
        no_progress_s: the referee's "lack of progress" call (SSL rules, Force Start:
            "a clear lack of progress for at least 10 seconds"): when the ball has stayed
            within ``NO_PROGRESS_RADIUS_M`` of one spot for this long (s), play is
            restarted as after the ball left the field (the ball placed at least 0.2 m
            inside the lines and out of the defense areas, robots within 0.5 m moved
            out; event ``no_progress``), which breaks two robots pinning the ball
            against each other. None switches the call off (see
            :mod:`ssl_marl.envs.referee`).
        ssl_restarts: SSL game control (:mod:`ssl_marl.envs.game_control`): kickoffs to
            the team that conceded, a STOP of ``stop_s`` before each free kick, free
            kicks to the team that did not touch the ball last, the referee's command
            in ``MatchTask.referee_state`` and ``referee`` events. False (default):
            play restarts at once, the ball placed and nearby robots moved out.
        fouls: call excessive dribbling, double touch, an attacker touching the
            ball in the opponent's defense area and, with ``ssl_restarts``, a defender
            within 0.48 m of a kickoff's or free kick's ball (event ``foul``; with
            ``ssl_restarts`` a free kick for the other team, without it the ball-out
            restart at the foul's spot). Default False.
        restart_jitter_m: every restart's robot placement is drawn from the env's
            seeded ``np_random``: kickoff formation positions moved by up to this
            many m (within the legal region) and robots cleared from a placed ball
            moved out to 0.5 m plus up to this many m at a random angle offset. 0
            (default): the fixed formation and radial clearance.
        stop_s: length of the STOP before a free kick (s, ``ssl_restarts``).
        free_kick_timeout_s: a kickoff or free kick not taken within this (s) turns
            into running play (the rules' 10 s of Division B).
        half_time_s: None (default): one period. A number (s): half-time at this
            simulated time: the score is kept, the teams change ends and yellow
            kicks off the second half (see :class:`ssl_marl.envs.tasks.match.MatchTask`).
        clock_stops: the match clock that ``max_time_s`` and ``half_time_s`` read stops
            during STOP (SSL rules: two halves of 300 s of playing time, the clock
            stopped during stop, halt and ball placement). False (default): the clock is
            the simulated time. Only ``ssl_restarts`` gives STOPs.
    """

    referee: bool = True
    after_goal: str = "kickoff"
    max_time_s: float = 300.0
    reward_scales: Mapping[str, float] = dc_field(default_factory=lambda: dict(DEFAULT_REWARD_SCALES))
    randomize_reset: bool = False
    no_progress_s: float | None = 10.0
    ssl_restarts: bool = False
    fouls: bool = False
    restart_jitter_m: float = 0.0
    stop_s: float = 1.0
    free_kick_timeout_s: float = 10.0
    half_time_s: float | None = None
    clock_stops: bool = False

    def __post_init__(self) -> None:
        for name in ("ssl_restarts", "fouls", "clock_stops"):
            if not isinstance(getattr(self, name), bool):
                raise ValueError(f"{name} must be True or False, got {getattr(self, name)!r}")
        for name, low in (("restart_jitter_m", 0.0), ("stop_s", 0.0), ("free_kick_timeout_s", 1e-9)):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) and v >= low):
                raise ValueError(f"{name} must be a finite number >= {low:g}, got {v!r}")
        h = self.half_time_s
        if h is not None and not (isinstance(h, (int, float)) and not isinstance(h, bool) and math.isfinite(h) and h > 0):
            raise ValueError(f"half_time_s must be None (one period) or a positive number of seconds, got {h!r}")
        v = self.max_time_s
        if not (isinstance(v, (int, float)) and not isinstance(v, bool) and v > 0):
            raise ValueError(f"max_time_s must be a positive number of seconds (math.inf: no limit), got {v!r}")
        if self.after_goal not in AFTER_GOAL:
            raise ValueError(f"after_goal must be one of {AFTER_GOAL}, got {self.after_goal!r}")
        check_no_progress_s(self.no_progress_s)
        scales = dict(self.reward_scales)
        for k, s in scales.items():
            if k not in REWARD_TERMS:
                raise ValueError(f"reward_scales: unknown term {k!r}; expected some of {REWARD_TERMS}")
            if not (isinstance(s, (int, float)) and math.isfinite(s)):
                raise ValueError(f"reward_scales[{k!r}] must be a finite number, got {s!r}")
        object.__setattr__(self, "reward_scales", {**DEFAULT_REWARD_SCALES, **scales})


#: the env options that are :class:`MatchRules` fields (collected into ``EnvConfig.match``)
MATCH_OPTIONS = tuple(f.name for f in fields(MatchRules))


@dataclass(frozen=True)
class EnvConfig:
    """Options of the full-field SSL engine (see :class:`ssl_marl.envs.ssl_env.SSLParallelEnv`).

    Build it with :func:`make_config`, which also takes the match parameters as single
    keywords (``max_time_s=60``, ...).

    Attributes:
        n_blue, n_yellow: robots per team (0-11 each, at least one robot in all, and
            no more than the division allows unless ``enforce_division_limit`` is False).
        field: "div_a", "div_b" or a :class:`FieldGeometry`.
        control_hz: control (and vision) rate; the paper uses 60 Hz.
        physics_substeps: Box2D steps per control step.
        robot, ball: physical parameters.
        realism: noise / latency settings, or a preset name ("none", "realistic",
            "randomized": the realistic preset as nominal conditions plus per-episode
            domain randomisation, see ``randomization``).
        randomization: per-episode domain randomisation
            (:mod:`ssl_marl.envs.randomization`): None (off; the default unless
            ``realism="randomized"``, which makes it True), True (default ranges), a dict
            of ranges, or a ``RandomizationRanges`` / ``DomainRandomization``. The env
            checks and resolves it when it is built.
        realtime: advance with the wall clock; a command that arrives after the
            control deadline misses its step (the paper's evaluation mode).
        obs_max_teammates, obs_max_opponents: observation slots (padded with a mask);
            with fewer slots than robots, each agent sees the nearest ones.
        task: what an episode is about: a name ("match", the default; "free_play": no
            rules, rewards or end; "keepaway") or a :class:`ssl_marl.envs.tasks.Task`
            object (see :mod:`ssl_marl.envs.tasks`, which checks it when the env is built).
        match: the match task's parameters (:class:`MatchRules`, or a dict of its fields).
        render_mode: None, "rgb_array" or "human".
        render_trails: draw trajectories (the paper's Fig. 7).
        render_width_px: frame width in pixels.
        render_team_labels: ``{"blue": text, "yellow": text}`` or None: a caption strip
            below the field says what each team is (e.g. "learned skills").
        chip_kicks: the env's v1 layout (False: v0, the default). On: the action gains a
            sixth entry, the chip (kick elevation = value x ``robot.chip_angle_max`` when
            > 0, else flat; :mod:`ssl_marl.envs.actions`), the observation gains the
            ball's height (m) and vertical velocity (m/s) at its end
            (:mod:`ssl_marl.envs.observation`), and the robots kick on contact
            (``robot.kick_on_contact`` is set: an armed kicker fires when the ball reaches
            its face, as an SSL robot's kicker fires when its light barrier sees the ball;
            needed for one-touch redirects). Off: the ball never leaves the ground.
        observations: False: ``reset`` and ``step`` return an empty observation dict
            instead of computing every agent's vector, for runners whose controllers
            read ``vision_state()`` (the match runner's STP teams); True (default) for
            every learner and API client.
    """

    n_blue: int = 6
    n_yellow: int = 6
    field: Any = "div_b"
    control_hz: float = 60.0
    physics_substeps: int = 2
    robot: RobotParams = dc_field(default_factory=RobotParams)
    ball: BallParams = dc_field(default_factory=BallParams)
    realism: Any = "none"
    realtime: bool = False
    obs_max_teammates: int = 10
    obs_max_opponents: int = 11
    task: Any = "match"
    match: MatchRules = dc_field(default_factory=MatchRules)
    enforce_division_limit: bool = False
    render_mode: str | None = None
    render_trails: bool = False
    render_width_px: int = 960
    render_team_labels: Mapping[str, str] | None = None
    randomization: Any = None
    chip_kicks: bool = False
    observations: bool = True

    def __post_init__(self) -> None:
        for name in ("chip_kicks", "observations"):
            if not isinstance(getattr(self, name), bool):
                raise ValueError(f"{name} must be True or False, got {getattr(self, name)!r}")
        if self.chip_kicks and not self.robot.kick_on_contact:
            object.__setattr__(self, "robot", replace(self.robot, kick_on_contact=True))
        if isinstance(self.realism, str) and self.realism == "randomized" and self.randomization is None:
            object.__setattr__(self, "randomization", True)
        if self.randomization is False:
            object.__setattr__(self, "randomization", None)
        geom = FieldGeometry.from_name(self.field)
        object.__setattr__(self, "field", geom)
        if isinstance(self.realism, str):
            object.__setattr__(self, "realism", RealismConfig.preset(self.realism))
        elif isinstance(self.realism, Mapping):
            object.__setattr__(self, "realism", RealismConfig(**self.realism))
        elif not isinstance(self.realism, RealismConfig):
            raise ValueError(f"realism: expected a preset name, a dict or a RealismConfig, got {self.realism!r}")
        if isinstance(self.match, Mapping):
            object.__setattr__(self, "match", MatchRules(**self.match))
        elif not isinstance(self.match, MatchRules):
            raise ValueError(f"match: expected a MatchRules or a dict of its fields, got {self.match!r}")
        for name in ("n_blue", "n_yellow"):
            v = getattr(self, name)
            if not isinstance(v, int) or isinstance(v, bool) or not 0 <= v <= 11:
                raise ValueError(f"{name} must be an integer in 0..11, got {v!r}")
            if self.enforce_division_limit and v > geom.max_robots_per_team:
                raise ValueError(f"{name}={v} exceeds the {geom.name} limit of {geom.max_robots_per_team} robots")
        if self.n_blue + self.n_yellow < 1:
            raise ValueError("n_blue + n_yellow must be at least 1 robot")
        if not (isinstance(self.control_hz, (int, float)) and math.isfinite(self.control_hz) and self.control_hz > 0):
            raise ValueError(f"control_hz must be a positive finite number, got {self.control_hz!r}")
        if not isinstance(self.physics_substeps, int) or self.physics_substeps < 1:
            raise ValueError(f"physics_substeps must be an integer >= 1, got {self.physics_substeps!r}")
        for name in ("obs_max_teammates", "obs_max_opponents"):
            v = getattr(self, name)
            if not isinstance(v, int) or v < 0:
                raise ValueError(f"{name} must be a non-negative integer, got {v!r}")
        if self.render_mode not in (None, "rgb_array", "human"):
            raise ValueError(f"render_mode must be None, 'rgb_array' or 'human', got {self.render_mode!r}")
        if not isinstance(self.render_width_px, int) or self.render_width_px < 64:
            raise ValueError(f"render_width_px must be an integer >= 64, got {self.render_width_px!r}")
        labels = self.render_team_labels
        if labels is not None and not (isinstance(labels, Mapping) and set(labels) <= {"blue", "yellow"}
                                       and all(isinstance(v, str) for v in labels.values())):
            raise ValueError(f"render_team_labels must map 'blue'/'yellow' to text, got {labels!r}")

    @property
    def dt(self) -> float:
        """Control period (s)."""
        return 1.0 / self.control_hz

    def with_(self, **changes: Any) -> "EnvConfig":
        return replace(self, **changes)


def make_config(**options: Any) -> EnvConfig:
    """An :class:`EnvConfig` from the env's keyword options: :class:`EnvConfig`'s fields,
    and :class:`MatchRules`' fields (``referee``, ``after_goal``, ``max_time_s``,
    ``reward_scales``, ``randomize_reset``, ``no_progress_s``, ``ssl_restarts``, ``fouls``,
    ``restart_jitter_m``, ``stop_s``, ``free_kick_timeout_s``, ``half_time_s``, ``clock_stops``) as single keywords, which
    make up ``match`` (or ``match=`` gives them all at once; not both). An unknown
    keyword is a ValueError listing the known ones."""
    known = {f.name for f in fields(EnvConfig)} | set(MATCH_OPTIONS)
    unknown = sorted(set(options) - known)
    if unknown:
        raise ValueError(f"unknown env option(s) {unknown}; known options: {sorted(known)}")
    rules = {k: options.pop(k) for k in MATCH_OPTIONS if k in options}
    if rules:
        if "match" in options:
            raise ValueError(f"match: give the match parameters either as match= or as keywords "
                             f"{sorted(rules)}, not both")
        options["match"] = MatchRules(**rules)
    return EnvConfig(**options)
