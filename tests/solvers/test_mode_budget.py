"""The mode budget (impactmaps.solvers.mode_budget): mode counts without building modes,
the memory cap, and what answers the light-impactor corner (issue 12, "Corners blow up")."""

from __future__ import annotations

import json
import math
import subprocess
import sys
import warnings

import numpy as np
import pytest

from impactmaps.contact.linear import LinearContact
from impactmaps.maps.family.structures import MapStructure
from impactmaps.solvers import mode_budget
from impactmaps.solvers.modal import ModalSettings, simulate, simulate_normalised
from impactmaps.solvers.mode_budget import ModeBudgetError, ModeBudgetWarning, plan_basis

from ..helpers import DATA, ROOT

GIB = 1024**3

STRUCTURES = [
    MapStructure(kind="plate", theory="kirchhoff", supports="SSSS"),
    MapStructure(kind="plate", theory="mindlin", supports="SSSS", slenderness=20),
    MapStructure(kind="plate", theory="kirchhoff", supports="SSSS", aspect_ratio=2.0, impact_fraction=(0.3, 0.4)),
    MapStructure(kind="plate", theory="kirchhoff", supports="CCCC"),
    MapStructure(kind="beam", theory="euler", supports="ss"),
    MapStructure(kind="beam", theory="timoshenko", supports="ss", slenderness=20),
    MapStructure(kind="beam", theory="rayleigh", supports="ss"),
    MapStructure(kind="beam", theory="euler", supports="cc"),
    MapStructure(kind="beam", theory="euler", supports="ff", impact_fraction=(0.3,)),
    MapStructure(kind="beam", theory="euler", supports="cf"),
    MapStructure(kind="beam", theory="euler", supports="cs"),
]


def _built_count(target, frequency: float) -> int:
    return int(np.sum(target.modes(frequency, min_modes=1).frequencies <= frequency))


@pytest.mark.parametrize("structure", STRUCTURES, ids=lambda s: s.name)
def test_mode_count_equals_the_modes_built(structure):
    target = structure.build()
    fundamental = target.fundamental_frequency()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # Ritz / thickness-shear notices at high cut-offs
        for ratio in (0.5, 1.0, 3.3, 17.0, 150.0, 1234.5):
            frequency = ratio * fundamental
            assert target.mode_count(frequency) == _built_count(target, frequency), ratio


@pytest.mark.parametrize("structure", STRUCTURES[:3] + STRUCTURES[4:6], ids=lambda s: s.name)
def test_mode_count_past_the_limit_is_a_lower_bound_above_it(structure):
    target = structure.build()
    frequency = 3000.0 * target.fundamental_frequency()
    exact = target.mode_count(frequency)
    assert exact > 50
    bounded = target.mode_count(frequency, limit=50)
    assert 50 < bounded <= exact


def test_mode_count_of_a_huge_cut_off_allocates_nothing_large():
    import tracemalloc

    target = STRUCTURES[1].build()  # Mindlin: ~ω² modes, billions at this cut-off
    tracemalloc.start()
    try:
        count = target.mode_count(1e7 * target.fundamental_frequency(), limit=mode_budget.MAX_MODES)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert count > mode_budget.MAX_MODES
    assert peak < 16 * 1024**2


def _doubling_cap(target, max_modes):
    """The sweep's original frequency cap: the same doubling on built modes."""
    frequency = float(target.modes(0.0, min_modes=1).frequencies[0]) * 1.5 + 1e-30
    count = 0
    while True:
        more = target.modes(2.0 * frequency, min_modes=1).size
        if more > max_modes or more <= count:
            return frequency
        count, frequency = more, 2.0 * frequency


@pytest.mark.parametrize("structure", STRUCTURES[:3] + STRUCTURES[4:6], ids=lambda s: s.name)
def test_frequency_cap_is_the_doubling_on_built_modes(structure):
    target = structure.build()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        assert mode_budget.frequency_cap(target, 3000) == _doubling_cap(target, 3000)


def test_frequency_cap_starts_from_the_first_elastic_mode_of_a_free_beam():
    target = MapStructure(kind="beam", theory="euler", supports="ff", impact_fraction=(0.3,)).build()
    cap = mode_budget.frequency_cap(target, 100)
    assert target.mode_count(cap) <= 100 < target.mode_count(2.0 * cap)


