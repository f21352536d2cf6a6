"""Spring-coupled impact on the clamped quasi-isotropic laminate against the composite-shell FE, and
what dropping D16/D26 changes (issue 39; ``validation/fe/level6_laminate_impact.py``, README level 6).

No ``ccx`` needed: the FE spring model's results are read from
``validation/fe/results/level6_laminate_impact.json`` and the toolkit side is recomputed now.
Plates: CCCC AS4/3501-6, ``[0/45/-45/90]2s`` 150 × 100 × 2 mm (``qi0``) and ``[45/0/-45/90]2s``
125 × 75 × 2 mm (``qi45``, the worked example's window); steel sphere R = 8 mm at 1.907 m/s,
0.0168 / 0.1 / 1 / 5.5 kg. The light impactors need large bases (20–90 s cold): those tests are
``slow``; 1 and 5.5 kg run in the default suite, but for the shell comparison at 1 kg (its default run
raises the patch cut-off to the heavy impactor's corner: 8–30 s each), which is ``slow`` too: the
5.5 kg comparisons check the same agreement of the default ``simulate`` on both plates.
"""

from __future__ import annotations

import dataclasses
import json
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

import impactmaps

RESULTS = Path(__file__).resolve().parents[2] / "validation" / "fe" / "results"
sys.path.insert(0, str(RESULTS.parent))          # validation/fe: cluster_duration
from level6_laminate_impact import cluster_duration  # noqa: E402
IMPACT = RESULTS / "level6_laminate_impact.json"
PLY = impactmaps.material("as4-3501-6")
STEEL = impactmaps.material("structural-steel")
ANGLES = {"qi0": [0, 45, -45, 90, 0, 45, -45, 90], "qi45": [45, 0, -45, 90, 45, 0, -45, 90]}

pytestmark = pytest.mark.skipif(not IMPACT.exists(), reason="level6_laminate_impact.json not committed")


def _data():
    return json.loads(IMPACT.read_text())


def _params(lightest_default=1.0):
    """(layup, case) of every committed case; those below ``lightest_default`` [kg] are ``slow``."""
    if not IMPACT.exists():
        return []
    out = []
    for layup, entry in _data()["plates"].items():
        for case in entry["cases"]:
            marks = () if case["mass_kg"] >= lightest_default else (pytest.mark.slow,)
            out.append(pytest.param(layup, case, id=f"{layup}-{case['mass_kg']:.3g}kg", marks=marks))
    return out


def _plate(layup, couplings=True):
    entry = _data()["plates"][layup]
    lam = impactmaps.Laminate.from_layup(PLY, ANGLES[layup], symmetric=True)
    p = impactmaps.Plate.from_laminate(entry["length_x_m"], entry["length_y_m"], lam,
                                       theory="mindlin", edges="CCCC")
    return (p if couplings else dataclasses.replace(p, D16=0.0, D26=0.0)), lam


def _first_contact(layup, mass, couplings=True, corner_cutoff=True):
    """(first-contact peak [N], first-contact duration [s], contact intervals) of ``simulate``."""
    plate, lam = _plate(layup, couplings)
    law = impactmaps.law_for_sphere("hertz", impactmaps.Sphere(0.008, STEEL, mass=mass), lam)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")       # the deflection/validity warnings of a 2 mm plate
        res = impactmaps.simulate(plate, law, mass, _data()["inputs"]["velocity_m_s"], corner_cutoff=corner_cutoff)
    start, end = res.contact_intervals[0]
    h = res.history
    peak = h[(h["time_s"] >= start) & (h["time_s"] <= end)]["force_N"].max()
    return float(peak), float(end - start), res.contact_intervals


def _spread(fe, quantity):
    ref = fe["reference"][quantity]
    return max(abs(v[quantity] / ref - 1) for v in fe.values())


def _fe_params():
    if not IMPACT.exists():
        return []
    return [pytest.param(layup, case, id=f"{layup}-{case['mass_kg']:.3g}kg")
            for layup, entry in _data()["plates"].items() for case in entry["cases"]]


@pytest.mark.parametrize("layup", sorted(_data()["plates"]) if IMPACT.exists() else [])
def test_fe_shell_mesh_converged(layup):
    """The two shell meshes: the 8 lowest frequencies within 0.3 % and the static compliance
    under each Hertz patch within 0.5 % (observed ≤ 0.13 % and ≤ 0.37 %); the fine mesh the more
    compliant (displacement FE converges from the stiff side)."""
    entry = _data()["plates"][layup]
    fine = np.array(entry["frequencies_hz"]["fe_fine_lowest"])
    coarse = np.array(entry["frequencies_hz"]["fe_coarse_lowest"])
    assert np.max(np.abs(coarse / fine - 1)) < 3e-3
    for row in entry["static"]:
        ratio = row["fe_coarse_m_per_N"] / row["fe_fine_m_per_N"]
        assert 1 - 5e-3 < ratio < 1 + 1e-4, row


