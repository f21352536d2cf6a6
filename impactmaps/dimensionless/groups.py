"""The dimensionless groups of seed 001 and the formulas between them and SI quantities.

The framework, conventions and the beam loss-factor correction: see
:mod:`impactmaps.dimensionless`.
"""

from __future__ import annotations

import math

import numpy as np

from .._checks import require_finite, require_positive

__all__ = [
    "contact_frequency",
    "halfspace_indentation",
    "force_scale",
    "normalised_force",
    "hertz_frequency",
    "impact_number",
    "velocity_for_impact_number",
    "relative_stiffness",
    "contact_stiffness_for_relative_stiffness",
    "effective_plate_stiffness",
    "loss_factor_plate",
    "impactor_mass_for_plate",
    "loss_factor_beam",
    "loss_factor_beam_paper",
    "zeta_beam_paper",
    "impactor_mass_for_beam",
    "BEAM_LOSS_CONSTANT",
]

#: ``4 sqrt(2π)``, the constant of the (corrected) beam loss factor.
BEAM_LOSS_CONSTANT = 4.0 * math.sqrt(2.0 * math.pi)


def _array(value) -> np.ndarray:
    return np.asarray(value, dtype=float)


# ---------------------------------------------------------------------------------
# Scales of the linear contact problem
# ---------------------------------------------------------------------------------
def contact_frequency(contact_stiffness, impactor_mass):
    """Linear contact frequency ``ω = sqrt(K/m_i)`` [rad/s] of ``contact_stiffness`` K [N/m]
    and ``impactor_mass`` m_i [kg]."""
    require_positive("contact_stiffness", contact_stiffness, "N/m")
    require_positive("impactor_mass", impactor_mass, "kg")
    return np.sqrt(_array(contact_stiffness) / _array(impactor_mass))


def halfspace_indentation(velocity, contact_frequency):
    """Half-space indentation ``α* = V0/ω`` [m] of ``velocity`` V0 [m/s] and ``contact_frequency`` ω [rad/s]."""
    require_positive("velocity", velocity, "m/s")
    require_positive("contact_frequency", contact_frequency, "rad/s")
    return _array(velocity) / _array(contact_frequency)


def force_scale(impactor_mass, velocity, contact_frequency):
    """Force scale ``m_i V0 ω`` [N], the half-space peak force (m_i [kg], V0 [m/s], ω [rad/s])."""
    require_positive("impactor_mass", impactor_mass, "kg")
    require_positive("velocity", velocity, "m/s")
    require_positive("contact_frequency", contact_frequency, "rad/s")
    return _array(impactor_mass) * _array(velocity) * _array(contact_frequency)


def normalised_force(force, impactor_mass, velocity, contact_frequency):
    """Normalised contact force ``F̄ = F/(m_i V0 ω)`` [-] of ``force`` F [N] (others as :func:`force_scale`)."""
    require_finite("force", force, "N")
    return _array(force) / force_scale(impactor_mass, velocity, contact_frequency)


# ---------------------------------------------------------------------------------
# Impact number (non-linear contact, compact bodies)
# ---------------------------------------------------------------------------------
def hertz_frequency(hertz_stiffness, yield_indentation, impactor_mass):
    """Hertz contact frequency ``ω_h = sqrt(K_h α_y^{1/2}/m_i)`` [rad/s] (K_h [N/m^{3/2}], α_y [m], m_i [kg])."""
    require_positive("hertz_stiffness", hertz_stiffness, "N/m^1.5")
    require_positive("yield_indentation", yield_indentation, "m")
    require_positive("impactor_mass", impactor_mass, "kg")
    return np.sqrt(_array(hertz_stiffness) * np.sqrt(_array(yield_indentation))
                   / _array(impactor_mass))


def impact_number(velocity, hertz_stiffness, yield_indentation, impactor_mass):
    """Impact number ``β = V0/(ω_h α_y)`` [-] of ``velocity`` V0 [m/s] (others as :func:`hertz_frequency`)."""
    require_positive("velocity", velocity, "m/s")
    omega_h = hertz_frequency(hertz_stiffness, yield_indentation, impactor_mass)
    return _array(velocity) / (omega_h * _array(yield_indentation))


def velocity_for_impact_number(impact_number, hertz_stiffness, yield_indentation,
                               impactor_mass):
    """Impact velocity V0 = β ω_h α_y [m/s] giving the impact number β (inverse of :func:`impact_number`)."""
    require_positive("impact_number", impact_number)
    omega_h = hertz_frequency(hertz_stiffness, yield_indentation, impactor_mass)
    return _array(impact_number) * omega_h * _array(yield_indentation)


# ---------------------------------------------------------------------------------
# Relative stiffness
# ---------------------------------------------------------------------------------
def relative_stiffness(static_stiffness, contact_stiffness):
    """Relative stiffness ``λ = K_st/K`` [-] of ``static_stiffness`` K_st and ``contact_stiffness`` K [N/m]."""
    require_positive("static_stiffness", static_stiffness, "N/m")
    require_positive("contact_stiffness", contact_stiffness, "N/m")
    return _array(static_stiffness) / _array(contact_stiffness)


def contact_stiffness_for_relative_stiffness(static_stiffness, relative_stiffness):
    """Contact stiffness ``K = K_st/λ`` [N/m] (inverse of :func:`relative_stiffness`)."""
    require_positive("static_stiffness", static_stiffness, "N/m")
    require_positive("relative_stiffness", relative_stiffness)
    return _array(static_stiffness) / _array(relative_stiffness)


