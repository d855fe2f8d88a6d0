"""A league of teams: scheduled matches, ratings with uncertainty, a results matrix.

:func:`play_league` plays a round-robin schedule (:func:`schedule`) among teams named
like ``ssl-marl match`` teams (a kind of :data:`~ssl_marl.runners.controllers.TEAM_KINDS`
or a JSON team file), through the worker pool (:func:`~ssl_marl.runners.pool.run_pool`),
and rates every team with the Plackett-Luce model of Weng and Lin (2011), "A Bayesian
approximation method for online ranking", JMLR 12, as implemented by the ``openskill``
package (the ``league`` extra): each match is a two-team game whose lower score ranks
second; equal scores are a tie. A team's rating is ``mu`` and ``sigma`` (skill units,
25 and 25/3 before any match); ``ordinal = mu - 3 sigma`` orders the table.

The output folder holds ``league.json`` (the arguments, every played match with its
seed and score, ratings, the results matrix and a manifest), ``ratings.md`` (the table
by ordinal) and ``matrix.png`` (mean goal difference per pair). ``league.json`` is
rewritten atomically after each chunk of matches (each match with the sha256 of the source its
worker ran, ``code``: workers start afresh for every chunk), so an interrupted league resumes:
a rerun with the same arguments plays only the missing matches, and a rerun with more
``rounds`` (the other arguments the same) extends the league, whose schedule begins with the
shorter one's; other arguments on the same folder are an error. When a rerun's command or
commit differs from the stored manifest's, that manifest is kept in ``earlier_manifests``, so
every match's code stays on record. Ratings are recomputed from the stored matches in schedule
order, so a resumed league rates exactly as an uninterrupted one.

Training draws its opponents from a league by prioritized fictitious self-play
(:mod:`ssl_marl.decisions.pfsp`, used by :class:`~ssl_marl.decisions.attack_match.AttackMatchEnv`).
"""

from __future__ import annotations

import os
import warnings
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any, Sequence

import numpy as np

from ..io import atomic_savefig, atomic_write_bytes, atomic_write_json, episode_seed, prepare_output_dir
from .match import format_options, play_match
from .pool import run_pool, validate_backend

LEAGUE_FILE = "league.json"
RATINGS_FILE = "ratings.md"
MATRIX_FILE = "matrix.png"
#: colour schemes of the schedule: "alternate" (each pair once per round, colours swapped
#: from round to round) or "both" (each ordered pair once per round: both colours)
COLOURS = ("alternate", "both")


@dataclass(frozen=True)
class LeagueConfig:
    """The arguments that define a league (a resumed league must match them).

    Attributes:
        teams: team names: kinds or JSON team files, at least two, all different.
        rounds: round-robin rounds.
        colours: "alternate" or "both" (:data:`COLOURS`).
        seed: league seed; match i uses ``ssl_marl.io.episode_seed(seed, i)``.
        seconds: simulated match length (s).
        robots: robots per team.
        field: "div_a" or "div_b".
        realism: "none" or "realistic".
        match_format: "ssl" (two halves, referee commands, fouls) or "plain".
    """

    teams: tuple[str, ...]
    rounds: int = 1
    colours: str = "alternate"
    seed: int = 0
    seconds: float = 600.0
    robots: int = 6
    field: str = "div_b"
    realism: str = "none"
    match_format: str = "ssl"

    def to_json(self) -> dict[str, Any]:
        d = asdict(self)
        d["teams"] = list(self.teams)
        d["seconds"] = float(self.seconds)
        return d


