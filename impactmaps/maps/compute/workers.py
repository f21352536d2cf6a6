"""The worker processes that solve map points: their set-up (one BLAS thread each, set with
``threadpoolctl``, SciPy's library loaded first, in the workers only; Ctrl-C left to the
parent), used by a sweep's pool and Dask's workers, and the pool that solves a map tile's points
on the machine's cores (:func:`solve_tile_points`): worker processes forked after the parent has
built what every point shares.

A tile's points (:func:`impactmaps.maps.compute.tiles.build_tile`) share their structure, its
frequency cap and its modes: on a plate of the general Ritz basis the largest eigen-solution,
seconds of one BLAS thread (kept in the process's lru caches and on disk,
:mod:`impactmaps.targets.plates.basis_cache`). :func:`solve_tile_points` solves the first point
in the parent, which builds these and what a first run loads (the solver's modules and compiled
kernels, the plate's static stiffness factors, which each worker would repeat; measured in
docs/plates_any_edges.rst), then forks one worker per core (the *fork* start method: a
worker inherits the parent's memory and caches, sharing its pages copy-on-write, and never
recomputes them) and hands each worker one of the other points at a time. A point is a pure
function of its inputs, so the rows are the same bits as the serial solve, returned in the
points' order.

The workers are those of a sweep (:func:`init_worker`: one
BLAS thread each, Ctrl-C left to the parent, ended with it); on Ctrl-C or SIGTERM (a
``KeyboardInterrupt`` in the parent) or a failure they are ended at once
(:func:`end_workers`). The points are solved serially in the
calling process when it has one core, when ``fork`` is not available or another thread runs
(a Jupyter kernel's: a fork copies the locks they hold), when the process is itself a worker (a
sweep's, Dask's: no nested pools), or when the workers would not fit in the memory available
(:func:`point_workers`).
"""

from __future__ import annotations

import multiprocessing
import os
import resource
import signal
import sys
import threading
import warnings
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait

from ..._compile.compile_helper import end_with_parent

__all__ = ["init_worker", "end_workers", "MAX_WORKERS", "available_cores", "available_memory", "nested_process",
           "point_workers", "solve_tile_points"]

#: Most worker processes a sweep starts (``max_workers``, ``--workers``): more only
#: oversubscribe the cores, and each costs a process of memory.
MAX_WORKERS = 64


def init_worker(ignore_interrupts: bool = True) -> None:
    """Initialise a worker process (the ``initializer`` of a
    :class:`concurrent.futures.ProcessPoolExecutor`): one BLAS thread, Ctrl-C left to the parent.

    Parameters
    ----------
    ignore_interrupts : bool
        Ignore SIGINT, end on SIGTERM and with the parent (Linux); False for a Dask worker.
    """
    import scipy.linalg.cython_lapack  # noqa: F401 (loads SciPy's BLAS, the one compiled kernels call, so that it is limited too)
    from threadpoolctl import threadpool_limits

    threadpool_limits(limits=1, user_api="blas")
    if ignore_interrupts:  # a worker of the sweep's own pool (a Dask worker keeps Dask's signal handling)
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        # SIGTERM ends the worker: a forked one inherits the command line's handler, which would turn it
        # into a KeyboardInterrupt its task loop survives (then the parent's death could not end it)
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
        end_with_parent(signal.SIGTERM)  # a parent killed outright cannot stop its workers otherwise


def end_workers(executor: ProcessPoolExecutor) -> None:
    """End the worker processes of a sweep's own pool now (SIGTERM), not after their chunks in hand.

    At exit Python joins a process pool's workers, so a stopped sweep would otherwise wait for
    the longest chunk in flight (minutes for a cold worker compiling its kernels on a loaded
    machine); the parent keeps only saved points, so nothing a worker holds is lost.
    """
    for process in list((getattr(executor, "_processes", None) or {}).values()):
        if process.is_alive():
            process.terminate()


#: What the forked workers solve (set by the parent just before it forks them, cleared after):
#: the family, structure, settings, table and control of the points, and the points.
_JOB: dict = {}
#: Where the warnings of the workers' points are remembered when shown again in the parent
#: (file name → the registry :func:`warnings.warn_explicit` keeps, as a module's own).
_REGISTRIES: dict = {}
#: Seconds between the parent's checks of its workers (a signal interrupts the wait anyway).
_POLL_SECONDS = 0.25


def solve_map_points(*args, **kwargs) -> list:
    """:func:`impactmaps.maps.compute.points.solve_map_points`, imported when first called (the
    command line reads :data:`MAX_WORKERS` here without loading the solver)."""
    from .points import solve_map_points as solve

    return solve(*args, **kwargs)


def available_cores() -> int:
    """The cores this process may run on (its CPU affinity; else :func:`os.cpu_count`) [-]."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):  # not Linux
        return max(1, os.cpu_count() or 1)


def available_memory() -> float | None:
    """The memory available to new processes [B] (``MemAvailable`` of ``/proc/meminfo``, else
    the free physical pages); None where neither is known."""
    try:
        with open("/proc/meminfo", encoding="ascii") as meminfo:
            for line in meminfo:
                if line.startswith("MemAvailable:"):
                    return float(line.split()[1]) * 1024.0
    except (OSError, ValueError, IndexError):
        pass
    try:
        return float(os.sysconf("SC_AVPHYS_PAGES")) * float(os.sysconf("SC_PAGE_SIZE"))
    except (AttributeError, ValueError, OSError):
        return None


def nested_process() -> bool:
    """Whether this process is itself a worker (a process of :mod:`multiprocessing`, as a
    sweep's and Dask's workers are, or a daemon): its tile's points are solved in it."""
    return multiprocessing.parent_process() is not None or multiprocessing.current_process().daemon


