"""Mindlin and laminated plates with any edges: the general Ritz basis (impactmaps.targets.plates.plate_general).

Invariants of issue 39: SSSS through the general basis equals Navier; frequencies fall
monotonically as the basis grows; a thin Mindlin plate tends to Kirchhoff; the symmetry
classes partition the spectrum; the specially orthotropic SSSS plate keeps its Navier
modes; unsymmetric laminates are refused by name.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import replace

import numpy as np
import pytest

from impactmaps.materials import Laminate, material
from impactmaps.targets.plates import plate_any_edges, plate_general, plate_navier, ritz
from impactmaps.targets.patch import hertz_transform
from impactmaps.targets.plates.plate import Plate

from ..helpers import case_text

ALUMINIUM = material("aluminium-6061-t6")
PLY = material("as4-3501-6")


def _orthotropic(theory="mindlin", edges="SSSS", thickness=0.015, **kwargs):
    """A 0.3 m × 0.2 m cross-ply-like plate (a/h = 20 by default), no couplings unless given."""
    lam = Laminate.from_layup(PLY, [0, 90, 0, 90])
    scale = (thickness / lam.thickness) ** 3
    return Plate(0.3, 0.2, thickness, lam.D11 * scale, lam.D22 * scale, lam.D12 * scale, lam.D66 * scale,
                 lam.A44 * thickness / lam.thickness, lam.A55 * thickness / lam.thickness,
                 lam.density * thickness, lam.density * thickness**3 / 12.0, theory=theory, edges=edges,
                 **kwargs)


def _quasi_isotropic(theory="mindlin", edges="CCCC", length_x=0.125, length_y=0.075):
    return Plate.from_laminate(length_x, length_y, Laminate.from_layup(PLY, [45, 0, -45, 90] * 2),
                               theory=theory, edges=edges)


def test_ssss_through_the_general_basis_equals_navier():
    """The general basis with SSSS edges and no couplings reproduces the Navier Mindlin
    frequencies (the 10 lowest, 1e-8) and, under a Hertz patch, the Navier participations
    φ T(k a) (1e-6; the disc quadrature against the closed-form transform)."""
    plate = _orthotropic(impact_point=(0.11, 0.07))
    top = 2.0 * float(plate_navier.navier_frequencies(plate, 4, 4))
    result = plate_general.solve_general_plate(*plate_any_edges._inputs(plate), 20, 20, top)
    m, n, omega, amplitude, _ = plate_navier._lowest_modes(plate, 0.0, 10)
    assert result.frequencies[:10] == pytest.approx(omega, rel=1e-8)
    radius = 0.004
    general = np.abs(plate_any_edges.patch_weights(result, np.array(plate.impact_point), radius, 10))
    x0, y0 = plate.impact_point
    navier = np.abs(amplitude * np.sin(m * math.pi * x0 / 0.3) * np.sin(n * math.pi * y0 / 0.2)
                    * hertz_transform(np.hypot(m * math.pi / 0.3, n * math.pi / 0.2) * radius))
    assert general == pytest.approx(navier, rel=1e-6, abs=1e-9 * navier.max())


def test_specially_orthotropic_ssss_laminate_keeps_its_navier_modes():
    """A cross-ply laminate has D16 = D26 = A45 = 0 (to round-off): from_laminate sets them
    to exactly 0 and the SSSS plate keeps its Navier modes, bit for bit."""
    lam = Laminate.from_layup(PLY, [0, 90, 0, 90])
    plate = Plate.from_laminate(0.3, 0.2, lam, theory="mindlin")
    assert (plate.D16, plate.D26, plate.A45) == (0.0, 0.0, 0.0)
    assert plate.uses_navier and not plate.bounded_modes
    old = Plate(0.3, 0.2, lam.thickness, lam.D11, lam.D22, lam.D12, lam.D66, lam.A44, lam.A55,
                lam.mass_per_area, lam.rotary_inertia_per_area, theory="mindlin")
    assert np.array_equal(plate.modes(1e5).frequencies, old.modes(1e5).frequencies)
    assert np.array_equal(plate.natural_frequencies_hz(8), old.natural_frequencies_hz(8))


def test_quasi_isotropic_laminate_keeps_its_bending_twisting_coupling():
    """[45/0/−45/90]2s: D16, D26 are kept (no warning, no silent drop) and the plate goes to
    the general basis; leaving them out raises the frequencies (the coupling softens)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        plate = _quasi_isotropic()
    assert plate.D16 > 0 and plate.D26 > 0 and not plate.uses_navier
    coupled = plate.natural_frequencies_hz(6)
    uncoupled = replace(plate, D16=0.0, D26=0.0).natural_frequencies_hz(6)
    assert np.all(coupled < uncoupled)


