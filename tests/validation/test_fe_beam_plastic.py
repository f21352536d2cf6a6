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
within 3 % of the 3D solid under the same prescribed force. On the 60 mm wide beam (b/h
2.16) they hold with the wide-section model (:mod:`impactmaps.fd.wide_section`, the
default); the uniaxial layered section (``width_constraint=False``) misses them, and
stays checked against its measured bands. The committed force is the coupled FD impact
with the uniaxial section (the run that made it).
"""

from __future__ import annotations

import dataclasses
import json
import sys
from pathlib import Path

import numpy as np
import pytest

FE_DIR = Path(__file__).resolve().parents[2] / "validation" / "fe"
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
    """The coupled FD impact of the case (uniaxial section) on the grid that made the
    committed force."""
    return l5.fd_impact(*l5.FD_GRID, duration=l5.FE_END)


@pytest.fixture(scope="module")
def fd_wide():
    """The FD beam with the wide-section model (200 × 10) under the committed load:
    (t, w_mid, permanent w_mid)."""
    _data()
    return l5.fd_prescribed(*l5.prescribed_force(), width_constraint=True, permanent=True)


@pytest.fixture(scope="module")
def fd_run(fd_result):
    return l5.fd_summary(fd_result)


@pytest.fixture(scope="module")
def fd_prescribed():
    """The uniaxial FD beam (N_l × N_h = 200 × 10) under the committed load: (t, w_mid)."""
    _data()
    return l5.fd_prescribed(*l5.prescribed_force())


def test_fd_static_bending_against_3d():
    """The section model alone: the FD beam loaded quasi-statically at mid-span (load
    ramped over 50 ms ≈ 5 periods, critically damped fundamental) against the 3D quarter
    beam in static 3-point bending (``level5_static_bending.py``), up to 1.4 P_y
    (M = 0.93 M_p): within 1.5 %. Measured: the uniaxial FD is within 0.2 % of the exact
    beam theory and the 3D beam within 0.7 % of it up to 1.37 P_y, 1.1 % stiffer at
    1.40 P_y (b = 60 mm; b = 10 mm: 0.1 %), so the FD − 3D difference is ≤ 1.3 %; the
    wide-section model (the default, run here) is within 0.8 % of the 3D beam up to
    1.5 P_y (``level5_wide_calibration.py``)."""
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
def test_fd_peak_deflection_goal(fd_wide):
    """Issue goal: peak mid-span deflection of the FD beam within 3 % of the 3D beam under
    the same force. Wide-section model, 200 × 10: +0.65 % (converged grids +0.27 … +0.52 %;
    100 × 10: +1.3 %); the FE time-step uncertainty of the peak is 1.3 %."""
    run, _h = _reference()
    assert fd_wide[1].max() == pytest.approx(run["peak_deflection_m"], rel=PEAK_GOAL)


def test_fd_permanent_deflection_goal(fd_wide):
    """Issue goal: permanent mid-span deflection (elastic unloading of the final state on
    both sides) within 5 % of the 3D beam under the same force. Wide-section model,
    200 × 10: −4.3 % — inside, with a thin margin: the finer FD grids give −4.1 … −5.2 %,
    the calibration's spread of ε_c (per width) moves it by −2.8 … +2.9 %, and the 3D value
    itself is +1.4 % from a point load (README, Level 5). Under a second load the goal is
    missed (+9.9 %, ``test_wide_model_under_its_own_force``)."""
    run, _h = _reference()
    assert fd_wide[2] == pytest.approx(run["permanent_deflection_m"], rel=PERMANENT_GOAL)


def test_fd_wide_history_follows_3d(fd_wide):
    """The wide-section FD deflection history under the same force: within 3 % of the 3D
    peak up to 8.5 ms (measured 2.2 %; 1.4 % up to 8 ms), within 5 % over the whole dynamic
    step (measured 4.4 %, at 10.5 ms in the free vibration after the last large contact,
    the FD below the 3D beam; the uniaxial section: 11.8 %)."""
    _run, h = _reference()
    t, w, _perm = fd_wide
    difference = np.abs(np.interp(h[:, 0], t, w) - h[:, 2])
    peak = h[:, 2].max()
    assert difference[h[:, 0] <= 8.5e-3].max() <= PEAK_GOAL * peak
    assert difference.max() <= 0.05 * peak


# Measured (committed runs, README Level 5) with the *uniaxial* section: the coupled FD
# (200 × 10) is +6.6 % above the 3D peak deflection and +22.7 % above its permanent
# deflection (grid-converged FD: +6.3 %, +23.9 %). It caps the mid-span hinge at M_p =
# σ_y b h²/4, while the 3D hinge of this wide beam (b/h = 2.2) is restrained across the
# width (static limit load 8 % above the beam theory's, 2 % for a 10 mm wide beam). The
# bands catch a change of the uniaxial FD beam.
PEAK_BAND = (0.04, 0.09)
PERMANENT_BAND = (0.15, 0.30)


def test_fd_peak_deflection_measured_band(fd_run, fd_prescribed):
    """The uniaxial FD peak (coupled run, and the FD under the committed force itself)
    stays in the measured band above the 3D peak (+6.6 % / +6.6 %; FE time-step uncertainty of
    the peak 1.3 %, mesh and width ≤ 0.2 %)."""
    run, _h = _reference()
    for peak in (fd_run["peak_deflection_m"], fd_prescribed[1].max()):
        excess = peak / run["peak_deflection_m"] - 1
        assert PEAK_BAND[0] <= excess <= PEAK_BAND[1]


def test_fd_permanent_deflection_measured_band(fd_run):
    """The uniaxial FD permanent deflection stays in the measured band above the 3D one (+22.7 %;
    the 3D value moves by 1.4 % when the load strip is halved)."""
    run, _h = _reference()
    excess = fd_run["permanent_deflection_m"] / run["permanent_deflection_m"] - 1
    assert PERMANENT_BAND[0] <= excess <= PERMANENT_BAND[1]


def test_fd_against_narrow_3d_beam(fd_run, fd_prescribed):
    """On a 10 mm wide beam (the force scaled by b/60 mm, so beam theory predicts the
    same deflection) the 3D hinge is no longer restrained across the width, and the FD
    beam (uniaxial there, b/h = 0.36; the uniaxial 60 mm FD beam is the same beam with
    everything scaled by b) meets the issue's goals: peak within 3 % (measured: coupled +1.0 %, same force
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


