r"""Asymptotes whose structure acts at the impact point alone: dashpot, spring, rigid.

For any registered contact law ``F(α; α_max)`` the impactor (mass m, speed V0) obeys
``m ẍ = −F``, the indentation is ``α = x − w`` and the struck point moves as

* **infinite plate** — a dashpot: ``ẇ = F/Z``, ``Z = 8 sqrt(ρh D*)`` the point impedance
  of an infinite Kirchhoff plate (seed 001 eq 30). With ``F = Kα`` this is the damped
  oscillator ``ᾱ'' + 2ζ_p ᾱ' + ᾱ = 0``, ``2ζ_p = sqrt(mK)/Z`` (seed 001 eqs 32–34); with
  Hertz contact it is Zener's model of a ball striking a plate (Zener, Phys. Rev. 59,
  1941, 669; see :mod:`impactmaps.hertz_similarity` for its parameter);
* **quasi-static** — a massless spring, the structure's static point stiffness K_st in
  series with the contact: ``w = F/K_st`` (seed 001 eq 28 for linear contact);
* **half-space** — ``w = 0``, delegated to :func:`impactmaps.solvers.halfspace.halfspace_impact`.

For the dashpot and the spring ``α̇`` is a function of the impactor velocity and the
contact state alone, ``α̇ = v − F/Z`` and ``α̇ = v/(1 + k_t/K_st)`` (``k_t = dF/dα``).
In both cases α rises to one maximum and then falls monotonically until the force
vanishes: once ``α̇ = 0`` with ``F > 0``, ``α̈ = −F/m < 0`` (dashpot: differentiate
``α̇ = v − F/Z``; spring: ``v`` has the sign of ``α̇``), and a later zero of ``α̇`` would
need ``α̈ ≥ 0``. So the run has two phases, as on the half-space: loading on the virgin
curve until ``α̇ = 0``, then unloading with ``α_max`` fixed until α reaches the permanent
indentation. At separation the plate point stops (a dashpot has no memory) and the
spring is relaxed, so the impactor leaves for good: one impact. With linear contact on
the infinite plate and ``ζ_p ≥ 1`` the force never vanishes (contact time ``inf``,
restitution 0, the impactor coming to rest).

Each phase is integrated with ``scipy`` DOP853 (rtol 1e-12) in variables scaled by the
indentation the impact energy would reach on a half-space, with terminal events at the
turning point and at separation. Where the indentation relaxes much faster than the contact
lasts (a dashpot far softer than the contact: a plate a few micrometres thick, where the
indentation follows ``F(α) = Z v`` at once) the equations are stiff and an explicit method
needs billions of steps: there the implicit Radau method integrates them. Every integration
has a budget, :data:`MAX_EVALUATIONS` evaluations of the equations, beyond which it is
refused (``ValueError``) instead of running on.
"""

from __future__ import annotations

import math

from scipy.integrate import solve_ivp

from .._checks import require_positive
from ..contact.base import ContactLaw
from ..solvers.halfspace import single_law_parameters, halfspace_impact
from .result import AsymptoteResult, contact_frequency_of

__all__ = ["halfspace_asymptote", "infinite_plate_impact", "plate_impedance", "quasi_static_impact"]

_RELATIVE_TOLERANCE = 1e-12
_ABSOLUTE_TOLERANCE = 1e-14  # on scaled states of order 1
_SCALED_TIME_LIMIT = 1e4  # in units α_scale/V0; a contact lasts O(1) of them
_REST_SPEED = 1e-10  # impactor speed / V0 below which it is taken to be at rest
#: Scaled relaxation rate |∂α̇/∂α| above which the equations count as stiff (Radau, not DOP853).
STIFF_RATE = 100.0
#: Most evaluations of the equations one asymptote may take (a contact takes 10²–10⁴).
MAX_EVALUATIONS = 200_000


class _OverBudget(Exception):
    """The integration used up :data:`MAX_EVALUATIONS`."""


def plate_impedance(plate) -> float:
    """Point impedance ``Z = 8 sqrt(ρh D*)`` [N s/m] of the infinite plate (seed 001 eq 30).

    Parameters
    ----------
    plate : Plate
        Needs ``mass_per_area`` ρh [kg/m²] and ``effective_bending_stiffness`` D* [N m].
    """
    return 8.0 * math.sqrt(float(plate.mass_per_area) * float(plate.effective_bending_stiffness))


