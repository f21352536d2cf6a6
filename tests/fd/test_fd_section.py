"""Verification of the layered elastic-plastic section (impactmaps.fd.section).

Exact references: the closed-form moment–curvature of an elastic–perfectly plastic
rectangle, the midpoint-rule second moment ``I (1 − 1/(4 N_h²))``, the bilinear
stress–strain curve of linear kinematic hardening, and the exact discrete work identity
of the trapezoidal plastic work.
"""

from __future__ import annotations

import numpy as np
import pytest

from impactmaps.fd import LayeredSection, rectangular_moment_curvature, stress_update

# the seed-000 drop-test beam section (b = 60 mm, h = 27.8 mm) in structural steel
WIDTH, HEIGHT, MODULUS, YIELD = 0.06, 0.0278, 206e9, 235e6


def _section(n_half_layers=10, hardening=0.0):
    return LayeredSection(WIDTH, HEIGHT, MODULUS, YIELD, hardening, n_half_layers)


def test_closed_form_constants():
    """M_p = 1.5 M_y = σ_y b h²/4, κ_y = 2σ_y/(Eh) (definitions, exact)."""
    s = _section()
    assert s.plastic_moment == pytest.approx(1.5 * s.yield_moment, rel=1e-14)
    assert s.plastic_moment == pytest.approx(YIELD * WIDTH * HEIGHT**2 / 4, rel=1e-14)
    assert s.yield_curvature == pytest.approx(2 * YIELD / (MODULUS * HEIGHT), rel=1e-14)


@pytest.mark.parametrize("n_half_layers", [2, 3, 10, 40])
def test_elastic_slope_is_midpoint_second_moment(n_half_layers):
    """Below first yield M = −E I_h κ with I_h = I (1 − 1/(4N_h²)) exactly (each layer's
    midpoint rule misses b Δz³/12 of ∫z²); roundoff tolerance."""
    s = _section(n_half_layers)
    kappa = 0.5 * s.yield_curvature
    moment = s.moment_curvature([-kappa])[0]
    expected = MODULUS * s.second_moment * (1 - 1 / (4 * n_half_layers**2)) * kappa
    assert moment == pytest.approx(expected, rel=1e-12)
    assert s.layered_second_moment == pytest.approx(s.second_moment * (1 - 1 / (4 * n_half_layers**2)),
                                                    rel=1e-12)


def test_fully_plastic_asymptote_is_exact():
    """Once every layer has yielded (κ > 2N_h κ_y) M = σ_y b Σ|z_i|Δz = M_p exactly (|z| is
    linear in each layer, so the midpoint rule is exact); roundoff tolerance."""
    s = _section(8)
    kappa = 50 * s.yield_curvature
    assert s.moment_curvature(np.linspace(0, -kappa, 20))[-1] == pytest.approx(s.plastic_moment, rel=1e-12)


def test_moment_curvature_converges_to_closed_form_at_second_order():
    """Layered M(κ) → exact M = EIκ (κ ≤ κ_y), M_p(1 − (κ_y/κ)²/3) (κ > κ_y) on 0…10 κ_y.

    The max error over the curve, relative to M_p, is 4.4e-2, 1.1e-2, 2.7e-3, 6.6e-4,
    1.6e-4 for N_h = 2, 4, 8, 16, 32: observed order 2.0 (midpoint rule; the kink of the
    stress profile at the elastic-plastic interface does not lower the order because the
    error is dominated by the elastic core). Asserted: order in [1.8, 2.2] for every
    halving and error < 3e-3 at the default N_h = 10.
    """
    errors = []
    for n_half_layers in (2, 4, 8, 16, 32):
        s = _section(n_half_layers)
        kappa = np.linspace(0, 10 * s.yield_curvature, 2001)[1:]
        layered = s.moment_curvature(-kappa)
        exact = rectangular_moment_curvature(kappa, WIDTH, HEIGHT, MODULUS, YIELD)
        errors.append(np.max(np.abs(layered - exact)) / s.plastic_moment)
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all((orders > 1.8) & (orders < 2.2)), orders
    s = _section(10)
    kappa = np.linspace(0, 10 * s.yield_curvature, 2001)[1:]
    error10 = np.max(np.abs(s.moment_curvature(-kappa) - rectangular_moment_curvature(
        kappa, WIDTH, HEIGHT, MODULUS, YIELD))) / s.plastic_moment
    assert error10 < 3e-3


