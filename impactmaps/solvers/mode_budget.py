"""How many modes a run may build, and what answers when a run would need more.

A light impactor on a flexible structure has a contact frequency ω far above the
structure's fundamental, and the cut-off ``cutoff_ratio · ω`` of the modal solver then
lies above millions of modes (a plate has ~ω of them, a Mindlin plate ~ω²): building
them exhausts memory long before the run ends. :func:`plan_basis` decides, from a count
of the modes that does not build them (:meth:`impactmaps.targets.base.Target.mode_count`),
what answers such a run (spec §3.6):

* the wanted cut-off lies below the cap — the modal solver as usual
  (``"modal+residual"``);
* above it, when the first wave reflected by a boundary returns to the impact point
  only after :data:`ASYMPTOTE_REFLECTION_FACTOR` times the peak time of the
  infinite-structure solution — that solution, exact until the reflection returns
  (``"infinite-structure-asymptote"``): the closed forms of
  :meth:`~impactmaps.targets.base.Target.infinite_structure_impact` for a linear law,
  the any-law asymptotes of :mod:`impactmaps.closed_forms.law_asymptotes` (infinite plate or beam)
  otherwise — for Euler beams and Kirchhoff plates only: these classical solutions do
  not answer for a Timoshenko beam or a Mindlin plate
  (:func:`impactmaps.targets.shear_range.has_classical_asymptote`);
* otherwise the modes up to the cap plus the residual compliance of the rest, with a
  warning (``"modal+residual-capped"``), if the cap still lies at least
  :data:`MIN_CAPPED_CUTOFF_RATIO` times above ω (the dropped modes then respond nearly
  statically, which is what the residual compliance assumes);
* else a ``ValueError`` naming the impactor mass, its value and the range it needs.

The modal solver (:func:`impactmaps.solvers.modal.simulate`) applies it with the memory
cap :data:`MAX_MODES`; the map sweep (:func:`impactmaps.maps.compute.linear_points.solve_points`) with
its own, smaller cost cap.
"""

from __future__ import annotations

import functools
import math
import warnings
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np

from ..contact.contact_scale import reference_contact_stiffness
from ..targets.shear_range import has_classical_asymptote

if TYPE_CHECKING:
    from ..result import ImpactResult

__all__ = ["MEMORY_BUDGET_BYTES", "BASELINE_BYTES", "BYTES_PER_MODE", "MAX_MODES",
           "ASYMPTOTE_REFLECTION_FACTOR", "MIN_CAPPED_CUTOFF_RATIO", "METHODS", "BasisPlan",
           "budget_cutoff", "frequency_cap", "plan_basis", "halved_cap_change", "asymptote_result", "ModeBudgetWarning",
           "ModeBudgetError", "AsymptoteDetails"]

#: Memory one run may use [B].
MEMORY_BUDGET_BYTES = 1024**3
#: What a run holds before any mode [B]: the interpreter with numpy, scipy, pandas, numba
#: and the compiled kernels (~300 MiB resident, measured with ``ru_maxrss`` after a small
#: run), rounded up.
BASELINE_BYTES = 384 * 1024**2
#: Bytes per mode below the cut-off, rounded up from the measured parts: building the
#: Navier modes peaks at ~81 B per mode (Kirchhoff) and ~360 B (Mindlin: the stacked 3×3
#: problems), the bases the targets' caches keep hold ~54 B, and the integrator allocates
#: 70 float64 per integrated mode (step coefficients 2 × 8, state 6, free-flight
#: propagators 11 × 4, a recorded run's scratch 4: 560 B) plus the basis it integrates
#: (24 B); ~1000 B in all.
BYTES_PER_MODE = 1024
#: Most modes a modal run builds: (budget − baseline) / bytes per mode = 655 360. Checked:
#: capped runs with the convergence re-run peak at 348 MiB (Kirchhoff plate, 307 567 modes
#: integrated) and 354 MiB (Mindlin plate, 170 981), ``ru_maxrss``.
MAX_MODES = (MEMORY_BUDGET_BYTES - BASELINE_BYTES) // BYTES_PER_MODE
#: The infinite-structure solution answers when the first reflection returns after this
#: many peak times (the contact is then long over: on the infinite plate and beam the
#: contact lasts at most ~3.3 peak times when it ends at all).
ASYMPTOTE_REFLECTION_FACTOR = 20.0
#: A capped basis is used only if the cap lies at least this many contact frequencies up.
#: Measured change of F̄max against a cut-off of 160 ω (with residual compliance): at 8 ω
#: ≤ 3.4e-4 for ζ ≤ 0.1 and 5.1e-3 at ζ = 1, λ = 0.1 (SS square Kirchhoff plate), ≤ 8.2e-5
#: … 7.8e-4 (SS Euler beam); at 4 ω up to 3.8e-2. No point of the shipped maps' plane
#: ([1e-3, 1e3]², sweep cap) is capped or refused.
MIN_CAPPED_CUTOFF_RATIO = 8.0
#: The methods a plan can choose (also the sweep's per-point method codes, in this order).
METHODS = ("modal+residual", "modal+residual-capped", "infinite-structure-asymptote")
#: Samples of the history of an infinite-structure answer.
HISTORY_SAMPLES = 2001


