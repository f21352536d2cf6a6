"""One run of the modal integrator: the basis, the step, the contact phase, the kernel call.

:func:`run_once`, the per-run worker of :func:`impactmaps.solvers.modal.simulate`, builds
the participating modes below the cut-off with their residual, chooses the time step
and the contact phase, checks the run's budget and calls the compiled integrator
through :class:`KernelInputs`.
"""

from __future__ import annotations

import math
import warnings
from typing import NamedTuple

import numpy as np
import pandas as pd

from .._checks import require_positive
from .._compile import compile_helper
from .._compile.interruptible import interrupts_ignored, run_interruptibly
from ..contact.base import kernel_pointer
from ..targets.base import DEGENERACY_TOLERANCE, ModalBasis, Target
from .integrator.coupled_contact import CoupledModes, coupled_modes
from .integrator.exact_step import STALL_LIMIT, integrate_impact
from .integrator.kernel_types import KernelCoupled, KernelImpact, KernelModes, KernelRun, KernelScalars, kernel_array
from .modal_settings import (
    ConvergenceWarning,
    ModalDetails,
    ModalSettings,
    linear_stiffness,
    settings_dict,
)
from ..contact.contact_scale import reference_contact_stiffness
from .mode_budget import budget_cutoff
from ..result import HISTORY_COLUMNS as COMMON_HISTORY_COLUMNS
from ..result import ImpactResult, energy_balance_error
from .run_budget import HISTORY_ROW_CAP, RunBudget, modal_run_budget, refuse_or_announce
from .time_step import STABLE_TOP_STEP, content_time_step, coupled_top_frequency

__all__ = ["run_once", "KernelInputs", "HISTORY_COLUMNS", "INTERRUPTIBLE_SECONDS",
           "COUPLED_COST_RATIO", "COUPLED_MAX_MODES", "COUPLED_ALWAYS_MODES"]

#: The exact linear contact phase replaces the sampled one when the sampled scheme would
#: take more than this many times (n + 1)² steps per contact of π/ω (n retained modes):
#: its set-up, an (n + 1)² eigenproblem, then costs less than the steps it saves
#: (see :func:`_coupled_phase`) …
COUPLED_COST_RATIO = 1.0
#: … and the retained modes are at most this many; below this many modes the set-up costs
#: microseconds and the exact phase is always taken (a contact then takes ~10–10² steps
#: instead of ≥ 250).
COUPLED_MAX_MODES = 400
COUPLED_ALWAYS_MODES = 32
_NO_COUPLED_MODES = CoupledModes(np.zeros(0), np.zeros(0), np.zeros((0, 0)), np.zeros((0, 0)))

#: Columns of the integrator's history array: the common ones, then the structure energy.
HISTORY_COLUMNS = COMMON_HISTORY_COLUMNS + ("structure_energy_J",)


def _history_frame(history: np.ndarray, impactor_mass: float) -> pd.DataFrame:
    """The kernel's history array as a DataFrame, with the impactor's kinetic energy."""
    frame = pd.DataFrame(history, columns=HISTORY_COLUMNS)
    frame["impactor_kinetic_energy_J"] = 0.5 * impactor_mass * frame["impactor_velocity_m_s"] ** 2
    return frame


def basis_for(target, contact_frequency, settings: ModalSettings, contact_radius=None,
               cap=None) -> ModalBasis:
    """The participating modes below the cut-off, with the residual the settings ask for
    (under a contact patch the cut-off is ``patch_cutoff_ratio`` · ω; never above ``cap``
    [rad/s] when given)."""
    ratio = settings.cutoff_ratio if contact_radius is None else settings.patch_cutoff_ratio
    max_frequency = float(ratio * contact_frequency)
    if cap is not None:
        max_frequency = min(max_frequency, float(cap))
    if isinstance(target, ModalBasis):  # (not a Target: no budget cut-off) the maps' runs, first
        basis = target.participating()
    elif isinstance(target, Target):
        max_frequency = budget_cutoff(target, max_frequency)  # never more modes than memory allows (simulate's plan)
        options = {} if contact_radius is None else {"contact_radius": contact_radius}
        basis = _participating_modes(target, max_frequency, int(settings.min_modes), options)
    else:
        raise ValueError(f"target = {target!r} is not a Target or a ModalBasis")
    floor = int(settings.min_modes)
    if settings.residual_flexibility:  # its residual carries the static modes
        floor = static_floor(basis, contact_frequency, floor)
    basis = basis.truncate(max_frequency, floor)
    if settings.residual_flexibility:
        return basis  # its residual is the one asked for
    return ModalBasis.from_validated(basis.frequencies, basis.participation, 0.0, basis.damping_ratios)


