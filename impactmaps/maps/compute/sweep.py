"""Sweeps of any map family over its axes → labelled xarray Datasets, resumable.

Points are solved in chunks (one structure, every axis but ζ) by any
:class:`concurrent.futures.Executor` or a Dask client (:mod:`.dask_backend`); finished
chunks are saved atomically, so an interrupted sweep resumes where it stopped.
"""

from __future__ import annotations

import itertools
import os
import signal
import sys
import threading
import time
from concurrent.futures import FIRST_COMPLETED, Executor, ProcessPoolExecutor, wait
from dataclasses import asdict
from typing import NamedTuple, Sequence

import numpy as np
import xarray as xr

from ..._checks import range_end_text, require_in_range, require_positive
from ...solvers.modal_settings import ModalSettings
from ...solvers.run_budget import (MEMORY_LIMIT_BYTES, SECONDS_PER_MAP_POINT, RunBudget, map_sweep_seconds,
                                   refuse_or_announce)
from ...targets.options import point_load_diverges
from ..family.map_family import ASYMPTOTE_PEAKS, RESULT_VARIABLES, MapFamily, map_family
from .dataset import classify_dataset, empty_dataset, with_asymptote_peaks
from .points import METHODS, SOLVER_REVISION, solve_map_points
from ..files.data_io import read_dataset
from ..files.shipped import load_shipped_result
from ..files.store import SweepInterrupted, fingerprint, load_matching, remove_stale_temporaries, save_atomic
from ..family.structures import MapStructure, warn_point_loaded_mindlin
from .workers import MAX_WORKERS, end_workers, init_worker

__all__ = ["sweep", "sweep_fingerprint", "log_grid", "check_axis", "sweep_grid", "run_sweep_grid", "SweepTask",
           "SweepGrid", "Pacing", "MAP_COPIES", "require_map_fits"]


def log_grid(start: float, stop: float, count: int) -> np.ndarray:
    """``count`` log-spaced values from ``start`` to ``stop`` (both > 0)."""
    require_positive("start", start)
    require_positive("stop", stop)
    return np.geomspace(start, stop, int(count))


class Pacing(NamedTuple):
    """How a sweep's work is cut and saved (the values do not depend on it): ``chunk_size``
    points per task, ``save_interval`` minimum seconds between saves.
    """

    chunk_size: int = 40
    save_interval: float = 1.0


class SweepTask(NamedTuple):
    """One chunk of a sweep: points sharing a structure and every axis value but ζ."""

    structure: MapStructure
    index: tuple  # (structure index, index along each axis before ζ)
    zeta_indices: list
    points: list  # the points' numbers, (…, ζ, λ)


class SweepGrid(NamedTuple):
    """A checked sweep (:func:`sweep_grid`): its structures, family, axes (name → values),
    description, fingerprint and solver settings."""

    structures: list
    family: MapFamily
    axes: dict
    description: dict
    digest: str
    settings: ModalSettings


def sweep(
    structures: Sequence[MapStructure],
    loss_factors,
    relative_stiffnesses,
    *,
    settings: ModalSettings | None = None,
    path: str | os.PathLike | None = None,
    executor: Executor | None = None,
    max_workers: int | None = None,
    progress: bool = True,
    pacing: Pacing = Pacing(),
    overwrite: bool = False,
    law: str | MapFamily = "linear",
    axes: dict | None = None,
) -> xr.Dataset:
    """Compute F̄max and companions over structures × the axes of a map family.

    Parameters
    ----------
    structures : sequence of MapStructure
    loss_factors, relative_stiffnesses : array_like
        The ζ and λ grids [-].
    settings : ModalSettings, optional
        Solver settings (part of the result's fingerprint).
    path : path-like, optional
        Result file, saved atomically as points complete; a re-run computes only the
        missing points.
    executor : concurrent.futures.Executor or dask.distributed.Client, optional
        Where chunks run (default: a local process pool of ``max_workers``, 1 inline).
    max_workers : int, optional
    progress : bool
        Show a tqdm progress bar.
    pacing : Pacing
    overwrite : bool
        Replace a result file made by another sweep instead of refusing it.
    law : str or MapFamily
        The map family (``"linear"``, ``"hertz"``, ``"yc"``, ``"stronge"``, ``"epp"``, …).
    axes : dict, optional
        The grids of the family's axes before λ and ζ (``{"beta": …}``) [-].

    Returns
    -------
    xarray.Dataset
        Dims ``structure`` and the family's axes; its variables, ``done`` and ``regime``.

    Raises
    ------
    SweepInterrupted
        On Ctrl-C, after saving the finished points.
    ValueError
        Bad grids or settings, a result file of another sweep, or a map too large.
    """
    settings = settings or ModalSettings()
    if max_workers is not None:
        require_in_range("max_workers", max_workers, 1, MAX_WORKERS)
    grid = _prepare(structures, loss_factors, relative_stiffnesses, settings, law, axes)
    return _run_grid(grid, path, executor, max_workers, progress, pacing, overwrite)