class ModeBudgetWarning(RuntimeWarning):
    """A run's cut-off needs more modes than the cap: another method answers it (which, and
    why, in the message and the result's ``method``)."""


class ModeBudgetError(ValueError):
    """No method answers a run within the mode cap (raised by :func:`plan_basis`).

    Attributes
    ----------
    reason : str
        Why, in words.
    impactor_mass : float
        m_i [kg] of the run.
    highest_frequency : float
        Highest contact frequency [rad/s] the target can answer at this impact point.
    stiffness : float
        Reference contact stiffness K [N/m] of the run; ``K/highest_frequency²`` [kg] is
        the lightest impactor answered at this stiffness.
    """

    def __init__(self, reason: str, impactor_mass: float, highest_frequency: float, stiffness: float):
        self.reason, self.impactor_mass = reason, float(impactor_mass)
        self.highest_frequency, self.stiffness = float(highest_frequency), float(stiffness)
        super().__init__(
            f"impactor_mass = {impactor_mass:.6g} kg is invalid on this target: {reason}; valid range: "
            f"a contact frequency ≤ {highest_frequency:.4g} rad/s (at this contact stiffness, "
            f"impactor_mass ≥ {self.lightest_mass:.4g} kg), or an impact point farther from the boundary")

    @property
    def lightest_mass(self) -> float:
        """Lightest impactor [kg] answered at this contact stiffness, K/ω_max²."""
        return self.stiffness / self.highest_frequency**2


@dataclass(frozen=True)
class BasisPlan:
    """What answers one run (see the module docstring).

    Attributes
    ----------
    method : str
        One of :data:`METHODS`.
    max_frequency : float
        Cut-off [rad/s] to build the basis at: the wanted one, or the cap.
    cap_frequency : float
        The cap [rad/s] the cut-off was held against: :func:`frequency_cap` of the
        target (or the caller's cap), or the cut-off itself when it needs none.
    contact_frequency : float
        ω [rad/s] of the run.
    reflection_time : float
        First wave return to the impact point [s] (``nan`` when not needed).
    asymptote : object or None
        The infinite-structure answer: :class:`~impactmaps.targets.base.InfiniteImpact`
        (linear law, normalised) or :class:`~impactmaps.closed_forms.law_asymptotes.AsymptoteResult`.
    asymptote_name : str or None
        Which asymptote: ``"infinite-plate"`` or ``"infinite-beam"``, with
        ``" (linear, closed form)"`` or ``" (any law)"``.
    message : str
        Why this method (empty for the plain modal run).
    """

    method: str
    max_frequency: float
    cap_frequency: float
    contact_frequency: float
    reflection_time: float = math.nan
    asymptote: object = None
    asymptote_name: str | None = None
    message: str = ""