# ---------------------------------------------------------------------------------
# Loss factors
# ---------------------------------------------------------------------------------
def effective_plate_stiffness(D11, D22, D12, D66):  # noqa: N803 (CLT symbols)
    """Effective plate stiffness ``D* = ½(D12 + 2 D66 + sqrt(D11 D22))`` [N·m] of the
    stiffnesses [N·m]; ``ValueError`` unless D* > 0."""
    require_positive("D11", D11, "N m")
    require_positive("D22", D22, "N m")
    require_finite("D12", D12, "N m")
    require_positive("D66", D66, "N m")
    result = 0.5 * (_array(D12) + 2.0 * _array(D66) + np.sqrt(_array(D11) * _array(D22)))
    if np.any(result <= 0):
        raise ValueError(f"D* = {result!r} is not positive: D12 = {D12!r} is too negative "
                         "for the given D11, D22, D66")
    return result


def loss_factor_plate(impactor_mass, contact_stiffness, mass_per_area,
                      effective_bending_stiffness):
    """Plate loss factor ``ζ_p = (1/16) sqrt(m_i K/(ρh D*))`` [-] (seed 001 eq 34).

    ``impactor_mass`` m_i [kg], ``contact_stiffness`` K [N/m], ``mass_per_area`` ρh [kg/m²],
    ``effective_bending_stiffness`` D* [N·m], all > 0.
    """
    require_positive("impactor_mass", impactor_mass, "kg")
    require_positive("contact_stiffness", contact_stiffness, "N/m")
    require_positive("mass_per_area", mass_per_area, "kg/m^2")
    require_positive("effective_bending_stiffness", effective_bending_stiffness, "N m")
    return np.sqrt(_array(impactor_mass) * _array(contact_stiffness)
                   / (_array(mass_per_area) * _array(effective_bending_stiffness))) / 16.0


def impactor_mass_for_plate(loss_factor, contact_stiffness, mass_per_area,
                            effective_bending_stiffness):
    """Impactor mass ``m_i = 256 ζ² ρh D*/K`` [kg] for plate ``loss_factor`` ζ_p [-] (others as
    :func:`loss_factor_plate`)."""
    require_positive("loss_factor", loss_factor)
    require_positive("contact_stiffness", contact_stiffness, "N/m")
    require_positive("mass_per_area", mass_per_area, "kg/m^2")
    require_positive("effective_bending_stiffness", effective_bending_stiffness, "N m")
    return (256.0 * _array(loss_factor) ** 2 * _array(mass_per_area)
            * _array(effective_bending_stiffness) / _array(contact_stiffness))


def loss_factor_beam(impactor_mass, contact_stiffness, mass_per_length, bending_stiffness):
    """Corrected beam loss factor ``ζ_b = (1/(4 sqrt(2π))) (m_i/m')^{3/4} (K/(b D11))^{1/4}`` [-].

    ``impactor_mass`` m_i [kg], ``contact_stiffness`` K [N/m], ``mass_per_length`` m' [kg/m],
    ``bending_stiffness`` bD11 [N·m²], all > 0. Half of seed 001's printed eq (38)
    (docs/physics.rst).
    """
    require_positive("impactor_mass", impactor_mass, "kg")
    require_positive("contact_stiffness", contact_stiffness, "N/m")
    require_positive("mass_per_length", mass_per_length, "kg/m")
    require_positive("bending_stiffness", bending_stiffness, "N m^2")
    mass_ratio = _array(impactor_mass) / _array(mass_per_length)
    return (mass_ratio ** 0.75
            * (_array(contact_stiffness) / _array(bending_stiffness)) ** 0.25
            / BEAM_LOSS_CONSTANT)


def loss_factor_beam_paper(impactor_mass, contact_stiffness, mass_per_length,
                           bending_stiffness):
    """Beam loss factor as printed in seed 001 eq (38), ``2 ζ_b`` [-] (comparison only; as
    :func:`loss_factor_beam`)."""
    return 2.0 * loss_factor_beam(impactor_mass, contact_stiffness, mass_per_length,
                                  bending_stiffness)


def zeta_beam_paper(loss_factor):
    """The paper's printed beam loss factor ``2 ζ_b`` [-] for a corrected ``loss_factor`` ζ_b > 0."""
    require_positive("loss_factor", loss_factor)
    return 2.0 * _array(loss_factor)


def impactor_mass_for_beam(loss_factor, contact_stiffness, mass_per_length,
                           bending_stiffness):
    """Impactor mass ``m_i = m' (4 sqrt(2π) ζ)^{4/3} (b D11/K)^{1/3}`` [kg] for beam ``loss_factor`` ζ_b [-]."""
    require_positive("loss_factor", loss_factor)
    require_positive("contact_stiffness", contact_stiffness, "N/m")
    require_positive("mass_per_length", mass_per_length, "kg/m")
    require_positive("bending_stiffness", bending_stiffness, "N m^2")
    return (_array(mass_per_length) * (BEAM_LOSS_CONSTANT * _array(loss_factor)) ** (4.0 / 3.0)
            * (_array(bending_stiffness) / _array(contact_stiffness)) ** (1.0 / 3.0))
