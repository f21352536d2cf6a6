"""Plates with any edges against independent references (issue 39): published Kirchhoff tables
and the project's own CalculiX runs (``validation/fe/level6_plates.py``; README level 6).

No ``ccx`` needed: the references are read from ``validation/fe/results/``
(``level6_published_kirchhoff.csv``, ``level6_plates.json``, ``level6_plate_shapes.npz``) and the
toolkit side is recomputed now.

* Published tables (Kirchhoff, λ² = ω a² sqrt(ρh/D)): the toolkit's Kirchhoff plate within the
  printed precision of each value plus 0.3 % (the Ritz basis converges from above; the sources
  print 3–4 digits), except the rows the CSV's header documents as a misprint.
* 3D solid (C3D20R, steel, a/h 10 and 20, CCCC / SCSC / CCSS / CFFF): the FE is mesh-converged to
  the ``MESH_CONVERGED`` difference between its two meshes (asserted); the Mindlin plate within
  1 % at a/h = 20 and 2 % at a/h = 10 (the 3D clamp is stiffer than the plate theory's clamp,
  PHYSICS.md §3.7) — these need ``Plate.natural_frequencies_hz`` and Mindlin plates with any
  edges (issue 39, the "plates" work): until then they fail with ``AttributeError`` /
  ``ValueError``. The Kirchhoff plate, which exists now, is checked against the same FE for
  what it is: above the 3D plate (no shear flexibility) by a bounded, growing amount.
* Composite shell (S8R, CCCC AS4/3501-6 [0/45/−45/90]2s and [0/90]4s, 150 × 100 × 2 mm): the
  laminated plate (Mindlin) within 1 %. The current Kirchhoff laminate (D16/D26 dropped with a
  warning) is checked against its measured difference.

Modes are paired by shape where the order can differ: the FE's mid-surface w on a 9 × 9 grid
(MAC against the Kirchhoff Ritz shapes) labels each FE mode; the frequency comparisons use the
sorted spectra of the first 8 bending modes, which is what a user compares with a tap test.
"""

from __future__ import annotations

import csv
import json
import math
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

import impactmaps
from impactmaps.targets.plates import ritz

RESULTS = Path(__file__).resolve().parents[2] / "validation" / "fe" / "results"
sys.path.insert(0, str(RESULTS.parent))          # validation/fe: spring_integrator
PUBLISHED = RESULTS / "level6_published_kirchhoff.csv"
LEVEL6 = RESULTS / "level6_plates.json"
SHAPES = RESULTS / "level6_plate_shapes.npz"
STEEL = impactmaps.material("structural-steel")
PLY = impactmaps.material("as4-3501-6")

N_MODES = 8
MESH_CONVERGED = 3e-3           # second-best vs best FE mesh, every mode (observed ≤ 0.22 %)
MINDLIN_TOLERANCE = {20: 0.01, 10: 0.02}
LAMINATE_TOLERANCE = 0.01
# Published rows that are not used: (source, edges, mode) -> reason.
MISPRINTS = {("harris", "SSSS", 4): "B = 28.82 gives 99.84, exact 10π² = 98.70 (+1.2 %)"}

_skip_no_level6 = pytest.mark.skipif(not LEVEL6.exists(), reason="level6_plates.json not committed")


def _published():
    with PUBLISHED.open() as f:
        rows = [r for r in csv.DictReader(line for line in f if not line.startswith("#"))]
    groups = {}
    for r in rows:
        groups.setdefault((r["source"], r["edges"]), []).append(r)
    return groups


def _lambda2(plate, omega):
    d = plate.D11
    return np.asarray(omega) * plate.length_x ** 2 * math.sqrt(plate.mass_per_area / d)


def _kirchhoff_plate(a, h, edges, b=None):
    return impactmaps.Plate.isotropic(a, b or a, h, STEEL, theory="kirchhoff", edges=edges)


def _kirchhoff_omegas(plate, count):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return np.asarray(plate.modes(0.0, min_modes=count).frequencies[:count])


