"""Set-up of the worker processes that solve map points: one BLAS thread each (set with
``threadpoolctl``, SciPy's library loaded first, in the workers only), and Ctrl-C left
to the parent.
"""

from __future__ import annotations

import signal
from concurrent.futures import ProcessPoolExecutor

from ..._compile.compile_helper import end_with_parent

#: Most worker processes a sweep starts (``max_workers``, ``--workers``): more only
#: oversubscribe the cores, and each costs a process of memory.
MAX_WORKERS = 64

__all__ = ["init_worker", "MAX_WORKERS"]


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
