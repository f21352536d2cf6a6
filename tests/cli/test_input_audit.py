"""Inputs an audit of 2026-11-27 found taken wrongly, each now refused naming what the user
wrote (exit 2, one line) or announced: wrong TOML types, silently dropped values, unbounded
inputs (files, workers, sweep size) and an interrupted ``--json`` run."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

from impactmaps.cli import main
from impactmaps.solvers.modal import ModalSettings

_GRID = '[grid]\nzeta = [1.0]\nlambda = [1.0]\n'


def _one_error_line(capsys) -> str:
    lines = [line for line in capsys.readouterr().err.splitlines() if not line.startswith("warning:")]
    assert len(lines) == 1, lines
    return lines[0]


@pytest.mark.parametrize("options, named", [({"residual_flexibility": "false"}, "residual_flexibility"),
                                            ({"check_convergence": "yes"}, "check_convergence"),
                                            ({"max_events": 10.5}, "max_events")])
def test_settings_refuse_a_value_of_the_wrong_type(options, named):
    """``residual_flexibility = "false"`` ran as true (a non-empty string)."""
    with pytest.raises(ValueError, match=named):
        ModalSettings(**options)
    assert ModalSettings(min_modes=4.0).min_modes == 4.0  # a whole float is a whole number


@pytest.mark.parametrize("structure, named", [
    ('kind = "beam"\nsupports = 3', "#1.supports = 3"),  # was a traceback (AttributeError), exit 1
    ('kind = [["beam"]]', "#1.kind"),  # was "unhashable type: 'list'"
    ('kind = "plate"\nimpact_fraction = ["a", "b"]', "#1.impact_fraction"),
    ('kind = "beam"\nimpact_fraction = [0.3, 0.9]', "invalid for a beam"),  # 0.9 was dropped
    ('kind = "beam"\nslenderness = "20"', "#1.slenderness"),
])
def test_a_sweep_file_refuses_wrong_types_naming_the_key(tmp_path, capsys, structure, named):
    path = tmp_path / "sweep.toml"
    path.write_text(f"{_GRID}[[structure]]\n{structure}\n")
    assert main(["sweep", str(path), "--quiet", "--json"]) == 2
    assert json.loads(capsys.readouterr().out.strip().splitlines()[-1])["error"]
    assert main(["sweep", str(path), "--quiet"]) == 2
    assert named in _one_error_line(capsys)


def test_a_sweep_file_refuses_grid_keys_its_law_does_not_read(tmp_path, capsys):
    path = tmp_path / "sweep.toml"
    path.write_text(f"{_GRID}beta = [1.0]\n[[structure]]\nkind = \"beam\"\n")
    assert main(["sweep", str(path), "--quiet"]) == 2
    assert "['beta'] in [grid]" in _one_error_line(capsys)


def test_input_files_are_bounded_and_regular(tmp_path, capsys):
    """``check /dev/zero`` grew to 2.8 GB before running out of memory; a FIFO blocked forever."""
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    assert main(["check", str(fifo)]) == 2
    assert "not a regular file" in _one_error_line(capsys)
    big = tmp_path / "big.toml"
    big.write_text("# " + "x" * 1_000_100 + "\n")
    assert main(["sweep", str(big)]) == 2
    assert "bytes: valid range is up to" in _one_error_line(capsys)


def test_workers_are_bounded(tmp_path, capsys):
    """``--workers 1000`` forked ~800 processes on 2 cores."""
    assert main(["chart", "--workers", "1000", "--out", str(tmp_path)]) == 2
    assert "--workers = 1000" in _one_error_line(capsys)
    from impactmaps.maps.family.structures import structure_from_name
    from impactmaps.maps.compute.sweep import sweep

    with pytest.raises(ValueError, match="max_workers"):
        sweep([structure_from_name("beam-ss-euler")], [1.0], [1.0], max_workers=1000, progress=False)


def test_a_long_sweep_is_announced_before_it_starts():
    from impactmaps.maps.compute import sweep as sweep_module
    from impactmaps.solvers.run_budget import LongRunWarning

    with pytest.warns(LongRunWarning, match="100000 points to compute on 2 worker"):
        sweep_module._announce(100_000, None, 2)


def test_an_interrupted_json_command_still_prints_json(monkeypatch, capsys):
    """``--json`` printed nothing when interrupted: no strict parser accepts an empty output."""
    from impactmaps.cli import commands_maps

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(commands_maps, "check", interrupted)  # the command's first step
    status = main(["classify", "--zeta", "1", "--lambda", "1", "--kind", "beam", "--json"])
    captured = capsys.readouterr()
    assert status == 130
    assert json.loads(captured.out) == {"error": "interrupted"}


def test_sigterm_ends_a_sweep_as_ctrl_c_does_and_workers_end_with_their_parent(tmp_path):
    """``kill`` of a sweep left its workers behind (orphans waiting for tasks forever) and its
    lock; now SIGTERM saves and stops like Ctrl-C (exit 130), and the workers ask the kernel
    to end them with their parent, so even ``kill -9`` leaves none."""
    import signal
    import subprocess
    import sys
    import time

    text = ('[grid]\nzeta = {min = 0.001, max = 10, count = 100000}\nlambda = [1.0]\n'
            '[[structure]]\nkind = "beam"\n')
    sweep_file = tmp_path / "big.toml"
    command = [sys.executable, "-m", "impactmaps.cli", "sweep", str(sweep_file), "--quiet", "--workers", "2"]
    import impactmaps

    package_root = str(Path(impactmaps.__file__).resolve().parents[1])  # this package, not another install
    env = dict(os.environ, IMPACTMAPS_NO_BACKGROUND_WARMUP="1",
               PYTHONPATH=os.pathsep.join([package_root, os.environ.get("PYTHONPATH", "")]))
    for how in (signal.SIGTERM, signal.SIGKILL):
        run_dir = tmp_path / how.name
        run_dir.mkdir()
        sweep_file = run_dir / "big.toml"
        sweep_file.write_text(text)
        command[-4] = str(sweep_file)
        process = subprocess.Popen(command, cwd=run_dir, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                   text=True)
        workers: list[int] = []
        deadline = time.monotonic() + 60
        while len(workers) < 2 and time.monotonic() < deadline:
            time.sleep(0.2)
            found = subprocess.run(["pgrep", "-P", str(process.pid)], capture_output=True, text=True).stdout
            workers = [int(pid) for pid in found.split()]
        assert len(workers) >= 2, "the sweep started no workers"
        store = run_dir / "big-output" / "sweep.nc"  # the first save: the workers run (a cold one compiles first)
        while not store.exists() and time.monotonic() < deadline + 240:
            time.sleep(0.2)
        process.send_signal(how)
        _, err = process.communicate(timeout=120)  # the workers hold the pipes: they too must end
        if how == signal.SIGTERM:
            assert process.returncode == 130 and "points saved" in err
        deadline = time.monotonic() + 20
        while any(os.path.exists(f"/proc/{pid}") and "Z" not in open(f"/proc/{pid}/stat").read().split()[2]
                  for pid in workers) and time.monotonic() < deadline:
            time.sleep(0.2)
        assert not any(os.path.exists(f"/proc/{pid}") and "Z" not in open(f"/proc/{pid}/stat").read().split()[2]
                       for pid in workers), f"workers left after {how.name}"


def test_outputs_are_replaced_whole_and_a_failed_write_leaves_no_trace(tmp_path):
    """``sweep.csv`` was truncated in place and rewritten; a Ctrl-C then left half a file."""
    from impactmaps._files import written_atomically

    target = tmp_path / "table.csv"
    target.write_text("old\n")
    with pytest.raises(RuntimeError), written_atomically(target) as part:
        part.write_text("half")
        raise RuntimeError("interrupted")
    assert target.read_text() == "old\n" and sorted(p.name for p in tmp_path.iterdir()) == ["table.csv"]
    with written_atomically(target) as part:
        assert part.suffix == ".csv" and part.parent == tmp_path
        part.write_text("new\n")
    assert target.read_text() == "new\n" and sorted(p.name for p in tmp_path.iterdir()) == ["table.csv"]


def test_the_same_sweep_writes_the_same_bytes(tmp_path, capsys):
    """A ``created`` time stamp made two identical sweeps' NetCDF files differ."""
    path = tmp_path / "s.toml"
    path.write_text(f'output = "one"\n{_GRID}[[structure]]\nkind = "beam"\n')
    assert main(["sweep", str(path), "--quiet"]) == 0
    path.write_text(f'output = "two"\n{_GRID}[[structure]]\nkind = "beam"\n')
    assert main(["sweep", str(path), "--quiet"]) == 0
    for name in ("sweep.nc", "sweep.csv"):
        assert (tmp_path / "one" / name).read_bytes() == (tmp_path / "two" / name).read_bytes()