# Sources whose values are upper bounds above the converged Kirchhoff spectrum (few-term
# Ritz / crossed-beam approximations of the free edges): the toolkit's converged Ritz basis
# (an upper bound itself) may lie below them by up to this much. Measured: CFFF −0.2 … −0.7 %
# (Barton 1951), −0.6 … −1.1 % (Harris); README level 6.
BELOW_UPPER_BOUND = {"CFFF": 1.2e-2}


def _distinct(values, rel=1e-6):
    """The distinct values of a sorted spectrum (degenerate pairs of the square plate once)."""
    out = []
    for v in values:
        if not out or v > out[-1] * (1 + rel):
            out.append(v)
    return np.array(out)


@pytest.mark.parametrize("key", sorted(_published()) if PUBLISHED.exists() else [])
def test_published_kirchhoff_tables(key):
    """Toolkit Kirchhoff plate (Ritz for non-SSSS, Navier for SSSS) vs the printed tables.

    The tables list distinct frequencies (a degenerate pair of the square plate once), so the
    toolkit's spectrum is compared with its repeated values merged."""
    source, edges = key
    rows = _published()[key]
    plate = _kirchhoff_plate(1.0, 0.001, edges)
    lam = _distinct(_lambda2(plate, _kirchhoff_omegas(plate, 2 * len(rows) + 2)))
    for r in rows:
        mode = int(r["mode"])
        if (source, edges, mode) in MISPRINTS:
            continue
        printed = float(r["value_as_printed"])
        digits = int(r["digits"])
        rounding = 0.5 * 10 ** (math.floor(math.log10(abs(printed))) - digits + 1) / printed
        diff = lam[mode - 1] / float(r["lambda2"]) - 1
        below = BELOW_UPPER_BOUND.get(edges, 3e-3)
        assert -below - rounding <= diff <= 3e-3 + rounding, (source, edges, mode, diff)


def _level6():
    return json.loads(LEVEL6.read_text())


def _cases(kind):
    if not LEVEL6.exists():
        return []
    return sorted(k for k in _level6()["cases"] if k.startswith(kind))


def _mac(a, b):
    a, b = a.reshape(len(a), -1), b.reshape(len(b), -1)
    num = (a @ b.T) ** 2
    return num / np.outer((a * a).sum(1), (b * b).sum(1))


@_skip_no_level6
@pytest.mark.parametrize("key", _cases("solid") + _cases("shell"))
def test_fe_mesh_converged(key):
    """The committed FE frequencies are known to better than the tolerances on the toolkit."""
    case = _level6()["cases"][key]
    assert len(case["fine"]["fe_bending_hz"]) == N_MODES
    assert np.max(np.abs(case["mesh_difference"])) <= MESH_CONVERGED, case["mesh_difference"]
    # the coarse mesh is stiffer (displacement FE converges from above)
    assert min(case["mesh_difference"]) > -1e-4


def _solid_inputs(key):
    _, edges, ratio = key.split("-")
    case = _level6()["cases"][key]["fine"]
    return edges, int(ratio), case


@_skip_no_level6
@pytest.mark.parametrize("key", _cases("solid"))
def test_fe_shapes_pair_with_kirchhoff(key):
    """Pairing by shape: FE bending mode i (mid-surface w on the 9 × 9 grid) has MAC ≥ 0.95 with
    the Kirchhoff mode i of the same plate (with the degenerate group it belongs to, for the
    square's repeated frequencies). So the stored modes are the plate's bending family, in
    the same order as the plate theory's, and comparing sorted spectra pairs modes by shape."""
    edges, ratio, case = _solid_inputs(key)
    shapes = np.load(SHAPES)[key]
    a, h = case["length_x_m"], case["thickness_m"]
    plate = _kirchhoff_plate(a, h, edges)
    n = 12
    args = (plate.length_x, plate.length_y, plate.D11, plate.D22, plate.D12, plate.D66,
            plate.mass_per_area)
    solution = ritz.solve_ritz_plate(*args, edges, 14, 14)
    omega = solution.frequencies[:n]
    g = np.linspace(0.0, a, shapes.shape[1])
    points = np.array([(x, y) for x in g for y in g])
    kirchhoff = solution.mode_shapes(points, n).T.reshape(n, len(g), len(g))
    mac = _mac(shapes, kirchhoff)
    for i in range(len(shapes)):
        group = np.flatnonzero(np.abs(omega / omega[i] - 1) < 1e-6)
        assert mac[i, group].sum() >= 0.95, (i, np.round(mac[i], 3))


