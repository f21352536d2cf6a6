"""The dimensionless framework (docs/physics_contract.md §1 and §4).

Round trips are algebraic identities, checked to rtol 1e-12 (a few ulps after powers
such as ^(4/3) and ^(3/4)). The loss-factor constants are re-derived from first
principles (wave-number integrals of the infinite Euler beam and Kirchhoff plate) with
adaptive quadrature to rtol ~1e-8, which is what ``scipy.integrate.quad`` reaches on
these oscillatory integrals.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from scipy import integrate, special

from impactmaps import dimensionless as dl
from impactmaps.materials import IsotropicMaterial, Laminate
from impactmaps.targets.base import ModalBasis, Target

RTOL = 1e-12

ZETA = np.geomspace(1e-3, 1e3, 25)
LAMBDA = np.geomspace(1e-3, 1e3, 25)[:, None]


# -- scales ---------------------------------------------------------------------------------
def test_scales_and_halfspace_force():
    """ω = sqrt(K/m), α* = V0/ω, and the half-space peak force K α* equals m V0 ω (F̄max = 1)."""
    stiffness, mass, velocity = 3.2e7, 0.25, 2.5
    omega = dl.contact_frequency(stiffness, mass)
    assert omega == pytest.approx(math.sqrt(3.2e7 / 0.25), rel=RTOL)
    alpha_star = dl.halfspace_indentation(velocity, omega)
    assert alpha_star == pytest.approx(velocity / omega, rel=RTOL)
    peak_force = stiffness * alpha_star  # F̄ = sin τ → F_max = K α*
    assert dl.force_scale(mass, velocity, omega) == pytest.approx(mass * velocity * omega, rel=RTOL)
    assert dl.normalised_force(peak_force, mass, velocity, omega) == pytest.approx(1.0, rel=RTOL)
    assert dl.normalised_force(-3.0, mass, velocity, omega) < 0  # finite forces accepted


def test_functions_broadcast():
    """Vectorised: arrays broadcast like NumPy (here 25 × 25)."""
    mass = dl.impactor_mass_for_plate(ZETA, 1e6 / LAMBDA, 10.0, 500.0)
    assert mass.shape == (25, 25)
    assert dl.contact_frequency(1e6 / LAMBDA, mass).shape == (25, 25)


def test_impact_number():
    """β = V0/(ω_h α_y), ω_h² = K_h α_y^{1/2}/m_i (eqs 11–12), and its inverse."""
    k_h, alpha_y, mass, velocity = 1.3e10, 2e-6, 0.05, 0.7
    omega_h = math.sqrt(k_h * math.sqrt(alpha_y) / mass)
    assert dl.hertz_frequency(k_h, alpha_y, mass) == pytest.approx(omega_h, rel=RTOL)
    beta = dl.impact_number(velocity, k_h, alpha_y, mass)
    assert beta == pytest.approx(velocity / (omega_h * alpha_y), rel=RTOL)
    assert dl.velocity_for_impact_number(beta, k_h, alpha_y, mass) == pytest.approx(velocity,
                                                                                 rel=RTOL)


def test_relative_stiffness_round_trip():
    """λ = K_st/K and K = K_st/λ are inverse."""
    k_st = 4.2e6
    k = dl.contact_stiffness_for_relative_stiffness(k_st, LAMBDA)
    np.testing.assert_allclose(dl.relative_stiffness(k_st, k), np.broadcast_to(LAMBDA, k.shape),
                               rtol=RTOL)


def test_effective_plate_stiffness_isotropic_and_laminate():
    """Isotropic (D12 = νD, D66 = (1−ν)D/2) gives D* = D; agrees with Laminate's D*."""
    d, nu = 123.4, 0.3
    assert dl.effective_plate_stiffness(d, d, nu * d, (1 - nu) * d / 2) == pytest.approx(d, rel=RTOL)
    plate = Laminate.from_isotropic(IsotropicMaterial(70e9, 0.33, 2700.0), 3e-3)
    assert dl.effective_plate_stiffness(plate.D11, plate.D22, plate.D12, plate.D66) == \
        pytest.approx(plate.effective_bending_stiffness, rel=RTOL)
    with pytest.raises(ValueError, match="D12"):
        dl.effective_plate_stiffness(1.0, 1.0, -10.0, 1.0)


