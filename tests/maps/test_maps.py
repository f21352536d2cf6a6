"""Sweeps, the resumable store, regime classification and the Dask path."""

from __future__ import annotations

import json
import os
import pathlib
import subprocess
import sys

import numpy as np
import pytest
import xarray as xr

import impactmaps

from impactmaps.maps.compute import linear_points
from impactmaps.maps.compute import points as points_module
from impactmaps.maps.family.accuracy import STATUSES
from impactmaps.maps.compute import sweep as sweep_module
from impactmaps.maps.family.regimes import classify
from impactmaps.maps.files.store import StoreMismatchError
from impactmaps.maps.family.structures import MapStructure
from impactmaps.maps.compute.sweep import Pacing, sweep
from impactmaps.maps.compute.linear_points import solve_points
from impactmaps.solvers.modal_settings import ModalSettings

PLATE = MapStructure(kind="plate", theory="kirchhoff", supports="SSSS")
BEAM = MapStructure(kind="beam", theory="euler", supports="ss", impact_fraction=(0.5,))
ZETAS = np.geomspace(0.03, 30, 7)
_SOLVE_POINT = points_module.controlled_point  # the real point solver, before any test patches it
LAMBDAS = [0.2, 2.0]


@pytest.mark.parametrize("structure", [PLATE, BEAM], ids=lambda s: s.name)
def test_published_cases_are_classified_as_in_seed_001(structure):
    """Seed 001 §6: λ = 0.425 with ζ = 11.3 is fully global (quasi-static), ζ = 0.038
    locally dominated, ζ = 1.198 in the transition — for the plate and for the beam."""
    rows = solve_points(structure, [(11.3, 0.425), (0.038, 0.425), (1.198, 0.425)], ModalSettings())
    regimes = classify(
        [r["fmax_normalised"] for r in rows],
        [r["zeta"] for r in rows],
        [r["lambda_"] for r in rows],
        structure.kind,
        peak_time=[r["peak_time_normalised"] for r in rows],
        reflection_time=[r["reflection_time_normalised"] for r in rows],
    )
    assert list(regimes) == ["quasi-static", "local", "transition"]


def test_classify_needs_no_infinite_peak_after_the_reflection(monkeypatch):
    """Points that all peak after their first reflection are classified without the infinite
    structure's peak (it decides nothing there), as with it; one peaking before asks for it."""
    from impactmaps.maps.family import regimes

    fmax, zeta, lam = [0.2, 0.95, 0.5], [50.0, 0.01, 1.0], [0.05, 0.05, 4.0]
    late = dict(peak_time=[3.0, 3.0, 3.0], reflection_time=[1.0, 1.0, 1.0])
    expected = classify(fmax, zeta, lam, "plate", **late)
    asked = []
    monkeypatch.setattr(regimes, "infinite_structure_peak", lambda *args: asked.append(args) or 0.5)
    assert list(classify(fmax, zeta, lam, "plate", **late)) == list(expected) and not asked
    classify(fmax, zeta, lam, "plate", peak_time=[0.5, 3.0, 3.0], reflection_time=[1.0, 1.0, 1.0])
    assert asked


def test_classify_limits_and_validation():
    """Exact asymptote values classify as their regime; bad input is a ValueError."""
    lam = 0.425
    qs = np.sqrt(lam / (1 + lam))
    assert classify(1.0, 0.01, lam, "plate") == "local"
    assert classify(qs, 50.0, lam, "plate") == "quasi-static"
    from impactmaps.closed_forms.asymptotes import infinite_plate_peak

    assert classify(float(infinite_plate_peak(0.5)), 0.5, 0.05, "plate") == "infinite-structure"
    assert classify(0.3, 1.0, 4.0, "plate") == "transition"
    with pytest.raises(ValueError, match="kind"):
        classify(0.5, 1.0, 1.0, "shell")
    with pytest.raises(ValueError, match="tolerance"):
        classify(0.5, 1.0, 1.0, "plate", tolerance=0)


def _counting(monkeypatch, fail_after=None):
    """Count the point solves (one per point: the base run and its refinements)."""
    calls = {"n": 0}
    original = _SOLVE_POINT

    def counted(*args, **kwargs):
        calls["n"] += 1
        if fail_after is not None and calls["n"] > fail_after:
            raise KeyboardInterrupt
        return original(*args, **kwargs)

    monkeypatch.setattr(points_module, "controlled_point", counted)
    return calls