def validate_config(config: LeagueConfig) -> None:
    """Clear ValueErrors (or FileNotFoundError for a missing team file) before any match."""
    from .controllers import TEAM_KINDS, resolve_team_option

    teams = list(config.teams)
    if len(teams) < 2:
        raise ValueError(f"a league needs at least two teams, got {teams}")
    if len(set(teams)) != len(teams):
        raise ValueError(f"each team may appear once, got {teams}")
    for t in teams:
        if not isinstance(t, str) or (t not in TEAM_KINDS and not t.lower().endswith(".json")):
            raise ValueError(f"unknown team {t!r}: use one of {TEAM_KINDS} or a JSON team file ending in .json")
        resolve_team_option(t, (), where=f"team {t}")
    if not isinstance(config.rounds, int) or isinstance(config.rounds, bool) or config.rounds < 1:
        raise ValueError(f"rounds must be a positive integer, got {config.rounds!r}")
    if config.colours not in COLOURS:
        raise ValueError(f"colours must be one of {COLOURS}, got {config.colours!r}")
    if not (isinstance(config.seconds, (int, float)) and np.isfinite(config.seconds) and config.seconds > 0):
        raise ValueError(f"seconds must be a positive number, got {config.seconds!r}")
    format_options(config.match_format, config.seconds)  # raises for an unknown format


def schedule(config: LeagueConfig) -> list[dict[str, Any]]:
    """The league's matches in order: ``{"index", "round", "blue", "yellow", "seed"}``.

    Each round visits the pairs (i, j), i < j, in team order; "alternate" plays one
    match per pair, team i blue in even rounds (from 0) and yellow in odd ones; "both"
    plays i blue then j blue. Match ``index``'s seed is ``episode_seed(config.seed, index)``.
    """
    teams = list(config.teams)
    out: list[dict[str, Any]] = []
    for r in range(config.rounds):
        for i in range(len(teams)):
            for j in range(i + 1, len(teams)):
                pairs = [(teams[i], teams[j]), (teams[j], teams[i])] if config.colours == "both" else \
                    [(teams[i], teams[j]) if r % 2 == 0 else (teams[j], teams[i])]
                for blue, yellow in pairs:
                    k = len(out)
                    out.append({"index": k, "round": r, "blue": blue, "yellow": yellow,
                                "seed": episode_seed(config.seed, k)})
    return out


def _league_worker(job: tuple[dict, dict]) -> dict[str, Any]:
    """Play one scheduled match; return the match entry with its score and ``code``, the
    sha256 of the package source the worker ran (:func:`~ssl_marl.runners.provenance.code_hash`:
    the pool starts new workers for each chunk, so a league resumed or extended across code
    changes records which matches ran which code)."""
    from .controllers import resolve_team_option
    from .provenance import code_hash

    entry, match_kwargs = job
    blue, blue_skills, blue_decision = resolve_team_option(entry["blue"], (), where="blue")
    yellow, yellow_skills, yellow_decision = resolve_team_option(entry["yellow"], (), where="yellow")
    res = play_match(blue=blue, yellow=yellow, blue_skills=blue_skills, yellow_skills=yellow_skills,
                     blue_decision=blue_decision, yellow_decision=yellow_decision,
                     seed=entry["seed"], progress=False, **match_kwargs)
    return {**entry, "score": {"blue": int(res.score["blue"]), "yellow": int(res.score["yellow"])},
            "sim_time_s": float(res.sim_time_s), "played_s": float(res.played_s), "code": code_hash()}


def match_kwargs(config: LeagueConfig) -> dict[str, Any]:
    """:func:`~ssl_marl.runners.match.play_match` options shared by the league's matches."""
    return dict(robots=config.robots, field=config.field, seconds=float(config.seconds), realism=config.realism,
                env_kwargs=format_options(config.match_format, config.seconds))


def load_state(out: str | os.PathLike, config: LeagueConfig) -> tuple[list[dict[str, Any]], list[dict[str, Any]]]:
    """The matches already played in ``out`` and the manifests of the runs that played them
    (both empty for a new folder); ValueError when the folder holds a league with other
    arguments (more ``rounds`` than stored extend it; fewer are an error)."""
    path = Path(out) / LEAGUE_FILE
    if not path.is_file():
        return [], []
    import json

    try:
        state = json.loads(path.read_text())
        stored = state["config"]
    except (json.JSONDecodeError, KeyError, TypeError):
        raise ValueError(f"{path} is not a league file; give another --out") from None
    mine = config.to_json()
    diff = sorted(k for k in set(stored) | set(mine) if stored.get(k) != mine.get(k))
    extends = diff == ["rounds"] and isinstance(stored.get("rounds"), int) and stored["rounds"] < mine["rounds"]
    if diff and not extends:
        raise ValueError(f"{path} holds a league with other arguments ({', '.join(diff)}: "
                         + "; ".join(f"{k} {stored.get(k)!r} there, {mine.get(k)!r} here" for k in diff)
                         + "); use the same arguments to resume (or more --rounds to extend it) or another --out")
    matches = list(state.get("matches", []))
    plan = {m["index"]: m for m in schedule(config)}
    for m in matches:
        want = plan.get(m.get("index"))
        if want is None or any(m.get(k) != want[k] for k in ("blue", "yellow", "seed")):
            raise ValueError(f"{path}: stored match {m.get('index')!r} is not the schedule's; give another --out")
    manifests = list(state.get("earlier_manifests", []))
    if state.get("manifest") is not None:
        manifests.append(state["manifest"])
    return matches, manifests