# -- loss factors ---------------------------------------------------------------------------------
def test_plate_loss_factor_round_trip():
    """ζ_p(m_i(ζ)) = ζ over six decades of ζ and λ."""
    rho_h, d_star, k_st = 15.6, 1.9e3, 2.0e6
    k = k_st / LAMBDA
    mass = dl.impactor_mass_for_plate(ZETA, k, rho_h, d_star)
    np.testing.assert_allclose(dl.loss_factor_plate(mass, k, rho_h, d_star),
                               np.broadcast_to(ZETA, mass.shape), rtol=RTOL)
    # and the forward formula itself, eq (34)
    assert dl.loss_factor_plate(2.0, 3e6, rho_h, d_star) == pytest.approx(
        math.sqrt(2.0 * 3e6 / (rho_h * d_star)) / 16, rel=RTOL)


def test_beam_loss_factor_round_trip_and_paper_factor():
    """ζ_b(m_i(ζ)) = ζ; the printed eq (38) is exactly 2 ζ_b (spec correction)."""
    m_prime, bending, k_st = 3.9, 2.1e3, 5.0e5
    k = k_st / LAMBDA
    mass = dl.impactor_mass_for_beam(ZETA, k, m_prime, bending)
    zeta_b = dl.loss_factor_beam(mass, k, m_prime, bending)
    np.testing.assert_allclose(zeta_b, np.broadcast_to(ZETA, mass.shape), rtol=RTOL)
    np.testing.assert_allclose(dl.loss_factor_beam_paper(mass, k, m_prime, bending), 2 * zeta_b,
                               rtol=RTOL)


def test_paper_eq38_as_printed_is_twice_the_corrected_value():
    """Seed 001 eq (38) as printed, ζ = 1/(2√(2π)) sqrt(m_i/(ρb²h)) [m_i K/(ρh D11)]^{1/4},
    evaluated from ρ, b, h, D11 directly, equals :func:`loss_factor_beam_paper`."""
    rho, b, h, d11, mass, k = 7850.0, 0.02, 0.01, 1.9e4, 0.3, 4e7
    printed = (1 / (2 * math.sqrt(2 * math.pi)) * math.sqrt(mass / (rho * b**2 * h))
               * (mass * k / (rho * h * d11)) ** 0.25)
    assert dl.loss_factor_beam_paper(mass, k, rho * b * h, b * d11) == pytest.approx(printed,
                                                                                     rel=RTOL)


def _infinite_euler_beam_displacement_coefficient(bending, m_prime):
    """C with w(0, t) = C sqrt(t) for a unit impulse on an infinite Euler beam.

    Modal (wave-number) superposition: w(0, t) = (1/(π m')) ∫0^∞ sin(c k² t)/(c k²) dk,
    c = sqrt(EI/m'). With v = k² at t = 1: (1/(2π m' c)) ∫0^∞ sin(c v) v^{-3/2} dv.
    """
    c = math.sqrt(bending / m_prime)
    near, _ = integrate.quad(lambda v: math.sin(c * v) * v**-1.5, 0.0, 1.0,
                             epsabs=0, epsrel=1e-12, limit=200)
    far, _ = integrate.quad(lambda v: v**-1.5, 1.0, np.inf, weight="sin", wvar=c,
                            epsabs=1e-14, limit=200)
    return (near + far) / (2 * math.pi * m_prime * c)


def test_beam_loss_factor_from_infinite_beam_green_function():
    """The corrected ζ_b follows from the exact infinite Euler beam (docs/physics_contract.md §1).

    w(0,t) = C sqrt(t) (unit impulse) means ẇ = (C/2) ∫ F(ξ)/sqrt(t−ξ) dξ; inserted in
    m_i ẅ_i = −Kα and normalised (τ = ωt) this gives 2ζ = (C/2) K ω^{-3/2}. The paper's
    eq (35)/(38) would be twice as large. Quadrature accuracy ~1e-9.
    """
    bending, m_prime, mass, k = 2.1e3, 3.9, 0.8, 3e6
    coefficient = _infinite_euler_beam_displacement_coefficient(bending, m_prime)
    c = math.sqrt(bending / m_prime)
    assert coefficient == pytest.approx(1 / (m_prime * math.sqrt(2 * math.pi * c)), rel=1e-8)
    omega = math.sqrt(k / mass)
    zeta_from_green = coefficient / 2 * k * omega**-1.5 / 2
    assert dl.loss_factor_beam(mass, k, m_prime, bending) == pytest.approx(zeta_from_green,
                                                                           rel=1e-8)
    assert dl.loss_factor_beam_paper(mass, k, m_prime, bending) == pytest.approx(
        2 * zeta_from_green, rel=1e-8)