def test_resume_recomputes_nothing_finished(tmp_path, monkeypatch):
    """Interrupt a sweep, resume it with the same path: the solver is called exactly
    once per missing point, and the result equals an uninterrupted sweep."""
    path = tmp_path / "map.nc"
    total = 2 * len(LAMBDAS) * len(ZETAS)
    calls = _counting(monkeypatch, fail_after=9)
    with pytest.raises(KeyboardInterrupt):
        sweep([PLATE, BEAM], ZETAS, LAMBDAS, path=path, max_workers=1, progress=False, pacing=Pacing(3, 0.0))
    stored = xr.open_dataset(path, engine="scipy").load()
    finished = int(stored["done"].sum())
    assert 0 < finished < total
    assert not list(tmp_path.glob(".*.tmp*"))  # atomic writes leave no temporaries

    calls = _counting(monkeypatch)
    resumed = sweep([PLATE, BEAM], ZETAS, LAMBDAS, path=path, max_workers=1, progress=False, pacing=Pacing(3))
    assert calls["n"] == total - finished
    assert bool(resumed["done"].all())

    calls = _counting(monkeypatch)
    again = sweep([PLATE, BEAM], ZETAS, LAMBDAS, path=path, max_workers=1, progress=False)
    assert calls["n"] == 0

    fresh = sweep([PLATE, BEAM], ZETAS, LAMBDAS, max_workers=1, progress=False)
    np.testing.assert_array_equal(resumed["fmax_normalised"].values, fresh["fmax_normalised"].values)
    np.testing.assert_array_equal(again["regime"].values, fresh["regime"].values)


def test_foreign_or_corrupted_file_is_refused(tmp_path):
    """A result file from other settings, or an unreadable one, is refused — not mixed in."""
    path = tmp_path / "map.nc"
    sweep([PLATE], ZETAS[:2], [1.0], path=path, max_workers=1, progress=False)
    with pytest.raises(StoreMismatchError, match="different"):
        sweep([PLATE], ZETAS[:2], [1.0], path=path, settings=ModalSettings(cutoff_ratio=20.0),
              max_workers=1, progress=False)
    with pytest.raises(ValueError, match="different"):
        sweep([PLATE], ZETAS[:3], [1.0], path=path, max_workers=1, progress=False)
    broken = tmp_path / "broken.nc"
    broken.write_bytes(b"CDF\x02 this is not a sweep")
    with pytest.raises(ValueError, match="cannot be read"):
        sweep([PLATE], ZETAS[:2], [1.0], path=broken, max_workers=1, progress=False)
    other = tmp_path / "other.nc"
    xr.Dataset({"x": ("a", [1.0])}).to_netcdf(other, engine="scipy")
    with pytest.raises(ValueError, match="not an impactmaps sweep"):
        sweep([PLATE], ZETAS[:2], [1.0], path=other, max_workers=1, progress=False)


def test_dataset_is_labelled():
    """Dims, units and provenance attributes are present; the regime is filled in."""
    dataset = sweep([PLATE], ZETAS[:3], [1.0], max_workers=1, progress=False)
    assert dataset["fmax_normalised"].dims == ("structure", "lambda_", "zeta")
    assert dataset["fmax_normalised"].attrs["units"] == "1"
    assert "impactmaps_version" in dataset.attrs and "fingerprint" in dataset.attrs
    assert '"cutoff_ratio"' in dataset.attrs["description"]
    assert set(np.unique(dataset["regime"].values)) <= {"local", "infinite-structure", "transition", "quasi-static"}


def test_dask_executor_gives_the_same_numbers():
    """The same sweep on a local Dask cluster (threads) equals the local run exactly."""
    from dask import distributed  # in the test extra; imported here, not at collection (~1 s)

    local = sweep([PLATE], ZETAS[:4], LAMBDAS, max_workers=1, progress=False)
    with distributed.Client(processes=False, n_workers=1, threads_per_worker=2, dashboard_address=None) as client:
        remote = sweep([PLATE], ZETAS[:4], LAMBDAS, executor=client.get_executor(), progress=False, pacing=Pacing(2))
    np.testing.assert_array_equal(local["fmax_normalised"].values, remote["fmax_normalised"].values)
    np.testing.assert_array_equal(local["impacts"].values, remote["impacts"].values)


