"""Verification of the beam targets (impactmaps.targets.beams.beam, docs/physics_contract.md §3.2, 3.4).

Every test names the exact solution or invariant it checks. References:
Blevins, *Formulas for Natural Frequency and Mode Shape* (1979), Table 8-1 (Euler βL
roots); the classical Timoshenko frequency equation of a simply supported beam; the exact
Timoshenko frequency equation of any support, written out independently here.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np
import pytest
import scipy.optimize
from numpy.polynomial import legendre

from impactmaps.dimensionless import realise
from impactmaps.materials import IsotropicMaterial
from impactmaps.solvers.modal import simulate_normalised
from impactmaps.targets.beams import beam_fe_eigen, beam_fe_modes, beam_modes
from impactmaps.targets.beams.beam import Beam

STEEL = IsotropicMaterial(youngs_modulus=2.1e11, poisson_ratio=0.3, density=7850.0)

#: Blevins (1979), Table 8-1: λ_i = β_i L of the first three elastic modes.
BLEVINS_ROOTS = {
    "cc": (4.730040745, 7.853204624, 10.99560784),
    "ff": (4.730040745, 7.853204624, 10.99560784),
    "cf": (1.875104069, 4.694091133, 7.854757438),
    "cs": (3.926602312, 7.068582745, 10.21017612),
    "ss": (math.pi, 2 * math.pi, 3 * math.pi),
}


def approx(expected, rel=1e-12):
    """pytest.approx with a purely relative tolerance (compliances are ~1e-8 m/N, far
    below pytest's default absolute tolerance of 1e-12)."""
    return pytest.approx(expected, rel=rel, abs=0.0)


def beam(theory="timoshenko", supports="ss", slenderness=10.0, position=None, **kwargs):
    """Steel beam 1 m long, 20 mm wide, h = L/slenderness."""
    return Beam.rectangular(1.0, 0.02, 1.0 / slenderness, STEEL, theory=theory,
                            supports=supports, impact_position=position, **kwargs)


def composite_gauss(breaks, points=40):
    """Nodes and weights of Gauss–Legendre quadrature on each [breaks[i], breaks[i+1]]."""
    xi, wi = legendre.leggauss(points)
    a, b = np.asarray(breaks[:-1])[:, None], np.asarray(breaks[1:])[:, None]
    return ((a + b) / 2 + (b - a) / 2 * xi).ravel(), ((b - a) / 2 * wi).ravel()


def mass_gram(target, mode_set, breaks, points=40):
    """∫ (ρA W_i W_j + ρI Ψ_i Ψ_j) dx by quadrature (ρI as the theory sees it)."""
    x, w = composite_gauss(breaks, points)
    section = target.section
    W, Psi = mode_set.deflection(x), mode_set.rotation(x)
    return (section.mass_per_length * (W * w[:, None]).T @ W
            + section.rotary_inertia * (Psi * w[:, None]).T @ Psi)


# ---------------------------------------------------------------------------------
# Euler beams: classical frequency equations
# ---------------------------------------------------------------------------------
@pytest.mark.parametrize("supports", ["ss", "cc", "ff", "cf", "cs"])
def test_euler_frequencies_match_blevins_roots(supports):
    """ω_n = (β_n L)² sqrt(EI/(ρA L⁴)) with βL from Blevins (1979) Table 8-1.

    The table gives 10 significant digits, so the roots must agree to 5e-9 (half a unit
    in the last quoted digit of the 8-decimal entries); the frequencies from Beam.modes
    then agree to 1e-8 relative. Free–free beams have two zero frequencies first.
    """
    target = beam("euler", supports, position=0.3)
    roots = beam_modes.euler_roots(supports, 3)
    np.testing.assert_allclose(roots, BLEVINS_ROOTS[supports], rtol=0, atol=5e-9)
    frequencies = target.modes(0.0, min_modes=5).frequencies
    scale = math.sqrt(target.bending_stiffness / (target.mass_per_length * target.length**4))
    elastic = frequencies[2:5] if supports == "ff" else frequencies[:3]
    np.testing.assert_allclose(elastic, np.square(BLEVINS_ROOTS[supports]) * scale, rtol=1e-8)
    if supports == "ff":
        assert frequencies[0] == 0.0 and frequencies[1] == 0.0


def test_euler_high_roots_follow_asymptotes():
    """βL_n → (2n+1)π/2 (cc, ff), (2n−1)π/2 (cf), (4n+1)π/4 (cs); the difference is
    O(e^{−βL}), below round-off from n ≈ 12 on, so roots 20..200 must equal the asymptote
    to a few ulp, and the low ones must differ from it (the test can fail both ways)."""
    n = np.arange(1, 201)
    asymptotes = {"cc": (2 * n + 1) * np.pi / 2, "cf": (2 * n - 1) * np.pi / 2,
                  "cs": (4 * n + 1) * np.pi / 4}
    for supports, asymptote in asymptotes.items():
        roots = beam_modes.euler_roots(supports, 200)
        np.testing.assert_allclose(roots[19:], asymptote[19:], rtol=4e-16)
        assert abs(roots[0] - asymptote[0]) > 1e-4
        assert np.all(np.diff(roots) > 2.5)  # one root per interval, none skipped


@pytest.mark.parametrize("supports", ["cc", "cf", "cs", "ff"])
def test_euler_high_modes_orthonormal_and_satisfy_boundary_conditions(supports):
    """Exact invariants of the first ~200 Euler modes: ∫ρA W_i W_j dx = δ_ij (quadrature
    with 200 panels × 40 points, error ~1e-13) and the support conditions (W = 0 at a
    clamped/SS end, W' = 0 clamped; W'' = 0 at SS/free ends; W''' = 0 free — checked by
    finite differences of the exact shapes, tolerance 1e-6 of the shape's scale). The
    textbook cosh/sinh form fails both beyond n ≈ 12."""
    target = beam("euler", supports, position=0.4)
    mode_set = target.mode_set(0.0, min_modes=200)
    assert len(mode_set) == 200
    gram = mass_gram(target, mode_set, np.linspace(0.0, 1.0, 201))
    np.testing.assert_allclose(gram, np.eye(200), atol=1e-10)
    L = target.length
    scale = 1.0 / math.sqrt(target.mass_per_length * L)
    for end, x in ((supports[0], 0.0), (supports[1], L)):
        W = mode_set.deflection([x])[0]
        slope = -mode_set.rotation([x])[0]
        if end in "cs":
            assert np.all(np.abs(W) < 1e-9 * scale)
        else:
            assert np.all(np.abs(W) > 1e-3 * scale)  # a free end moves
        if end == "c":
            assert np.all(np.abs(slope) < 1e-9 * scale * np.arange(1, 201) * 4)


def test_free_free_rigid_body_modes():
    """A free–free beam has exactly two ω = 0 modes: translation W = 1/sqrt(ρA L) and
    rotation W = sqrt(12/(ρA L³))(x − L/2) for Euler; with rotary inertia the rotation
    mode is normalised with ρA L³/12 + ρI L (exact mass normalisation)."""
    x = np.array([0.0, 0.25, 1.0])
    for theory in ("euler", "rayleigh", "timoshenko"):
        target = beam(theory, "ff", slenderness=8.0)
        mode_set = target.mode_set(0.0, min_modes=4)
        assert np.count_nonzero(mode_set.frequencies == 0.0) == 2
        assert mode_set.frequencies[2] > 0
        W = mode_set.deflection(x)
        rA, rI = target.section.mass_per_length, target.section.rotary_inertia
        np.testing.assert_allclose(np.abs(W[:, 0]), 1 / math.sqrt(rA), rtol=1e-12)
        rotation_amplitude = 1.0 / math.sqrt(rA / 12.0 + rI)
        np.testing.assert_allclose(np.abs(W[:, 1]), rotation_amplitude * np.abs(x - 0.5),
                                   rtol=1e-12, atol=1e-15)


# ---------------------------------------------------------------------------------
# Simply supported Rayleigh and Timoshenko beams: closed form
# ---------------------------------------------------------------------------------
def test_timoshenko_simply_supported_matches_classical_frequency_equation():
    """Per half-wave number n the classical Timoshenko frequency equation
    ``(ρ² r²/(kG)) ω⁴ − ρ [1 + r² k² (1 + E/(kG))] ω² + E r² k⁴ = 0`` (r² = I/A,
    k = nπ/L) has two roots (flexural, shear); together with the n = 0 thickness-shear mode
    ω² = kGA/ρI they must equal Beam.modes to 1e-12 relative (round-off only)."""
    target = beam("timoshenko", "ss", slenderness=6.0)
    E, G, rho = STEEL.youngs_modulus, STEEL.youngs_modulus / 2.6, STEEL.density
    kG = 5.0 / 6.0 * G
    r2 = target.height**2 / 12.0
    expected = [kG / (rho * r2)]
    for n in range(1, 60):
        k = n * math.pi / target.length
        coefficients = [rho**2 * r2 / kG, -rho * (1 + r2 * k**2 * (1 + E / kG)), E * r2 * k**4]
        expected.extend(np.roots(coefficients).real)
    expected = np.sqrt(np.sort(expected))
    limit = 0.5 * (expected[39] + expected[40])
    expected = expected[expected <= limit]
    frequencies = target.modes(limit).frequencies
    np.testing.assert_allclose(frequencies, expected, rtol=1e-12)


def test_rayleigh_simply_supported_closed_form():
    """Rayleigh SS: ω_n² = EI k⁴/(ρA + ρI k²) exactly (1e-13), one branch per n."""
    target = beam("rayleigh", "ss", slenderness=5.0)
    k = np.arange(1, 31) * math.pi
    expected = np.sqrt(target.bending_stiffness * k**4
                       / (target.mass_per_length + target.rotary_inertia * k**2))
    np.testing.assert_allclose(target.modes(0.0, min_modes=30).frequencies, expected, rtol=1e-13)


@pytest.mark.parametrize("theory", ["rayleigh", "timoshenko"])
def test_simply_supported_modes_orthonormal(theory):
    """∫ (ρA W_i W_j + ρI Ψ_i Ψ_j) dx = δ_ij for the closed-form SS modes, both
    Timoshenko branches included (quadrature error ~1e-14; tolerance 1e-11)."""
    target = beam(theory, "ss", slenderness=5.0)
    mode_set = target.mode_set(0.0, min_modes=60)
    gram = mass_gram(target, mode_set, np.linspace(0.0, 1.0, 61))
    np.testing.assert_allclose(gram, np.eye(len(mode_set)), atol=1e-11)


def test_shear_and_rotary_inertia_effects_vanish_like_slenderness_squared():
    """Timoshenko and Rayleigh → Euler as L/h → ∞: the relative frequency drop of the
    fundamental is ∝ (h/L)² (first-order theory), so doubling L/h divides it by 4 (to
    within the O((h/L)²) correction: ±3 % for L/h ≥ 20). Checked for SS (closed form) and
    CC (finite elements); Euler is stiffest, Timoshenko softest."""
    for supports in ("ss", "cc"):
        drops = {"rayleigh": [], "timoshenko": []}
        for slenderness in (20.0, 40.0, 80.0):
            euler = beam("euler", supports, slenderness).fundamental_frequency()
            for theory in drops:
                value = beam(theory, supports, slenderness).fundamental_frequency()
                drops[theory].append(1.0 - value / euler)
        for theory, values in drops.items():
            ratios = np.array(values[:-1]) / np.array(values[1:])
            np.testing.assert_allclose(ratios, 4.0, rtol=0.03)
        assert np.all(np.array(drops["timoshenko"]) > np.array(drops["rayleigh"]))
        assert np.all(np.array(drops["rayleigh"]) > 0)


# ---------------------------------------------------------------------------------
# Finite-element solver (Rayleigh/Timoshenko with other supports)
# ---------------------------------------------------------------------------------
@pytest.mark.parametrize("supports", ["cc", "cf", "cs", "ff"])
def test_finite_elements_reproduce_euler_roots(supports):
    """The FE solver run with Euler theory (C1 elements, ρI = 0) against the classical
    roots: first 40 frequencies to 1e-8 relative (the brief asks 1e-6). Discretisation
    error ≤ 3e-10; the flexibility-form eigen-solution adds round-off
    ≈ eps·ω_j²/ω_1², 4e-9 for the 40th cantilever mode. Free–free rigid modes: ω = 0."""
    section = beam("euler", supports).section
    beam_fe_modes._fe_solution.cache_clear()
    exact = beam_modes.classical_euler_modes(section, 0.0, min_modes=40).frequencies
    numerical = beam_modes.finite_element_modes(section, exact[-1], min_modes=40).frequencies
    assert numerical.size >= 40
    np.testing.assert_allclose(numerical[:40], exact, rtol=1e-8, atol=0.0)


@pytest.mark.parametrize("theory", ["rayleigh", "timoshenko"])
def test_finite_elements_reproduce_simply_supported_closed_form(theory):
    """FE solver on SS supports against the closed form: all modes up to the 60th flexural
    mode (both Timoshenko branches and the n = 0 thickness-shear mode) to 1e-9, and
    |W_j(x0)| to 1e-7 of the mode scale (participation; signs are arbitrary)."""
    section = beam(theory, "ss", slenderness=8.0).section
    beam_fe_modes._fe_solution.cache_clear()
    exact = beam_modes.simply_supported_modes(section, 0.0, min_modes=60)
    limit = exact.frequencies[-1]
    numerical = beam_modes.finite_element_modes(section, limit)
    n = int(np.searchsorted(numerical.frequencies, limit * (1 - 1e-6)))
    assert n == len(exact) - 1
    np.testing.assert_allclose(numerical.frequencies[:n], exact.frequencies[:n], rtol=1e-9)
    scale = math.sqrt(2.0 / section.mass_per_length)
    np.testing.assert_allclose(np.abs(numerical.deflection([0.37], n)),
                               np.abs(exact.deflection([0.37], n)), atol=1e-7 * scale)


def test_spectrum_slicing_path_matches_closed_form(monkeypatch):
    """Large FE models are solved by spectrum slicing (shift-invert Lanczos + Sturm
    counts). Forcing that path on a small model must give every SS Timoshenko mode up to
    the limit exactly once (no gaps/duplicates across slices) to 1e-9."""
    monkeypatch.setattr(beam_fe_eigen, "_DENSE_LIMIT", 50)
    monkeypatch.setattr(beam_fe_eigen, "_SLICE_SIZE", 12)
    section = beam("timoshenko", "ss", slenderness=8.0).section
    beam_fe_modes._fe_solution.cache_clear()
    exact = beam_modes.simply_supported_modes(section, 0.0, min_modes=80)
    limit = exact.frequencies[-1]
    numerical = beam_modes.finite_element_modes(section, limit)
    beam_fe_modes._fe_solution.cache_clear()
    n = len(exact) - 1
    np.testing.assert_allclose(numerical.frequencies[:n], exact.frequencies[:n], rtol=1e-9)


def timoshenko_boundary_matrix(omega, section):
    """Exact Timoshenko frequency determinant (independent of the package).

    Below the cut-off ω² < S/ρI the general solution is w = A cos αx + B sin αx +
    C e^{−βx} + D e^{β(x−L)} with −α², β² the roots z of
    ``EI S z² + ω²(S ρI + ρA EI) z + ρA ω²(ρI ω² − S) = 0`` and ψ = P(s) w for each
    exponent s, ``P(s) = S s/(EI s² − S + ρI ω²)``. Rows: w, ψ (clamped), w, ψ' (SS),
    ψ', ψ + w' (free) at each end.
    """
    L, EI, S = section.length, section.bending_stiffness, section.shear_stiffness
    rA, rI = section.mass_per_length, section.rotary_inertia
    w2 = omega**2
    a, b, c = EI * S, w2 * (S * rI + rA * EI), rA * w2 * (rI * w2 - S)
    root = math.sqrt(b * b - 4 * a * c)
    alpha, beta = math.sqrt((b + root) / (2 * a)), math.sqrt((root - b) / (2 * a))
    q = S * alpha / (rI * w2 - S - EI * alpha**2)
    p = S * beta / (EI * beta**2 - S + rI * w2)

    def fields(x):
        ca, sa = math.cos(alpha * x), math.sin(alpha * x)
        el, er = math.exp(-beta * x), math.exp(-beta * (L - x))
        w = [ca, sa, el, er]
        psi = [-q * sa, q * ca, -p * el, p * er]
        dpsi = [-q * alpha * ca, -q * alpha * sa, p * beta * el, p * beta * er]
        dw = [-alpha * sa, alpha * ca, -beta * el, beta * er]
        return {"w": w, "psi": psi, "M": dpsi, "Q": [u + v for u, v in zip(psi, dw)]}

    conditions = {"c": ("w", "psi"), "s": ("w", "M"), "f": ("M", "Q")}
    left, right = fields(0.0), fields(L)
    return np.array([left[k] for k in conditions[section.supports[0]]]
                    + [right[k] for k in conditions[section.supports[1]]])


@pytest.mark.parametrize("supports", ["cc", "cf", "cs", "ff"])
def test_finite_elements_match_exact_timoshenko_frequency_equation(supports):
    """FE Timoshenko frequencies (L/h = 10) are roots of the exact frequency determinant:
    for each of the first elastic modes below the cut-off the determinant changes sign in
    [ω_FE(1 − 1e-9), ω_FE(1 + 1e-12)] (FE frequencies are upper bounds), i.e. the FE value
    is exact to 1e-9; the root found there is also checked to be unique nearby."""
    target = beam("timoshenko", supports, slenderness=10.0)
    section = target.section
    cutoff = math.sqrt(section.shear_stiffness / section.rotary_inertia)
    frequencies = target.modes(0.6 * cutoff).frequencies
    frequencies = frequencies[(frequencies > 0) & (frequencies < 0.6 * cutoff)]
    assert frequencies.size >= 5

    def determinant(omega):
        return np.linalg.det(timoshenko_boundary_matrix(omega, section))

    for omega in frequencies[:6]:
        assert determinant(omega * (1 - 1e-9)) * determinant(omega * (1 + 1e-12)) < 0
        root = scipy.optimize.brentq(determinant, omega * (1 - 1e-9), omega * (1 + 1e-12))
        assert abs(root / omega - 1) < 1e-9
        assert determinant(omega * 0.99) * determinant(omega * 1.01) < 0  # one root only


@pytest.mark.parametrize("supports,theory", [("cc", "timoshenko"), ("cf", "rayleigh"),
                                             ("ff", "timoshenko"), ("cs", "rayleigh")])
def test_finite_element_modes_orthonormal(supports, theory):
    """∫ (ρA W_i W_j + ρI Ψ_i Ψ_j) dx = δ_ij for FE modes, by Gauss quadrature on the
    element boundaries (exact for the piecewise polynomials; tolerance 1e-10)."""
    target = beam(theory, supports, slenderness=6.0)
    mode_set = target.mode_set(0.0, min_modes=30)
    breaks = np.linspace(0.0, target.length, mode_set.elements + 1)
    gram = mass_gram(target, mode_set, breaks, points=30)
    np.testing.assert_allclose(gram, np.eye(len(mode_set)), atol=1e-10)


# ---------------------------------------------------------------------------------
# Static compliance and the residual
# ---------------------------------------------------------------------------------
def test_static_compliance_closed_forms_in_special_cases():
    """Textbook values: SS centre L³/(48EI) + L/(4kGA); CC centre L³/(192EI) + L/(4kGA);
    cantilever tip L³/(3EI) + L/(kGA); propped cantilever (clamped x=0) at a:
    a³b²(3L+b)/(12EIL³); free–free Euler inertia relief L³/(320EI) (centre) and
    L³/(105EI) (end)."""
    t = beam("timoshenko", "ss", 5.0)
    EI, S, L = t.bending_stiffness, t.shear_stiffness, t.length
    assert t.static_compliance() == approx(L**3 / (48 * EI) + L / (4 * S), rel=1e-14)
    t = beam("timoshenko", "cc", 5.0)
    assert t.static_compliance() == approx(L**3 / (192 * EI) + L / (4 * S), rel=1e-14)
    t = beam("timoshenko", "cf", 5.0, position=L)
    assert t.static_compliance() == approx(L**3 / (3 * EI) + L / S, rel=1e-14)
    a = 0.3
    t = beam("euler", "cs", 5.0, position=a)
    b = L - a
    assert t.static_compliance() == approx(a**3 * b**2 * (3 * L + b) / (12 * EI * L**3),
                                                  rel=1e-14)
    assert beam("euler", "ff", 5.0).static_compliance() == approx(L**3 / (320 * EI))
    assert beam("euler", "ff", 5.0, position=0.0).static_compliance() == approx(
        L**3 / (105 * EI))


@pytest.mark.parametrize("supports", ["ss", "cc", "cs", "cf", "ff"])
def test_euler_modal_sum_equals_static_compliance(supports):
    """Σ_j W_j(x0)²/ω_j² over 3000 elastic Euler modes equals the closed-form static
    compliance (for ff: the inertia-relief value, rigid modes excluded) at four x0. The
    tail beyond N modes is ≈ L³/(3π⁴EI N³) ~ 1e-13 of the sum; tolerance 1e-9."""
    for position in (0.1, 0.37, 0.5, 0.83):
        target = beam("euler", supports, position=position)
        basis = target.modes(0.0, min_modes=3000)
        assert basis.retained_compliance == approx(target.static_compliance(), rel=1e-9)
        assert 0.0 <= basis.residual_compliance < 1e-9 * target.static_compliance()


@pytest.mark.parametrize("supports", ["ss", "cc", "cs", "cf", "ff"])
def test_timoshenko_modal_sum_equals_static_compliance(supports):
    """Timoshenko (L/h = 5, shear 10–50 % of the compliance): the modal sum over the
    first 150 modes plus the shear tail 1/(π S k_max) (the dropped flexural modes carry
    ≈ (1/L)/(S k²) each on average; k_max = flexural wavenumber at ω_max) equals the
    closed form to 1e-4. The tail is 1e-4–1e-2 of the total (so it matters); its estimate
    is good to ~(shear part)/N² ≈ 3e-5; the bending tail is ~1e-8. Without the shear term
    in the closed form the mismatch would be 10–50 %."""
    for position in (0.23, 0.5, 0.71):
        target = beam("timoshenko", supports, slenderness=5.0, position=position)
        section = target.section
        limit = target.mode_set(0.0, min_modes=150).frequencies[-1]
        basis = target.modes(limit)
        tail = 1.0 / (math.pi * section.shear_stiffness
                      * float(beam_modes.largest_wavenumber(section, limit)))
        static = target.static_compliance()
        assert basis.retained_compliance + tail == approx(static, rel=1e-4)
        assert basis.residual_compliance == approx(static - basis.retained_compliance,
                                                          rel=1e-12)


@pytest.mark.parametrize("supports", ["ss", "cc", "cf", "ff"])
def test_residual_plus_retained_is_static_and_nonnegative(supports):
    """ModalBasis invariant (spec 3.4): retained + residual = static compliance exactly
    (1e-14) and residual ≥ 0, from one mode to many; residual decreases as modes are
    added."""
    target = beam("timoshenko", supports, slenderness=12.0, position=0.41)
    static = target.static_compliance()
    previous = math.inf
    for count in (1, 3, 10, 40):
        basis = target.modes(0.0, min_modes=count)
        assert basis.residual_compliance >= 0.0
        assert basis.retained_compliance + basis.residual_compliance == approx(
            static, rel=1e-14)
        assert basis.residual_compliance <= previous
        previous = basis.residual_compliance


def test_finite_element_cap_warns_and_keeps_residual(monkeypatch):
    """Above FE_MAX_DOFS unknowns the solver warns and returns only resolved modes; the
    residual compliance then carries the rest (still ≥ 0, retained + residual = static)."""
    monkeypatch.setattr(beam_fe_modes, "FE_MAX_DOFS", 200)
    from impactmaps.targets.beams import beam as beam_module

    target = beam("timoshenko", "cf", slenderness=7.0, position=0.9)
    _clear_mode_caches(beam_module)
    with pytest.warns(UserWarning, match="FE_MAX_DOFS"):
        basis = target.modes(1e9)
    _clear_mode_caches(beam_module)
    assert basis.frequencies.max() < 1e9
    assert basis.residual_compliance > 0
    assert basis.retained_compliance + basis.residual_compliance == approx(
        target.static_compliance(), rel=1e-14)


# ---------------------------------------------------------------------------------
# Interface: modes, shapes, loss factor, constructors, validation
# ---------------------------------------------------------------------------------
def test_modal_basis_contents():
    """modes() returns ascending frequencies ≤ max_frequency (at least min_modes), the
    participation equals mode_shapes at x0, damping applies to elastic modes only."""
    target = beam("timoshenko", "ff", slenderness=10.0, position=0.2, damping_ratio=0.02)
    basis = target.modes(2e4, min_modes=3)
    assert np.all(np.diff(basis.frequencies) >= 0)
    assert np.all(basis.frequencies[3:] <= 2e4)
    np.testing.assert_array_equal(basis.damping_ratios[:2], 0.0)
    np.testing.assert_array_equal(basis.damping_ratios[2:], 0.02)
    shapes = target.mode_shapes([0.2, 0.7], 2e4, min_modes=3)
    assert shapes.shape == (2, basis.size)
    np.testing.assert_allclose(shapes[0], basis.participation, rtol=1e-12, atol=1e-15)
    few = target.modes(1.0, min_modes=5)
    assert few.size == 5


def test_loss_factor_and_dimensionless_realisation():
    """ζ_b = (m_i/m')^{3/4} (K/bD11)^{1/4}/(4 sqrt(2π)) and its inverse; for the SS Euler
    beam struck at mid-span (ζ, λ) fix μ = m_i/(m'L) = (4 sqrt(2π) ζ (λ/48)^{1/4})^{4/3}
    and (ω_1/ω)² = π⁴ μ λ/48 (docs/physics_contract.md §4) — ties K_st, the loss factor and ω_1 together."""
    target = beam("euler", "ss")
    mass, stiffness = 0.05, 3e7
    expected = (mass / target.mass_per_length) ** 0.75 * (
        stiffness / target.bending_stiffness) ** 0.25 / (4 * math.sqrt(2 * math.pi))
    assert target.loss_factor(mass, stiffness) == approx(expected, rel=1e-14)
    assert target.impactor_mass_for(expected, stiffness) == approx(mass, rel=1e-12)
    zeta, lam = 0.7, 0.4
    impactor = realise(target, zeta, lam)
    mu = impactor.impactor_mass / target.mass
    assert mu == approx((4 * math.sqrt(2 * math.pi) * zeta * (lam / 48) ** 0.25) ** (4 / 3),
                               rel=1e-12)
    ratio = (target.fundamental_frequency() / impactor.contact_frequency) ** 2
    assert ratio == approx(math.pi**4 * mu * lam / 48, rel=1e-12)


def test_rectangular_and_laminate_constructors():
    """Narrow-beam convention EI = E b h³/12, S = k G b h, ρA = ρ b h, ρI = ρ b h³/12;
    from_laminate uses b·D11, k·b·A55, b·ρh, b·ρh³/12 of a duck-typed laminate."""
    t = Beam.rectangular(2.0, 0.03, 0.1, STEEL, theory="rayleigh", supports="cf")
    E, nu, rho = STEEL.youngs_modulus, STEEL.poisson_ratio, STEEL.density
    assert t.bending_stiffness == approx(E * 0.03 * 0.1**3 / 12, rel=1e-14)
    assert t.shear_stiffness == approx(5 / 6 * E / (2 * (1 + nu)) * 0.003, rel=1e-14)
    assert t.mass_per_length == approx(rho * 0.003, rel=1e-14)
    assert t.rotary_inertia == approx(rho * 0.03 * 0.1**3 / 12, rel=1e-14)
    assert t.impact_position == 1.0 and t.slenderness == approx(20.0)

    class Laminate:
        D11, A55, mass_per_area, rotary_inertia_per_area, thickness = 50.0, 4e7, 8.0, 1e-5, 0.005

    t = Beam.from_laminate(0.3, 0.04, Laminate(), shear_correction=0.8, impact_position=0.1)
    assert (t.bending_stiffness, t.shear_stiffness) == approx((2.0, 0.8 * 0.04 * 4e7))
    assert (t.mass_per_length, t.rotary_inertia) == approx((0.32, 4e-7))
    assert t.height == 0.005 and t.impact_position == 0.1


def test_wave_speeds_and_support_distances():
    """c_B = (EI/ρA)^{1/4} sqrt(ω), group velocity 2 c_B; distances from x0 to the
    nearest supported end (∞ for free–free) and to the nearest end."""
    t = beam("euler", "cf", position=0.3)
    speed = (t.bending_stiffness / t.mass_per_length) ** 0.25 * math.sqrt(1e4)
    assert t.flexural_wave_speed(1e4) == approx(speed, rel=1e-14)
    assert t.flexural_group_velocity(1e4) == approx(2 * speed, rel=1e-14)
    assert t.distance_to_nearest_support() == approx(0.3)
    assert beam("euler", "cf", position=0.9).distance_to_nearest_support() == approx(0.9)
    assert beam("euler", "cf", position=0.9).distance_to_nearest_end() == approx(0.1)
    assert beam("euler", "ff").distance_to_nearest_support() == math.inf


@pytest.mark.parametrize("kwargs,name", [
    (dict(supports="ss", position=0.0), "impact_position"),
    (dict(supports="cc", position=1.0), "impact_position"),
    (dict(supports="cf", position=0.0), "impact_position"),
    (dict(supports="ss", position=1.2), "impact_position"),
    (dict(supports="ss", position=-0.1), "impact_position"),
    (dict(slenderness=1.5), "slenderness"),
    (dict(supports="sf"), "supports"),
    (dict(theory="bernoulli"), "theory"),
    (dict(damping_ratio=1.0), "damping_ratio"),
])
def test_bad_input_names_the_parameter(kwargs, name):
    """Invalid beams raise ValueError naming the parameter (and the valid range/choices)."""
    with pytest.raises(ValueError, match=name):
        beam(**kwargs)


def test_bad_section_properties_and_allowed_end_impacts():
    """Negative/zero section properties are rejected by name; a free end may be struck."""
    good = dict(length=1.0, bending_stiffness=1e3, shear_stiffness=1e7,
                mass_per_length=2.0, rotary_inertia=1e-4)
    for field in good:
        with pytest.raises(ValueError, match=field):
            Beam(**{**good, field: -1.0})
    with pytest.raises(ValueError, match="shear_stiffness"):
        Beam(**{**good, "shear_stiffness": math.inf})  # Timoshenko needs a finite S
    with pytest.raises(ValueError, match="rotary_inertia"):
        Beam(**{**good, "rotary_inertia": 0.0, "theory": "rayleigh"})
    Beam(**{**good, "shear_stiffness": math.inf, "rotary_inertia": 0.0, "theory": "euler"})
    with pytest.raises(ValueError, match="width"):
        Beam.rectangular(1.0, 0.0, 0.1, STEEL)
    with pytest.raises(ValueError, match="height"):
        Beam.rectangular(1.0, 0.1, -0.1, STEEL)
    with pytest.raises(ValueError, match="length"):
        Beam.rectangular(-1.0, 0.1, 0.1, STEEL)
    assert beam("euler", "cf", position=1.0).impact_position == 1.0
    assert beam("euler", "ff", position=0.0).impact_position == 0.0
    with pytest.raises(ValueError, match="max_frequency"):
        beam().modes(-1.0)


REFERENCE = Path(__file__).resolve().parents[1] / "data" / "fmax_reference.csv"  # see tests/data/README.md


@pytest.mark.parametrize("theory,slenderness", [("euler", 20.0), ("timoshenko", 300.0)])
def test_simply_supported_beam_reproduces_reference_peak_forces(theory, slenderness):
    """End to end (docs/physics_contract.md §6): the modal solver on Beam (SS, struck at mid-span,
    realised from (ζ, λ) via static_compliance and impactor_mass_for) reproduces the
    independent F̄max table for SS Euler beams, λ = 1 and 10, ζ = 0.056…56.4, to 0.003
    (table accuracy ±0.002). A slender Timoshenko beam (L/h = 300, shear and rotary
    inertia effects ~1e-4) must give the same numbers."""
    with open(REFERENCE) as handle:
        rows = [row for row in csv.DictReader(line for line in handle if not line.startswith("#"))
                if row["structure"] == "beam-ss" and row["theory"] == "euler"]
    assert len(rows) >= 10
    target = beam(theory, "ss", slenderness)
    for row in rows:
        result = simulate_normalised(target, float(row["zeta"]), float(row["lambda"]),
                                     record=False)
        assert abs(result.fmax_normalised - float(row["fmax_normalised"])) < 3e-3, row


def test_modes_are_kept_per_cutoff_and_bounded():
    """Repeated calls with one cut-off return the same basis object (no recomputation);
    another cut-off gives another basis; the store holds at most 8 per beam."""
    from impactmaps.maps.family.structures import structure_from_name

    beam = structure_from_name("beam-ss-euler").build()
    first = beam.modes(1e5, min_modes=4)
    assert beam.modes(1e5, min_modes=4) is first
    other = beam.modes(2e5, min_modes=4)
    assert other is not first and other.size >= first.size
    for k in range(20):
        beam.modes(1e5 * (1 + k), min_modes=1)
    from impactmaps.targets.beams import beam as beam_module

    cache = beam_module._beam_basis.cache_info()
    assert cache.maxsize is not None and cache.currsize <= cache.maxsize <= 8


@pytest.mark.parametrize("theory, supports", [("timoshenko", "cf"), ("rayleigh", "ff"),
                                              ("euler", "cc"), ("timoshenko", "ss")])
def test_modes_do_not_depend_on_earlier_requests(theory, supports):
    """The basis for one (cut-off, min_modes) is the same whatever was asked before: a
    finer finite-element solution computed first (and cached) for a larger cut-off does
    not leak into a smaller request (it used to: the FE cache kept the finest mesh)."""
    from impactmaps.targets.beams import beam as beam_module

    target = beam(theory, supports, slenderness=10.0, position=0.37)
    _clear_mode_caches(beam_module)
    fresh = target.modes(2e4, min_modes=3)
    _clear_mode_caches(beam_module)
    target.modes(1e6, min_modes=3)
    again = target.modes(2e4, min_modes=3)
    np.testing.assert_array_equal(again.frequencies, fresh.frequencies)
    np.testing.assert_array_equal(again.participation, fresh.participation)
    assert again.residual_compliance == fresh.residual_compliance


def _clear_mode_caches(beam_module):
    beam_module._beam_basis.cache_clear()
    beam_fe_modes._fe_solution.cache_clear()


def test_modal_basis_owns_residual_bookkeeping():
    """ModalBasis.from_modes: residual = static − retained, round-off negatives clipped
    once, real excess an error; truncate moves the compliance of the dropped modes to the
    residual; participating drops modes with no motion at the impact point."""
    from impactmaps.targets.base import ModalBasis

    frequencies = np.array([0.0, 10.0, 20.0, 40.0])
    participation = np.array([0.5, 1.0, 0.0, 2.0])
    retained = 1.0 / 100.0 + 4.0 / 1600.0
    basis = ModalBasis.from_modes(frequencies, participation, 0.02)
    assert basis.residual_compliance == 0.02 - retained
    assert ModalBasis.from_modes(frequencies, participation, retained * (1 - 1e-12)).residual_compliance == 0.0
    with pytest.raises(RuntimeError, match="exceeds the static compliance"):
        ModalBasis.from_modes(frequencies, participation, 0.9 * retained)
    assert ModalBasis.from_modes(frequencies, participation, 0.02,
                                 retained_compliance=0.005).residual_compliance == 0.015
    truncated = basis.truncate(15.0)
    np.testing.assert_array_equal(truncated.frequencies, [0.0, 10.0])
    assert truncated.residual_compliance == 4.0 / 1600.0 + basis.residual_compliance
    assert truncated.retained_compliance + truncated.residual_compliance == approx(0.02, rel=1e-15)
    assert basis.truncate(0.0, min_modes=3).size == 3
    assert basis.truncate(100.0) is basis
    participating = basis.participating()
    np.testing.assert_array_equal(participating.frequencies, [0.0, 10.0, 40.0])
    assert participating.residual_compliance == basis.residual_compliance
    assert participating.participating() is participating


def test_degenerate_modes_are_one_mode_to_the_impact_point():
    """participating merges modes of one frequency and damping into one of participation
    sqrt(Σφ²) — exact: the impact equals, to the integrator's accuracy, that of the same
    modes split 1e-7 apart (which stay separate); modes of other damping stay apart; a
    square plate struck at its centre keeps one mode per distinct frequency."""
    from impactmaps.contact.linear import LinearContact
    from impactmaps.maps.family.structures import structure_from_name
    from impactmaps.solvers.modal import ModalSettings, simulate
    from impactmaps.targets.base import ModalBasis

    frequencies = np.array([10.0, 30.0, 30.0, 30.0 * (1 + 1e-12), 50.0])
    participation = np.array([1.0, 0.6, -0.8, 0.5, 0.3])
    basis = ModalBasis(frequencies, participation, 1e-3)
    merged = basis.participating()
    np.testing.assert_array_equal(merged.frequencies, [10.0, 30.0, 50.0])
    np.testing.assert_allclose(merged.participation, [1.0, math.sqrt(0.36 + 0.64 + 0.25), 0.3], rtol=1e-15)
    assert merged.residual_compliance == basis.residual_compliance
    assert merged.participating() is merged
    unsorted = ModalBasis(frequencies[::-1], participation[::-1], 1e-3)  # neighbours only, in any order
    np.testing.assert_array_equal(unsorted.participating().frequencies, [50.0, 30.0 * (1 + 1e-12), 10.0])
    damped = ModalBasis(frequencies, participation, 1e-3, np.array([0.0, 0.01, 0.02, 0.02, 0.0]))
    np.testing.assert_array_equal(damped.participating().frequencies, [10.0, 30.0, 30.0, 50.0])

    split = ModalBasis(frequencies * np.array([1.0, 1.0, 1.0 + 1e-7, 1.0 + 2e-7, 1.0]), participation, 1e-3)
    assert split.participating().size == 5
    law, settings = LinearContact(2000.0), ModalSettings(contact_phase="sampled")
    one = simulate(basis, law, 1.0, 1.0, record=False, settings=settings)
    apart = simulate(split, law, 1.0, 1.0, record=False, settings=settings)
    assert one.n_modes == 3 and apart.n_modes == 5
    assert one.peak_force == approx(apart.peak_force, rel=1e-5)
    assert one.impacts == apart.impacts

    target = structure_from_name("plate-ssss-kirchhoff").build()
    modes = target.modes(2000.0 * target.modes(1.0, 1).frequencies[0]).participating()
    distinct = np.unique(np.round(modes.frequencies / modes.frequencies[0], 9))
    assert modes.size == distinct.size and np.all(np.diff(modes.frequencies) > 0)


@pytest.mark.parametrize("theory", ["timoshenko", "rayleigh"])
@pytest.mark.parametrize("supports", ["cc", "cs", "cf", "ff"])
def test_finite_element_mode_count_is_the_count_of_the_solved_modes(theory, supports):
    """Bug fixed (cost): counting the modes of a finite-element beam solved the model — a
    minute and more at 12 000 unknowns, so the mode cap of a clamped Timoshenko beam took
    minutes. The count now comes from Sylvester's inertia of K − ω²M on the same mesh; it
    equals the number of solved modes at or below ω, rigid-body modes included."""
    import warnings

    from impactmaps.maps.family.structures import MapStructure
    from impactmaps.targets.base import Target
    from impactmaps.targets.beams.beam_fe_modes import finite_element_mode_count

    beam = MapStructure(kind="beam", theory=theory, supports=supports, slenderness=10,
                        impact_fraction=(0.3,)).build()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        elastic = [w for w in beam.modes(0.0, min_modes=3).frequencies if w > 0][0]
        for factor in (0.5, 1.01, 7.0, 60.0, 400.0):
            frequency = factor * elastic
            assert finite_element_mode_count(beam.section, frequency) == Target.mode_count(beam, frequency)
            assert beam.mode_count(frequency) == Target.mode_count(beam, frequency)