def test_closed_form_formula_itself():
    """Independent check of the reference: continuity at κ_y (M = M_y from both sides) and
    M → M_p as κ → ∞."""
    s = _section()
    ky = s.yield_curvature
    below = rectangular_moment_curvature(ky * (1 - 1e-12), WIDTH, HEIGHT, MODULUS, YIELD)
    above = rectangular_moment_curvature(ky * (1 + 1e-12), WIDTH, HEIGHT, MODULUS, YIELD)
    assert below == pytest.approx(s.yield_moment, rel=1e-9)
    assert above == pytest.approx(s.yield_moment, rel=1e-9)
    assert rectangular_moment_curvature(1e6 * ky, WIDTH, HEIGHT, MODULUS, YIELD) == pytest.approx(
        s.plastic_moment, rel=1e-10)


def test_elastic_unloading_and_residual_curvature():
    """Unloading from κ_m = 3κ_y is elastic (slope E I_h) down to M = 0, leaving the residual
    curvature κ_m − M(κ_m)/(E I_h): exact for the layered section as long as no layer
    reverse-yields (Δκ = M_m/EI ≤ 1.5κ_y < 2κ_y). Closed form for the exact section:
    κ_r = κ_m − M_p(1 − 1/27)/(EI), matched to the O(N_h⁻²) of the layering."""
    s = _section(20)
    ky = s.yield_curvature
    km = 3 * ky
    loading = np.linspace(0, -km, 50)
    m_peak = s.moment_curvature(loading)[-1]
    slope = MODULUS * s.layered_second_moment
    residual = -km + m_peak / slope  # w'' at M = 0
    path = np.concatenate([loading, np.linspace(-km, residual, 30)])
    moments = s.moment_curvature(path)
    unloading = moments[50:]
    np.testing.assert_allclose(np.diff(unloading) / np.diff(path[50:]), -slope, rtol=1e-9)
    assert abs(moments[-1]) < 1e-9 * s.plastic_moment
    exact_residual = km - s.plastic_moment * (1 - 1 / 27) / (MODULUS * s.second_moment)
    assert -residual == pytest.approx(exact_residual, rel=5e-3)


def test_kinematic_hardening_bilinear_and_bauschinger():
    """One layer under linear kinematic hardening (plastic modulus H): monotonic stress
    σ = σ_y + E_t(ε − ε_y), E_t = EH/(E+H) (exact for any increment size); on reversal it
    re-yields after a stress drop of exactly 2σ_y (Bauschinger). Roundoff tolerances."""
    hardening = 0.05 * MODULUS
    tangent = MODULUS * hardening / (MODULUS + hardening)
    strain_y = YIELD / MODULUS
    increments = np.concatenate([np.full(7, 3 * strain_y / 7), np.full(40, -6 * strain_y / 40)])
    stress, back, strain = 0.0, 0.0, 0.0
    history = []
    for d in increments:
        stress, back, _p, _w = (float(v) for v in stress_update(stress, back, d, MODULUS, YIELD, hardening))
        strain += d
        history.append((strain, stress))
    history = np.array(history)
    peak_stress = YIELD + tangent * (3 * strain_y - strain_y)
    assert history[6, 1] == pytest.approx(peak_stress, rel=1e-12)
    # reverse: elastic until σ = σ_peak − 2σ_y, then slope E_t again
    unloading = history[7:]
    elastic = unloading[:, 1] >= peak_stress - 2 * YIELD - 1e-6 * YIELD
    predicted = peak_stress + MODULUS * (unloading[elastic, 0] - 3 * strain_y)
    np.testing.assert_allclose(unloading[elastic, 1], predicted, rtol=1e-12, atol=1e-6)
    reverse = unloading[~elastic]
    assert reverse.shape[0] > 5
    np.testing.assert_allclose(np.diff(reverse[:, 1]) / np.diff(reverse[:, 0]), tangent, rtol=1e-9)


