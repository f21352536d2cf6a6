"""Sweeps as a user runs them: config defaults and validation, resumable output that
is never written before the first point, --overwrite, interruption, Dask."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest
import xarray as xr

from impactmaps.cli import main
from impactmaps.maps.compute import sweep as sweep_module
from impactmaps.maps.compute.config import load_sweep_config
from impactmaps.maps.files.store import SweepInterrupted
from impactmaps.maps.family.structures import MapStructure

from ..helpers import ROOT


BEAM_CONFIG = """
output = "out"
[grid]
zeta = {{min = 0.2, max = 2.0, count = {count}}}
lambda = {lambdas}
[[structure]]
kind = "beam"
"""


def write_config(tmp_path, count=2, lambdas="[1.0]", extra=""):
    path = tmp_path / "sweep.toml"
    path.write_text(BEAM_CONFIG.format(count=count, lambdas=lambdas) + extra)
    return path


def test_beam_defaults_follow_the_kind(tmp_path):
    structures, *_ = load_sweep_config(write_config(tmp_path))
    assert structures == [MapStructure(kind="beam", theory="euler", supports="ss", impact_fraction=(0.5,))]


@pytest.mark.parametrize("extra, fragment", [
    ("impact_fraction = 1.5\n", "impact_fraction"),
    ("impact_fraction = \"middle\"\n", "impact_fraction"),
    ("supports = \"xx\"\n", "supports"),
    ("theory = \"kirchhoff\"\n", "theory"),
])
def test_bad_structure_keys_exit_2(tmp_path, extra, fragment, capsys):
    assert main(["sweep", str(write_config(tmp_path, extra=extra)), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert fragment in err and "Traceback" not in err
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("count, fragment", [("2.7", "grid.zeta.count = 2.7"), ("0", "grid.zeta.count = 0"),
                                             ("-3", "grid.zeta.count = -3"), ('"two"', "grid.zeta.count")])
def test_grid_count_is_a_whole_number(tmp_path, count, fragment, capsys):
    assert main(["sweep", str(write_config(tmp_path, count=count)), "--quiet"]) == 2
    assert fragment in capsys.readouterr().err


@pytest.mark.parametrize("count, lambdas, extra, fragment", [
    ("1e9", "[1.0]", "", "grid.zeta.count = 1000000000.0 is invalid: valid range is [1, 1000000]"),
    ("1000000", "{min = 0.1, max = 1, count = 1000}", "",
     "the sweep has 1e+09 points (1 structures × 1000 lambda_ × 1000000 zeta): its map would take 78.2 GiB"),
    ("2", "[1e300]", "", "grid.lambda = [1e+300] is invalid: every value must be in [1e-09, 1e+09]"),
    ("2", "[1e-300]", "", "grid.lambda = [1e-300] is invalid"),
    ("2", "[1.0]", 'law = "yc"\n[grid]\nbeta = [1e300]\n', "grid.beta = [1e+300] is invalid: every value must be in [0.001, 1e+06]"),
])
def test_a_grid_beyond_the_realisable_or_the_memory_is_refused(tmp_path, count, lambdas, extra, fragment, capsys):
    """Found by fuzzing sweep files: count = 1e9 ran (allocating gigabytes) with no word; ζ or λ of
    1e±300 failed inside the realisation naming `impactor_mass`; β = 1e300 a law's internals."""
    path = tmp_path / "sweep.toml"
    text = BEAM_CONFIG.format(count=count, lambdas=lambdas)
    if extra:  # the law goes on top, β into the [grid] table
        law, _grid, beta, _ = extra.split("\n")
        text = law + "\n" + text.replace("[grid]\n", "[grid]\n" + beta + "\n")
    path.write_text(text)
    assert main(["sweep", str(path), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert fragment in err and "Traceback" not in err
    assert not (tmp_path / "out").exists()


def test_nothing_is_written_before_the_first_point(tmp_path, monkeypatch):
    def fail(*args):
        raise ValueError("solver failed")

    monkeypatch.setattr(sweep_module, "solve_map_points", fail)
    path = tmp_path / "result.nc"
    with pytest.raises(ValueError, match="solver failed"):
        sweep_module.sweep([MapStructure(kind="beam", theory="euler", supports="ss")], [0.5, 1.0], [1.0],
                           path=path, max_workers=1, progress=False)
    assert not path.exists() and not list(tmp_path.iterdir())


def test_changed_config_names_the_key_and_overwrite_replaces(tmp_path, capsys):
    config = write_config(tmp_path)
    assert main(["sweep", str(config), "--quiet", "--workers", "1"]) == 0
    netcdf = tmp_path / "out" / "sweep.nc"
    assert oct(netcdf.stat().st_mode & 0o777) == oct(0o666 & ~_umask())
    stale = tmp_path / "out" / ".sweep.nc.dead.tmp"
    stale.write_text("left by a killed save")
    config = write_config(tmp_path, lambdas="[2.0]")
    capsys.readouterr()
    assert main(["sweep", str(config), "--quiet", "--workers", "1"]) == 2
    err = capsys.readouterr().err
    assert "lambda_" in err and "--overwrite" in err
    assert not stale.exists()
    assert main(["sweep", str(config), "--quiet", "--workers", "1", "--overwrite"]) == 0
    with xr.open_dataset(netcdf, engine="scipy") as dataset:
        assert dataset["lambda_"].values.tolist() == [2.0] and int(dataset["done"].sum()) == 2
    csv = (tmp_path / "out" / "sweep.csv").read_text()
    assert "modal+residual" in csv.splitlines()[1]


def _umask() -> int:
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def test_interrupted_sweep_saves_and_resumes(tmp_path, monkeypatch, capsys):
    real = sweep_module.solve_map_points
    calls = []

    def interrupt_second(*args):
        calls.append(1)
        if len(calls) == 2:
            raise KeyboardInterrupt
        return real(*args)

    config = write_config(tmp_path, count=3, lambdas="[0.5, 2.0]")
    monkeypatch.setattr(sweep_module, "solve_map_points", interrupt_second)
    assert main(["sweep", str(config), "--quiet", "--workers", "1"]) == 130
    err = capsys.readouterr().err
    assert "interrupted: 3 of 6 points saved; run the same command to resume" in err
    monkeypatch.setattr(sweep_module, "solve_map_points", real)
    assert main(["sweep", str(config), "--quiet", "--workers", "1"]) == 0
    with xr.open_dataset(tmp_path / "out" / "sweep.nc", engine="scipy") as dataset:
        assert int(dataset["done"].sum()) == 6


def test_library_sweep_raises_sweep_interrupted(tmp_path, monkeypatch):
    def interrupt(*args):
        raise KeyboardInterrupt

    monkeypatch.setattr(sweep_module, "solve_map_points", interrupt)
    with pytest.raises(SweepInterrupted) as stop:
        sweep_module.sweep([MapStructure(kind="beam", theory="euler", supports="ss")], [0.5, 1.0], [1.0], path=tmp_path / "r.nc", max_workers=1,
                           progress=False)
    assert (stop.value.saved, stop.value.total) == (0, 2) and not (tmp_path / "r.nc").exists()


def test_sigint_during_a_real_sweep_exits_130(tmp_path):
    """Ctrl-C on the command: one line, exit 130, the finished points kept."""
    config = tmp_path / "sweep.toml"
    config.write_text(BEAM_CONFIG.format(count=5000, lambdas="[0.3, 1.0, 3.0]").replace('"beam"', '"plate"'))
    # a terminal's Ctrl-C: SIGINT not ignored in the child, even when the test run itself was started in
    # the background of a non-interactive shell (which ignores SIGINT, and the child inherited it)
    process = subprocess.Popen([sys.executable, "-m", "impactmaps.cli", "sweep", str(config), "--workers", "1",
                                "--quiet"], cwd=ROOT, stderr=subprocess.PIPE, text=True,
                               env=os.environ | {"PYTHONPATH": str(ROOT)},
                               preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    netcdf = tmp_path / "out" / "sweep.nc"
    deadline = time.monotonic() + 120
    while not netcdf.exists() and process.poll() is None and time.monotonic() < deadline:
        time.sleep(0.1)
    process.send_signal(signal.SIGINT)
    _, err = process.communicate(timeout=120)
    assert process.returncode == 130, err
    assert "Traceback" not in err
    assert "points saved; run the same command to resume" in err
    with xr.open_dataset(netcdf, engine="scipy") as dataset:
        assert 0 < int(dataset["done"].sum()) < 15000


def test_sweep_on_a_local_dask_cluster(tmp_path, capsys):
    from dask import distributed  # in the test extra; imported here, not at collection (~1 s)

    config = write_config(tmp_path, count=2, lambdas="[0.5, 2.0]")
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                                  dashboard_address=None) as cluster:
        status = main(["sweep", str(config), "--quiet", "--scheduler", cluster.scheduler_address, "--json"])
    assert status == 0, capsys.readouterr().err
    with xr.open_dataset(tmp_path / "out" / "sweep.nc", engine="scipy") as dataset:
        assert int(dataset["done"].sum()) == 4
        assert np.all(dataset["fmax_normalised"].values > 0)


def test_scheduler_that_cannot_be_reached_exits_2(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr("impactmaps.cli.commands_maps.SCHEDULER_TIMEOUT_S", 1.0)
    status = main(["sweep", str(write_config(tmp_path)), "--quiet", "--scheduler", "tcp://127.0.0.1:9"])
    assert status == 2 and "--scheduler" in capsys.readouterr().err


def test_workers_with_scheduler_is_refused(tmp_path, capsys):
    status = main(["sweep", str(write_config(tmp_path)), "--workers", "2", "--scheduler", "tcp://127.0.0.1:9"])
    assert status == 2 and "--workers" in capsys.readouterr().err


def test_a_plastic_sweep_is_configured_with_its_beta_grid(tmp_path):
    """An elastic-plastic law takes the grid of its third axis, β, from [grid]; without it the
    file is refused naming the axes the law needs."""
    path = tmp_path / "plastic.toml"
    path.write_text('law = "yc"\n' + BEAM_CONFIG.format(count=2, lambdas="[1.0]").replace(
        "[grid]\n", "[grid]\nbeta = [3.0, 30.0]\n"))
    *_, law, axes = load_sweep_config(path)
    assert law == "yc" and axes["beta"].tolist() == [3.0, 30.0]
    path.write_text('law = "yc"\n' + BEAM_CONFIG.format(count=2, lambdas="[1.0]"))
    with pytest.raises(ValueError, match="'zeta', 'lambda', 'beta'"):
        load_sweep_config(path)
