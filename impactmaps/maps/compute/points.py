"""The map point solver: one point of any map family realised, simulated and controlled.

A point is a pure function of (family, structure, its numbers, settings): the family
realises, plans and scales it; :func:`solve_map_points` runs it on modes truncated from
one basis table per structure (:func:`basis_table`) under the accuracy control. The
sweep, the tiles and the refinement call it.
"""

from __future__ import annotations

import functools
import warnings
from collections.abc import Sequence
from dataclasses import replace
from enum import StrEnum

from ...solvers.modal_settings import ModalSettings
from ...solvers.mode_budget import METHODS as BUDGET_METHODS
from ...solvers.mode_budget import ModeBudgetError, halved_cap_change, plan_basis
from ...solvers.mode_budget import MIN_CAPPED_CUTOFF_RATIO, frequency_cap
from ...targets.shear_range import beyond_shear_theory
from ..family.accuracy import STATUSES, AccuracyControl, PointStatus, controlled_point
from ..family.map_family import RESULT_VARIABLES
from ..family.structures import MAX_MODES, BasisTable, MapStructure

__all__ = ["SOLVER_REVISION", "METHODS", "PlanMethod", "method_code", "basis_table",
           "map_cap", "capped_resolvable", "map_plan", "unresolved_point", "table_run_key", "table_runner", "solve_map_points"]

SOLVER_REVISION = 8  # bump when a numerical change invalidates stored results (5: exact linear contact phase; 6: shear-deformable points beyond their theory unresolved, no classical asymptote for them; 7: sensitive bands from runs perturbed at the base settings, at least the tolerance wide; 8: degenerate modes merged, so the mode floor counts modes the impact point sees; free flight up to 1024 h; two-rate exact contact phase)

#: Per-point method codes (the ``method`` variable; CF flag_values/flag_meanings).
METHODS = BUDGET_METHODS


class PlanMethod(StrEnum):
    """The model that answers a map point (the names of :data:`METHODS`)."""

    MODAL = "modal+residual"
    CAPPED = "modal+residual-capped"
    ASYMPTOTE = "infinite-structure-asymptote"


assert tuple(PlanMethod) == METHODS, "PlanMethod must list the mode budget's methods in their order"


def method_code(method: str) -> int:
    """The ``method`` code of a model's name [-]."""
    return METHODS.index(method)


@functools.lru_cache(maxsize=8)
def basis_table(structure: MapStructure, min_modes: int) -> BasisTable:
    """The one basis table every point on ``structure`` is truncated from, built at
    :func:`~impactmaps.solvers.mode_budget.frequency_cap` so that a point's result does not
    depend on chunking or order (cached).
    """
    with warnings.catch_warnings():
        # the table reaches past the Mindlin thickness-shear cut-off; a point whose own
        # cut-off does is unresolved (map_plan)
        warnings.simplefilter("ignore", UserWarning)
        return BasisTable(structure.build(), frequency_cap(structure.build(), MAX_MODES), min_modes)


def _resolves_below_cap(target) -> bool:
    """A plate of bounded Ritz basis: its modes stop where its largest basis stops resolving."""
    return getattr(target, "kind", None) == "plate" and bool(getattr(target, "bounded_modes", False))


def map_cap(target) -> float:
    """The cap [rad/s] on the cut-off of a point of a family with ``capped_points``:
    :func:`~impactmaps.solvers.mode_budget.frequency_cap` at :data:`MAX_MODES`, and on a plate
    of bounded Ritz basis no higher than what its largest basis resolves
    (``resolution_limit``, the cap ``simulate`` holds a run to; ``frequency_cap`` stops at
    the doubling past it)."""
    cap = frequency_cap(target, MAX_MODES)
    if _resolves_below_cap(target):
        cap = min(cap, float(target.resolution_limit()))
    return cap