#: Doublings without a new mode after which :func:`frequency_cap` takes the model to have
#: no more: 3, a factor 8 — the widest gap between consecutive bending modes is a
#: cantilever's first, ω2/ω1 = 6.27 (a stop at the first doubling without a new mode
#: capped a cantilever at 3 ω1, so every map point on it came out unresolved).
_STALLED_DOUBLINGS = 3


@functools.lru_cache(maxsize=16)
def frequency_cap(target, max_modes: int = MAX_MODES) -> float:
    """Largest frequency [rad/s] below which ``target`` has at most ~``max_modes`` modes.

    From 1.5 × the fundamental, the frequency is doubled while the count
    (:meth:`~impactmaps.targets.base.Target.mode_count`, no mode built) stays within
    ``max_modes``; it also stops where the target has no more modes to give (a Ritz plate
    or a finite-element beam stops at its largest model): at the last frequency that
    added a mode, once ``_STALLED_DOUBLINGS`` doublings have added none. ``inf`` for a target without
    elastic modes (a half-space). A pure function of its arguments (targets are frozen),
    cached (bounded).
    """
    frequencies = target.modes(0.0, min_modes=1).frequencies
    if frequencies.size and frequencies[0] == 0.0:  # rigid-body modes: start from the first elastic one
        frequencies = target.modes(0.0, min_modes=3).frequencies
    elastic = frequencies[frequencies > 0.0]
    if not elastic.size:
        return math.inf
    frequency = float(elastic[0]) * 1.5 + 1e-30
    count, probe, stalled = 0, frequency, 0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # probing only
        while math.isfinite(2.0 * probe):
            probe *= 2.0
            more = max(target.mode_count(probe, limit=max_modes), 1)
            if more > max_modes:
                return frequency
            if more > count:
                count, frequency, stalled = more, probe, 0
                continue
            # no new mode in this doubling: a gap (a cantilever's ω2 = 6.27 ω1), or the
            # model has no more modes to give once _STALLED_DOUBLINGS doublings add none
            stalled += 1
            if stalled >= _STALLED_DOUBLINGS:
                return frequency
    return frequency


def budget_cutoff(target, max_frequency: float, max_modes: int = MAX_MODES) -> float:
    """The cut-off [rad/s] to build ``target``'s basis at: ``max_frequency``, or
    :func:`frequency_cap` when more than ``max_modes`` modes lie below it.

    A target of bounded size (``target.bounded_modes``: Ritz plates, finite-element
    beams) keeps its cut-off. Otherwise a cut-off below the (cached) cap holds at most
    ``max_modes`` modes; one above it is counted
    (:meth:`~impactmaps.targets.base.Target.mode_count`, no mode built).
    """
    max_frequency = float(max_frequency)
    if getattr(target, "bounded_modes", False):
        return max_frequency
    cap = frequency_cap(target, int(max_modes))
    if max_frequency <= cap or target.mode_count(max_frequency, limit=int(max_modes)) <= max_modes:
        return max_frequency
    return cap