def test_plate_loss_factor_from_infinite_plate_green_function():
    """ζ_p follows from the exact infinite Kirchhoff plate (seed 001 eqs 30, 34).

    Unit impulse: w(0, t) = (1/(2π ρh c)) ∫0^∞ sin(c k² t)/k dk = 1/(8 sqrt(ρh D)), so
    ẇ = F/(8 sqrt(ρh D)) and ᾱ'' + (K/(8 sqrt(ρhD) ω)) ᾱ' + ᾱ = 0, i.e. 2ζ = K/(8 ω sqrt(ρhD)).
    """
    rho_h, d, mass, k = 15.6, 1.9e3, 0.8, 3e6
    c = math.sqrt(d / rho_h)
    # with v = k²: ∫0^∞ sin(c v)/(2v) dv
    near, _ = integrate.quad(lambda v: math.sin(c * v) / (2 * v), 0.0, 1.0, epsrel=1e-12)
    # tail ∫1^∞ sin(c v)/(2v) dv = (π/2 − Si(c))/2 (sine integral; QAWF converges badly on 1/v)
    far = (math.pi / 2 - special.sici(c)[0]) / 2
    displacement = (near + far) / (2 * math.pi * rho_h * c)
    assert displacement == pytest.approx(1 / (8 * math.sqrt(rho_h * d)), rel=1e-8)
    omega = math.sqrt(k / mass)
    zeta_from_green = displacement * k / omega / 2
    assert dl.loss_factor_plate(mass, k, rho_h, d) == pytest.approx(zeta_from_green, rel=1e-8)


# -- simply supported Euler beam at mid-span ---------------------------------------------------
def test_ss_euler_beam_ratios_against_physical_beam():
    """μ = m_i/(m'L) and ω1/ω from (ζ, λ) agree with a physical beam (EI, m', L).

    K_st = 48 EI/L³, K = K_st/λ, m_i from the corrected beam formula, ω1 = π² sqrt(EI/(m'L⁴)).
    """
    bending, m_prime, length = 2.1e3, 3.9, 0.75
    k_st = 48 * bending / length**3
    k = k_st / LAMBDA
    mass = dl.impactor_mass_for_beam(ZETA, k, m_prime, bending)
    mu = dl.ss_euler_beam_midspan_mass_ratio(ZETA, LAMBDA)
    np.testing.assert_allclose(mu, mass / (m_prime * length), rtol=RTOL)
    omega_1 = math.pi**2 * math.sqrt(bending / (m_prime * length**4))
    omega = np.sqrt(k / mass)
    np.testing.assert_allclose(dl.ss_euler_beam_midspan_frequency_ratio(ZETA, LAMBDA),
                               omega_1 / omega, rtol=RTOL)
    np.testing.assert_allclose(dl.ss_euler_beam_midspan_loss_factor(mu, LAMBDA),
                               np.broadcast_to(ZETA, mu.shape), rtol=RTOL)


# -- realise() on a generic target ---------------------------------------------------------------
@dataclasses.dataclass(frozen=True)
class _PlateLikeTarget(Target):
    """Minimal stand-in: fixed static stiffness and the plate loss-factor formula."""

    stiffness: float = 2.0e6
    mass_per_area: float = 15.6
    effective_bending_stiffness: float = 1.9e3
    structure = "plate"

    def modes(self, max_frequency, min_modes=1):
        return ModalBasis(np.array([1.0]), np.array([1.0]))

    def static_compliance(self):
        return 1.0 / self.stiffness

    def loss_factor(self, impactor_mass, contact_stiffness):
        return dl.loss_factor_plate(impactor_mass, contact_stiffness, self.mass_per_area,
                                    self.effective_bending_stiffness)

    def impactor_mass_for(self, loss_factor, contact_stiffness):
        return dl.impactor_mass_for_plate(loss_factor, contact_stiffness, self.mass_per_area,
                                          self.effective_bending_stiffness)


class _BrokenTarget(_PlateLikeTarget):
    """Its two loss-factor formulas are not inverse (the beam/plate mix-up to catch)."""

    def impactor_mass_for(self, loss_factor, contact_stiffness):
        return dl.impactor_mass_for_beam(loss_factor, contact_stiffness, 3.9, 2.1e3)


