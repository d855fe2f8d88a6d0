"""Actor files: the one format of skill actors and decision actors, loaded without ever executing code.

An actor file is a ``torch.save``-d plain dict::

    {"format": "ssl_marl.actor", "version": 2, "kind": "skill" | "decision",
     "state_dict": {...tensors...}, "metadata": {...str/int/float/bool/None/list/dict...}}

read back with ``torch.load(..., weights_only=True)``, which refuses anything but tensors
and plain containers (:func:`read_actor_file`). ``kind`` says which network it holds:

* ``"skill"`` -- a learned skill's :class:`~ssl_marl.skills.networks.Actor` (:func:`save_actor`,
  :func:`load_actor`). Metadata: ``skill``, ``obs_spec`` (the env's observation version
  string, e.g. ``"go_to_ball/v1"``), ``obs_dim``, ``act_dim``, ``hidden``, ``layer_norm``, plus
  provenance (``hyperparameters``, ``seed``, ``samples``, ``git_commit``, ``created``).
* ``"decision"`` -- a MAPPO decision actor (:func:`ssl_marl.decisions.learned.load_decision_actor`):
  the state dict holds the policy network's ``net.*`` weights and the observation scaling
  ``obs_mean`` / ``obs_std``; metadata: ``task``, ``obs_dim``, ``n_options``, ``hidden``,
  ``continuous``, ``agent_ids``, ``option_names`` and provenance (``seed``, ``decisions``,
  ``val_score``, ``commit``, ``selection``, ...).

:func:`read_actor_file` also reads the two earlier layouts, so every stored actor loads:
version 1 of ``ssl_marl.actor`` (skill actors, no ``kind``) and ``ssl_marl.decision_actor/1``
(one flat dict: the metadata entries beside ``state_dict``, ``obs_mean`` and ``obs_std``).
Files are written atomically (temp file in the same directory, then ``os.replace``), so a
crash never leaves a half-written file.
"""

from __future__ import annotations

import datetime as _dt
import os
import pickle
import subprocess
import warnings
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import torch

from .networks import Actor

FORMAT = "ssl_marl.actor"
VERSION = 2
#: actor kinds (the ``kind`` entry)
KINDS = ("skill", "decision")
_DECISION_V1 = "ssl_marl.decision_actor/1"
_DECISION_TENSORS = ("obs_mean", "obs_std")
_PLAIN = (str, int, float, bool, type(None))


def git_commit(cwd: str | os.PathLike[str] | None = None) -> str:
    """Best-effort ``git rev-parse HEAD`` of ``cwd`` (default: this package's checkout); "unknown" on failure."""
    where = Path(cwd) if cwd is not None else Path(__file__).resolve().parent
    try:
        out = subprocess.run(["git", "rev-parse", "HEAD"], cwd=where, capture_output=True, text=True,
                             timeout=5, check=True)
        return out.stdout.strip() or "unknown"
    except (OSError, subprocess.SubprocessError):
        return "unknown"


def to_plain(value: Any, where: str = "metadata") -> Any:
    """Return ``value`` as nested str/int/float/bool/None/list/dict (tuples become lists).

    Raises TypeError on anything else, so metadata stays loadable with ``weights_only=True``.
    """
    if isinstance(value, _PLAIN):
        return value
    if isinstance(value, Mapping):
        out: dict[str, Any] = {}
        for k, v in value.items():
            if not isinstance(k, str):
                raise TypeError(f"{where}: dict keys must be str, got {k!r}")
            out[k] = to_plain(v, f"{where}.{k}")
        return out
    if isinstance(value, (list, tuple)):
        return [to_plain(v, f"{where}[{i}]") for i, v in enumerate(value)]
    if hasattr(value, "item") and getattr(value, "shape", None) == ():  # numpy / torch scalar
        return to_plain(value.item(), where)
    raise TypeError(f"{where}: {type(value).__name__} is not allowed in checkpoint metadata "
                    "(use str/int/float/bool/None/list/dict)")