#: The highest mode the floor keeps, over the contact frequency (:func:`static_floor`). Not
#: :data:`~impactmaps.solvers.modal_settings.MAX_CUTOFF_RATIO` (10⁴): the shipped maps and
#: sweep results were computed with floors reaching above 10⁴ ω, and a floor capped there
#: changed their quasi-static corner by up to 1.4e-7 (a fresh point no longer the shipped
#: bits); capped at 10⁶ they are unchanged, and the item's point stays within 5.4e-8 of the
#: exact limit at every level to step/128 (5.2e-8 at the base: what the maps store there).
STATIC_FLOOR_RATIO = 1e6
#: How far :func:`_participating_modes` raises the modes it asks a target for (× min_modes).
_FLOOR_REQUEST_LIMIT = 64


def static_floor(basis: ModalBasis, contact_frequency: float, min_modes: int) -> int:
    """The mode floor a run keeps: ``min_modes``, but never a mode above
    :data:`STATIC_FLOOR_RATIO` (10⁶) times the contact frequency ``contact_frequency`` [rad/s].

    Such a mode responds statically (to (10⁻⁶)² = 10⁻¹²) and the residual compliance carries
    it. Kept, it made refinement diverge: the coupled contact phase's eigenproblem spans
    (ω_max/ω)², and where the floor kept modes 10⁹ times above the contact frequency (SS
    Euler beam, ζ = 440.656, λ = 912.912: 128 modes at the fifth refinement) its round-off
    swamped the contact mode (F̄max 0.99997, then 1.0000, 6.6e-6 for the exact 0.99945).
    """
    return min(int(min_modes), basis.cutoff_count(STATIC_FLOOR_RATIO * float(contact_frequency), 0))


def _participating_modes(target, max_frequency: float, min_modes: int, options: dict) -> ModalBasis:
    """The participating modes of ``target`` below ``max_frequency`` [rad/s], at least
    ``min_modes`` of them (counted as the impact point sees them, degenerate groups whole)
    when it has them: more are asked for, doubling, until enough participate.
    """
    every = target.modes(max_frequency, min_modes=min_modes, **options)
    basis = every.participating()
    if np.searchsorted(basis.frequencies, max_frequency, side="right") >= min_modes:
        return basis  # the cut-off holds enough modes: the floor plays no part
    requested = 2 * max(min_modes, 1)
    while True:
        every = target.modes(max_frequency, min_modes=requested, **options)
        basis = every.participating()
        # a degenerate group at the highest mode asked for may be cut: count the groups below it
        top = every.frequencies[-1] * (1.0 - DEGENERACY_TOLERANCE) if every.size else 0.0
        whole = int(np.searchsorted(basis.frequencies, top, side="left"))
        if whole >= min_modes or every.size < requested or requested >= _FLOOR_REQUEST_LIMIT * min_modes:
            return basis.truncate(max_frequency, min_modes)
        requested *= 2


def _coupled_phase(basis: ModalBasis, stiffness: float, impactor_mass: float, time_step: float,
                   contact_frequency: float, choice: str) -> CoupledModes:
    """The coupled modes for the exact contact phase, or empty arrays for the sampled one.
    ``stiffness``: the law's :func:`linear_stiffness` [N/m] (0: not linear); ``choice``:
    :attr:`ModalSettings.contact_phase` (``"auto"``: exact where the sampled step
    ``time_step`` [s] would cost more, :data:`COUPLED_COST_RATIO`).
    """
    size = basis.size
    sampled_steps = np.pi / (contact_frequency * time_step)
    cheaper = size < COUPLED_ALWAYS_MODES or sampled_steps > COUPLED_COST_RATIO * (size + 1) ** 2
    wanted = choice == "exact" or (choice == "auto" and cheaper)
    # never beyond COUPLED_MAX_MODES: the set-up holds (n + 1)² matrices
    if stiffness > 0.0 and wanted and size <= COUPLED_MAX_MODES:
        coupled = coupled_modes(basis, stiffness, impactor_mass)
        if coupled is not None:
            return coupled
    return _NO_COUPLED_MODES


