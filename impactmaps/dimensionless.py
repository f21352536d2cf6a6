"""The dimensionless framework of seed 001 (PHYSICS.md §1 and §4).

With a linear contact spring ``F = K α`` the impact of a sphere of mass ``m_i`` at
speed ``V0`` is scaled by the contact frequency ``ω = sqrt(K/m_i)``: time ``τ = ω t``,
indentation ``ᾱ = α/α*`` with the half-space indentation ``α* = V0/ω``, force
``F̄ = F/(m_i V0 ω)`` (seed 001 eq 26). The normalised response of a given structure type
then depends on two numbers only (seed 001 section 4):

* the relative stiffness ``λ = K_st/K`` (eq 29), ``K_st`` the static point stiffness of
  the target at the impact point, which governs the quasi-static limit;
* the loss factor ``ζ`` (eq 34 for plates, the corrected eq 38 for beams), which
  governs the response of the infinite structure (before reflections return).

Given a target, ``(ζ, λ)`` fixes the impactor: :func:`realise`.

All functions accept scalars or arrays (NumPy broadcasting) and validate their inputs
through :mod:`impactmaps._checks`, so bad input raises a ``ValueError`` naming the
parameter.

**Correction (beam loss factor, PHYSICS.md §1).** The driving-point velocity of an
infinite Euler–Bernoulli beam under a force ``F(t)`` is

    ẇ(t) = 1/(2 sqrt(2π) m' c^{1/2}) ∫0^t F(ξ)/sqrt(t − ξ) dξ,   c = sqrt(EI/m'),

(its Laplace transform is the textbook point mobility ``(1 − i)/(4 m' c_B)``,
``c_B = sqrt(ω c)``). Seed 001 eq (35) lacks the factor 1/2, and its eq (38) is twice
the loss factor for which the normalised infinite-beam equation (36),
``ᾱ'' + 2ζ ∫0^τ ᾱ'(s)/sqrt(τ − s) ds + ᾱ = 0``, holds. impactmaps therefore defines
``ζ_b = (1/(4 sqrt(2π))) (m_i/m')^{3/4} (K/(b D11))^{1/4}`` (:func:`loss_factor_beam`)
and offers :func:`loss_factor_beam_paper` ``= 2 ζ_b`` for comparison with the printed
paper. ``tests/test_dimensionless.py`` re-derives both constants from the wave-number
integrals of the infinite beam and plate.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ._checks import require_finite, require_positive

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
    "Realisation",
    "realise",
    "ss_euler_beam_midspan_mass_ratio",
    "ss_euler_beam_midspan_frequency_ratio",
    "ss_euler_beam_midspan_loss_factor",
]

#: ``4 sqrt(2π)``, the constant of the (corrected) beam loss factor.
_BEAM_CONSTANT = 4.0 * math.sqrt(2.0 * math.pi)


def _array(value) -> np.ndarray:
    return np.asarray(value, dtype=float)


# ---------------------------------------------------------------------------------
# Scales of the linear contact problem
# ---------------------------------------------------------------------------------
def contact_frequency(contact_stiffness, impactor_mass):
    """Linear contact frequency ``ω = sqrt(K/m_i)`` [rad/s] (seed 001, after eq 20).

    Parameters
    ----------
    contact_stiffness : float or array_like
        Linear contact stiffness K [N/m], > 0.
    impactor_mass : float or array_like
        Impactor mass m_i [kg], > 0.

    Returns
    -------
    float or ndarray
        ω [rad/s].
    """
    require_positive("contact_stiffness", contact_stiffness, "N/m")
    require_positive("impactor_mass", impactor_mass, "kg")
    return np.sqrt(_array(contact_stiffness) / _array(impactor_mass))


def halfspace_indentation(velocity, contact_frequency):
    """Half-space (maximum) indentation ``α* = V0/ω`` [m], the indentation scale.

    Parameters
    ----------
    velocity : float or array_like
        Impact velocity V0 [m/s], > 0.
    contact_frequency : float or array_like
        ω [rad/s], > 0.
    """
    require_positive("velocity", velocity, "m/s")
    require_positive("contact_frequency", contact_frequency, "rad/s")
    return _array(velocity) / _array(contact_frequency)


def force_scale(impactor_mass, velocity, contact_frequency):
    """Force scale ``m_i V0 ω`` [N], the peak force of a half-space impact (eq 26–27).

    Parameters
    ----------
    impactor_mass : float or array_like
        m_i [kg], > 0.
    velocity : float or array_like
        V0 [m/s], > 0.
    contact_frequency : float or array_like
        ω [rad/s], > 0.
    """
    require_positive("impactor_mass", impactor_mass, "kg")
    require_positive("velocity", velocity, "m/s")
    require_positive("contact_frequency", contact_frequency, "rad/s")
    return _array(impactor_mass) * _array(velocity) * _array(contact_frequency)


def normalised_force(force, impactor_mass, velocity, contact_frequency):
    """Normalised contact force ``F̄ = F/(m_i V0 ω)`` [-] (seed 001 eq 26).

    Parameters
    ----------
    force : float or array_like
        Contact force F [N] (finite).
    impactor_mass, velocity, contact_frequency : float or array_like
        See :func:`force_scale`.
    """
    require_finite("force", force, "N")
    return _array(force) / force_scale(impactor_mass, velocity, contact_frequency)


# ---------------------------------------------------------------------------------
# Impact number (non-linear contact, compact bodies)
# ---------------------------------------------------------------------------------
def hertz_frequency(hertz_stiffness, yield_indentation, impactor_mass):
    """Hertz contact frequency ``ω_h = sqrt(K_h α_y^{1/2}/m_i)`` [rad/s] (seed 001 eq 12).

    Parameters
    ----------
    hertz_stiffness : float or array_like
        K_h [N/m^{3/2}], > 0.
    yield_indentation : float or array_like
        α_y [m], > 0.
    impactor_mass : float or array_like
        m_i [kg], > 0.
    """
    require_positive("hertz_stiffness", hertz_stiffness, "N/m^1.5")
    require_positive("yield_indentation", yield_indentation, "m")
    require_positive("impactor_mass", impactor_mass, "kg")
    return np.sqrt(_array(hertz_stiffness) * np.sqrt(_array(yield_indentation))
                   / _array(impactor_mass))


def impact_number(velocity, hertz_stiffness, yield_indentation, impactor_mass):
    """Characteristic impact number ``β = V0/(ω_h α_y)`` [-] (seed 001 eqs 11–12).

    Parameters
    ----------
    velocity : float or array_like
        V0 [m/s], > 0.
    hertz_stiffness, yield_indentation, impactor_mass : float or array_like
        See :func:`hertz_frequency`.

    Returns
    -------
    float or ndarray
        β; the contact stays elastic (e = 1) for β ≤ sqrt(4/5) (PHYSICS.md §2).
    """
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
    """Relative stiffness ``λ = K_st/K`` [-] (seed 001 eq 29).

    Parameters
    ----------
    static_stiffness : float or array_like
        Static point stiffness K_st of the target at the impact point [N/m], > 0.
    contact_stiffness : float or array_like
        Linear contact stiffness K [N/m], > 0.
    """
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
    """Effective plate stiffness ``D* = ½(D12 + 2 D66 + sqrt(D11 D22))`` [N·m] (seed 001 eq 31).

    Parameters
    ----------
    D11, D22 : float or array_like
        Bending stiffnesses [N·m], > 0.
    D12 : float or array_like
        Bending stiffness [N·m] (finite; may be negative for auxetic layups).
    D66 : float or array_like
        Twisting stiffness [N·m], > 0.

    Returns
    -------
    float or ndarray
        D* [N·m]; equals D for an isotropic plate. Must be > 0 (checked).
    """
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

    From the infinite-plate point mobility ``ẇ = F/(8 sqrt(ρh D*))`` (seed 001 eq 30),
    the indentation obeys ``ᾱ'' + 2ζ_p ᾱ' + ᾱ = 0`` (eq 32).

    Parameters
    ----------
    impactor_mass : float or array_like
        m_i [kg], > 0.
    contact_stiffness : float or array_like
        K [N/m], > 0.
    mass_per_area : float or array_like
        ρh [kg/m²], > 0.
    effective_bending_stiffness : float or array_like
        D* [N·m], > 0 (:func:`effective_plate_stiffness`).
    """
    require_positive("impactor_mass", impactor_mass, "kg")
    require_positive("contact_stiffness", contact_stiffness, "N/m")
    require_positive("mass_per_area", mass_per_area, "kg/m^2")
    require_positive("effective_bending_stiffness", effective_bending_stiffness, "N m")
    return np.sqrt(_array(impactor_mass) * _array(contact_stiffness)
                   / (_array(mass_per_area) * _array(effective_bending_stiffness))) / 16.0


