"""Closed-form asymptotes of sphere impact with linear contact (seed 001 §4, spec 3.5).

Half-space, quasi-static and infinite-plate force, peak, peak time and contact time in the
normalised variables ``τ = ωt``, ``F̄ = F/(m_i V0 ω)``; the infinite beam is re-exported
from :mod:`impactmaps.closed_forms.infinite_beam`. Inputs are validated (``ValueError``).
"""

from __future__ import annotations

import math

import numpy as np

from .._checks import require_nonnegative, require_positive
from .infinite_beam import (
    INFINITE_BEAM_METHODS,
    InfiniteBeamImpact,
    scalar_or_array,
    critical_beam_loss_factor,
    infinite_beam_contact_time,
    infinite_beam_force,
    infinite_beam_impact,
    infinite_beam_impactor_velocity,
    infinite_beam_indentation,
    infinite_beam_indentation_rate,
    infinite_beam_peak,
    infinite_beam_peak_time,
    recontact_beam_loss_factor,
)

__all__ = [
    "halfspace_force",
    "halfspace_peak",
    "halfspace_contact_time",
    "quasi_static_force",
    "quasi_static_peak",
    "quasi_static_contact_time",
    "infinite_plate_indentation",
    "infinite_plate_indentation_rate",
    "infinite_plate_force",
    "infinite_plate_peak",
    "infinite_plate_peak_time",
    "infinite_plate_contact_time",
    # infinite beam (re-exported)
    "INFINITE_BEAM_METHODS",
    "InfiniteBeamImpact",
    "critical_beam_loss_factor",
    "infinite_beam_contact_time",
    "infinite_beam_force",
    "infinite_beam_impact",
    "infinite_beam_impactor_velocity",
    "infinite_beam_indentation",
    "infinite_beam_indentation_rate",
    "infinite_beam_peak",
    "infinite_beam_peak_time",
    "recontact_beam_loss_factor",
]


# --------------------------------------------------------------------------- half-space


def halfspace_force(tau):
    """Normalised force on a rigid half-space, F̄ = sin τ on [0, π], 0 after [-], at τ ≥ 0 [-] (eq 27)."""
    require_nonnegative("tau", tau)
    tau = np.asarray(tau, dtype=float)
    return scalar_or_array(np.where(tau <= math.pi, np.sin(np.minimum(tau, math.pi)), 0.0))


def halfspace_peak() -> float:
    """Peak normalised force on a half-space, F̄max = 1 [-]."""
    return 1.0


def halfspace_contact_time() -> float:
    """Normalised contact duration on a half-space, τ_c = π [-]."""
    return math.pi


# --------------------------------------------------------------------------- quasi-static


def _quasi_static_frequency(relative_stiffness):
    require_positive("relative_stiffness", relative_stiffness)
    lam = np.asarray(relative_stiffness, dtype=float)
    return np.sqrt(lam / (1.0 + lam))


def quasi_static_force(tau, relative_stiffness):
    """Normalised quasi-static force ``Ω sin(Ω τ)``, ``Ω = sqrt(λ/(1+λ))`` [-] (eq 28), zero after π/Ω.

    ``tau`` τ ≥ 0 [-]; ``relative_stiffness`` λ = K_st/K > 0 [-], broadcast against ``tau``.
    """
    require_nonnegative("tau", tau)
    frequency = _quasi_static_frequency(relative_stiffness)
    phase = np.asarray(tau, dtype=float) * frequency
    force = frequency * np.sin(np.minimum(phase, math.pi))
    return scalar_or_array(np.where(phase <= math.pi, force, 0.0))


def quasi_static_peak(relative_stiffness):
    """Quasi-static peak force F̄max = sqrt(λ/(1+λ)) [-] for λ = K_st/K > 0 [-]."""
    return scalar_or_array(_quasi_static_frequency(relative_stiffness))


def quasi_static_contact_time(relative_stiffness):
    """Quasi-static contact duration τ_c = π sqrt((1+λ)/λ) [-] for λ = K_st/K > 0 [-]."""
    return scalar_or_array(math.pi / _quasi_static_frequency(relative_stiffness))


# --------------------------------------------------------------------------- infinite plate


def _plate_inputs(tau, loss_factor):
    require_nonnegative("tau", tau)
    require_positive("loss_factor", loss_factor)
    return np.broadcast_arrays(np.asarray(tau, dtype=float), np.asarray(loss_factor, dtype=float))


