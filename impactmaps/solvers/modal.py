"""The modal impact solver: a sphere striking any target that supplies modes.

Equations (spec §3.4): ``q̈_j + 2ζ_jω_j q̇_j + ω_j² q_j = φ_j(x0) F``,
``m_i ẅ_i = −F``, ``α = w_i − Σ φ_j q_j − r F``, ``F = F(α; α_max)`` from any registered
contact law, with ``r`` the residual static compliance of the dropped modes in series
with the contact (mode-acceleration correction). The integrator is
:mod:`impactmaps.solvers.integrator.exact_step`.

Load: on Mindlin (shear-deformable) SSSS plates the force is, by default, the Hertz
pressure over the contact disc of the peak indentation (participations times the
patch's modal transform, residual under the same patch; :attr:`ModalSettings.contact_patch`,
``docs/contact_patch.rst``): their point-load deflection diverges, so a point load never
converges in the cut-off. Every other target takes the point load.

Mode cut-off rule: every participating mode with ``ω_j ≤ cutoff_ratio · ω`` is
integrated (at least ``min_modes`` of them, but with residual flexibility none above
``STATIC_FLOOR_RATIO · ω`` = 10⁶ ω: those respond statically, and kept they swamped the
coupled contact phase in round-off, :func:`~impactmaps.solvers.modal_run.static_floor`),
where ``ω`` is the contact frequency; the rest enter through ``r``.

Time step: :mod:`~impactmaps.solvers.time_step` (docs/physics.rst, "The exact-step integrator").
"""

from __future__ import annotations

import functools
import math
import warnings
from dataclasses import replace

import numpy as np

from .._checks import require_positive
from ..contact.base import ContactLaw
from ..contact.linear import LinearContact
from ..targets.base import Target
from .._compile import compile_helper
from .modal_run import prepare_run, run_once
from .modal_settings import (
    DEFAULT_SETTINGS,
    ConvergenceWarning,
    ModalSettings,
    linear_stiffness,
    settings_dict,
    uses_patch,
    CORNER_MAX_MODES,
    corner_ratios,
    with_corner_cutoff,
)
from ..contact.geometry import contact_radius_function
from ..contact.contact_scale import reference_contact_stiffness
from .mode_budget import METHODS, ModeBudgetWarning, asymptote_result, halved_cap_change, plan_basis
from ..result import ImpactResult

__all__ = [
    "simulate",
    "simulate_normalised",
    "estimate_run",
    "simulate_batch",
]

#: The peak-indentation patch radius is iterated until it moves by less than this (relative).
PATCH_TOLERANCE = 1e-4
#: At most this many runs of the peak-indentation iteration.
PATCH_PASSES = 8

