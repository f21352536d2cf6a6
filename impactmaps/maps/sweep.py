"""Sweeps over (ζ, λ) and structure parameters → labelled xarray Datasets.

Work is split into chunks of points sharing one structure and one λ; each chunk is
solved by :func:`solve_points` in a worker (any :class:`concurrent.futures.Executor`:
local processes by default, a Dask cluster through
``dask.distributed.Client.get_executor()``). Finished chunks are written to the result
file atomically as they complete, so an interrupted sweep resumes where it stopped.
"""

from __future__ import annotations

import functools
import os
import signal
import sys
import threading
import time
import warnings
from concurrent.futures import FIRST_COMPLETED, Executor, ProcessPoolExecutor, wait
from dataclasses import asdict, replace
from datetime import datetime, timezone
from typing import Sequence

import numpy as np
import xarray as xr

from .._checks import require_choice, require_positive
from ..contact.linear import LinearContact
from ..dimensionless import realise
from ..jsonio import dumps
from ..solvers.modal import ModalSettings, simulate
from ..solvers.mode_budget import ASYMPTOTE_REFLECTION_FACTOR  # noqa: F401 (the sweep's criterion)
from ..solvers.mode_budget import METHODS as BUDGET_METHODS
from ..solvers.mode_budget import frequency_cap as budget_frequency_cap
from ..solvers.mode_budget import ModeBudgetError, plan_basis
from ..solvers.shear_range import beyond_shear_theory
from .accuracy import STATUSES, AccuracyControl, controlled_point, exact_point
from .hertz_points import HERTZ_AXES, HERTZ_DESCRIPTIONS, solve_hertz_points
from .regimes import MAP_LAWS, classify
from .shipped_results import load_shipped_result
from .store import (
    SweepInterrupted,
    fingerprint,
    load_matching,
    remove_stale_temporaries,
    save_atomic,
)
from .structures import BasisTable, MapStructure
from .workers import init_worker

__all__ = ["sweep", "sweep_fingerprint", "solve_points", "SOLVER_REVISION", "RESULT_VARIABLES", "table_run_key",
           "MAP_LAWS", "map_law", "log_grid", "warn_point_loaded_mindlin"]

SOLVER_REVISION = 8  # bump when a numerical change invalidates stored results (5: exact linear contact phase; 6: shear-deformable points beyond their theory unresolved, no classical asymptote for them; 7: sensitive bands from runs perturbed at the base settings, at least the tolerance wide; 8: degenerate modes merged, so the mode floor counts modes the impact point sees; free flight up to 1024 h; two-rate exact contact phase)

RESULT_VARIABLES = {
    # name: (dtype, missing value, units, description)
    "fmax_normalised": ("f8", np.nan, "1", "maximum contact force / (m_i V0 ω) over all impacts"),
    "impacts": ("i4", -1, "1", "number of separate contacts"),
    "contact_time_normalised": ("f8", np.nan, "1", "total contact time × ω"),
    "first_contact_normalised": ("f8", np.nan, "1", "duration of the first contact × ω"),
    "peak_time_normalised": ("f8", np.nan, "1", "time of the maximum force × ω"),
    "energy_transferred_fraction": ("f8", np.nan, "1", "vibration energy left in the structure / impact energy"),
    "reflection_time_normalised": ("f8", np.nan, "1", "ω d²/c: first wave return to the impact point (d: distance to nearest support/edge, c = sqrt(bending stiffness / mass per length or area))"),
    "n_modes": ("i4", -1, "1", "number of modes integrated"),
    "time_limit_reached": ("i1", -1, "1", "1 if the run stopped at its time limit"),
    "method": ("i1", -1, "1", "which model produced the point: see flag_meanings"),
    "fmax_error": ("f8", np.nan, "1", "error estimate of fmax_normalised (change under refinement, or half the spread of a sensitive point)"),
    "fmax_low": ("f8", np.nan, "1", "lower end of the band that holds fmax_normalised"),
    "fmax_high": ("f8", np.nan, "1", "upper end of the band that holds fmax_normalised"),
    "status": ("i1", -1, "1", "converged, refined, sensitive, asymptotic or unresolved: see flag_meanings"),
}

