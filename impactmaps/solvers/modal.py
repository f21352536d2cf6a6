"""The modal impact solver: a sphere striking any target that supplies modes.

Equations (spec §3.4): ``q̈_j + 2ζ_jω_j q̇_j + ω_j² q_j = φ_j(x0) F``,
``m_i ẅ_i = −F``, ``α = w_i − Σ φ_j q_j − r F``, ``F = F(α; α_max)`` from any registered
contact law, with ``r`` the residual static compliance of the dropped modes in series
with the contact (mode-acceleration correction). The integrator is
:mod:`impactmaps.solvers.exact_step`.

Load: on Mindlin (shear-deformable) SSSS plates the force is, by default, the Hertz
pressure over the contact disc of the peak indentation (participations times the
patch's modal transform, residual under the same patch; :attr:`ModalSettings.contact_patch`,
``docs/contact_patch.rst``): their point-load deflection diverges, so a point load never
converges in the cut-off. Every other target takes the point load.

Mode cut-off rule: every participating mode with ``ω_j ≤ cutoff_ratio · ω`` is
integrated (at least ``min_modes`` of them), where ``ω`` is the contact frequency; the
rest enter through ``r``.

Time step: ``Δt = min(time_step_ratio/ω, max(resolve_ratio/ω_top, Δt_content))``.
``ω_top`` is the highest natural frequency of the coupled impactor–contact–structure
system in contact (it lies above the highest retained mode by the interlacing of the
point receptance); resolving it resolves every oscillation of the contact force.
``Δt_content`` (:func:`~impactmaps.solvers.time_step.content_time_step`, capped at ``STABLE_TOP_STEP/ω_top``) is the
step that resolves the oscillations the force actually carries: a light impactor on a
plate couples only weakly to the modes near the cut-off, their share of the force is
~1e-7, and the step need not follow them (the local plate case of the benchmarks takes
305 steps instead of 775, at the same F̄max to 1e-5).
"""

from __future__ import annotations

import functools
import warnings
from dataclasses import asdict, dataclass, replace

import numpy as np
import pandas as pd

from .._checks import require_choice, require_in_range, require_positive
from ..contact.base import ContactLaw, kernel_pointer
from ..contact.linear import LinearContact
from ..targets.base import DEGENERACY_TOLERANCE, ModalBasis, Target
from .coupled_contact import CoupledModes, coupled_modes
from .exact_step import integrate_impact
from .mode_budget import METHODS, ModeBudgetWarning, asymptote_result, budget_cutoff, plan_basis
from .result import HISTORY_COLUMNS as COMMON_HISTORY_COLUMNS
from .result import ImpactResult, energy_balance_error
from .run_budget import modal_run_budget, refuse_or_announce
from .time_step import STABLE_TOP_STEP, content_time_step, coupled_top_frequency

__all__ = [
    "ModalSettings",
    "ModalDetails",
    "simulate",
    "simulate_normalised",
    "simulate_batch",
    "reference_contact_stiffness",
    "coupled_top_frequency",
    "content_time_step",
    "ConvergenceWarning",
    "CONTACT_PATCHES",
    "CONTACT_PHASES",
    "contact_radius_function",
]

#: Loads the modal solver can apply: "auto" (the default) — the patch on shear-deformable
#: targets that support it (Mindlin SSSS plates), the point load elsewhere; "point" — at
#: the impact point; "hertz-peak" — as a Hertz pressure over the contact disc at the peak
#: indentation (targets with ``supports_contact_patch``).
CONTACT_PATCHES = ("auto", "point", "hertz-peak")
#: How the modal solver integrates a contact (:attr:`ModalSettings.contact_phase`).
CONTACT_PHASES = ("auto", "exact", "sampled")
#: The peak-indentation patch radius is iterated until it moves by less than this (relative).
PATCH_TOLERANCE = 1e-4
#: At most this many runs of the peak-indentation iteration.
PATCH_PASSES = 8

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

#: Largest ``cutoff_ratio`` and ``patch_cutoff_ratio``: modes 10⁴ times above the contact
#: frequency respond statically (the residual compliance carries them); the convergence
#: check's refinement stops doubling there.
MAX_CUTOFF_RATIO = 1e4
#: Largest ``min_modes`` (the refinement stops doubling there).
MAX_MIN_MODES = 100_000
#: Largest ``max_events``: the kernel allocates the contact-interval table whole (16 B each).
MAX_EVENTS = 10_000_000