def test_unsymmetric_laminate_is_refused_naming_the_coupling():
    lam = Laminate.from_layup(PLY, [0, 90], symmetric=False)
    with pytest.raises(ValueError, match="unsymmetric.*extension–bending"):
        Plate.from_laminate(0.2, 0.2, lam)


def test_indefinite_bending_stiffness_is_refused():
    plate = _orthotropic()
    with pytest.raises(ValueError, match="D16"):
        replace(plate, D16=2.0 * math.sqrt(plate.D11 * plate.D66))


@pytest.mark.parametrize("theory", ["mindlin", "kirchhoff"])
def test_frequencies_fall_monotonically_as_the_basis_grows(theory):
    """Nested polynomial spaces: every Ritz frequency is non-increasing in the basis size
    (clamped quasi-isotropic laminate with D16, D26, full basis)."""
    plate = _quasi_isotropic(theory)
    previous = None
    for n in (10, 14, 18, 22):
        result = plate_general.solve_general_plate(*plate_any_edges._inputs(plate), n, n, 1e5)
        current = result.frequencies[:8]
        assert current.size == 8
        if previous is not None:
            assert np.all(current <= previous * (1.0 + 1e-12))
        previous = current


def test_symmetry_classes_partition_the_spectrum():
    """The classes of a symmetric plate struck at the centre together hold every mode of the
    full basis (with D16/D26: two classes; without: four)."""
    for plate in (_quasi_isotropic(), replace(_quasi_isotropic(), D16=0.0, D26=0.0)):
        groups = plate_any_edges.class_groups(plate)
        assert len(groups) == (2 if plate.D16 else 4)
        inputs = plate_any_edges._inputs(plate)
        full = plate_general.solve_general_plate(*inputs, 14, 14, 4e4).frequencies
        parts = np.sort(np.concatenate([plate_general.solve_general_plate(*inputs, 14, 14, 4e4, g).frequencies
                                        for g in groups]))
        assert parts[parts <= 4e4] == pytest.approx(full, rel=1e-9)


def test_general_kirchhoff_basis_equals_the_kirchhoff_ritz_basis():
    """Without couplings the general Kirchhoff basis is the Ritz basis of ritz.py (same
    polynomials, same energy)."""
    plate = _orthotropic("kirchhoff", "CSCF", thickness=0.004)
    args = (plate.length_x, plate.length_y, plate.D11, plate.D22, plate.D12, plate.D66, plate.mass_per_area)
    reference = ritz.solve_ritz_plate(*args, "CSCF", 16, 16).frequencies[:20]
    general = plate_general.solve_general_plate(*plate_any_edges._inputs(plate), 16, 16, 1e12).frequencies[:20]
    assert general == pytest.approx(reference, rel=1e-10)


def test_thin_mindlin_plate_tends_to_kirchhoff():
    """Clamped 0.3 × 0.2 m plate: the Mindlin frequencies approach the Kirchhoff ones as
    a/h → ∞, the difference falling as (h/a)² (a/h = 500 → 1000: a factor 4 ± 10 %), and at
    a/h = 1000 it is below 1e-4 for the 8 lowest modes (the basis does not lock)."""
    differences = []
    for thickness in (0.0006, 0.0003):
        mindlin = Plate.isotropic(0.3, 0.2, thickness, ALUMINIUM, theory="mindlin", edges="CCCC")
        kirchhoff = replace(mindlin, theory="kirchhoff")
        ratio = mindlin.natural_frequencies_hz(8) / kirchhoff.natural_frequencies_hz(8)
        assert np.all(ratio < 1.0)
        differences.append(1.0 - ratio)
    assert np.max(differences[1]) < 1e-4
    assert differences[0][0] / differences[1][0] == pytest.approx(4.0, rel=0.1)


def test_mindlin_is_softer_than_kirchhoff_on_a_thick_clamped_plate():
    """a/h = 10: shear deformation and rotary inertia lower every frequency."""
    mindlin = Plate.isotropic(0.2, 0.2, 0.02, ALUMINIUM, theory="mindlin", edges="CCCC")
    kirchhoff = replace(mindlin, theory="kirchhoff")
    assert np.all(mindlin.natural_frequencies_hz(8) < 0.97 * kirchhoff.natural_frequencies_hz(8))