def simulate(
    target,
    law: ContactLaw,
    impactor_mass: float,
    velocity: float,
    *,
    settings: ModalSettings | None = None,
    record: bool = True,
    time_step: float | None = None,
    effective_radius: float | None = None,
    corner_cutoff: bool = True,
) -> ImpactResult:
    """Simulate a sphere striking a modal target, through every re-impact.

    Parameters
    ----------
    target : Target or ModalBasis
        The struck structure (beam, plate, half-space, …) or directly its modes at the
        impact point (a :class:`ModalBasis` is integrated as given).
    law : ContactLaw
        Any registered contact law with scalar parameters.
    impactor_mass : float
        Sphere mass m_i [kg].
    velocity : float
        Approach velocity V0 [m/s], > 0.
    settings : ModalSettings, optional
        Cut-off, time-step and convergence settings.
    record : bool
        Keep full time histories (``False`` keeps scalars only, for sweeps).
    time_step : float, optional
        Force this time step [s] instead of the automatic choice (every phase then runs
        the sampled scheme).
    effective_radius : float, optional
        Effective radius R [m] for the contact patch when the law carries none; ignored
        for point loads.
    corner_cutoff : bool
        Under the contact patch, raise ``settings.patch_cutoff_ratio`` to
        :func:`~impactmaps.solvers.modal_settings.patch_cutoff_ratio_for` (a heavy impactor's
        force reaches far above the contact frequency); ``result.settings`` holds the ratio
        used. ``False``: the settings' ratio as given (map points, which refine their
        cut-off themselves).

    Returns
    -------
    ImpactResult
        ``method`` says what answered: ``"modal+residual"`` (``"modal"`` without the
        residual), ``"modal+residual-capped"`` or ``"infinite-structure-asymptote"``;
        with a patch, ``result.settings["contact_radius_m"]`` is its radius [m].

    Raises
    ------
    ValueError
        Bad input, an impact no method answers within the mode cap, or a run above the
        1 GiB memory budget (naming the knob and the value that fits).

    Notes
    -----
    Memory is bounded for every input: above :data:`~impactmaps.solvers.mode_budget.MAX_MODES`
    modes, or the target's :meth:`~impactmaps.targets.base.Target.resolution_limit`,
    :func:`~impactmaps.solvers.mode_budget.plan_basis` picks the infinite-structure solution,
    a capped basis (:class:`~impactmaps.solvers.mode_budget.ModeBudgetWarning`) or a refusal.
    A run estimated above a minute issues
    :class:`~impactmaps.solvers.run_budget.LongRunWarning`.
    """
    settings = settings or DEFAULT_SETTINGS
    require_positive("impactor_mass", impactor_mass, "kg")
    require_positive("velocity", velocity, "m/s")
    if not isinstance(law, ContactLaw):
        raise ValueError(f"law = {law!r} is not a ContactLaw")
    params = np.array(law.kernel_parameters, dtype=float, order="C")
    if params.ndim != 1:
        raise ValueError("simulate() takes a contact law with scalar parameters (one case)")
    radius_of = None
    if uses_patch(target, settings.contact_patch):
        radius_of = contact_radius_function(law, effective_radius)
    plan = None
    if isinstance(target, Target):  # the budget of the cut-off the run will use
        stiffness = reference_contact_stiffness(law, impactor_mass, velocity)
        if radius_of is not None and corner_cutoff:
            used, wanted = corner_ratios(settings, target, impactor_mass, stiffness)
            if used < wanted:
                warnings.warn(f"the heavy impactor's contact force reaches {wanted:.3g} × the contact frequency "
                              f"(twice its corner against the plate's local impedance); the patch cut-off is "
                              f"raised only to {used:.3g} × (the budget of {CORNER_MAX_MODES} modes): the peak "
                              f"force may be off by a few per cent (docs/plates_any_edges.rst); set [solver] "
                              f"patch_cutoff_ratio to go further", ConvergenceWarning, stacklevel=2)
            if used != settings.patch_cutoff_ratio:  # with_corner_cutoff's settings, its ratios computed once
                settings = replace(settings, patch_cutoff_ratio=used)
        ratio = settings.cutoff_ratio if radius_of is None else settings.patch_cutoff_ratio
        contact_frequency = np.sqrt(stiffness / impactor_mass)
        plan = _plan(target, law, impactor_mass, velocity, float(ratio * contact_frequency))
        if plan.method == METHODS[2]:
            warnings.warn(plan.message, ModeBudgetWarning, stacklevel=2)
            return asymptote_result(plan, target, law, impactor_mass, velocity, record,
                                    settings_dict(settings))
        if plan.method == METHODS[1]:
            warnings.warn(plan.message, ModeBudgetWarning, stacklevel=2)
    cap = plan.max_frequency if plan is not None and plan.method == METHODS[1] else None
    compile_helper.start(_possible_variants(law, settings, time_step))  # a cold first run: the 2nd core compiles
    result = _run_at(target, law, params, impactor_mass, velocity, settings, time_step, radius_of, record, cap)
    if cap is not None:
        result = replace(result, method=METHODS[1])
    if settings.check_convergence:
        fine = simulate(target, law, impactor_mass, velocity, settings=settings.refined(), record=False,
                        effective_radius=effective_radius, corner_cutoff=False)  # its ratio: twice the one used
        run = functools.partial(_run_at, target, law, params, impactor_mass, velocity, settings, time_step,
                                radius_of)
        result = _checked(result, fine, settings.tolerance, cap, run)
    _warn_energy_ledger(result, settings.tolerance)
    if isinstance(target, Target):
        _warn_target_validity(target, result)
    return result


def _warn_energy_ledger(result: ImpactResult, tolerance: float) -> None:
    """A :class:`ConvergenceWarning` when the run's energy ledger closes only beyond
    ``tolerance`` [-] of the impact energy.
    """
    error = float(result.energy_balance_error)
    if not math.isfinite(error) or abs(error) <= tolerance:
        return
    why = (" the damping work is integrated by the trapezoidal rule over each step, which misses the modes "
           "that turn within a step; a smaller step (ModalSettings.step_scale) tightens it") \
        if result.damping_work > 0.0 else " a smaller step (ModalSettings.step_scale) or more modes tighten it"
    warnings.warn(f"energy balance: the run's energy ledger closes only to {abs(error):.2g} of the impact energy "
                  f"(tolerance {tolerance:g}):{why}", ConvergenceWarning, stacklevel=3)


