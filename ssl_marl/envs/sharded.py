"""The batched env sharded over worker processes, talking through shared memory.

:class:`ShardedBatchedEnv` starts ``n_workers`` processes, each running a
:class:`~ssl_marl.envs.batched_env.BatchedSSLEnv` with ``worlds_per_worker``
worlds. Actions, observations, rewards, terminations and the per-world info arrays
live in :mod:`multiprocessing.shared_memory` blocks that every process maps; a
step writes the actions in place, sends each worker a one-byte command over its
pipe, and waits for a one-byte answer. Nothing is pickled per step.

World g = w * worlds_per_worker + j (worker w, world j) behaves exactly as world g
of one ``BatchedSSLEnv`` with all the worlds (seed ``seed + g``; tested). Arrays
are as :class:`BatchedSSLEnv`'s with K = n_workers * worlds_per_worker; ``info``
holds ``goal``, ``ball_out``, ``no_progress``, ``kicker``, ``kick_speed``, ``t``, ``autoreset``
(K,) and ``score`` (K, 2); the returned arrays are copies.

Workers are started with the "spawn" method (no fork after torch or threads) and
stopped by :meth:`close` (also on garbage collection and at interpreter exit).
"""

from __future__ import annotations

import atexit
import multiprocessing as mp
import weakref
from multiprocessing import shared_memory
from typing import Any

import numpy as np

_STEP, _RESET, _CLOSE, _OK = b"s", b"r", b"c", b"k"


def _layout(K: int, n: int, d: int, W: int, a: int) -> dict[str, tuple[tuple[int, ...], str]]:
    """Name -> (shape, dtype) of every shared array (K worlds, n agents, observation
    length d, W workers, action length a)."""
    return {"cpu_s": ((W,), "f8"), "actions": ((K, n, a), "f8"), "obs": ((K, n, d), "f4"), "rewards": ((K, n), "f8"),
            "terminated": ((K,), "?"), "truncated": ((K,), "?"), "goal": ((K,), "i8"), "ball_out": ((K,), "?"),
            "no_progress": ((K,), "?"),
            "kicker": ((K,), "i8"), "kick_speed": ((K,), "f8"), "t": ((K,), "f8"), "autoreset": ((K,), "?"),
            "score": ((K, 2), "i8"), "seeds": ((K,), "i8")}


def _map(buf, K: int, n: int, d: int, W: int, a: int) -> dict[str, np.ndarray]:
    out, off = {}, 0
    for name, (shape, dt) in _layout(K, n, d, W, a).items():
        a = np.ndarray(shape, dtype=np.dtype(dt), buffer=buf, offset=off)
        out[name] = a
        off += (a.nbytes + 63) // 64 * 64
    return out