def run_sweep_grid(grid: SweepGrid, *, path: str | os.PathLike | None = None, executor: Executor | None = None,
                   max_workers: int | None = None, progress: bool = True, pacing: Pacing = Pacing(),
                   overwrite: bool = False) -> xr.Dataset:
    """Run a checked sweep (:func:`sweep_grid`) without checking its grid again; the other
    parameters, the result and the errors are those of :func:`sweep`."""
    if max_workers is not None:
        require_in_range("max_workers", max_workers, 1, MAX_WORKERS)
    return _run_grid(grid, path, executor, max_workers, progress, pacing, overwrite)


def _run_grid(grid: SweepGrid, path, executor, max_workers, progress, pacing, overwrite) -> xr.Dataset:
    """The sweep of a checked grid (:func:`sweep`, :func:`run_sweep_grid`; warnings name their caller)."""
    settings = grid.settings
    diverging = [structure for structure in grid.structures if point_load_diverges(structure.theory)]
    if diverging:
        warn_point_loaded_mindlin("the Mindlin points of this sweep strike", stacklevel=3,
                                  ritz=any(not structure.build().uses_navier for structure in diverging))
    dataset, shipped = _resume(path, overwrite, grid)
    if shipped and progress:
        print(f"impact map: all {dataset['done'].size} points from the result shipped for this sweep "
              f"(impactmaps.maps.files.shipped, {grid.digest[:12]}…)", file=sys.stderr)
    done = dataset["done"].values.astype(bool)
    if progress and not shipped and path is not None and done.any():
        print(f"impact map: resuming {path}: {int(done.sum())} of {done.size} points already saved", file=sys.stderr)
    chunk_size = max(1, int(pacing.chunk_size))
    missing_per_row = done.shape[-1] - np.count_nonzero(done, axis=-1)
    remaining = int(missing_per_row.sum())
    n_tasks = int(np.ceil(missing_per_row / chunk_size).sum())
    ritz = [s.kind == "plate" and not s.build().uses_navier for s in grid.structures]  # Ritz bases cost more
    _announce(remaining, executor, max_workers, progress=progress, seconds=map_sweep_seconds(
        missing_per_row.reshape(len(grid.structures), -1).sum(axis=1), ritz))
    results = _Results(dataset, path, pacing.save_interval, remaining, progress, grid.family.variables)
    # the tasks are made as they are submitted: a list of them took ~165 B a point (1.5 GB for 9·10⁶)
    stopped = _run(_chunks(grid, done, chunk_size), n_tasks, settings, executor, max_workers, results, grid.family)
    return _finish(results, stopped, grid.family)