def _plate_solution(tau, zeta):
    """ᾱ and ᾱ' of ᾱ'' + 2ζᾱ' + ᾱ = 0, ᾱ(0) = 0, ᾱ'(0) = 1, each branch in a stable form
    (continuous across ζ = 1 to rounding)."""
    value = np.empty(tau.shape)
    rate = np.empty(tau.shape)
    under, over = zeta < 1.0, zeta > 1.0
    critical = ~(under | over)
    t, z = tau[under], zeta[under]
    omega = np.sqrt((1.0 - z) * (1.0 + z))
    decay = np.exp(-z * t)
    value[under] = decay * np.sin(omega * t) / omega
    rate[under] = decay * (np.cos(omega * t) - z * np.sin(omega * t) / omega)
    t = tau[critical]
    value[critical] = t * np.exp(-t)
    rate[critical] = (1.0 - t) * np.exp(-t)
    t, z = tau[over], zeta[over]
    kappa = np.sqrt(z - 1.0) * np.sqrt(z + 1.0)
    slow = 1.0 / (z + kappa)  # = ζ − κ, the slow decay rate
    growth = -np.expm1(-2.0 * kappa * t) / (2.0 * kappa)  # (1 − e^{−2κτ})/(2κ)
    value[over] = np.exp(-slow * t) * growth
    # d/dτ: −(ζ−κ) e^{−(ζ−κ)τ} g + e^{−(ζ−κ)τ} e^{−2κτ}
    rate[over] = np.exp(-slow * t) * (np.exp(-2.0 * kappa * t) - slow * growth)
    return value, rate


def infinite_plate_indentation(tau, loss_factor):
    """Normalised indentation ᾱ(τ) = α ω/V0 [-] of ``ᾱ'' + 2ζᾱ' + ᾱ = 0`` (eqs 32–34).

    ``tau`` τ ≥ 0 [-]; ``loss_factor`` ζ_p > 0 [-], broadcast against ``tau``. The linear
    solution (negative after the first contact for ζ < 1).
    """
    return scalar_or_array(_plate_solution(*_plate_inputs(tau, loss_factor))[0])


def infinite_plate_indentation_rate(tau, loss_factor):
    """Normalised indentation rate ᾱ'(τ) = α̇/V0 [-] of the infinite plate (τ ≥ 0, ζ_p > 0)."""
    return scalar_or_array(_plate_solution(*_plate_inputs(tau, loss_factor))[1])


def infinite_plate_force(tau, loss_factor):
    """Normalised contact force F̄ = F/(m_i V0 ω) [-] on an infinite plate at τ ≥ 0, ζ_p > 0.

    ``F̄ = ᾱ`` up to the first zero of ᾱ (ζ < 1 only), zero after; no re-impact.
    """
    tau, zeta = _plate_inputs(tau, loss_factor)
    value = _plate_solution(tau, zeta)[0]
    contact = _plate_contact_time(zeta)
    return scalar_or_array(np.where(tau < contact, np.maximum(value, 0.0), 0.0))


def _plate_contact_time(zeta):
    under = zeta < 1.0
    bounded = np.minimum(zeta, 1.0)
    damped_frequency = np.sqrt(np.where(under, (1.0 - bounded) * (1.0 + bounded), 1.0))
    return np.where(under, math.pi / damped_frequency, math.inf)


def _plate_peak_time(zeta):
    """τ_max: θ/sin θ (θ = arccos ζ) for ζ < 1, 1 at ζ = 1, η/sinh η (η = arccosh ζ) for ζ > 1."""
    zeta = np.asarray(zeta, dtype=float)
    theta = np.arccos(np.minimum(zeta, 1.0))
    eta = np.arccosh(np.maximum(zeta, 1.0))
    with np.errstate(over="ignore"):  # sinh(η) → inf only where η/sinh η → 0 correctly
        hyperbolic = np.where(eta > 0, eta / np.where(eta > 0, np.sinh(eta), 1.0), 1.0)
    return np.where(zeta < 1.0, 1.0 / np.sinc(theta / math.pi), hyperbolic)


def infinite_plate_peak(loss_factor):
    """Peak normalised force F̄max = exp(−ζ τ_max) [-] on an infinite plate, for ζ_p > 0 [-]."""
    require_positive("loss_factor", loss_factor)
    zeta = np.asarray(loss_factor, dtype=float)
    return scalar_or_array(np.exp(-zeta * _plate_peak_time(zeta)))


def infinite_plate_peak_time(loss_factor):
    """Normalised peak time τ_max = ω t_max [-] on an infinite plate, for ζ_p > 0 [-]."""
    require_positive("loss_factor", loss_factor)
    return scalar_or_array(_plate_peak_time(loss_factor))


def infinite_plate_contact_time(loss_factor):
    """Normalised contact duration on an infinite plate [-]: π/sqrt(1−ζ²) for ζ < 1, ``inf`` for ζ ≥ 1."""
    require_positive("loss_factor", loss_factor)
    return scalar_or_array(_plate_contact_time(np.asarray(loss_factor, dtype=float)))
