"""Provenance manifests: what produced a result folder.

A manifest (``manifest.json`` beside ``results.json``) records the command, the package
version, the git commit of the checkout (and whether its tree had uncommitted changes),
the sha256 of every actor file the run could load (the shipped actors of
``ssl_marl/skills/pretrained`` and ``ssl_marl/decisions/pretrained`` plus any actor file
named on the command line), the rule flags that decide the episodes (realism, tracker,
field, the referee's no-progress call, the passing plays' snap shot, team kinds, ...),
the seeds, the machine and the date (UTC, ISO 8601).

A value nobody recorded is the string ``"unrecorded"`` (:data:`UNRECORDED`), never a guess.
"""

from __future__ import annotations

import datetime as _dt
import functools
import hashlib
import os
import platform
import subprocess
import sys
from importlib import metadata
from pathlib import Path
from typing import Any, Iterable

UNRECORDED = "unrecorded"
MANIFEST_FILE = "manifest.json"
MANIFEST_FORMAT = 1

PACKAGE_DIR = Path(__file__).resolve().parents[1]
REPO_DIR = PACKAGE_DIR.parent
ACTOR_FOLDERS = ("ssl_marl/skills/pretrained", "ssl_marl/decisions/pretrained")
#: environment variable naming the commit of a source tree sent to another machine (whose own git
#: metadata, if any, need not be the tree's); when set, it is the commit a manifest records
COMMIT_ENV = "SSL_MARL_GIT_COMMIT"


def sha256_file(path: str | os.PathLike) -> str:
    """Hex sha256 of a file's bytes."""
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def git_state(repo: Path = REPO_DIR) -> dict[str, Any]:
    """``{"commit": HEAD's hash, "dirty": True when tracked files differ from HEAD}``.

    Where the environment variable :data:`COMMIT_ENV` names another commit (a tree copied to
    another machine, whose own git metadata, if any, is not the tree's; the sender vouches for
    the name): that commit, ``dirty`` ``UNRECORDED``, ``"source"`` naming the variable and the
    checkout's own answer under ``"checkout"``. Outside a git checkout or without git and no
    name given: ``UNRECORDED`` for both."""
    def git(*args: str) -> str:
        return subprocess.run(["git", "-C", str(repo), *args], check=True, capture_output=True,
                              text=True, timeout=30).stdout.strip()
    named = os.environ.get(COMMIT_ENV, "").strip()
    try:
        own: dict[str, Any] = {"commit": git("rev-parse", "HEAD"),
                               "dirty": bool(git("status", "--porcelain", "--untracked-files=no"))}
    except (OSError, subprocess.SubprocessError):
        own = {"commit": UNRECORDED, "dirty": UNRECORDED}
    if named and named != own["commit"]:
        return {"commit": named, "dirty": UNRECORDED, "source": COMMIT_ENV, "checkout": own}
    return own


@functools.lru_cache(maxsize=None)
def code_hash(package: Path = PACKAGE_DIR) -> str:
    """Hex sha256 over the package's Python source (every ``*.py`` under ``package``, by
    relative path and bytes, in path order) as it stands at the first call in this process
    (cached: a league worker calls it after its first match, when its modules are imported).
    Two runs with the same hash ran the same code, committed or not."""
    h = hashlib.sha256()
    for f in sorted(package.rglob("*.py")):
        h.update(f.relative_to(package).as_posix().encode() + b"\0")
        h.update(f.read_bytes() + b"\0")
    return h.hexdigest()


def shipped_actors(repo: Path = REPO_DIR) -> dict[str, str]:
    """sha256 of every shipped actor file, keyed by its path relative to the repository."""
    out: dict[str, str] = {}
    for folder in ACTOR_FOLDERS:
        for f in sorted((repo / folder).glob("*.pt")):
            out[f"{folder}/{f.name}"] = sha256_file(f)
    return out


def machine() -> dict[str, Any]:
    """CPU model, logical cores, OS, and the Python / torch / numpy versions (torch is
    read from its package metadata, not imported)."""
    return {"cpu": _cpu_model(), "cores": os.cpu_count(), "os": platform.platform(),
            "python": platform.python_version(), "torch": _version("torch"), "numpy": _version("numpy")}


def _cpu_model() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine() or UNRECORDED


def _version(package: str) -> str:
    try:
        return metadata.version(package)
    except metadata.PackageNotFoundError:
        return UNRECORDED


def code_rules() -> dict[str, Any]:
    """The rule switches whose defaults live in the code: the referee's no-progress call
    (s; None = off) and the passing plays' snap shot."""
    from ..envs.config import MatchRules
    from ..plays.pass_coordinator import PassingParams

    return {"no_progress_s": MatchRules.no_progress_s, "passing_snap_shot": PassingParams.snap_shot}


def build_manifest(rules: dict[str, Any], seeds: dict[str, Any],
                   actor_files: Iterable[str | os.PathLike | None] = (),
                   argv: list[str] | None = None) -> dict[str, Any]:
    """The manifest of a run started now by this process.

    Args:
        rules: the run's rule flags (realism, tracker, field, team kinds, ...); the code's
            own switches (:func:`code_rules`) are added unless given.
        seeds: the run's seeds (e.g. ``{"seed": 10000, "episodes": 1000}``; episode i's
            seed is ``ssl_marl.io.episode_seed(seed, i)``).
        actor_files: actor files the run loads besides the shipped ones (None entries
            are skipped); every ``*.pt`` path inside ``rules`` is hashed too.
        argv: the command (default ``sys.argv``).
    """
    named = [*actor_files, *_actor_paths(rules)]
    extra = {str(f): sha256_file(f) for f in named if f is not None and Path(f).is_file()}
    return {"format": MANIFEST_FORMAT,
            "command": list(sys.argv if argv is None else argv),
            "package_version": _package_version(),
            "git": git_state(),
            "actors": {**shipped_actors(), **extra},
            "rules": {**code_rules(), **rules},
            "seeds": dict(seeds),
            "machine": machine(),
            "date": _dt.datetime.now(_dt.timezone.utc).replace(microsecond=0).isoformat()}


def _actor_paths(value: Any) -> list[str]:
    """Every string ending in ``.pt`` inside ``value`` (nested dicts and lists)."""
    if isinstance(value, dict):
        return [p for v in value.values() for p in _actor_paths(v)]
    if isinstance(value, (list, tuple)):
        return [p for v in value for p in _actor_paths(v)]
    return [value] if isinstance(value, (str, os.PathLike)) and str(value).endswith(".pt") else []


def _package_version() -> str:
    from .. import __version__

    return __version__
