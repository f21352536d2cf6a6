"""A sweep on a Dask LocalCluster of worker *processes* (not threads): bit-identical to the
local run, and every worker set up by ``init_worker`` (one BLAS thread) as the local pool's."""

from __future__ import annotations

import numpy as np
import pytest

from impactmaps.maps.family.structures import MapStructure
from impactmaps.maps.compute.sweep import Pacing, sweep

distributed = pytest.importorskip("distributed")  # the test extra has it; the [dask] extra for users

BEAM = MapStructure(kind="beam", theory="euler", supports="ss")
ZETAS = np.geomspace(0.01, 3.0, 8)
LAMBDAS = [0.05, 0.5, 5.0]


def _identical(a, b) -> None:
    """Every variable and coordinate of two sweeps, byte for byte."""
    assert sorted(a.variables) == sorted(b.variables)
    for name in a.variables:
        left, right = a[name].values, b[name].values
        assert left.dtype == right.dtype, name
        if left.dtype.kind in "OUS":
            assert left.tolist() == right.tolist(), name
        else:
            assert left.tobytes() == right.tobytes(), name


def test_sweep_on_dask_process_workers_is_bit_identical_and_workers_are_set_up():
    """24 points (8 ζ × 3 λ, Euler beam, linear law) in chunks of 2 on 2 worker processes
    × 1 thread: the same bytes as the inline run; the plugin gave each worker one BLAS thread."""
    from impactmaps.maps.compute.dask_backend import PLUGIN_NAME, worker_blas_threads

    local = sweep([BEAM], ZETAS, LAMBDAS, max_workers=1, progress=False)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                  worker_dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        remote = sweep([BEAM], ZETAS, LAMBDAS, executor=client, progress=False, pacing=Pacing(2))
        pids = client.run(lambda: __import__("os").getpid())
        threads = client.run(worker_blas_threads)
        plugins = client.run(lambda dask_worker: sorted(dask_worker.plugins))
    assert len(set(pids.values())) == 2 and __import__("os").getpid() not in pids.values()  # separate processes
    assert set(threads.values()) <= {1} and len(threads) == 2, threads
    assert all(PLUGIN_NAME in names for names in plugins.values())
    _identical(local, remote)
    assert int(remote["done"].sum()) == ZETAS.size * len(LAMBDAS)


def test_dask_executor_refuses_what_is_not_dask():
    from impactmaps.maps.compute.dask_backend import dask_executor

    with pytest.raises(ValueError, match="client_or_executor = ThreadPoolExecutor"):
        from concurrent.futures import ThreadPoolExecutor

        dask_executor(ThreadPoolExecutor(1))