#: Columns of the integrator's history array: the common ones, then the structure energy.
HISTORY_COLUMNS = COMMON_HISTORY_COLUMNS + ("structure_energy_J",)


def _history_frame(history: np.ndarray, impactor_mass: float) -> pd.DataFrame:
    """The kernel's history array as a DataFrame, with the impactor's kinetic energy."""
    frame = pd.DataFrame(history, columns=HISTORY_COLUMNS)
    frame["impactor_kinetic_energy_J"] = 0.5 * impactor_mass * frame["impactor_velocity_m_s"] ** 2
    return frame


@dataclass(frozen=True)
class ModalDetails:
    """Extras of a modal run (``ImpactResult.details``).

    Attributes
    ----------
    steps : int
        Steps the integrator took (contact and free flight) [-].
    contact_phase : {"exact", "sampled"}
        How contacts were integrated: ``"exact"`` through the coupled modes of a linear
        contact (:mod:`~impactmaps.solvers.coupled_contact`), ``"sampled"`` by the
        exact-step scheme with the force sampled once per step
        (:mod:`~impactmaps.solvers.exact_step`).
    """

    steps: int
    contact_phase: str

    def summary(self) -> dict:
        """The details as JSON-ready scalars."""
        return {"steps": int(self.steps), "contact_phase": self.contact_phase}


class ConvergenceWarning(UserWarning):
    """A result moved by more than the tolerance when the model was refined."""