def plan_basis(target, law, impactor_mass: float, velocity: float, max_frequency: float, *,
               max_modes: int = MAX_MODES, cap_frequency: float | None = None,
               loss_factor: float | None = None, estimate: bool = False) -> BasisPlan:
    """Decide what answers a modal run on ``target`` whose cut-off is ``max_frequency``.

    Parameters
    ----------
    target : Target
        The struck structure.
    law : ContactLaw
        The contact law (linear: the closed-form asymptotes; any other: the any-law ones).
    impactor_mass : float
        m_i [kg].
    velocity : float
        V0 [m/s].
    max_frequency : float
        The cut-off the settings ask for [rad/s].
    max_modes : int, optional
        The cap on the modes below the cut-off (default :data:`MAX_MODES`, from memory).
    cap_frequency : float, optional
        The cap as a frequency [rad/s], when the caller's modes are built there (a map
        sweep's basis table: :func:`frequency_cap` of its structure); the cut-off then
        exceeds the cap when it lies above it. Default: when more than ``max_modes``
        modes lie below the cut-off (:func:`budget_cutoff`).
    loss_factor : float, optional
        ζ [-] of a linear-law run when the caller knows it exactly (a map point);
        default ``target.loss_factor(m_i, K)``.
    estimate : bool, optional
        Plan without integrating anything (``impactmaps check``): for a law other than
        linear, the infinite-structure peak time is the closed form's at the law's reference
        stiffness, and the plan's ``answer`` that closed form (normalised), not the any-law run.

    Returns
    -------
    BasisPlan

    Raises
    ------
    ValueError
        When the cut-off needs more than ``max_modes`` modes, the infinite-structure
        solution does not hold (a reflection returns too early) and the cap lies below
        :data:`MIN_CAPPED_CUTOFF_RATIO` ω.
    """
    stiffness = reference_contact_stiffness(law, impactor_mass, velocity)
    omega = math.sqrt(stiffness / impactor_mass)
    if cap_frequency is None:
        cap = budget_cutoff(target, max_frequency, max_modes)
        exceeds = cap < max_frequency
    else:
        cap, exceeds = float(cap_frequency), max_frequency > cap_frequency
    if not exceeds:
        return BasisPlan(METHODS[0], float(max_frequency), cap, omega)
    reflection = float(target.reflection_time(omega)) / omega
    name, answer, peak_time, contact_end = _infinite_structure(target, law, impactor_mass, velocity, stiffness,
                                                               loss_factor, estimate)
    plan = BasisPlan(METHODS[0], cap, cap, omega, reflection, answer, name)
    many = (f"the cut-off {max_frequency:.4g} rad/s ({max_frequency / omega:.3g} ω) needs more than "
            f"{max_modes} modes")
    # exact for the whole event only: the contact must also end before the reflection returns
    whole_event = math.isfinite(contact_end) and reflection >= contact_end
    if answer is not None and reflection >= ASYMPTOTE_REFLECTION_FACTOR * peak_time and whole_event:
        return _replace(plan, METHODS[2], f"{many}; the first reflection returns after "
                        f"{reflection / peak_time:.3g} peak times: answered by the {name} asymptote")
    if cap >= MIN_CAPPED_CUTOFF_RATIO * omega:
        return _replace(plan, METHODS[1], f"{many}; integrating the modes up to {cap:.4g} rad/s "
                        f"({cap / omega:.3g} ω), residual flexibility for the rest")
    highest = cap / MIN_CAPPED_CUTOFF_RATIO
    if not has_classical_asymptote(target):
        why = (f"no infinite-structure solution answers for a {getattr(target, 'theory', '?')} target: the "
               "closed forms are those of Euler beams and Kirchhoff plates")
    else:
        returns = f"{reflection / peak_time:.3g} peak times" if answer is not None else "too early"
        why = (f"a wave reflected from the boundary returns after {returns} ({reflection:.3g} s), before the "
               f"{ASYMPTOTE_REFLECTION_FACTOR:g} peak times and the end of the contact "
               f"({contact_end:.3g} s) the infinite-structure solution needs")
    raise ModeBudgetError(f"its contact frequency {omega:.4g} rad/s is too high ({many}, and {why})",
                          impactor_mass, highest, stiffness)


def halved_cap_change(base: ImpactResult, cap: float, run_at) -> tuple[float, ImpactResult]:
    """The check of a capped basis (``"modal+residual-capped"``): the run with the cap halved.

    Parameters
    ----------
    base : ImpactResult
        The run at the cap.
    cap : float
        The cap, in the unit ``run_at`` takes (rad/s for :func:`~impactmaps.solvers.modal.simulate`,
        a ratio to ω for a map point).
    run_at : callable
        ``run_at(cap / 2) -> ImpactResult``: the same run with the cap halved.

    Returns
    -------
    tuple
        The change of F̄max [-] from ``base`` to the halved run, and that run.
    """
    coarse = run_at(0.5 * cap)
    return abs(coarse.fmax_normalised - base.fmax_normalised), coarse


def _replace(plan: BasisPlan, method: str, message: str) -> BasisPlan:
    return replace(plan, method=method, message=message)


