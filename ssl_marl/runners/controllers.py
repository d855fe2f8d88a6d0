"""How a team is named on the command line, and the team it names.

A team is one of :data:`TEAM_KINDS`:

* ``"learned"`` / ``"baseline"``: an STP :class:`~ssl_marl.plays.team.TeamController`
  whose skills are the shipped DDPG actors / the hand-coded skills;
* ``"passing-learned"`` / ``"passing-baseline"``: the same controller with the passing
  plays (:mod:`ssl_marl.plays.passing_play`: shoot, pass or keep by cost, set plays with
  passes) and those skills (:func:`~ssl_marl.plays.skillset.team_skill_set`);
* ``"passing-learned-decision"``: ``"passing-learned"`` whose ball carrier decides
  with the learned Attack 3v2 decision (:mod:`ssl_marl.decisions.match_decider`,
  the shipped actor ``ssl_marl/decisions/pretrained/attack_3v2.pt``) instead of the cost
  decision;
* ``"attack-learned"`` / ``"attack-baseline"``: the attacking plays
  (:mod:`ssl_marl.plays.attack_play`: shot, flat pass, chip pass, pass into a redirect
  or dribble by cost, supports on rated spots) with those skills; they chip, so they
  play only in an env with chip kicks (:data:`CHIP_KINDS`; the match runner builds one);
* ``"attack-learned-decision"``: ``"attack-learned"`` whose ball carrier decides in open
  play with the learned attack-drill decision (the shipped actor
  ``ssl_marl/decisions/pretrained/attack_drill.pt``) instead of the cost decision;
* ``"random"``: uniform random actions (seeded); ``"idle"``: zero actions.

A passing or attacking team's carrier decision can also be chosen per team
(``decision=``, ``ssl-marl match --blue-decision handcoded|learned|PATH``): a passing
team's learned decision is an Attack 3v2 actor, an attacking team's an attack-drill actor
(:mod:`ssl_marl.decisions.attack_drill`).

:func:`team_spec` resolves an STP kind, its skill sources and its decision to a
:class:`~ssl_marl.plays.team.TeamSpec` (loading a learned decider here: ``plays``
imports nothing of ``decisions``); :func:`make_controller` builds any kind's controller
(STP teams through :func:`~ssl_marl.plays.team.build_team`).

An STP team may replace any skill with another source (:func:`team_skills`):
``{"go-to-ball": "runs/gtb/actor.pt"}`` runs that trained actor inside the tactics,
``{"aim-to-shoot": "baseline"}`` the hand-coded skill. A team can also be read from a
small JSON team file (:func:`load_team_file`)::

    {"kind": "learned", "skills": {"go-to-ball": "runs/gtb/actor.pt"}}
    {"kind": "attack-learned", "decision": "runs/mappo_attack_match_s0/actors/actor-1502.pt"}

(checkpoint paths relative to the file's folder; ``decision``: "handcoded", "learned" or
a decision actor of the kind's decision task, for the kinds of :data:`DECISION_KINDS`);
:func:`resolve_team_option` reads a team named on the command line (a kind or a team
file, plus per-skill sources and a decision). Any object with ``agents`` and
``act(env) -> {agent: action}`` is accepted as a controller too.
"""

from __future__ import annotations

import json
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING, Any, Mapping, NamedTuple

import numpy as np

if TYPE_CHECKING:
    from ..plays.team import TeamController, TeamSpec

TEAM_KINDS = ("learned", "baseline", "random", "idle", "passing-learned", "passing-baseline",
              "passing-learned-decision", "attack-learned", "attack-baseline", "attack-learned-decision")
STP_KINDS = ("learned", "baseline", "passing-learned", "passing-baseline", "passing-learned-decision",
             "attack-learned", "attack-baseline", "attack-learned-decision")
PASSING_KINDS = ("passing-learned", "passing-baseline", "passing-learned-decision")
#: team kinds with the attacking plays; they chip, so they need an env with ``chip_kicks=True``
ATTACK_KINDS = ("attack-learned", "attack-baseline", "attack-learned-decision")
CHIP_KINDS = ATTACK_KINDS
#: team kinds whose carrier decision is learned by default
LEARNED_DECISION_KINDS = ("passing-learned-decision", "attack-learned-decision")
#: team kinds whose carrier decision can be chosen (``decision=``): the passing plays'
#: (decision task attack-3v2) and the attacking plays' (decision task attack-drill)
DECISION_KINDS = PASSING_KINDS + ATTACK_KINDS
TEAM_FILE_KEYS = ("kind", "skills", "decision")