@dataclass(frozen=True)
class ModalSettings:
    """Numerical settings of the modal solver (all dimensionless).

    Attributes
    ----------
    cutoff_ratio : float
        Integrate modes with ω_j ≤ ``cutoff_ratio`` · ω (contact frequency); in
        (0, :data:`MAX_CUTOFF_RATIO`].
    patch_cutoff_ratio : float
        The same for a run under the contact patch (``contact_patch``): the patch's
        modal transform suppresses the modes above a few times the contact frequency
        (their participation falls like (k a)⁻²) and the residual compliance under the
        patch carries them statically, so fewer modes suffice. Default 20: on the README
        plate 20 ω lies within 5e-5 of 40–160 ω (987 modes and 726 steps instead of 3129
        and 1398), on a thick plate (a/h = 10) within 3e-5, on the shear-soft laminate of
        ``examples/composite_plate_sun_chen.toml`` within 1.2e-4 (10 ω: 2e-3 there;
        ``validation/patch_convergence.py``).
    min_modes : int
        Integrate at least this many participating modes; in [0, :data:`MAX_MIN_MODES`].
    residual_flexibility : bool
        Add the static compliance of the dropped modes in series with the contact.
    time_step_ratio : float
        Upper bound of ω·Δt.
    resolve_ratio : float
        Upper bound of ω_top·Δt (ω_top: highest coupled frequency in contact), unless
        the force's content allows a longer step (``force_resolution``).
    force_resolution : float
        Tolerated interpolation error of the structural oscillations of the contact
        force, in units of m_i V0 ω (:func:`content_time_step`); 0 always resolves ω_top.
    max_time_ratio : float
        Time limit in units of 1/ω.
    max_events : int
        Most contacts a run follows, in [1, :data:`MAX_EVENTS`] (the table is allocated
        whole); a run with more stops there, with a warning and
        ``time_limit_reached`` set (a sphere resting on a structure can chatter through
        millions of contacts that carry no force).
    check_convergence : bool
        Re-run with twice the cut-off and half the step and warn
        (:class:`ConvergenceWarning`) if F̄max moves by more than ``tolerance``.
    tolerance : float
        Convergence tolerance on F̄max.
    step_scale : float
        Factor in (0, 1] applied to the automatically chosen time step after every rule,
        the stability cap included, so that a refinement really shortens the step also
        where the stability limit sets it (:meth:`refined` halves it).
    contact_patch : {"auto", "point", "hertz-peak"}
        ``"point"``: the force acts at the impact point. ``"hertz-peak"``: on targets
        that support it (``target.supports_contact_patch``, SSSS plates) and with a
        contact law that has a geometry (:func:`contact_radius_function`), the force is
        a Hertz pressure over the contact disc of the peak indentation,
        ``a = sqrt(R α_max)``, found by fixed-point iteration (run → α_max → a → run,
        from the half-space α_max, until a moves by < :data:`PATCH_TOLERANCE`); each
        mode's participation is multiplied by the patch's modal transform and the
        residual is the static compliance under the patch. Otherwise the point load.
        ``"auto"`` (default): ``"hertz-peak"`` on shear-deformable targets that support
        it (Mindlin SSSS plates), whose point-load deflection diverges logarithmically so
        that a point-load peak force never converges in the cut-off (≈ −1 % per doubling
        on the README example); the point load elsewhere — Kirchhoff plates and Euler,
        Rayleigh and Timoshenko beams, bit for bit as ``"point"`` (their point-load
        compliance is finite: the patch would move their peak force by O((k a)²) only;
        a Timoshenko beam's shear deflection under a point load is finite, see
        ``docs/contact_patch.rst``), laws without a contact geometry (linear laws, the
        maps' normalised runs) and :class:`ModalBasis` targets. The converged patch
        result lies 3.8 … 5.9 % under the 3D spring-coupled FE plate of
        ``validation/fe`` (the point load at 40 ω: 2.7 … 3.4 %, but it keeps falling
        with the cut-off): the remaining Mindlin-vs-3D near-field difference, see
        ``docs/contact_patch.rst``.
    contact_phase : {"auto", "exact", "sampled"}
        How a contact is integrated. ``"exact"``: through the coupled modes of a linear
        contact (:mod:`~impactmaps.solvers.coupled_contact`; linear laws on at most
        :data:`COUPLED_MAX_MODES` undamped modes without rigid-body modes, otherwise
        sampled); ``"sampled"``: the exact-step
        scheme with the force sampled once per step; ``"auto"``: the exact phase where it
        costs less (:data:`COUPLED_COST_RATIO`, :data:`COUPLED_MAX_MODES`). A forced
        ``time_step`` always runs the sampled scheme.
    """

    cutoff_ratio: float = 40.0
    patch_cutoff_ratio: float = 20.0
    min_modes: int = 4
    residual_flexibility: bool = True
    time_step_ratio: float = 0.0125
    resolve_ratio: float = 0.2
    force_resolution: float = 1e-5
    max_time_ratio: float = 5000.0
    max_events: int = 1000
    check_convergence: bool = False
    tolerance: float = 1e-3
    step_scale: float = 1.0
    contact_patch: str = "auto"
    contact_phase: str = "auto"

    def __post_init__(self):
        require_in_range("cutoff_ratio", self.cutoff_ratio, 0.0, MAX_CUTOFF_RATIO, low_inclusive=False)
        require_in_range("patch_cutoff_ratio", self.patch_cutoff_ratio, 0.0, MAX_CUTOFF_RATIO, low_inclusive=False)
        require_in_range("min_modes", self.min_modes, 0, MAX_MIN_MODES)
        require_in_range("time_step_ratio", self.time_step_ratio, 0, 1.0, low_inclusive=False)
        require_in_range("resolve_ratio", self.resolve_ratio, 0, 2.0, low_inclusive=False)
        require_in_range("force_resolution", self.force_resolution, 0, 1e-2)
        require_positive("max_time_ratio", self.max_time_ratio)
        require_in_range("max_events", self.max_events, 1, MAX_EVENTS)
        require_positive("tolerance", self.tolerance)
        require_in_range("step_scale", self.step_scale, 0.0, 1.0, low_inclusive=False)
        require_choice("contact_patch", self.contact_patch, CONTACT_PATCHES)
        require_choice("contact_phase", self.contact_phase, CONTACT_PHASES)

    def refined(self) -> "ModalSettings":
        """Settings with twice the cut-off, twice the modes and half the time step (the
        cut-off and the modes at most :data:`MAX_CUTOFF_RATIO` and :data:`MAX_MIN_MODES`).

        The step rules are applied to the larger basis and the step they give is then
        halved (:attr:`step_scale`), so the step is really halved even where the
        stability limit sets it.
        """
        return _refined(self)


