"""Contact laws: every registered law through the same invariants, then each law's own
equations, continuity at every phase boundary, energies, random load paths, bad input."""

from __future__ import annotations

import dataclasses
import itertools
import math
from dataclasses import dataclass

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from scipy.integrate import quad
from scipy.optimize import brentq

from impactmaps.contact import (
    ContactLaw,
    ContactPair,
    HertzContact,
    LinearContact,
    Sphere,
    StrongeContact,
    YigitChristoforouContact,
    available_contact_laws,
    contact_law,
    contact_law_class,
    effective_modulus,
    hertz_stiffness,
    law_for_sphere,
    stronge_continuity_coefficient,
    yield_indentation,
)
from impactmaps.closed_forms.halfspace import halfspace_impact, hertz_peak_force

from ..printed_stronge import PrintedStrongeContact


@dataclass(frozen=True)
class Material:
    """Stand-in for impactmaps.materials.IsotropicMaterial (duck-typed by the library)."""

    youngs_modulus: float
    poisson_ratio: float
    density: float
    yield_strength: float | None = None


STEEL = Material(210e9, 0.30, 7850.0, 1.2e9)
ALUMINIUM = Material(70e9, 0.33, 2700.0, 2.8e8)
BALL = Sphere(0.00635, STEEL)

KNOWN_LAWS = {"hertz", "linear", "stronge", "yigit-christoforou"}


def example_law(name: str) -> ContactLaw:
    """A physically sized law for a 12.7 mm steel ball on aluminium (any registered law)."""
    return law_for_sphere(name, BALL, ALUMINIUM)


def yield_scale(law: ContactLaw) -> float:
    """A characteristic indentation [m]: first yield for plastic laws, 1 µm otherwise."""
    for attribute in ("yield_indentation",):
        value = getattr(law, attribute, None)
        if value is not None:
            return float(np.asarray(value))
    return 1e-6


def kinks(law: ContactLaw) -> list[float]:
    points = [yield_scale(law)]
    if isinstance(law, StrongeContact):
        points.append(float(law.plastic_indentation))
    return points


# -- registry -------------------------------------------------------------------------------
def test_registry_holds_the_four_laws():
    """The four laws of docs/physics_contract.md §2 are registered under their names."""
    assert KNOWN_LAWS <= set(available_contact_laws())


def test_unknown_law_name_lists_the_known_ones():
    """An unknown name is a ValueError that lists every registered law (no silent default)."""
    with pytest.raises(ValueError) as info:
        contact_law_class("hertzian")
    for name in available_contact_laws():
        assert repr(name) in str(info.value)
    with pytest.raises(ValueError, match="stronge"):
        law_for_sphere("no-such-law", BALL, ALUMINIUM)


@pytest.mark.parametrize("name", available_contact_laws())
def test_registered_law_invariants(name):
    """Invariants every law must satisfy (docs/physics_contract.md §2, base.py convention).

    No tension (F = dF = 0 for α ≤ 0 whatever the history); F ≥ 0 on a grid of (α, α_max);
    tangent = central difference of the force (rel. 1e-5: O(h²) error with h = 1e-6 α);
    unloading leaves the loading curve continuously at α_m (rel. 1e-7 for a 1e-9 step,
    C¹ curves); 0 ≤ α_f ≤ α_m with zero force below α_f, ≤ 1e-9 F_m at α_f (rounding of
    α_f = (α_f^{3/2})^{2/3}) and positive force just above;
    closed-form energies equal the base-class Simpson quadrature (rel. 1e-6); dissipation
    ≥ 0; elastic laws dissipate nothing; the name round-trips through the registry.
    """
    law = example_law(name)
    assert law.name == name and contact_law_class(name) is type(law)
    rebuilt = contact_law(name, **{f.name: getattr(law, f.name) for f in dataclasses.fields(law)})
    assert rebuilt == law
    scale = yield_scale(law)
    history = np.array([0.0, 0.3, 1.0, 3.0, 30.0, 300.0]) * scale

    for alpha_max in history:
        force, stiffness = law.kernel(-scale, alpha_max, law.kernel_parameters.reshape(-1))
        assert force == 0.0 and stiffness == 0.0
        assert law.force(0.0, alpha_max) == 0.0

    alpha = np.linspace(-0.5, 400.0, 1601) * scale
    grid_alpha, grid_max = np.meshgrid(alpha, history, indexing="ij")
    force = law.force(grid_alpha, np.maximum(grid_max, 0.0))
    assert np.all(force >= 0.0) and np.all(np.isfinite(force))

    # tangent stiffness against the force (away from the kinks of the loading curve)
    points = np.array([0.37, 0.81, 2.3, 17.0, 150.0]) * scale
    for alpha_max in (0.0, 400.0 * scale):
        step = 1e-6 * points
        numeric = (law.force(points + step, alpha_max) - law.force(points - step, alpha_max)) / (2 * step)
        analytic = law.tangent_stiffness(points, alpha_max)
        positive = analytic > 0
        np.testing.assert_allclose(numeric[positive], analytic[positive], rtol=1e-5)

    peaks = np.array([0.5, 2.0, 10.0, 100.0, 1000.0]) * scale
    at_peak = law.loading_force(peaks)
    just_below = law.force(peaks * (1 - 1e-9), peaks)
    np.testing.assert_allclose(just_below, at_peak, rtol=1e-7)

    final = law.permanent_indentation(peaks)
    assert np.all(final >= 0.0) and np.all(final < peaks)
    assert np.all(law.force(final, peaks) <= 1e-9 * at_peak)  # zero up to rounding of α_f
    assert np.all(law.force(final * (1 - 1e-9), peaks) == 0.0)
    assert np.all(law.force(final + 1e-3 * (peaks - final), peaks) > 0.0)

    closed_loading = law.loading_energy(peaks)
    closed_recovered = law.recovered_energy(peaks)
    np.testing.assert_allclose(closed_loading, ContactLaw.loading_energy(law, peaks, points=4001), rtol=1e-6)
    np.testing.assert_allclose(closed_recovered, ContactLaw.recovered_energy(law, peaks, points=4001), rtol=1e-6)
    dissipated = law.dissipated_energy(peaks)
    if law.elastic:
        assert np.all(final == 0.0)
        np.testing.assert_allclose(closed_recovered, closed_loading, rtol=1e-12)
    assert np.all(dissipated >= -1e-12 * closed_loading)