#: The (λ, ζ) axis descriptions of a map of each law.
_AXES = {"linear": ("relative stiffness K_st/K", "loss factor"), "hertz": HERTZ_AXES}


def map_law(dataset: xr.Dataset) -> str:
    """The contact law a map dataset was swept with (a map without the attribute is linear).

    The law is part of a map's identity: it is in the fingerprint (for every law of
    :data:`MAP_LAWS` but the linear one, whose fingerprints predate it), in the
    ``contact_law`` attribute and in the variables' descriptions.
    """
    return str(dataset.attrs.get("contact_law", "linear"))


#: Per-point method codes (the ``method`` variable; CF flag_values/flag_meanings).
METHODS = BUDGET_METHODS
MAX_MODES = 80_000  # cost cap on the modes (all, incl. non-participating) below the cut-off; see solve_points


def log_grid(start: float, stop: float, count: int) -> np.ndarray:
    """``count`` log-spaced values from ``start`` to ``stop`` (both > 0)."""
    require_positive("start", start)
    require_positive("stop", stop)
    return np.geomspace(start, stop, int(count))


# -- the worker ------------------------------------------------------------------------
@functools.lru_cache(maxsize=16)
def frequency_cap(structure: MapStructure, max_modes: int = MAX_MODES) -> float:
    """Largest frequency [rad/s] below which ``structure`` has at most ~``max_modes`` modes.

    :func:`impactmaps.solvers.mode_budget.frequency_cap` of the built target (modes
    counted, not built). A pure function of its arguments (cached, bounded): the cut-off
    of every point of a sweep on ``structure`` is clipped to it.
    """
    return budget_frequency_cap(structure.build(), max_modes)


@functools.lru_cache(maxsize=8)
def basis_table(structure: MapStructure, min_modes: int) -> BasisTable:
    """The one basis table every point on ``structure`` is truncated from.

    Built once at :func:`frequency_cap` — never at a cut-off that depends on which
    points a worker happened to compute before — so a point's modes, and therefore its
    result, are a pure function of (structure, ζ, λ, settings): the same bits alone, in
    any chunk, in any order, after a resume. Cached (bounded) as a pure function.
    """
    with warnings.catch_warnings():
        # the table reaches past the Mindlin thickness-shear cut-off; a point whose own
        # cut-off does is warned about in solve_points
        warnings.simplefilter("ignore", UserWarning)
        return BasisTable(structure.build(), frequency_cap(structure), min_modes)


def _asymptote_row(target, zeta: float) -> dict:
    """Scalars of the infinite-structure solution (exact until waves return)."""
    impact = target.infinite_structure_impact(zeta)
    contact, rebound = impact.contact_time, impact.rebound_velocity
    contact = float(contact) if np.isfinite(contact) else np.nan
    return {
        "fmax_normalised": float(impact.peak_force),
        "impacts": 1,
        "contact_time_normalised": contact,
        "first_contact_normalised": contact,
        "peak_time_normalised": float(impact.peak_time),
        "energy_transferred_fraction": float(1.0 - float(rebound) ** 2) if np.isfinite(rebound) else np.nan,
        "n_modes": 0,
        "time_limit_reached": 0,
        "method": METHODS.index("infinite-structure-asymptote"),
    }


def warn_point_loaded_mindlin(who: str, stacklevel: int = 2) -> None:
    """Say that a map of a Mindlin plate is a point load, whose answer depends on where its
    divergent shear deflection is cut (``docs/contact_patch.rst``, section Maps).

    ``who``: the subject of the sentence, e.g. "the shipped Mindlin maps strike".
    """
    from ..validity import ModelValidityWarning

    warnings.warn(f"point load: {who} the plate at a point, whose deflection diverges; their F̄max holds the "
                  f"shear of every mode up to the sweep's cap of {MAX_MODES} modes and has no converged value "
                  "(simulate, which cuts it at its own cut-off, differs by up to ~3 %); a sphere's Hertz impact "
                  "spread over its contact patch converges: `impactmaps lookup --case`", ModelValidityWarning,
                  stacklevel=stacklevel + 1)


