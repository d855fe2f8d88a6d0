"""Prioritized fictitious self-play: how training draws its opponents from a league.

Vinyals et al. 2019, "Grandmaster level in StarCraft II using multi-agent reinforcement
learning", Nature 575, Methods: "Prioritized fictitious self-play" (docs/references.md,
"Keepaway and MAPPO"). Pure numpy; the league runner (:mod:`ssl_marl.runners.league`) and
the full-match decision task (:mod:`ssl_marl.decisions.attack_match`) use it.
"""

from __future__ import annotations

from typing import Any, Sequence

import numpy as np

PFSP_KINDS = ("hard", "even")


def pfsp_weights(win_probs: Sequence[float], kind: str = "hard") -> np.ndarray:
    """Prioritized fictitious self-play weights of opponents, normalised to sum 1.

    ``win_probs[i]`` is the learner's probability of beating opponent i (in [0, 1]).
    "hard": f(p) = (1 - p)^2 (stronger opponents more often); "even": f(p) = p (1 - p)
    (opponents of the learner's level). Where every f is 0 the weights are uniform.
    """
    p = np.asarray(win_probs, dtype=float)
    if p.ndim != 1 or p.size == 0:
        raise ValueError(f"win_probs must be a non-empty sequence, got {win_probs!r}")
    if not np.all(np.isfinite(p)) or np.any(p < 0) or np.any(p > 1):
        raise ValueError(f"win probabilities must lie in [0, 1], got {list(p)}")
    if kind == "hard":
        f = (1.0 - p) ** 2
    elif kind == "even":
        f = p * (1.0 - p)
    else:
        raise ValueError(f"kind must be one of {PFSP_KINDS}, got {kind!r}")
    total = f.sum()
    return f / total if total > 0 else np.full(p.size, 1.0 / p.size)


def sample_opponent(opponents: Sequence[Any], win_probs: Sequence[float], rng: np.random.Generator,
                    kind: str = "hard") -> Any:
    """One opponent drawn with :func:`pfsp_weights` (``rng`` makes the draw reproducible)."""
    if len(opponents) != len(win_probs):
        raise ValueError(f"{len(opponents)} opponents but {len(win_probs)} win probabilities")
    return opponents[int(rng.choice(len(opponents), p=pfsp_weights(win_probs, kind)))]


def win_probability(wins: Sequence[float], games: Sequence[float]) -> np.ndarray:
    """The learner's estimated probability of beating each opponent from its results
    (``wins`` with draws counted 0.5, ``games`` played): ``(wins + 1) / (games + 2)``, a
    one-win-one-loss prior, so an opponent never met counts as even."""
    w, g = np.asarray(wins, float), np.asarray(games, float)
    if w.shape != g.shape or np.any(w < 0) or np.any(w > g):
        raise ValueError(f"wins must lie in [0, games] per opponent, got wins {w.tolist()} games {g.tolist()}")
    return (w + 1.0) / (g + 2.0)


__all__ = ["PFSP_KINDS", "pfsp_weights", "sample_opponent", "win_probability"]