@pytest.mark.parametrize("name", available_contact_laws())
def test_batched_parameters_match_single_laws(name):
    """A law with array parameters evaluates each batch member as its own scalar law.

    Every float field is given the values (x, 1.3 x); forces and stiffnesses must be
    bit-identical to the scalar laws (the same kernel runs on the same numbers).
    """
    law = example_law(name)
    fields = {f.name: getattr(law, f.name) for f in dataclasses.fields(law)}
    batch = type(law)(**{k: np.array([v, 1.3 * v]) for k, v in fields.items()})
    members = [type(law)(**fields), type(law)(**{k: 1.3 * v for k, v in fields.items()})]
    scale = yield_scale(law)
    alpha = np.array([[0.4, 3.0, 40.0]]).T * scale  # shape (3, 1) → broadcast (3, 2)
    alpha_max = 60.0 * scale
    batch_force = batch.force(alpha, alpha_max)
    assert batch_force.shape == (3, 2)
    for column, member in enumerate(members):
        np.testing.assert_array_equal(batch_force[:, column], member.force(alpha[:, 0], alpha_max))
    np.testing.assert_allclose(
        batch.loading_energy(np.array([5.0, 5.0]) * scale),
        [m.loading_energy(5.0 * scale) for m in members],
        rtol=1e-14,
    )


# -- random load / unload / reload paths --------------------------------------------------
def _path_work(law, turning_points):
    """Work ∫F dα along a piecewise-linear indentation path, α_max updated on the way.

    Each leg is split where it overtakes α_max; every piece is integrated by adaptive
    quadrature (rel. 1e-11) with the law's kernel at fixed history.
    """
    params = law.kernel_parameters.reshape(-1)
    alpha_max = 0.0
    work = 0.0
    breaks = kinks(law)
    for start, end in zip(turning_points[:-1], turning_points[1:]):
        pieces = []
        if end > alpha_max and start < end:
            if start < alpha_max:
                pieces.append((start, alpha_max, alpha_max))
            pieces.append((max(start, alpha_max), end, None))  # virgin loading
        else:
            pieces.append((start, end, alpha_max))
        for low, high, history in pieces:
            if history is None:
                integrand = lambda a: law.kernel(a, a, params)[0]  # noqa: E731
            else:
                integrand = lambda a, h=history: law.kernel(a, h, params)[0]  # noqa: E731
            inner = [b for b in breaks + [law.permanent_indentation(alpha_max).item(), 0.0]
                     if min(low, high) < b < max(low, high)]
            value = quad(integrand, low, high, points=inner or None, epsabs=0.0, epsrel=1e-11, limit=200)[0]
            work += value
        alpha_max = max(alpha_max, start, end)
    return work, alpha_max


paths = st.lists(
    st.tuples(st.floats(0.05, 60.0), st.floats(-0.3, 0.98)), min_size=1, max_size=6
)