def test_mode_table_labels_and_json_keys():
    navier = _orthotropic().mode_table(4)
    assert navier["labels"][0] == "(1, 1)" and navier["resolved"]
    clamped = _orthotropic(edges="CCCC").mode_table(4)
    assert clamped["labels"] == ["1", "2", "3", "4"] and clamped["resolved"]
    assert clamped["frequencies_hz"][0] > navier["frequencies_hz"][0]
    assert math.isfinite(clamped["resolved_frequency_hz"])


def test_general_basis_is_pure_and_cached():
    """Same inputs, same bits; the basis is built once (lru cache keyed by the inputs)."""
    plate = _quasi_isotropic()
    first = plate_any_edges.solution(plate, 14, plate_any_edges.class_groups(plate)[0])
    again = plate_any_edges.solution(replace(plate), 14, plate_any_edges.class_groups(plate)[0])
    assert again is first


def test_patch_residual_closes_the_static_patch_compliance():
    """Under a contact patch the retained modes plus the residual equal the static patch
    compliance of the basis (plus the SSSS correction): the residual is ≥ 0 and shrinks as
    the cut-off grows."""
    plate = _quasi_isotropic()
    omega1 = plate.fundamental_frequency()
    low = plate.modes(3.0 * omega1, contact_radius=5e-4)
    high = plate.modes(12.0 * omega1, contact_radius=5e-4)
    total_low = low.retained_compliance + low.residual_compliance
    total_high = high.retained_compliance + high.residual_compliance
    assert 0.0 < high.residual_compliance < low.residual_compliance
    assert total_high == pytest.approx(total_low, rel=1e-3)  # the two bases differ in size


# -- impacts -----------------------------------------------------------------------------------
def _run(*, radius, mass, velocity, a, b, h, theory, edges, duration=""):
    """Run the Hertz impact of a steel ball (``radius`` [m], ``mass`` [kg], ``velocity`` [m/s]) on an
    ``a`` × ``b`` × ``h`` [m] aluminium plate of ``theory`` and ``edges``; ``duration``: a [solver] line."""
    from impactmaps.cases import parse_case, run_case

    text = case_text(f"""
        type = "plate"
        length_x = {a!r}
        length_y = {b!r}
        thickness = {h!r}
        material = "aluminium-6061-t6"
        theory = "{theory}"
        edges = "{edges}"
    """, radius=radius, mass=mass, velocity=velocity, after=f"[solver]\ncheck_convergence = false\n{duration}\n")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return run_case(parse_case(text))


@pytest.mark.slow
def test_edges_do_not_matter_before_the_first_reflection():
    """A 0.25 kg, 12.7 mm steel ball at 2 m/s on a 400 × 400 × 8 mm aluminium Mindlin plate:
    the first contact's peak comes before any reflection returns, so CCCC (general basis,
    symmetry class of the centre) equals SSSS (Navier) within 0.5 % (measured 6.0e-5; 1.4e-5 before
    the 3D-consistent near field under the patch)."""
    common = dict(radius=0.00635, mass=0.25, velocity=2.0, a=0.4, b=0.4, h=0.008, theory="mindlin",
                  duration="duration = 0.0005")
    clamped, _ = _run(edges="CCCC", **common)
    supported, _ = _run(edges="SSSS", **common)
    assert clamped.peak_force == pytest.approx(supported.peak_force, rel=0.005)


@pytest.mark.slow
@pytest.mark.parametrize("theory", ["kirchhoff", "mindlin"])
def test_energy_balance_with_re_impacts_on_a_clamped_plate(theory):
    """The issue's clamped 150 × 100 × 3 mm aluminium plate, 20 mm steel ball at 5.4 m/s: a
    full history with re-impacts (before: the infinite-plate asymptote, one impact, no
    history), and the energy ledger closes (impact energy = rebound + plate + contact)."""
    result, summary = _run(radius=0.010, mass=0.0328824, velocity=5.4, a=0.15, b=0.10, h=0.003,
                           theory=theory, edges="CCCC")
    assert result.method.startswith("modal")
    assert summary["impacts"] >= 2
    assert abs(summary["energy_balance_error"]) < 1e-4