def _mindlin_hz(edges, a, h, count):
    plate = impactmaps.Plate.isotropic(a, a, h, STEEL, theory="mindlin", edges=edges)
    return np.sort(np.asarray(plate.natural_frequencies_hz(count)))[:count]


@_skip_no_level6
@pytest.mark.parametrize("key", _cases("solid"))
def test_mindlin_any_edges_vs_3d_solid(key):
    """Mindlin plate with any edges within 1 % (a/h 20) / 2 % (a/h 10) of the 3D solid, first 8
    bending modes. Needs issue 39's Mindlin plates with any edges and ``natural_frequencies_hz``."""
    edges, ratio, case = _solid_inputs(key)
    fe = np.sort(case["fe_bending_hz"])
    got = _mindlin_hz(edges, case["length_x_m"], case["thickness_m"], N_MODES)
    np.testing.assert_allclose(got, fe, rtol=MINDLIN_TOLERANCE[ratio])


@_skip_no_level6
@pytest.mark.parametrize("key", [k for k in _cases("solid") if "-SSSS-" in k])
def test_ssss_mindlin_vs_3d_solid_now(key):
    """The 3D simple support of level 6 (tangential displacement held, thickness-averaged w
    held per node column) against the Navier Mindlin plate, which exists now: within 1 % at
    a/h = 20 and 10 (observed −0.03 … −0.19 % and −0.13 … −0.6 %). This checks the support
    model that the SCSC / CCSS cases use."""
    edges, ratio, case = _solid_inputs(key)
    plate = impactmaps.Plate.isotropic(case["length_x_m"], case["length_y_m"], case["thickness_m"],
                                       STEEL, theory="mindlin")
    got = np.sort(np.asarray(plate.modes(0.0, min_modes=N_MODES).frequencies[:N_MODES])) / (2 * np.pi)
    np.testing.assert_allclose(got, np.sort(case["fe_bending_hz"]), rtol=0.01)


# Kirchhoff − FE (relative) at a/h = 20, first 8 bending modes: measured bounds (the classical
# plate has no shear flexibility, so it is above the 3D plate; how much grows with the mode
# and with the clamps). Lower/upper bound over the 8 modes; see README level 6.
# Observed (32×32×4 mesh): CCCC +2.5 … +9.1 %, SCSC +2.0 … +8.2 %, CCSS +1.6 … +7.3 %,
# CFFF +0.2 … +4.5 %; bands = observed ± 0.5 %.
KIRCHHOFF_BANDS = {"CCCC": (0.019, 0.097), "SCSC": (0.014, 0.087), "CCSS": (0.011, 0.078),
                   "CFFF": (-0.003, 0.050), "SSSS": (0.003, 0.060)}


@_skip_no_level6
@pytest.mark.parametrize("key", [k for k in _cases("solid") if k.endswith("-20")])
def test_kirchhoff_above_3d_solid_thin(key):
    """Kirchhoff (what exists now) against the a/h = 20 solid: above it, by a bounded amount."""
    edges, ratio, case = _solid_inputs(key)
    plate = _kirchhoff_plate(case["length_x_m"], case["thickness_m"], edges)
    got = np.sort(_kirchhoff_omegas(plate, N_MODES)) / (2 * np.pi)
    diff = got / np.sort(case["fe_bending_hz"]) - 1
    low, high = KIRCHHOFF_BANDS[edges]
    assert np.all(diff > low) and np.all(diff < high), np.round(100 * diff, 3)