def atomic_torch_save(obj: Any, path: str | os.PathLike[str]) -> Path:
    """``torch.save(obj)`` to ``path`` atomically (via :func:`ssl_marl.io.atomic_write_bytes`)."""
    import io

    from ..io import atomic_write_bytes

    buf = io.BytesIO()
    torch.save(obj, buf)
    atomic_write_bytes(path, buf.getvalue())
    return Path(path)


#: What a valid file is, per kind (shown in every "is not a valid ..." error).
VALID_FILES = {
    "ssl_marl checkpoint": "a valid one is an actor file written by ssl_marl's trainer (RUN/actor.pt from "
                           "`ssl-marl train` / `python -m train`, or `python -m train.export`), like the shipped "
                           "ssl_marl/skills/pretrained/go_to_ball.pt",
    "ssl_marl training checkpoint": "a valid one is RUN/checkpoint.pt written by `ssl-marl train` / "
                                    "`python -m train`",
    "ssl_marl decision actor": "a valid one is a decision actor written by `python -m train mappo` "
                               "(RUN/actors/actor-N.pt) or `python -m train.mappo_export`, like the shipped "
                               "ssl_marl/decisions/pretrained/keepaway.pt",
}
_WHAT = {"skill": "ssl_marl checkpoint", "decision": "ssl_marl decision actor"}
_ZIP_MAGIC = b"PK\x03\x04"


def safe_torch_load(path: str | os.PathLike[str], what: str = "ssl_marl checkpoint") -> Any:
    """``torch.load(weights_only=True)`` with clear errors.

    Raises FileNotFoundError naming ``path`` if it is missing, ValueError
    "<path> is not a valid <what>: <what the file is not>; <what a valid one is>"
    if it cannot be unpickled safely. PyTorch's own message is not repeated: it
    suggests ``weights_only=False``, i.e. running code from the file, which a
    user must never do with a checkpoint that fails this check.
    """
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"checkpoint not found: {path}" + (" (it is a folder)" if path.is_dir() else ""))
    valid = VALID_FILES.get(what, "a valid one is written by ssl_marl with torch.save")
    with open(path, "rb") as fh:
        head = fh.read(4)
    if head != _ZIP_MAGIC:
        kind = "an empty file" if not head else "not a PyTorch file (torch.save writes a zip archive)"
        raise ValueError(f"{path} is not a valid {what}: it is {kind}; {valid}")
    try:
        with warnings.catch_warnings():  # torch warns about foreign pickle protocols before failing
            warnings.filterwarnings("ignore", message="Detected pickle protocol")
            return torch.load(path, map_location="cpu", weights_only=True)
    except pickle.UnpicklingError as exc:
        raise ValueError(f"{path} is not a valid {what}: it holds Python objects other than tensors and plain "
                         f"containers, which are never loaded (loading them could run code); {valid}") from exc
    except Exception as exc:  # RuntimeError / OSError from a truncated or damaged zip, EOFError, KeyError, ...
        raise ValueError(f"{path} is not a valid {what}: it is a damaged or truncated PyTorch archive "
                         f"({type(exc).__name__}); {valid}") from exc


def save_actor_file(path: str | os.PathLike[str], kind: str, state_dict: Mapping[str, torch.Tensor],
                    metadata: Mapping[str, Any]) -> Path:
    """Write an actor file of ``kind`` ("skill" or "decision") atomically; return the path.
    Tensors are copied to the CPU; ``metadata`` must be plain (:func:`to_plain`)."""
    if kind not in KINDS:
        raise ValueError(f"actor kind must be one of {KINDS} (got {kind!r})")
    state = {k: v.detach().cpu().clone() for k, v in state_dict.items()}
    return atomic_torch_save({"format": FORMAT, "version": VERSION, "kind": kind, "state_dict": state,
                              "metadata": to_plain(dict(metadata))}, path)