def test_realise_scalar():
    """K = K_st/λ, m_i = 256 ζ² ρh D*/K, ω = sqrt(K/m_i), and the target sees (ζ, λ)."""
    target = _PlateLikeTarget()
    point = dl.realise(target, 1.198, 0.425)
    assert isinstance(point, dl.Realisation)
    assert point.contact_stiffness == pytest.approx(2.0e6 / 0.425, rel=RTOL)
    assert point.impactor_mass == pytest.approx(256 * 1.198**2 * 15.6 * 1.9e3
                                                / point.contact_stiffness, rel=RTOL)
    assert point.contact_frequency == pytest.approx(
        math.sqrt(point.contact_stiffness / point.impactor_mass), rel=RTOL)
    assert target.loss_factor(point.impactor_mass, point.contact_stiffness) == \
        pytest.approx(1.198, rel=RTOL)
    assert dl.relative_stiffness(target.static_stiffness(), point.contact_stiffness) == \
        pytest.approx(0.425, rel=RTOL)
    velocity = 3.0
    assert point.force_scale(velocity) == pytest.approx(
        point.impactor_mass * velocity * point.contact_frequency, rel=RTOL)
    assert point.indentation_scale(velocity) == pytest.approx(velocity / point.contact_frequency,
                                                              rel=RTOL)
    assert point.time_scale == pytest.approx(1 / point.contact_frequency, rel=RTOL)


def test_realise_broadcasts_over_a_map():
    """A whole (λ, ζ) grid in one call, consistent point by point."""
    point = dl.realise(_PlateLikeTarget(), ZETA, LAMBDA)
    assert point.impactor_mass.shape == (25, 25)
    np.testing.assert_allclose(point.relative_stiffness, np.broadcast_to(LAMBDA, (25, 25)))
    np.testing.assert_allclose(
        dl.loss_factor_plate(point.impactor_mass, point.contact_stiffness, 15.6, 1.9e3),
        np.broadcast_to(ZETA, (25, 25)), rtol=RTOL)


def test_realise_detects_inconsistent_target():
    """A target whose impactor_mass_for does not invert its loss_factor is an error."""
    with pytest.raises(RuntimeError, match="inconsistent"):
        dl.realise(_BrokenTarget(), 0.5, 1.0)


# -- validation --------------------------------------------------------------------------------
@pytest.mark.parametrize(
    "function, args, parameter",
    [
        (dl.contact_frequency, (1e6, -1.0), "impactor_mass"),
        (dl.contact_frequency, (0.0, 1.0), "contact_stiffness"),
        (dl.halfspace_indentation, (0.0, 10.0), "velocity"),
        (dl.force_scale, (1.0, 1.0, np.nan), "contact_frequency"),
        (dl.normalised_force, (np.inf, 1.0, 1.0, 1.0), "force"),
        (dl.impact_number, (1.0, 1e9, -1e-6, 1.0), "yield_indentation"),
        (dl.relative_stiffness, (1e6, 0.0), "contact_stiffness"),
        (dl.relative_stiffness, (-1e6, 1.0), "static_stiffness"),
        (dl.loss_factor_plate, (-0.1, 1e6, 10.0, 100.0), "impactor_mass"),
        (dl.loss_factor_plate, (0.1, 1e6, 0.0, 100.0), "mass_per_area"),
        (dl.impactor_mass_for_plate, (0.0, 1e6, 10.0, 100.0), "loss_factor"),
        (dl.loss_factor_beam, (0.1, 1e6, 1.0, [1.0, -2.0]), "bending_stiffness"),
        (dl.impactor_mass_for_beam, (0.5, 1e6, -1.0, 1.0), "mass_per_length"),
        (dl.ss_euler_beam_midspan_mass_ratio, (0.5, 0.0), "relative_stiffness"),
        (dl.ss_euler_beam_midspan_loss_factor, (-1.0, 1.0), "mass_ratio"),
    ],
)
def test_bad_input_names_the_parameter(function, args, parameter):
    """Invalid input → ValueError whose message names the offending parameter."""
    with pytest.raises(ValueError, match=parameter):
        function(*args)


def test_realise_rejects_bad_point():
    """λ ≤ 0 or ζ ≤ 0 cannot be realised."""
    with pytest.raises(ValueError, match="relative_stiffness"):
        dl.realise(_PlateLikeTarget(), 1.0, -0.1)
    with pytest.raises(ValueError, match="loss_factor"):
        dl.realise(_PlateLikeTarget(), 0.0, 1.0)