def _warn_target_validity(target: Target, result: ImpactResult) -> None:
    """Issue :func:`impactmaps.validity.target_warnings` of a run on a structure as
    :class:`~impactmaps._checks.ModelValidityWarning` (the checks that need no sphere)."""
    from .._checks import ModelValidityWarning
    from ..validity import target_warnings  # beside the solvers: on use

    for message in target_warnings(target, result):
        warnings.warn(message, ModelValidityWarning, stacklevel=3)


def _possible_variants(law: ContactLaw, settings: ModalSettings, time_step) -> tuple:
    """The integrator variants (``exact_phase``) a run may need."""
    exact = linear_stiffness(law) > 0.0 and settings.contact_phase != "sampled" and time_step is None
    return (None, True) if exact else (None,)


def _plan(target: Target, law, impactor_mass: float, velocity: float, wanted: float, estimate: bool = False):
    """:func:`~impactmaps.solvers.mode_budget.plan_basis` of a run whose cut-off is ``wanted``
    [rad/s], also where the target's :meth:`Target.resolution_limit` (not memory) caps it.
    """
    limit = float(target.resolution_limit())
    if wanted <= limit:
        return plan_basis(target, law, impactor_mass, velocity, wanted, estimate=estimate)
    return plan_basis(target, law, impactor_mass, velocity, wanted, max_modes=target.resolved_mode_count(),
                      cap_frequency=limit, estimate=estimate)


def estimate_run(target, law: ContactLaw, impactor_mass: float, velocity: float, *,
                 settings: ModalSettings | None = None, record: bool = True,
                 time_step: float | None = None, corner_cutoff: bool = True) -> dict:
    """What :func:`simulate` would integrate and what it would cost, without integrating
    (arguments as for :func:`simulate`).

    Returns
    -------
    dict
        ``method``, ``modes``, ``time_step_s``, ``expected_steps``, ``history_rows``,
        ``memory_bytes``, ``seconds`` (compilation excluded) and ``runs`` (2 with the
        convergence check's re-run); an infinite-structure answer has ``modes`` 0.
    """
    from .run_budget import EXPECTED_RUN_RATIO

    settings = settings or DEFAULT_SETTINGS
    require_positive("impactor_mass", impactor_mass, "kg")
    require_positive("velocity", velocity, "m/s")
    method, cap, radius = "modal+residual" if settings.residual_flexibility else "modal", None, None
    radius_of = contact_radius_function(law, None) if uses_patch(target, settings.contact_patch) else None
    if radius_of is not None:
        radius = radius_of(law.indentation_for_energy(0.5 * impactor_mass * velocity**2))
    if isinstance(target, Target):
        stiffness = reference_contact_stiffness(law, impactor_mass, velocity)
        if radius_of is not None and corner_cutoff:
            settings = with_corner_cutoff(settings, target, impactor_mass, stiffness)
        ratio = settings.cutoff_ratio if radius_of is None else settings.patch_cutoff_ratio
        contact_frequency = np.sqrt(stiffness / impactor_mass)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # the run says these; an estimate only counts
            plan = _plan(target, law, impactor_mass, velocity, float(ratio * contact_frequency), estimate=True)
        if plan.method == METHODS[2]:
            return {"method": plan.method, "modes": 0, "time_step_s": None, "expected_steps": 0,
                    "history_rows": 0, "memory_bytes": 0.0, "seconds": 0.0, "runs": 1}
        if plan.method == METHODS[1]:
            method, cap = plan.method, plan.max_frequency
    setup = prepare_run(target, law, impactor_mass, velocity, settings, record, time_step, radius, cap)
    expected = min(math.ceil(setup.max_time / setup.time_step) + 2,
                   math.ceil(EXPECTED_RUN_RATIO / (setup.contact_frequency * setup.time_step)) + 2)
    out = {"method": method, "modes": int(setup.basis.size), "time_step_s": setup.time_step,
           "expected_steps": int(expected), "history_rows": int(expected) if record else 0,
           "memory_bytes": float(setup.budget.memory_bytes), "seconds": float(setup.budget.seconds), "runs": 1}
    if settings.check_convergence:
        fine = estimate_run(target, law, impactor_mass, velocity, settings=settings.refined(), record=False,
                            time_step=time_step, corner_cutoff=False)
        out.update(runs=2, memory_bytes=out["memory_bytes"] + fine["memory_bytes"],
                   seconds=out["seconds"] + fine["seconds"])
    return out