def impactor_mass_for_plate(loss_factor, contact_stiffness, mass_per_area,
                            effective_bending_stiffness):
    """Impactor mass ``m_i = 256 ζ² ρh D*/K`` [kg] giving the plate loss factor ζ (PHYSICS.md §4).

    Parameters
    ----------
    loss_factor : float or array_like
        ζ_p [-], > 0.
    contact_stiffness, mass_per_area, effective_bending_stiffness : float or array_like
        See :func:`loss_factor_plate`.
    """
    require_positive("loss_factor", loss_factor)
    require_positive("contact_stiffness", contact_stiffness, "N/m")
    require_positive("mass_per_area", mass_per_area, "kg/m^2")
    require_positive("effective_bending_stiffness", effective_bending_stiffness, "N m")
    return (256.0 * _array(loss_factor) ** 2 * _array(mass_per_area)
            * _array(effective_bending_stiffness) / _array(contact_stiffness))


def loss_factor_beam(impactor_mass, contact_stiffness, mass_per_length, bending_stiffness):
    """Beam loss factor ``ζ_b = (1/(4 sqrt(2π))) (m_i/m')^{3/4} (K/(b D11))^{1/4}`` [-].

    This is the **corrected** loss factor of PHYSICS.md §1: with it the infinite
    Euler-beam asymptote is exactly ``ᾱ'' + 2ζ_b ∫0^τ ᾱ'(s)/sqrt(τ−s) ds + ᾱ = 0``
    (seed 001 eq 36). Seed 001's printed eq (38) is twice this value
    (:func:`loss_factor_beam_paper`), because its eq (35) for the infinite-beam point
    mobility lacks a factor 1/2: the exact kernel is
    ``ẇ(t) = 1/(2 sqrt(2π) m' c^{1/2}) ∫ F(ξ)/sqrt(t−ξ) dξ``, ``c = sqrt(bD11/m')``,
    whose frequency response is the textbook mobility ``(1 − i)/(4 m' c_B)``.

    Parameters
    ----------
    impactor_mass : float or array_like
        m_i [kg], > 0.
    contact_stiffness : float or array_like
        K [N/m], > 0.
    mass_per_length : float or array_like
        m' = ρbh [kg/m], > 0.
    bending_stiffness : float or array_like
        b D11 (= EI for an isotropic narrow beam) [N·m²], > 0.
    """
    require_positive("impactor_mass", impactor_mass, "kg")
    require_positive("contact_stiffness", contact_stiffness, "N/m")
    require_positive("mass_per_length", mass_per_length, "kg/m")
    require_positive("bending_stiffness", bending_stiffness, "N m^2")
    mass_ratio = _array(impactor_mass) / _array(mass_per_length)
    return (mass_ratio ** 0.75
            * (_array(contact_stiffness) / _array(bending_stiffness)) ** 0.25
            / _BEAM_CONSTANT)