def test_zeta_1e_6_point_is_answered_by_the_infinite_plate():
    target = STRUCTURES[0].build()
    with pytest.warns(ModeBudgetWarning, match="infinite-plate"):
        result = simulate_normalised(target, 1e-6, 1.0, settings=ModalSettings(check_convergence=True))
    assert result.method == "infinite-structure-asymptote"
    assert "infinite-plate (linear" in result.details.asymptote
    assert 0.0 <= result.fmax_normalised <= 1.0
    assert result.fmax_normalised == pytest.approx(float(target.infinite_structure_peak(1e-6)), rel=1e-9)
    assert result.n_modes == 0 and result.impacts == 1 and not result.time_limit_reached
    history = result.normalised_history()
    assert history["force_normalised"].max() == pytest.approx(result.fmax_normalised, rel=1e-5)
    assert result.summary()["asymptote"] == result.details.asymptote


def test_below_the_cap_the_plan_is_the_plain_modal_run():
    target = STRUCTURES[0].build()
    law = LinearContact(1e6)
    plan = plan_basis(target, law, 0.01, 1.0, 40.0 * math.sqrt(1e6 / 0.01))
    assert plan.method == "modal+residual" and plan.asymptote is None


def _near_edge_plate():
    from impactmaps.materials import material
    from impactmaps.targets.plates.plate import Plate

    return Plate.isotropic(0.25, 0.25, 0.004, material("structural-steel"), impact_point=(0.001, 0.125))


def test_capped_basis_when_a_reflection_returns_early():
    plate, law = _near_edge_plate(), LinearContact(1e6)
    omega = math.sqrt(1e6 / 1e-9)
    plan = plan_basis(plate, law, 1e-9, 1.0, 40.0 * omega)
    assert plan.method == "modal+residual-capped"
    assert plate.mode_count(plan.max_frequency) <= mode_budget.MAX_MODES
    assert plan.max_frequency >= mode_budget.MIN_CAPPED_CUTOFF_RATIO * omega
    with pytest.warns(ModeBudgetWarning, match="residual flexibility for the rest"):
        result = simulate(plate, law, 1e-9, 1.0, record=False)
    assert result.method == "modal+residual-capped"
    assert 0 < result.n_modes <= mode_budget.MAX_MODES


def test_refused_with_the_input_its_value_and_the_valid_range():
    plate, law = _near_edge_plate(), LinearContact(1e6)
    with pytest.raises(ModeBudgetError, match=r"impactor_mass = 1e-10 kg is invalid.*valid range") as error:
        simulate(plate, law, 1e-10, 1.0)
    assert isinstance(error.value, ValueError)
    heavier = 1.01 * error.value.lightest_mass  # inside the valid range: answered
    plan = plan_basis(plate, law, heavier, 1.0, 40.0 * math.sqrt(1e6 / heavier))
    assert plan.method in mode_budget.METHODS


@pytest.mark.parametrize("mass, method", [("1e-9", "modal+residual"), ("1e-12", "infinite-structure-asymptote")])
def test_light_sphere_cases_on_a_kirchhoff_plate_are_answered(mass, method, tmp_path):
    """The 1e-12 kg sphere needs millions of modes: the infinite plate answers; the 1e-9 kg
    one fits the cap (64 k modes): the modal run. Both at the Hertz half-space value to 1e-4
    (the plate barely moves in so short a contact), restitution 1."""
    from impactmaps.cases import load_case, run_case, write_case_outputs
    from impactmaps.closed_forms.law_asymptotes import asymptote

    case = load_case(DATA / f"light_sphere_{mass}kg_kirchhoff.toml")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the mode-budget notice, no history, Hertz pressure
        result, summary = run_case(case)
    assert result.method == method
    if method == "infinite-structure-asymptote":
        assert summary["asymptote"] == "infinite-plate (any law)"
        assert result.history is None
    assert not result.time_limit_reached
    half_space = asymptote("half-space", None, case.law, case.impactor_mass, case.velocity)
    assert result.peak_force == pytest.approx(half_space.peak_force, rel=1e-4)
    assert 0.0 < summary["fmax_normalised"] < 1.0  # Hertz: the half-space value is ~0.913
    assert summary["restitution"] == pytest.approx(1.0, abs=1e-4)
    paths = write_case_outputs(case, result, tmp_path)
    assert paths["summary"].exists()