def unresolved_point(row: dict) -> dict:
    """A map point no model here vouches for: every result missing, status ``unresolved``."""
    missing = {name: spec[1] for name, spec in RESULT_VARIABLES.items()}
    return row | missing | {"reflection_time_normalised": row["reflection_time_normalised"],
                            "status": STATUSES.index("unresolved")}


def _map_plan(target, law, mass: float, omega: float, wanted: float, cap: float, zeta: float | None):
    """The :class:`~impactmaps.solvers.mode_budget.BasisPlan` of one map point, or None.

    None — the point is ``unresolved`` — when its contact frequency ``omega`` [rad/s] lies
    beyond what the target's shear-deformable theory holds
    (:func:`~impactmaps.solvers.shear_range.beyond_shear_theory`), or when the mode budget
    answers it only by capping the modes (the cut-off could not be refined) or not at all.
    """
    if beyond_shear_theory(target, omega):
        return None
    try:
        plan = plan_basis(target, law, mass, 1.0, wanted, max_modes=MAX_MODES, cap_frequency=cap, loss_factor=zeta)
    except ModeBudgetError:
        return None
    # a capped run cannot have its cut-off doubled, so its refinement would only halve the
    # step and call it converged: the map does not vouch for it
    return None if plan.method == "modal+residual-capped" else plan


def solve_points(structure: MapStructure, points: Sequence[tuple[float, float]], settings: ModalSettings,
                 table: BasisTable | None = None, control: AccuracyControl = AccuracyControl()) -> list[dict]:
    """Simulate the linear-contact impacts realising each (ζ, λ) on ``structure``.

    Parameters
    ----------
    structure : MapStructure
    points : sequence of (loss_factor, relative_stiffness)
    settings : ModalSettings
    table : BasisTable, optional
        The modes to truncate from; default :func:`basis_table` of ``structure`` (pass one
        to reuse it explicitly across calls).
    control : AccuracyControl, optional
        Tolerance and cost cap of the per-point refinement (:mod:`impactmaps.maps.accuracy`).

    Returns
    -------
    list of dict
        One dict of normalised scalars per point (keys of ``RESULT_VARIABLES`` plus
        ``zeta``, ``lambda_``).

    Notes
    -----
    Modes up to ``settings.cutoff_ratio · ω`` are integrated with the residual
    flexibility of the rest. A point whose cut-off lies above :func:`frequency_cap`
    (more than ``MAX_MODES`` modes: light impactors on flexible plates, spec §3.6) is
    answered as :func:`impactmaps.solvers.mode_budget.plan_basis` decides: the
    infinite-structure solution if the first wave returns after
    ``ASYMPTOTE_REFLECTION_FACTOR`` times its peak time (it is then exact for the peak;
    Euler beams and Kirchhoff plates only). Otherwise — the modes could only be capped,
    so the cut-off could not be refined — and where the contact frequency lies beyond
    what a Timoshenko/Mindlin theory holds (:mod:`impactmaps.solvers.shear_range`), the
    point is ``unresolved``: status only, every result missing. The ``method`` variable records
    which model produced each point.
    """
    target = structure.build()
    zetas = np.array([p[0] for p in points], dtype=float)
    lambdas = np.array([p[1] for p in points], dtype=float)
    impactors = realise(target, zetas, lambdas)
    omegas = np.atleast_1d(impactors.contact_frequency)
    masses = np.atleast_1d(impactors.impactor_mass)
    stiffnesses = np.atleast_1d(impactors.contact_stiffness)
    reflections = np.atleast_1d(target.reflection_time(omegas))
    cap = frequency_cap(structure)
    wanted = settings.cutoff_ratio * omegas
    if table is None:
        table = basis_table(structure, settings.min_modes)
    rows = []
    for k in range(len(points)):
        row = {"zeta": zetas[k], "lambda_": lambdas[k], "reflection_time_normalised": float(reflections[k])}
        plan = _map_plan(target, LinearContact(stiffnesses[k]), masses[k], omegas[k], wanted[k], cap, zetas[k])
        if plan is None:
            rows.append(unresolved_point(row))
            continue
        if plan.method == "infinite-structure-asymptote":
            rows.append(exact_point(row | _asymptote_row(target, zetas[k])))
            continue
        run = _point_runner(target, table, cap, zetas[k], lambdas[k],
                            (float(masses[k]), float(stiffnesses[k]), float(omegas[k])))
        rows.append(row | controlled_point(run, settings, control) | {"method": METHODS.index(plan.method)})
    return rows