def _announce(points: int, executor: Executor | None, max_workers: int | None, seconds: float | None = None,
              progress: bool = False) -> None:
    """Say (``progress``: one line on stderr) and announce (:class:`~impactmaps.solvers.run_budget.LongRunWarning`,
    above a minute) the cost of the ``points`` to compute, ``seconds`` of CPU (default at the linear
    plane's mean, :data:`~impactmaps.solvers.run_budget.SECONDS_PER_MAP_POINT`), before the sweep starts."""
    workers = (getattr(executor, "_max_workers", None) or 1) if executor is not None else \
        (max_workers or os.cpu_count() or 1)
    seconds = points * SECONDS_PER_MAP_POINT if seconds is None else seconds
    if progress and points:
        print(f"impact map: {points} points to compute on {workers} worker(s), about {seconds / workers:.0f} s "
              f"({seconds:.0f} CPU-s)", file=sys.stderr)
    hint = (f"{points} points to compute on {workers} worker(s) at {seconds / max(points, 1) * 1e3:.1f} ms a point "
            "(docs/sweeps.rst); Hertz and elastic-plastic points cost more")
    refuse_or_announce(RunBudget(0.0, seconds / workers, "", hint), "this sweep", stacklevel=5)


def sweep_fingerprint(structures: Sequence[MapStructure], loss_factors, relative_stiffnesses,
                      settings: ModalSettings | None = None, law: str | MapFamily = "linear",
                      axes: dict | None = None) -> str:
    """The fingerprint of the sweep these arguments describe (what its result file is named by).

    Parameters are those of :func:`sweep`; the fingerprint covers them and
    :data:`SOLVER_REVISION` (:func:`impactmaps.maps.files.store.fingerprint`).
    """
    return _prepare(structures, loss_factors, relative_stiffnesses, settings or ModalSettings(), law, axes).digest


# -- the stages of a sweep -------------------------------------------------------------------
#: The parameter of :func:`sweep` that gives each axis (another axis: its name in ``axes``).
_PARAMETERS = {"zeta": "loss_factors", "lambda_": "relative_stiffnesses"}


def check_axis(family: MapFamily, name: str, values, label: str | None = None, written=None) -> np.ndarray:
    """The grid of axis ``name`` of ``family`` as a flat float array [-], checked: every value
    finite and in the family's range for the axis (> 0 where it states none).

    ``ValueError`` names ``label`` (default: the parameter of :func:`sweep`) and the value as
    the user wrote it: ``written`` (a sweep file's table or list, then ``label`` is its key) or
    ``values``.
    """
    grid = np.asarray(values, dtype=float).ravel()
    if written is not None:  # a sweep file: its values are already finite and > 0
        low, high = family.axis_range(name)
        if np.any(grid < low) or np.any(grid > high):
            raise ValueError(f"{label} = {written!r} is invalid: every value must be in [{range_end_text(low)}, "
                             f"{range_end_text(high)}] (beyond it the realised impactor's numbers under- or overflow)")
        return grid
    label = label or _PARAMETERS.get(name, name)
    if name in family.axis_ranges:
        require_in_range(label, grid, *family.axis_ranges[name])
    else:  # an axis whose family states no range: any positive value
        require_positive(label, grid)
    return grid


def _prepare(structures, loss_factors, relative_stiffnesses, settings: ModalSettings, law="linear",
             axes: dict | None = None) -> SweepGrid:
    """The checked grid of :func:`sweep`'s arguments (:func:`check_axis`, :func:`sweep_grid`)."""
    family = map_family(law)
    structures = list(structures)
    if not structures:
        raise ValueError("structures is empty: give at least one MapStructure")
    extra = {axis.name for axis in family.extra_axes}
    given = dict(axes or {})
    if set(given) != extra:
        raise ValueError(f"axes = {sorted(given)} is invalid for the {family.name} maps: give "
                         + (f"the grids of {sorted(extra)}" if extra else "none (their axes are ζ and λ)"))
    given = {name: np.asarray(values, dtype=float).ravel() for name, values in given.items()}
    given |= {"lambda_": np.asarray(relative_stiffnesses, dtype=float).ravel(),
              "zeta": np.asarray(loss_factors, dtype=float).ravel()}
    checked = {name: check_axis(family, name, given[name]) for name in ("zeta", "lambda_", *sorted(extra))}
    return sweep_grid(structures, family, {name: checked[name] for name in given}, settings)


