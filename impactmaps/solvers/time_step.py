"""The time step of the modal solver: what the contact force carries, and stability.

:func:`coupled_top_frequency` gives ω_top, :func:`content_time_step` the step that
resolves the oscillations the force carries; the rule and its derivation: docs/physics.rst,
"The exact-step integrator".
"""

from __future__ import annotations

import numba
import numpy as np

from ..targets.base import ModalBasis

__all__ = ["STABLE_TOP_STEP", "content_time_step", "coupled_top_frequency"]

#: Largest ω_top·Δt the content rule may use. The exact-step scheme advances each mode
#: exactly, but the contact force is sampled once per step, and the sampled loop is not
#: unconditionally stable: runs blew up at ω_top·Δt ≈ 4 and ≈ 19 (a mode turning almost
#: an integer number of times per step), none at ω_top·Δt ≤ 3.5 over 600 random chart
#: points and forced steps (tests/solvers/test_integrator.py keeps the failing case).
STABLE_TOP_STEP = 2.0


def coupled_top_frequency(
    basis: ModalBasis, contact_stiffness: float, impactor_mass: float, rtol: float = 1e-10
) -> float:
    """Highest natural frequency [rad/s] of impactor + contact spring + retained modes: the
    root of the point-receptance equation above the highest retained mode, to relative
    tolerance ``rtol`` in ω².
    """
    series = 1.0 / contact_stiffness + basis.residual_compliance
    return float(_top_root(basis.frequencies, basis.participation, series, float(impactor_mass),
                           float(rtol)))


def content_time_step(basis: ModalBasis, contact_stiffness: float, impactor_mass: float,
                      tolerance: float) -> float:
    """Longest step [s] that resolves the structural oscillations of the contact force
    (docs/physics.rst): ``basis`` (modes, residual r [m/N]), linear(ised) contact stiffness
    K [N/m], impactor mass m_i [kg], ``tolerance`` in units of m_i V0 ω [-]; ``inf`` when no
    mode lies above 2ω.
    """
    if tolerance <= 0:
        return 0.0
    weight = _content_weight(basis.frequencies, basis.participation, float(contact_stiffness),
                             float(impactor_mass), float(basis.residual_compliance))
    return float(np.sqrt(8.0 * tolerance / weight)) if weight > 0 else np.inf


@numba.njit(cache=True, no_cfunc_wrapper=True)
def _content_weight(frequencies, participation, stiffness, mass, residual):
    """Σ_{ω_j > 2ω} min(Â_j, 1) ω_j² of :func:`content_time_step` [1/s²]."""
    omega = np.sqrt(stiffness / mass)
    series = (1.0 + stiffness * residual) ** 2
    weight = 0.0
    for j in range(frequencies.shape[0]):
        if frequencies[j] > 2.0 * omega:
            ratio = omega / frequencies[j]
            amplitude = mass * participation[j] ** 2 * ratio * ratio * ratio / series
            weight += min(amplitude, 1.0) * frequencies[j] ** 2
    return weight


@numba.njit(cache=True, no_cfunc_wrapper=True)
def _receptance(omega2, frequencies, participation, series, mass):
    total = series - 1.0 / (mass * omega2)
    for j in range(frequencies.shape[0]):
        total += participation[j] ** 2 / (frequencies[j] ** 2 - omega2)
    return total


@numba.njit(cache=True, no_cfunc_wrapper=True)
def _top_root(frequencies, participation, series, mass, rtol):
    if frequencies.shape[0] == 0:
        return np.sqrt(1.0 / (mass * series))
    top = frequencies[0]
    for j in range(1, frequencies.shape[0]):  # a loop, not np.max: numba compiles its reduction for ~0.5 s
        if frequencies[j] > top:
            top = frequencies[j]
    low = top ** 2 * (1.0 + 1e-12) + 1e-300
    high = max(4.0 * low, 1.0)
    while _receptance(high, frequencies, participation, series, mass) < 0.0:
        high *= 4.0
    # bisection in log(ω²); the receptance increases monotonically above the last mode
    for _ in range(200):
        middle = np.sqrt(low * high)
        if _receptance(middle, frequencies, participation, series, mass) < 0.0:
            low = middle
        else:
            high = middle
        if high - low <= rtol * high:
            break
    return np.sqrt(0.5 * (low + high))