def test_process_pool_gives_the_same_numbers():
    """The default local process pool equals the inline run exactly."""
    inline = sweep([PLATE], ZETAS[:4], [1.0], max_workers=1, progress=False)
    pooled = sweep([PLATE], ZETAS[:4], [1.0], max_workers=2, progress=False, pacing=Pacing(2))
    np.testing.assert_array_equal(inline["fmax_normalised"].values, pooled["fmax_normalised"].values)


def _blas_threads() -> list[int]:
    from threadpoolctl import threadpool_info

    return [pool["num_threads"] for pool in threadpool_info() if pool["user_api"] == "blas"]


def _default_blas_environment(**extra) -> dict:
    """This environment without the BLAS thread variables conftest sets (each BLAS library
    then starts with a thread per core)."""
    names = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")
    return {name: value for name, value in os.environ.items() if name not in names} | extra


def test_sweep_workers_run_one_blas_thread_and_leave_the_parent_alone(monkeypatch):
    """A sweep's worker processes run one BLAS thread each (NumPy's default of one per core in
    every worker oversubscribed the cores: the bench grid took 26.5 s instead of 20.9 s on 2
    cores), and the user's own process keeps its BLAS threads."""
    from concurrent.futures import ProcessPoolExecutor

    from impactmaps.maps.compute.workers import init_worker

    before = _blas_threads()
    assert before, "no BLAS library found by threadpoolctl"
    with ProcessPoolExecutor(max_workers=1, initializer=init_worker) as pool:
        in_worker = pool.submit(_blas_threads).result()
    # in a fresh interpreter, where no BLAS is loaded before init_worker (a forked worker
    # inherits the libraries this process loaded): then a run with an exact contact phase
    package_root = str(pathlib.Path(impactmaps.__file__).resolve().parents[1])  # the package tested, installed or not
    probe = ("import json; from impactmaps.maps.compute.workers import init_worker; init_worker(False); "
             "from impactmaps.solvers.warm_up import _tiny_impacts; _tiny_impacts(); "
             "from threadpoolctl import threadpool_info; "
             "print(json.dumps([p['num_threads'] for p in threadpool_info() if p['user_api'] == 'blas']))")
    after_a_run = json.loads(subprocess.run(
        [sys.executable, "-c", probe], capture_output=True, text=True, check=True, cwd=package_root,
        env=_default_blas_environment(PYTHONPATH=package_root)).stdout.splitlines()[-1])
    assert in_worker and all(count == 1 for count in in_worker)
    assert after_a_run and all(count == 1 for count in after_a_run)
    pools = []

    def recording_pool(**options):
        pools.append(options)
        return ProcessPoolExecutor(**options)

    monkeypatch.setattr(sweep_module, "ProcessPoolExecutor", recording_pool)
    sweep([BEAM], ZETAS[:2], [1.0], max_workers=2, progress=False, pacing=Pacing(1))
    assert [options.get("initializer") for options in pools] == [init_worker]
    assert _blas_threads() == before


def test_sweep_config_sweeps_structure_parameters(tmp_path):
    """`impactmaps sweep CONFIG.toml`: a list-valued structure field (aspect ratio) is swept
    too; results land in the output directory as NetCDF and tidy CSV."""
    import pandas as pd

    from impactmaps.cli import main

    config = tmp_path / "study.toml"
    config.write_text(
        'output = "out"\n'
        "[grid]\nzeta = [0.1, 1.0]\nlambda = { min = 0.5, max = 2.0, count = 2 }\n"
        "[solver]\ncutoff_ratio = 40\n"
        '[[structure]]\nkind = "plate"\ntheory = "kirchhoff"\nsupports = "SSSS"\naspect_ratio = [1.0, 2.0]\n'
    )
    assert main(["sweep", str(config), "--quiet"]) == 0
    frame = pd.read_csv(tmp_path / "out" / "sweep.csv")
    assert len(frame) == 2 * 2 * 2
    assert set(frame["structure"]) == {"plate-ssss-kirchhoff", "plate-ssss-kirchhoff-ar2"}
    assert set(frame["status"]) <= {"converged", "refined", "sensitive", "asymptotic"}  # names, not codes
    assert set(frame["method"]) <= {"modal+residual", "infinite-structure-asymptote"}
    bad = tmp_path / "bad.toml"
    bad.write_text("[grid]\nzeta = [1.0]\nlambda = [1.0]\n[[structure]]\nkind = \"plate\"\nthickness = 3\n")
    assert main(["sweep", str(bad), "--quiet"]) == 2


