"""The shipped result of the default chart's sweep, and the integrator compiled on first use.

The README's first command (``impactmaps chart``) draws the chart from the shipped result
of its sweep (:mod:`impactmaps.maps.files.shipped`); these tests hold that result to
what the code computes today, and that nothing else ever takes it for an answer.
"""

from __future__ import annotations

import subprocess
import sys
import textwrap

import numpy as np
import pytest
import xarray as xr

from impactmaps.maps.compute import sweep as sweep_module
from impactmaps.plotting.chart import CHART_STRUCTURES, DEFAULT_CHART_LAMBDAS, DEFAULT_ZETA_COUNT, DEFAULT_ZETA_RANGE
from impactmaps.maps.files.shipped import SHIPPED_RESULTS, load_shipped_result, shipped_result_path
from impactmaps.maps.family.map_family import map_family
from impactmaps.maps.family.map_family import RESULT_VARIABLES
from impactmaps.maps.compute.sweep import log_grid, sweep, sweep_fingerprint
from impactmaps.maps.compute.points import solve_map_points
from impactmaps.solvers.modal_settings import ModalSettings

ZETAS = log_grid(*DEFAULT_ZETA_RANGE, DEFAULT_ZETA_COUNT)
DIGEST = sweep_fingerprint(CHART_STRUCTURES, ZETAS, DEFAULT_CHART_LAMBDAS)
HERTZ_DIGEST = sweep_fingerprint(CHART_STRUCTURES, ZETAS, DEFAULT_CHART_LAMBDAS, law="hertz")


def _shipped(digest: str = DIGEST) -> xr.Dataset:
    dataset = load_shipped_result(digest)
    assert dataset is not None, ("no shipped result for a default chart at this solver revision: "
                                 "run python data_build/build_default_chart.py")
    return dataset


def test_the_shipped_results_are_the_default_charts_and_no_other():
    """Current (their fingerprints are today's default chart sweeps', linear and Hertz,
    solver revision included), complete, and no stale result of an earlier revision."""
    for digest in (DIGEST, HERTZ_DIGEST):
        dataset = _shipped(digest)
        assert dataset.attrs["fingerprint"] == digest
        assert dataset["done"].values.all()
    shipped = [*SHIPPED_RESULTS.glob("*.nc"), *SHIPPED_RESULTS.glob("*.npz")]
    assert sorted(shipped) == sorted(shipped_result_path(d) for d in (DIGEST, HERTZ_DIGEST))


@pytest.mark.parametrize("law, structure_index", [("linear", 0), ("linear", 1), ("hertz", 0), ("hertz", 1)])
def test_shipped_points_are_what_the_code_computes(law, structure_index):
    """Random points of each structure and law recomputed: every result variable as shipped.

    The shipped results were computed with another build of the numeric libraries (numba's
    LLVM, NumPy, LAPACK); the same code on another build can differ in the last digits, and a
    peak time found by root refinement by ~1e-12 relative. Bit equality within one build is
    tested by the sweep tests (alone / in chunks / resumed).
    """
    dataset = _shipped(DIGEST if law == "linear" else HERTZ_DIGEST)
    rng = np.random.default_rng(11 + structure_index)
    count = 12 if law == "linear" else 4
    picks = [(int(rng.integers(len(DEFAULT_CHART_LAMBDAS))), int(rng.integers(ZETAS.size))) for _ in range(count)]
    points = [(float(ZETAS[z]), float(DEFAULT_CHART_LAMBDAS[lam])) for lam, z in picks]
    rows = solve_map_points(map_family(law), CHART_STRUCTURES[structure_index], points, ModalSettings())
    for (lam, z), row in zip(picks, rows):
        for name in RESULT_VARIABLES:
            stored = dataset[name].values[structure_index, lam, z]
            assert stored == pytest.approx(row[name], rel=1e-11, abs=1e-12, nan_ok=True), (name, points)