@pytest.mark.parametrize("layup, case", _fe_params())
def test_fe_laminate_impact_converged(layup, case):
    """FE spring model: the coarse mesh, half the step and half the modes move the first-contact
    peak and (graze-merged) duration by ≤ 1 % (observed ≤ 0.50 % and ≤ 0.25 %)."""
    for quantity in ("first_peak_N", "first_contact_merged_s"):
        assert _spread(case["fe"], quantity) <= 0.01, quantity


@pytest.mark.parametrize("layup", sorted(_data()["plates"]) if IMPACT.exists() else [])
def test_laminate_static_patch_compliance_vs_shell(layup):
    """The toolkit's CCCC Mindlin laminate under each Hertz patch (a = 0.51–1.32 mm) against the
    shell's static centre compliance: within 1.5 % (observed −0.27 … +0.65 % qi0, −0.46 … +1.03 %
    qi45). The shell grows more compliant than the plate as the patch shrinks (the through-thickness
    squash of its expanded brick under the load, which the plate does not have); the plate is the
    more compliant under the larger patches, as its frequencies are 0.3–0.9 % below the shell's."""
    plate, _ = _plate(layup)
    for row in _data()["plates"][layup]["static"]:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            basis = plate.modes(1e5, contact_radius=row["patch_radius_m"])
        got = basis.retained_compliance + basis.residual_compliance
        assert got == pytest.approx(row["fe_fine_m_per_N"], rel=0.015), row


@pytest.mark.parametrize("layup, case", _params(lightest_default=5.5))
def test_laminate_impact_vs_composite_shell(layup, case):
    """Issue 39: spring-coupled impact on the CCCC quasi-isotropic laminate (Mindlin, full D16/D26,
    Hertz patch) within 3 % of the composite-shell FE spring model in first-contact peak and
    duration. Where the FE's first contact ends in a graze (the force touches zero for < 1 % of
    the contact and the contact resumes: ``qi0`` at 1 kg, a 16 µs gap at 4.70 ms) the strict
    first-contact duration is ill-conditioned — the toolkit's force dips to 1.6 N there without
    reaching zero, so its first contact is the merged one (+4.1 % on the strict
    duration) — and the durations compared are the graze-merged ones. The default suite runs the
    5.5 kg cases (9–11 s each, most of it one eigen-solution of the basis the raised cut-off grows); the 1 kg ones (8–30 s: the raised patch cut-off) are ``slow``."""
    peak, _, intervals = _first_contact(layup, case["mass_kg"])
    ref = case["fe"]["reference"]
    assert peak == pytest.approx(ref["first_peak_N"], rel=0.03)
    # the graze-merged duration is the strict one wherever neither model grazes
    assert cluster_duration(intervals) == pytest.approx(ref["first_contact_merged_s"], rel=0.03)


def test_a_graze_is_merged_into_the_first_contact():
    """The graze rule of the durations compared (``cluster_duration``), on the intervals of the
    FE's ``qi0`` 1 kg graze (a 16 µs gap at 4.70 ms, < 1 % of the contact: merged) and of a
    rebound (a gap longer than 1 %: the first contact alone). The default suite's comparisons
    (5.5 kg) have no graze; the 1 kg one that has is ``slow``."""
    graze = [(0.0, 4.70e-3), (4.716e-3, 5.1e-3), (9.0e-3, 9.5e-3)]
    assert cluster_duration(graze) == pytest.approx(5.1e-3, rel=1e-12)
    assert cluster_duration([(0.0, 4.70e-3), (4.80e-3, 5.1e-3)]) == pytest.approx(4.70e-3, rel=1e-12)
    assert cluster_duration([(1e-4, 2e-3)]) == pytest.approx(1.9e-3, rel=1e-12)


@pytest.mark.parametrize("layup, case", _params())
def test_d16_d26_quantified(layup, case):
    """D16/D26 quantified (issue 39): the toolkit's plate with D16 = D26 = 0 (all else equal) gives the
    first-contact peak committed beside the shell's, within 0.3 %. Measured: dropping them raises the
    peak by +1.7 … +2.3 % on the worked example's [45/0/−45/90]2s 125 × 75 mm (D16 = 0.116
    sqrt(D11 D22)), against the shell +1.15 … +4.30 % (with them −1.16 … +2.52 %), and moves it by
    −0.2 … +1.2 % on [0/45/−45/90]2s 150 × 100 mm (0.050; against the shell +0.02 … +1.50 %, with
    them −0.53 … +1.23 %); the durations by ≤ 0.54 %. The committed values were computed at the
    patch cut-off of their day, 20 ω (before simulate's heavy-impactor rule): they are compared at it."""
    peak, _, _ = _first_contact(layup, case["mass_kg"], couplings=False, corner_cutoff=False)
    assert peak == pytest.approx(case["toolkit_without_D16_D26"]["first_peak_N"], rel=3e-3)