class IdleController:
    """Zero actions for every robot of ``team``."""

    def __init__(self, team: str, n_robots: int) -> None:
        self.agents = [f"{team}_{i}" for i in range(n_robots)]

    def reset(self) -> None:
        pass

    def act(self, env_or_world: Any) -> dict[str, np.ndarray]:
        return {a: np.zeros(5, np.float32) for a in self.agents}


class RandomController:
    """Uniform random actions in [-1, 1] (seeded)."""

    def __init__(self, team: str, n_robots: int, seed: int = 0) -> None:
        self.agents = [f"{team}_{i}" for i in range(n_robots)]
        self.seed = seed
        self.reset()

    def reset(self) -> None:
        self.rng = np.random.default_rng(self.seed)

    def act(self, env_or_world: Any) -> dict[str, np.ndarray]:
        a = self.rng.uniform(-1.0, 1.0, (len(self.agents), 5)).astype(np.float32)
        return dict(zip(self.agents, a))


def team_skills(kind: str, sources: Mapping[str, Any] | None = None, where: str = "team") -> Any:
    """The :mod:`~ssl_marl.plays.skillset` spec for an STP team of ``kind`` whose
    skills ``sources`` ({skill: "baseline" | "learned" | checkpoint path}) replace
    the kind's own: ``kind`` itself when there are none, else a full mapping.
    Raises ValueError for a non-STP kind with sources or an unknown skill."""
    from ..plays.skillset import CORE_SKILLS, swappable_skills, team_skill_set, validate_skills

    if not sources:
        return kind
    if kind not in STP_KINDS:
        raise ValueError(f"{where}: skill sources need an STP team ({' or '.join(STP_KINDS)}), not {kind!r}")
    spec: dict[str, Any] = (dict(kind_skills(kind)) if kind in PASSING_KINDS + ATTACK_KINDS
                            else team_skill_set(kind, CORE_SKILLS, where=where))
    for name, source in sources.items():
        key = name.replace("-", "_") if isinstance(name, str) else name
        if key not in swappable_skills():
            raise ValueError(f"{where}: unknown skill {name!r}; expected one of "
                             f"{tuple(n.replace('_', '-') for n in swappable_skills())}")
        spec[key] = str(source) if not isinstance(source, str) else source
    validate_skills(spec)
    return spec


def parse_skill_source(text: str) -> tuple[str, str]:
    """``"go-to-ball=runs/gtb/actor.pt"`` -> ("go_to_ball", "runs/gtb/actor.pt")."""
    from ..plays.skillset import swappable_skills

    name, sep, source = text.partition("=")
    key = name.strip().replace("-", "_")
    if not sep or not source.strip():
        raise ValueError(f"skill source must be SKILL=SOURCE (e.g. go-to-ball=runs/gtb/actor.pt), got {text!r}")
    if key not in swappable_skills():
        raise ValueError(f"skill source {text!r}: unknown skill {name.strip()!r}; expected one of "
                         f"{tuple(n.replace('_', '-') for n in swappable_skills())}")
    return key, source.strip()


class TeamFile(NamedTuple):
    """A JSON team file's content (:func:`load_team_file`): the team ``kind``, its
    ``skills`` ({skill: source}) and its carrier ``decision`` (None: the kind's own)."""

    kind: str
    skills: dict[str, str]
    decision: str | None = None


def _file_path(path: Path, source: str, names: tuple[str, ...]) -> str:
    """``source`` resolved against the team file's folder unless it is one of ``names``
    or absolute."""
    return source if source in names or Path(source).is_absolute() else str(path.parent / source)