def table_run_key(settings: ModalSettings, zeta_factor: float, basis) -> tuple:
    """What a run of one map point on a basis table depends on: the ζ factor, the modes
    (a truncation of the table is fixed by its size) and every setting but the cut-off
    ratios, which act only through the modes. A point's runners return the earlier
    result for a key they have seen: a sensitive point's cut-off perturbed by ±1 % often
    keeps the same modes (the mode floor, or no mode in the 2 % window), and that run is
    the base run, bit for bit.

    Parameters
    ----------
    settings : ModalSettings
        The run's settings.
    zeta_factor : float
        Factor on the point's ζ [-] (1 but for a sensitive point's perturbed runs).
    basis : ModalBasis
        The modes the run integrates, truncated from the point's basis table.

    Returns
    -------
    tuple
        Hashable: equal keys mean runs with the same bits.
    """
    return zeta_factor, basis.size, _without_cutoffs(settings)


@functools.lru_cache(maxsize=256)
def _without_cutoffs(settings: ModalSettings) -> ModalSettings:
    """``settings`` with both cut-off ratios set to 1 (a pure function of frozen settings,
    cached: a sweep asks it twice per run with a handful of distinct settings)."""
    return replace(settings, cutoff_ratio=1.0, patch_cutoff_ratio=1.0)


def _point_runner(target, table: BasisTable, cap: float, zeta: float, lambda_: float, impactor):
    """``run(settings, zeta_factor)`` of one point: the realised impact on truncated modes."""
    seen = {}

    def run(settings: ModalSettings, zeta_factor: float):
        mass, stiffness, omega = impactor
        if zeta_factor != 1.0:
            moved = realise(target, zeta * zeta_factor, lambda_)
            mass, stiffness, omega = (float(moved.impactor_mass), float(moved.contact_stiffness),
                                      float(moved.contact_frequency))
        basis = table.truncate(min(settings.cutoff_ratio * omega, cap), settings.min_modes)
        key = table_run_key(settings, zeta_factor, basis)
        if key not in seen:
            seen[key] = simulate(basis, LinearContact(stiffness), mass, 1.0, settings=settings, record=False)
        return seen[key]

    return run


def _point_solver(law: str):
    """The per-chunk worker of a map law (a module-level function: it pickles for processes)."""
    return solve_points if law == "linear" else solve_hertz_points


# -- the orchestration ---------------------------------------------------------------------
def _empty_dataset(structures, lambdas, zetas, description, digest, law: str = "linear") -> xr.Dataset:
    shape = (len(structures), len(lambdas), len(zetas))
    data_vars = {}
    for name, (dtype, missing, units, text) in RESULT_VARIABLES.items():
        text = HERTZ_DESCRIPTIONS.get(name, text) if law == "hertz" else text
        data_vars[name] = (("structure", "lambda_", "zeta"), np.full(shape, missing, dtype=dtype),
                           {"units": units, "long_name": text})
    data_vars["method"][2]["flag_values"] = np.arange(len(METHODS), dtype="i1")
    data_vars["method"][2]["flag_meanings"] = " ".join(METHODS)
    data_vars["status"][2]["flag_values"] = np.arange(len(STATUSES), dtype="i1")
    data_vars["status"][2]["flag_meanings"] = " ".join(STATUSES)
    data_vars["done"] = (("structure", "lambda_", "zeta"), np.zeros(shape, dtype="i1"),
                         {"long_name": "1 where the point has been computed"})
    coords = {
        "structure": ("structure", [s.name for s in structures]),
        "lambda_": ("lambda_", np.asarray(lambdas, float), {"long_name": _AXES[law][0], "units": "1"}),
        "zeta": ("zeta", np.asarray(zetas, float), {"long_name": _AXES[law][1], "units": "1"}),
        "kind": ("structure", [s.kind for s in structures]),
        "theory": ("structure", [s.theory for s in structures]),
        "supports": ("structure", [s.supports for s in structures]),
        "aspect_ratio": ("structure", [s.aspect_ratio for s in structures]),
        "slenderness": ("structure", [s.slenderness for s in structures]),
    }
    from .. import __version__

    attrs = {
        "title": "impactmaps normalised impact map",
        "fingerprint": digest,
        "description": dumps(description, sort_keys=True),
        "impactmaps_version": __version__,
        "solver_revision": SOLVER_REVISION,
        "method": f"modal impact solver (exact-step integrator, residual flexibility), {law} contact",
        "contact_law": law,
        "created": datetime.now(timezone.utc).isoformat(timespec="seconds"),
    }
    return xr.Dataset(data_vars, coords=coords, attrs=attrs)