@functools.lru_cache(maxsize=256)
def _refined(settings: ModalSettings) -> ModalSettings:
    """:meth:`ModalSettings.refined` (a pure function of frozen settings, cached: every map
    point asks it once or twice, of a handful of distinct settings)."""
    return replace(
        settings,
        cutoff_ratio=min(2 * settings.cutoff_ratio, MAX_CUTOFF_RATIO),
        patch_cutoff_ratio=min(2 * settings.patch_cutoff_ratio, MAX_CUTOFF_RATIO),
        min_modes=min(2 * settings.min_modes, MAX_MIN_MODES),
        step_scale=settings.step_scale / 2,
        check_convergence=False,
    )


DEFAULT_SETTINGS = ModalSettings()

def _settings_dict(settings: ModalSettings) -> dict:
    """``asdict(settings)`` as a fresh dict (its items are cached per settings value)."""
    return dict(_settings_items(settings))


@functools.lru_cache(maxsize=64)
def _settings_items(settings: ModalSettings) -> tuple:
    """The fields of frozen, hashable ``settings`` as (name, value) pairs."""
    return tuple(asdict(settings).items())


def _linear_stiffness(law: ContactLaw) -> float:
    """K [N/m] if ``law`` is linear (the integrator then solves the contact in closed
    form), else 0. The one place that asks whether a law is linear."""
    return law.linear_stiffness or 0.0


def reference_contact_stiffness(law: ContactLaw, impactor_mass: float, velocity: float) -> float:
    """Contact stiffness [N/m] that sets the contact frequency of a run.

    For a linear law its stiffness; otherwise the tangent stiffness on the loading
    curve at the half-space peak indentation (where ``loading_energy = ½ m V0²``),
    the stiffest the contact gets in a rigid-target impact.
    """
    linear = _linear_stiffness(law)
    if linear > 0.0:
        return linear
    alpha_peak = float(law.indentation_for_energy(0.5 * impactor_mass * velocity**2))
    stiffness = float(law.tangent_stiffness(alpha_peak, alpha_peak))
    if not stiffness > 0:
        raise ValueError("contact law has zero stiffness at the half-space peak indentation")
    return stiffness


def contact_radius_function(law: ContactLaw, effective_radius: float | None = None):
    """α [m] → contact radius a [m] of ``law``, or ``None`` when the law has no geometry.

    A law with ``loading_contact_radius`` (Stronge) uses it; otherwise
    ``a = sqrt(R α)`` with R the ``effective_radius`` given [m], else the law's
    :attr:`~impactmaps.contact.base.ContactLaw.contact_radius_scale`. Laws without
    either (a linear law, or a Hertz law built from its stiffness alone) give ``None``:
    the point load.
    """
    if hasattr(law, "loading_contact_radius"):
        return lambda alpha: float(law.loading_contact_radius(alpha))
    radius = effective_radius if effective_radius is not None else law.contact_radius_scale
    if radius is None:
        return None
    require_positive("effective_radius", radius, "m")
    return lambda alpha: float(np.sqrt(float(radius) * max(float(alpha), 0.0)))


def _uses_patch(target, contact_patch: str) -> bool:
    """Whether ``contact_patch`` asks for the Hertz patch on ``target`` and it supports one."""
    if not getattr(target, "supports_contact_patch", False):
        return False
    if contact_patch == "auto":
        return getattr(target, "theory", None) == "mindlin"
    return contact_patch == "hertz-peak"


def _basis_for(target, contact_frequency, settings: ModalSettings, contact_radius=None,
               cap=None) -> ModalBasis:
    """The participating modes below the cut-off, with the residual the settings ask for
    (under a contact patch the cut-off is ``patch_cutoff_ratio`` · ω; never above ``cap``
    [rad/s] when given)."""
    ratio = settings.cutoff_ratio if contact_radius is None else settings.patch_cutoff_ratio
    max_frequency = float(ratio * contact_frequency)
    if cap is not None:
        max_frequency = min(max_frequency, float(cap))
    if isinstance(target, Target):  # never more modes than memory allows (simulate's plan)
        max_frequency = budget_cutoff(target, max_frequency)
    if isinstance(target, ModalBasis):
        basis = target.participating().truncate(max_frequency, int(settings.min_modes))
    elif isinstance(target, Target):
        options = {} if contact_radius is None else {"contact_radius": contact_radius}
        basis = _participating_modes(target, max_frequency, int(settings.min_modes), options)
    else:
        raise ValueError(f"target = {target!r} is not a Target or a ModalBasis")
    residual = basis.residual_compliance if settings.residual_flexibility else 0.0
    return ModalBasis.from_validated(basis.frequencies, basis.participation, residual, basis.damping_ratios)