#: Runs estimated above this many seconds (:mod:`~impactmaps.solvers.run_budget`) integrate
#: in a worker thread, so that Ctrl-C stops them at once (see :func:`_integrate`).
INTERRUPTIBLE_SECONDS = 0.5


def _integrate(interruptible: bool, args: KernelInputs):
    """:data:`~impactmaps.solvers.integrator.exact_step.integrate_impact` on ``args``; when
    ``interruptible``, in a worker thread that Ctrl-C stops through ``args.run.stop`` (bit
    for bit a direct call).
    """
    compile_helper.await_variant(integrate_impact.variant_of(args))  # a helper compiling it (first run only)
    if not interruptible or interrupts_ignored():
        return integrate_impact(*args)
    integrate_impact.compile(*args)  # the variant this run needs; compiling holds the interpreter: do it here, not in the worker
    return run_interruptibly(lambda: integrate_impact(*args), args.run.stop, "impactmaps-modal-kernel")


class KernelInputs(NamedTuple):
    """The arguments of :data:`~impactmaps.solvers.integrator.exact_step.integrate_impact`, by name and
    in its order: the law's kernel pointer, parameters and linear stiffness [N/m] (0 if
    not linear), then the named tuples of :mod:`~impactmaps.solvers.integrator.kernel_types`."""

    kernel: object
    params: np.ndarray
    linear_stiffness: float
    modes: KernelModes
    impact: KernelImpact
    run: KernelRun
    coupled: KernelCoupled


#: What a run stopped at the row cap says (its warning and ``convergence_note``).
_ROW_CAP_NOTE = ("row cap reached: the history holds HISTORY_ROW_CAP = {rows} rows and the run stopped there, "
                 "at t = {time:.3g} s, before re-impact became impossible (time_limit_reached; the result is not "
                 "converged); for the whole event run without the history (record=False), or shorten it with the "
                 "time limit (solver.duration, max_time_ratio)")
#: What a stalled run says (its warning and ``convergence_note``; ``exact_step.STALL_LIMIT``).
_STALL_NOTE = ("stalled: more than {limit} exact contact phases in a row moved the time on by nothing (a touchdown "
               "the flight found again at one instant); the run stopped there, at t = {time:.3g} s "
               "(time_limit_reached; the result is not converged)")


#: Entries kept by :func:`_step_and_phase`'s set-up cache (a full cache is emptied) …
SETUP_CACHE_SIZE = 64
#: … for bases of at most this many modes (its (n + 1)² matrices: ≤ 4.3 MB in all).
SETUP_CACHE_MODES = 64
_setup_cache: dict = {}


def _setup_key(basis: ModalBasis, *numbers: float) -> tuple:
    """The exact inputs of a run's set-up: the bytes of the basis arrays and the numbers."""
    return (basis.frequencies.tobytes(), basis.participation.tobytes(), basis.damping_ratios.tobytes(),
            basis.frequencies.dtype.char, basis.participation.dtype.char, basis.damping_ratios.dtype.char,
            basis.residual_compliance) + numbers


def _cached(key: tuple, compute):
    """``compute()``, kept under ``key`` (exact input bytes; at most :data:`SETUP_CACHE_SIZE`),
    so a repeated run skips its pure set-up. The values are read-only.
    """
    value = _setup_cache.get(key)
    if value is None:
        value = compute()
        if len(_setup_cache) >= SETUP_CACHE_SIZE:
            _setup_cache.clear()
        _setup_cache[key] = value
    return value


