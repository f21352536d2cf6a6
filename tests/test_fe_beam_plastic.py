"""Level 5 of the CalculiX cross-check: the FD beam's own plasticity against a 3D beam.

The FE numbers are read from ``validation/fe/results/level5_beam_plastic.json``
(produced by ``validation/fe/level5_beam_plastic.py``, commands in
validation/fe/README.md, section "Level 5"): a quarter of the seed-000 example beam in
C3D20R, von Mises elastic–perfectly plastic, implicit dynamics, driven by the contact
force history of the FD impact (30 kg, 70 mm nose, 2 m/s, Hertz contact), then unloaded
statically. The FD side is recomputed now, so a change of the FD beam (section layers,
grid operators, time loop, residual state) that moves it away from the 3D solid fails
here. No ``ccx`` needed.

Goals (issue 28, step 5): permanent mid-span deflection within 5 %, peak deflection
within 3 % of the 3D solid. They are asserted against the FE reference only where the
committed FE runs show that reference converged (mesh and time-step differences a third
of the goal or less, checked below).
"""

from __future__ import annotations

import dataclasses
import json
import sys
from pathlib import Path

import numpy as np
import pytest

FE_DIR = Path(__file__).resolve().parents[1] / "validation" / "fe"
sys.path.insert(0, str(FE_DIR))

import level5_beam_plastic as l5  # noqa: E402

PEAK_GOAL = 0.03                 # the issue: peak deflection within 3 %
PERMANENT_GOAL = 0.05            # the issue: permanent deflection within 5 %


def _data():
    if not l5.JSON.exists():
        pytest.skip("validation/fe/results/level5_beam_plastic.json not committed")
    return json.loads(l5.JSON.read_text())


def _reference(tag=l5.REFERENCE):
    """A committed FE run (entry of the JSON) and its history CSV."""
    run = _data().get("fe_runs", {}).get(tag)
    csv = l5.ct.RESULTS / f"level5_fe_{tag}.csv"
    if run is None or not csv.exists():
        pytest.skip(f"FE run {tag} not committed")
    return run, np.loadtxt(csv, delimiter=",", skiprows=1)


@pytest.fixture(scope="module")
def fd_result():
    """The coupled FD impact of the case on the grid that made the committed force."""
    return l5.fd_impact(*l5.FD_GRID, duration=l5.FE_END)


@pytest.fixture(scope="module")
def fd_run(fd_result):
    return l5.fd_summary(fd_result)


@pytest.fixture(scope="module")
def fd_prescribed():
    """The FD beam (N_l × N_h = 200 × 10) under the committed load: (t, w_mid)."""
    _data()
    return l5.fd_prescribed(*l5.prescribed_force())


def test_fd_static_bending_against_3d():
    """The section model alone: the FD beam loaded quasi-statically at mid-span (load
    ramped over 50 ms ≈ 5 periods, critically damped fundamental) against the 3D quarter
    beam in static 3-point bending (``level5_static_bending.py``), up to 1.4 P_y
    (M = 0.93 M_p): within 1.5 %. Measured: the FD is within 0.2 % of the exact beam
    theory and the 3D beam within 0.7 % of it up to 1.37 P_y, 1.1 % stiffer at 1.40 P_y
    (b = 60 mm; b = 10 mm: 0.1 %), so the FD − 3D difference is ≤ 1.3 %: the uniaxial
    layered section holds statically."""
    static = _data().get("static_runs", {}).get("static_b60mm_nz4_ny1")
    if static is None:
        pytest.skip("static bending run not committed")
    rows = np.loadtxt(l5.ct.RESULTS / "level5_static_b60mm_nz4_ny1.csv", delimiter=",",
                      skiprows=1)
    beam = l5.fd_beam(100, 20)
    damping = 2.0 * beam.mass_per_length * float(beam.simply_supported_frequency(1))
    beam = dataclasses.replace(beam, damping_per_length=damping)
    for level in (1.0, 1.2, 1.3, 1.4):
        load = level * static["yield_load_N"]
        response = l5.simulate_fd_response(beam, lambda t, p=load: p * np.minimum(t / 0.05, 1.0),
                                           duration=0.08)
        w_fd = response.history["deflection_at_load_m"].to_numpy()[-1]
        w_fe = np.interp(level, rows[:, 0], rows[:, 1])
        assert w_fd == pytest.approx(w_fe, rel=0.015), level


def test_fd_elastic_phase_against_3d(fd_prescribed):
    """Before the section yields much (t ≤ 3 ms, deflection up to 4.9 mm of the 7 mm
    peak) the FD beam under the committed load follows the 3D beam within 2 % of the
    3D deflection reached (measured 1.1 %: the elastic Rayleigh beam under these
    force spikes is right)."""
    _run, h = _reference()
    t, w = fd_prescribed
    early = h[:, 0] <= 3e-3
    difference = np.interp(h[early, 0], t, w) - h[early, 2]
    assert np.abs(difference).max() <= 0.02 * h[early, 2].max()
