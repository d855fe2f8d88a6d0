"""The outcome of a match, the summary of a series (plain data, JSON-ready), and how
result records are written to and read from disk."""

from __future__ import annotations

import csv
import gzip
import io
import json
import os
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np


@dataclass
class MatchResult:
    """Outcome of one match.

    Attributes:
        score: goals per team.
        goals: [{"team": scorer, "t": simulated time (s)}] in order.
        shots: kick events per team (every kick, not only shots on goal).
        possession: fraction of control steps in which a robot of the team held the
            ball on its dribbler (ground truth; the two may sum to less than 1).
        steps: control steps simulated. sim_time_s: simulated seconds. played_s: seconds on
            the match clock (the SSL format stops it during STOP; 0: not recorded, the
            simulated time counts).
        wall_time_s: wall-clock seconds for the whole match (env + controllers).
        act_time_ms: mean wall time of each team's ``act`` (ms).
        missed_deadlines: real-time mode: ticks whose command was lost, per team.
        seed: env seed. config: the match options.
        stats: per team, from :class:`~ssl_marl.plays.stats.MatchStatsTracker`: kicks,
            shots (kicks aimed at the goal), goals, passes attempted / completed /
            intercepted / lost, interceptions, pass_completion, and shots, goals and
            passes by kind (direct / redirect / after a chip pass; flat / chip);
            ``"events"``: the tracker's log of passes (with outcomes) and shots, in
            time order; ``"referee"`` (SSL game control on): counts of ball-out,
            no-progress, half-time, ``foul_<name>`` and ``command_<command>`` events.
    """

    score: dict[str, int]
    goals: list[dict] = field(default_factory=list)
    shots: dict[str, int] = field(default_factory=dict)
    possession: dict[str, float] = field(default_factory=dict)
    steps: int = 0
    sim_time_s: float = 0.0
    played_s: float = 0.0
    wall_time_s: float = 0.0
    act_time_ms: dict[str, float] = field(default_factory=dict)
    missed_deadlines: dict[str, int] = field(default_factory=dict)
    seed: int = 0
    config: dict = field(default_factory=dict)
    stats: dict = field(default_factory=dict)

    @property
    def winner(self) -> str | None:
        """"blue", "yellow" or None for a draw."""
        b, y = self.score.get("blue", 0), self.score.get("yellow", 0)
        return None if b == y else ("blue" if b > y else "yellow")

    def to_dict(self) -> dict:
        d = asdict(self)
        d["winner"] = self.winner
        return d


def summarize(results: list[MatchResult]) -> dict:
    """Table summary from blue's side: wins / draws / losses, goals for / against, ...;
    ``statistics``: :func:`~ssl_marl.runners.statistics.series_statistics` (win rate and
    goal difference per match and per 600 s with 95 % intervals); ``stats``: per-team
    totals of the match statistics (:func:`~ssl_marl.plays.stats.summarize_stats`)."""
    from ..plays.stats import summarize_stats
    from .statistics import series_statistics

    n = len(results)
    wins = sum(r.winner == "blue" for r in results)
    losses = sum(r.winner == "yellow" for r in results)
    gf = sum(r.score["blue"] for r in results)
    ga = sum(r.score["yellow"] for r in results)
    mean = (lambda xs: float(np.mean(xs)) if xs else 0.0)
    return {"matches": n, "blue": results[0].config.get("blue") if n else None,
            "yellow": results[0].config.get("yellow") if n else None,
            "wins": wins, "draws": n - wins - losses, "losses": losses, "goals_for": gf, "goals_against": ga,
            "goal_diff_mean": (gf - ga) / n if n else 0.0,
            "shots_blue_mean": mean([r.shots["blue"] for r in results]),
            "shots_yellow_mean": mean([r.shots["yellow"] for r in results]),
            "possession_blue_mean": mean([r.possession["blue"] for r in results]),
            "possession_yellow_mean": mean([r.possession["yellow"] for r in results]),
            "missed_deadlines_blue": sum(r.missed_deadlines["blue"] for r in results),
            "missed_deadlines_yellow": sum(r.missed_deadlines["yellow"] for r in results),
            "wall_time_s_total": float(sum(r.wall_time_s for r in results)),
            "statistics": series_statistics([r.score["blue"] for r in results], [r.score["yellow"] for r in results],
                                            [_played_s(r) for r in results]) if n else None,
            "stats": summarize_stats([r.stats for r in results if r.stats])}


def _played_s(r: MatchResult) -> float:
    """Seconds of play of a match (:func:`~ssl_marl.runners.statistics.played_seconds`)."""
    from .statistics import played_seconds

    return played_seconds(r.played_s, r.sim_time_s, r.config.get("seconds"))


# ------------------------------------------------------------------ result records on disk
#
# A result folder holds ``results.json`` (the summary), ``manifest.json`` (provenance,
# :mod:`.provenance`) and the per-episode (per-run, per-match) rows as a gzip CSV whose
# name ``results.json`` gives under ``rows_file``. Every CSV cell is one JSON value
# (floats in their shortest exact form, lists and dicts as JSON); an empty cell means the
# row has no such field, so the rows load back equal to what was written.

