"""Series of matches spread over worker processes or a Ray cluster: :func:`play_series`."""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any

from .match import play_match
from .pool import run_pool, validate_backend
from .result import MatchResult, summarize


def _series_worker(job: tuple[int, dict, str | None, str]) -> tuple[int, MatchResult]:
    i, kwargs, keep_dir, key = job
    result = play_match(**kwargs)
    if keep_dir is not None:  # kept at once: an interrupted series loses only the matches in play
        from ..io import atomic_write_json

        atomic_write_json(Path(keep_dir) / f"match_{kwargs['seed']}.json", {"key": key, "result": result.to_dict()})
    return i, result


def match_key(kwargs: dict) -> str:
    """The options of one series match as a canonical string (a kept match is reused only
    for exactly these options)."""
    return json.dumps({k: (v if isinstance(v, (str, int, float, bool, type(None))) else repr(v))
                       for k, v in sorted(kwargs.items()) if k != "progress"}, sort_keys=True)


def load_kept_match(keep_dir: str | os.PathLike, seed: int, key: str) -> MatchResult | None:
    """The kept result of the match with ``seed`` (None when not played yet); ValueError
    when the folder holds that match with other options."""
    f = Path(keep_dir) / f"match_{seed}.json"
    if not f.exists():
        return None
    data = json.loads(f.read_text())
    if data.get("key") != key:
        raise ValueError(f"keep_dir: {f} holds match seed {seed} played with other options; use another folder "
                         f"or delete it")
    d = {k: v for k, v in data["result"].items() if k != "winner"}
    return MatchResult(**d)


def play_series(blue: Any = "baseline", yellow: Any = "baseline", matches: int = 10, workers: int | None = 1,
                seed: int = 0, progress: bool = True, backend: str = "local", address: str | None = None,
                keep_dir: str | os.PathLike | None = None, **match_kwargs: Any) -> tuple[list[MatchResult], dict]:
    """Play ``matches`` matches (match i with seed ``seed + i``).

    ``match_kwargs`` go to :func:`~ssl_marl.runners.match.play_match` (robots, field,
    seconds, realism, realtime, blue_skills, ...; ``render`` is not allowed: render
    single matches). ``workers``, ``backend`` and ``address`` pick the pool
    (:func:`~ssl_marl.runners.pool.run_pool`); results do not depend on them.
    ``keep_dir``: each finished match is written there at once (``match_<seed>.json``,
    atomically) and a rerun with the same options plays only the matches not kept yet, so
    a long series resumes after an interruption (a kept match with other options is an
    error). Returns ``(results in match order, summary)`` with the summary of
    :func:`~ssl_marl.runners.result.summarize`.
    """
    if not isinstance(matches, int) or isinstance(matches, bool) or matches < 1:
        raise ValueError(f"matches must be a positive integer, got {matches!r}")
    validate_backend(backend, workers, address)
    if match_kwargs.get("render") is not None:
        raise ValueError("play_series does not render; use play_match(render=...) for a video")
    match_kwargs.pop("render", None)
    if any(isinstance(k, str) and k in ("learned", "baseline") for k in (blue, yellow)):
        _check_teams(blue, yellow, match_kwargs)
    _check_decisions(blue, yellow, match_kwargs)
    results: list[MatchResult | None] = [None] * matches
    jobs = []
    keep = None if keep_dir is None else str(keep_dir)
    if keep is not None:
        Path(keep).mkdir(parents=True, exist_ok=True)
    for i in range(matches):
        kwargs = dict(blue=blue, yellow=yellow, seed=seed + i, progress=False, **match_kwargs)
        key = match_key(kwargs)
        kept = None if keep is None else load_kept_match(keep, seed + i, key)
        if kept is None:
            jobs.append((i, kwargs, keep, key))
        results[i] = kept
    if jobs:
        done = run_pool(_series_worker, jobs, workers, f"{blue} vs {yellow}", progress, unit="match",
                        backend=backend, address=address)
        for i, r in done:
            results[i] = r
    return results, summarize(results)


def _check_decisions(blue: Any, yellow: Any, match_kwargs: dict) -> None:
    """Load the carrier decisions once here (a missing or mismatched actor fails with
    one error before any worker starts)."""
    from .controllers import decision_spec, decision_task

    for team, kind in (("blue", blue), ("yellow", yellow)):
        spec = decision_spec(kind, match_kwargs.get(f"{team}_decision"), team)
        if spec is not None:
            from ..decisions.match_decider import make_match_decider

            make_match_decider(spec, where=f"{team} decision", task=decision_task(kind))


def _check_teams(blue: Any, yellow: Any, match_kwargs: dict) -> None:
    """Build the STP teams' learned skills once here, so that a bad checkpoint fails
    with one error before any worker starts."""
    from ..physics.field import FieldGeometry
    from ..plays.skillset import check_skills

    field = FieldGeometry.from_name(match_kwargs.get("field", "div_b"))
    for kind, skills in ((blue, match_kwargs.get("blue_skills")), (yellow, match_kwargs.get("yellow_skills"))):
        if isinstance(kind, str) and kind in ("learned", "baseline"):
            check_skills(kind if skills is None else skills, field)
