"""The wide-section model of the FD beam (impactmaps.fd.wide_section and the constraint
back stress of impactmaps.fd.section.return_map).

Exact references: the monotonic stress of a perfectly plastic layer with an
Armstrong–Frederick back stress, ``σ = σ_y + β_sat (1 − exp(−ε_p/ε_c))``, reached for an
increment of any size; the trapezoidal plastic-work identity; the uniaxial section
recovered for b/h ≤ 1. The calibration against the 3D limit loads is checked here too
(``validation/fe/results/level5_wide_calibration.json``, committed; no ccx).
"""

from __future__ import annotations

import dataclasses
import json
import math
from pathlib import Path

import numpy as np
import pytest

from impactmaps.fd import FDBeam, LayeredSection, simulate_fd_response, stress_update
from impactmaps.fd import wide_section as ws
from impactmaps.fd.section import return_map

E, SY = 210e9, 235e6
CALIBRATION = Path(__file__).resolve().parents[2] / "validation" / "fe" / "results" / \
    "level5_wide_calibration.json"


@pytest.mark.parametrize("steps", [1, 3, 40])
def test_constraint_stress_is_exact_for_any_increment(steps):
    """Monotonic straining of one perfectly plastic layer: σ(ε_p) = σ_y + β_sat(1 − e^{−ε_p/ε_c})
    whatever the number of increments (the return solves the increment exactly)."""
    saturation, strain = 0.1 * SY, 2e-3
    total = 5 * SY / E + 4e-3
    stress = back = constraint = plastic = 0.0
    for d in np.full(steps, total / steps):
        stress, back, constraint, p, _w = return_map(stress, back, constraint, d, E, SY, 0.0,
                                                     saturation, 1 / strain)
        plastic += p
    expected = SY + saturation * (1 - math.exp(-plastic / strain))
    assert stress == pytest.approx(expected, rel=1e-12)
    assert back == pytest.approx(constraint, rel=1e-12)
    assert plastic == pytest.approx(total - stress / E, rel=1e-12)


def test_constraint_is_kinematic_and_bounded():
    """After loading to saturation a reversal re-yields at β_c − σ_y (kinematic), and β_c
    never leaves [−β_sat, β_sat] along a cyclic path; the plastic-work identity
    ½(σ* + σ)Δε = Δ(σ²/2E) + ΔW_p holds to round-off on every step."""
    saturation, rate = 0.12 * SY, 800.0
    rng = np.random.default_rng(3)
    path = np.concatenate([np.full(30, 1e-4), np.full(60, -1e-4), rng.normal(0, 3e-4, 300)])
    stress = back = constraint = 0.0
    for d in path:
        new, back, constraint, _p, work = return_map(stress, back, constraint, d, E, SY, 0.0,
                                                     saturation, rate)
        identity = 0.5 * (stress + new) * d - (new**2 - stress**2) / (2 * E) - work
        assert abs(identity) <= 1e-9 * SY * abs(d) + 1e-6
        assert abs(constraint) <= saturation * (1 + 1e-12)
        assert abs(new - back) <= SY * (1 + 1e-12)
        stress = new
    # load to saturation, then reverse: first reverse yield at β_c − σ_y
    stress = back = constraint = 0.0
    stress, back, constraint, _p, _w = return_map(stress, back, constraint, 0.05, E, SY, 0.0,
                                                  saturation, rate)
    assert constraint == pytest.approx(saturation, rel=1e-9)
    elastic_range = 2 * SY
    trial, *_ = return_map(stress, back, constraint, -0.999 * elastic_range / E, E, SY, 0.0,
                           saturation, rate)
    assert trial == pytest.approx(stress - 0.999 * elastic_range, rel=1e-12)  # still elastic


def test_without_constraint_the_update_is_the_uniaxial_one():
    """β_sat = 0 gives bit for bit the closed-form linear-kinematic return."""
    rng = np.random.default_rng(7)
    stress, back, inc = rng.normal(0, SY, 50), rng.normal(0, 0.1 * SY, 50), rng.normal(0, 3e-3, 50)
    old = stress_update(stress, back, inc, E, SY, 1e9)
    trial = stress + E * inc
    excess = np.abs(trial - back) - SY
    mult = np.where(excess > 0, excess, 0.0) / (E + 1e9) * np.sign(trial - back)
    assert np.array_equal(old[0], trial - E * mult)
    assert len(old) == 4


def test_fraction_is_zero_for_narrow_sections_and_grows_to_its_limit():
    """φ(b/h) − φ(1): 0 for b/h ≤ 1, increasing, below 1 − φ(1) (plane strain at b ≫ h)."""
    h = 0.02
    assert ws.constraint_fraction(0.5 * h, h) == 0.0
    assert ws.constraint_fraction(h, h) == 0.0
    ratios = np.array([1.01, 1.5, 2, 4, 8, 50, 1e4])
    values = [ws.constraint_fraction(r * h, h) for r in ratios]
    assert np.all(np.diff(values) > 0)
    limit = 1 - (1 - math.tanh(0.5 / ws.EDGE_LENGTH) / (0.5 / ws.EDGE_LENGTH))
    assert values[-1] == pytest.approx(limit, rel=1e-3)
    assert ws.constraint_parameters(0.5 * h, h, E, SY) == (0.0, 0.0)


