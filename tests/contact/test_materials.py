"""Materials: isotropic solids, plies, laminates by classical lamination theory, catalogue.

Most checks compare CLT with closed-form hand results; these are exact up to floating
point round-off, so the tolerances are a few hundred ulps (rtol 1e-12) unless stated.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from impactmaps.contact.base import effective_modulus
from impactmaps.materials import (
    CATALOGUE,
    DEFAULT_PLY_THICKNESS,
    IsotropicMaterial,
    Laminate,
    Ply,
    available_materials,
    material,
)

RTOL = 1e-12

STEEL = IsotropicMaterial(210e9, 0.3, 7850.0, yield_strength=235e6, name="steel")
CARBON = Ply(
    longitudinal_modulus=126e9, transverse_modulus=11e9, shear_modulus=6.6e9,
    poisson_ratio=0.28, density=1600.0, thickness=0.125e-3,
    transverse_shear_modulus_13=6.6e9, transverse_shear_modulus_23=3.9e9,
)


def _q(ply: Ply):
    """Hand reduced stiffness (Q11, Q22, Q12, Q66) of a ply."""
    nu21 = ply.poisson_ratio * ply.transverse_modulus / ply.longitudinal_modulus
    den = 1 - ply.poisson_ratio * nu21
    return (ply.longitudinal_modulus / den, ply.transverse_modulus / den,
            ply.poisson_ratio * ply.transverse_modulus / den, ply.shear_modulus)


# -- isotropic material ---------------------------------------------------------------
def test_isotropic_derived_moduli():
    """G = E/(2(1+ν)) and the plate modulus E/(1−ν²), by definition."""
    assert STEEL.shear_modulus == pytest.approx(210e9 / 2.6, rel=RTOL)
    assert STEEL.plate_bending_modulus == pytest.approx(210e9 / 0.91, rel=RTOL)


@pytest.mark.parametrize(
    "kwargs, parameter",
    [
        (dict(youngs_modulus=-1.0, poisson_ratio=0.3, density=7850.0), "youngs_modulus"),
        (dict(youngs_modulus=0.0, poisson_ratio=0.3, density=7850.0), "youngs_modulus"),
        (dict(youngs_modulus=1e9, poisson_ratio=0.5, density=7850.0), "poisson_ratio"),
        (dict(youngs_modulus=1e9, poisson_ratio=0.7, density=7850.0), "poisson_ratio"),
        (dict(youngs_modulus=1e9, poisson_ratio=-1.0, density=7850.0), "poisson_ratio"),
        (dict(youngs_modulus=1e9, poisson_ratio=0.3, density=0.0), "density"),
        (dict(youngs_modulus=1e9, poisson_ratio=0.3, density=np.nan), "density"),
        (dict(youngs_modulus=1e9, poisson_ratio=0.3, density=1.0, yield_strength=-5.0),
         "yield_strength"),
        (dict(youngs_modulus=[1e9, 2e9], poisson_ratio=0.3, density=1.0), "youngs_modulus"),
    ],
)
def test_isotropic_rejects_bad_input(kwargs, parameter):
    """Invalid constants raise ValueError naming the parameter."""
    with pytest.raises(ValueError, match=parameter):
        IsotropicMaterial(**kwargs)


def test_materials_are_frozen():
    """Frozen dataclasses: no silent mutation of a material shared between targets."""
    with pytest.raises(dataclasses.FrozenInstanceError):
        STEEL.youngs_modulus = 1.0
    laminate = Laminate.from_layup(CARBON, [0, 90])
    with pytest.raises(ValueError):
        laminate.D[0, 0] = 0.0  # cached matrices are read-only


# -- ply ---------------------------------------------------------------------------------
def test_ply_defaults_and_validation():
    """G13, G23 default to G12; thickness defaults to 0.125 mm; bad constants rejected."""
    ply = Ply(120e9, 7.9e9, 5.5e9, 0.3, 1580.0)
    assert ply.thickness == DEFAULT_PLY_THICKNESS == 0.125e-3
    assert ply.transverse_shear_modulus_13 == ply.transverse_shear_modulus_23 == 5.5e9
    assert ply.minor_poisson_ratio == pytest.approx(0.3 * 7.9 / 120, rel=RTOL)
    # |ν12| < sqrt(E1/E2) is the positive-definiteness limit
    limit = math.sqrt(120 / 7.9)
    Ply(120e9, 7.9e9, 5.5e9, 0.999 * limit, 1580.0)
    with pytest.raises(ValueError, match="poisson_ratio"):
        Ply(120e9, 7.9e9, 5.5e9, limit, 1580.0)
    with pytest.raises(ValueError, match="thickness"):
        Ply(120e9, 7.9e9, 5.5e9, 0.3, 1580.0, thickness=0.0)
    with pytest.raises(ValueError, match="transverse_shear_modulus_23"):
        Ply(120e9, 7.9e9, 5.5e9, 0.3, 1580.0, transverse_shear_modulus_23=-1.0)
    with pytest.raises(ValueError, match="angle_deg"):
        Ply(120e9, 7.9e9, 5.5e9, 0.3, 1580.0, angle_deg=np.inf)


@pytest.mark.parametrize("angle", [0.0, 15.0, 30.0, 45.0, 60.0, 90.0, -37.0, 123.0])
def test_transformed_stiffness_matches_tensor_rotation(angle):
    """Q̄ (closed-form Jones eq. 2.85) equals T_σ⁻¹ Q T_ε (rotation of stress and strain).

    Two independent constructions of the same matrix; round-off only.
    """
    ply = CARBON.rotated(angle)
    t = math.radians(angle)
    m, n = math.cos(t), math.sin(t)
    stress = np.array([[m * m, n * n, 2 * m * n], [n * n, m * m, -2 * m * n],
                       [-m * n, m * n, m * m - n * n]])
    strain = np.array([[m * m, n * n, m * n], [n * n, m * m, -m * n],
                       [-2 * m * n, 2 * m * n, m * m - n * n]])
    expected = np.linalg.solve(stress, ply.reduced_stiffness @ strain)
    scale = ply.reduced_stiffness[0, 0]
    np.testing.assert_allclose(ply.transformed_reduced_stiffness, expected,
                               rtol=0, atol=1e-13 * scale)


def test_isotropic_ply_is_rotation_invariant():
    """An isotropic ply has the same Q̄ and transverse shear at every angle."""
    ply = STEEL.as_ply(1e-3)
    assert ply.is_isotropic and not CARBON.is_isotropic
    for angle in (17.0, 45.0, 90.0):
        rotated = ply.rotated(angle)
        np.testing.assert_allclose(rotated.transformed_reduced_stiffness,
                                   ply.transformed_reduced_stiffness, rtol=0,
                                   atol=1e-12 * ply.reduced_stiffness[0, 0])
        np.testing.assert_allclose(rotated.transverse_shear_stiffness,
                                   ply.transverse_shear_stiffness, rtol=RTOL, atol=1e-6)


# -- laminates: hand results ---------------------------------------------------------------
def test_single_isotropic_ply_gives_plate_formulas():
    """One isotropic ply of thickness h: A = E h/(1−ν²)[..], D = E h³/(12(1−ν²))[..], B = 0.

    D12 = ν D, D66 = (1−ν)D/2, A44 = A55 = G h, rotary inertia ρh³/12, D* = D.
    """
    h = 7e-3
    lam = Laminate.from_isotropic(STEEL, h)
    e, nu = STEEL.youngs_modulus, STEEL.poisson_ratio
    d = e * h**3 / (12 * (1 - nu**2))
    np.testing.assert_allclose(lam.D, d * np.array([[1, nu, 0], [nu, 1, 0], [0, 0, (1 - nu) / 2]]),
                               rtol=RTOL, atol=1e-12 * d)
    np.testing.assert_allclose(lam.A, e * h / (1 - nu**2)
                               * np.array([[1, nu, 0], [nu, 1, 0], [0, 0, (1 - nu) / 2]]),
                               rtol=RTOL, atol=1e-3)
    np.testing.assert_array_equal(lam.B, np.zeros((3, 3)))
    assert lam.A44 == pytest.approx(STEEL.shear_modulus * h, rel=RTOL)
    assert lam.A55 == pytest.approx(STEEL.shear_modulus * h, rel=RTOL)
    assert lam.mass_per_area == pytest.approx(7850 * h, rel=RTOL)
    assert lam.rotary_inertia_per_area == pytest.approx(7850 * h**3 / 12, rel=RTOL)
    assert lam.effective_bending_stiffness == pytest.approx(d, rel=RTOL)
    assert lam.is_specially_orthotropic
    assert lam.yield_strength == STEEL.yield_strength


def test_cross_ply_symmetric_hand_result():
    """[0/90]s with ply thickness t (z = −2t…2t): exact CLT sums.

    D11 = (14 Q11 + 2 Q22) t³/3, D22 = (14 Q22 + 2 Q11) t³/3, D12 = Q12 h³/12,
    D66 = Q66 h³/12, D16 = D26 = 0, B = 0, A11 = 2(Q11 + Q22) t.
    """
    t = CARBON.thickness
    lam = Laminate.from_layup(CARBON, [0, 90])
    assert lam.angles_deg == (0.0, 90.0, 90.0, 0.0)
    q11, q22, q12, q66 = _q(CARBON)
    h = 4 * t
    assert lam.thickness == pytest.approx(h, rel=RTOL)
    assert lam.D11 == pytest.approx((14 * q11 + 2 * q22) * t**3 / 3, rel=RTOL)
    assert lam.D22 == pytest.approx((14 * q22 + 2 * q11) * t**3 / 3, rel=RTOL)
    assert lam.D12 == pytest.approx(q12 * h**3 / 12, rel=RTOL)
    assert lam.D66 == pytest.approx(q66 * h**3 / 12, rel=RTOL)
    assert lam.A[0, 0] == pytest.approx(2 * (q11 + q22) * t, rel=RTOL)
    assert abs(lam.D[0, 2]) < 1e-14 * lam.D11 and abs(lam.D[1, 2]) < 1e-14 * lam.D11
    assert np.max(np.abs(lam.B)) < 1e-14 * math.sqrt(lam.A[0, 0] * lam.D11)
    assert lam.is_specially_orthotropic
    # transverse shear: 0° plies give G23 to y–z and G13 to x–z, 90° plies the reverse
    g13, g23 = CARBON.transverse_shear_modulus_13, CARBON.transverse_shear_modulus_23
    assert lam.A44 == pytest.approx(2 * t * (g23 + g13), rel=RTOL)
    assert lam.A55 == pytest.approx(2 * t * (g13 + g23), rel=RTOL)
    assert abs(lam.A45) < 1e-12 * lam.A44


def test_balanced_symmetric_angle_ply_has_bending_twisting_coupling():
    """[45/−45]s: B = 0 but D16 = D26 = 4 Q̄16(45°) t³ with Q̄16(45°) = (Q11 − Q22)/4 ≠ 0.

    So a balanced symmetric angle ply is *not* specially orthotropic in bending.
    """
    t = CARBON.thickness
    lam = Laminate.from_layup(CARBON, [45, -45])
    q11, q22, _, _ = _q(CARBON)
    expected = 4 * (q11 - q22) / 4 * t**3
    assert lam.D[0, 2] == pytest.approx(expected, rel=1e-11)
    assert lam.D[1, 2] == pytest.approx(expected, rel=1e-11)
    assert np.max(np.abs(lam.B)) < 1e-14 * math.sqrt(lam.A[0, 0] * lam.D11)
    assert not lam.is_specially_orthotropic
    assert lam.coupling_ratios()["D16"] > 0.1
    # transverse shear of ±45 plies: A45 = Σ (G13 − G23) m n t cancels in a balanced stack
    assert abs(lam.A45) < 1e-12 * lam.A44
    assert lam.A44 == pytest.approx(lam.A55, rel=RTOL)


def test_antisymmetric_angle_ply_has_coupling_B():
    """[45/−45] (two plies, not mirrored): B16 = B26 = −t² Q̄16(45°), D16 = D26 = 0.

    B = ½ Σ Q̄_k (z_k² − z_{k−1}²) with the +45 ply on z ∈ [−t, 0].
    """
    t = CARBON.thickness
    lam = Laminate.from_layup(CARBON, [45, -45], symmetric=False)
    q11, q22, _, _ = _q(CARBON)
    qbar16 = (q11 - q22) / 4
    assert lam.B[0, 2] == pytest.approx(-t**2 * qbar16, rel=1e-11)
    assert lam.B[1, 2] == pytest.approx(-t**2 * qbar16, rel=1e-11)
    assert abs(lam.D[0, 2]) < 1e-12 * lam.D11
    assert not lam.is_specially_orthotropic
    assert lam.coupling_ratios()["B"] > 0.01


def test_angle_ply_transverse_shear_rotation():
    """One 45° ply with G13 ≠ G23: A44 = A55 = (G13 + G23) t/2, A45 = (G13 − G23) t/2."""
    t = CARBON.thickness
    g13, g23 = CARBON.transverse_shear_modulus_13, CARBON.transverse_shear_modulus_23
    lam = Laminate((CARBON.rotated(45),))
    assert lam.A44 == pytest.approx((g13 + g23) * t / 2, rel=RTOL)
    assert lam.A55 == pytest.approx((g13 + g23) * t / 2, rel=RTOL)
    assert lam.A45 == pytest.approx((g13 - g23) * t / 2, rel=RTOL)
    assert not lam.is_specially_orthotropic  # A45 ≠ 0 is not in seed 001's equations
    zero = Laminate((CARBON,))
    assert zero.A44 == pytest.approx(g23 * t, rel=RTOL)
    assert zero.A55 == pytest.approx(g13 * t, rel=RTOL)


def test_mass_and_rotary_inertia():
    """ρh = Σ ρ_k t_k and I = Σ ρ_k (z_k³ − z_{k−1}³)/3: homogeneous → ρh³/12; two materials by hand."""
    lam = Laminate.from_layup(CARBON, [0, 45, -45, 90])  # 8 plies, one density
    h = 8 * CARBON.thickness
    assert lam.mass_per_area == pytest.approx(1600 * h, rel=RTOL)
    assert lam.rotary_inertia_per_area == pytest.approx(1600 * h**3 / 12, rel=RTOL)
    assert lam.density == pytest.approx(1600, rel=RTOL)
    # sandwich-like: steel skins 1 mm, light core 4 mm (ρ = 100): hand integral
    skin = STEEL.as_ply(1e-3)
    core = IsotropicMaterial(1e9, 0.3, 100.0).as_ply(4e-3)
    sandwich = Laminate((skin, core, skin))
    np.testing.assert_allclose(sandwich.interfaces, [-3e-3, -2e-3, 2e-3, 3e-3], atol=1e-18)
    assert sandwich.mass_per_area == pytest.approx(2 * 7850e-3 + 100 * 4e-3, rel=RTOL)
    expected = 2 * 7850 * ((3e-3) ** 3 - (2e-3) ** 3) / 3 + 100 * 2 * (2e-3) ** 3 / 3
    assert sandwich.rotary_inertia_per_area == pytest.approx(expected, rel=RTOL)


def test_effective_bending_stiffness_formula():
    """D* = ½(D12 + 2 D66 + sqrt(D11 D22)) (seed 001 eq 31) from the laminate's own D."""
    lam = Laminate.from_layup(CARBON, [0, 90, 0])
    d = lam.D
    expected = 0.5 * (d[0, 1] + 2 * d[2, 2] + math.sqrt(d[0, 0] * d[1, 1]))
    assert lam.effective_bending_stiffness == pytest.approx(expected, rel=RTOL)