def loss_factor_beam_paper(impactor_mass, contact_stiffness, mass_per_length,
                           bending_stiffness):
    """Beam loss factor as printed in seed 001 eq (38): ``2 ζ_b`` [-].

    Provided only for comparison with the paper; impactmaps uses
    :func:`loss_factor_beam` everywhere (see its docstring for the correction).
    Parameters as :func:`loss_factor_beam`.
    """
    return 2.0 * loss_factor_beam(impactor_mass, contact_stiffness, mass_per_length,
                                  bending_stiffness)


def zeta_beam_paper(loss_factor):
    """The paper's printed beam loss factor (seed 001 eq 38) for a corrected ζ_b: ``2 ζ_b`` [-].

    Parameters
    ----------
    loss_factor : float or array_like
        Corrected beam loss factor ζ_b of :func:`loss_factor_beam` [-], > 0.
    """
    require_positive("loss_factor", loss_factor)
    return 2.0 * _array(loss_factor)


def impactor_mass_for_beam(loss_factor, contact_stiffness, mass_per_length,
                           bending_stiffness):
    """Impactor mass ``m_i = m' (4 sqrt(2π) ζ)^{4/3} (b D11/K)^{1/3}`` [kg] (PHYSICS.md §4).

    Inverse of :func:`loss_factor_beam` (the corrected ζ_b).

    Parameters
    ----------
    loss_factor : float or array_like
        ζ_b [-], > 0.
    contact_stiffness, mass_per_length, bending_stiffness : float or array_like
        See :func:`loss_factor_beam`.
    """
    require_positive("loss_factor", loss_factor)
    require_positive("contact_stiffness", contact_stiffness, "N/m")
    require_positive("mass_per_length", mass_per_length, "kg/m")
    require_positive("bending_stiffness", bending_stiffness, "N m^2")
    return (_array(mass_per_length) * (_BEAM_CONSTANT * _array(loss_factor)) ** (4.0 / 3.0)
            * (_array(bending_stiffness) / _array(contact_stiffness)) ** (1.0 / 3.0))