def _run_at(target, law, params, impactor_mass, velocity, settings, time_step, radius_of, record, cap):
    """One run of :func:`simulate` (point load or patch) with the cut-off capped at ``cap`` [rad/s]
    (``None``: the settings' cut-off)."""
    if radius_of is None:
        return run_once(target, law, params, impactor_mass, velocity, settings, record, time_step, cap=cap)
    return _run_with_patch(target, law, params, impactor_mass, velocity, settings, record, time_step,
                           radius_of, cap)


def _checked(result: ImpactResult, fine: ImpactResult, tolerance: float, cap, run) -> ImpactResult:
    """``result`` with ``converged`` set: F̄max against the ``fine`` run and, for a capped
    basis (``cap`` [rad/s]), against a run at half the cap.
    """
    changes = [(abs(fine.fmax_normalised - result.fmax_normalised), "the cut-off was doubled and the step halved")]
    if cap is not None:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # the coarse run's own warnings say nothing new
            change, _ = halved_cap_change(result, cap, functools.partial(run, False))
        changes.append((change, f"the capped basis (modes up to {cap:.4g} rad/s, "
                        f"{cap / result.contact_frequency:.3g} ω) was halved"))
    failed = [f"F̄max changed by {change:.2e} (> tolerance {tolerance:g}) when {how}"
              for change, how in changes if not change <= tolerance]
    if not failed:
        return replace(result, converged=True)
    note = "; ".join(failed) + "; the result is not converged"
    warnings.warn(note, ConvergenceWarning, stacklevel=3)
    return replace(result, converged=False, convergence_note=note)


def _run_with_patch(target, law, params, impactor_mass, velocity, settings, record, time_step,
                    radius_of, cap=None) -> ImpactResult:
    """:func:`~impactmaps.solvers.modal_run.run_once` under the Hertz patch of the peak
    indentation, by fixed-point iteration on its radius (to :data:`PATCH_TOLERANCE`); only
    the last run's warnings are issued.
    """
    radius = radius_of(law.indentation_for_energy(0.5 * impactor_mass * velocity**2))
    for _ in range(PATCH_PASSES):
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            result = run_once(target, law, params, impactor_mass, velocity, settings, False, time_step, radius, cap)
        new_radius = radius_of(result.max_indentation)
        if abs(new_radius - radius) <= PATCH_TOLERANCE * radius:
            break
        radius = new_radius
    else:
        warnings.warn(
            f"the contact-patch radius did not settle to {PATCH_TOLERANCE:g} in "
            f"{PATCH_PASSES} runs (last {radius:.6g} m → {new_radius:.6g} m)",
            ConvergenceWarning, stacklevel=3)
    if record:  # only the run at the settled radius records its history (the same scalars, bit for bit)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            result = run_once(target, law, params, impactor_mass, velocity, settings, True, time_step, radius, cap)
    for caught_warning in caught:
        warnings.warn(caught_warning.message, stacklevel=3)
    result.settings["contact_radius_m"] = float(radius)
    return result


def simulate_normalised(
    target: Target,
    loss_factor: float,
    relative_stiffness: float,
    *,
    settings: ModalSettings | None = None,
    record: bool = True,
) -> ImpactResult:
    """Simulate the linear-contact impact that realises (ζ, λ) on ``target`` at V0 = 1 m/s
    (read the result's normalised properties).
    """
    from ..dimensionless import realise

    impactor = realise(target, loss_factor, relative_stiffness)
    return simulate(
        target,
        LinearContact(impactor.contact_stiffness),
        impactor.impactor_mass,
        1.0,
        settings=settings,
        record=record,
    )


def simulate_batch(
    cases,
    *,
    settings: ModalSettings | None = None,
    record: bool = False,
    max_workers: int | None = None,
) -> list[ImpactResult]:
    """Simulate many independent impacts in parallel threads (the kernel releases the GIL).

    Parameters
    ----------
    cases : iterable of (target, law, impactor_mass, velocity)
        Each entry as the positional arguments of :func:`simulate`.
    settings : ModalSettings, optional
        Shared by all cases.
    record : bool
        Keep histories (default: scalars only).
    max_workers : int, optional
        Threads (default: ``os.cpu_count()``); 1 runs sequentially.

    Returns
    -------
    list of ImpactResult
        In the order of ``cases``, identical to :func:`simulate` one by one.
    """
    import os
    from concurrent.futures import ThreadPoolExecutor

    cases = list(cases)
    workers = max_workers or os.cpu_count() or 1

    def run(case):
        target, law, mass, velocity = case
        return simulate(target, law, mass, velocity, settings=settings, record=record)

    if workers == 1 or len(cases) < 2:
        return [run(case) for case in cases]
    with ThreadPoolExecutor(max_workers=workers) as pool:
        return list(pool.map(run, cases))