def _chunks(structures, lambdas, zetas, done, chunk_size):
    for s_index, structure in enumerate(structures):
        for l_index, lam in enumerate(lambdas):
            missing = [z_index for z_index in range(len(zetas)) if not done[s_index, l_index, z_index]]
            for start in range(0, len(missing), chunk_size):
                indices = missing[start:start + chunk_size]
                yield structure, s_index, l_index, indices, [(float(zetas[z]), float(lam)) for z in indices]


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
    chunk_size: int = 40,
    save_interval: float = 1.0,
    overwrite: bool = False,
    law: str = "linear",
) -> xr.Dataset:
    """Compute F̄max and companions over structures × λ × ζ.

    Parameters
    ----------
    structures : sequence of MapStructure
    loss_factors, relative_stiffnesses : array_like
        The ζ and λ grids [-].
    settings : ModalSettings, optional
        Solver settings (part of the result's fingerprint).
    path : path-like, optional
        NetCDF result file. Finished points are saved there atomically as they
        complete (nothing is written before the first point is done); re-running with
        the same path computes only the missing points. A file made with other
        settings is refused (``ValueError`` naming the keys that changed) unless
        ``overwrite``. Temporaries of an interrupted save are removed.
    executor : concurrent.futures.Executor, optional
        Where chunks run (e.g. ``dask.distributed.Client(...).get_executor()``).
        Default: a local process pool over the machine's cores.
    max_workers : int, optional
        Size of the default process pool (default: ``os.cpu_count()``); 1 runs inline.
    progress : bool
        Show a tqdm progress bar.
    chunk_size : int
        Points per task (at most, within one λ row). 40 (10 until 2026-11-24): each task
        costs the executor ~0.5–2 ms of pickling and queueing, as much as a few cheap
        points; the 200 × 50 grid of ``benchmarks/bench_plane.py`` took 20.3–20.8 s against
        21.3–22.7 s with 10. The values do not depend on it (a point is a pure function of
        its inputs).
    save_interval : float
        Minimum seconds between two saves of the result file (the final save always
        happens).
    overwrite : bool
        Replace an existing result file instead of resuming it (it is replaced when
        the first point is saved).
    law : {"linear", "hertz"}
        Contact law of the map (:data:`MAP_LAWS`). ``"linear"``: ζ, λ of PHYSICS.md and
        F̄max = F_max/(m V0 ω), times × ω (:func:`solve_points`). ``"hertz"``: the Hertz
        numbers ζ_h, λ_h (:mod:`impactmaps.hertz_similarity`), F̄max = F_max/F_hs, times
        / t* (:func:`~impactmaps.maps.hertz_points.solve_hertz_points`).

    Returns
    -------
    xarray.Dataset
        Dims ``structure``, ``lambda_``, ``zeta``; variables of ``RESULT_VARIABLES``,
        ``regime``, ``done``; units and provenance in attributes.

    Raises
    ------
    SweepInterrupted
        (a ``KeyboardInterrupt``) on Ctrl-C, after saving the finished points; it
        carries how many of the grid's points are saved.
    """
    settings = settings or ModalSettings()
    structures, zetas, lambdas, description, digest = _prepare(structures, loss_factors, relative_stiffnesses,
                                                               settings, law)
    if any(structure.theory == "mindlin" for structure in structures):
        warn_point_loaded_mindlin("the Mindlin points of this sweep strike", stacklevel=2)
    dataset, shipped = _resume(path, overwrite, digest, description, structures, lambdas, zetas, law)
    if shipped and progress:
        print(f"impact map: all {dataset['done'].size} points from the result shipped for this sweep "
              f"(impactmaps.maps.shipped_results, {digest[:12]}…)", file=sys.stderr)
    done = dataset["done"].values.astype(bool)
    tasks = list(_chunks(structures, lambdas, zetas, done, max(1, int(chunk_size))))
    results = _Results(dataset, path, save_interval, sum(len(task[3]) for task in tasks), progress)
    stopped = _run(tasks, settings, executor, max_workers, results, _point_solver(law))
    return _finish(results, stopped)


