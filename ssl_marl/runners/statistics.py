"""The statistics every series, evaluation and league reports: one place for intervals.

* :func:`t_interval`: two-sided Student-t interval for a mean (goal difference per
  match, episode durations).
* :func:`wilson_interval`: Wilson score interval for a rate (success, win, pass
  completion).
* :func:`time_summary`: mean, spread and percentiles of times (s).
* :func:`series_statistics`: a match series from one side's view: wins / draws /
  losses, goals, and the goal difference per match and per 600 s of play (SSL's
  two halves of 300 s) with its 95 % interval.

Why intervals: a strong SSL team scores 4-10 goals per 600 s against a weak one and
even top teams about 2 in all (docs/references.md, "SSL rules"); short or few
matches end level by chance, so comparisons quote the goal difference's interval.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

SSL_MATCH_S = 600.0  #: s of play in an SSL match (two halves of 300 s)
Z95 = 1.959964  #: two-sided 95 % normal quantile (7 significant digits)


def played_seconds(played_s: float | None, sim_time_s: float | None, configured_s: float | None = None) -> float:
    """Seconds of play of one match (what its goals count per): its match clock ``played_s``
    (the SSL format stops it during STOP), else its simulated time, else its configured
    length, else :data:`SSL_MATCH_S` (records that lack the newer fields)."""
    return float(played_s or sim_time_s or configured_s or SSL_MATCH_S)


def t_interval(values: Sequence[float], conf: float = 0.95) -> tuple[float, float]:
    """Two-sided Student-t confidence interval for the mean of ``values`` ((nan, nan)
    for none; (x, x) for one value)."""
    if not 0.0 < conf < 1.0:
        raise ValueError(f"conf must lie in (0, 1), got {conf!r}")
    a = np.asarray(values, float)
    n = a.size
    if n == 0:
        return (math.nan, math.nan)
    m = float(a.mean())
    if n == 1:
        return (m, m)
    from scipy import stats

    half = float(stats.t.ppf(0.5 + conf / 2, n - 1)) * float(a.std(ddof=1)) / math.sqrt(n)
    return (m - half, m + half)


def wilson_interval(successes: int, n: int, z: float = Z95) -> tuple[float, float]:
    """Wilson score interval of a rate ``successes / n`` ((0, 1) for n = 0)."""
    if n < 0 or successes < 0 or successes > n:
        raise ValueError(f"need 0 <= successes <= n, got {successes} of {n}")
    if n == 0:
        return (0.0, 1.0)
    p = successes / n
    den = 1.0 + z * z / n
    centre = (p + z * z / (2 * n)) / den
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / den
    return (max(0.0, centre - half), min(1.0, centre + half))


def series_statistics(goals_for: Sequence[int], goals_against: Sequence[int],
                      seconds: Sequence[float] | float = SSL_MATCH_S) -> dict:
    """One side's view of a series of matches.

    Args:
        goals_for, goals_against: goals per match (same length).
        seconds: simulated seconds of play per match (one number for all), for the
            per-600 s figures.

    Returns a JSON-ready dict: matches, wins, draws, losses, win_rate (+ Wilson 95 %),
    goals_for / goals_against (totals and per match), goal_diff_per_match (mean and
    t 95 % interval) and goal_diff_per_600s (the same, each match scaled by
    600 s / its length).
    """
    gf, ga = np.asarray(goals_for, float), np.asarray(goals_against, float)
    if gf.shape != ga.shape or gf.ndim != 1:
        raise ValueError(f"goals_for and goals_against must be equal-length lists, got {gf.shape} and {ga.shape}")
    n = gf.size
    secs = np.full(n, float(seconds)) if np.isscalar(seconds) else np.asarray(seconds, float)
    if secs.shape != gf.shape or not np.all(np.isfinite(secs)) or np.any(secs <= 0):
        raise ValueError(f"seconds must be positive and one per match (or one number), got {seconds!r}")
    diff = gf - ga
    per600 = diff * (SSL_MATCH_S / secs)
    wins, losses = int((diff > 0).sum()), int((diff < 0).sum())
    lo, hi = t_interval(diff.tolist())
    lo6, hi6 = t_interval(per600.tolist())
    wlo, whi = wilson_interval(wins, n)
    return {
        "matches": n, "wins": wins, "draws": n - wins - losses, "losses": losses,
        "win_rate": wins / n if n else math.nan, "win_rate_ci95": [wlo, whi],
        "goals_for": int(gf.sum()), "goals_against": int(ga.sum()),
        "goals_for_per_match": float(gf.mean()) if n else math.nan,
        "goals_against_per_match": float(ga.mean()) if n else math.nan,
        "goal_diff_per_match": float(diff.mean()) if n else math.nan, "goal_diff_per_match_ci95": [lo, hi],
        "goal_diff_per_600s": float(per600.mean()) if n else math.nan, "goal_diff_per_600s_ci95": [lo6, hi6],
    }


def time_summary(times: Sequence[float]) -> dict[str, float | None]:
    """Mean, std (ddof 1), min, percentiles and max (s) of a list of times; None when empty."""
    keys = ("mean", "std", "min", "p5", "p25", "median", "p75", "p95", "max")
    if not len(times):
        return {k: None for k in keys}
    a = np.asarray(times, dtype=float)
    q = np.percentile(a, [5, 25, 50, 75, 95])
    return {"mean": float(a.mean()), "std": float(a.std(ddof=1)) if a.size > 1 else 0.0, "min": float(a.min()),
            "p5": float(q[0]), "p25": float(q[1]), "median": float(q[2]), "p75": float(q[3]), "p95": float(q[4]),
            "max": float(a.max())}