# ---------------------------------------------------------------------------------
# From (ζ, λ) to an impactor
# ---------------------------------------------------------------------------------
@dataclass(frozen=True)
class Realisation:
    """The impactor and contact that realise a point (ζ, λ) of the map on a target.

    Attributes
    ----------
    impactor_mass : float or ndarray
        m_i [kg].
    contact_stiffness : float or ndarray
        K [N/m].
    contact_frequency : float or ndarray
        ω = sqrt(K/m_i) [rad/s].
    loss_factor : float or ndarray
        ζ [-] (structure type of the target).
    relative_stiffness : float or ndarray
        λ = K_st/K [-].
    """

    impactor_mass: float
    contact_stiffness: float
    contact_frequency: float
    loss_factor: float
    relative_stiffness: float

    def __post_init__(self):
        require_positive("impactor_mass", self.impactor_mass, "kg")
        require_positive("contact_stiffness", self.contact_stiffness, "N/m")
        require_positive("contact_frequency", self.contact_frequency, "rad/s")
        require_positive("loss_factor", self.loss_factor)
        require_positive("relative_stiffness", self.relative_stiffness)

    @property
    def time_scale(self):
        """1/ω [s]: ``t = τ/ω``."""
        return 1.0 / _array(self.contact_frequency)

    def force_scale(self, velocity):
        """m_i V0 ω [N] for impact velocity ``velocity`` [m/s]: ``F = F̄ · m_i V0 ω``."""
        return force_scale(self.impactor_mass, velocity, self.contact_frequency)

    def indentation_scale(self, velocity):
        """α* = V0/ω [m] for impact velocity ``velocity`` [m/s]: ``w = w̄ · α*``."""
        return halfspace_indentation(velocity, self.contact_frequency)