#: How far :func:`_participating_modes` raises the modes it asks a target for (× min_modes).
_FLOOR_REQUEST_LIMIT = 64


def _participating_modes(target, max_frequency: float, min_modes: int, options: dict) -> ModalBasis:
    """The participating modes of ``target`` below ``max_frequency`` [rad/s], at least
    ``min_modes`` of them when it has them.

    The floor counts the modes the impact point sees (:meth:`ModalBasis.participating`:
    a mode at rest there is dropped, degenerate ones merge), as the maps' basis tables
    do: asked for four modes, an SS beam struck at mid-span gives two that move it and a
    square plate struck at its centre one or two, which left heavy impactors
    under-resolved (plate ζ = 10.9, λ = 0.119: F̄max 0.359 on 2 modes, 0.366 converged).
    More modes are asked for (doubling) until enough participate — whole: a degenerate group
    is kept with all its copies, as the maps' tables keep it — or the target has no more.
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
) -> ImpactResult:
    """Simulate a sphere striking a modal target, through every re-impact.

    Parameters
    ----------
    target : Target or ModalBasis
        The struck structure (beam, plate, half-space, …) or directly its modes at the
        impact point (:class:`impactmaps.targets.halfspace.HalfSpace` is the same as an
        empty :class:`ModalBasis` with zero residual).
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
        the sampled scheme, also a linear contact that would take the exact phase).
    effective_radius : float, optional
        Effective radius R [m] of the sphere–target contact for the contact patch
        (``settings.contact_patch``, default ``"auto"``) when the law carries none
        (:func:`contact_radius_function`); ignored for point loads.

    Returns
    -------
    ImpactResult
        Where the patch was applied (``settings.contact_patch``), ``result.settings``
        also holds ``contact_radius_m``, the converged patch radius [m].
        ``method`` says what answered: ``"modal+residual"`` (or ``"modal"`` without
        the residual), ``"modal+residual-capped"`` or ``"infinite-structure-asymptote"``.

    Raises
    ------
    ValueError
        Bad input, or an impact no method answers within the memory cap.

    Notes
    -----
    Memory is bounded for every input: when the cut-off of a :class:`Target` lies above
    more than :data:`~impactmaps.solvers.mode_budget.MAX_MODES` modes (counted, not
    built), :func:`~impactmaps.solvers.mode_budget.plan_basis` decides — the
    infinite-structure solution if no reflection returns before the contact is over,
    else the modes up to the cap plus residual compliance (a
    :class:`~impactmaps.solvers.mode_budget.ModeBudgetWarning`), else a ``ValueError``.
    The same holds where the target's own model caps the cut-off (a Ritz plate, a
    finite-element beam: :meth:`~impactmaps.targets.base.Target.resolution_limit`).
    A :class:`ModalBasis` target is integrated as given. Before each integration the
    run's memory and time are estimated (:mod:`~impactmaps.solvers.run_budget`): above
    1 GiB the run is refused (``ValueError`` naming the knob and the value that fits),
    above a minute it is announced (:class:`~impactmaps.solvers.run_budget.LongRunWarning`).
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
    if _uses_patch(target, settings.contact_patch):
        radius_of = contact_radius_function(law, effective_radius)
    plan = None
    if isinstance(target, Target):  # the budget of the cut-off the run will use
        ratio = settings.cutoff_ratio if radius_of is None else settings.patch_cutoff_ratio
        contact_frequency = np.sqrt(reference_contact_stiffness(law, impactor_mass, velocity) / impactor_mass)
        plan = _plan(target, law, impactor_mass, velocity, float(ratio * contact_frequency))
        if plan.method == METHODS[2]:
            warnings.warn(plan.message, ModeBudgetWarning, stacklevel=2)
            return asymptote_result(plan, target, law, impactor_mass, velocity, record,
                                    _settings_dict(settings))
        if plan.method == METHODS[1]:
            warnings.warn(plan.message, ModeBudgetWarning, stacklevel=2)
    cap = plan.max_frequency if plan is not None and plan.method == METHODS[1] else None
    run = functools.partial(_run_at, target, law, params, impactor_mass, velocity, settings, time_step,
                            radius_of)
    result = run(record, cap)
    if cap is not None:
        result = replace(result, method=METHODS[1])
    if settings.check_convergence:
        fine = simulate(target, law, impactor_mass, velocity, settings=settings.refined(), record=False,
                        effective_radius=effective_radius)
        result = _checked(result, fine, settings.tolerance, cap, run)
    return result