def test_a_section_outside_the_checked_range_is_announced():
    """The uniaxial section (``width_constraint=False``) yielding at b/h = 2.16 (which
    misses both goals, above) is announced by the FD run itself, a ModelValidityWarning
    naming width/height; the wide-section model is not, inside its calibrated range, and
    is beyond it (b/h > 8.63). A coarse grid and 3 ms suffice: the section yields in the
    first contact."""
    import warnings

    from impactmaps._checks import ModelValidityWarning

    with pytest.warns(ModelValidityWarning, match="width/height = 2.16"):
        result = l5.fd_impact(50, 4, duration=0.003)
    assert result.details.residual["max_plastic_strain"].max() > 0.0
    with warnings.catch_warnings():
        warnings.simplefilter("error", ModelValidityWarning)
        result = l5.fd_impact(50, 4, duration=0.003, width_constraint=True)
    assert result.details.residual["max_plastic_strain"].max() > 0.0
    wide = dataclasses.replace(l5.fd_beam(50, 4), width=0.3)
    sphere = l5.Sphere(l5.RADIUS, l5.STEEL, mass=5 * l5.MASS)
    with pytest.warns(ModelValidityWarning, match="beyond the 3D calibration"):
        l5.simulate_fd(wide, l5.law_for_sphere(l5.LAW, sphere, l5.STEEL), 5 * l5.MASS,
                       l5.VELOCITY, duration=0.003)


@pytest.fixture(scope="module")
def wide_coupled():
    """The coupled FD impact with the wide-section model (200 × 10): it made FORCE_WIDE_CSV."""
    return l5.fd_impact(*l5.FD_GRID, duration=l5.FE_END, width_constraint=True)


def test_committed_wide_force_is_the_current_fd_force(wide_coupled):
    """The second committed load (the wide-section model's coupled impact, sampled every
    5 µs) is still what the FD gives: largest sample and impulse within 0.5 %."""
    if not l5.FORCE_WIDE_CSV.exists():
        pytest.skip("level5_force_wide.csv not committed")
    times, force = l5.prescribed_force(csv=l5.FORCE_WIDE_CSV)
    h = wide_coupled.history
    now = np.interp(times, h["time_s"], h["force_N"])
    assert now.max() == pytest.approx(force.max(), rel=0.005)
    assert np.trapezoid(now, times) == pytest.approx(np.trapezoid(force, times), rel=0.005)


def test_wide_model_under_its_own_force(wide_coupled):
    """A second load history: the 3D beam driven by the wide-section model's own coupled
    force (11 contacts, 68.0 kN largest). Peak: the goal holds (FD under the same force
    +1.9 %, finer grids +1.0 … +1.4 %; the coupled run +2.0 %). Permanent: **the 5 % goal is
    missed here** — measured +9.9 % (200 × 10; +8.6 % at 200 × 20, +7.5 % at 400 × 20; the
    uniaxial section +38.5 %), asserted as a band; under the first load it is −4.3 %. The
    model removes three quarters of the uniaxial section's bias, but its permanent
    deflection is within about ±10 % of the 3D beam, not 5 % (README, Level 5)."""
    run, _h = _reference(l5.REFERENCE_WIDE_FORCE)
    t, w, perm = l5.fd_prescribed(*l5.prescribed_force(csv=l5.FORCE_WIDE_CSV),
                                  width_constraint=True, permanent=True)
    assert w.max() == pytest.approx(run["peak_deflection_m"], rel=PEAK_GOAL)
    assert 0.05 <= perm / run["permanent_deflection_m"] - 1 <= 0.15
    coupled = l5.fd_summary(wide_coupled)
    assert coupled["peak_deflection_m"] == pytest.approx(run["peak_deflection_m"], rel=PEAK_GOAL)
    assert 0.05 <= coupled["permanent_deflection_m"] / run["permanent_deflection_m"] - 1 <= 0.15