def test_progress_bar_is_shown_and_can_be_switched_off(capsys):
    """A sweep reports its progress on stderr (tqdm) unless ``progress=False``."""
    sweep([BEAM], ZETAS[:2], [1.0], max_workers=1, progress=True)
    shown = capsys.readouterr().err
    assert "impact map" in shown and "2/2" in shown
    sweep([BEAM], ZETAS[:2], [1.0], max_workers=1, progress=False)
    assert capsys.readouterr().err == ""


@pytest.mark.parametrize("structure", [PLATE, BEAM], ids=lambda s: s.name)
def test_targets_answer_the_physics_of_their_kind(structure):
    """Wave-return time and infinite-structure asymptote come from the target: the
    reflection time is ω d²/c of its nearest support or edge, the peak the asymptote of
    its kind (also through the string-keyed regimes helper), and an asymptote row of a
    sweep is made of the target's InfiniteImpact."""
    import math

    from impactmaps.maps.family.regimes import infinite_structure_peak
    from impactmaps.closed_forms import asymptotes, infinite_beam

    target = structure.build()
    omega = np.array([1e3, 2e4])
    if structure.kind == "beam":
        distance = target.distance_to_nearest_support()
        speed = math.sqrt(target.bending_stiffness / target.mass_per_length)
        peak = infinite_beam.infinite_beam_peak
    else:
        distance = target.distance_to_nearest_edge()
        speed = math.sqrt(target.effective_bending_stiffness / target.mass_per_area)
        peak = asymptotes.infinite_plate_peak
    np.testing.assert_array_equal(target.reflection_time(omega), omega * distance**2 / speed)
    zetas = np.array([0.05, 0.3, 0.3, 2.0])
    expected = np.array([float(peak(z)) for z in zetas])
    np.testing.assert_array_equal(type(target).infinite_structure_peak(zetas), expected)
    np.testing.assert_array_equal(infinite_structure_peak(zetas, structure.kind), expected)
    row = linear_points.infinite_structure_row(target, 0.3)
    impact = target.infinite_structure_impact(0.3)
    assert row["fmax_normalised"] == float(impact.peak_force) == expected[1]
    assert row["peak_time_normalised"] == float(impact.peak_time)
    assert row["contact_time_normalised"] == float(impact.contact_time)
    assert row["energy_transferred_fraction"] == 1.0 - float(impact.rebound_velocity) ** 2
    assert row["method"] == sweep_module.METHODS.index("infinite-structure-asymptote")


def test_basis_table_truncates_like_the_basis_it_holds():
    """A basis table is an explicit participating ModalBasis: truncating it keeps
    retained + residual equal to the target's static compliance, and a table asked for
    after a larger one holds the same modes as a fresh one (no hidden state)."""
    from impactmaps.maps.family.structures import BasisTable

    target = BEAM.build()
    table = BasisTable(target, 1e6, 4)
    for cutoff in (1e3, 1e4, 1e5, 1e6):
        basis = table.truncate(cutoff, 4)
        assert basis.size >= 4
        assert basis.retained_compliance + basis.residual_compliance == pytest.approx(
            target.static_compliance(), rel=1e-12)
    BasisTable(target, 1e7, 4)
    again = BasisTable(target, 1e6, 4).basis
    np.testing.assert_array_equal(again.frequencies, table.basis.frequencies)
    np.testing.assert_array_equal(again.participation, table.basis.participation)
    assert again.residual_compliance == table.basis.residual_compliance


def test_a_point_is_a_pure_function_of_its_inputs():
    """The result of a (ζ, λ) point does not depend on what else its worker computed:
    one by one, in one chunk, or in shuffled chunks after a light-impactor point that
    needs a high cut-off, every scalar is the same to the bit (the basis of every point
    is a truncation of one canonical table, never of whatever a cache happened to hold)."""
    from impactmaps.maps.family.structures import structure_from_name
    from impactmaps.maps.compute.linear_points import solve_points
    from impactmaps.solvers.modal_settings import ModalSettings

    rng = np.random.default_rng(12)
    settings = ModalSettings()
    for name in ("plate-ssss-kirchhoff", "beam-ss-euler"):
        structure = structure_from_name(name)
        points = list(zip(10 ** rng.uniform(-2, 1.5, 12), 10 ** rng.uniform(-1.2, 1.2, 12)))
        alone = [solve_points(structure, [p], settings)[0] for p in points]
        order = rng.permutation(len(points))
        light = [(0.01, 20.0)]  # needs the most modes: would grow a history-dependent table
        shuffled = {}
        for chunk in np.array_split(order, 3):
            rows = solve_points(structure, light + [points[k] for k in chunk], settings)[1:]
            shuffled.update(zip(chunk.tolist(), rows))
        together = solve_points(structure, points, settings)
        for k, row in enumerate(alone):
            for key, value in row.items():
                assert shuffled[k][key] == value, (name, k, key)
                assert together[k][key] == value, (name, k, key)