def sweep_grid(structures: list, family: MapFamily, grids: dict, settings: ModalSettings) -> SweepGrid:
    """The sweep of ``structures`` (non-empty) over ``grids`` (each axis of ``family`` → its
    values, checked by :func:`check_axis`; the other axes first, then λ and ζ, the order the
    memory refusal names them) with ``settings``: refused (``ValueError``) if an
    axis is empty or the map would not fit in memory (:func:`require_map_fits`); else its
    description and fingerprint (what a stored result must match).
    """
    extra = [name for name in grids if name not in ("zeta", "lambda_")]
    if any(values.size == 0 for values in grids.values()):
        sizes = " × ".join(f"{grids[name].size} {symbol}" for name, symbol in
                           (("zeta", "ζ"), ("lambda_", "λ"), *((name, name) for name in sorted(extra))))
        raise ValueError(f"the grid is empty ({sizes} values): give at least one of each")
    symbols = {"zeta": "ζ", "lambda_": "λ"}
    require_map_fits(len(structures), {symbols.get(name, name): values.size for name, values in grids.items()}, family)
    description = {"structures": [s.as_dict() for s in structures], "zeta": grids["zeta"],
                   "lambda_": grids["lambda_"], "settings": asdict(settings), "solver_revision": SOLVER_REVISION}
    description |= {name: grids[name] for name in extra}
    if family.law_in_description:  # the linear description has no law key: its fingerprints stay those shipped
        description["law"] = family.name
    if family.law_revision != 1:  # a redefined law: no stored result of its old definition matches
        description["law_revision"] = family.law_revision
    if revisions := {s.name: r for s in structures if (r := s.model_revisions())}:  # a Ritz plate's basis
        description["model_revisions"] = revisions
    axes_in_order = {name: grids[name] for name in family.axis_names}
    return SweepGrid(structures, family, axes_in_order, description, fingerprint(description), settings)


#: Copies of the map a sweep holds at once: the dataset, the working arrays it fills, the
#: snapshot written to NetCDF, the asymptote peaks and regimes added at the end (measured on a
#: 10⁵-point linear sweep, 84 B a point: 3.1 copies while running and saving, 4.2 while its
#: regimes are classified; ``tests/test_hostile_cases.py`` checks the bound).
MAP_COPIES = 5.0


def require_map_fits(structures: int, sizes: dict, family: MapFamily | str = "linear",
                     advice: str = "sweep it in parts (fewer values per axis, or several sweep files)") -> None:
    """Refuse (``ValueError``, with ``advice``) a sweep of ``structures`` structures and axis
    ``sizes`` (name → count) whose :data:`MAP_COPIES` copies of the ``family``'s map would
    exceed :data:`~impactmaps.solvers.run_budget.MEMORY_LIMIT_BYTES`, before allocating.
    """
    family = map_family(family) if isinstance(family, str) else family
    points = float(structures) * float(np.prod([float(size) for size in sizes.values()]))
    point_bytes = MAP_COPIES * (sum(np.dtype(spec[0]).itemsize for spec in family.variables.values()) + 1)
    if points * point_bytes > MEMORY_LIMIT_BYTES:
        shown = " × ".join([f"{structures} structures", *(f"{size} {name}" for name, size in sizes.items())])
        raise ValueError(f"the sweep has {points:.4g} points ({shown}): it would take "
                         f"{points * point_bytes / 2**30:.3g} GiB (limit {MEMORY_LIMIT_BYTES / 2**30:g} GiB); "
                         f"{advice}")


def _resume(path, overwrite: bool, grid: SweepGrid) -> tuple[xr.Dataset, bool]:
    """(dataset, shipped): the stored result at ``path`` if it matches the grid's fingerprint
    (and not ``overwrite``), else the shipped result of this sweep, else an empty one.
    """
    dataset = None
    if path is not None:
        remove_stale_temporaries(path)
        if overwrite:
            _announce_discarded(path)
        dataset = None if overwrite else load_matching(path, grid.digest, grid.description)
    if dataset is not None:
        return dataset, False
    dataset = load_shipped_result(grid.digest, grid.description)
    if dataset is None:
        return empty_dataset(grid.family, grid.structures, grid.axes, grid.description, grid.digest), False
    if path is not None:
        save_atomic(dataset, path)
    return dataset, True


