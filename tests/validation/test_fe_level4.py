"""Level 4 of the CalculiX cross-check: full 3D contact dynamics against the toolkit.

The FE numbers are read from ``validation/fe/results/level4_contact.json`` (produced by
``validation/fe/level4_contact.py``, commands in validation/fe/README.md); the toolkit
side is recomputed now (modal solver: Hertz for the elastic target, refined Stronge
for the elastic–plastic one; FD Rayleigh beam with the same laws), so a change of the
solvers that moves them away from 3D elasticity fails here.  No ``ccx`` needed, except
for the end-to-end smoke test (marker ``fe``).

Tolerances: the issue's goals for full contact are peak force within 5 % and
restitution within 0.05 of FE.  They are asserted where the committed FE value is
converged (its mesh and step differences, stored with the runs, are checked here to be
several times smaller than the tolerance); where the toolkit misses a goal, the test
asserts the measured difference band instead and says why.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np
import pytest

FE_DIR = Path(__file__).resolve().parents[2] / "validation" / "fe"
sys.path.insert(0, str(FE_DIR))

import ccx_tools  # noqa: E402

RESULTS = FE_DIR / "results" / "level4_contact.json"
_AVAILABLE, _REASON = ccx_tools.have_fe_tools()

PEAK_GOAL = 0.05                 # the issue: peak force within 5 %
RESTITUTION_GOAL = 0.05          # the issue: restitution within 0.05
# An FE value is a reference only if its own mesh / step differences are at most this
# (relative for forces and durations, absolute for the restitution): a fifth of the goal.
FE_CONVERGED = {"peak_force_N": 0.01, "first_contact_s": 0.01, "restitution": 0.01}


def _data():
    if not RESULTS.exists():
        pytest.skip("validation/fe/results/level4_contact.json not committed")
    return json.loads(RESULTS.read_text())


def _reference(case):
    import level4_contact
    data = _data()
    ref, mesh_pair, step_pair = level4_contact.fe_reference(data.get("runs", {}), case)
    if ref is None:
        pytest.skip(f"no separated level-4 FE run of the {case} case committed")
    return ref, mesh_pair, step_pair


def _toolkit(case):
    import level4_contact
    return {k: level4_contact.summary(*v)
            for k, v in level4_contact.toolkit_runs_cached(case).items()}


def _spread(pair, key):
    a, b = pair[0][key], pair[1][key]
    return abs(a - b) if key == "restitution" else abs(a / b - 1)


@pytest.mark.fe
@pytest.mark.skipif(not _AVAILABLE, reason=_REASON)
def test_level4_smoke_end_to_end(tmp_path):
    """Mesh → deck → ccx (implicit contact dynamics, 5 increments) → momentum force.

    A very coarse mesh (h0 = the Hertz radius) over the first 10 µs of the elastic
    impact: the sphere's meshed mass is its true mass (isoparametric mass row sums),
    and the contact force at 9 µs, where the beam has barely moved, is the Hertz
    force K_h (V0 t)^{3/2} within 15 % (this coarse mesh gives +7 %; the production
    meshes are three and more times finer).
    """
    import level4_contact

    data = level4_contact.main(["--smoke", "--out-dir", str(tmp_path)])
    (run,) = data["runs"].values()
    assert run["sphere_mesh_mass_kg"] == pytest.approx(run["sphere_mass_kg"], rel=5e-3)
    history = np.loadtxt(tmp_path / run["csv"], delimiter=",", skiprows=1)
    t, force = history[-1, 0], history[-1, 1]
    stiffness = level4_contact.impactmaps.law_for_sphere(
        "hertz", level4_contact.sphere(), level4_contact.STEEL).stiffness
    assert force == pytest.approx(stiffness * (level4_contact.VELOCITY * t) ** 1.5, rel=0.15)


def test_level4_elastic_fe_is_converged():
    """The committed elastic FE reference has its convergence evidence: a run on the
    other contact mesh and a run at the other time step, each within ``FE_CONVERGED``
    of its partner for peak force, first-contact duration and restitution."""
    ref, mesh_pair, step_pair = _reference("elastic")
    for pair in (mesh_pair, step_pair):
        assert pair is not None, "a mesh pair and a step pair must be committed"
        for key, limit in FE_CONVERGED.items():
            assert _spread(pair, key) <= limit, (key, pair[0]["csv"], pair[1]["csv"])


@pytest.mark.parametrize("solver", ["modal_hertz", "fd_hertz"])
def test_level4_elastic_peak_and_restitution(solver):
    """The issue's goals on the elastic case: peak force within 5 %, restitution within
    0.05 of the 3D contact run (measured: modal Timoshenko −2.7 %, −0.003; FD Rayleigh
    −1.0 %, +0.010; the FE reference converged to 0.5 %: mesh ≤ 0.02 %, step ≤ 0.49 %)."""
    ref, _, _ = _reference("elastic")
    run = _toolkit("elastic")[solver]
    assert abs(run["peak_force_N"] / ref["peak_force_N"] - 1) <= PEAK_GOAL
    assert abs(run["restitution"] - ref["restitution"]) <= RESTITUTION_GOAL
    assert run["impacts"] == 1


@pytest.mark.parametrize("solver", ["modal_hertz", "fd_hertz"])
def test_level4_elastic_first_contact(solver):
    """First-contact duration within 5 % of FE (the issue sets no goal for full contact;
    5 % is its goal for the spring-coupled level 3; measured +1.9 % modal, +1.0 % FD)."""
    ref, _, _ = _reference("elastic")
    run = _toolkit("elastic")[solver]
    assert run["first_contact_s"] == pytest.approx(ref["first_contact_s"], rel=0.05)


INDENT = FE_DIR / "results" / "level4_plastic_indent.json"
# refined Stronge law (the energy-consistent form) / FE − 1, quasi-static load–unload to
# the impact's α_max (101 δ_y, past δ_p: force and dent are those of the printed form,
# the work absorbed on the way is smaller), fine mesh, 20 + 20 increments: measured
# +7.5 % / −9.3 % / +1.1 % (coarse − fine mesh: −2.4 % / +0.3 % / +0.7 %; 10 − 20
# increments: +1.0 % / −0.1 % / +1.5 %); the bands hold the measured value with a margin
# of about twice those differences (at least 3 points) on each side. (The printed form
# dissipated +8.9 %: band (0.07, 0.14) until the law was made consistent.)
INDENT_BANDS = {"force_at_max_N": (0.035, 0.135),
                "permanent_indentation_m": (-0.125, -0.06),
                "dissipated_energy_J": (-0.02, 0.045)}


def test_level4_stronge_law_against_3d_plasticity():
    """The refined Stronge law against the 3D elastic–perfectly plastic indentation.

    ccx 2.20 cannot run the plastic impact dynamically (validation/fe/README.md,
    level 4), so the elastic–plastic case is checked on its contact law: the elastic
    sphere pressed quasi-statically into a 235 MPa block to the impact's largest
    indentation (the toolkit's modal refined-Stronge run) and unloaded.  The law is
    stiffer than the 3D solid (force at α_max above FE), leaves a smaller dent and
    dissipates more energy; the issue's 5 % / 0.05 goals concern the dynamic peak and
    restitution, which this check does not give, so the measured differences are
    asserted as bands (``INDENT_BANDS``), so that a change of the law that moves it
    away from — or towards — 3D plasticity shows up here.  Measured (fine mesh):
    the law's force at α_max +7.5 %, its permanent indentation −9.3 %, its
    dissipated energy +1.1 % against FE (fine mesh, 20 + 20 increments).  The FE cycle
    went to the α_max of the modal run with the printed law; the consistent law's run
    goes 2.2 % deeper (softer from δ_y to δ_p), within 3 %.
    """
    if not INDENT.exists():
        pytest.skip("validation/fe/results/level4_plastic_indent.json not committed")
    import level4_plastic_indent
    data = json.loads(INDENT.read_text())
    ref = data[level4_plastic_indent.reference(data)[0]]
    law = level4_plastic_indent.stronge_law()
    alpha_max = ref["max_indentation_m"]
    toolkit = {"force_at_max_N": float(law.loading_force(alpha_max)),
               "permanent_indentation_m": float(law.permanent_indentation(alpha_max)),
               "dissipated_energy_J": float(law.dissipated_energy(alpha_max))}
    for key, (low, high) in INDENT_BANDS.items():
        assert low <= toolkit[key] / ref[key] - 1 <= high, (key, toolkit[key], ref[key])
    # the FE cycle went to the modal run's α_max: it must still be the impact's
    modal = level4_plastic_indent.l4.toolkit_runs_cached("plastic")["modal_stronge"][0]
    assert modal.max_indentation == pytest.approx(alpha_max, rel=0.03)