def _can_fork() -> bool:
    """Whether workers may be forked here: ``fork`` exists and no other thread runs (a fork copies
    the locks another thread holds; the command line has none when it builds a tile)."""
    return "fork" in multiprocessing.get_all_start_methods() and threading.active_count() == 1


def _peak_resident_bytes() -> float:
    """The largest resident set of this process so far [B] (``ru_maxrss``: KiB on Linux)."""
    peak = float(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss)
    return peak if sys.platform == "darwin" else peak * 1024.0


def point_workers(points: int, worker_bytes: float, cores: int | None = None, memory: float | None = None) -> int:
    """The worker processes to solve ``points`` points with: one per core (at most one per point),
    fewer while ``workers × worker_bytes`` would exceed ``memory`` (default
    :func:`available_memory`; unknown: no limit); 1 means serially in this process.

    Parameters
    ----------
    points : int
        Points to solve [-].
    worker_bytes : float
        What one worker may hold [B]: the parent's largest resident set so far in
        :func:`solve_tile_points` (a forked worker shares the parent's pages copy-on-write and copies
        only those it writes; its own solves hold dense matrices no larger than the eigen-solution the
        parent built), so the sum over the workers overstates their memory.
    cores : int, optional
        Default :func:`available_cores`.
    memory : float, optional
        The memory available [B].
    """
    workers = min(int(points), cores or available_cores())
    memory = available_memory() if memory is None else memory
    if memory is not None and worker_bytes > 0:
        workers = min(workers, int(memory // worker_bytes))
    return max(1, workers)


def solve_tile_points(family, structure, points: list, settings, table, control, progress=None,
                      chunk: int | None = None, workers: int | None = None) -> list[dict]:
    """Solve a tile's points (:func:`~impactmaps.maps.compute.points.solve_map_points`): the first
    in this process, the others on :func:`point_workers` forked workers when there are several
    (module docstring).

    Parameters
    ----------
    family, structure, points, settings, table, control
        As :func:`~impactmaps.maps.compute.points.solve_map_points`.
    progress : callable, optional
        ``progress(done, total)`` [points], each time ``done`` reaches a multiple of ``chunk``
        and at the end.
    chunk : int, optional
        Points per progress report and per call when solved serially (default 1 on the
        workers, all serially).
    workers : int, optional
        Most worker processes (default one per core; 1: serially).

    Returns
    -------
    list of dict
        One row per point, in the order of ``points``: the same bits however solved.
    """
    points = list(points)
    total = len(points)
    step = chunk or 1

    def report(done: int) -> None:
        if progress is not None and (done % step == 0 or done == total):
            progress(done, total)

    # the first point here: what every point shares (the target, its cap, the table, the Ritz
    # eigen-solution) and what a first run loads (its solver's modules and compiled kernels, the
    # plate's static factors) are built once, and the workers forked below inherit them
    rows = solve_map_points(family, structure, points[:1], settings, table, control)
    if rows:
        report(len(rows))
    rest = points[1:]
    count = min(len(rest), workers or len(rest))
    if count > 1 and not nested_process() and _can_fork():
        count = point_workers(len(rest), _peak_resident_bytes(), min(available_cores(), count))
    else:  # a worker's own tile, or nothing to share: here
        count = 1
    if count > 1:
        return rows + _on_workers(count, dict(family=family, structure=structure, points=rest, settings=settings,
                                              table=table, control=control), report, len(rows))
    step = chunk or max(total, 1)
    while len(rows) < total:  # the calls end where the reports fall (the chunks of all the points)
        end = min((len(rows) // step + 1) * step, total)
        rows += solve_map_points(family, structure, points[len(rows):end], settings, table, control)
        report(len(rows))
    return rows


def _on_workers(count: int, job: dict, report, before: int) -> list[dict]:
    """The rows of ``job``'s points solved one a task on ``count`` forked workers, in order;
    ``report(done)`` after each, counting the ``before`` points solved already; each point's
    warnings shown again here, in the points' order, after all are solved."""
    results = [None] * len(job["points"])
    _JOB.update(job)  # read by the workers forked below (the fork copies it; nothing is pickled)
    executor = ProcessPoolExecutor(max_workers=count, mp_context=multiprocessing.get_context("fork"),
                                   initializer=init_worker)
    finished = False
    try:
        futures = {executor.submit(_solve_one, index): index for index in range(len(results))}
        pending, done = set(futures), before
        while pending:
            ready, pending = wait(pending, timeout=_POLL_SECONDS, return_when=FIRST_COMPLETED)
            for future in sorted(ready, key=futures.get):
                results[futures[future]] = future.result()
                done += 1
                report(done)
        finished = True
    finally:
        _JOB.clear()
        if not finished:  # Ctrl-C, SIGTERM or a failure: the points in hand are not waited for
            end_workers(executor)
        executor.shutdown(wait=finished, cancel_futures=True)
    for _, caught in results:
        for message, category, filename, lineno in caught:
            warnings.warn_explicit(message, category, filename, lineno,
                                   registry=_REGISTRIES.setdefault(filename, {}))
    return [row for row, _ in results]


def _solve_one(index: int) -> tuple[dict, list]:
    """(row, warnings) of the ``index``-th point of the inherited job (in a worker); the warnings
    as (message, category, file name, line) to be shown by the parent."""
    job = _JOB
    with warnings.catch_warnings(record=True) as caught:  # the parent's filters, inherited
        row, = solve_map_points(job["family"], job["structure"], [job["points"][index]], job["settings"],
                                job["table"], job["control"])
    return row, [(str(w.message), w.category, w.filename, w.lineno) for w in caught]
