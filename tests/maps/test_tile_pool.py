"""A tile's points solved on the machine's cores (impactmaps.maps.compute.workers, issue 39
item 7): the same bits as the serial solve, in the points' order, with progress and the points'
warnings; the workers gone when the parent is interrupted (Ctrl-C, SIGTERM: exit 130); serial
in a worker process, on one core, or when the workers would not fit in memory."""

from __future__ import annotations

import multiprocessing
import os
import signal
import subprocess
import sys
import textwrap
import time
import warnings
from pathlib import Path

import numpy as np
import pytest

from impactmaps.maps.compute import tiles
from impactmaps.maps.compute import workers as tile_pool
from impactmaps.maps.family.structures import MapStructure

from ..helpers import case_text

_BEAM = MapStructure(kind="beam", theory="euler", supports="cc", impact_fraction=(0.5,))
_CLAMPED_BEAM = """
    type = "beam"
    length = 0.5
    width = 0.02
    height = 0.02
    material = "structural-steel"
    theory = "euler"
    supports = "cc"
"""

needs_fork = pytest.mark.skipif("fork" not in multiprocessing.get_all_start_methods(), reason="no fork here")


def _alive(pid: int) -> bool:
    """Whether process ``pid`` runs (a zombie, ended but not yet reaped, does not)."""
    try:
        with open(f"/proc/{pid}/stat") as stat:
            return stat.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


@needs_fork
@pytest.mark.parametrize("law, numbers", [("hertz", (0.3, 2.0)),
                                          pytest.param("linear", (2.0, 0.05), marks=pytest.mark.slow)])
def test_a_tile_solved_on_two_workers_is_the_serial_tile_bit_for_bit(law, numbers, monkeypatch):
    """A clamped beam's 16-point tile built on 2 forked workers and serially: identical arrays
    (every variable, NaN where unresolved), attributes and digest; the parallel build first, so
    that its workers start from the parent's state after one point."""
    key = tiles.tile_for(_BEAM, law, None, *numbers)
    pools = []
    monkeypatch.setattr(tile_pool, "_on_workers", lambda count, *args, solve=tile_pool._on_workers: (
        pools.append(count) or solve(count, *args)))
    monkeypatch.setattr(tile_pool, "available_cores", lambda: 2)
    monkeypatch.setattr(tile_pool, "_can_fork", lambda: True)  # whatever threads the test session runs
    parallel = tiles.build_tile(key, workers=2)
    assert pools == [2]
    serial = tiles.build_tile(key, workers=1)
    assert parallel.attrs == serial.attrs
    for name in serial.data_vars:
        assert parallel[name].dtype == serial[name].dtype
        np.testing.assert_array_equal(parallel[name].values, serial[name].values, err_msg=name, strict=True)


def _fake_solve(family, structure, points, *rest):
    """A stand-in of solve_map_points: a row per point naming it and the process, a warning each."""
    for point in points:
        warnings.warn(f"point {point[0]}", UserWarning)
    return [{"point": point[0], "pid": os.getpid()} for point in points]


@needs_fork
def test_the_rows_come_in_the_points_order_with_progress_and_the_points_warnings(monkeypatch):
    """Rows in the order of the points whichever process solved them (the first the parent, the
    others the workers), progress (done, total) after each point up to (total, total), each point's
    warning shown by the parent in the points' order."""
    monkeypatch.setattr(tile_pool, "solve_map_points", _fake_solve)
    monkeypatch.setattr(tile_pool, "available_cores", lambda: 2)
    monkeypatch.setattr(tile_pool, "_can_fork", lambda: True)
    calls = []
    points = [(float(k), 1.0) for k in range(12)]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        rows = tile_pool.solve_tile_points(None, None, points, None, None, None, lambda *a: calls.append(a),
                                           workers=2)
    assert [row["point"] for row in rows] == [point[0] for point in points]
    assert rows[0]["pid"] == os.getpid() and os.getpid() not in {row["pid"] for row in rows[1:]}
    assert calls == [(k, 12) for k in range(1, 13)]
    calls.clear()  # a report each chunk of points (a plane of a tile), on the workers as serially
    for workers in (2, 1):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            again = tile_pool.solve_tile_points(None, None, points, None, None, None, lambda *a: calls.append(a),
                                                chunk=5, workers=workers)
        assert [row["point"] for row in again] == [point[0] for point in points]
        assert calls == [(5, 12), (10, 12), (12, 12)]
        calls.clear()
    assert [str(w.message) for w in caught] == [f"point {float(k)}" for k in range(12)]