def test_a_default_chart_sweep_starts_from_the_shipped_result(tmp_path, monkeypatch, capsys):
    """Nothing is computed (and no empty progress bar drawn: one line says where the points
    come from); the result file is written where asked, equal to the shipped one."""
    def no_solving(*args, **kwargs):
        raise AssertionError("a point was computed")

    monkeypatch.setattr(sweep_module, "solve_map_points", no_solving)
    result = sweep(CHART_STRUCTURES, ZETAS, DEFAULT_CHART_LAMBDAS, path=tmp_path / "map.nc", progress=True)
    said = capsys.readouterr().err
    assert "all 3200 points from the result shipped for this sweep" in said and "pt/s" not in said
    with xr.open_dataset(tmp_path / "map.nc", engine="scipy") as written:
        for name in RESULT_VARIABLES:
            np.testing.assert_array_equal(written[name].values, _shipped()[name].values)
            np.testing.assert_array_equal(result[name].values, _shipped()[name].values)
    assert "regime" in result


def test_another_sweep_is_not_answered_by_the_shipped_result():
    """One ζ fewer, other settings, one structure: another fingerprint, nothing shipped."""
    for digest in (sweep_fingerprint(CHART_STRUCTURES, ZETAS[:-1], DEFAULT_CHART_LAMBDAS),
                   sweep_fingerprint(CHART_STRUCTURES, ZETAS, DEFAULT_CHART_LAMBDAS, ModalSettings(cutoff_ratio=41.0)),
                   sweep_fingerprint(CHART_STRUCTURES, ZETAS[:-1], DEFAULT_CHART_LAMBDAS, law="hertz"),
                   sweep_fingerprint(CHART_STRUCTURES[:1], ZETAS, DEFAULT_CHART_LAMBDAS)):
        assert digest not in (DIGEST, HERTZ_DIGEST)
        assert load_shipped_result(digest) is None


def test_a_damaged_shipped_result_is_computed_instead(tmp_path, monkeypatch):
    """A shipped file that cannot be read (or does not match its name) is not used: a
    warning, and the sweep computes its points."""
    import impactmaps.maps.files.shipped as shipped

    zetas, lambdas = ZETAS[[10, 20]], DEFAULT_CHART_LAMBDAS[:1]
    digest = sweep_fingerprint(CHART_STRUCTURES[:1], zetas, lambdas)
    monkeypatch.setattr(shipped, "SHIPPED_RESULTS", tmp_path)
    (tmp_path / f"{digest}.nc").write_bytes(b"not a NetCDF file")
    with pytest.warns(UserWarning, match="not usable"):
        assert load_shipped_result(digest) is None
    with pytest.warns(UserWarning, match="not usable"):
        result = sweep(CHART_STRUCTURES[:1], zetas, lambdas, progress=False, max_workers=1)
    assert result["done"].values.all() and np.isfinite(result["fmax_normalised"].values).all()


def test_the_default_chart_compiles_no_integrator(tmp_path):
    """In a fresh interpreter: importing the solvers compiles nothing, the default chart
    integrates nothing (the integrator has no compiled specialisation after it), and the
    first integration compiles exactly one."""
    script = textwrap.dedent(f"""
        from impactmaps.solvers.integrator.exact_step import integrate_impact
        assert not integrate_impact.dispatcher.signatures
        from impactmaps.plotting.chart import make_chart
        make_chart({str(tmp_path)!r}, progress=False)
        assert not integrate_impact.dispatcher.signatures, "the default chart integrated"
        print("ok")
    """)
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "fmax_map.nc").exists() and (tmp_path / "fmax_chart.png").exists()


