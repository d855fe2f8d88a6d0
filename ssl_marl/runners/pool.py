"""One worker pool for every runner: in-process, a local process pool, or a Ray cluster.

:func:`run_pool` maps a module-level function over a list of jobs and returns the
results in job order. Each job's result must depend only on the job (every runner
seeds its episodes / matches / training runs from the job itself), so the backend
and the number of workers never change the results.

Backends:

* ``"local"`` (default, nothing to start): ``workers == 1`` runs in this process;
  ``workers > 1`` uses a :mod:`multiprocessing` pool with the ``spawn`` start method
  (forking a process whose torch thread pool has started can deadlock the child).
* ``"ray"``: Ray core tasks (``ray.remote``), one CPU each, at most ``workers`` in
  flight (``workers=None``: as many as the cluster has CPUs). ``address`` is passed
  to :func:`ray.init`: ``None`` starts a local Ray instance for this process
  (``num_cpus=workers``), ``"auto"`` or ``"HOST:6379"`` joins a running cluster
  (``ray start --head`` on one machine, ``ray start --address HOST:6379`` on the
  others; every node needs this package installed, see docs/DESIGN.md). Ray is an
  optional dependency (``pip install -e ".[ray]"``).
"""

from __future__ import annotations

import math
import sys
from typing import Any, Callable, Sequence

BACKENDS = ("local", "ray")


def validate_backend(backend: str, workers: int | None, address: str | None = None) -> None:
    """Raise ValueError for an unknown backend, a bad worker count or an address without Ray."""
    if backend not in BACKENDS:
        raise ValueError(f"backend must be one of {BACKENDS}, got {backend!r}")
    if workers is not None and (not isinstance(workers, int) or isinstance(workers, bool) or workers < 1):
        raise ValueError(f"workers must be a positive integer, got {workers!r}")
    if backend == "local" and workers is None:
        raise ValueError("workers must be a positive integer for the local backend, got None")
    if address is not None and backend != "ray":
        raise ValueError(f"address {address!r} needs backend='ray' (the local pool has no address)")


def chunk_indices(n: int, workers: int | None, max_chunk: int = 25) -> list[list[int]]:
    """Split ``range(n)`` into consecutive chunks: about four per worker, at most
    ``max_chunk`` long, so that progress is smooth and per-job overhead small."""
    w = workers or 1
    size = max(1, min(max_chunk, math.ceil(n / (w * 4))))
    return [list(range(s, min(s + size, n))) for s in range(0, n, size)]


def run_pool(worker: Callable[[Any], Any], jobs: Sequence[Any], workers: int | None = 1, desc: str = "",
             progress: bool = True, unit: str = "job", backend: str = "local", address: str | None = None,
             size: Callable[[Any], int] | None = None, total: int | None = None) -> list:
    """``[worker(job) for job in jobs]`` on the chosen backend, with a tqdm bar.

    Args:
        worker: a module-level function (it is pickled by reference).
        jobs: picklable job arguments.
        workers: processes (local) or tasks in flight (ray; None = cluster CPUs).
        desc, unit: progress bar label and unit.
        backend: "local" or "ray" (see the module docstring).
        address: Ray cluster address (ray only).
        size: how many bar units one result is (default 1), e.g. ``len`` for a
            job that returns a list of episodes.
        total: bar length in those units (default ``len(jobs)``).

    Returns: the results in job order.
    """
    validate_backend(backend, workers, address)
    from tqdm.auto import tqdm

    jobs = list(jobs)
    weight = size or (lambda _res: 1)
    out: list = [None] * len(jobs)
    with tqdm(total=total if total is not None else len(jobs), desc=desc, unit=unit, disable=not progress,
              file=sys.stderr) as bar:
        if backend == "ray":
            for i, res in _ray_map(worker, jobs, workers, address):
                out[i] = res
                bar.update(weight(res))
            return out
        if workers <= 1 or len(jobs) <= 1:
            for i, job in enumerate(jobs):
                out[i] = worker(job)
                bar.update(weight(out[i]))
            return out
        import multiprocessing as mp

        ctx = mp.get_context("spawn")
        with ctx.Pool(processes=min(workers, len(jobs))) as pool:
            for i, res in pool.imap_unordered(_Indexed(worker), list(enumerate(jobs))):
                out[i] = res
                bar.update(weight(res))
    return out


class _Indexed:
    """Picklable wrapper: ``(i, job) -> (i, worker(job))``."""

    def __init__(self, worker: Callable[[Any], Any]) -> None:
        self.worker = worker

    def __call__(self, item: tuple[int, Any]) -> tuple[int, Any]:
        i, job = item
        return i, self.worker(job)


def ray_init(address: str | None = None, num_cpus: int | None = None) -> None:
    """Start (``address=None``: a local instance with ``num_cpus``) or join a Ray
    cluster, once per process. Local workers import this checkout of ``ssl_marl``;
    on a cluster every node needs it installed (``pip install -e .``)."""
    try:
        import ray
    except ImportError:
        raise ValueError("backend 'ray' needs Ray, which is not installed: pip install -e \".[ray]\"") from None
    if ray.is_initialized():
        return
    kwargs: dict[str, Any] = dict(include_dashboard=False, log_to_driver=False)
    if address is None:
        import os
        from pathlib import Path

        # local workers inherit this environment: let them import this very checkout
        root = str(Path(__file__).resolve().parents[2])
        paths = os.environ.get("PYTHONPATH", "").split(os.pathsep)
        if root not in paths:
            os.environ["PYTHONPATH"] = os.pathsep.join([root, *[p for p in paths if p]])
        kwargs.update(num_cpus=num_cpus)
    else:
        kwargs.update(address=address)
    ray.init(**kwargs)


def _ray_map(worker: Callable[[Any], Any], jobs: list, workers: int | None, address: str | None):
    """Yield (index, result) as Ray tasks finish, at most ``workers`` in flight."""
    import ray

    ray_init(address, num_cpus=workers)
    remote = ray.remote(num_cpus=1)(worker)
    limit = workers or max(1, int(ray.cluster_resources().get("CPU", 1)))
    pending: dict[Any, int] = {}
    next_job = 0
    while next_job < len(jobs) or pending:
        while next_job < len(jobs) and len(pending) < limit:
            pending[remote.remote(jobs[next_job])] = next_job
            next_job += 1
        done, _ = ray.wait(list(pending), num_returns=1)
        for ref in done:
            yield pending.pop(ref), ray.get(ref)