def _plan(target: Target, law, impactor_mass: float, velocity: float, wanted: float):
    """:func:`~impactmaps.solvers.mode_budget.plan_basis` of a run whose cut-off is ``wanted``
    [rad/s], also where the target's model, not memory, caps it.

    A target of bounded size resolves modes up to :meth:`Target.resolution_limit` only (a
    Ritz plate's largest basis, a finite-element beam's largest mesh): a cut-off above it
    is a capped basis like one above the memory cap — the infinite-structure solution if
    no reflection returns before the contact is over, else the modes up to the limit
    (residual flexibility for the rest) if it lies far enough above ω, else a refusal
    naming the impactor mass that fits. (Before, such a run silently integrated the
    resolved modes and let the residual stand in for the rest.)
    """
    limit = float(target.resolution_limit())
    if wanted <= limit:
        return plan_basis(target, law, impactor_mass, velocity, wanted)
    return plan_basis(target, law, impactor_mass, velocity, wanted, max_modes=target.resolved_mode_count(),
                      cap_frequency=limit)


def _run_at(target, law, params, impactor_mass, velocity, settings, time_step, radius_of, record, cap):
    """One run of :func:`simulate` (point load or patch) with the cut-off capped at ``cap`` [rad/s]
    (``None``: the settings' cut-off)."""
    if radius_of is None:
        return _run(target, law, params, impactor_mass, velocity, settings, record, time_step, cap=cap)
    return _run_with_patch(target, law, params, impactor_mass, velocity, settings, record, time_step,
                           radius_of, cap)


