"""A rigid sphere on a fixed half-space (compact-body impact), and its closed forms.

:func:`halfspace_impact` integrates ``m α'' = −F(α; α_max)`` for any registered law
(DOP853, rtol 1e-12, compression then restitution); Hertz closed forms and the
Yigit–Christoforou restitution e(β). Derivations: docs/physics.rst (Closed forms).
"""

from __future__ import annotations

import warnings

import numpy as np
from scipy.special import beta as beta_function

from .._checks import require_positive
from ..contact.base import ContactLaw, evaluate_kernel
from ..contact.contact_scale import reference_contact_stiffness
from ..result import ImpactResult, energy_balance_error

__all__ = [
    "HERTZ_CONTACT_TIME_FACTOR",
    "energy_balance_restitution",
    "halfspace_impact",
    "single_law_parameters",
    "hertz_contact_time",
    "hertz_max_indentation",
    "hertz_peak_force",
    "restitution",
]

#: ``t_c V0 / α_m`` for Hertz impact: ``2 ∫0^1 dx/sqrt(1 − x^{5/2}) = (4/5) B(2/5, 1/2)``
#: = 2.9432751843… (Johnson 1985 §11.4 and Goldsmith 1960 quote 2.94; the value 2.9437
#: sometimes quoted is off in the 4th digit).
HERTZ_CONTACT_TIME_FACTOR = float(0.8 * beta_function(0.4, 0.5))

_RELATIVE_TOLERANCE = 1e-12
_ABSOLUTE_TOLERANCE = 1e-13  # on the scaled state (indentation/α_scale, velocity/V0) ~ O(1)
_DEFAULT_SCALED_TIME_LIMIT = 1e4  # in units α_scale/V0; a contact lasts O(1) of them
_HISTORY_SAMPLES = 1000


# -- closed forms ----------------------------------------------------------------------
def hertz_max_indentation(mass, velocity, hertz_stiffness):
    """Maximum Hertz indentation ``α_m = (5 m V0² / (4 K_h))^{2/5}`` [m] (``mass`` [kg], ``velocity`` [m/s],
    ``hertz_stiffness`` [N/m^1.5])."""
    require_positive("mass", mass, "kg")
    require_positive("velocity", velocity, "m/s")
    require_positive("hertz_stiffness", hertz_stiffness, "N/m^1.5")
    m, v, k = (np.asarray(x, float) for x in (mass, velocity, hertz_stiffness))
    return (1.25 * m * v**2 / k) ** 0.4


def hertz_peak_force(mass, velocity, hertz_stiffness):
    """Peak Hertz force ``K_h α_m^{3/2}`` [N] (arguments as :func:`hertz_max_indentation`)."""
    alpha_max = hertz_max_indentation(mass, velocity, hertz_stiffness)
    return np.asarray(hertz_stiffness, float) * alpha_max**1.5


def hertz_contact_time(mass, velocity, hertz_stiffness):
    """Hertz contact duration ``t_c = 2.943275… α_m / V0`` [s] (arguments as :func:`hertz_max_indentation`)."""
    alpha_max = hertz_max_indentation(mass, velocity, hertz_stiffness)
    return HERTZ_CONTACT_TIME_FACTOR * alpha_max / np.asarray(velocity, float)


def restitution(beta):
    """Coefficient of restitution e(β) [-] of the Yigit–Christoforou law, closed form.

    Parameters
    ----------
    beta : float or array_like
        Normalised impact velocity ``β = V0/(ω α_y)`` > 0 [-] (seed 001 eq 11).

    Returns
    -------
    ndarray
        e (1 for β² ≤ 4/5), same shape as ``beta``; finite for every finite β.
    """
    require_positive("beta", beta)
    b = np.asarray(beta, dtype=float)
    with np.errstate(over="ignore", invalid="ignore"):
        energy = 0.5 * b * b  # inf beyond β ≈ 1.3e154: only the elastic test and the small-β root use it
        excess_energy = np.clip(energy - 0.4, 0.0, None)
        # root of ¾x² + x − excess = 0, written without cancellation ...
        excess = 2.0 * excess_energy / (1.0 + np.sqrt(1.0 + 3.0 * excess_energy))
    # ... and, where ½β² would overflow or round 0.4 away, from sqrt(1 + 3E) = sqrt(1.5) β exactly
    excess = np.where(b > 1e8, np.sqrt(2.0 / 3.0) * b - 2.0 / 3.0, excess)
    peak = 1.0 + excess
    # a_f^{3/2} = a_m^{3/2} (1 − u); the recovered work is W_r = a_m^{5/2} S(u) with
    # S(u) = (2/5)(1 − (1−u)^{5/3}) − (1−u)(1 − (1−u)^{2/3}) = u²/3 + u³/27 + u⁴/81 + …
    u = 1.5 * peak**-0.5 - 0.5 * peak**-1.5
    with np.errstate(divide="ignore"):  # u = 1 at the elastic limit: log(0) = −inf, expm1 → −1
        log_rest = np.log1p(-u)
    direct = -0.4 * np.expm1(5.0 / 3.0 * log_rest) + (1.0 - u) * np.expm1(2.0 / 3.0 * log_rest)
    series = u**2 * (1 / 3 + u * (1 / 27 + u * (1 / 81 + u * (7 / 1215 + u * 7 / 2187))))
    shape = np.where(u < 1e-3, series, direct)  # the direct form cancels to eps/u below 1e-3
    # e = sqrt(W_r / (½β²)) = sqrt(S) a_m^{5/4} sqrt(2)/β, in logarithms (no overflow)
    with np.errstate(divide="ignore"):
        e = np.exp(0.5 * (np.log(np.clip(shape, 0.0, None)) + 2.5 * np.log(peak) + np.log(2.0)) - np.log(b))
    return np.where(energy <= 0.4, 1.0, e)


