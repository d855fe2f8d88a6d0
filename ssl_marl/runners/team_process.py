"""A team controller in its own process: the two teams of a match decide at the same time.

In SSL each team's software runs on its own computer and sees the same vision
frame; :class:`TeamProcess` does that on one machine. It builds a team controller
in a child process (the ``spawn`` start method, as :mod:`ssl_marl.runners.pool`:
forking a process whose torch thread pool has started can deadlock the child) and
plays the request-reply loop of one control period:

1. :meth:`TeamProcess.submit` sends the :class:`TeamView` of this period (the
   team's vision frame in its own frame, the score, the referee's command),
2. the caller computes the other team's actions meanwhile,
3. :meth:`TeamProcess.result` returns this team's actions and the wall time (s)
   the child spent computing them.

A :class:`TeamView` carries exactly what
:meth:`ssl_marl.plays.team.TeamController.act` reads from an env (``vision_state``,
``score``, ``task.referee_state``), so the child's controller gets the same inputs
as it would in the caller's process and returns the same actions: a match played
with one team in a :class:`TeamProcess` is the same match, bit for bit, as one
played in one process (``tests/test_team_process.py``). An error in the child is
raised in the caller as the same exception (a ``ValueError`` for a bad team spec stays
one), with the child's traceback as a note.
"""

from __future__ import annotations

import multiprocessing as mp
import os
import pickle
import signal
import time
import traceback
from dataclasses import dataclass
from types import SimpleNamespace
from typing import Any

import numpy as np

from ..physics.state import TeamState, WorldState

__all__ = ["TeamView", "TeamProcess", "team_view"]


@dataclass(frozen=True)
class TeamView:
    """One control period's input of team ``team``'s software.

    Attributes:
        team: "blue" or "yellow".
        world: the team's vision frame in its own frame (own goal at -x; m, rad, s).
        score: goals so far, ``{"blue": int, "yellow": int}``.
        referee_state: the referee's command (a
            :class:`~ssl_marl.envs.game_control.RefereeState`, field frame), or None
            when the env has no referee task.
    """

    team: str
    world: WorldState
    score: dict
    referee_state: Any = None

    def vision_state(self, team: str | None = None) -> WorldState:
        """The team's frame (only the view's own team can be asked for)."""
        if team != self.team:
            raise ValueError(f"TeamView of {self.team!r} has no vision frame for {team!r}")
        return self.world

    @property
    def task(self) -> SimpleNamespace:
        """What a team reads of the env's task: its ``referee_state``."""
        return SimpleNamespace(referee_state=self.referee_state)

    def __reduce__(self) -> tuple:
        """Pickle the frame as two byte strings (:func:`pack_world`): a few microseconds
        instead of one numpy pickle per array; the child rebuilds the same arrays."""
        packed = pack_world(self.world)
        if packed is None:
            return TeamView, (self.team, self.world, self.score, self.referee_state)
        return _view_from_wire, (self.team, packed, self.score, self.referee_state)


_FLOAT = np.dtype(np.float64)
_BOOL = np.dtype(bool)


def pack_world(ws: WorldState) -> tuple | None:
    """``ws`` as (robots per team, float64 bytes, bool bytes, scalars) for :func:`unpack_world`,
    or None when an array is not of the snapshot's usual dtype and shape (then it pickles
    as it is)."""
    teams = (ws.blue, ws.yellow)
    floats = [ws.ball_pos, ws.ball_vel]
    flags = []
    for ts in teams:
        n = ts.pos.shape[0]
        arrays = (ts.pos, ts.heading, ts.vel, ts.omega)
        if any(a.dtype != _FLOAT for a in arrays) or ts.pos.shape != (n, 2) or ts.vel.shape != (n, 2) \
                or ts.heading.shape != (n,) or ts.omega.shape != (n,) or ts.ball_on_dribbler.shape != (n,) \
                or ts.kick_ready.shape != (n,) or ts.ball_on_dribbler.dtype != _BOOL or ts.kick_ready.dtype != _BOOL:
            return None
        floats += [ts.pos.ravel(), ts.heading, ts.vel.ravel(), ts.omega]
        flags += [ts.ball_on_dribbler, ts.kick_ready]
    if ws.ball_pos.shape != (2,) or ws.ball_vel.shape != (2,) or ws.ball_pos.dtype != _FLOAT \
            or ws.ball_vel.dtype != _FLOAT:
        return None
    return ((ws.blue.pos.shape[0], ws.yellow.pos.shape[0]), np.concatenate(floats).tobytes(),
            np.concatenate(flags).tobytes(),
            (ws.t, ws.ball_visible, ws.frame, ws.ball_height, ws.ball_vz, ws.ball_max_height))