def _announce_discarded(path) -> None:
    """Warn that ``overwrite`` discards the finished points of the result file at ``path`` (if any)."""
    if not os.path.exists(path):
        return
    try:
        finished = int(read_dataset(path)["done"].sum())
    except Exception:  # noqa: BLE001 (unreadable: it holds no point worth counting)
        finished = None
    count = "its finished points" if finished is None else f"{finished} finished point(s)"
    import warnings

    warnings.warn(f"overwrite: {path} is replaced, discarding {count}", UserWarning, stacklevel=5)


def _chunks(grid: SweepGrid, done: np.ndarray, chunk_size: int):
    """The sweep's tasks: the missing points, by structure and every axis value but ζ."""
    zetas = grid.axes["zeta"]
    rows = [grid.axes[name] for name in grid.family.axis_names[:-1]]  # (extra…, λ)
    for s_index, structure in enumerate(grid.structures):
        for row_index in itertools.product(*(range(len(values)) for values in rows)):
            values = tuple(float(axis[k]) for axis, k in zip(rows, row_index))
            *extra, lam = values
            missing = [z for z in range(len(zetas)) if not done[(s_index, *row_index, z)]]
            for start in range(0, len(missing), chunk_size):
                indices = missing[start:start + chunk_size]
                yield SweepTask(structure, (s_index, *row_index), indices,
                                [(*extra, float(zetas[z]), lam) for z in indices])


class _Results:
    """The arrays of a running sweep: absorbs finished chunks, shows the progress, saves the file."""

    def __init__(self, dataset: xr.Dataset, path, save_interval: float, pending: int, progress: bool,
                 variables=RESULT_VARIABLES):
        self.dataset, self.path, self.save_interval, self.variables = dataset, path, save_interval, tuple(variables)
        self.arrays = {name: dataset[name].values.copy() for name in (*self.variables, "done")}
        self.methods = set(str(dataset.attrs.get("point_methods", "")).split(",")) - {""}
        self.absorbed = 0
        from tqdm.auto import tqdm  # imported when a sweep runs, not with the module (import time)
        self.bar = tqdm(total=pending, disable=not progress or not pending, desc="impact map", unit="pt")
        self.last_save = time.monotonic()

    def absorb(self, task: SweepTask, rows) -> None:
        """Store the rows of a finished chunk."""
        for z_index, row in zip(task.zeta_indices, rows):
            at = (*task.index, z_index)
            for name in self.variables:
                self.arrays[name][at] = row[name]
            self.arrays["done"][at] = 1
            if row["method"] >= 0:  # an unresolved point has no method
                self.methods.add(METHODS[row["method"]])
        self.absorbed += len(task.zeta_indices)
        self.bar.update(len(task.zeta_indices))

    def snapshot(self) -> xr.Dataset:
        """The dataset with every point absorbed so far."""
        out = self.dataset.copy()
        for name, values in self.arrays.items():
            out[name] = (out[name].dims, values, out[name].attrs)
        out.attrs["point_methods"] = ",".join(sorted(self.methods))
        out.attrs["complete"] = int(bool(self.arrays["done"].all()))
        return out

    def save(self, final: bool = False) -> None:
        """Write the file atomically, at most every ``save_interval`` seconds unless ``final``."""
        if self.path is not None and self.absorbed and (
                final or time.monotonic() - self.last_save >= self.save_interval):
            save_atomic(self.snapshot(), self.path)
            self.last_save = time.monotonic()

    def interrupted(self) -> SweepInterrupted:
        """The exception saying how many of the grid's points are saved."""
        done = self.arrays["done"]
        return SweepInterrupted(int(done.sum()), done.size, self.path)