@pytest.mark.parametrize("name", available_contact_laws())
@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(legs=paths)
def test_random_paths(name, legs):
    """Random load/unload/reload paths 0 → p1 → v1 → p2 → … → 0 (property-based).

    Along the path (sampled densely): the force is never negative; the stored α_max
    never decreases; below α_max the force is the unloading curve of α_max (reloading
    retraces it) and once α overtakes α_max it is the virgin loading curve. Over the
    closed path the work done on the contact equals the law's ``dissipated_energy`` of the
    final α_max (path independence, rel. 1e-7: quadrature at 1e-11 of terms that cancel
    to ~1e-4 of their size), and is ≥ 0.
    """
    law = example_law(name)
    scale = yield_scale(law)
    turning = [0.0]
    for peak, valley_fraction in legs:
        turning.append(peak * scale)
        turning.append(valley_fraction * peak * scale)
    turning.append(0.0)
    turning = [t for i, t in enumerate(turning) if i == 0 or t != turning[i - 1]]

    samples = np.concatenate([np.linspace(a, b, 41)[1:] for a, b in zip(turning[:-1], turning[1:])])
    history = np.maximum.accumulate(np.concatenate(([0.0], samples[:-1])))  # α_max before each sample
    assert np.all(np.diff(history) >= 0.0)
    force = law.force(samples, history)
    assert np.all(force >= 0.0)
    loading = samples >= history
    np.testing.assert_array_equal(force[loading], law.loading_force(samples[loading]))
    unloading = ~loading
    np.testing.assert_array_equal(force[unloading], law.force(samples[unloading], history[unloading]))
    below_final = samples < law.permanent_indentation(history)
    assert np.all(force[below_final] == 0.0)
    # reloading retraces the unloading curve: the force on the way back up through the
    # previous valley equals the force on the way down at the same indentation
    for i in range(1, len(turning) - 2, 2):
        peak, valley, next_peak = turning[i], turning[i + 1], turning[i + 2]
        if valley < peak and next_peak > valley:
            common = np.linspace(max(valley, 0.0), min(peak, next_peak), 7)
            stored = max(turning[: i + 1])
            down = law.force(common, stored)
            up = law.force(common, np.maximum(stored, common))
            np.testing.assert_array_equal(up, down)

    final_max = max(turning)
    work, reached = _path_work(law, turning)
    assert reached == final_max
    stored = float(law.loading_energy(final_max))
    assert work >= -1e-9 * stored
    assert work == pytest.approx(float(law.dissipated_energy(final_max)), rel=1e-7, abs=1e-9 * stored)


# -- Hertz --------------------------------------------------------------------------------------
def test_hertz_stiffness_from_sphere():
    """K_h = (4/3) sqrt(R) E* with 1/E* = Σ(1 − ν²)/E (seed 001 eqs 7–8), by hand."""
    modulus = 1.0 / ((1 - 0.30**2) / 210e9 + (1 - 0.33**2) / 70e9)
    expected = 4.0 / 3.0 * math.sqrt(0.00635) * modulus
    assert HertzContact.from_sphere(0.00635, STEEL, ALUMINIUM).stiffness == pytest.approx(expected, rel=1e-14)
    assert example_law("hertz").stiffness == pytest.approx(expected, rel=1e-14)
    assert HertzContact.from_geometry(modulus, 0.00635).stiffness == pytest.approx(expected, rel=1e-14)
    law = HertzContact(expected)
    assert law.force(2e-6, 5e-6) == pytest.approx(expected * 2e-6**1.5, rel=1e-14)


# -- Yigit–Christoforou -------------------------------------------------------------------------
def _yc_by_hand(alpha, alpha_max, hertz, yield_alpha):
    """Seed 001 eqs (4)–(6) transcribed literally (independent of the kernel)."""
    linear = 1.5 * hertz * math.sqrt(yield_alpha)
    if alpha <= 0:
        return 0.0
    if alpha >= alpha_max:
        if alpha <= yield_alpha:
            return hertz * alpha**1.5
        return linear * (alpha - yield_alpha) + hertz * yield_alpha**1.5
    if alpha_max <= yield_alpha:
        return hertz * alpha**1.5
    value = hertz * (alpha**1.5 - alpha_max**1.5 + yield_alpha**1.5) + linear * (alpha_max - yield_alpha)
    return max(value, 0.0)