def energy_balance_restitution(law: ContactLaw, impactor_mass, velocity):
    """Restitution [-] of a half-space impact from a single ``law``'s energies (no time stepping),
    for ``impactor_mass`` m [kg] at ``velocity`` V0 [m/s]."""
    require_positive("impactor_mass", impactor_mass, "kg")
    require_positive("velocity", velocity, "m/s")
    single_law_parameters(law)
    energy = 0.5 * float(impactor_mass) * float(velocity) ** 2
    alpha_max = float(law.indentation_for_energy(energy))
    return float(np.sqrt(float(law.recovered_energy(alpha_max)) / energy))


# -- time integration --------------------------------------------------------------------
def single_law_parameters(law: ContactLaw) -> np.ndarray:
    """The kernel parameters of one (non-batched) contact law, as a flat float array.

    Raises
    ------
    ValueError
        ``law`` is not a ContactLaw, or a batch of laws.
    """
    if not isinstance(law, ContactLaw):
        raise ValueError(f"law = {law!r} is not a ContactLaw")
    params = np.asarray(law.kernel_parameters, dtype=float)
    if params.ndim > 1 and params[0].size != 1:
        raise ValueError(
            f"law has parameter batch shape {params.shape[1:]}: the half-space solver takes one "
            "law at a time (valid batch size is 1)"
        )
    return np.ascontiguousarray(params.reshape(params.shape[0]))


def _indentation_scale(law: ContactLaw, energy: float) -> float:
    """Indentation [m] at which the loading work reaches ``energy`` (±4 %)."""
    params = single_law_parameters(law)
    alpha = np.geomspace(1e-18, 1e3, 1300)
    force = evaluate_kernel(law.kernel, params, alpha, alpha)[0]
    work = np.concatenate(([0.0], np.cumsum(0.5 * (force[1:] + force[:-1]) * np.diff(alpha))))
    index = int(np.searchsorted(work, energy))
    if index >= alpha.size:
        raise ValueError(
            f"impact energy = {energy!r} J is not absorbed within 1000 m of indentation by this law "
            "(check the units of the law's parameters)"
        )
    return float(alpha[max(index, 1)])