def infinite_plate_impact(plate, law: ContactLaw, impactor_mass, velocity) -> AsymptoteResult:
    """Impact on an infinite plate (a dashpot of impedance ``8 sqrt(ρh D*)``), any law.

    Parameters
    ----------
    plate : Plate
        The plate whose ρh [kg/m²] and D* [N m] define the infinite plate (its size,
        edges and theory are ignored: exact until reflections return, see
        :mod:`impactmaps.validity`).
    law : ContactLaw
        A single registered contact law.
    impactor_mass : float
        m > 0 [kg].
    velocity : float
        V0 > 0 [m/s].

    Returns
    -------
    AsymptoteResult
        ``method = "infinite-plate"``.
    """
    impedance = plate_impedance(plate)
    return _two_phase_impact(law, impactor_mass, velocity, "infinite-plate",
                             lambda v, force, stiffness: v - force / impedance,
                             lambda force, moved: moved)


def quasi_static_impact(target, law: ContactLaw, impactor_mass, velocity) -> AsymptoteResult:
    """Heavy-impactor asymptote: the static point stiffness in series with any law.

    Parameters
    ----------
    target : Target or float
        A target (its ``static_compliance()`` [m/N] at the impact point is used) or the
        static stiffness K_st > 0 itself [N/m].
    law : ContactLaw
        A single registered contact law.
    impactor_mass : float
        m > 0 [kg].
    velocity : float
        V0 > 0 [m/s].

    Returns
    -------
    AsymptoteResult
        ``method = "quasi-static"``; with ``F = Kα``, ``F̄max = sqrt(λ/(1+λ))`` (eq 28).
    """
    if isinstance(target, (int, float)):
        stiffness_static = float(target)
        require_positive("target (static stiffness)", stiffness_static, "N/m")
    else:
        stiffness_static = 1.0 / float(target.static_compliance())
    return _two_phase_impact(law, impactor_mass, velocity, "quasi-static",
                             lambda v, force, stiffness: v / (1.0 + stiffness / stiffness_static),
                             lambda force, moved: force / stiffness_static)


def halfspace_asymptote(law: ContactLaw, impactor_mass, velocity) -> AsymptoteResult:
    """Half-space impact (rigid, immovable target) with any law, as an :class:`AsymptoteResult`.

    Parameters
    ----------
    law : ContactLaw
        A single registered contact law.
    impactor_mass : float
        m > 0 [kg].
    velocity : float
        V0 > 0 [m/s].

    Returns
    -------
    AsymptoteResult
        ``method = "half-space"``, from :func:`impactmaps.solvers.halfspace.halfspace_impact`.
    """
    run = halfspace_impact(law, impactor_mass, velocity)
    separated = not run.time_limit_reached
    return AsymptoteResult(
        method="half-space",
        peak_force=float(run.peak_force),
        peak_time=float(run.peak_time),
        contact_time=float(run.end_time) if separated else math.inf,
        restitution=float(run.restitution),
        fmax_normalised=float(run.fmax_normalised),
        impacts=1,
        contact_intervals=((0.0, float(run.end_time) if separated else math.inf),),
        max_indentation=float(run.max_indentation),
        permanent_indentation=float(run.permanent_indentation),
        max_target_displacement=0.0,
        impactor_mass=float(impactor_mass),
        velocity=float(velocity),
        contact_frequency=float(run.contact_frequency),
        time_limit_reached=not separated,
    )