def _laminate(key):
    angles = {"qi": [0, 45, -45, 90, 0, 45, -45, 90], "cp": [0, 90, 0, 90, 0, 90, 0, 90]}
    ply = PLY  # catalogue ply, 0.125 mm default thickness
    return impactmaps.Laminate.from_layup(ply, angles[key.split("-")[1]], symmetric=True)


@_skip_no_level6
@pytest.mark.parametrize("key", _cases("shell"))
def test_laminate_mindlin_vs_composite_shell(key):
    """Laminated (Mindlin, full D16/D26) CCCC plate within 1 % of the S8R composite shell.
    Needs issue 39's laminated plates with any edges and ``natural_frequencies_hz``."""
    case = _level6()["cases"][key]["fine"]
    plate = impactmaps.Plate.from_laminate(case["length_x_m"], case["length_y_m"], _laminate(key),
                                           theory="mindlin", edges="CCCC")
    got = np.sort(np.asarray(plate.natural_frequencies_hz(N_MODES)))[:N_MODES]
    np.testing.assert_allclose(got, np.sort(case["fe_bending_hz"]), rtol=LAMINATE_TOLERANCE)


# --------------------------------------------------------------------------- CCCC impact
IMPACT = RESULTS / "level6_impact.json"
LEVEL3_SSSS_MODES = RESULTS / "level3_modes_plate_a070_fine.json"
PATCH_RADIUS = 7e-4


def _impact():
    return json.loads(IMPACT.read_text())


def _impact_cases():
    return _impact()["cases"] if IMPACT.exists() else []


def _spread(fe, quantity):
    ref = fe["reference"][quantity]
    return max(abs(v[quantity] / ref - 1) for v in fe.values())


@pytest.mark.skipif(not IMPACT.exists(), reason="level6_impact.json not committed")
def test_fe_cccc_static_patch_compliance_converged():
    """The 3D CCCC plate's patch compliance: two meshes within 0.3 % (observed 0.17 %), and
    the edge invariant: its excess over the Kirchhoff point compliance is that of the SSSS
    plate (the near field does not see the edges) within 2 % (observed 3.57 vs 3.54 × 10⁻⁹ m/N)."""
    data = _impact()
    c = data["static_patch_compliance_m_per_N"]
    assert abs(c["cccc_a070_coarse"] / c["cccc_a070_fine"] - 1) < 3e-3
    cccc_excess = c["cccc_a070_fine"] - data["toolkit_kirchhoff_point_compliance_m_per_N"]
    ssss = json.loads(LEVEL3_SSSS_MODES.read_text())["static_compliance_m_per_N"]
    ssss_excess = ssss - _kirchhoff_plate(0.2, 0.01, "SSSS").static_compliance()
    assert cccc_excess == pytest.approx(ssss_excess, rel=0.02)


def _patch_compliance(plate):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        basis = plate.modes(4e6, contact_radius=PATCH_RADIUS)
    return basis.retained_compliance + basis.residual_compliance


@pytest.mark.skipif(not IMPACT.exists(), reason="level6_impact.json not committed")
def test_mindlin_cccc_static_patch_compliance_vs_3d():
    """Issue 39: the static centre compliance of the CCCC Mindlin plate under the Hertz-sized
    patch (a_c = 0.7 mm) within 2 % of the 3D solid's structural part (the FE patch compliance
    minus the half-space compliance of the patch, which the Hertz law carries). Observed +0.57 %
    with the 3D-consistent near field (:mod:`impactmaps.targets.plates.near_field`; the
    Mindlin patch model without it: +9.0 %)."""
    data = _impact()
    plate = impactmaps.Plate.isotropic(0.2, 0.2, 0.01, STEEL, theory="mindlin", edges="CCCC")
    fe = data["structural_patch_compliance_m_per_N"][data["reference"]]
    assert _patch_compliance(plate) == pytest.approx(fe, rel=0.02)