def halfspace_impact(law: ContactLaw, impactor_mass, velocity, *, time_step=None, max_time=None):
    """Impact of a rigid sphere on a fixed half-space with any contact law.

    Parameters
    ----------
    law : ContactLaw
        A single (non-batched) registered contact law.
    impactor_mass : float
        Impactor mass m > 0 [kg].
    velocity : float
        Impact velocity V0 > 0 [m/s].
    time_step : float, optional
        Sampling interval of ``history`` [s] (default: contact time / 1000).
    max_time : float, optional
        Time limit of the integration [s] (default 10⁴ α_m/V0, α_m ≈ the peak
        indentation); reaching it warns.

    Returns
    -------
    ImpactResult
        ``method = "half-space"``: one contact, no structure energy, ``n_modes = 0``.

    Warns
    -----
    ModelValidityWarning
        :func:`impactmaps.contact.range_checks.law_warnings`: an indentation beyond 0.1 R, or beyond
        the ``epp`` law's calibration (the checks the ``halfspace`` command prints too).
    """
    require_positive("impactor_mass", impactor_mass, "kg")
    require_positive("velocity", velocity, "m/s")
    if time_step is not None:
        require_positive("time_step", time_step, "s")
    if max_time is not None:
        require_positive("max_time", max_time, "s")
    params = single_law_parameters(law)
    kernel = law.kernel
    mass = float(impactor_mass)
    speed = float(velocity)
    energy = 0.5 * mass * speed**2

    scale = _indentation_scale(law, energy)
    time_unit = scale / speed
    force_factor = scale / (mass * speed**2)  # scaled acceleration per newton
    time_limit = _DEFAULT_SCALED_TIME_LIMIT if max_time is None else float(max_time) / time_unit

    def compression(_tau, state):
        alpha = scale * state[0]
        force = kernel(alpha, alpha, params)[0]
        return (state[1], -force_factor * force)

    def turning_point(_tau, state):
        return state[1]

    turning_point.terminal = True
    turning_point.direction = -1.0

    from scipy.integrate import solve_ivp  # the integrators: imported where an impact is integrated

    options = dict(method="DOP853", rtol=_RELATIVE_TOLERANCE, atol=_ABSOLUTE_TOLERANCE, dense_output=True)
    first = solve_ivp(compression, (0.0, time_limit), (0.0, 1.0), events=turning_point, **options)
    _raise_on_failure(first)
    turned = first.t_events[0].size > 0
    if turned:
        tau_max, (x_max, _u) = first.t_events[0][0], first.y_events[0][0]
    else:
        tau_max, x_max = first.t[-1], first.y[0, -1]
    alpha_max = scale * float(x_max)
    final = float(law.permanent_indentation(alpha_max))

    second, separated, tau_end, rebound = None, False, tau_max, np.nan
    if turned and tau_max < time_limit:
        second, separated, tau_end, rebound = _restitution(
            kernel, params, scale, force_factor, alpha_max, final, float(x_max), tau_max, time_limit,
            speed, options)
    if not separated:
        warnings.warn(
            f"half-space impact did not end within max_time = {time_limit * time_unit!r} s: "
            "restitution and rebound velocity are NaN",
            RuntimeWarning,
            stacklevel=2,
        )

    contact_time = tau_end * time_unit
    time_of_max = tau_max * time_unit
    history = _sample_history(
        first, second, kernel, params, scale, speed, time_unit, tau_max, tau_end, alpha_max,
        time_step if time_step is not None else contact_time / _HISTORY_SAMPLES,
    )
    peak_force = max(float(kernel(alpha_max, alpha_max, params)[0]), float(history["force_N"].max()))
    dissipation = float(law.dissipated_energy(alpha_max))
    result = ImpactResult(
        history=history,
        peak_force=peak_force,
        peak_time=time_of_max,
        contact_intervals=np.array([[0.0, contact_time]]),
        max_indentation=alpha_max,
        permanent_indentation=final,
        rebound_velocity=rebound,
        energy_transferred=0.0,
        contact_dissipation=dissipation,
        damping_work=0.0,
        energy_balance_error=energy_balance_error(mass, speed, rebound, dissipation),
        impactor_mass=mass,
        velocity=speed,
        contact_frequency=float(np.sqrt(reference_contact_stiffness(law, mass, speed) / mass)),
        end_time=contact_time,
        time_limit_reached=not separated,
        time_step=float(time_step if time_step is not None else contact_time / _HISTORY_SAMPLES),
        method="half-space",
    )
    from .._checks import ModelValidityWarning
    from ..contact.range_checks import law_warnings

    for message in law_warnings(law, result):
        warnings.warn(message, ModelValidityWarning, stacklevel=2)
    return result


def _restitution(kernel, params, scale, force_factor, alpha_max, final, x_max, tau_max, time_limit,
                 speed, options):
    """The unloading phase from the turning point in scaled variables:
    (solution, separated, scaled end time, rebound velocity [m/s] or NaN)."""

    def restitution_phase(_tau, state):
        force = kernel(scale * state[0], alpha_max, params)[0]
        return (state[1], -force_factor * force)

    def separation(_tau, state):
        return state[0] - final / scale

    separation.terminal = True
    separation.direction = -1.0
    from scipy.integrate import solve_ivp

    second = solve_ivp(restitution_phase, (tau_max, time_limit), (x_max, 0.0), events=separation, **options)
    _raise_on_failure(second)
    if second.t_events[0].size > 0:
        return second, True, float(second.t_events[0][0]), -float(second.y_events[0][0][1]) * speed
    return second, False, float(second.t[-1]), np.nan


def _raise_on_failure(solution):
    if solution.status == -1:
        raise RuntimeError(f"half-space impact integration failed: {solution.message}")


def _sample_history(first, second, kernel, params, scale, speed, time_unit, tau_max, tau_end,
                    alpha_max, time_step):
    step = float(time_step) / time_unit
    tau = np.unique(np.concatenate((np.arange(0.0, tau_end, step), [tau_max, tau_end])))
    loading = tau <= tau_max
    state = np.empty((2, tau.size))
    state[:, loading] = first.sol(tau[loading])
    if second is not None and np.any(~loading):
        state[:, ~loading] = second.sol(tau[~loading])
    alpha = scale * state[0]
    history_max = np.where(loading, alpha, alpha_max)
    force = evaluate_kernel(kernel, params, alpha, history_max)[0]
    import pandas as pd

    return pd.DataFrame({
        "time_s": tau * time_unit,
        "force_N": force,
        "indentation_m": alpha,
        "impactor_displacement_m": alpha,
        "impactor_velocity_m_s": state[1] * speed,
        "target_displacement_m": np.zeros_like(alpha),
        "target_velocity_m_s": np.zeros_like(alpha),
    })
