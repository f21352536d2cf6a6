"""Sweeps on a Dask cluster: the workers set up as the local pool's, the chunks as futures.

:func:`dask_executor` installs :class:`InitWorker` (one BLAS thread per worker) on a
``dask.distributed.Client``'s cluster and returns its executor; a sweep on Dask is
bit-identical to the same sweep run locally. Optional extra ``impactmaps[dask]``.
"""

from __future__ import annotations

import os

from distributed import WorkerPlugin

from .workers import init_worker

__all__ = ["InitWorker", "dask_executor", "is_dask", "worker_blas_threads"]

#: The name the plugin is registered under (registering it again replaces it).
PLUGIN_NAME = "impactmaps-init-worker"


def is_dask(executor) -> bool:
    """True if ``executor`` is a ``dask.distributed`` Client or a Client's executor (decided by
    its class's module: no import of Dask)."""
    return type(executor).__module__.split(".")[0] == "distributed"


def _worker_setup() -> None:
    """:func:`init_worker` in a Dask worker process: one BLAS thread (SIGINT left as Dask set it)."""
    init_worker(ignore_interrupts=False)


class InitWorker(WorkerPlugin):
    """Dask worker plugin: :func:`impactmaps.maps.compute.workers.init_worker` on each worker at
    start, also workers that join later (a thread worker of this process is left alone).
    """

    name = PLUGIN_NAME

    def __init__(self):
        self.owner_pid = os.getpid()

    def setup(self, worker=None) -> None:
        """Run :func:`init_worker` in the worker's process (not in the owner's)."""
        if os.getpid() != self.owner_pid:
            _worker_setup()

    def teardown(self, worker=None) -> None:
        """Nothing to undo (the worker process ends)."""


def dask_executor(client_or_executor):
    """``client.get_executor()`` of a Dask client (or the executor itself), with
    :class:`InitWorker` registered on its cluster: what
    :func:`impactmaps.maps.compute.sweep.sweep` submits chunks to.

    Raises
    ------
    ValueError
        ``client_or_executor`` is not a Dask client or a client's executor.
    """
    if not is_dask(client_or_executor):
        raise ValueError(f"client_or_executor = {type(client_or_executor).__name__} is not a dask.distributed "
                         "Client or a Client's get_executor()")
    client = getattr(client_or_executor, "_client", client_or_executor)
    client.register_plugin(InitWorker(), name=PLUGIN_NAME)
    return client_or_executor if client_or_executor is not client else client.get_executor()


def worker_slots(executor) -> int:
    """The threads of a Dask client's workers (at least 1): how many chunks run at once."""
    client = getattr(executor, "_client", executor)
    return max(1, sum(client.nthreads().values()))


def worker_blas_threads() -> int:
    """The BLAS threads of this process (the largest over the BLAS libraries loaded; 0 if none)."""
    from threadpoolctl import threadpool_info

    return max([int(info["num_threads"]) for info in threadpool_info() if info.get("user_api") == "blas"] or [0])