def sweep_fingerprint(structures: Sequence[MapStructure], loss_factors, relative_stiffnesses,
                      settings: ModalSettings | None = None, law: str = "linear") -> str:
    """The fingerprint of the sweep these arguments describe (what its result file is named by).

    Parameters are those of :func:`sweep`; the fingerprint covers them and
    :data:`SOLVER_REVISION` (:func:`impactmaps.maps.store.fingerprint`).
    """
    return _prepare(structures, loss_factors, relative_stiffnesses, settings or ModalSettings(), law)[4]


# -- the stages of a sweep -------------------------------------------------------------------
def _prepare(structures, loss_factors, relative_stiffnesses, settings: ModalSettings, law: str = "linear"):
    """Check the grid; return it with its description and fingerprint (what a stored result must match)."""
    require_choice("law", law, MAP_LAWS)
    structures = list(structures)
    if not structures:
        raise ValueError("structures is empty: give at least one MapStructure")
    zetas = np.asarray(loss_factors, dtype=float).ravel()
    lambdas = np.asarray(relative_stiffnesses, dtype=float).ravel()
    require_positive("loss_factors", zetas)
    require_positive("relative_stiffnesses", lambdas)
    if zetas.size == 0 or lambdas.size == 0:
        raise ValueError(f"the grid is empty ({zetas.size} ζ × {lambdas.size} λ values): give at least one of each")
    description = {
        "structures": [s.as_dict() for s in structures],
        "zeta": zetas,
        "lambda_": lambdas,
        "settings": asdict(settings),
        "solver_revision": SOLVER_REVISION,
    }
    if law != "linear":  # a linear description has no law key: its fingerprints stay those of the shipped maps
        description["law"] = law
    return structures, zetas, lambdas, description, fingerprint(description)


def _resume(path, overwrite: bool, digest: str, description: dict, structures, lambdas, zetas,
            law: str = "linear") -> tuple[xr.Dataset, bool]:
    """(dataset, shipped): the stored result at ``path`` if it matches ``digest`` (and not
    ``overwrite``), else the package's shipped result of this sweep (:mod:`.shipped_results`,
    then written to ``path``; ``shipped`` True), else an empty one."""
    dataset = None
    if path is not None:
        remove_stale_temporaries(path)
        dataset = None if overwrite else load_matching(path, digest, description)
    if dataset is not None:
        return dataset, False
    dataset = load_shipped_result(digest, description)
    if dataset is None:
        return _empty_dataset(structures, lambdas, zetas, description, digest, law), False
    if path is not None:
        save_atomic(dataset, path)
    return dataset, True


class _Results:
    """The arrays of a running sweep: absorbs finished chunks, shows the progress, saves the file."""

    def __init__(self, dataset: xr.Dataset, path, save_interval: float, pending: int, progress: bool):
        self.dataset, self.path, self.save_interval = dataset, path, save_interval
        self.arrays = {name: dataset[name].values.copy() for name in (*RESULT_VARIABLES, "done")}
        self.methods = set(str(dataset.attrs.get("point_methods", "")).split(",")) - {""}
        self.absorbed = 0
        from tqdm.auto import tqdm  # imported when a sweep runs, not with the module
        self.bar = tqdm(total=pending, disable=not progress or not pending, desc="impact map", unit="pt")
        self.last_save = time.monotonic()

    def absorb(self, task, rows) -> None:
        """Store the rows of a finished chunk."""
        _, s_index, l_index, indices, _ = task
        for z_index, row in zip(indices, rows):
            for name in RESULT_VARIABLES:
                self.arrays[name][s_index, l_index, z_index] = row[name]
            self.arrays["done"][s_index, l_index, z_index] = 1
            if row["method"] >= 0:  # an unresolved point has no method
                self.methods.add(METHODS[row["method"]])
        self.absorbed += len(indices)
        self.bar.update(len(indices))

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


