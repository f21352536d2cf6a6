"""``impactmaps chart --case CASE.toml`` / ``--target KIND-SUPPORTS`` (issue 39, item 4).

``chart`` drew only the shipped simply supported beam and square plate; a clamped, mixed-edge
or laminated structure's chart needed a sweep file and ``plot``. Now the chart sweeps the
structure beside the simply supported one of its kind (the sweep machinery: resumable, its
store locked, its cost said before it starts) and names both in the legend. Tiny grids: the
tests check the command's path, its JSON, its refusals and its resume, not the physics (the
sweep's points are the same bits as ``sweep``'s: ``tests/maps/test_laminate_sweep.py``).
"""

from __future__ import annotations

import json

import numpy as np
import pytest
import xarray as xr

from impactmaps.cli import main
from tests.helpers import CLAMPED_PLATE_TARGET, case_text

#: A chart grid as small as a chart allows: 2 ζ (large, so the points are cheap) × 2 λ.
TINY = ["--zeta-range", "1", "10", "--zeta-count", "2", "--lambdas", "0.2", "1", "--workers", "1", "--quiet"]

#: The keys of a structure chart's JSON besides the files of its two regime maps.
CHART_KEYS = {"netcdf", "csv", "png", "svg", "markdown", "structures", "structure", "reference"}


def _json_run(capsys, *arguments) -> tuple[int, dict, str]:
    status = main(["chart", *arguments, "--json"])
    captured = capsys.readouterr()
    return status, json.loads(captured.out), captured.err


def test_a_clamped_beam_chart_is_drawn_beside_the_simply_supported_one_and_resumed(tmp_path, capsys, monkeypatch):
    """``--target beam-cc``: both structures swept and drawn, the JSON names them and its files; the
    chart's store is the sweep's, so a second run reads every point back (no point solved)."""
    arguments = ["--target", "beam-cc", *TINY, "--out", str(tmp_path)]
    status, values, _ = _json_run(capsys, *arguments)
    assert status == 0
    assert values["structures"] == ["beam-ss-euler", "beam-cc-euler"]
    assert (values["structure"], values["reference"]) == ("beam-cc-euler", "beam-ss-euler")
    assert set(values) == CHART_KEYS | {"regime_map_beam-ss-euler", "regime_map_beam-cc-euler"}
    for key in set(values) - {"structures", "structure", "reference"}:
        assert (tmp_path / values[key].rpartition("/")[2]).is_file(), key
    with xr.open_dataset(values["netcdf"]) as dataset:
        assert list(dataset["structure"].values) == values["structures"]
        assert dataset["done"].values.all()
        fmax = dataset["fmax_normalised"].values
        assert np.all((fmax > 0) & (fmax <= 1))  # a linear law: F̄max in (0, 1]
        assert not np.array_equal(fmax[0], fmax[1])  # the clamped beam is another structure
    first = (tmp_path / "fmax_map.csv").read_text()
    heading = (tmp_path / "lookup_table.md").read_text().splitlines()[2]
    assert heading.startswith("Linear contact, each structure as its name says;")  # not the shipped maps' words

    def solved(*_args, **_kw):
        raise AssertionError("a point was computed again")

    monkeypatch.setattr("impactmaps.maps.compute.sweep.solve_map_points", solved)
    status, again, _ = _json_run(capsys, *arguments)
    assert status == 0 and again == values
    assert (tmp_path / "fmax_map.csv").read_text() == first


def test_a_clamped_plate_case_is_charted_and_its_cost_said_first(tmp_path, capsys):
    """``--case`` of a CCCC Kirchhoff plate (120 × 100 mm): its structure is the case's target
    (aspect ratio 100/120), and without ``--quiet`` the points to compute and their cost are said
    before the sweep starts."""
    case = tmp_path / "plate.toml"
    case.write_text(case_text(CLAMPED_PLATE_TARGET))
    arguments = [argument for argument in TINY if argument != "--quiet"]
    status, values, err = _json_run(capsys, "--case", str(case), *arguments, "--out", str(tmp_path / "out"))
    assert status == 0, err
    assert values["structure"] == "plate-cccc-kirchhoff-ar0.833333"
    assert values["reference"] == "plate-ssss-kirchhoff"
    assert "impact map: 8 points to compute on 1 worker(s), about" in err


