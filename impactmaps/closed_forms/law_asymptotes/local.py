"""Asymptotes whose structure acts at the impact point alone: dashpot, spring, rigid.

Infinite plate (``ẇ = F/Z``, ``Z = 8 sqrt(ρh D*)``), quasi-static spring (``w = F/K_st``)
and half-space, for any contact law: a loading and an unloading phase, DOP853
(rtol 1e-12), or Radau where the equations are stiff (a dashpot far softer than the contact:
a plate a few micrometres thick); every integration has a budget of :data:`MAX_EVALUATIONS`
evaluations, beyond which it is refused (``ValueError``). Why two phases suffice:
docs/physics.rst (Closed forms).
"""

from __future__ import annotations

import math

from scipy.integrate import solve_ivp

from ..._checks import require_positive
from ...contact.base import ContactLaw
from ..halfspace import single_law_parameters, halfspace_impact
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
    """Point impedance ``Z = 8 sqrt(ρh D*)`` [N s/m] of the infinite ``plate`` (seed 001 eq 30)."""
    return 8.0 * math.sqrt(float(plate.mass_per_area) * float(plate.effective_bending_stiffness))


def infinite_plate_impact(plate, law: ContactLaw, impactor_mass, velocity) -> AsymptoteResult:
    """Impact on an infinite plate (a dashpot of impedance ``8 sqrt(ρh D*)``), any law.

    ``plate`` gives ρh [kg/m²] and D* [N m] (size, edges and theory ignored); ``law`` a
    single registered contact law; ``impactor_mass`` m > 0 [kg]; ``velocity`` V0 > 0 [m/s].
    Returns an :class:`AsymptoteResult` (``method = "infinite-plate"``).
    """
    impedance = plate_impedance(plate)
    return _two_phase_impact(law, impactor_mass, velocity, "infinite-plate",
                             lambda v, force, stiffness: v - force / impedance,
                             lambda force, moved: moved)


def quasi_static_impact(target, law: ContactLaw, impactor_mass, velocity) -> AsymptoteResult:
    """Heavy-impactor asymptote: the static point stiffness in series with any law.

    ``target`` is a target (its ``static_compliance()`` [m/N]) or K_st > 0 [N/m]; ``law``,
    ``impactor_mass`` [kg] and ``velocity`` [m/s] as :func:`infinite_plate_impact`.
    Returns an :class:`AsymptoteResult` (``method = "quasi-static"``).
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
    """Half-space impact with any single ``law`` (``impactor_mass`` m > 0 [kg], ``velocity``
    V0 > 0 [m/s]) as an :class:`AsymptoteResult` (``method = "half-space"``)."""
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
    """Integrate loading then unloading for a structure with ``α̇ = indentation_rate(v, F, k_t)``;
    ``displacement(force, x − α)`` gives the struck point's displacement [m]."""
    require_positive("impactor_mass", impactor_mass, "kg")
    require_positive("velocity", velocity, "m/s")
    params = single_law_parameters(law)
    kernel = law.python_kernel  # called from Python: compiled code would gain nothing
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