def _infinite_structure(target, law, impactor_mass, velocity, stiffness, loss_factor, estimate=False):
    """(name, answer, peak time [s], contact end [s], ``inf`` if it never ends) of the
    infinite-structure impact, or (None, None, nan, nan); ``estimate``: from the closed form
    at the reference stiffness, for any law (no integration)."""
    kind = getattr(target, "kind", None)
    if kind not in ("plate", "beam") or not has_classical_asymptote(target):
        return None, None, math.nan, math.nan
    omega = math.sqrt(stiffness / impactor_mass)
    if law.linear_stiffness is not None or estimate:
        zeta = float(target.loss_factor(impactor_mass, stiffness)) if loss_factor is None else float(loss_factor)
        impact = target.infinite_structure_impact(zeta)
        end = float(impact.contact_time) / omega if np.isfinite(impact.contact_time) else math.inf
        form = "linear, closed form" if law.linear_stiffness is not None else "any law"
        return f"infinite-{kind} ({form})", impact, float(impact.peak_time) / omega, end
    from ..closed_forms.law_asymptotes import asymptote  # scipy's integrators: only where an asymptote answers

    answer = asymptote(f"infinite-{kind}", target, law, impactor_mass, velocity)
    end = float(answer.contact_time) if np.isfinite(answer.contact_time) else math.inf
    return f"infinite-{kind} (any law)", answer, float(answer.peak_time), end


# -- the infinite-structure answer as an ImpactResult ------------------------------------------
@dataclass(frozen=True)
class AsymptoteDetails:
    """What an infinite-structure answer adds to :class:`ImpactResult` (``details``).

    Attributes
    ----------
    asymptote : str
        Which solution answered (see :attr:`BasisPlan.asymptote_name`).
    reflection_time : float
        First wave return to the impact point [s]: the answer is exact until then.
    cap_frequency : float
        The mode cap [rad/s] the wanted cut-off exceeded.
    max_target_displacement : float
        Largest displacement of the struck point [m].
    """

    asymptote: str
    reflection_time: float
    cap_frequency: float
    max_target_displacement: float

    def summary(self) -> dict:
        """The details as unit-suffixed JSON-ready keys."""
        return {"asymptote": self.asymptote, "reflection_time_s": float(self.reflection_time),
                "mode_cap_frequency_rad_s": float(self.cap_frequency),
                "max_target_displacement_m": float(self.max_target_displacement)}