# Measured (committed runs, README Level 5): the coupled FD (200 × 10) is +6.6 % above the
# 3D peak deflection and +22.7 % above its permanent deflection (grid-converged FD: +6.3 %,
# +23.9 %). The goals are missed because the FD's uniaxial section caps the mid-span hinge
# at M_p = σ_y b h²/4, while the 3D hinge of this wide beam (b/h = 2.2) is restrained
# across the width: its static limit load is 8 % above the beam theory's (2 % for a
# 10 mm wide beam), and the force spikes drive the mid-span moment to collapse level.
# The bands below catch a change of the FD beam; the goals stay as strict xfails.
PEAK_BAND = (0.04, 0.09)
PERMANENT_BAND = (0.15, 0.30)
GOAL_MISSED = ("issue 28 step 5 goal not met: the FD section's uniaxial hinge (M_p = σ_y b h²/4) "
               "is weaker than the 3D wide beam's laterally restrained hinge (static limit load "
               "+8 %); see validation/fe/README.md, Level 5")


@pytest.mark.xfail(strict=True, reason=GOAL_MISSED)
def test_fd_peak_deflection_goal(fd_run):
    """Issue goal: peak mid-span deflection of the FD impact within 3 % of the 3D beam
    driven by the same force."""
    run, _h = _reference()
    assert fd_run["peak_deflection_m"] == pytest.approx(run["peak_deflection_m"], rel=PEAK_GOAL)


@pytest.mark.xfail(strict=True, reason=GOAL_MISSED)
def test_fd_permanent_deflection_goal(fd_run):
    """Issue goal: permanent mid-span deflection (elastic unloading of the final state on
    both sides) within 5 % of the 3D beam."""
    run, _h = _reference()
    assert fd_run["permanent_deflection_m"] == pytest.approx(run["permanent_deflection_m"],
                                                             rel=PERMANENT_GOAL)


def test_fd_peak_deflection_measured_band(fd_run, fd_prescribed):
    """The FD peak (coupled run, and the FD under the committed force itself) stays in
    the measured band above the 3D peak (+6.6 % / +6.6 %; FE time-step uncertainty of
    the peak 1.3 %, mesh and width ≤ 0.2 %)."""
    run, _h = _reference()
    for peak in (fd_run["peak_deflection_m"], fd_prescribed[1].max()):
        excess = peak / run["peak_deflection_m"] - 1
        assert PEAK_BAND[0] <= excess <= PEAK_BAND[1]


def test_fd_permanent_deflection_measured_band(fd_run):
    """The FD permanent deflection stays in the measured band above the 3D one (+22.7 %;
    the 3D value moves by 1.4 % when the load strip is halved)."""
    run, _h = _reference()
    excess = fd_run["permanent_deflection_m"] / run["permanent_deflection_m"] - 1
    assert PERMANENT_BAND[0] <= excess <= PERMANENT_BAND[1]


def test_fd_against_narrow_3d_beam(fd_run, fd_prescribed):
    """On a 10 mm wide beam (the force scaled by b/60 mm, so beam theory predicts the
    same deflection) the 3D hinge is no longer restrained across the width, and the FD
    beam meets the issue's goals: peak within 3 % (measured: coupled +1.0 %, same force
    +1.0 %; FD converged −0.0 %), and the history within 3 % of the peak up to 8.5 ms
    (measured 1.9 %; 3.2 % over the whole run)."""
    run, h = _reference(l5.NARROW)
    for peak in (fd_run["peak_deflection_m"], fd_prescribed[1].max()):
        assert peak == pytest.approx(run["peak_deflection_m"], rel=PEAK_GOAL)
    t, w = fd_prescribed
    early = h[:, 0] <= 8.5e-3
    assert np.abs(np.interp(h[early, 0], t, w) - h[early, 2]).max() <= PEAK_GOAL * h[:, 2].max()


def test_fd_permanent_deflection_against_narrow_3d_beam(fd_run):
    """The permanent deflection of the FD impact within 5 % of the narrow 3D beam's (the
    issue's goal). Measured +4.6 % (FD 2.732 mm, 3D 2.612 mm with the 3.475 mm strip;
    with the point-load correction measured on the wide beam, +1.4 % on the 3D value,
    the FD is +3.1 %; the grid-converged FD is +1.0 % higher still)."""
    run, _h = _reference(l5.NARROW)
    assert fd_run["permanent_deflection_m"] == pytest.approx(run["permanent_deflection_m"],
                                                             rel=PERMANENT_GOAL)


def test_committed_force_is_the_current_fd_force(fd_result):
    """The committed load is still what the FD impact gives, sampled the same way (every
    5 µs): largest sample and impulse within 0.5 %. If the FD contact coupling changes,
    this says the FE reference must be regenerated (``level5_beam_plastic.py fd``, then
    the FE runs, README Level 5)."""
    _data()
    times, force = l5.prescribed_force()
    now = np.interp(times, fd_result.history["time_s"], fd_result.history["force_N"])
    assert now.max() == pytest.approx(force.max(), rel=0.005)
    assert np.trapezoid(now, times) == pytest.approx(np.trapezoid(force, times), rel=0.005)


def test_a_wide_yielding_section_is_announced():
    """The measured limit of the layered section (above: b/h = 2.16 misses both goals, the
    3D hinge being held across the width) is announced by the FD run itself: a
    ModelValidityWarning naming width/height when the section yielded with b/h > 1 (a
    coarse grid and 3 ms suffice: the section yields in the first contact)."""
    from impactmaps.validity import ModelValidityWarning

    with pytest.warns(ModelValidityWarning, match="width/height = 2.16"):
        result = l5.fd_impact(50, 4, duration=0.003)
    assert result.details.residual["max_plastic_strain"].max() > 0.0