@pytest.mark.slow
def test_the_drop_weight_laminate_is_charted(tmp_path, capsys):
    """The CCCC Mindlin [45/0/−45/90]2s laminate of the drop-weight example, named by its
    laminate in the structure, every computed F̄max in [0, 1]."""
    from pathlib import Path

    example = Path(__file__).resolve().parents[2] / "examples" / "drop_weight_quasi_isotropic.toml"
    status, values, err = _json_run(capsys, "--case", str(example), *TINY, "--out", str(tmp_path))
    assert status == 0, err
    assert values["structure"].startswith("plate-cccc-mindlin-ar0.6-s62.5-lam")
    with xr.open_dataset(values["netcdf"]) as dataset:
        fmax = dataset["fmax_normalised"].values
        assert np.all(np.isnan(fmax) | ((fmax >= 0) & (fmax <= 1)))


@pytest.mark.parametrize("arguments, named", [
    (["--target", "plate-cccc", "--case", "x.toml"], "--case and --target"),
    (["--target", "plate-xyz"], "edges"),
    (["--target", "shell-cc"], "--target = 'shell-cc'"),
    (["--aspect", "2"], "--aspect"),
    (["--target", "plate-cccc", "--aspect", "0"], "--aspect = 0"),
    (["--target", "plate-cccc", "--position", "1"], "--position = 1"),
    (["--target", "beam-cc", "--aspect", "2"], "--aspect"),
    (["--target", "plate-cccc", "--theory", "shell"], "--theory shell"),
    (["--target", "plate-cccc", "--law", "yc"], "--target"),
    (["--case", "missing.toml"], "missing.toml"),
    (["--target", "plate-cccc", "--zeta-count", "1"], "--zeta-count"),
])
def test_bad_structure_options_exit_2_with_one_line(tmp_path, capsys, monkeypatch, arguments, named):
    """Refused before anything is computed or written: status 2, one line naming the option, and
    with ``--json`` the error as JSON."""
    monkeypatch.chdir(tmp_path)
    status = main(["chart", *arguments, "--out", str(tmp_path / "out"), "--json"])
    captured = capsys.readouterr()
    lines = captured.err.strip().splitlines()
    assert status == 2 and len(lines) == 1 and named in lines[0], captured.err
    assert named in json.loads(captured.out)["error"]
    assert not (tmp_path / "out" / "fmax_map.nc").exists()


def test_a_half_space_case_has_no_chart(tmp_path, capsys):
    case = tmp_path / "half.toml"
    case.write_text(case_text('type = "halfspace"\nmaterial = "structural-steel"'))
    status = main(["chart", "--case", str(case), "--out", str(tmp_path / "out")])
    err = capsys.readouterr().err.strip().splitlines()
    assert status == 2 and len(err) == 1 and "beam or a plate" in err[0]


def test_the_cost_said_first_counts_a_ritz_basis_and_its_points():
    """The estimate before a sweep: a Ritz plate's points at 0.2 CPU-s and its basis once (30
    CPU-s), a beam's or a Navier plate's at the plane's 2.9 ms; nothing for a structure done."""
    from impactmaps.solvers.run_budget import (RITZ_BASIS_SECONDS, SECONDS_PER_MAP_POINT,
                                               SECONDS_PER_RITZ_MAP_POINT, map_sweep_seconds)

    assert map_sweep_seconds([80, 80], [False, True]) == pytest.approx(
        80 * SECONDS_PER_MAP_POINT + 80 * SECONDS_PER_RITZ_MAP_POINT + RITZ_BASIS_SECONDS)
    assert map_sweep_seconds([80, 0], [False, True]) == pytest.approx(80 * SECONDS_PER_MAP_POINT)