def play_league(config: LeagueConfig, out: str | os.PathLike, workers: int | None = 1, backend: str = "local",
                address: str | None = None, progress: bool = True, chunk: int | None = None,
                argv: list[str] | None = None) -> dict[str, Any]:
    """Play (or resume) the league in ``out``; return the ``league.json`` content.

    Args:
        config: the league (:class:`LeagueConfig`).
        out: output folder (created; an existing league there resumes).
        workers, backend, address: the pool (:func:`~ssl_marl.runners.pool.run_pool`);
            results do not depend on them.
        progress: a tqdm bar over the league's matches.
        chunk: matches per pool call, after each of which the state is saved
            (default two per worker, 16 on a Ray cluster of unknown size).
        argv: the command recorded in the manifest (default ``sys.argv``).
    """
    validate_config(config)
    validate_backend(backend, workers, address)
    folder = prepare_output_dir(out, "league folder")
    stored, manifests = load_state(folder, config)
    played = {m["index"]: m for m in stored}
    plan = schedule(config)
    todo = [m for m in plan if m["index"] not in played]
    kwargs = match_kwargs(config)
    size = chunk or (2 * workers if workers else 16)
    import sys

    from tqdm.auto import tqdm

    with tqdm(total=len(plan), initial=len(plan) - len(todo), desc="league", unit="match", disable=not progress,
              file=sys.stderr) as bar:
        for s in range(0, len(todo), size):
            part = todo[s:s + size]
            for m in run_pool(_league_worker, [(e, kwargs) for e in part], workers, "league", False,
                              unit="match", backend=backend, address=address):
                played[m["index"]] = m
            state = league_state(config, [played[i] for i in sorted(played)], argv, manifests)
            atomic_write_json(folder / LEAGUE_FILE, state)
            bar.update(len(part))
    state = league_state(config, [played[i] for i in sorted(played)], argv, manifests)
    atomic_write_json(folder / LEAGUE_FILE, state)
    atomic_write_bytes(folder / RATINGS_FILE, ratings_markdown(state).encode())
    write_matrix_plot(state, folder / MATRIX_FILE)
    return state


def league_state(config: LeagueConfig, matches: list[dict[str, Any]], argv: list[str] | None = None,
                 earlier: Sequence[dict[str, Any]] = ()) -> dict:
    """``league.json``'s content from the matches played so far (in schedule order);
    ``earlier``: manifests of the runs that played stored matches, kept in
    ``earlier_manifests`` unless their command and commit are this run's."""
    from .controllers import load_team_file
    from .provenance import build_manifest

    matches = sorted(matches, key=lambda m: m["index"])
    rules = {k: v for k, v in config.to_json().items() if k not in ("seed", "rounds")}
    files = {t: load_team_file(t)._asdict() for t in config.teams if t.lower().endswith(".json")}
    if files:  # the team files' kinds, skill sources and decisions (their checkpoints are hashed)
        rules["team_files"] = files
    manifest = build_manifest(rules, {"seed": config.seed, "rounds": config.rounds,
                                      "match_seed": "ssl_marl.io.episode_seed(seed, match index)"},
                              argv=argv)
    same = lambda m: m.get("command") == manifest.get("command") and m.get("git") == manifest.get("git")  # noqa: E731
    kept = [m for i, m in enumerate(earlier) if not (i == len(earlier) - 1 and same(m))]
    state = {"config": config.to_json(), "scheduled": len(schedule(config)), "played": len(matches),
             "matches": matches, "ratings": rate(config.teams, matches),
             "matrix": results_matrix(config.teams, matches), "manifest": manifest}
    if kept:
        state["earlier_manifests"] = kept
    return state


