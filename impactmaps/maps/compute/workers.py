"""Set-up of the worker processes that solve map points.

A worker solves one point after another in a single thread, so it runs with one BLAS
thread: NumPy's default of one BLAS thread per core in *every* worker oversubscribes the
cores as soon as two workers share them. On the 2-core development machine the
200 × 50 grid of ``benchmarks/studies/bench_plane.py`` (Euler beam and Kirchhoff plate) took
26.5 s as a sweep with the default BLAS threads and 20.9 s with one per worker
(2026-11-24). The limit is set with ``threadpoolctl`` (it finds the BLAS library NumPy
and SciPy actually loaded: OpenBLAS, MKL or BLIS) and only inside the worker processes:
the user's own process keeps its threads. SciPy's library is loaded first: the compiled
set-up of the exact contact phase (``numpy.linalg.eigh`` in numba) calls LAPACK through
SciPy, whose OpenBLAS is a library of its own, and loaded after the limit it kept a
thread per core.
"""

from __future__ import annotations

import signal

from ..._compile.compile_helper import end_with_parent

#: Most worker processes a sweep starts (``max_workers``, ``--workers``): more only
#: oversubscribe the cores, and each costs a process of memory.
MAX_WORKERS = 64

__all__ = ["init_worker", "MAX_WORKERS"]


def init_worker(ignore_interrupts: bool = True) -> None:
    """Initialise a worker process: one BLAS thread, and Ctrl-C left to the parent.

    Parameters
    ----------
    ignore_interrupts : bool
        A worker of the sweep's own pool: ignore SIGINT (the parent catches Ctrl-C, saves
        what is done and stops the workers), end on SIGTERM, and end when the parent dies
        (Linux). False for a Dask worker, whose signals stay Dask's.

    Use as the ``initializer`` of a :class:`concurrent.futures.ProcessPoolExecutor`.
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