def _team_from_wire(f: np.ndarray, k: np.ndarray, n: int) -> TeamState:
    return TeamState(f[:2 * n].reshape(n, 2), f[2 * n:3 * n], f[3 * n:5 * n].reshape(n, 2), f[5 * n:6 * n], k[:n],
                     k[n:2 * n])


def unpack_world(packed: tuple) -> WorldState:
    """The :class:`WorldState` of :func:`pack_world`'s tuple: the same values, dtypes and
    shapes, in read-only arrays."""
    (nb, ny), fbytes, kbytes, scalars = packed
    f = np.frombuffer(fbytes, _FLOAT)
    k = np.frombuffer(kbytes, _BOOL)
    t, visible, frame, height, vz, max_height = scalars
    return WorldState(t, f[0:2], f[2:4], _team_from_wire(f[4:], k, nb), _team_from_wire(f[4 + 6 * nb:], k[2 * nb:], ny),
                      visible, frame, height, vz, max_height)


def _view_from_wire(team: str, packed: tuple, score: dict, referee_state: Any) -> TeamView:
    return TeamView(team, unpack_world(packed), score, referee_state)


def pack_actions(actions: Any) -> Any:
    """A team's actions ``{agent: 1-D float32 array}`` as (agents, lengths, bytes) for
    :func:`unpack_actions`; anything else is returned as it is."""
    if not isinstance(actions, dict) or not actions or not all(
            isinstance(a, np.ndarray) and a.dtype == np.float32 and a.ndim == 1 for a in actions.values()):
        return actions
    values = list(actions.values())
    return _PackedActions((tuple(actions), tuple(a.shape[0] for a in values), np.concatenate(values).tobytes()))


class _PackedActions(tuple):
    """:func:`pack_actions`'s tuple (a type of its own, so no other payload is taken for one)."""

    __slots__ = ()


def unpack_actions(payload: Any) -> Any:
    """The actions dict of :func:`pack_actions` (writable float32 arrays)."""
    if not isinstance(payload, _PackedActions):
        return payload
    agents, sizes, buf = payload
    flat = np.frombuffer(buf, np.float32).copy()
    out, i = {}, 0
    for agent, n in zip(agents, sizes):
        out[agent] = flat[i:i + n]
        i += n
    return out


def team_view(env: Any, team: str) -> TeamView:
    """The :class:`TeamView` of ``team`` for the env's current control period."""
    task = getattr(env, "task", None)
    return TeamView(team, env.vision_state(team), dict(env.score), getattr(task, "referee_state", None))


#: s: how long a waiting side polls its pipe before it blocks. A blocked process is woken
#: by the kernel (about 0.2 ms per round trip on a 2-core VM, a fifth of a team's
#: decision time); one that polls sees the message within microseconds. Both sides wait
#: about one control period for the other, so each keeps its core busy for at most this.
#: Between polls the waiting side yields its core (``os.sched_yield``): on a busy host the
#: process it waits for, or any other, runs there instead of a busy loop.
SPIN_S = 0.05


def _wait(conn: Any, spin_s: float = SPIN_S) -> bool:
    """Poll ``conn`` for up to ``spin_s``, yielding the core between polls; True when a
    message is there (then recv does not block)."""
    t0 = time.perf_counter()
    while not conn.poll():
        if time.perf_counter() - t0 > spin_s:
            return False
        os.sched_yield()
    return True


def _error(exc: BaseException) -> tuple[Exception | None, str]:
    """(the exception if it pickles, else None; its traceback) for the parent."""
    tb = traceback.format_exc()
    try:
        pickle.loads(pickle.dumps(exc))
    except Exception:  # noqa: BLE001 - the traceback says what it was
        return None, tb
    return (exc if isinstance(exc, Exception) else None), tb