def capped_resolvable(target, omega: float, cap: float) -> bool:
    """Whether a point of contact frequency ``omega`` [rad/s] whose cut-off lies above ``cap``
    [rad/s] is answered as ``simulate`` answers it: on a plate of bounded Ritz basis whose
    cap lies at least :data:`~impactmaps.solvers.mode_budget.MIN_CAPPED_CUTOFF_RATIO` ω up,
    on the modes up to the cap with the residual compliance of the rest, its error measured
    by halving the cap (:func:`solve_map_points`)."""
    return _resolves_below_cap(target) and cap >= MIN_CAPPED_CUTOFF_RATIO * float(omega)


def map_plan(target, law, mass: float, omega: float, wanted: float, cap: float, zeta: float | None,
             capped: bool = False):
    """The :class:`~impactmaps.solvers.mode_budget.BasisPlan` of one map point, or None
    (``unresolved``): ``omega`` [rad/s] beyond the target's shear theory, or the mode budget
    answering only by capping the modes (unless ``capped`` and :func:`capped_resolvable`)
    or not at all.
    """
    if beyond_shear_theory(target, omega):
        return None
    try:
        plan = plan_basis(target, law, mass, 1.0, wanted, max_modes=MAX_MODES, cap_frequency=cap, loss_factor=zeta)
    except ModeBudgetError:
        return None
    # a capped run cannot have its cut-off doubled, so its refinement would only halve the
    # step and call it converged: the map vouches for it only where halving the cap checks it
    if plan.method == PlanMethod.CAPPED and not (capped and capped_resolvable(target, omega, cap)):
        return None
    return plan


def unresolved_point(row: dict) -> dict:
    """A map point no model here vouches for: every result missing, status ``unresolved``."""
    missing = {name: spec[1] for name, spec in RESULT_VARIABLES.items()}
    return row | missing | {"reflection_time_normalised": row["reflection_time_normalised"],
                            "status": STATUSES.index(PointStatus.UNRESOLVED)}


def simulate(target, law, impactor_mass, velocity, **options):
    """:func:`impactmaps.solvers.modal.simulate`, imported on first use: a lookup imports this
    module but runs no point, and the integrator's module is not needed until one is run."""
    return _modal_simulate()(target, law, impactor_mass, velocity, **options)


@functools.cache
def _modal_simulate():
    """:func:`impactmaps.solvers.modal.simulate` (imported at the first call; an import
    statement in :func:`simulate` cost ~3 µs a run)."""
    from ...solvers.modal import simulate as modal_simulate

    return modal_simulate


def table_run_key(settings: ModalSettings, zeta_factor: float, basis) -> tuple:
    """What a run of one map point on a basis table depends on (``settings``, the ζ factor
    ``zeta_factor`` [-], the truncated ``basis``): equal keys mean runs with the same bits.
    """
    return zeta_factor, basis.size, _without_cutoffs(settings)


@functools.lru_cache(maxsize=256)
def _without_cutoffs(settings: ModalSettings) -> ModalSettings:
    """``settings`` with both cut-off ratios set to 1 (a pure function of frozen settings, cached)."""
    return replace(settings, cutoff_ratio=1.0, patch_cutoff_ratio=1.0)


def table_runner(family, target, table: BasisTable, cap: float, point, realised, runs: list):
    """``run(settings, zeta_factor)`` of one point: the realised impact on modes truncated from
    ``table`` at ``settings.cutoff_ratio`` times its contact frequency (clipped to ``cap``
    [rad/s]), read in the family's scales. A run equal to an earlier one is not repeated
    (:func:`table_run_key`); every result is appended to ``runs``."""
    seen = {}

    def run(settings: ModalSettings, zeta_factor: float):
        impact = realised if zeta_factor == 1.0 else family.realise(target, family.moved(point, zeta_factor))
        basis = table.truncate(min(settings.cutoff_ratio * impact.omega, cap), settings.min_modes)
        key = table_run_key(settings, zeta_factor, basis)
        scaled = seen.get(key)  # one look-up: a key hashes its settings
        if scaled is None:
            result = simulate(basis, impact.law, impact.mass, impact.velocity, settings=settings, record=False)
            scaled = seen[key] = family.scaled(result, impact)
        runs.append(scaled)
        return scaled

    return run