def test_mindlin_ssss_static_patch_vs_3d():
    """The SSSS Mindlin plate under the Hertz patch (0.7 mm) against level 3's 3D structural
    patch compliance (FE minus the half-space compliance of the patch): within 0.5 % (observed
    +0.11 %). Without the 3D-consistent near field it was +4.4 % — the Mindlin shear flexibility
    under a patch much smaller than h (≈ ln(h/a)/(2π k G h)), which in the 3D solid is the
    half-space field the Hertz law already carries (docs/contact_patch.rst)."""
    from spring_integrator import halfspace_patch_compliance
    fe = (json.loads(LEVEL3_SSSS_MODES.read_text())["static_compliance_m_per_N"]
          - halfspace_patch_compliance(PATCH_RADIUS, STEEL))
    plate = impactmaps.Plate.isotropic(0.2, 0.2, 0.01, STEEL, theory="mindlin")
    assert _patch_compliance(plate) == pytest.approx(fe, rel=5e-3)


def test_the_contract_patch_model_without_the_near_field_is_too_compliant(monkeypatch):
    """The flaw the near-field correction removes (docs/physics_contract.md §8, Correction):
    the Hertz patch on a Mindlin plate *without* the near-field weights (the plate treated as
    if it were not isotropic: the contract's §8 as first written) is more than 3 % more
    compliant than the 3D solid's structural part (measured +4.4 % SSSS, +9 % CCCC): the local
    deformation counted twice, once by the Hertz law and once by the plate's shear."""
    from spring_integrator import halfspace_patch_compliance

    from impactmaps.targets.plates import near_field, plate as plate_module
    ssss_fe = (json.loads(LEVEL3_SSSS_MODES.read_text())["static_compliance_m_per_N"]
               - halfspace_patch_compliance(PATCH_RADIUS, STEEL))
    plate_module._plate_modes.cache_clear()  # a basis cached with the weights must not answer
    try:
        monkeypatch.setattr(near_field, "isotropic_constants", lambda plate: None)
        unweighted = _patch_compliance(impactmaps.Plate.isotropic(0.2, 0.2, 0.01, STEEL, theory="mindlin"))
    finally:
        plate_module._plate_modes.cache_clear()  # nor one cached without them afterwards
    assert unweighted > 1.03 * ssss_fe


@pytest.mark.parametrize("case", _impact_cases(), ids=lambda c: f"cccc-mass×{c['mass_factor']:g}")
def test_fe_cccc_impact_converged(case):
    """FE spring model (CCCC 3D modes): mesh, step and modes move the first-contact peak and
    duration by ≤ 1 % (observed ≤ 0.35 %)."""
    for quantity in ("first_peak_N", "first_contact_s"):
        assert _spread(case["fe"], quantity) <= 0.01


@pytest.mark.parametrize("case", _impact_cases(), ids=lambda c: f"cccc-mass×{c['mass_factor']:g}")
def test_mindlin_cccc_impact_vs_3d(case):
    """Issue 39: spring-coupled impact on the CCCC Mindlin plate (steel 200 × 200 × 10 mm, R 10 mm
    steel sphere, 1 m/s, 0.1–100 × the solid sphere's mass): first-contact peak and duration
    within 3 % of the FE spring model (observed −0.3 … −0.04 % and +0.2 … +0.4 %)."""
    sphere = impactmaps.Sphere(0.01, STEEL, mass=case["mass_kg"])
    law = impactmaps.law_for_sphere("hertz", sphere, STEEL)
    plate = impactmaps.Plate.isotropic(0.2, 0.2, 0.01, STEEL, theory="mindlin", edges="CCCC")
    res = impactmaps.simulate(plate, law, case["mass_kg"], 1.0)
    start, end = res.contact_intervals[0]
    if res.history is None:
        peak = res.peak_force
    else:
        h = res.history
        peak = h[(h["time_s"] >= start) & (h["time_s"] <= end)]["force_N"].max()
    ref = case["fe"]["reference"]
    assert peak == pytest.approx(ref["first_peak_N"], rel=0.03)
    assert end - start == pytest.approx(ref["first_contact_s"], rel=0.03)