def read_actor_file(path: str | os.PathLike[str], kind: str) -> tuple[dict[str, torch.Tensor], dict[str, Any]]:
    """``(state_dict, metadata)`` of an actor file of ``kind``, in any stored layout (module docstring).

    Raises FileNotFoundError if ``path`` is missing; ValueError naming the file when it is not
    a valid actor file of that kind."""
    what = _WHAT[kind]
    blob = safe_torch_load(path, what)
    bad = f"{path} is not a valid {what}"
    valid = VALID_FILES[what]
    if not isinstance(blob, dict):
        raise ValueError(f"{bad}: it is a PyTorch file without the format tag {FORMAT!r}; {valid}")
    if blob.get("format") == _DECISION_V1:
        if kind != "decision":
            raise ValueError(f"{bad}: it holds a decision actor, not a skill actor; {valid}")
        state = blob.get("state_dict")
        if not isinstance(state, dict):
            raise ValueError(f"{bad}: missing 'state_dict'")
        state = {**state, **{k: blob[k] for k in _DECISION_TENSORS if blob.get(k) is not None}}
        return state, {k: v for k, v in blob.items() if k not in ("format", "state_dict", *_DECISION_TENSORS)}
    if blob.get("format") != FORMAT:
        raise ValueError(f"{bad}: it is a PyTorch file without the format tag {FORMAT!r}; {valid}")
    version = blob.get("version")
    if version not in (1, VERSION):
        raise ValueError(f"{bad} (unsupported version {version!r}, expected {VERSION})")
    stored_kind = blob.get("kind", "skill")  # version 1 holds skill actors only
    if stored_kind != kind:
        raise ValueError(f"{bad}: it holds a {stored_kind} actor, not a {kind} actor; {valid}")
    meta, state = blob.get("metadata"), blob.get("state_dict")
    if not isinstance(meta, dict) or not isinstance(state, dict):
        raise ValueError(f"{bad} (metadata or state_dict missing)")
    return state, meta


def save_actor(path: str | os.PathLike[str], actor: Actor, metadata: Mapping[str, Any]) -> Path:
    """Write skill actor ``actor`` and ``metadata`` to ``path`` atomically; return the path.

    ``metadata`` should hold at least ``skill`` and ``obs_spec``; network shape
    (``obs_dim``, ``act_dim``, ``hidden``, ``layer_norm``) is taken from the actor,
    and ``git_commit`` / ``created`` (UTC ISO-8601) are added when absent.
    """
    if not isinstance(actor, Actor):
        raise TypeError(f"save_actor expects an Actor, got {type(actor).__name__}")
    meta = to_plain(dict(metadata))
    meta.update(obs_dim=actor.obs_dim, act_dim=actor.act_dim, hidden=list(actor.hidden),
                layer_norm=actor.layer_norm)
    meta.setdefault("git_commit", git_commit())
    meta.setdefault("created", _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"))
    return save_actor_file(path, "skill", actor.state_dict(), meta)


def load_actor(path: str | os.PathLike[str], expected_skill: str | None = None,
               expected_spec: str | tuple[str, ...] | None = None) -> tuple[Actor, dict[str, Any]]:
    """Load a skill actor file; return ``(actor in eval mode, metadata)``.

    Raises FileNotFoundError if ``path`` is missing; ValueError if the file is not
    a valid skill actor file, or its ``skill`` / ``obs_spec`` differ from the
    expected ones (when given; ``expected_spec`` may be a tuple of accepted specs).
    """
    state, meta = read_actor_file(path, "skill")
    bad = f"{path} is not a valid ssl_marl checkpoint"
    if expected_skill is not None and meta.get("skill") != expected_skill:
        raise ValueError(f"{path}: skill mismatch: expected {expected_skill!r}, found {meta.get('skill')!r}")
    accepted = (expected_spec,) if isinstance(expected_spec, str) else expected_spec
    if accepted is not None and meta.get("obs_spec") not in accepted:
        raise ValueError(f"{path}: observation spec mismatch: expected {' or '.join(map(repr, accepted))}, "
                         f"found {meta.get('obs_spec')!r}")
    try:
        actor = Actor(int(meta["obs_dim"]), int(meta["act_dim"]), tuple(int(h) for h in meta["hidden"]),
                      bool(meta["layer_norm"]))
        actor.load_state_dict(state, strict=True)
    except (KeyError, TypeError, ValueError, RuntimeError) as exc:
        raise ValueError(f"{bad} (network does not match its metadata: {exc})") from exc
    actor.eval()
    for p in actor.parameters():
        p.requires_grad_(False)
    return actor, meta