def _step_and_phase(basis, linear, impactor_mass, stiffness, omega_c, settings: ModalSettings):
    """(time step [s], coupled modes) chosen automatically; ``linear``: the law's
    :func:`linear_stiffness` [N/m]; ``stiffness``: the reference contact stiffness [N/m].
    The set-up of a basis of at most :data:`SETUP_CACHE_MODES` modes is cached.
    """
    if basis.size > SETUP_CACHE_MODES:  # a large set-up is a small share of its run
        return _step_and_phase_now(basis, linear, impactor_mass, stiffness, omega_c, settings)
    key = _setup_key(basis, stiffness, impactor_mass, omega_c, settings.force_resolution, settings.step_scale,
                     settings.time_step_ratio, settings.resolve_ratio, linear)
    # the module's thresholds too (a benchmark or test may set them)
    key += (settings.contact_phase, COUPLED_COST_RATIO, COUPLED_ALWAYS_MODES, COUPLED_MAX_MODES, STABLE_TOP_STEP)
    return _cached(key,
                   lambda: _step_and_phase_now(basis, linear, impactor_mass, stiffness, omega_c, settings))


def _step_and_phase_now(basis, linear, impactor_mass, stiffness, omega_c, settings: ModalSettings):
    """:func:`_step_and_phase` without its cache."""
    omega_top = coupled_top_frequency(basis, stiffness, impactor_mass, rtol=1e-3)
    content = content_time_step(basis, stiffness, impactor_mass, settings.force_resolution)

    def step(cap):
        return settings.step_scale * min(settings.time_step_ratio / omega_c,
                                         max(settings.resolve_ratio / omega_top, min(content, cap)))

    time_step = step(STABLE_TOP_STEP / omega_top)
    coupled = _coupled_phase(basis, linear, impactor_mass, time_step, omega_c, settings.contact_phase)
    if coupled.frequencies.size:
        # contacts are exact: the step only serves free flight, where every mode moves
        # exactly, so the stability limit of the sampled contact loop does not apply
        time_step = step(np.inf)
    return time_step, coupled


class RunSetup(NamedTuple):
    """What one run integrates, decided before it starts (SI units)."""

    basis: ModalBasis
    contact_frequency: float
    time_step: float
    coupled: object
    max_time: float
    budget: RunBudget


def prepare_run(target, law, impactor_mass, velocity, settings, record, time_step, contact_radius=None,
                cap=None) -> RunSetup:
    """The :class:`RunSetup` of :func:`run_once` (its basis, step, exact-phase modes and
    :func:`~impactmaps.solvers.run_budget.modal_run_budget`), without integrating."""
    return RunSetup(*_prepare(target, law, linear_stiffness(law), impactor_mass, velocity, settings, record,
                              time_step, contact_radius, cap))


def _prepare(target, law, linear, impactor_mass, velocity, settings, record, time_step, contact_radius,
             cap) -> tuple:
    """The fields of :func:`prepare_run`'s :class:`RunSetup`, as a plain tuple (``linear``: the
    law's :func:`linear_stiffness` [N/m], asked once per run)."""
    stiffness = reference_contact_stiffness(law, impactor_mass, velocity)
    # math.sqrt and np.sqrt are both the correctly rounded IEEE square root: the same bits
    omega_c = math.sqrt(stiffness / impactor_mass)
    basis = basis_for(target, omega_c, settings, contact_radius, cap)
    automatic = time_step is None
    coupled = _NO_COUPLED_MODES
    if automatic:
        time_step, coupled = _step_and_phase(basis, linear, impactor_mass, stiffness, omega_c, settings)
    else:
        require_positive("time_step", time_step, "s")
    time_step = float(time_step)
    max_time = float(settings.max_time_ratio / omega_c)
    budget = modal_run_budget(basis.size, time_step, max_time, omega_c, bool(record), int(settings.max_events),
                              not automatic)
    return basis, omega_c, time_step, coupled, max_time, budget