def asymptote_result(plan: BasisPlan, target, law, impactor_mass: float, velocity: float,
                     record: bool, settings: dict) -> ImpactResult:
    """The :class:`ImpactResult` of a run ``plan`` answers by the infinite-structure solution.

    ``method = "infinite-structure-asymptote"``, ``n_modes = 0``, ``time_step = nan`` and
    ``details`` an :class:`AsymptoteDetails`. The event ends at the separation; if the
    sphere does not leave the infinite structure for good (no separation, or it still
    moves towards the beam when it separates), the result stops at the reflection time
    with ``time_limit_reached`` (and a warning). ``record`` keeps a sampled history for a
    linear law (closed forms); the any-law asymptotes give scalars only (``history``
    ``None``, with a warning).
    """
    from ..result import ImpactResult

    answer, omega, mass, speed = plan.asymptote, plan.contact_frequency, float(impactor_mass), float(velocity)
    if hasattr(answer, "fmax_normalised"):  # AsymptoteResult (SI)
        finished = not answer.time_limit_reached
        peak, peak_time, contact = answer.peak_force, answer.peak_time, answer.contact_time
        rebound = answer.restitution * speed if finished else math.nan
        alpha_max, moved = answer.max_indentation, answer.max_target_displacement
        intervals = np.array(answer.contact_intervals, dtype=float).reshape(-1, 2)
        history = None
        if record:
            warnings.warn(f"the {plan.asymptote_name} asymptote gives scalars only: no history",
                          RuntimeWarning, stacklevel=3)
    else:  # InfiniteImpact (linear law, normalised)
        first = answer.contact_time / omega if np.isfinite(answer.contact_time) else math.inf
        finished = bool(math.isfinite(first) and answer.rebound_velocity < 0)
        peak, peak_time = answer.peak_force * mass * speed * omega, answer.peak_time / omega
        contact = first if finished else math.inf
        rebound = -answer.rebound_velocity * speed if finished else math.nan
        alpha_max = peak / law.linear_stiffness
        intervals = np.array([[0.0, first]])
        history, moved = _linear_history(target, answer, plan, law, mass, speed, first)
        history = history if record else None
    end = contact if finished else plan.reflection_time
    if not finished:
        if not math.isfinite(intervals[-1, 1]):
            intervals[-1, 1] = math.nan  # a contact still open
        warnings.warn(f"on the infinite structure the impact is not over when the first reflection "
                      f"returns ({plan.reflection_time:.4g} s): the peak is exact, the later scalars "
                      "describe the event up to then", RuntimeWarning, stacklevel=3)
    impact_energy = 0.5 * mass * speed**2
    dissipation = 0.0 if law.elastic else float(law.dissipated_energy(alpha_max))
    left = impact_energy - 0.5 * mass * rebound**2 - dissipation if finished else math.nan
    return ImpactResult(
        history=history, peak_force=float(peak), peak_time=float(peak_time), contact_intervals=intervals,
        max_indentation=float(alpha_max),
        permanent_indentation=0.0 if law.elastic else float(law.permanent_indentation(alpha_max)),
        rebound_velocity=float(rebound), energy_transferred=float(left), contact_dissipation=dissipation,
        damping_work=0.0, energy_balance_error=0.0 if finished else math.nan, impactor_mass=mass,
        velocity=speed, contact_frequency=omega, end_time=float(end), time_limit_reached=not finished,
        time_step=math.nan, method=METHODS[2], n_modes=0, settings=settings,
        details=AsymptoteDetails(str(plan.asymptote_name), plan.reflection_time, plan.cap_frequency,
                                 float(moved)),
    )


def _linear_history(target, impact, plan: BasisPlan, law, mass, speed, contact):
    """(history DataFrame, largest target displacement [m]) of a linear-law infinite impact.

    The closed-form indentation ᾱ(τ) (the force is Kα while in contact) sampled on
    :data:`HISTORY_SAMPLES` points up to the first separation at ``contact`` [s] (or, if
    there is none, the reflection time); the
    impactor velocity and displacement integrate the force (trapezoids), the struck
    point moves by ``w_i − α``.
    """
    import pandas as pd

    from ..closed_forms.asymptotes import infinite_plate_indentation
    from ..closed_forms.infinite_beam import infinite_beam_indentation
    from ..result import HISTORY_COLUMNS

    omega = plan.contact_frequency
    end = contact if math.isfinite(contact) else min(plan.reflection_time,
                                                     ASYMPTOTE_REFLECTION_FACTOR * impact.peak_time / omega)
    tau = np.linspace(0.0, end * omega, HISTORY_SAMPLES)
    zeta = float(target.loss_factor(mass, law.linear_stiffness))
    shape = infinite_plate_indentation if target.kind == "plate" else infinite_beam_indentation
    force_bar = np.maximum(np.asarray(shape(tau, zeta), dtype=float), 0.0)
    step = np.diff(tau)
    velocity_bar = 1.0 - np.concatenate(([0.0], np.cumsum(0.5 * step * (force_bar[1:] + force_bar[:-1]))))
    position_bar = np.concatenate(([0.0], np.cumsum(0.5 * step * (velocity_bar[1:] + velocity_bar[:-1]))))
    target_bar = position_bar - force_bar
    scale = speed / omega
    frame = pd.DataFrame(dict(zip(HISTORY_COLUMNS, (
        tau / omega, force_bar * mass * speed * omega, force_bar * scale, position_bar * scale,
        velocity_bar * speed, target_bar * scale, np.gradient(target_bar, tau) * speed))))
    frame["impactor_kinetic_energy_J"] = 0.5 * mass * frame["impactor_velocity_m_s"] ** 2
    return frame, float(np.max(np.abs(target_bar)) * scale)