def rate(teams: Sequence[str], matches: Sequence[dict[str, Any]]) -> list[dict[str, Any]]:
    """Plackett-Luce ratings of ``teams`` after ``matches`` (applied in the given order).

    Returns one row per team, by ordinal (best first), ties by team order:
    ``{"team", "mu", "sigma", "ordinal", "matches", "wins", "draws", "losses",
    "goals_for", "goals_against"}``.
    """
    from openskill.models import PlackettLuce

    model = PlackettLuce()
    ratings = {t: model.rating(name=t) for t in teams}
    for m in matches:
        b, y = m["score"]["blue"], m["score"]["yellow"]
        [[rb], [ry]] = model.rate([[ratings[m["blue"]]], [ratings[m["yellow"]]]],
                                  ranks=[0 if b >= y else 1, 0 if y >= b else 1])
        ratings[m["blue"]], ratings[m["yellow"]] = rb, ry
    rows = [{"team": t, "mu": float(ratings[t].mu), "sigma": float(ratings[t].sigma),
             "ordinal": float(ratings[t].ordinal()), **team_series(t, matches)} for t in teams]
    order = {t: i for i, t in enumerate(teams)}
    return sorted(rows, key=lambda r: (-r["ordinal"], order[r["team"]]))


def team_series(team: str, matches: Sequence[dict[str, Any]]) -> dict[str, Any]:
    """``team``'s matches of a league (either colour) through the one statistics helper
    (:func:`~ssl_marl.runners.statistics.series_statistics`): wins, draws, losses, goals,
    the win rate with its Wilson 95 % interval and the goal difference per 600 s with its
    t 95 % interval (each match scaled by its match clock ``played_s``, else its ``sim_time_s``)."""
    from .statistics import played_seconds, series_statistics

    gf, ga, secs = [], [], []
    for m in matches:
        for side, opp in (("blue", "yellow"), ("yellow", "blue")):
            if m[side] == team:
                gf.append(m["score"][side])
                ga.append(m["score"][opp])
                secs.append(played_seconds(m.get("played_s"), m.get("sim_time_s")))
    st = series_statistics(gf, ga, secs)
    keys = ("matches", "wins", "draws", "losses", "goals_for", "goals_against", "win_rate", "win_rate_ci95",
            "goal_diff_per_600s", "goal_diff_per_600s_ci95")
    return {k: st[k] for k in keys}


def results_matrix(teams: Sequence[str], matches: Sequence[dict[str, Any]]) -> dict[str, dict[str, dict]]:
    """Per ordered pair, from the row team's view, both colours together:
    ``matrix[a][b] = {"matches", "wins", "draws", "losses", "goal_diff", "mean_goal_diff"}``
    (goal_diff: a's goals minus b's over their matches; mean None without a match)."""
    cell = lambda: dict(matches=0, wins=0, draws=0, losses=0, goal_diff=0, mean_goal_diff=None)  # noqa: E731
    matrix = {a: {b: cell() for b in teams if b != a} for a in teams}
    for m in matches:
        b, y = m["score"]["blue"], m["score"]["yellow"]
        for row, col, d in ((m["blue"], m["yellow"], b - y), (m["yellow"], m["blue"], y - b)):
            c = matrix[row][col]
            c["matches"] += 1
            c["wins" if d > 0 else "losses" if d < 0 else "draws"] += 1
            c["goal_diff"] += d
            c["mean_goal_diff"] = c["goal_diff"] / c["matches"]
    return matrix


def win_probabilities(state: dict[str, Any], team: str) -> dict[str, float]:
    """``team``'s win probability against each other team of a league state, from the
    results matrix: (wins + draws / 2) / matches; 0.5 against a team not yet met."""
    row = state["matrix"][team]
    return {o: (c["wins"] + 0.5 * c["draws"]) / c["matches"] if c["matches"] else 0.5 for o, c in row.items()}