def test_every_point_carries_its_error_and_status():
    """Issue 'Every map point right or marked': the SS Euler beam at ζ = 10, λ = 0.003162
    (dozens of impacts) gave F̄max = 0.1913 at the default settings against ≈ 0.218 when
    converged (cut-off 160–640 ω, step /8), stored as if right. Now the point is refined
    and, having no converged value, marked `sensitive` with a band that holds 0.218; a
    smooth point is `converged` with an error below the tolerance and its band around it."""
    from impactmaps.maps.family.accuracy import STATUSES
    from impactmaps.maps.family.structures import structure_from_name
    from impactmaps.maps.compute.linear_points import solve_points
    from impactmaps.solvers.modal_settings import ModalSettings

    beam = structure_from_name("beam-ss-euler")
    hard, easy = solve_points(beam, [(10.0, 0.003162), (1.0, 0.001)], ModalSettings())
    assert STATUSES[hard["status"]] == "sensitive"
    assert hard["fmax_low"] <= 0.218 <= hard["fmax_high"]
    assert hard["fmax_error"] == pytest.approx(0.5 * (hard["fmax_high"] - hard["fmax_low"]))
    assert STATUSES[easy["status"]] == "converged" and easy["fmax_error"] <= 1e-3
    assert easy["fmax_low"] <= easy["fmax_normalised"] <= easy["fmax_high"]


def test_sensitive_band_holds_every_level_and_the_last_change():
    """A point that never settles: the band holds the base run, every refinement level,
    the runs perturbed from the base settings and the finest value ± its last change, at
    least the tolerance (validation/sensitive_bands.py: how often a third refinement falls
    inside)."""
    from dataclasses import replace as replaced

    from impactmaps.maps.family.accuracy import STATUSES, AccuracyControl, controlled_point

    class Run:
        def __init__(self, value, impacts):
            self.fmax_normalised, self.impacts = value, impacts

        def normalised_summary(self):
            return {"fmax_normalised": self.fmax_normalised, "impacts": self.impacts}

    levels = {40.0: (0.30, 3), 80.0: (0.26, 4), 160.0: (0.25, 5)}  # by cut-off ratio

    def run(settings, zeta_factor):
        value, impacts = levels.get(settings.cutoff_ratio, (0.255, 5))
        return Run(value + 0.001 * (zeta_factor - 1.0), impacts)

    settings = replaced(ModalSettings(), cutoff_ratio=40.0)
    row = controlled_point(run, settings, AccuracyControl(tolerance=1e-3, max_refinements=2))
    assert STATUSES[row["status"]] == "sensitive"
    assert row["fmax_normalised"] == 0.25
    assert row["fmax_low"] == pytest.approx(0.24)  # 0.25 − |0.25 − 0.26|
    assert row["fmax_high"] == pytest.approx(0.30001)  # the base run at ζ × 1.01 (perturbed from the base)
    assert row["fmax_error"] == pytest.approx(0.030005)


def test_sensitive_band_is_at_least_the_tolerance_wide():
    """Levels that agree to 1e-4 but never in their impact count: the finest value is
    widened by the tolerance, not by the (coincidentally small) last change."""
    from impactmaps.maps.family.accuracy import STATUSES, AccuracyControl, controlled_point

    class Run:
        def __init__(self, value, impacts):
            self.fmax_normalised, self.impacts = value, impacts

        def normalised_summary(self):
            return {"fmax_normalised": self.fmax_normalised, "impacts": self.impacts}

    impacts = {40.0: 3, 80.0: 4, 160.0: 5}

    def run(settings, zeta_factor):
        return Run(0.5 + 1e-4 * (settings.cutoff_ratio == 160.0), impacts.get(settings.cutoff_ratio, 4))

    row = controlled_point(run, ModalSettings(), AccuracyControl(tolerance=1e-3, max_refinements=2))
    assert STATUSES[row["status"]] == "sensitive"
    assert row["fmax_low"] == pytest.approx(0.5001 - 1e-3)
    assert row["fmax_high"] == pytest.approx(0.5001 + 1e-3)