def load_team_file(path: str | Path) -> TeamFile:
    """Read a JSON team file ``{"kind": ..., "skills": {skill: source}, "decision": ...}``
    (skills and decision optional) with checkpoint paths resolved against the file's folder.
    ValueError (naming the key) for anything else."""
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"team file {str(path)!r} does not exist")
    try:
        data = json.loads(path.read_text())
    except json.JSONDecodeError as exc:
        raise ValueError(f"team file {path}: not valid JSON ({exc})") from None
    if not isinstance(data, dict):
        raise ValueError(f"team file {path}: expected a JSON object with keys {TEAM_FILE_KEYS}")
    unknown = sorted(set(data) - set(TEAM_FILE_KEYS))
    if unknown:
        raise ValueError(f"team file {path}: unknown key(s) {unknown}; expected {TEAM_FILE_KEYS}")
    kind = data.get("kind", "baseline")
    if kind not in TEAM_KINDS:
        raise ValueError(f"team file {path}: kind must be one of {TEAM_KINDS}, got {kind!r}")
    skills = data.get("skills", {}) or {}
    if not isinstance(skills, dict):
        raise ValueError(f"team file {path}: skills must be an object {{skill: source}}, got {skills!r}")
    sources = {}
    for name, source in skills.items():
        if not isinstance(source, str):
            raise ValueError(f"team file {path}: skills[{name!r}] must be a string, got {source!r}")
        sources[name] = _file_path(path, source, STP_KINDS)
    team_skills(kind, sources, where=f"team file {path}")
    decision = data.get("decision")
    if decision is not None:
        from ..decisions.match_decider import DECISION_CHOICES, check_actor_file

        if not isinstance(decision, str) or not decision:
            raise ValueError(f"team file {path}: decision must be {' or '.join(DECISION_CHOICES)} or an actor "
                             f"path, got {decision!r}")
        decision = _file_path(path, decision, DECISION_CHOICES)
        decision_spec(kind, decision, where=f"team file {path}")
        if decision not in DECISION_CHOICES:
            check_actor_file(decision, where=f"team file {path}: decision", task=decision_task(kind))
    return TeamFile(kind, sources, decision)


def resolve_team_option(value: str, sources: Any = (), where: str = "team",
                        decision: Any = None) -> tuple[str, Any, Any]:
    """(kind, skills spec or None, decision or None) for a team named on the command
    line: a kind of :data:`TEAM_KINDS` or a JSON team file (``*.json``,
    :func:`load_team_file`), with per-skill ``sources`` ((skill, source) pairs,
    :func:`parse_skill_source`) and a ``decision`` that win over the file's; the spec
    is :func:`team_skills`, None without sources."""
    team = load_team_file(value) if value.lower().endswith(".json") else TeamFile(value, {})
    merged = {**{k.replace("-", "_"): v for k, v in team.skills.items()}, **dict(sources)}  # later wins
    decision = team.decision if decision is None else decision
    if not merged:
        return team.kind, None, decision
    return team.kind, team_skills(team.kind, merged, where=where), decision


def controller_label(kind: Any, skills: Any = None) -> Any:
    """How a team appears in results: its kind, or {kind, skills} with sources."""
    if not isinstance(kind, str):
        return type(kind).__name__
    if skills is None or isinstance(skills, str):
        return kind
    return {"kind": kind, "skills": dict(skills)}


def decision_spec(kind: Any, decision: Any = None, where: str = "team") -> Any:
    """The carrier-decision spec a team of ``kind`` plays with: ``decision`` if given
    ("handcoded", "learned", an actor path or a decider / policy object), else
    "learned" for :data:`LEARNED_DECISION_KINDS` and None (the cost decision) otherwise.
    ValueError when a decision is given for a team without the passing plays."""
    if decision is not None and not (isinstance(kind, str) and kind in DECISION_KINDS):
        raise ValueError(f"{where}: a carrier decision ({decision!r}) needs a passing or attacking team "
                         f"({' or '.join(DECISION_KINDS)}), not {kind!r}")
    if decision is None and isinstance(kind, str) and kind in LEARNED_DECISION_KINDS:
        return "learned"
    return decision


def decision_task(kind: Any) -> str:
    """The decision task whose actors a team of ``kind`` plays: "attack-drill" for the
    attacking plays (:data:`ATTACK_KINDS`), "attack-3v2" for the passing plays."""
    from ..decisions.match_decider import DRILL_TASK, TASK

    return DRILL_TASK if kind in ATTACK_KINDS else TASK


def decision_label(kind: Any, decision: Any = None) -> Any:
    """How a team's carrier decision appears in results: "handcoded", "learned", a
    path, a type name, or None for teams without the passing plays."""
    spec = decision_spec(kind, decision) if isinstance(kind, str) else decision
    if not (isinstance(kind, str) and kind in DECISION_KINDS):
        return None
    if spec is None:
        return "handcoded"
    return str(spec) if isinstance(spec, (str, Path)) else type(spec).__name__