# --------------------------------------------------------------------------- CCCC impact, a/h = 10
IMPACT_THICK = RESULTS / "level6_impact_h20.json"
# Mindlin (near field) − 3D structural patch compliance of the thick CCCC plate, measured: +2.09 %
# (the fine mesh; the coarse mesh's structural part is 0.78 % lower, so the FE's is converged to
# about that and the difference would shrink with a finer mesh). The test holds it to ± 0.5 %.
THICK_STATIC_DIFFERENCE = 0.0209
_skip_no_thick = pytest.mark.skipif(not IMPACT_THICK.exists(), reason="level6_impact_h20.json not committed")


def _thick():
    return json.loads(IMPACT_THICK.read_text())


def _thick_params():
    if not IMPACT_THICK.exists():
        return []
    # the light spheres need large bases (15–60 s cold): slow; 10 and 100 × run by default
    return [pytest.param(c, id=f"cccc-h20-mass×{c['mass_factor']:g}",
                         marks=() if c["mass_factor"] >= 10 else (pytest.mark.slow,))
            for c in _thick()["cases"]]


@_skip_no_thick
def test_fe_cccc_thick_static_patch_compliance():
    """The thick (a/h = 10, 200 × 200 × 20 mm) 3D CCCC plate's patch compliance (a_c = 0.7 mm): two
    meshes within 0.3 % (observed 0.24 %); the CCCC Mindlin plate with the 3D-consistent near field
    against its structural part (FE minus the half-space compliance of the patch, a third of the
    whole here) within the measured difference ± 0.5 % (observed +2.09 %; the issue's 2 % is met
    at a/h = 20, +0.57 %; the structural part moves by 0.78 % between the two meshes)."""
    data = _thick()
    c = data["static_patch_compliance_m_per_N"]
    assert abs(c["cccc_h20_a070_coarse"] / c["cccc_h20_a070_fine"] - 1) < 3e-3
    plate = impactmaps.Plate.isotropic(0.2, 0.2, 0.02, STEEL, theory="mindlin", edges="CCCC")
    fe = data["structural_patch_compliance_m_per_N"][data["reference"]]
    diff = _patch_compliance(plate) / fe - 1
    assert THICK_STATIC_DIFFERENCE - 5e-3 < diff < THICK_STATIC_DIFFERENCE + 5e-3, diff


@pytest.mark.parametrize("case", _thick_params())
def test_fe_cccc_thick_impact_converged(case):
    """FE spring model of the thick plate: mesh, step and modes move the first-contact peak and
    duration by ≤ 1 %."""
    for quantity in ("first_peak_N", "first_contact_s"):
        assert _spread(case["fe"], quantity) <= 0.01


@pytest.mark.parametrize("case", _thick_params())
def test_mindlin_cccc_thick_impact_vs_3d(case):
    """Issue 39 and the near field (``targets/plates/near_field.py``) checked dynamically where it
    moves the answer most: the thick CCCC Mindlin plate (steel 200 × 200 × 20 mm, a/h = 10, R 10 mm
    steel sphere at 1 m/s, 0.1–100 × the solid sphere's mass) within 3 % of the 3D FE spring model
    in first-contact peak and duration."""
    sphere = impactmaps.Sphere(0.01, STEEL, mass=case["mass_kg"])
    law = impactmaps.law_for_sphere("hertz", sphere, STEEL)
    plate = impactmaps.Plate.isotropic(0.2, 0.2, 0.02, STEEL, theory="mindlin", edges="CCCC")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = impactmaps.simulate(plate, law, case["mass_kg"], 1.0)
    start, end = res.contact_intervals[0]
    h = res.history
    peak = h[(h["time_s"] >= start) & (h["time_s"] <= end)]["force_N"].max()
    ref = case["fe"]["reference"]
    assert peak == pytest.approx(ref["first_peak_N"], rel=0.03)
    assert end - start == pytest.approx(ref["first_contact_s"], rel=0.03)