def realise(target, loss_factor, relative_stiffness) -> Realisation:
    """The impactor mass and contact stiffness that give (ζ, λ) on ``target`` (PHYSICS.md §4).

    ``K = K_st/λ`` with ``K_st = target.static_stiffness()``, then
    ``m_i = target.impactor_mass_for(ζ, K)``; the target's own loss-factor formula
    decides whether ζ is a plate or a beam loss factor.

    Parameters
    ----------
    target : impactmaps.targets.Target
        Any target (only ``static_stiffness``, ``impactor_mass_for`` and
        ``loss_factor`` are used).
    loss_factor : float or array_like
        ζ [-], > 0.
    relative_stiffness : float or array_like
        λ [-], > 0. Broadcast against ``loss_factor``.

    Returns
    -------
    Realisation

    Raises
    ------
    RuntimeError
        If ``target.loss_factor(m_i, K)`` does not return ζ (to 1e-9 relative): the
        target's two formulas are not inverse to each other.
    """
    require_positive("loss_factor", loss_factor)
    require_positive("relative_stiffness", relative_stiffness)
    zeta, lam = np.broadcast_arrays(_array(loss_factor), _array(relative_stiffness))
    static_stiffness = float(target.static_stiffness())
    require_positive("static stiffness of the target", static_stiffness, "N/m")
    stiffness = contact_stiffness_for_relative_stiffness(static_stiffness, lam)
    mass = _array(target.impactor_mass_for(zeta, stiffness))
    check = _array(target.loss_factor(mass, stiffness))
    if not np.allclose(check, zeta, rtol=1e-9, atol=0.0):
        raise RuntimeError(
            f"{type(target).__name__}.loss_factor(impactor_mass_for(ζ, K), K) does not "
            f"return ζ (got {check!r} for ζ = {zeta!r}): the target's loss-factor formulas "
            "are inconsistent"
        )
    omega = contact_frequency(stiffness, mass)
    if zeta.ndim == 0:
        return Realisation(float(mass), float(stiffness), float(omega), float(zeta),
                           float(lam))
    return Realisation(mass, stiffness, omega, zeta.copy(), lam.copy())


# ---------------------------------------------------------------------------------
# Simply supported Euler beam struck at mid-span: (ζ, λ) fix everything
# ---------------------------------------------------------------------------------
def ss_euler_beam_midspan_mass_ratio(loss_factor, relative_stiffness):
    """Mass ratio ``μ = m_i/(m'L) = (4 sqrt(2π) ζ (λ/48)^{1/4})^{4/3}`` [-] (PHYSICS.md §4).

    For a simply supported Euler–Bernoulli beam struck at mid-span
    (``K_st = 48 EI/L³``) with the corrected beam loss factor ζ_b.

    Parameters
    ----------
    loss_factor : float or array_like
        ζ_b [-], > 0.
    relative_stiffness : float or array_like
        λ [-], > 0.
    """
    require_positive("loss_factor", loss_factor)
    require_positive("relative_stiffness", relative_stiffness)
    return (_BEAM_CONSTANT * _array(loss_factor)
            * (_array(relative_stiffness) / 48.0) ** 0.25) ** (4.0 / 3.0)


def ss_euler_beam_midspan_frequency_ratio(loss_factor, relative_stiffness):
    """First beam frequency over contact frequency, ``ω_1/ω = sqrt(π⁴ μ λ/48)`` [-] (PHYSICS.md §4).

    ``ω_1 = π² sqrt(EI/(m' L⁴))``; μ from :func:`ss_euler_beam_midspan_mass_ratio`.

    Parameters
    ----------
    loss_factor : float or array_like
        ζ_b [-], > 0.
    relative_stiffness : float or array_like
        λ [-], > 0.
    """
    mu = ss_euler_beam_midspan_mass_ratio(loss_factor, relative_stiffness)
    return np.sqrt(math.pi**4 * mu * _array(relative_stiffness) / 48.0)


def ss_euler_beam_midspan_loss_factor(mass_ratio, relative_stiffness):
    """Loss factor ζ_b of the mid-span SS Euler beam from ``μ = m_i/(m'L)`` and λ [-].

    Inverse of :func:`ss_euler_beam_midspan_mass_ratio`:
    ``ζ_b = μ^{3/4} / (4 sqrt(2π) (λ/48)^{1/4})``.

    Parameters
    ----------
    mass_ratio : float or array_like
        μ [-], > 0.
    relative_stiffness : float or array_like
        λ [-], > 0.
    """
    require_positive("mass_ratio", mass_ratio)
    require_positive("relative_stiffness", relative_stiffness)
    return (_array(mass_ratio) ** 0.75
            / (_BEAM_CONSTANT * (_array(relative_stiffness) / 48.0) ** 0.25))