def _run(tasks, settings: ModalSettings, executor: Executor | None, max_workers: int | None,
         results: _Results, solver) -> bool:
    """Solve the chunks, absorbing and saving as they finish (and at the end, even if a chunk
    fails); True if Ctrl-C stopped the run (the chunk in hand finishes first)."""
    own_executor = None
    stop = []
    previous = _defer_interrupts(stop)
    try:
        workers = max_workers or os.cpu_count() or 1
        if executor is None and (workers == 1 or len(tasks) <= 1):
            _run_inline(tasks, settings, results, stop, solver)
        elif tasks:
            if executor is None:
                # one BLAS thread per worker; workers ignore Ctrl-C: the parent saves and stops them
                own_executor = executor = ProcessPoolExecutor(max_workers=workers, initializer=init_worker)
            _run_on_executor(executor, tasks, settings, results, stop, solver)
    except KeyboardInterrupt:
        stop.append(signal.SIGINT)
    finally:
        if previous is not None:
            signal.signal(signal.SIGINT, previous)
        results.bar.close()
        if own_executor is not None:
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


def _run_inline(tasks, settings: ModalSettings, results: _Results, stop: list, solver) -> None:
    """Solve the chunks one after the other in this process, until ``stop``."""
    for task in tasks:
        if stop:
            break
        results.absorb(task, solver(task[0], task[4], settings))
        results.save()


def _run_on_executor(executor: Executor, tasks, settings: ModalSettings, results: _Results, stop: list,
                     solver) -> None:
    """Submit every chunk to ``executor``; absorb them as they complete, until ``stop``."""
    futures = {executor.submit(solver, task[0], task[4], settings): task for task in tasks}
    running = set(futures)
    while running and not stop:
        finished, running = wait(running, timeout=0.25, return_when=FIRST_COMPLETED)
        for future in finished:
            results.absorb(futures[future], future.result())
        results.save()
    for future in running:
        future.cancel()


def _finish(results: _Results, stopped: bool) -> xr.Dataset:
    """The finished dataset with its regimes; ``SweepInterrupted`` if Ctrl-C stopped the run."""
    if stopped:
        raise results.interrupted() from None
    result = results.snapshot()
    try:
        result["regime"] = classify_dataset(result)
    except KeyboardInterrupt:
        raise results.interrupted() from None
    return result


def classify_dataset(dataset: xr.Dataset, **criteria) -> xr.DataArray:
    """Regime label of every computed point of a sweep dataset (see :mod:`.regimes`);
    ``""`` where a point is not computed or ``unresolved``."""
    labels = np.full(dataset["fmax_normalised"].shape, "", dtype=object)
    criteria.setdefault("law", map_law(dataset))
    for s_index, kind in enumerate(dataset["kind"].values):
        fmax = dataset["fmax_normalised"].values[s_index]
        lam, zeta = np.meshgrid(dataset["lambda_"].values, dataset["zeta"].values, indexing="ij")
        ok = dataset["done"].values[s_index].astype(bool) & np.isfinite(fmax)  # unresolved: no label
        if ok.any():
            labels[s_index][ok] = classify(
                fmax[ok], zeta[ok], lam[ok], str(kind),
                peak_time=dataset["peak_time_normalised"].values[s_index][ok],
                reflection_time=dataset["reflection_time_normalised"].values[s_index][ok],
                **criteria,
            )
    return xr.DataArray(labels.astype(str), dims=("structure", "lambda_", "zeta"),
                        attrs={"long_name": "impact regime (local / infinite-structure / transition / quasi-static)"})