def test_case_refusal_names_the_case_key():
    from impactmaps.cases import load_case, run_case

    case = load_case(DATA / "light_sphere_near_edge.toml")
    with pytest.raises(ValueError, match=r"impactor\.mass = 1e-09 kg is invalid.*valid range: impactor\.mass ≥ about"):
        run_case(case)


def test_sweep_point_past_the_cap_takes_the_asymptote():
    from impactmaps.maps.compute.sweep import METHODS, solve_points

    structure = STRUCTURES[0]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        (row,) = solve_points(structure, [(1e-6, 1.0)], ModalSettings())
    assert METHODS[row["method"]] == "infinite-structure-asymptote"
    assert row["fmax_normalised"] == float(structure.build().infinite_structure_peak(1e-6))


def _child_run(argv) -> tuple[subprocess.CompletedProcess, int]:
    """Run ``impactmaps ARGV`` as the child of a fresh interpreter; (its result, its peak RSS [B])."""
    script = (
        "import resource, subprocess, sys\n"
        f"done = subprocess.run([sys.executable, '-m', 'impactmaps.cli', *{list(argv)!r}], "
        "capture_output=True, text=True)\n"
        "sys.stdout.write(done.stdout); sys.stderr.write(done.stderr)\n"
        "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)\n"
        "sys.exit(done.returncode)\n"
    )
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, cwd=ROOT)
    *output, peak = run.stdout.strip().splitlines()
    return subprocess.CompletedProcess(run.args, run.returncode, "\n".join(output), run.stderr), int(peak) * 1024


def test_cli_point_at_zeta_1e_6_stays_within_1_gib():
    run, peak = _child_run(["point", "--target", "plate-ss", "--zeta", "1e-6", "--lambda", "1", "--json"])
    assert run.returncode == 0, run.stderr
    values = json.loads(run.stdout)
    assert values["method"] == "infinite-structure-asymptote"
    assert values["asymptote"].startswith("infinite-plate")
    assert values["fmax_normalised"] <= 1.0
    assert peak < GIB


def test_cli_light_sphere_case_stays_within_1_gib(tmp_path):
    run, peak = _child_run(["simulate", str(DATA / "light_sphere_1e-12kg_kirchhoff.toml"), "--out",
                            str(tmp_path), "--json"])
    assert run.returncode == 0, run.stderr
    assert json.loads(run.stdout)["method"] == "infinite-structure-asymptote"
    assert peak < GIB


@pytest.mark.parametrize("mass", ["1e-9", "1e-12"])
def test_cli_light_sphere_on_a_mindlin_plate_is_refused_within_1_gib(mass, tmp_path):
    """No infinite-structure solution holds for a Mindlin plate (the classical closed forms
    are Kirchhoff's), so past the mode cap the run is refused: one line, exit 2."""
    run, peak = _child_run(["simulate", str(DATA / f"light_sphere_{mass}kg.toml"), "--out", str(tmp_path)])
    assert run.returncode == 2
    lines = run.stderr.strip().splitlines()
    assert len(lines) == 1 and "no infinite-structure solution answers for a mindlin target" in lines[0]
    assert "Traceback" not in run.stderr
    assert peak < GIB


def test_cli_refusal_is_exit_2_and_one_line(tmp_path):
    run, peak = _child_run(["simulate", str(DATA / "light_sphere_near_edge.toml"), "--out", str(tmp_path)])
    assert run.returncode == 2
    lines = run.stderr.strip().splitlines()
    assert len(lines) == 1 and "impactor.mass" in lines[0] and "Traceback" not in run.stderr
    assert peak < GIB


def test_frequency_cap_crosses_the_cantilever_gap():
    """Bug fixed: the cap stopped at the first doubling that added no mode, so a cantilever
    (ω2/ω1 = 6.27: 3 ω1 and 6 ω1 both hold one mode) was capped at 3 ω1 and every map point
    on it came out unresolved. The cap now holds many modes, and a bounded model still
    stops at its largest frequency."""
    cantilever = MapStructure(kind="beam", theory="euler", supports="cf", impact_fraction=(0.7,)).build()
    cap = mode_budget.frequency_cap(cantilever)
    assert cantilever.mode_count(cap, limit=mode_budget.MAX_MODES) > 100
    ritz = MapStructure(kind="plate", theory="kirchhoff", supports="CCCC").build()
    top = mode_budget.frequency_cap(ritz)
    assert math.isfinite(top) and ritz.mode_count(8.0 * top, limit=10**6) == ritz.mode_count(top, limit=10**6)