def test_yigit_christoforou_equations():
    """The kernel reproduces eqs (4)–(6) at sample points of every phase (rel. 1e-12);
    α_f is the zero of eq (6); K_y = 1.5 K_h sqrt(α_y) (eq 10); α_y from eq (9)."""
    hertz, yield_alpha = 3.0e10, 2.0e-6
    law = YigitChristoforouContact(hertz, yield_alpha)
    for alpha_max in (0.0, 0.7e-6, 2.0e-6, 5e-6, 80e-6):
        for alpha in np.linspace(-1e-6, 100e-6, 77):
            expected = _yc_by_hand(alpha, alpha_max, hertz, yield_alpha)
            assert float(law.force(alpha, alpha_max)) == pytest.approx(expected, rel=1e-12, abs=1e-12 * hertz * 1e-9)
    final = float(law.permanent_indentation(80e-6))
    plastic_branch = hertz * (final**1.5 - 80e-6**1.5 + yield_alpha**1.5) + law.linearised_stiffness * (80e-6 - yield_alpha)
    assert abs(plastic_branch) < 1e-12 * float(law.loading_force(80e-6))
    assert float(law.linearised_stiffness) == pytest.approx(1.5 * hertz * math.sqrt(yield_alpha), rel=1e-15)
    modulus, radius, strength = 80e9, 0.01, 3e8
    assert float(yield_indentation(strength, radius, modulus)) == pytest.approx(
        0.68 * math.pi**2 * strength**2 * radius / modulus**2, rel=1e-15)
    built = YigitChristoforouContact.from_properties(modulus, radius, strength)
    assert float(built.hertz_stiffness) == pytest.approx(4 / 3 * math.sqrt(radius) * modulus, rel=1e-15)


def test_yigit_christoforou_continuity():
    """Force and stiffness are continuous at α_y (eq 5 is the Hertz tangent there; rel. 1e-8
    for a 1e-9 relative step, the jump being O(step)); between loading and unloading at
    α_m the change over a step 1e-9 α_m is no more than slope × step (a real jump would be
    O(F)); the unloading curve depends continuously on α_m across α_y."""
    law = YigitChristoforouContact(3.0e10, 2.0e-6)
    y = 2.0e-6
    eps = 1e-9
    assert float(law.loading_force(y * (1 + eps))) == pytest.approx(float(law.loading_force(y * (1 - eps))), rel=1e-8)
    assert float(law.tangent_stiffness(y * (1 + eps), y * (1 + eps))) == pytest.approx(
        float(law.tangent_stiffness(y * (1 - eps), y * (1 - eps))), rel=1e-8)
    for peak in (y * (1 + 1e-7), 3 * y, 500 * y):
        jump = float(law.force(peak * (1 - eps), peak)) - float(law.loading_force(peak))
        slope = float(law.tangent_stiffness(peak * (1 - eps), peak))
        assert abs(jump) <= 1.01 * eps * peak * slope  # no jump beyond the slope × step
    # unloading curve depends continuously on α_m across α_y
    assert float(law.force(0.5 * y, y * (1 + 1e-10))) == pytest.approx(float(law.force(0.5 * y, y)), rel=1e-6)


def test_yigit_christoforou_normalised_energies():
    """In units a = α/α_y, K_h α_y^{5/2}: loading work 2/5 + (a−1) + ¾(a−1)² (docs/physics_contract.md
    §2) and the unloading integral ∫ (a^{3/2} − a_f^{3/2}) da by quadrature (rel. 1e-10)."""
    law = YigitChristoforouContact(1.0, 1.0)
    for a in (1.5, 7.0, 300.0):
        assert float(law.loading_energy(a)) == pytest.approx(0.4 + (a - 1) + 0.75 * (a - 1) ** 2, rel=1e-14)
        af = float(law.permanent_indentation(a))
        integral = quad(lambda s: s**1.5 - af**1.5, af, a, epsabs=0, epsrel=1e-13)[0]
        assert float(law.recovered_energy(a)) == pytest.approx(integral, rel=1e-10)


# -- Stronge --------------------------------------------------------------------------------------
def test_stronge_continuity_coefficient_default():
    """κ = ln(2·84 − 1)/(3·2.8/(2·1.6) − 1) = ln 167 / 1.625 = 3.149534653794927 (the spec's
    "≈ 3.15"), exact to rounding."""
    kappa = float(stronge_continuity_coefficient())
    assert kappa == pytest.approx(math.log(167.0) / 1.625, rel=1e-15)
    assert kappa == pytest.approx(3.149534653794927, rel=1e-13)
    assert round(kappa, 2) == 3.15


def stronge_law():
    return StrongeContact(effective_modulus=1.1e11, radius=0.01, yield_strength=4e8)