def test_from_layup_and_validation():
    """Symmetric mirroring, ply angle overridden, bad stacks rejected."""
    lam = Laminate.from_layup(CARBON.rotated(30), [0, 90, 45], symmetric=True)
    assert lam.angles_deg == (0, 90, 45, 45, 90, 0)
    lam = Laminate.from_layup(CARBON, [10, 20], symmetric=False, name="x")
    assert lam.angles_deg == (10, 20) and lam.name == "x"
    with pytest.raises(ValueError, match="plies"):
        Laminate(())
    with pytest.raises(ValueError, match="plies"):
        Laminate((CARBON, STEEL))
    with pytest.raises(ValueError, match="angles_deg"):
        Laminate.from_layup(CARBON, [])
    with pytest.raises(ValueError, match="yield_strength"):
        Laminate((CARBON,), yield_strength=0.0)


# -- contact properties ------------------------------------------------------------------
def test_laminate_contact_modulus_is_top_ply_transverse_modulus():
    """Composite struck face: E = E2 of plies[0], ν = 0, so 1/E* = (1−ν_s²)/E_s + 1/E2.

    (Tan & Sun's laminate contact law.) The back-face ply does not matter.
    """
    other = dataclasses.replace(CARBON, transverse_modulus=8e9)
    lam = Laminate((CARBON.rotated(0), other.rotated(90), other.rotated(0)))
    assert lam.youngs_modulus == CARBON.transverse_modulus
    assert lam.poisson_ratio == 0.0
    assert lam.yield_strength is None
    e_star = effective_modulus(210e9, 0.3, lam.youngs_modulus, lam.poisson_ratio)
    assert e_star == pytest.approx(1 / ((1 - 0.09) / 210e9 + 1 / 11e9), rel=RTOL)
    flipped = Laminate(tuple(reversed(lam.plies)))
    assert flipped.youngs_modulus == 8e9


