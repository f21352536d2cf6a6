"""The 3D-consistent near field of isotropic Mindlin plates under the contact patch
(:mod:`impactmaps.targets.plates.near_field`; docs/contact_patch.rst). The comparison with the
3D FE (static compliance, impact peaks) is in ``tests/validation/test_fe_plates.py`` and
``tests/validation/test_fe_results.py``."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
import scipy.integrate

import impactmaps
from impactmaps.targets.plates import near_field

STEEL = impactmaps.material("structural-steel")
E, NU = 210e9, 0.3


def _layer_by_bvp(k, h):
    """Top-face deflection per unit pressure of a free layer, from the plane-strain Navier
    equations in displacement form (u = U(z) sin kx, w = W(z) cos kx) solved as a boundary
    value problem: independent of the Airy-function closed form."""
    lam = E * NU / ((1 + NU) * (1 - 2 * NU))
    mu = E / (2 * (1 + NU))
    c = h / 2

    def rhs(z, y):
        u, du, w, dw = y
        ddu = ((lam + 2 * mu) * k**2 * u + (lam + mu) * k * dw) / mu
        ddw = (mu * k**2 * w - (lam + mu) * k * du) / (lam + 2 * mu)
        return np.vstack([du, ddu, dw, ddw])

    def bc(bottom, top):  # no shear traction on both faces; σzz = −1 on the top, 0 below
        return np.array([bottom[1] - k * bottom[2], top[1] - k * top[2],
                         lam * k * bottom[0] + (lam + 2 * mu) * bottom[3],
                         lam * k * top[0] + (lam + 2 * mu) * top[3] + 1.0])

    z = np.linspace(-c, c, 401)
    sol = scipy.integrate.solve_bvp(rhs, bc, z, np.zeros((4, z.size)), tol=1e-10, max_nodes=200000)
    assert sol.success
    return -sol.sol(c)[2]  # downward deflection of the top face


@pytest.mark.parametrize("kh", [0.3, 1.0, 3.0, 8.0])
def test_layer_kernel_against_the_navier_equations(kh):
    h = 0.01
    k = kh / h
    expected = _layer_by_bvp(k, h) - 2 * (1 - NU**2) / (E * k)
    got = near_field.layer_excess_compliance(k, h, E, NU)
    assert got == pytest.approx(expected, rel=1e-6, abs=1e-9 * 2 * (1 - NU**2) / (E * k))


def test_layer_kernel_limits():
    """kh → 0: the Kirchhoff plate, ``(1/(D k⁴))(1 + (kh)²/5 − (kh)³/6 + …)`` (the last term is
    the half-space's, ``2(1 − ν²)/(E k)`` = ``(kh)³/6`` of ``1/(D k⁴)``); kh → ∞: nothing beyond the
    half-space (exponentially small), never negative, finite for any k."""
    h = 0.01
    d = E * h**3 / (12 * (1 - NU**2))
    for kh in (1e-3, 1e-2):
        k = kh / h
        ratio = near_field.layer_excess_compliance(k, h, E, NU) * d * k**4
        assert (ratio - 1 + kh**3 / 6) / kh**2 == pytest.approx(0.2, rel=1e-3)
    k = np.geomspace(1e-2, 1e6, 400) / h
    excess = near_field.layer_excess_compliance(k, h, E, NU)
    assert np.all(np.isfinite(excess)) and np.all(excess >= 0.0)
    assert excess[-1] == 0.0 and near_field.layer_excess_compliance(20 / h, h, E, NU) < 1e-15


def test_factor_bounds_and_where_it_applies():
    """ρ in (0, 1], decreasing, → 1 for kh → 0; 1 for Kirchhoff and non-isotropic plates."""
    mindlin = impactmaps.Plate.isotropic(0.2, 0.2, 0.01, STEEL, theory="mindlin")
    k = np.geomspace(1e-3, 30, 200) / 0.01
    rho = near_field.near_field_factor(mindlin, k)
    assert np.all(rho > 0) and np.all(rho <= 1) and np.all(np.diff(rho) < 0)
    assert rho[0] == pytest.approx(1.0, abs=1e-6)
    kirchhoff = impactmaps.Plate.isotropic(0.2, 0.2, 0.01, STEEL, theory="kirchhoff")
    assert np.all(near_field.near_field_factor(kirchhoff, k) == 1.0)
    orthotropic = impactmaps.Plate(**{**mindlin.__dict__, "D22": 0.5 * mindlin.D22})
    assert near_field.isotropic_constants(orthotropic) is None
    assert np.all(near_field.near_field_factor(orthotropic, k) == 1.0)
    got = near_field.isotropic_constants(mindlin)
    assert got == pytest.approx((E, NU), rel=1e-12)


def test_flexural_wavenumber_inverts_the_navier_frequencies():
    """On an SSSS Mindlin plate the flexural branch's frequency of (m, n) gives back
    k = hypot(mπ/a, nπ/b)."""
    plate = impactmaps.Plate.isotropic(0.3, 0.2, 0.02, STEEL, theory="mindlin")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        omega = np.asarray(plate.modes(0.0, min_modes=1).frequencies)[0]
    k = math.hypot(math.pi / 0.3, math.pi / 0.2)
    assert near_field.flexural_wavenumber(plate, omega) == pytest.approx(k, rel=1e-9)


@pytest.mark.parametrize("edges", ["SSSS", pytest.param("CCCC", marks=pytest.mark.slow)])
def test_patch_compliance_converges_with_the_basis(edges):
    """Retained + residual under the patch does not depend on the cut-off (the reason the
    patch exists) and is below the Mindlin patch model's (the near field removed)."""
    plate = impactmaps.Plate.isotropic(0.2, 0.2, 0.01, STEEL, theory="mindlin", edges=edges)
    values = []
    for cutoff in (1e6, 4e6):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            basis = plate.modes(cutoff, contact_radius=7e-4)
        assert basis.residual_compliance > 0.0
        values.append(basis.retained_compliance + basis.residual_compliance)
    assert values[0] == pytest.approx(values[1], rel=1e-4)