def test_stronge_phase_boundaries_are_continuous():
    """Force and contact radius continuous at δ_y and δ_p (rel. 1e-8 for a 1e-9 step: the
    force slope jumps at δ_p, so the jump is O(step·slope ratio)); the force *tangent* is
    continuous at δ_y too (rel. 1e-6: the kernel's analytic stiffness on both sides), with
    F_y = (4/3)E* R^{1/2} δ_y^{3/2} and δ_y = R(π c_y Y/(2E*))²; the fully plastic branch
    is π R(2δ − δ_y) c_p Y; unloading meets loading at δ_m and equals
    (4/3) E* R_ℓ^{1/2} (δ − δ_r)^{3/2} with R_ℓ = 4E* a_m³/(3F_m)."""
    law = stronge_law()
    modulus, radius, strength = 1.1e11, 0.01, 4e8
    yield_delta = radius * (math.pi * 1.6 * strength / (2 * modulus)) ** 2
    assert float(law.yield_indentation) == pytest.approx(yield_delta, rel=1e-15)
    assert float(law.yield_force) == pytest.approx(4 / 3 * modulus * math.sqrt(radius) * yield_delta**1.5, rel=1e-15)
    eps = 1e-9
    for boundary in (float(law.yield_indentation), float(law.plastic_indentation)):
        below, above = boundary * (1 - eps), boundary * (1 + eps)
        assert float(law.loading_force(above)) == pytest.approx(float(law.loading_force(below)), rel=1e-8)
        assert float(law.loading_contact_radius(above)) == pytest.approx(
            float(law.loading_contact_radius(below)), rel=1e-8)
    slopes = law.tangent_stiffness(yield_delta * np.array([1 - eps, 1 + eps]), yield_delta * np.array([1 - eps, 1 + eps]))
    assert slopes[1] == pytest.approx(slopes[0], rel=1e-6)
    plastic_delta = float(law.plastic_indentation)
    assert float(law.loading_force(2 * plastic_delta)) == pytest.approx(
        math.pi * radius * (4 * plastic_delta - yield_delta) * 2.8 * strength, rel=1e-14)
    for peak in np.array([0.5, 1.0001, 3.0, 20.0, 84.0, 400.0]) * yield_delta:
        peak_force = float(law.loading_force(peak))
        a_m = float(law.loading_contact_radius(peak))
        deformed = 4 * modulus * a_m**3 / (3 * peak_force)
        residual = peak - 3 * peak_force / (4 * modulus * a_m)
        assert residual >= -1e-15 * peak
        assert float(law.unloading_radius(peak)) == pytest.approx(deformed, rel=1e-12)
        for delta in np.linspace(max(residual, 0.0), peak, 9)[1:]:
            expected = 4 / 3 * modulus * math.sqrt(deformed) * (delta - residual) ** 1.5
            assert float(law.force(delta, peak)) == pytest.approx(expected, rel=1e-10)
        jump = float(law.force(peak * (1 - eps), peak)) - peak_force
        assert abs(jump) <= 1.01 * eps * peak * float(law.tangent_stiffness(peak * (1 - eps), peak))


def test_stronge_elastic_plastic_branch_is_the_documented_area_law():
    """The elastic-plastic branch, transcribed from docs/contact_laws.rst independently of
    the kernel: A = ((x − 1 + τ)/τ)^n, F = F_y A(1 + ln A/κ), a² = R δ_y A, with n = sτ,
    s = 1.5κ/(1 + κ) and sτ ln(1 + (x_p − 1)/τ) = ln(2x_p − 1) (checked to 1e-13); at the
    defaults n = 1.15990, τ = 1.01879; A(x_p) = 2x_p − 1 (area continuous at δ_p, 1e-12);
    dF/dx = 3/2 at yield (tangent to Hertz, 1e-12)."""
    law = stronge_law()
    exponent, offset = (float(v) for v in law.area_law)
    kappa = float(law.continuity_coefficient)
    slope = 1.5 * kappa / (1 + kappa)
    assert exponent == pytest.approx(slope * offset, rel=1e-15)
    assert slope * offset * math.log1p(83.0 / offset) == pytest.approx(math.log(167.0), rel=1e-13)
    assert (round(exponent, 5), round(offset, 5)) == (1.1599, 1.01879)
    assert ((84.0 - 1 + offset) / offset) ** exponent == pytest.approx(167.0, rel=1e-12)
    assert exponent / offset * (1 + 1 / kappa) == pytest.approx(1.5, rel=1e-12)
    yield_delta, yield_force = float(law.yield_indentation), float(law.yield_force)
    for x in (1.0001, 1.7, 5.0, 16.65, 40.0, 83.9):
        area = ((x - 1 + offset) / offset) ** exponent
        assert float(law.loading_force(x * yield_delta)) == pytest.approx(
            yield_force * area * (1 + math.log(area) / kappa), rel=1e-13)
        assert float(law.loading_contact_radius(x * yield_delta)) == pytest.approx(
            math.sqrt(0.01 * yield_delta * area), rel=1e-13)