def test_outputs_through_a_dangling_link_and_a_csv_directory_are_refused_first(tmp_path, capsys):
    (tmp_path / "dangling").symlink_to(tmp_path / "missing")
    assert main(["point", "--target", "beam-ss", "--zeta", "1", "--lambda", "1", "--no-check",
                 "--plot", str(tmp_path / "dangling" / "p.png")]) == 2
    assert "link to a missing target" in _one_error_line(capsys)
    sweep_file = tmp_path / "s.toml"
    sweep_file.write_text(f'output = "out"\n{_GRID}[[structure]]\nkind = "beam"\n')
    (tmp_path / "out" / "sweep.csv").mkdir(parents=True)
    assert main(["sweep", str(sweep_file), "--quiet"]) == 2
    assert "holds a directory 'sweep.csv'" in _one_error_line(capsys)
    assert not (tmp_path / "out" / "sweep.nc").exists()  # nothing computed


def test_a_duration_that_overflows_names_the_duration(tmp_path, capsys):
    """``duration = 1e308`` was refused as ``solver.max_time_ratio = inf``, a key the user did not write."""
    assert main(["init", "beam", str(tmp_path / "b.toml")]) == 0
    text = (tmp_path / "b.toml").read_text()
    import re

    (tmp_path / "b.toml").write_text(re.sub(r"(?m)^duration = [0-9.e+-]+", "duration = 1e308", text))
    capsys.readouterr()
    assert main(["check", str(tmp_path / "b.toml")]) == 2
    assert "solver.duration = 1e+308" in _one_error_line(capsys)


def test_an_empty_output_directory_is_refused(capsys):
    """``--out ""`` wrote into the current directory."""
    assert main(["chart", "--out", ""]) == 2
    assert "--out = ''" in _one_error_line(capsys)