def _checked(result: ImpactResult, fine: ImpactResult, tolerance: float, cap, run) -> ImpactResult:
    """``result`` with ``converged`` set: F̄max against the ``fine`` run (twice the cut-off,
    half the step), and, for a capped basis (``cap`` [rad/s]), against a run at half the cap
    — what is actually capped; a warning and ``convergence_note`` say why when not."""
    changes = [(abs(fine.fmax_normalised - result.fmax_normalised), "the cut-off was doubled and the step halved")]
    if cap is not None:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # the coarse run's own warnings say nothing new
            coarse = run(False, 0.5 * cap)
        changes.append((abs(coarse.fmax_normalised - result.fmax_normalised),
                        f"the capped basis (modes up to {cap:.4g} rad/s, "
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
    """:func:`_run` under the Hertz patch of the peak indentation, by fixed-point iteration.

    From the half-space peak indentation: run → α_max → ``a = radius_of(α_max)`` → run,
    until a moves by < :data:`PATCH_TOLERANCE`; the passes record no history, the run at the
    settled radius records it when asked. The warnings of the passes are held back
    and only those of the last run (the converged radius) are issued: the first guess
    (a rigid target's α_max) can be several times the converged radius on a compliant
    plate and would raise a "contact radius exceeds half the thickness" warning that
    does not apply. ``result.settings["contact_radius_m"]`` is the radius used [m].
    """
    radius = radius_of(law.indentation_for_energy(0.5 * impactor_mass * velocity**2))
    for _ in range(PATCH_PASSES):
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            result = _run(target, law, params, impactor_mass, velocity, settings, False, time_step, radius, cap)
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
            result = _run(target, law, params, impactor_mass, velocity, settings, True, time_step, radius, cap)
    for caught_warning in caught:
        warnings.warn(caught_warning.message, stacklevel=3)
    result.settings["contact_radius_m"] = float(radius)
    return result


def _coupled_phase(basis: ModalBasis, law: ContactLaw, impactor_mass: float, time_step: float,
                   contact_frequency: float, choice: str) -> CoupledModes:
    """The coupled modes for the exact contact phase, or empty arrays for the sampled one.

    ``choice`` is :attr:`ModalSettings.contact_phase`. With ``"auto"`` the exact phase
    (:mod:`~impactmaps.solvers.coupled_contact`) serves linear laws on undamped modes
    when the sampled scheme's step ``time_step`` would cost more than the set-up
    (:data:`COUPLED_COST_RATIO`): in the quasi-static corner the modes the mode
    floor keeps lie ~10⁴ ω above the contact, the stability limit holds the sampled step
    to ~1/ω_top and a contact took ~10⁷ steps; the exact phase takes ~10².
    """
    stiffness = _linear_stiffness(law)
    sampled_steps = np.pi / (contact_frequency * time_step)
    cheaper = basis.size < COUPLED_ALWAYS_MODES or sampled_steps > COUPLED_COST_RATIO * (basis.size + 1) ** 2
    wanted = choice == "exact" or (choice == "auto" and cheaper)
    # never beyond COUPLED_MAX_MODES: the set-up holds (n + 1)² matrices
    if stiffness > 0.0 and wanted and basis.size <= COUPLED_MAX_MODES:
        coupled = coupled_modes(basis, stiffness, impactor_mass)
        if coupled is not None:
            return coupled
    return _NO_COUPLED_MODES


#: Runs estimated above this many seconds (:mod:`~impactmaps.solvers.run_budget`) integrate
#: in a worker thread, so that Ctrl-C stops them at once (see :func:`_integrate`).
INTERRUPTIBLE_SECONDS = 0.5


def _integrate(interruptible: bool, *args):
    """:data:`~impactmaps.solvers.exact_step.integrate_impact` on ``args`` (the last one the
    kernel's one-element ``stop`` flag).

    A compiled loop does not see Ctrl-C (the signal is handled between Python bytecodes).
    When ``interruptible``, the kernel (which releases the GIL) runs in a worker thread
    while this thread waits in 0.1 s slices; on ``KeyboardInterrupt`` it sets the stop flag,
    which the kernel reads at every step, waits for the kernel to return and re-raises.
    The arithmetic is the kernel's own either way: results are bit for bit those of a direct
    call. Short runs (most map points) call the kernel directly, without a thread.
    """
    if not interruptible:
        return integrate_impact(*args)
    import threading

    integrate_impact.compile()  # compiling holds the interpreter: do it here, not in the worker
    outcome = {}
    done = threading.Event()  # not Thread.join: a join interrupted by Ctrl-C can return early later

    def work():
        try:
            outcome["result"] = integrate_impact(*args)
        except BaseException as error:  # noqa: BLE001 (handed to the caller's thread)
            outcome["error"] = error
        finally:
            done.set()

    threading.Thread(target=work, name="impactmaps-modal-kernel", daemon=True).start()
    try:
        while not done.wait(0.1):
            pass
    except KeyboardInterrupt:
        args[-1][0] = 1
        done.wait()
        raise
    if "error" in outcome:
        raise outcome["error"]
    return outcome["result"]


def _kernel_array(values: np.ndarray) -> np.ndarray:
    """``values`` as the kernel's signature takes them: C-contiguous, writeable float64 (the
    same array when it already is; a copy of a read-only view, such as a cached Ritz
    solution's frequencies, which the compiled signature would refuse with a TypeError)."""
    return np.require(values, dtype=np.float64, requirements=("C", "W"))


def _run(target, law, params, impactor_mass, velocity, settings, record, time_step,
         contact_radius=None, cap=None) -> ImpactResult:
    """One run of :func:`simulate` (validated inputs) with a point load or a patch [m], the
    cut-off capped at ``cap`` [rad/s] when given."""
    stiffness = reference_contact_stiffness(law, impactor_mass, velocity)
    omega_c = float(np.sqrt(stiffness / impactor_mass))
    basis = _basis_for(target, omega_c, settings, contact_radius, cap)
    automatic = time_step is None
    coupled = _NO_COUPLED_MODES
    if automatic:
        omega_top = coupled_top_frequency(basis, stiffness, impactor_mass, rtol=1e-3)
        content = content_time_step(basis, stiffness, impactor_mass, settings.force_resolution)

        def step(cap):
            return settings.step_scale * min(settings.time_step_ratio / omega_c,
                                             max(settings.resolve_ratio / omega_top, min(content, cap)))

        time_step = step(STABLE_TOP_STEP / omega_top)
        coupled = _coupled_phase(basis, law, impactor_mass, time_step, omega_c, settings.contact_phase)
        if coupled.frequencies.size:
            # contacts are exact: the step only serves free flight, where every mode moves
            # exactly, so the stability limit of the sampled contact loop does not apply
            time_step = step(np.inf)
    else:
        require_positive("time_step", time_step, "s")
    max_time = settings.max_time_ratio / omega_c
    budget = modal_run_budget(basis.size, float(time_step), max_time, omega_c, bool(record),
                              int(settings.max_events), not automatic)
    refuse_or_announce(budget, f"modal run of {basis.size} modes", stacklevel=4)
    history, intervals, scalars = _integrate(budget.seconds > INTERRUPTIBLE_SECONDS,
        kernel_pointer(law.kernel),
        params,
        _linear_stiffness(law),
        _kernel_array(basis.frequencies),
        _kernel_array(basis.participation),
        _kernel_array(basis.damping_ratios),
        float(basis.residual_compliance),
        float(impactor_mass),
        float(velocity),
        float(time_step),
        float(max_time),
        bool(record),
        int(settings.max_events),
        coupled.frequencies,
        coupled.force_row,
        coupled.from_coupled,
        coupled.to_coupled,
        float(settings.time_step_ratio / omega_c),
        float(settings.step_scale),
        np.zeros(1, dtype=np.int64),
    )
    if scalars[9]:
        warnings.warn(
            f"more than max_events = {settings.max_events} contacts: the run stopped there (time_limit_reached)",
            RuntimeWarning,
            stacklevel=3,
        )
    alpha_max = float(scalars[2])
    dissipation = 0.0 if law.elastic else float(law.dissipated_energy(alpha_max))
    result = ImpactResult(
        history=_history_frame(history, impactor_mass) if record else None,
        peak_force=float(scalars[0]),
        peak_time=float(scalars[1]),
        contact_intervals=np.asarray(intervals),
        max_indentation=alpha_max,
        permanent_indentation=0.0 if law.elastic else float(law.permanent_indentation(alpha_max)),
        rebound_velocity=float(-scalars[3]),
        energy_transferred=float(scalars[4]),
        contact_dissipation=dissipation,
        damping_work=float(scalars[5]),
        energy_balance_error=energy_balance_error(
            impactor_mass, velocity, float(-scalars[3]), float(scalars[4]), dissipation, float(scalars[5])),
        end_time=float(scalars[6]),
        time_limit_reached=bool(scalars[7]),
        impactor_mass=float(impactor_mass),
        velocity=float(velocity),
        contact_frequency=omega_c,
        n_modes=basis.size,
        time_step=float(time_step),
        method="modal+residual" if settings.residual_flexibility else "modal",
        settings=_settings_dict(settings),
        details=ModalDetails(int(scalars[8]), "exact" if coupled.frequencies.size else "sampled"),
    )
    if result.time_limit_reached:
        warnings.warn(
            f"impact run stopped at its time limit ({max_time:.3g} s) before re-impact "
            "became impossible; scalars describe a truncated event",
            ConvergenceWarning,
            stacklevel=3,
        )
    return result


def simulate_normalised(
    target: Target,
    loss_factor: float,
    relative_stiffness: float,
    *,
    settings: ModalSettings | None = None,
    record: bool = True,
) -> ImpactResult:
    """Simulate the linear-contact impact that realises (ζ, λ) on ``target``.

    The impactor is built by the inverse of the dimensionless framework (spec §4):
    ``K = K_st/λ`` and ``m_i`` from the structure's loss-factor formula; the velocity
    is 1 m/s (the linear problem scales with it). Use the normalised properties of
    the result (``fmax_normalised``, ``normalised_history()``).
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
    """Simulate many independent impacts, in parallel threads (the kernel releases the GIL).

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
        In the order of ``cases``; identical to running :func:`simulate` one by one.
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