def test_stronge_keeps_the_contract_analytically():
    """The consistency conditions of docs/contact_laws.rst on a fine grid of the
    elastic-plastic branch (x = δ/δ_y from 1 to 84, 200 001 points), in units F_y, δ_y:
    f ≤ x^{3/2} (loading ≤ Hertz); df/dx ≤ (3/2) ā (never stiffer than the elastic
    unloading 2E*a); recovery f/ā ≤ x (δ_r ≥ 0); δ_r non-decreasing; the second
    derivative at yield, 0.647, below Hertz's 0.75 (so the curve leaves Hertz downwards);
    cycle dissipation ≥ 0 from the closed forms over 10⁻²–10⁴ δ_y (to 1e-14)."""
    law = stronge_law()
    exponent, offset = (float(v) for v in law.area_law)
    kappa = float(law.continuity_coefficient)
    x = np.linspace(1.0, 84.0, 200001)
    u = (x - 1 + offset) / offset
    area = u**exponent
    f = area * (1 + np.log(area) / kappa)
    df = exponent * area / (u * offset) * (1 + (1 + np.log(area)) / kappa)
    recovery = f / np.sqrt(area)
    assert np.all(f <= x**1.5 * (1 + 1e-14))
    assert np.all(df <= 1.5 * np.sqrt(area) * (1 + 1e-14))
    assert np.all(recovery <= x * (1 + 1e-14))
    assert np.all(np.diff(x - recovery) >= 0.0)
    slope = exponent / offset
    curvature = slope**2 * (exponent - 1) / exponent * (1 + 1 / kappa) + slope**2 / kappa
    assert curvature == pytest.approx(0.647, abs=1e-3) and curvature < 0.75
    peaks = np.geomspace(1e-2, 1e4, 2001) * float(law.yield_indentation)
    assert np.all(law.dissipated_energy(peaks) >= -1e-14 * law.loading_energy(peaks))
    assert np.all(law.permanent_indentation(peaks) >= 0.0)


def test_stronge_closed_form_energies_match_the_kernel():
    """Closed-form loading and recovered energies against adaptive quadrature of the
    kernel itself, split at δ_y, δ_p and δ_r (rel. 1e-10: quad's own accuracy on the
    x^{3/2} endpoint behaviour), from just past yield to 10⁴ δ_y."""
    law = stronge_law()
    params = law.kernel_parameters
    yield_delta, plastic_delta = float(law.yield_indentation), float(law.plastic_indentation)
    for ratio in (0.5, 1.0001, 1.6, 2.0, 10.0, 84.0, 300.0, 1e4):
        peak = ratio * yield_delta
        breaks = [b for b in (yield_delta, plastic_delta) if b < peak]
        edges = [0.0] + breaks + [peak]
        loading = sum(quad(lambda a: law.kernel(a, a, params)[0], lo, hi, epsabs=0, epsrel=1e-13, limit=200)[0]
                      for lo, hi in itertools.pairwise(edges))
        final = float(law.permanent_indentation(peak))
        recovered = quad(lambda a, m=peak: law.kernel(a, m, params)[0], final, peak, epsabs=0, epsrel=1e-13,
                         limit=200)[0]
        assert float(law.loading_energy(peak)) == pytest.approx(loading, rel=1e-10)
        assert float(law.recovered_energy(peak)) == pytest.approx(recovered, rel=1e-10)


def test_stronge_constants_that_break_the_contract_are_refused():
    """A fully plastic phase that starts too early lies above Hertz (its line
    k(2x − 1), k = 3c_p/(2c_y), crosses x^{3/2} at x = 26.6 with the defaults) or leaves an
    area law that cannot stay below it: δ_p/δ_y below 37.39 (defaults) is a ValueError
    naming plastic_indentation_ratio and its smallest valid value; 37.39 itself and the
    default 84 are accepted."""
    with pytest.raises(ValueError, match=r"plastic_indentation_ratio = 20\.0 .*valid range is \[37\.38"):
        StrongeContact(1e11, 0.01, 3e8, plastic_indentation_ratio=20.0)
    StrongeContact(1e11, 0.01, 3e8, plastic_indentation_ratio=37.39)
    with pytest.raises(ValueError, match="plastic_indentation_ratio"):
        StrongeContact(1e11, 0.01, 3e8, plastic_pressure_factor=6.0)