def test_serial_when_nested_on_one_core_or_short_of_memory(monkeypatch):
    """No pool with one core, while another thread runs, nor inside a worker process (a sweep's,
    Dask's); the memory: as many workers as ``memory // worker_bytes`` allows, at least 1 (serial)."""
    monkeypatch.setattr(tile_pool, "solve_map_points", _fake_solve)

    def no_pool(*args, **kwargs):
        raise AssertionError("a pool was started")

    monkeypatch.setattr(tile_pool, "ProcessPoolExecutor", no_pool)
    points = [(float(k), 1.0) for k in range(4)]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        monkeypatch.setattr(tile_pool, "available_cores", lambda: 1)
        assert {row["pid"] for row in tile_pool.solve_tile_points(None, None, points, None, None, None)} == {os.getpid()}
        monkeypatch.setattr(tile_pool, "available_cores", lambda: 8)
        monkeypatch.setattr(tile_pool.threading, "active_count", lambda: 2)  # another thread runs
        assert {row["pid"] for row in tile_pool.solve_tile_points(None, None, points, None, None, None)} == {os.getpid()}
        monkeypatch.setattr(tile_pool.threading, "active_count", lambda: 1)
        monkeypatch.setattr(multiprocessing, "parent_process", lambda: object())
        assert {row["pid"] for row in tile_pool.solve_tile_points(None, None, points, None, None, None)} == {os.getpid()}
    assert tile_pool.point_workers(9, 1e9, cores=2, memory=64e9) == 2
    assert tile_pool.point_workers(9, 1e9, cores=8, memory=3.5e9) == 3
    assert tile_pool.point_workers(9, 1e9, cores=8, memory=0.5e9) == 1
    assert tile_pool.point_workers(1, 1e9, cores=8, memory=64e9) == 1


def _slow_solve(family, structure, points, *rest):
    """A stand-in of solve_map_points whose points take a minute but the first (the parent's)."""
    if points and points[0][0] > 0:
        time.sleep(60)
    return [{} for _ in points]


@needs_fork
def test_ctrl_c_ends_the_workers_at_once(monkeypatch):
    """Ctrl-C (a KeyboardInterrupt in the parent, raised here by a timer's signal) while the workers
    solve: the interrupt reaches the caller without waiting for the points in hand, and the workers
    are gone."""
    monkeypatch.setattr(tile_pool, "solve_map_points", _slow_solve)
    monkeypatch.setattr(tile_pool, "available_cores", lambda: 2)
    monkeypatch.setattr(tile_pool, "_can_fork", lambda: True)
    workers = []

    def interrupt(*_):
        workers[:] = [child.pid for child in multiprocessing.active_children()]
        raise KeyboardInterrupt

    previous = signal.signal(signal.SIGALRM, interrupt)
    start = time.monotonic()
    try:
        signal.setitimer(signal.ITIMER_REAL, 1.0)
        with pytest.raises(KeyboardInterrupt):
            tile_pool.solve_tile_points(None, None, [(0.0, 1.0)] + [(1.0, 1.0)] * 4, None, None, None, workers=2)
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0.0)
        signal.signal(signal.SIGALRM, previous)
    assert len(workers) == 2 and time.monotonic() - start < 30  # not the minute of a point
    deadline = time.monotonic() + 10
    while any(_alive(pid) for pid in workers) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert not any(_alive(pid) for pid in workers)


@needs_fork
@pytest.mark.parametrize("how", [signal.SIGTERM, pytest.param(signal.SIGINT, marks=pytest.mark.slow)])
def test_a_signal_ends_a_lookup_building_its_tile_with_130_and_no_worker_left(tmp_path, how):
    """``impactmaps lookup --case`` of a clamped beam (a new tile), its points made to take a
    minute: SIGTERM or Ctrl-C while the workers solve ends the command with status 130 and
    ``interrupted``, long before a point would end, and its workers with it."""
    case = tmp_path / "beam.toml"
    case.write_text(case_text(_CLAMPED_BEAM, radius=0.01))
    program = textwrap.dedent(f"""
        import sys, time
        from impactmaps.maps.compute import workers as tile_pool
        def slow(family, structure, points, *rest, solve=tile_pool.solve_map_points):
            if points and tile_pool.nested_process():  # a worker's point (the parent's first: solved)
                time.sleep(60)
            return solve(family, structure, points, *rest)
        tile_pool.solve_map_points = slow
        tile_pool.available_cores = lambda: 2
        from impactmaps.cli import main
        sys.argv = ["impactmaps", "lookup", "--case", {str(case)!r}, "--quiet"]
        main()
    """)
    import impactmaps

    root = str(Path(impactmaps.__file__).resolve().parents[1])
    env = dict(os.environ, IMPACTMAPS_CACHE_DIR=str(tmp_path), IMPACTMAPS_NO_BACKGROUND_WARMUP="1",
               PYTHONPATH=os.pathsep.join([root, os.environ.get("PYTHONPATH", "")]))
    process = subprocess.Popen([sys.executable, "-c", program], env=env, stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True)
    workers: list[int] = []
    deadline = time.monotonic() + 60
    while len(workers) < 2 and time.monotonic() < deadline and process.poll() is None:
        time.sleep(0.1)
        found = subprocess.run(["pgrep", "-P", str(process.pid)], capture_output=True, text=True).stdout
        workers = [int(pid) for pid in found.split()]
    assert len(workers) >= 2, "the lookup started no workers"
    time.sleep(0.3)  # the workers set up (their signal handlers)
    process.send_signal(how)
    _, err = process.communicate(timeout=30)  # not the minute of a point: the workers hold the pipes too
    assert process.returncode == 130 and "interrupted" in err and "Traceback" not in err, err
    deadline = time.monotonic() + 10
    while any(_alive(pid) for pid in workers) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert not any(_alive(pid) for pid in workers), f"workers left after {how.name}"
