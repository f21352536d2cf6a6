"""A sweep of many points on a Dask LocalCluster of worker processes: points/s, 1 vs 2 workers.

Workload: a square log grid over ζ, λ ∈ [1e-3, 1e3]² for ``beam-ss-euler`` (linear law),
``n × n`` points with ``n = round(sqrt(--points))`` (10⁶ by default: 1000 × 1000), every
point solved as a sweep solves it (:func:`impactmaps.maps.compute.sweep.sweep`: base run,
refinement, error and status; chunks of ``--chunk`` points per task, no result file). A
smaller count samples the same plane on a coarser grid, so its points/s is that of the
full grid up to the sampling of the costly corners; the 10⁶-point time is estimated from
it as 10⁶ / (points/s).

For each worker count (``--workers``, default 1 and 2): a ``LocalCluster(n_workers=W,
threads_per_worker=1, processes=True)``; its start and a warm-up sweep of a 6 × 6 grid of the
same plane (the workers import impactmaps and load or compile every kernel the grid uses; :mod:`impactmaps.maps.compute.dask_backend`
registers ``init_worker``) are timed apart from the measured sweep. The local process pool
(``sweep(..., max_workers=2)``, after the same warm-up inline) runs the same grid as the
reference (``--no-local`` skips it).
Every run's F̄max and status are compared bit for bit with the first run's.

Run: ``python benchmarks/studies/bench_dask.py [--points N] [--workers 1 2] [--out benchmarks/studies/RESULTS_dask.md]``.
"""

from __future__ import annotations

import argparse
import datetime
import os
import pathlib
import sys
import time
import warnings

if __name__ == "__main__":  # one BLAS thread per process, before NumPy loads it (workers inherit it)
    for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ.setdefault(_name, "1")

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))  # this checkout's impactmaps, not an installed one
STRUCTURE = "beam-ss-euler"
FULL = 10**6
#: Points of the warm-up sweep (a 6 × 6 grid of the same plane: every code path the grid takes compiles or loads).
WARM_UP = 36


def grid(points: int):
    """The ζ and λ grids of a ``points``-point square log grid over [1e-3, 1e3]²."""
    n = max(2, int(round(np.sqrt(points))))
    values = np.geomspace(1e-3, 1e3, n)
    return values, values.copy()


def run_sweep(executor, zetas, lambdas, chunk: int, max_workers=None):
    """(seconds, dataset) of one sweep of the grid."""
    from impactmaps.maps.family.structures import structure_from_name
    from impactmaps.maps.compute.sweep import Pacing, sweep

    start = time.perf_counter()
    dataset = sweep([structure_from_name(STRUCTURE)], zetas, lambdas, executor=executor, max_workers=max_workers,
                    progress=False, pacing=Pacing(chunk_size=chunk))
    return time.perf_counter() - start, dataset


def dask_run(workers: int, zetas, lambdas, chunk: int) -> dict:
    """Start a LocalCluster of ``workers`` processes, warm it up, time the sweep."""
    from dask.distributed import Client, LocalCluster

    start = time.perf_counter()
    with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None,
                      worker_dashboard_address=None) as cluster, Client(cluster) as client:
        started = time.perf_counter() - start
        warm, _ = run_sweep(client, *grid(WARM_UP), 1)
        seconds, dataset = run_sweep(client, zetas, lambdas, chunk)
    return {"label": f"Dask LocalCluster, {workers} worker process(es) × 1 thread", "workers": workers,
            "start": started, "warm": warm, "seconds": seconds, "dataset": dataset}


def local_run(workers: int, zetas, lambdas, chunk: int) -> dict:
    """The same grid on the sweep's own process pool, after the warm-up inline (its workers
    fork this process: what it compiled or loaded, they have)."""
    warm, _ = run_sweep(None, *grid(WARM_UP), 1, max_workers=1)
    seconds, dataset = run_sweep(None, zetas, lambdas, chunk, max_workers=workers)
    return {"label": f"local process pool (sweep's default), {workers} workers", "workers": workers,
            "start": 0.0, "warm": warm, "seconds": seconds, "dataset": dataset}


def report(args, runs, zetas, lambdas) -> str:
    points = zetas.size * lambdas.size
    first = runs[0]["dataset"]
    lines = [f"# A sweep on a Dask LocalCluster: {points} points ({zetas.size} ζ × {lambdas.size} λ, {STRUCTURE})", "",
             f"`python benchmarks/studies/bench_dask.py {' '.join(args.argv)}`".replace("  ", " "),
             f"run {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC on {os.cpu_count()} cores "
             f"(load average before: {args.load:.1f}), chunks of {args.chunk} points, no result file", "",
             "| run | workers | cluster start [s] | warm-up [s] | sweep wall [s] | points/s | points/s per worker | "
             "10⁶ points (est.) [min] | F̄max, status vs first run |", "|---|---|---|---|---|---|---|---|---|"]
    for run in runs:
        rate = points / run["seconds"]
        same = all(np.array_equal(run["dataset"][name].values, first[name].values, equal_nan=True)
                   for name in ("fmax_normalised", "status"))
        lines.append(f"| {run['label']} | {run['workers']} | {run['start']:.1f} | {run['warm']:.1f} | "
                     f"{run['seconds']:.1f} | {rate:.0f} | {rate / run['workers']:.0f} | {FULL / rate / 60:.1f} | "
                     f"{'identical' if same else 'DIFFER'} |")
    dasks = [run for run in runs if run["label"].startswith("Dask")]
    if len(dasks) >= 2:
        one, two = dasks[0], dasks[-1]
        lines += ["", f"Speed-up {one['workers']} → {two['workers']} Dask workers: "
                  f"**{one['seconds'] / two['seconds']:.2f}×** (wall of the measured sweep)."]
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--points", type=int, default=FULL, help="grid points (a square grid; default 10⁶)")
    parser.add_argument("--workers", type=int, nargs="+", default=[1, 2], help="Dask worker processes to compare")
    parser.add_argument("--chunk", type=int, default=40, help="points per task (the sweep's Pacing.chunk_size)")
    parser.add_argument("--no-local", action="store_true", help="skip the local process-pool reference run")
    parser.add_argument("--out", type=pathlib.Path, default=ROOT / "benchmarks" / "studies" / "RESULTS_dask.md")
    args = parser.parse_args(argv)
    if args.points < 4 or min(args.workers) < 1 or args.chunk < 1:
        parser.error(f"--points = {args.points} (≥ 4), --workers = {args.workers} (≥ 1), --chunk = {args.chunk} (≥ 1)")
    args.argv = sys.argv[1:] if argv is None else list(argv)
    args.load = os.getloadavg()[0]
    warnings.simplefilter("ignore")
    zetas, lambdas = grid(args.points)
    runs = []
    for workers in args.workers:
        runs.append(dask_run(workers, zetas, lambdas, args.chunk))
        print(f"{runs[-1]['label']}: {runs[-1]['seconds']:.1f} s", flush=True)
    if not args.no_local:
        runs.append(local_run(max(args.workers), zetas, lambdas, args.chunk))
        print(f"{runs[-1]['label']}: {runs[-1]['seconds']:.1f} s", flush=True)
    text = report(args, runs, zetas, lambdas)
    args.out.write_text(text)
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