def test_printed_stronge_law_creates_energy_just_above_yield():
    """PROOF OF THE PRINTED FORM'S FLAW (the reason the package's law differs from it).

    The refined Stronge law as docs/physics_contract.md §2 printed it (tests/printed_stronge.py, never
    run by the package): its elastic-plastic loading curve is stiffer than Hertz at
    yield (tangent 2(1 + 1/κ) = 2.635 vs 1.5 F_y/δ_y) and lies above it up to
    16.65 δ_y; the elastic recovery 3F_m/(4E* a_m) exceeds δ_m, δ_r ≈ −(2/κ)(δ_m − δ_y)
    near yield, and a load–unload cycle to 2δ_y returns 1.308 times the work it absorbed.
    Dissipation is negative up to δ_m = 4.897 δ_y, the permanent indentation up to
    5.396 δ_y. On the issue-28 half-space (12.7 mm
    steel ball, E 200 GPa, ν 0.3, ρ 7850, on aluminium E 70 GPa, ν 0.33, Y 275 MPa) at
    2 V_y it rebounds with e = 1.158 and 15.11 N against Hertz's 12.18 N. Checked with
    independent quadratures of the kernel; the package's law on the same cases: e ≤ 1,
    δ_r ≥ 0, dissipation ≥ 0.
    """
    law = PrintedStrongeContact(effective_modulus=1.1e11, radius=0.01, yield_strength=4e8)
    yield_delta = float(law.yield_indentation)
    kappa = float(law.continuity_coefficient)
    slightly = yield_delta * (1 + 1e-4)
    assert float(law.signed_permanent_indentation(slightly)) == pytest.approx(
        -(2 / kappa) * (slightly - yield_delta), rel=1e-3)
    x = np.linspace(1.0001, 20.0, 20000)
    above = law.loading_force(x * yield_delta) > float(law.yield_force) * x**1.5
    assert np.all(above[x < 16.6]) and not np.any(above[x > 16.7])
    peak = 2.0 * yield_delta
    params = law.kernel_parameters
    loading = quad(lambda a: law.kernel(a, a, params)[0], 0, peak, points=[yield_delta], epsrel=1e-12)[0]
    recovered = quad(lambda a: law.kernel(a, peak, params)[0], 0, peak, epsrel=1e-12)[0]
    assert recovered / loading == pytest.approx(1.308, abs=1e-3)
    threshold = brentq(lambda r: float(law.dissipated_energy(r * yield_delta)), 2.0, 10.0, xtol=1e-10)
    assert threshold == pytest.approx(4.897382, rel=1e-5)
    # the spec said δ_r < 0 below 4.897 δ_y; δ_r is negative up to 5.396 δ_y (4.897 δ_y is
    # where the dissipation turns positive): docs/physics_contract.md §2 says so now
    negative_dent = brentq(lambda r: float(law.signed_permanent_indentation(r * yield_delta)), 2.0, 10.0, xtol=1e-10)
    assert negative_dent == pytest.approx(5.396, abs=1e-3)

    pair = ContactPair(float(effective_modulus(200e9, 0.3, 70e9, 0.33)), 0.00635, 275e6)
    mass = 7850.0 * 4 / 3 * math.pi * 0.00635**3
    printed = PrintedStrongeContact.from_contact_pair(pair)
    energy = 0.4 * float(printed.yield_force) * float(printed.yield_indentation)
    velocity = 2.0 * math.sqrt(2 * energy / mass)  # twice V_y
    assert velocity / 2 == pytest.approx(0.0214, abs=1e-4)
    result = halfspace_impact(printed, mass, velocity)
    hertz = float(hertz_peak_force(mass, velocity, hertz_stiffness(pair.effective_modulus, 0.00635)))
    assert result.restitution == pytest.approx(1.158, abs=1e-3)
    assert (result.peak_force, hertz) == (pytest.approx(15.11, abs=0.01), pytest.approx(12.18, abs=0.01))
    consistent = halfspace_impact(StrongeContact.from_contact_pair(pair), mass, velocity)
    assert consistent.restitution <= 1.0 and consistent.peak_force <= hertz