def test_a_sweep_of_a_mindlin_plate_says_it_is_a_point_load():
    """A sweep over a Mindlin plate strikes it at a point (no converged value): it says so."""
    import warnings

    from impactmaps.maps.family.structures import MapStructure
    from impactmaps.maps.compute.sweep import sweep
    from impactmaps._checks import ModelValidityWarning

    mindlin = MapStructure(kind="plate", theory="mindlin", supports="SSSS", slenderness=20)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        sweep([mindlin], [1.0], [1.0], max_workers=1, progress=False)
    said = [w for w in caught if issubclass(w.category, ModelValidityWarning)]
    assert said and str(said[0].message).startswith("point load: the Mindlin points of this sweep")


def test_a_point_does_not_repeat_a_run_equal_to_an_earlier_one(monkeypatch):
    """A sensitive point whose modes are set by the mode floor (SS beam ζ = 706.7,
    λ = 0.001758: 4 modes at the base level) keeps its modes when the cut-off is perturbed
    by ±1 %: those two of its eight runs are the base run, and the runner returns it
    instead of repeating it (sweep.table_run_key). The row is bit for bit the row of a
    runner that repeats every run."""
    from impactmaps.contact.linear import LinearContact
    from impactmaps.dimensionless import realise
    from impactmaps.maps.family.accuracy import AccuracyControl, controlled_point
    from impactmaps.maps.family.structures import structure_from_name
    from impactmaps.maps.compute.points import basis_table
    from impactmaps.maps.family.structures import MAX_MODES
    from impactmaps.solvers.mode_budget import frequency_cap

    structure = structure_from_name("beam-ss-euler")
    zeta, lam = 706.7, 0.001758
    calls = []
    original = points_module.simulate

    def counted(*args, **kwargs):
        calls.append(kwargs["settings"])
        return original(*args, **kwargs)

    monkeypatch.setattr(points_module, "simulate", counted)
    (row,) = solve_points(structure, [(zeta, lam)], ModalSettings())
    assert STATUSES[row["status"]] == "sensitive"
    assert len(calls) == 6  # base, two refinements, step −1 %, ζ ± 1 %

    target = structure.build()
    table, cap = basis_table(structure, ModalSettings().min_modes), frequency_cap(structure.build(), MAX_MODES)

    def every_run(settings, zeta_factor):
        moved = realise(target, zeta * zeta_factor, lam)
        omega = float(moved.contact_frequency)
        basis = table.truncate(min(settings.cutoff_ratio * omega, cap), settings.min_modes)
        return original(basis, LinearContact(float(moved.contact_stiffness)), float(moved.impactor_mass), 1.0,
                        settings=settings, record=False)

    plain = controlled_point(every_run, ModalSettings(), AccuracyControl())
    for name in ("fmax_normalised", "fmax_error", "fmax_low", "fmax_high", "status", "impacts"):
        assert row[name] == plain[name], name


def test_an_executor_holds_a_bounded_window_of_chunks():
    """The sweep keeps four chunks per worker slot submitted, not the whole grid: a Dask client
    that held every chunk of a 10⁶-point sweep took 1.3 GB. Same numbers as the inline run."""
    from concurrent.futures import ThreadPoolExecutor

    from impactmaps.maps.compute.sweep import IN_FLIGHT_PER_SLOT

    class Counting(ThreadPoolExecutor):
        def __init__(self):
            super().__init__(max_workers=1)
            self.outstanding = self.most = 0

        def submit(self, fn, *args):
            self.outstanding += 1
            self.most = max(self.most, self.outstanding)
            future = super().submit(fn, *args)
            future.add_done_callback(lambda _: setattr(self, "outstanding", self.outstanding - 1))
            return future

    local = sweep([PLATE], ZETAS, LAMBDAS[:2], max_workers=1, progress=False)
    with Counting() as executor:
        windowed = sweep([PLATE], ZETAS, LAMBDAS[:2], executor=executor, progress=False, pacing=Pacing(1))
    chunks = ZETAS.size * 2
    assert chunks > IN_FLIGHT_PER_SLOT and executor.most == IN_FLIGHT_PER_SLOT
    np.testing.assert_array_equal(windowed["fmax_normalised"].values, local["fmax_normalised"].values)