def test_narrow_beam_is_unchanged_and_wide_beam_is_stronger():
    """b/h ≤ 1: the FD beam is the uniaxial one bit for bit; b/h = 2.16 (seed-000 beam):
    the section's limit moment is (σ_y + β_sat) b h²/4 and a static overload deflects less."""
    narrow = FDBeam(0.78, 0.02, 0.0278, E, 7850.0, SY, n_elements=40, n_half_layers=4)
    wide = dataclasses.replace(narrow, width=0.06)

    def run(beam):
        load = 1.45 * 4 * SY * beam.width * beam.height**2 / 6 / beam.length
        damping = 2.0 * beam.mass_per_length * float(beam.simply_supported_frequency(1))
        beam = dataclasses.replace(beam, damping_per_length=damping)
        r = simulate_fd_response(beam, lambda t: load * np.minimum(t / 0.03, 1.0), duration=0.05)
        return r.history["deflection_at_load_m"].to_numpy()

    a = run(narrow)
    b = run(dataclasses.replace(narrow, width_constraint=False))
    assert np.array_equal(a, b)
    c = run(wide)
    d = run(dataclasses.replace(wide, width_constraint=False))
    assert np.allclose(d, a, rtol=1e-9, atol=1e-15)  # uniaxial: w independent of b at P ∝ b
    assert c[-1] < 0.99 * d[-1]
    section = wide.section
    assert section.constraint_saturation > 0
    assert section.limit_moment == pytest.approx(
        (SY + section.constraint_saturation) * 0.06 * 0.0278**2 / 4, rel=1e-14)
    kappa = -np.geomspace(1, 2000, 400) * section.yield_curvature
    assert section.moment_curvature(kappa)[-1] == pytest.approx(section.limit_moment, rel=2e-3)


def test_constants_are_the_committed_calibration():
    """The module's λ and n_c are the fit of validation/fe/level5_wide_calibration.py
    (to the 2 digits printed), and the fitted form reproduces every 3D limit load within
    1 % (measured 0.45–0.84 %)."""
    if not CALIBRATION.exists():
        pytest.skip("calibration not committed")
    data = json.loads(CALIBRATION.read_text())
    assert ws.EDGE_LENGTH == pytest.approx(data["edge_length_over_h"], abs=0.006)
    assert ws.CONSTRAINT_STRAIN_RATIO == pytest.approx(data["constraint_strain_ratio"], abs=0.006)
    assert ws.CALIBRATED_RATIO == pytest.approx(max(r["width_over_height"]
                                                    for r in data["limit_loads"]), abs=0.01)
    for row in data["limit_loads"]:
        assert abs(row["fit_error"]) <= 0.01, row


def test_wide_limit_moment_follows_the_3d_limit_loads():
    """The FD section's limit moment relative to the uniaxial M_p against the 3D limit load
    relative to the b/h = 1 beam's (the 3D beam's strip-load excess common to all widths
    divides out): within 1.5 % at b/h = 2.16, 4.32, 8.63 (the model is uniaxial at 1)."""
    if not CALIBRATION.exists():
        pytest.skip("calibration not committed")
    rows = {round(r["width_over_height"], 2): r["fe_limit_over_Py"]
            for r in json.loads(CALIBRATION.read_text())["limit_loads"]}
    h = 0.0278
    for ratio in (2.16, 4.32, 8.63):
        section = LayeredSection(ratio * h, h, E, SY, 0.0, 10,
                                 *ws.constraint_parameters(ratio * h, h, E, SY))
        model = section.limit_moment / section.plastic_moment
        assert model == pytest.approx(rows[ratio] / rows[1.0], rel=0.015), ratio


def test_settings_and_case_key_turn_the_model_off():
    """``FDSettings(width_constraint=False)`` (the case file's ``[fd] width_constraint``)
    reaches the FDBeam; a non-boolean is typed like ``plastic``."""
    from impactmaps.fd import FDSettings
    from impactmaps.materials import IsotropicMaterial
    from impactmaps.targets.beams.beam import Beam

    steel = IsotropicMaterial(E, 0.3, 7850.0, SY)
    beam = Beam.rectangular(0.78, 0.06, 0.0278, steel, theory="rayleigh", supports="ss")
    assert FDBeam.from_beam(beam, steel).width_constraint is True
    off = FDBeam.from_beam(beam, steel, FDSettings(width_constraint=False))
    assert off.width_constraint is False
    assert off.section.constraint_saturation == 0.0
    assert FDBeam.from_beam(beam, steel).section.constraint_saturation > 0.0