def _run(tasks, n_tasks: int, settings: ModalSettings, executor: Executor | None, max_workers: int | None,
         results: _Results, family) -> bool:
    """Solve the chunks (an iterable of ``n_tasks`` tasks), absorbing and saving as they finish
    (and at the end, even if a chunk fails); True if Ctrl-C stopped the run (inline, the chunk in
    hand finishes first; the sweep's own workers are ended at once, their chunks left for the resume)."""
    own_executor = None
    stop = []
    previous = _defer_interrupts(stop)
    try:
        workers = max_workers or os.cpu_count() or 1
        if executor is None and (workers == 1 or n_tasks <= 1):
            _run_inline(tasks, settings, results, stop, family)
        elif n_tasks:
            slots = getattr(executor, "_max_workers", None) or workers  # a process or thread pool's
            if executor is None:
                # one BLAS thread per worker; workers ignore Ctrl-C: the parent saves and stops them
                own_executor = executor = ProcessPoolExecutor(max_workers=workers, initializer=init_worker)
            elif type(executor).__module__.startswith("distributed."):  # the same set-up on Dask's workers
                from .dask_backend import dask_executor, worker_slots

                executor = dask_executor(executor)
                slots = worker_slots(executor)
            _run_on_executor(executor, tasks, settings, results, stop, family, slots)
    except KeyboardInterrupt:
        stop.append(signal.SIGINT)
    finally:
        if previous is not None:
            signal.signal(signal.SIGINT, previous)
        results.bar.close()
        if own_executor is not None:
            if stop or sys.exc_info()[0] is not None:  # stopped or failed: the chunks in hand are not waited for
                end_workers(own_executor)
            own_executor.shutdown(wait=False, cancel_futures=True)
        results.save(final=True)
    return bool(stop)


def _defer_interrupts(stop: list):
    """Make a first Ctrl-C append to ``stop`` (a second raises); the replaced handler, or None (not
    installed outside the main thread or over a custom handler)."""

    def on_interrupt(signum, frame):
        if stop:  # a second Ctrl-C stops at once
            raise KeyboardInterrupt
        stop.append(signum)

    if threading.current_thread() is threading.main_thread() and \
            signal.getsignal(signal.SIGINT) is signal.default_int_handler:
        return signal.signal(signal.SIGINT, on_interrupt)
    return None


def _run_inline(tasks, settings: ModalSettings, results: _Results, stop: list, family) -> None:
    """Solve the chunks one after the other in this process, until ``stop``."""
    for task in tasks:
        if stop:
            break
        results.absorb(task, solve_map_points(family, task.structure, task.points, settings))
        results.save()


#: Chunks a sweep keeps submitted per worker slot of its executor.
IN_FLIGHT_PER_SLOT = 4


def _run_on_executor(executor: Executor, tasks, settings: ModalSettings, results: _Results, stop: list,
                     family, slots: int) -> None:
    """Keep four chunks per worker slot submitted to ``executor`` (bounding what it holds),
    absorbing them as they complete, until ``stop``.
    """
    pending = iter(tasks)
    window = IN_FLIGHT_PER_SLOT * max(1, slots)
    futures = {}
    while not stop:
        for task in itertools.islice(pending, window - len(futures)):
            futures[executor.submit(solve_map_points, family, task.structure, task.points, settings)] = task
        if not futures:
            break
        finished, _ = wait(futures, timeout=0.25, return_when=FIRST_COMPLETED)
        for future in finished:
            results.absorb(futures.pop(future), future.result())
        results.save()
    for future in futures:
        future.cancel()


def _finish(results: _Results, stopped: bool, family: MapFamily) -> xr.Dataset:
    """The finished dataset with its regimes (a family that has them); ``SweepInterrupted`` if
    Ctrl-C stopped the run."""
    if stopped:
        raise results.interrupted() from None
    result = results.snapshot()
    if not family.classifies:
        return result
    try:
        if not all(name in result for name in ASYMPTOTE_PEAKS):
            result = with_asymptote_peaks(result)
            if results.path is not None:  # kept with the stored result: a re-run classifies without integrating
                save_atomic(result, results.path)
        result["regime"] = classify_dataset(result)
    except KeyboardInterrupt:
        raise results.interrupted() from None
    return result
