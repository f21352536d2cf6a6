"""One vocabulary: the numbers a command prints for a case mean what ``lookup`` means by
them, so that one command's output can be fed to another (issue 29, item 4)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from impactmaps.cli import main

from ..helpers import HERTZ_BEAM_CASE

HERTZ_BEAM = 'name = "hertz beam"\n' + HERTZ_BEAM_CASE


def _json(argv, capsys) -> dict:
    assert main([*argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


@pytest.fixture
def hertz_beam(tmp_path):
    path = tmp_path / "hertz_beam.toml"
    path.write_text(HERTZ_BEAM)
    return path


def test_simulate_numbers_fed_to_lookup_give_its_force(hertz_beam, tmp_path, capsys):
    """simulate prints ζ_h, λ_h and F/F_hs under zeta, lambda, fmax_normalised; lookup at
    those numbers, scaled by the printed F_hs, gives lookup --case's force exactly (same
    map point), and simulate's own force lies within the lookup's band plus the modal
    run's tolerance (1e-3 relative: the solver's default convergence tolerance)."""
    simulated = _json(["simulate", str(hertz_beam), "--out", str(tmp_path / "out")], capsys)
    by_case = _json(["lookup", "--case", str(hertz_beam)], capsys)
    assert simulated["zeta"] == pytest.approx(by_case["zeta"], rel=1e-12)
    assert simulated["lambda"] == pytest.approx(by_case["lambda"], rel=1e-12)
    assert simulated["force_scale_N"] == pytest.approx(by_case["force_scale_N"], rel=1e-12)
    fed = _json(["lookup", "--kind", "beam", "--theory", "euler", "--law", "hertz",
                 "--zeta", repr(simulated["zeta"]), "--lambda", repr(simulated["lambda"])], capsys)
    force = fed["fmax_normalised"] * simulated["force_scale_N"]
    assert force == pytest.approx(by_case["peak_force_N"], rel=1e-12)
    band = fed["fmax_error"] * simulated["force_scale_N"]
    assert abs(simulated["peak_force_N"] - force) <= band + 1e-3 * force
    # fmax_normalised means F/F_hs in both
    assert simulated["fmax_normalised"] == pytest.approx(simulated["peak_force_N"] / simulated["force_scale_N"])
    assert abs(simulated["fmax_normalised"] - fed["fmax_normalised"]) <= fed["fmax_error"] + 1e-3


def test_hertz_summary_keeps_linearised_numbers_under_their_own_names(hertz_beam):
    """The K_y-linearised ζ, λ of a Hertz case are reported as zeta_linearised and
    lambda_linearised, never as zeta/lambda (ζ_h, λ_h): they differ by the ratio of the
    stiffnesses, a factor ≈ 0.77 and ≈ 2.8 here."""
    from impactmaps.cases import case_dimensionless, case_numbers, load_case

    case = load_case(hertz_beam)
    numbers, linear = case_numbers(case), case_dimensionless(case)
    assert numbers["vocabulary"] == "hertz"
    assert numbers["zeta_linearised"] == linear["zeta"] and numbers["lambda_linearised"] == linear["lambda"]
    assert numbers["zeta"] != pytest.approx(linear["zeta"], rel=0.1)
    assert "Hertz numbers" in numbers["lambda_basis"]


def test_linear_case_numbers_are_the_linear_map_numbers():
    """For a linear law the vocabulary is the linear maps' own: ζ(m, K), λ = K_st/K and the
    force scale m V0 ω with ω = sqrt(K/m) (exact identities)."""
    import math

    from impactmaps.cases import case_dimensionless, case_numbers, load_case

    case = load_case(Path(__file__).resolve().parents[2] / "examples" / "aluminium_beam_linear.toml")
    numbers, linear = case_numbers(case), case_dimensionless(case)
    assert numbers["zeta"] == linear["zeta"] and numbers["lambda"] == linear["lambda"]
    omega = math.sqrt(linear["contact_stiffness_N_m"] / case.impactor_mass)
    assert numbers["force_scale_N"] == pytest.approx(case.impactor_mass * case.velocity * omega, rel=1e-15)