def ratings_markdown(state: dict[str, Any]) -> str:
    """The ratings table (Markdown) of a league state, sorted by ordinal."""
    c = state["config"]
    lines = ["# League ratings\n",
             f"{state['played']} of {state['scheduled']} matches of {c['seconds']:g} s ({c['match_format']} format, "
             f"{c['robots']} robots, {c['field']}, realism {c['realism']}), {c['rounds']} round(s), colours "
             f"{c['colours']}, seed {c['seed']}. Plackett-Luce ratings (openskill): ordinal = mu - 3 sigma.\n",
             "| rank | team | ordinal | mu | sigma | matches | W | D | L | win rate [95% CI] | goals "
             "| goal diff per 600 s [95% CI] |",
             "|---:|---|---:|---:|---:|---:|---:|---:|---:|---|---|---|"]
    for k, r in enumerate(state["ratings"], 1):
        st = team_series(r["team"], state["matches"])  # also for league files written before these keys
        wr, (wlo, whi) = st["win_rate"], st["win_rate_ci95"]
        gd, (glo, ghi) = st["goal_diff_per_600s"], st["goal_diff_per_600s_ci95"]
        rate_cell = f"{100 * wr:.0f} % [{100 * wlo:.0f}, {100 * whi:.0f}]" if st["matches"] else "-"
        gd_cell = f"{gd:+.2f} [{glo:+.2f}, {ghi:+.2f}]" if st["matches"] > 1 else "-"
        lines.append(f"| {k} | {r['team']} | {r['ordinal']:.2f} | {r['mu']:.2f} | {r['sigma']:.2f} | {st['matches']} "
                     f"| {st['wins']} | {st['draws']} | {st['losses']} | {rate_cell} "
                     f"| {st['goals_for']}-{st['goals_against']} | {gd_cell} |")
    return "\n".join(lines) + "\n"


def write_matrix_plot(state: dict[str, Any], path: str | os.PathLike, dpi: int = 100) -> None:
    """Heat map of the mean goal difference per match (row team minus column team), teams
    in rating order, written atomically; each cell is annotated with W-D-L."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    teams = [r["team"] for r in state["ratings"]]
    labels = [Path(t).stem if t.lower().endswith(".json") else t for t in teams]  # a team file by its name
    n = len(teams)
    values = np.full((n, n), np.nan)
    for i, a in enumerate(teams):
        for j, b in enumerate(teams):
            if a != b and state["matrix"][a][b]["mean_goal_diff"] is not None:
                values[i, j] = state["matrix"][a][b]["mean_goal_diff"]
    lim = max(1.0, float(np.nanmax(np.abs(values))) if np.isfinite(values).any() else 1.0)
    longest = max(len(t) for t in labels)
    fig = Figure(figsize=(2.2 + 1.1 * n + 0.08 * longest, 1.6 + 0.9 * n + 0.05 * longest), dpi=dpi)
    FigureCanvasAgg(fig)
    ax = fig.add_subplot(1, 1, 1)
    im = ax.imshow(np.ma.masked_invalid(values), cmap="RdBu", vmin=-lim, vmax=lim)
    for i, a in enumerate(teams):
        for j, b in enumerate(teams):
            if a != b:
                c = state["matrix"][a][b]
                text = f"{values[i, j]:+.1f}\n{c['wins']}-{c['draws']}-{c['losses']}" if c["matches"] else "-"
                ax.text(j, i, text, ha="center", va="center", fontsize=8)
    ax.set_xticks(range(n), labels, rotation=30, ha="right", fontsize=8)
    ax.set_yticks(range(n), labels, fontsize=8)
    ax.set_xlabel("opponent")
    ax.set_title(f"mean goal difference per match (row - column), W-D-L; {state['played']} matches", fontsize=9)
    fig.colorbar(im, ax=ax, label="goals per match")
    with warnings.catch_warnings():  # a figure too small for its labels is still written
        warnings.simplefilter("ignore", UserWarning)
        fig.tight_layout()
    atomic_savefig(fig, path)