def test_laminate_works_as_hertz_target_material():
    """Duck typing with the contact laws: K_h = (4/3) sqrt(R) / ((1−ν_s²)/E_s + 1/E2)."""
    from impactmaps.contact.hertz import HertzContact

    lam = Laminate.from_layup(CARBON, [0, 90, 0])
    radius = 6.35e-3
    law = HertzContact.from_sphere(radius, STEEL, lam)
    expected = 4 / 3 * math.sqrt(radius) / ((1 - 0.09) / 210e9 + 1 / 11e9)
    assert float(law.stiffness) == pytest.approx(expected, rel=RTOL)


def test_isotropic_laminate_contact_uses_its_own_poisson_ratio():
    """A one-ply isotropic laminate is contacted like the isotropic solid (E, ν)."""
    lam = Laminate.from_isotropic(STEEL, 5e-3)
    assert lam.youngs_modulus == STEEL.youngs_modulus
    assert lam.poisson_ratio == STEEL.poisson_ratio


# -- catalogue ----------------------------------------------------------------------------
def test_catalogue_contents():
    """The four catalogue entries and their documented values."""
    assert available_materials() == ("aluminium-6061-t6", "as4-3501-6", "structural-steel",
                                     "t300-934")
    steel = material("structural-steel")
    assert isinstance(steel, IsotropicMaterial)
    assert (steel.youngs_modulus, steel.poisson_ratio, steel.density,
            steel.yield_strength) == (210e9, 0.30, 7850.0, 235e6)
    aluminium = material("aluminium-6061-t6")
    assert (aluminium.youngs_modulus, aluminium.poisson_ratio, aluminium.density,
            aluminium.yield_strength) == (68.9e9, 0.33, 2700.0, 276e6)
    t300 = material("t300-934")
    assert (t300.longitudinal_modulus, t300.transverse_modulus, t300.shear_modulus,
            t300.poisson_ratio, t300.density) == (120e9, 7.9e9, 5.5e9, 0.30, 1580.0)
    as4 = material("as4-3501-6")
    assert (as4.longitudinal_modulus, as4.transverse_modulus, as4.shear_modulus,
            as4.poisson_ratio) == (126e9, 11e9, 6.6e9, 0.28)
    for name in ("t300-934", "as4-3501-6"):
        assert CATALOGUE[name].thickness == DEFAULT_PLY_THICKNESS


def test_unknown_catalogue_name_lists_known_names():
    """Unknown name → ValueError listing every known name (no silent default)."""
    with pytest.raises(ValueError) as info:
        material("unobtainium")
    message = str(info.value)
    assert "unobtainium" in message
    for name in available_materials():
        assert name in message