def _two_phase_impact(law, impactor_mass, velocity, method, indentation_rate, displacement):
    """Integrate loading then unloading for a structure with ``α̇ = indentation_rate(v, F, k_t)``.

    ``displacement(force, x − α)`` gives the struck point's displacement [m] (the dashpot
    integrates it: ``x − α``; the spring: ``F/K_st``).
    """
    require_positive("impactor_mass", impactor_mass, "kg")
    require_positive("velocity", velocity, "m/s")
    params = single_law_parameters(law)
    kernel = law.kernel
    mass, speed = float(impactor_mass), float(velocity)
    scale = float(law.indentation_for_energy(0.5 * mass * speed**2))  # α_scale [m]
    time_unit = scale / speed
    acceleration = scale / (mass * speed**2)  # scaled dv/dτ per newton

    evaluations = [0]

    def rates(state, alpha_max):
        evaluations[0] += 1
        if evaluations[0] > MAX_EVALUATIONS:
            raise _OverBudget
        alpha = scale * state[0]
        force, stiffness = kernel(alpha, alpha_max if alpha_max is not None else alpha, params)
        rate = indentation_rate(speed * state[1], force, stiffness) / speed
        return rate, -acceleration * force, state[1]  # dα/dτ, dv/dτ, dx/dτ (scaled)

    def turning(_tau, state):
        return rates(state, None)[0]

    turning.terminal, turning.direction = True, -1.0
    stiff = _relaxation_rate(rates) > STIFF_RATE
    options = {"method": "Radau" if stiff else "DOP853", "rtol": _RELATIVE_TOLERANCE, "atol": _ABSOLUTE_TOLERANCE}
    try:
        loading = solve_ivp(lambda _t, s: rates(s, None), (0.0, _SCALED_TIME_LIMIT), (0.0, 1.0, 0.0),
                            events=turning, **options)
    except _OverBudget:
        raise _over_budget(method) from None
    _raise_on_failure(loading, method)
    if loading.t_events[0].size == 0:
        raise RuntimeError(f"{method} impact: the indentation still grows after "
                           f"{_SCALED_TIME_LIMIT:g} time units (contact law too soft?)")
    tau_peak, peak_state = float(loading.t_events[0][0]), loading.y_events[0][0]
    alpha_max = scale * float(peak_state[0])
    final = float(law.permanent_indentation(alpha_max))

    def separation(_tau, state):
        return state[0] - final / scale

    separation.terminal, separation.direction = True, -1.0
    try:
        unloading = solve_ivp(lambda _t, s: rates(s, alpha_max), (tau_peak, _SCALED_TIME_LIMIT),
                              peak_state, events=separation, **options)
    except _OverBudget:
        raise _over_budget(method) from None
    _raise_on_failure(unloading, method)
    separated = unloading.t_events[0].size > 0
    end_state = unloading.y_events[0][0] if separated else unloading.y[:, -1]
    tau_end = float(unloading.t_events[0][0]) if separated else float(unloading.t[-1])
    # the impactor at rest (|v| < 1e-10 V0) while α decays to rounding: the linear ζ_p ≥ 1
    # plate, where the contact never ends (a "separation" found there is round-off)
    settled = abs(float(end_state[1])) < _REST_SPEED
    separated = separated and not settled
    peak_force = float(kernel(alpha_max, alpha_max, params)[0])
    omega = contact_frequency_of(law, mass, speed)
    contact_time = tau_end * time_unit if separated else math.inf
    moved = scale * (float(end_state[2]) - float(end_state[0]))
    return AsymptoteResult(
        method=method,
        peak_force=peak_force,
        peak_time=tau_peak * time_unit,
        contact_time=contact_time,
        restitution=max(-float(end_state[1]), 0.0) if separated else 0.0,
        fmax_normalised=peak_force / (mass * speed * omega),
        impacts=1,
        contact_intervals=((0.0, contact_time),),
        max_indentation=alpha_max,
        permanent_indentation=final,
        max_target_displacement=max(displacement(peak_force, moved), moved),
        impactor_mass=mass,
        velocity=speed,
        contact_frequency=omega,
        time_limit_reached=not (separated or settled),
    )


def _relaxation_rate(rates) -> float:
    """|∂α̇/∂α| of the scaled equations at the half-space peak indentation, loading (how fast the
    indentation relaxes, in units V0/α_scale; a contact lasts O(1) of them)."""
    step = 1e-6
    state, moved = (1.0, 1.0, 0.0), (1.0 + step, 1.0, 0.0)
    return abs(rates(moved, None)[0] - rates(state, None)[0]) / step


def _over_budget(method: str) -> ValueError:
    return ValueError(f"the {method} asymptote needs more than {MAX_EVALUATIONS} evaluations of its "
                      "equations: the contact lasts far longer than the contact scale of the law (a "
                      "structure far softer than the contact); it is refused rather than left running")


def _raise_on_failure(solution, method):
    if solution.status == -1:
        raise RuntimeError(f"{method} impact integration failed: {solution.message}")