def team_spec(kind: str, skills: Any = None, decision: Any = None, where: str = "team") -> TeamSpec:
    """The :class:`~ssl_marl.plays.team.TeamSpec` of STP team ``kind`` (one of
    :data:`STP_KINDS`).

    ``skills``: a :mod:`~ssl_marl.plays.skillset` spec that replaces the kind's skills
    (see :func:`team_skills`). ``decision`` (passing and attacking kinds): the ball
    carrier's decision, "handcoded" (the cost decision, default), "learned" (the shipped
    actor of the kind's decision task, attack-3v2 or attack-drill; default of
    "passing-learned-decision"), an actor path, or a decider /
    decision-policy object (:func:`ssl_marl.decisions.match_decider.make_match_decider`,
    called once per spec: build one spec per team)."""
    from ..plays.team import TeamSpec

    if not (isinstance(kind, str) and kind in STP_KINDS):
        raise ValueError(f"{where}: a team spec needs an STP team ({' or '.join(STP_KINDS)}), not {kind!r}")
    decision = decision_spec(kind, decision, where=where)
    team_set = kind_skills(kind) if skills is None else skills
    if kind not in DECISION_KINDS:
        return TeamSpec(skills=team_set)
    decider = None
    if decision is not None:
        from ..decisions.match_decider import make_match_decider

        decider = make_match_decider(decision, where=f"{where} decision", task=decision_task(kind))
    if kind in ATTACK_KINDS:
        from ..plays.attack_play import attack_plays

        return TeamSpec(plays=attack_plays, skills=team_set, decider=decider)
    from ..plays.passing_play import passing_plays

    return TeamSpec(plays=passing_plays, skills=team_set, decider=decider)


def make_controller(kind: Any, team: str, n_robots: int, field: Any = "div_b", seed: int = 0,
                    skills: Any = None, decision: Any = None, robot: Any = None, ball: Any = None,
                    dt: float = 1.0 / 60.0, **options: Any) -> TeamController | Any:
    """Controller ``kind`` (one of :data:`TEAM_KINDS`) for ``team``.

    STP kinds: :func:`~ssl_marl.plays.team.build_team` of :func:`team_spec` (``skills``,
    ``decision``; ``options`` replace further :class:`~ssl_marl.plays.team.TeamSpec`
    fields: min_hold_s, adaptive, stickiness, plays) with ``robot`` / ``ball``
    parameters and control period ``dt`` (s).
    ``"random"`` / ``"idle"``: :class:`RandomController` / :class:`IdleController`. An
    object with ``act(env) -> {agent: action}`` and ``agents`` is passed through."""
    decision = decision_spec(kind, decision, where=team)
    if not isinstance(kind, str):
        if not (hasattr(kind, "act") and hasattr(kind, "agents")):
            raise ValueError(f"controller for {team} must be one of {TEAM_KINDS} or an object with act() and "
                             f"agents, got {kind!r}")
        return kind
    if kind in STP_KINDS:
        from ..plays.team import build_team

        spec = team_spec(kind, skills, decision, where=team)
        return build_team(replace(spec, **options) if options else spec, team, n_robots, field, robot, ball,
                          seed=seed, dt=dt)
    if skills is not None:
        raise ValueError(f"{team}: skill sources need an STP team ({' or '.join(STP_KINDS)}), not {kind!r}")
    if kind == "random":
        return RandomController(team, n_robots, seed=seed)
    if kind == "idle":
        return IdleController(team, n_robots)
    raise ValueError(f"unknown controller {kind!r} for {team}; expected one of {TEAM_KINDS}")


def kind_skills(kind: str) -> Any:
    """The skill set of STP team ``kind``: the kind itself ("learned" / "baseline"), or
    :func:`~ssl_marl.plays.skillset.team_skill_set` of its skill kind for a passing team
    (:data:`~ssl_marl.plays.skillset.TEAM_SKILLS`) or an attacking team
    (:data:`~ssl_marl.plays.skillset.ATTACK_SKILLS`: with the chip pass and the redirect)."""
    from ..plays.skillset import ATTACK_SKILLS, TEAM_SKILLS, team_skill_set

    if kind in PASSING_KINDS + ATTACK_KINDS:
        return team_skill_set(kind.split("-")[1], ATTACK_SKILLS if kind in ATTACK_KINDS else TEAM_SKILLS, where=kind)
    return kind