ROWS_FILES = {"episodes_detail": "episodes.csv.gz", "runs_detail": "runs.csv.gz", "matches": "matches.csv.gz"}


def encode_rows(rows: list[dict[str, Any]]) -> bytes:
    """Rows (dicts of JSON values) as gzip CSV bytes; the header is every key in order of
    first appearance; the bytes do not depend on the date (gzip mtime 0)."""
    columns: dict[str, None] = {}
    for r in rows:
        columns.update(dict.fromkeys(r))
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(columns)
    for r in rows:
        w.writerow(["" if c not in r else json.dumps(r[c], default=_json_default, allow_nan=True) for c in columns])
    return gzip.compress(buf.getvalue().encode(), compresslevel=9, mtime=0)


def decode_rows(data: bytes) -> list[dict[str, Any]]:
    """Inverse of :func:`encode_rows`."""
    reader = csv.reader(io.StringIO(gzip.decompress(data).decode()))
    header = next(reader, [])
    return [{c: json.loads(v) for c, v in zip(header, line) if v != ""} for line in reader]


def write_result_folder(out: str | os.PathLike, summary: dict[str, Any], manifest: dict[str, Any]) -> Path:
    """Write ``out/results.json`` (``summary`` without its row list), the rows file and
    ``out/manifest.json``, each atomically; returns the folder. The row list is the
    summary's ``episodes_detail``, ``runs_detail`` or ``matches`` entry (:data:`ROWS_FILES`)."""
    from ..io import atomic_write_bytes, atomic_write_json
    from .provenance import MANIFEST_FILE

    out = Path(out)
    head, key, rows = _split_rows(summary)
    if key is not None:
        head["rows_key"], head["rows_file"] = key, ROWS_FILES[key]
        atomic_write_bytes(out / ROWS_FILES[key], encode_rows(rows))
    atomic_write_json(out / "results.json", head)
    atomic_write_json(out / MANIFEST_FILE, manifest)
    return out


def result_stem(path: str | os.PathLike) -> str:
    """A JSON result file's name without ``.json``: the stem of the files written beside it."""
    name = Path(path).name
    return name[:-5] if name.lower().endswith(".json") else name


def manifest_path(path: str | os.PathLike) -> Path:
    """The manifest beside a JSON result file (a series or a single match):
    ``<stem>.manifest.json``."""
    return Path(path).parent / f"{result_stem(path)}.manifest.json"


def write_series_file(path: str | os.PathLike, summary: dict[str, Any], matches: list[dict[str, Any]],
                      manifest: dict[str, Any]) -> Path:
    """A match series as ``path`` (JSON: ``summary``, ``rows_file``, ``manifest_file``)
    with ``<stem>.matches.csv.gz`` and ``<stem>.manifest.json`` beside it, each atomically."""
    from ..io import atomic_write_bytes, atomic_write_json

    path = Path(path)
    rows_file, manifest_file = f"{result_stem(path)}.matches.csv.gz", manifest_path(path).name
    atomic_write_bytes(path.parent / rows_file, encode_rows(matches))
    atomic_write_json(path.parent / manifest_file, manifest)
    atomic_write_json(path, {"summary": summary, "rows_key": "matches", "rows_file": rows_file,
                             "manifest_file": manifest_file})
    return path


def load_result(path: str | os.PathLike) -> dict[str, Any]:
    """A result folder (or a series file) as one dict with its rows back under their key;
    records that keep the rows inside ``results.json`` load as they are."""
    path = Path(path)
    file = path / "results.json" if path.is_dir() else path
    data = json.loads(file.read_text())
    if "rows_file" in data:
        data[data.pop("rows_key")] = decode_rows((file.parent / data.pop("rows_file")).read_bytes())
        data.pop("manifest_file", None)
    return data


def load_manifest(path: str | os.PathLike) -> dict[str, Any] | None:
    """The manifest of a result folder or series file (None when it has none)."""
    from .provenance import MANIFEST_FILE

    path = Path(path)
    if path.is_dir():
        f = path / MANIFEST_FILE
    else:
        f = path.parent / json.loads(path.read_text()).get("manifest_file", manifest_path(path).name)
    return json.loads(f.read_text()) if f.exists() else None


def _split_rows(summary: dict[str, Any]) -> tuple[dict[str, Any], str | None, list]:
    for key in ROWS_FILES:
        if key in summary:
            return {k: v for k, v in summary.items() if k != key}, key, summary[key]
    return dict(summary), None, []


def _json_default(o: Any) -> Any:
    if isinstance(o, np.generic):
        return o.item()
    if isinstance(o, np.ndarray):
        return o.tolist()
    raise TypeError(f"not JSON serialisable: {type(o).__name__}")