def run_once(target, law, params, impactor_mass, velocity, settings, record, time_step,
             contact_radius=None, cap=None) -> ImpactResult:
    """One run of :func:`~impactmaps.solvers.modal.simulate` (validated inputs) with a point
    load or a patch of radius ``contact_radius`` [m], the cut-off capped at ``cap`` [rad/s]
    when given, the step automatic when ``time_step`` is ``None``."""
    linear = linear_stiffness(law)
    basis, omega_c, time_step, coupled, max_time, budget = _prepare(
        target, law, linear, impactor_mass, velocity, settings, record, time_step, contact_radius, cap)
    n_modes = basis.size
    refuse_or_announce(budget, f"modal run of {n_modes} modes", stacklevel=5)
    inputs = KernelInputs(
        kernel_pointer(law.kernel), params, linear,
        KernelModes(kernel_array(basis.frequencies), kernel_array(basis.participation),
                    kernel_array(basis.damping_ratios), float(basis.residual_compliance)),
        KernelImpact(float(impactor_mass), float(velocity)),
        KernelRun(time_step, max_time, bool(record), int(settings.max_events), HISTORY_ROW_CAP,
                  np.zeros(1, dtype=np.int64)),
        KernelCoupled(coupled.frequencies, coupled.force_row, coupled.from_coupled, coupled.to_coupled,
                      float(settings.time_step_ratio / omega_c), float(settings.step_scale)))
    history, intervals, scalars = _integrate(budget.seconds > INTERRUPTIBLE_SECONDS, inputs)
    if scalars.events_overflow:
        warnings.warn(
            f"more than max_events = {settings.max_events} contacts: the run stopped there (time_limit_reached)",
            RuntimeWarning, stacklevel=4)
    if scalars.row_cap_reached:
        warnings.warn(_ROW_CAP_NOTE.format(rows=HISTORY_ROW_CAP, time=scalars.end_time), ConvergenceWarning,
                      stacklevel=4)
    result = _result(law, inputs, scalars, history if record else None, intervals, omega_c, n_modes, settings,
                     "exact" if coupled.frequencies.size else "sampled")
    if scalars.stalled:
        warnings.warn(result.convergence_note, ConvergenceWarning, stacklevel=4)
    elif result.time_limit_reached and not scalars.row_cap_reached:
        warnings.warn(
            f"impact run stopped at its time limit ({max_time:.3g} s) before re-impact "
            "became impossible; scalars describe a truncated event",
            ConvergenceWarning, stacklevel=4)
    return result


def _result(law, inputs: KernelInputs, scalars: KernelScalars, history, intervals, omega_c, n_modes,
            settings: ModalSettings, phase: str) -> ImpactResult:
    """The :class:`ImpactResult` of a kernel run (``history`` ``None`` when not recorded)."""
    mass, velocity = inputs.impact.mass, inputs.impact.velocity
    alpha_max = float(scalars.max_indentation)
    elastic = law.elastic
    dissipation = 0.0 if elastic else float(law.dissipated_energy(alpha_max))
    rebound = float(-scalars.final_velocity)
    structure_energy, damping_work = float(scalars.structure_energy), float(scalars.damping_work)
    row_cap_reached = scalars.row_cap_reached
    return ImpactResult.from_fields({
        "history": _history_frame(history, mass) if history is not None else None,
        "peak_force": float(scalars.peak_force),
        "peak_time": float(scalars.peak_time),
        "contact_intervals": np.asarray(intervals),
        "max_indentation": alpha_max,
        "permanent_indentation": 0.0 if elastic else float(law.permanent_indentation(alpha_max)),
        "rebound_velocity": rebound,
        "energy_transferred": structure_energy,
        "contact_dissipation": dissipation,
        "damping_work": damping_work,
        "energy_balance_error": energy_balance_error(mass, velocity, rebound, structure_energy, dissipation,
                                                     damping_work),
        "end_time": float(scalars.end_time),
        "time_limit_reached": bool(scalars.time_limit_reached),
        "impactor_mass": float(mass),
        "velocity": float(velocity),
        "contact_frequency": omega_c,
        "n_modes": n_modes,
        "time_step": float(inputs.run.time_step),
        "method": "modal+residual" if settings.residual_flexibility else "modal",
        "settings": settings_dict(settings),
        "details": ModalDetails(int(scalars.steps), phase),
        "converged": False if row_cap_reached or scalars.stalled else None,
        "convergence_note": _ROW_CAP_NOTE.format(rows=HISTORY_ROW_CAP, time=scalars.end_time)
        if row_cap_reached else _STALL_NOTE.format(limit=STALL_LIMIT, time=scalars.end_time)
        if scalars.stalled else "",
    })