def _serve(conn: Any, factory: Any, args: tuple, kwargs: dict) -> None:
    """Child process: build ``factory(*args, **kwargs)`` and answer requests until told to stop."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is the parent's to handle; it closes us
    try:
        import torch

        torch.set_num_threads(1)  # one core per team: the other runs the caller
    except ImportError:  # pragma: no cover - torch is a core dependency
        pass
    try:
        ctrl = factory(*args, **kwargs)
        skills = getattr(ctrl, "skills", None)
        try:
            pickle.dumps(skills)
        except Exception:  # noqa: BLE001 - a label is enough for the match record
            skills = repr(skills)
        conn.send(("ready", {"agents": list(ctrl.agents), "skills": skills}))
    except BaseException as exc:  # noqa: BLE001 - reported to the parent
        conn.send(("error", _error(exc)))
        return
    while True:
        try:
            _wait(conn)
            msg = conn.recv()
        except EOFError:  # the parent went away
            return
        if msg is None:
            return
        kind, payload = msg
        try:
            if kind == "act":
                t0 = time.perf_counter()
                actions = ctrl.act(payload)
                conn.send(("ok", (pack_actions(actions), time.perf_counter() - t0)))
            elif kind == "reset":
                if hasattr(ctrl, "reset"):
                    ctrl.reset()
                conn.send(("ok", None))
            else:
                conn.send(("error", f"TeamProcess: unknown request {kind!r}"))
        except BaseException as exc:  # noqa: BLE001 - reported to the parent
            conn.send(("error", _error(exc)))


class TeamProcess:
    """A team controller ``factory(*args, **kwargs)`` served by a child process.

    ``factory`` and its arguments must pickle (a module-level function and plain
    values, e.g. :func:`~ssl_marl.runners.controllers.make_controller` with team
    kinds and skill names). Attributes ``agents`` and ``skills`` mirror the child's
    controller. The child starts at once and builds the controller while the caller
    goes on; the first use waits for it. Use :meth:`submit` then :meth:`result` once
    per control period, and :meth:`close` (or ``with``) at the end.
    """

    def __init__(self, factory: Any, *args: Any, timeout_s: float = 300.0, **kwargs: Any) -> None:
        self._proc = None
        ctx = mp.get_context("spawn")
        self._conn, child = ctx.Pipe()
        self._proc = ctx.Process(target=_serve, args=(child, factory, args, kwargs), daemon=True,
                                 name="ssl-marl-team")
        self._proc.start()
        child.close()
        self._timeout_s = float(timeout_s)
        self._pending = False
        self._info: dict | None = None  # the child's answer to starting: read on first use

    def _ready(self) -> dict:
        if self._info is None:
            self._info = self._receive("starting the team")
        return self._info

    @property
    def agents(self) -> list[str]:
        """The controller's agent names (``f"{team}_{i}"``)."""
        return self._ready()["agents"]

    @property
    def skills(self) -> Any:
        """The controller's ``skills`` attribute (None if it has none)."""
        return self._ready()["skills"]

    def _receive(self, what: str) -> Any:
        if not (_wait(self._conn) or self._conn.poll(self._timeout_s)):
            self.close()
            raise TimeoutError(f"TeamProcess: no answer within {self._timeout_s:.0f} s while {what}")
        try:
            status, payload = self._conn.recv()
        except EOFError:
            code = self._proc.exitcode
            self.close()
            raise RuntimeError(f"TeamProcess: the team's process ended (exit code {code}) while {what}") from None
        if status == "error":
            self.close()
            exc, tb = payload
            if exc is None:
                raise RuntimeError(f"TeamProcess: the team's controller failed while {what}:\n{tb}")
            exc.add_note(f"(raised in the team's process while {what}; its traceback:)\n{tb}")
            raise exc  # the same error as in one process (a ValueError stays a ValueError)
        return payload

    def reset(self) -> None:
        """Reset the child's controller (if it has ``reset``)."""
        self._ready()
        self._conn.send(("reset", None))
        self._receive("resetting the team")

    def submit(self, view: TeamView) -> None:
        """Send this control period's :class:`TeamView`; the child starts computing."""
        if self._pending:
            raise RuntimeError("TeamProcess.submit: the previous period's result was not collected")
        self._ready()
        self._conn.send(("act", view))
        self._pending = True

    def result(self) -> tuple[dict[str, np.ndarray], float]:
        """This period's actions ``{agent: (5,) float32}`` and the child's compute time (s)."""
        if not self._pending:
            raise RuntimeError("TeamProcess.result: nothing was submitted")
        self._pending = False
        actions, seconds = self._receive("computing actions")
        return unpack_actions(actions), seconds

    def close(self) -> None:
        """Stop the child process. Idempotent."""
        if getattr(self, "_proc", None) is None:
            return
        try:
            self._conn.send(None)
        except (OSError, ValueError):
            pass
        self._proc.join(timeout=5.0)
        if self._proc.is_alive():
            self._proc.terminate()
            self._proc.join(timeout=5.0)
        self._conn.close()
        self._proc = None

    def __enter__(self) -> "TeamProcess":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()

    def __del__(self) -> None:
        try:
            self.close()
        except Exception:
            pass