def test_the_integrator_has_its_specialisations_only_and_refuses_other_types():
    """Compiled lazily, it keeps what eager signatures gave: its variants' specialisations
    only (with and without the exact contact phase), and an argument of another type is
    refused instead of compiling another one."""
    from impactmaps.contact.linear import LinearContact
    from impactmaps.maps.family.structures import structure_from_name
    from impactmaps.solvers.integrator.exact_step import integrate_impact
    from impactmaps.solvers.modal import simulate

    basis = structure_from_name("beam-ss-euler").build().modes(1e5, min_modes=4)
    simulate(basis, LinearContact(1e7), 0.01, 1.0, record=False)
    compiled = len(integrate_impact.dispatcher.signatures)
    assert 1 <= compiled <= len(integrate_impact.signatures) == 2
    with pytest.raises(TypeError):
        integrate_impact.dispatcher(*([np.float32(1.0)] * 8))
    assert len(integrate_impact.dispatcher.signatures) == compiled


@pytest.mark.slow
@pytest.mark.parametrize("law", ["linear", "hertz"])
def test_the_whole_shipped_result_is_what_the_code_computes(monkeypatch, law):
    """All 3 200 points recomputed by a sweep that may not start from the shipped result."""
    monkeypatch.setattr(sweep_module, "load_shipped_result", lambda digest, description=None: None)
    fresh = sweep(CHART_STRUCTURES, ZETAS, DEFAULT_CHART_LAMBDAS, progress=False, law=law)
    shipped = _shipped(DIGEST if law == "linear" else HERTZ_DIGEST)
    for name in RESULT_VARIABLES:
        np.testing.assert_allclose(fresh[name].values, shipped[name].values, rtol=0, atol=1e-12)


def test_the_default_charts_integrate_no_asymptote(monkeypatch, tmp_path):
    """Issue 29 item 6 / issue 30: the regimes and the drawn asymptotes of the default linear
    and Hertz charts come from the peaks kept with the shipped results (they took 408 and
    108 asymptote integrations, 75 s, on every ``chart --law hertz``): with every asymptote
    integrator patched to raise, both charts are drawn, and the peaks equal a fresh
    computation to the infinite-beam asymptote's round-off (its history sum is an FFT
    convolution since the peaks were stored: 4.5e-16 relative measured; 1e-13 bounds it)."""
    import impactmaps.maps.compute.hertz_points as hertz_points
    from impactmaps.plotting.chart import make_chart
    from impactmaps.maps.family.map_family import ASYMPTOTE_PEAKS
    from impactmaps.maps.compute.dataset import with_asymptote_peaks

    for digest in (DIGEST, HERTZ_DIGEST):
        shipped = _shipped(digest)
        assert all(name in shipped for name in ASYMPTOTE_PEAKS)
        fresh = with_asymptote_peaks(shipped.drop_vars(list(ASYMPTOTE_PEAKS)).isel(zeta=slice(0, None, 40)))
        for name in ASYMPTOTE_PEAKS:
            np.testing.assert_allclose(fresh[name].values, shipped[name].isel(zeta=slice(0, None, 40)).values
                                       if "zeta" in shipped[name].dims else shipped[name].values, rtol=1e-13, atol=0)

    def no_integration(*args, **kwargs):
        raise AssertionError("an asymptote was integrated")

    monkeypatch.setattr(hertz_points, "asymptote", no_integration)
    with pytest.raises(AssertionError, match="integrated"):  # the patch reaches the integrations
        hertz_points.hertz_asymptote_peak("infinite", "beam", zeta_h=0.123456789)
    for law in ("linear", "hertz"):
        written = make_chart(tmp_path / law, law=law, progress=False)
        assert written
        # the same chart, the same bytes: matplotlib's SVG carries a date and random clip ids unless told
        # (one writer for every law: drawn again for the linear chart only, 4 s a chart)
        svg = written["svg"].read_text()
        assert "<dc:date>" not in svg and "clip-path" in svg
        if law == "linear":
            written["svg"].unlink()
            assert make_chart(tmp_path / law, law=law, progress=False)["svg"].read_text() == svg
