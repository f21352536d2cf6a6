"""The `impactmaps` command: JSON keys, values against the library, errors."""

from __future__ import annotations

import json

import numpy as np
import pytest

from impactmaps.cli import main

from ..helpers import EXAMPLES, strict_json_loads


def run(capsys, *argv):
    status = main([*argv, "--json"])
    out = capsys.readouterr().out
    return status, json.loads(out)


def test_restitution(capsys):
    from impactmaps.closed_forms.halfspace import restitution

    status, values = run(capsys, "restitution", "--beta", "10")
    assert status == 0 and values["restitution"] == pytest.approx(float(restitution(10.0)))
    status, values = run(capsys, "restitution", "--beta", "0.5")
    assert values["restitution"] == pytest.approx(1.0)


def test_halfspace_hertz_matches_closed_form(capsys):
    """Hertz impact from the command line equals the classical closed forms."""
    from impactmaps.contact import effective_modulus
    from impactmaps.closed_forms.halfspace import hertz_contact_time, hertz_peak_force

    status, values = run(capsys, "halfspace", "--law", "hertz", "--radius", "0.01", "--velocity", "2",
                         "--youngs-modulus", "2e11", "--poisson-ratio", "0.3", "--density", "7800")
    assert status == 0
    mass = 7800 * 4 / 3 * np.pi * 0.01**3
    stiffness = 4 / 3 * np.sqrt(0.01) * effective_modulus(2e11, 0.3, 2e11, 0.3)
    assert values["impactor_mass_kg"] == pytest.approx(mass)
    assert values["peak_force_N"] == pytest.approx(float(hertz_peak_force(mass, 2.0, stiffness)), rel=1e-6)
    assert values["first_contact_duration_s"] == pytest.approx(float(hertz_contact_time(mass, 2.0, stiffness)), rel=1e-6)
    assert values["restitution"] == pytest.approx(1.0, abs=1e-6)


def test_halfspace_with_catalogue_materials(capsys):
    status, values = run(capsys, "halfspace", "--law", "yigit-christoforou", "--radius", "0.005",
                         "--velocity", "3", "--material", "structural-steel", "--target-material",
                         "aluminium-6061-t6")
    assert status == 0 and 0 < values["restitution"] < 1 and values["permanent_indentation_m"] > 0


def test_asymptotes(capsys):
    from impactmaps.closed_forms.asymptotes import infinite_beam_peak

    _, values = run(capsys, "asymptote", "infinite-beam", "--zeta", "0.3")
    assert values["fmax_normalised"] == pytest.approx(float(infinite_beam_peak(0.3)))
    _, values = run(capsys, "asymptote", "infinite-plate", "--zeta", "1")
    assert values["fmax_normalised"] == pytest.approx(np.exp(-1))
    _, values = run(capsys, "asymptote", "quasi-static", "--lambda", "0.425")
    assert values["fmax_normalised"] == pytest.approx(np.sqrt(0.425 / 1.425))
    assert set(values) >= {"fmax_normalised", "impacts", "contact_time_normalised"}


def test_point_plate(capsys):
    status, values = run(capsys, "point", "--target", "plate-ss", "--theory", "kirchhoff", "--zeta", "1.198",
                         "--lambda", "0.425", "--no-check")
    assert status == 0
    assert values["regime"] == "transition"
    assert set(values) >= {"fmax_normalised", "impacts", "contact_time_normalised"}
    assert values["quasi_static_fmax"] == pytest.approx(np.sqrt(0.425 / 1.425))


@pytest.mark.parametrize(
    "argv, fragment",
    [
        (["point", "--target", "plate-ss", "--zeta", "-1", "--lambda", "1"], "--zeta = -1"),
        (["point", "--target", "shell-ss", "--zeta", "1", "--lambda", "1"], "--target"),
        (["point", "--target", "plate-ss", "--zeta", "1", "--lambda", "1", "--aspect", "0"], "--aspect = 0"),
        (["halfspace", "--law", "nope", "--radius", "0.01", "--velocity", "1", "--material", "structural-steel",
          "--target-material", "structural-steel"], "contact law"),
        (["halfspace", "--law", "hertz", "--radius", "-0.01", "--velocity", "1", "--material", "structural-steel",
          "--target-material", "structural-steel"], "radius"),
        (["halfspace", "--law", "hertz", "--radius", "0.01", "--velocity", "1", "--youngs-modulus", "2e11",
          "--poisson-ratio", "0.5", "--density", "7800"], "poisson_ratio"),
    ],
)
def test_bad_input_exits_2_with_message(capsys, argv, fragment):
    status = main(argv)
    captured = capsys.readouterr()
    assert status == 2
    assert fragment in captured.err


def test_public_api_names_resolve():
    """Every lazily re-exported name of the package resolves."""
    import impactmaps

    for name in impactmaps.__all__:
        assert getattr(impactmaps, name) is not None
    assert float(impactmaps.restitution(0.5)) == pytest.approx(1.0)


def test_asymptote_of_a_case_uses_its_own_law(capsys):
    """`impactmaps asymptote infinite-plate --case CASE.toml --json` (issue 'Maps and lookups
    for the contact a user really has'): the infinite-plate solution with the case's Hertz
    law, in newtons and seconds, the same numbers as the library call, strict JSON, the
    model's violated assumptions listed; a limit that does not fit the case is refused."""

    from impactmaps.cases import load_case
    from impactmaps.closed_forms.law_asymptotes import asymptote

    path = EXAMPLES / "steel_plate_hertz.toml"
    assert main(["asymptote", "infinite-plate", "--case", str(path), "--json"]) == 0
    values = strict_json_loads(capsys.readouterr().out)
    case = load_case(path)
    direct = asymptote("infinite-plate", case.target, case.law, case.impactor_mass, case.velocity)
    assert values["peak_force_N"] == pytest.approx(direct.peak_force, rel=1e-12)
    assert values["contact_time_s"] == pytest.approx(direct.contact_time, rel=1e-12)
    assert values["impacts"] == 1 and isinstance(values["model_warnings"], list)
    assert main(["asymptote", "infinite-beam", "--case", str(path)]) == 2
    assert main(["asymptote", "half-space", "--zeta", "1"]) == 2


def test_the_command_runs_one_blas_thread_unless_the_user_says_otherwise():
    """The command line sets one BLAS thread before NumPy loads (its sweep workers inherit
    it: N workers with N BLAS threads each oversubscribe the cores); a value the user set
    is kept."""
    import os
    import subprocess
    import sys

    probe = "import os, impactmaps.cli; print(os.environ['OPENBLAS_NUM_THREADS'], os.environ['OMP_NUM_THREADS'])"
    env = {k: v for k, v in os.environ.items() if k not in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")}
    done = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, env=env, check=True)
    assert done.stdout.split() == ["1", "1"]
    done = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, check=True,
                          env=env | {"OPENBLAS_NUM_THREADS": "4"})
    assert done.stdout.split() == ["4", "1"]