# -- sphere and law_for_sphere ------------------------------------------------------------------
def test_sphere_and_law_for_sphere():
    """Sphere mass ρ(4/3)πR³; α_y and K_y use the *softer* (smaller) yield strength (eq 9);
    "linear" is K_y (eq 18); a rigid target (E = inf) gives E* = E_i/(1 − ν_i²); the
    target's curvature enters through 1/R = 1/R1 + 1/R2."""
    assert BALL.mass == pytest.approx(7850.0 * 4 / 3 * math.pi * 0.00635**3, rel=1e-15)
    assert Sphere(0.01, STEEL, mass=2.0).mass == 2.0
    modulus = float(effective_modulus(210e9, 0.30, 70e9, 0.33))
    plastic = example_law("yigit-christoforou")
    assert float(plastic.yield_indentation) == pytest.approx(
        0.68 * math.pi**2 * 2.8e8**2 * 0.00635 / modulus**2, rel=1e-14)
    assert example_law("linear").stiffness == pytest.approx(float(plastic.linearised_stiffness), rel=1e-15)
    stronge = example_law("stronge")
    assert float(stronge.yield_strength) == 2.8e8 and float(stronge.effective_modulus) == pytest.approx(modulus)
    rigid = law_for_sphere("hertz", BALL, Material(np.inf, 0.0, 1.0))
    assert rigid.stiffness == pytest.approx(4 / 3 * math.sqrt(0.00635) * 210e9 / (1 - 0.09), rel=1e-14)
    curved = law_for_sphere("hertz", BALL, ALUMINIUM, target_radius=0.00635)
    assert curved.stiffness == pytest.approx(example_law("hertz").stiffness / math.sqrt(2), rel=1e-14)
    composite = law_for_sphere("yigit-christoforou", BALL, ALUMINIUM, yield_strength=1e8)
    assert float(composite.yield_indentation) < float(plastic.yield_indentation)
    custom = law_for_sphere("stronge", BALL, ALUMINIUM, plastic_pressure_factor=3.0)
    assert custom.plastic_pressure_factor == 3.0


# -- bad input ---------------------------------------------------------------------------------------
BAD_INPUT = [
    (lambda: HertzContact(0.0), "stiffness", "(0, inf)"),
    (lambda: HertzContact(-1.0), "stiffness", "-1.0"),
    (lambda: LinearContact(-5.0), "stiffness", "(0, inf)"),
    (lambda: YigitChristoforouContact(-1.0, 1e-6), "hertz_stiffness", "(0, inf)"),
    (lambda: YigitChristoforouContact(1e10, 0.0), "yield_indentation", "(0, inf)"),
    (lambda: YigitChristoforouContact(1e10, np.nan), "yield_indentation", "finite"),
    (lambda: yield_indentation(0.0, 0.01, 1e11), "yield_strength", "(0, inf)"),
    (lambda: yield_indentation(1e8, -0.01, 1e11), "radius", "(0, inf)"),
    (lambda: StrongeContact(1e11, 0.01, -3e8), "yield_strength", "(0, inf)"),
    (lambda: StrongeContact(1e11, 0.0, 3e8), "radius", "(0, inf)"),
    (lambda: StrongeContact(0.0, 0.01, 3e8), "effective_modulus", "(0, inf)"),
    (lambda: StrongeContact(1e11, 0.01, 3e8, plastic_indentation_ratio=0.5), "plastic_indentation_ratio", "(1, inf)"),
    (lambda: StrongeContact(1e11, 0.01, 3e8, plastic_pressure_factor=1.0), "plastic_pressure_factor", "inf)"),
    (lambda: Sphere(-0.01, STEEL), "radius", "(0, inf)"),
    (lambda: Sphere(0.01, STEEL, mass=0.0), "mass", "(0, inf)"),
    (lambda: Sphere(0.01, Material(210e9, 0.5, 7850.0)), "poisson_ratio", "(-1, 0.5)"),
    (lambda: Sphere(0.01, Material(210e9, -1.2, 7850.0)), "poisson_ratio", "(-1, 0.5)"),
    (lambda: Sphere(0.01, Material(-210e9, 0.3, 7850.0)), "youngs_modulus", "(0, inf)"),
    (lambda: Sphere(0.01, Material(210e9, 0.3, 0.0)), "density", "(0, inf)"),
    (lambda: Sphere(0.01, object()), "youngs_modulus", "material"),
    (lambda: law_for_sphere("hertz", BALL, Material(70e9, 0.7, 2700.0)), "poisson_ratio", "(-1, 0.5)"),
    (lambda: law_for_sphere("yigit-christoforou", Sphere(0.01, Material(210e9, 0.3, 7850.0)),
                            Material(70e9, 0.3, 2700.0)), "yield_strength", "(0, inf)"),
    (lambda: law_for_sphere("linear", Sphere(0.01, Material(210e9, 0.3, 7850.0)),
                            Material(70e9, 0.3, 2700.0)), "yield_strength", "missing"),
    (lambda: law_for_sphere("hertz", BALL, ALUMINIUM, yield_pressure_factor=2.0), "yield_pressure_factor", "valid"),
    (lambda: effective_modulus(210e9, 0.3, 70e9, 0.55), "poisson_ratio_2", "(-1, 0.5)"),
]


@pytest.mark.parametrize("build, parameter, detail", BAD_INPUT)
def test_bad_input_raises_value_error(build, parameter, detail):
    """Bad physical input is a ValueError naming the parameter, the value and the range."""
    with pytest.raises(ValueError) as info:
        build()
    message = str(info.value)
    assert parameter in message and detail in message