@pytest.mark.parametrize("hardening", [0.0, 0.02 * MODULUS])
def test_plastic_work_identity_is_exact(hardening):
    """For every increment ½(σ* + σ)Δε = Δ(σ²/2E) + ΔW_p (trapezoidal plastic work): the
    internal work splits into strain energy and plastic work with no discretisation
    error. Random increments up to 3 ε_y, random states; roundoff tolerance."""
    rng = np.random.default_rng(0)
    n = 5000
    back = rng.uniform(-0.5, 0.5, n) * YIELD * (hardening > 0)
    stress = back + rng.uniform(-1, 1, n) * YIELD
    increment = rng.uniform(-3, 3, n) * YIELD / MODULUS
    new_stress, new_back, plastic, work = stress_update(stress, back, increment, MODULUS, YIELD, hardening)
    lhs = 0.5 * (stress + new_stress) * increment
    rhs = (new_stress**2 - stress**2) / (2 * MODULUS) + work
    np.testing.assert_allclose(lhs, rhs, rtol=0, atol=1e-9 * YIELD**2 / MODULUS)
    assert np.all(np.abs(new_stress - new_back) <= YIELD * (1 + 1e-12))
    if hardening == 0.0:  # perfectly plastic: σ and Δε_p have the same sign, W_p never drops
        assert np.all(work >= 0.0)
    # (with kinematic hardening σ Δε_p < 0 is physical: reverse flow releases back-stress energy)


def test_section_update_tracks_plastic_work_per_length():
    """Curvature path 0 → 3κ_y, then a full cycle 3κ_y → −3κ_y → 3κ_y (elastic-perfectly
    plastic). The cycle ends in the same layer state it started from, so the plastic work
    per length accumulated over it equals the area of the M–κ hysteresis loop ∮(−M) dκ
    (trapezoidal on the fine path, 1e-3)."""
    s = _section(10)
    ky = s.yield_curvature
    loading = np.linspace(0, 3 * ky, 400)
    cycle = np.concatenate([np.linspace(3 * ky, -3 * ky, 800), np.linspace(-3 * ky, 3 * ky, 800)])
    state = s.initial_state(1)
    for kappa in loading:
        s.update(state, [kappa])
    work_before = state.plastic_work[0]
    stress_before = state.stress.copy()
    moments = np.array([s.update(state, [kappa])[0] for kappa in cycle])
    np.testing.assert_allclose(state.stress, stress_before, atol=1e-6 * YIELD)
    loop_area = -np.trapezoid(moments, cycle)
    dissipated = state.plastic_work[0] - work_before
    assert dissipated > 0
    assert dissipated == pytest.approx(loop_area, rel=1e-3)


@pytest.mark.parametrize(
    "kwargs, name",
    [
        (dict(yield_strength=0.0), "yield_strength"),
        (dict(yield_strength=-1e6), "yield_strength"),
        (dict(n_half_layers=1), "n_half_layers"),
        (dict(n_half_layers=2.5), "n_half_layers"),
        (dict(hardening_modulus=-1.0), "hardening_modulus"),
        (dict(width=0.0), "width"),
    ],
)
def test_bad_input_names_parameter(kwargs, name):
    """Invalid section data raise ValueError naming the parameter, its value and range."""
    base = dict(width=WIDTH, height=HEIGHT, youngs_modulus=MODULUS, yield_strength=YIELD)
    base.update(kwargs)
    with pytest.raises(ValueError, match=name) as info:
        LayeredSection(**base)
    message = str(info.value)
    assert repr(list(kwargs.values())[0]) in message or str(list(kwargs.values())[0]) in message
    assert "range" in message or "integer" in message