def _nbytes(K: int, n: int, d: int, W: int, a: int) -> int:
    return sum((int(np.prod(s)) * np.dtype(dt).itemsize + 63) // 64 * 64 for s, dt in _layout(K, n, d, W, a).values())


def _worker(conn, shm_name: str, K_total: int, n: int, d: int, W: int, a: int, w: int, lo: int, hi: int,
            config: dict) -> None:
    import time

    from .batched_env import BatchedSSLEnv

    shm = shared_memory.SharedMemory(name=shm_name)
    try:
        arr = _map(shm.buf, K_total, n, d, W, a)
        env = BatchedSSLEnv(hi - lo, **config)
        sl = slice(lo, hi)
        conn.send_bytes(_OK)
        while True:
            cmd = conn.recv_bytes()
            if cmd == _CLOSE:
                break
            try:
                if cmd == _RESET:
                    s = arr["seeds"][sl]
                    obs, info = env.reset(seed=[None if x < 0 else int(x) for x in s])
                    arr["obs"][sl] = obs
                    arr["rewards"][sl] = 0.0
                    for k in ("terminated", "truncated", "autoreset", "ball_out", "no_progress"):
                        arr[k][sl] = False
                    arr["goal"][sl], arr["kicker"][sl], arr["kick_speed"][sl] = 0, -1, 0.0
                    arr["t"][sl], arr["score"][sl] = info["t"], 0
                else:
                    obs, rew, term, trunc, info = env.step(arr["actions"][sl])
                    arr["obs"][sl], arr["rewards"][sl] = obs, rew
                    arr["terminated"][sl], arr["truncated"][sl] = term, trunc
                    for k in ("goal", "ball_out", "no_progress", "kicker", "kick_speed", "t", "autoreset", "score"):
                        arr[k][sl] = info[k]
                arr["cpu_s"][w] = time.process_time()
                conn.send_bytes(_OK)
            except Exception as e:  # noqa: BLE001  (report to the parent, keep serving)
                conn.send_bytes(b"e" + f"{type(e).__name__}: {e}".encode())
        env.close()
    finally:
        del arr
        shm.close()
        conn.close()


def _shutdown(conns, procs, shm) -> None:
    for c in conns:
        try:
            c.send_bytes(_CLOSE)
        except (OSError, BrokenPipeError):
            pass
    for p in procs:
        p.join(timeout=5)
        if p.is_alive():
            p.terminate()
    try:
        shm.close()
    except BufferError:  # arrays still map it (interpreter exit): the OS reclaims it with the process
        pass
    try:
        shm.unlink()
    except FileNotFoundError:
        pass


class ShardedBatchedEnv:
    """``n_workers`` processes x ``worlds_per_worker`` worlds (env options as :class:`BatchedSSLEnv`)."""

    def __init__(self, n_workers: int, worlds_per_worker: int, **config: Any) -> None:
        from .batched_env import BatchedSSLEnv

        for name, v in (("n_workers", n_workers), ("worlds_per_worker", worlds_per_worker)):
            if not isinstance(v, int) or isinstance(v, bool) or v < 1:
                raise ValueError(f"{name} must be a positive integer, got {v!r}")
        probe = BatchedSSLEnv(1, **config)  # bad options fail here, not in the workers
        self.possible_agents = probe.possible_agents
        self.single_observation_space, self.single_action_space = probe.single_observation_space, \
            probe.single_action_space
        self.n = probe.n
        #: action length per agent (5; 6 with chip kicks)
        self.action_dim = a = probe.action_dim
        d = probe.obs_dim
        self.K = K = n_workers * worlds_per_worker
        self.n_workers, self.worlds_per_worker = n_workers, worlds_per_worker
        self._shm = shared_memory.SharedMemory(create=True, size=_nbytes(K, self.n, d, n_workers, a))
        self._arr = _map(self._shm.buf, K, self.n, d, n_workers, a)
        ctx = mp.get_context("spawn")
        self._conns, self._procs = [], []
        for w in range(n_workers):
            parent, child = ctx.Pipe()
            lo, hi = w * worlds_per_worker, (w + 1) * worlds_per_worker
            p = ctx.Process(target=_worker, args=(child, self._shm.name, K, self.n, d, n_workers, a, w, lo, hi,
                                                  dict(config)),
                            daemon=True, name=f"ssl_marl-shard-{w}")
            p.start()
            child.close()
            self._conns.append(parent)
            self._procs.append(p)
        self._finalizer = weakref.finalize(self, _shutdown, self._conns, self._procs, self._shm)
        atexit.register(self._finalizer)
        self._wait()

    def _wait(self) -> None:
        errors = []
        for w, c in enumerate(self._conns):
            msg = c.recv_bytes()
            if msg != _OK:
                errors.append(f"worker {w}: {msg[1:].decode()}")
        if errors:
            raise ValueError("; ".join(errors))

    def _send(self, cmd: bytes) -> None:
        for c in self._conns:
            c.send_bytes(cmd)
        self._wait()

    def _result(self, keys: tuple[str, ...]) -> dict[str, np.ndarray]:
        return {k: self._arr[k].copy() for k in keys}

    def reset(self, seed: int | None = None):
        """Reset every world (world g with seed ``seed + g``)."""
        self._arr["seeds"][:] = -1 if seed is None else int(seed) + np.arange(self.K)
        self._send(_RESET)
        return self._arr["obs"].copy(), self._result(("t",))

    def step(self, actions: Any):
        """Step every world: actions (K, n, A), A = :attr:`action_dim`; see :meth:`BatchedSSLEnv.step`."""
        a, dim = np.asarray(actions, dtype=np.float64), self.action_dim
        if a.shape != (self.K, self.n, dim):
            raise ValueError(f"actions must have shape (worlds, agents, {dim}) = {(self.K, self.n, dim)}, "
                             f"got {a.shape}")
        bad = ~np.isfinite(a).all(axis=2)
        if bad.any():
            k, i = (int(x) for x in np.argwhere(bad)[0])
            raise ValueError(f"world {k}: action for agent {self.possible_agents[i]!r} contains NaN or inf: "
                             f"{a[k, i].tolist()}")
        self._arr["actions"][:] = a
        self._send(_STEP)
        r = self._arr
        info = self._result(("goal", "ball_out", "no_progress", "kicker", "kick_speed", "t", "autoreset", "score"))
        return r["obs"].copy(), r["rewards"].copy(), r["terminated"].copy(), r["truncated"].copy(), info

    def worker_cpu_seconds(self) -> np.ndarray:
        """(n_workers,) CPU time (s) each worker process has used, as of its last command."""
        return self._arr["cpu_s"].copy()

    def close(self) -> None:
        """Stop the workers and free the shared memory."""
        self._arr = {}
        self._finalizer()
