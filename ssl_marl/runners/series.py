"""Series of matches spread over worker processes or a Ray cluster: :func:`play_series`."""

from __future__ import annotations

from typing import Any

from .match import play_match
from .pool import run_pool, validate_backend
from .result import MatchResult, summarize


def _series_worker(job: tuple[int, dict]) -> tuple[int, MatchResult]:
    i, kwargs = job
    return i, play_match(**kwargs)


def play_series(blue: Any = "baseline", yellow: Any = "baseline", matches: int = 10, workers: int | None = 1,
                seed: int = 0, progress: bool = True, backend: str = "local", address: str | None = None,
                **match_kwargs: Any) -> tuple[list[MatchResult], dict]:
    """Play ``matches`` matches (match i with seed ``seed + i``).

    ``match_kwargs`` go to :func:`~ssl_marl.runners.match.play_match` (robots, field,
    seconds, realism, realtime, blue_skills, ...; ``render`` is not allowed: render
    single matches). ``workers``, ``backend`` and ``address`` pick the pool
    (:func:`~ssl_marl.runners.pool.run_pool`); results do not depend on them.
    Returns ``(results in match order, summary)`` with the summary of
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
    jobs = [(i, dict(blue=blue, yellow=yellow, seed=seed + i, progress=False, **match_kwargs))
            for i in range(matches)]
    done = run_pool(_series_worker, jobs, workers, f"{blue} vs {yellow}", progress, unit="match",
                    backend=backend, address=address)
    results = [r for _, r in done]
    return results, summarize(results)


def _check_decisions(blue: Any, yellow: Any, match_kwargs: dict) -> None:
    """Load the carrier decisions once here (a missing or mismatched actor fails with
    one error before any worker starts)."""
    from .controllers import decision_spec

    for team, kind in (("blue", blue), ("yellow", yellow)):
        spec = decision_spec(kind, match_kwargs.get(f"{team}_decision"), team)
        if spec is not None:
            from ..decisions.match_decider import make_match_decider

            make_match_decider(spec, where=f"{team} decision")


def _check_teams(blue: Any, yellow: Any, match_kwargs: dict) -> None:
    """Build the STP teams' learned skills once here, so that a bad checkpoint fails
    with one error before any worker starts."""
    from ..physics.field import FieldGeometry
    from ..plays.skillset import check_skills

    field = FieldGeometry.from_name(match_kwargs.get("field", "div_b"))
    for kind, skills in ((blue, match_kwargs.get("blue_skills")), (yellow, match_kwargs.get("yellow_skills"))):
        if isinstance(kind, str) and kind in ("learned", "baseline"):
            check_skills(kind if skills is None else skills, field)