def solve_map_points(family, structure: MapStructure, points: Sequence[tuple], settings: ModalSettings | None = None,
                     table: BasisTable | None = None, control: AccuracyControl = AccuracyControl()) -> list[dict]:
    """Solve points of a map family on ``structure``: one dict of map variables per point.

    Parameters
    ----------
    family : MapFamily
    structure : MapStructure
    points : sequence of tuple
        Each point's numbers, ``(ζ, λ)`` or with the family's extra axes first [-].
    settings : ModalSettings, optional
    table : BasisTable, optional
        The modes to truncate from (default :func:`basis_table`).
    control : AccuracyControl, optional
        Tolerance and cost cap of the per-point refinement.

    Returns
    -------
    list of dict
        Each point's map variables, coordinates, ``status`` and ``method`` codes (an
        ``unresolved`` point's values missing).
    """
    settings = settings or ModalSettings()
    target = structure.build()
    family.check(structure, target, settings)
    cap = map_cap(target) if family.capped_points else frequency_cap(target, MAX_MODES)
    if table is None and family.uses_table():
        table = basis_table(structure, settings.min_modes)
    rows = []
    for point, realised in zip(points, family.realise_points(target, points)):
        row = family.point_coordinates(point) | {"reflection_time_normalised": float(realised.reflection)}
        plan = family.plan(target, realised, point, cap, settings)
        if plan.method is None:
            rows.append(unresolved_point(row) | family.unresolved_extras())
            continue
        if plan.asymptote is not None:
            rows.append(row | plan.asymptote)
            continue
        runs = []
        run = family.runner(target, table, cap, point, realised, runs) or table_runner(
            family, target, table, cap, point, realised, runs)
        if plan.method == PlanMethod.CAPPED:  # keep its base run for the check of the cap
            run, first = _remembering_first(run)
        answer = controlled_point(run, settings, control)
        companions = family.companion_errors(runs, answer["status"], int(control.max_refinements) + 1)
        if plan.method == PlanMethod.CAPPED:
            answer = _halved_cap(answer, first[0], run, settings, control, cap / realised.omega,
                                 getattr(family, "patch", None) is not None)
        rows.append(row | answer | companions | {"method": method_code(plan.method)})
    return rows


def _remembering_first(run):
    """(``run`` that keeps its first result, the list holding it)."""
    first = []

    def remembering(settings: ModalSettings, zeta_factor: float):
        result = run(settings, zeta_factor)
        if not first:
            first.append(result)
        return result

    return remembering, first


def _halved_cap(answer: dict, base, run, settings: ModalSettings, control: AccuracyControl, cap_ratio: float,
                patch: bool) -> dict:
    """``answer`` of a capped point (its refinements could only halve the step) with the check
    ``simulate`` makes of a capped run: the ``base`` run against one with the cap halved
    (``cap_ratio`` = cap/ω [-]). The change widens the band; beyond the tolerance the point
    has no converged value (``sensitive``, the band holding both runs)."""
    change, coarse = halved_cap_change(base, cap_ratio, lambda half: run(
        replace(settings, patch_cutoff_ratio=half) if patch else replace(settings, cutoff_ratio=half), 1.0))
    fine = float(answer["fmax_normalised"])
    error = max(float(answer["fmax_error"]), change)
    low = min(float(answer["fmax_low"]), fine - error, coarse.fmax_normalised)
    high = max(float(answer["fmax_high"]), fine + error, coarse.fmax_normalised)
    if change <= control.tolerance and STATUSES[answer["status"]] != PointStatus.SENSITIVE:
        return answer | {"fmax_error": error, "fmax_low": fine - error, "fmax_high": fine + error}
    return answer | {"fmax_error": 0.5 * (high - low), "fmax_low": low, "fmax_high": high,
                     "status": STATUSES.index(PointStatus.SENSITIVE)}
