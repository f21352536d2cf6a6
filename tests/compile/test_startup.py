"""Start-up cost: what a command imports and compiles, the warm-up, and check's cost estimate.

* The commands that solve nothing import only what they run (issue 30 item 4, issue 29
  "Fast where it repeats"): each runs in a fresh interpreter and the test reads
  ``sys.modules`` and the compiled signatures afterwards — what was imported and compiled,
  not how long it took (wall time depends on the machine's load).
* ``impactmaps warm-up`` fills numba's cache so that a later process compiles nothing:
  read from the dispatchers' own cache statistics (no cache miss), not from a clock.
* ``impactmaps check`` prints the run's estimate, and :func:`estimate_run` plans the run
  :func:`simulate` makes (same modes, same step).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

import impactmaps
from impactmaps._compile_switch import DISABLE_ENV
from impactmaps.cli import main

from ..helpers import EXAMPLES

#: The checkout whose package the tests import (the subprocesses import the same one).
PACKAGE_ROOT = str(Path(impactmaps.__file__).resolve().parents[1])
#: Modules a command that solves nothing must not import.
HEAVY = ("numba", "xarray", "pandas", "matplotlib", "scipy", "scipy.integrate", "scipy.interpolate",
         "scipy.optimize", "impactmaps.solvers.modal", "impactmaps.solvers.integrator.exact_step", "impactmaps.plotting.chart")

_AFTER_COMMAND = """
    import io, contextlib, json, sys
    from impactmaps.cli import main
    with contextlib.redirect_stdout(io.StringIO()):
        try:
            status = main({argv!r})
        except SystemExit as stop:
            status = stop.code
    compiled = []
    base = sys.modules.get("impactmaps.contact.base")
    if base is not None and base._evaluate_many._compiled:
        compiled.append("_evaluate_many")
    step = sys.modules.get("impactmaps.solvers.integrator.exact_step")
    if step is not None and step.integrate_impact.dispatcher.signatures:
        compiled.append("integrate_impact")
    for name in ("linear", "hertz", "epp", "stronge", "yigit_christoforou"):
        law = sys.modules.get("impactmaps.contact." + name)
        kernel = getattr(law, "_" + name + "_kernel", None)
        if kernel is not None and kernel.signatures:
            compiled.append(name)
    print(json.dumps({{"status": status, "heavy": sorted(m for m in {heavy!r} if m in sys.modules),
                      "compiled": compiled}}))
"""


def _environment(**extra) -> dict:
    return dict(os.environ, PYTHONPATH=PACKAGE_ROOT + os.pathsep + os.environ.get("PYTHONPATH", ""), **extra)


def _after(argv: list[str]) -> dict:
    """Exit status, heavy modules imported and kernels compiled by ``impactmaps ARGV`` in a
    fresh interpreter."""
    script = textwrap.dedent(_AFTER_COMMAND.format(argv=argv, heavy=HEAVY))
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, env=_environment(),
                          cwd=PACKAGE_ROOT)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout.strip().splitlines()[-1])


@pytest.mark.parametrize("argv", [["--help"], ["materials"], ["init", "--help"], ["warm-up", "--help"]])
def test_commands_without_numbers_import_no_numerical_stack(argv):
    seen = _after(argv)
    assert seen["heavy"] == [] and seen["compiled"] == []


def test_laws_imports_the_laws_but_compiles_nothing():
    """``laws`` reads the law classes (their kernels are numba functions, so numba is
    imported) but neither evaluates a law nor imports a solver, the maps, xarray or plotting."""
    seen = _after(["laws"])
    assert seen["status"] == 0
    assert set(seen["heavy"]) <= {"numba", "scipy"}, seen
    assert seen["compiled"] == []


@pytest.mark.parametrize("argv", [
    ["--kind", "plate", "--theory", "kirchhoff", "--zeta", "1.198", "--lambda", "0.425"],
    ["--kind", "beam", "--theory", "euler", "--law", "hertz", "--zeta", "0.3", "--lambda", "2", "--json"],
    ["--kind", "plate", "--theory", "kirchhoff", "--law", "yc", "--beta", "3", "--zeta", "0.5", "--lambda", "1"],
], ids=["linear", "hertz", "yc"])
def test_lookup_on_a_shipped_map_imports_only_numpy(argv):
    """A lookup on a shipped map (linear, Hertz, elastic-plastic) interpolates the packed map
    with NumPy alone: no numba, xarray, pandas, SciPy or plotting, no solver, nothing
    compiled (the families' point solvers are not imported: :mod:`impactmaps.maps.family.builtin_families`)."""
    seen = _after(["lookup", *argv])
    assert seen["status"] == 0
    assert seen["heavy"] == [] and seen["compiled"] == [], seen


def test_check_compiles_nothing():
    seen = _after(["check", str(EXAMPLES / "aluminium_beam_linear.toml")])
    assert seen["status"] == 0
    assert "matplotlib" not in seen["heavy"] and "integrate_impact" not in seen["compiled"]


def test_check_prints_the_estimated_cost_of_the_run(tmp_path, capsys):
    """The estimate names the modes and step the run takes (simulate's own plan) and its
    memory and time (run_budget); the summary of the run has the same modes and step."""
    case = EXAMPLES / "aluminium_beam_linear.toml"
    assert main(["check", str(case), "--json"]) == 0
    checked = json.loads(capsys.readouterr().out)
    for key in ("estimated_method", "estimated_modes", "estimated_time_step_s", "estimated_expected_steps",
                "estimated_history_rows", "estimated_memory_MiB", "estimated_seconds", "estimated_runs"):
        assert key in checked, key
    assert checked["estimated_memory_MiB"] > 0 and checked["estimated_seconds"] > 0
    assert checked["estimated_history_rows"] == checked["estimated_expected_steps"] > 0
    assert main(["simulate", str(case), "--out", str(tmp_path / "out"), "--json"]) == 0
    ran = json.loads(capsys.readouterr().out)
    assert ran["n_modes"] == checked["estimated_modes"]
    assert ran["time_step_s"] == checked["estimated_time_step_s"]
    assert ran["steps"] <= checked["estimated_expected_steps"]


def test_estimate_run_refuses_what_simulate_refuses():
    from impactmaps.contact import contact_law
    from impactmaps.targets.base import ModalBasis
    from impactmaps.solvers.modal import estimate_run

    basis = ModalBasis.from_validated([2e3, 9e3], [3.0, 2.0], 1e-9, [0.0, 0.0])
    law = contact_law("linear", stiffness=1e7)
    assert estimate_run(basis, law, 0.01, 1.0)["modes"] == 2
    with pytest.raises(ValueError, match="time_step"):
        estimate_run(basis, law, 0.01, 1.0, time_step=1e-15)


def test_warm_up_option_is_checked(capsys):
    assert main(["warm-up", "--workers", "0"]) == 2
    assert "--workers" in capsys.readouterr().err


def test_a_variant_that_does_not_exist_is_refused():
    from impactmaps.solvers.integrator.exact_step import integrate_impact

    with pytest.raises(ValueError, match="variant"):
        integrate_impact.compile_variant("fast")


@pytest.mark.slow
def test_after_warm_up_a_simulation_compiles_nothing(tmp_path):
    """On an empty cache, ``impactmaps warm-up`` compiles; a later simulation of each law
    family then loads every kernel from the cache (numba's own statistics: no miss)."""
    env = _environment(NUMBA_CACHE_DIR=str(tmp_path / "cache"))
    warmed = subprocess.run([sys.executable, "-m", "impactmaps.cli", "warm-up", "--json"], capture_output=True,
                            text=True, env=env, cwd=PACKAGE_ROOT)
    assert warmed.returncode == 0, warmed.stderr
    assert json.loads(warmed.stdout)["compiled_variants"] == 2
    script = textwrap.dedent("""
        import json, numba
        from impactmaps.cli import main
        for case in ("aluminium_beam_linear.toml", "steel_plate_hertz.toml"):
            assert main(["simulate", "examples/" + case, "--out", {out!r} + case, "--json"]) == 0
        import sys
        from numba.core.dispatcher import Dispatcher
        misses, hits = set(), 0
        for name, module in list(sys.modules.items()):
            if name.startswith("impactmaps"):
                for value in vars(module).values():
                    dispatcher = getattr(value, "dispatcher", value)
                    if isinstance(dispatcher, Dispatcher):
                        hits += sum(dispatcher.stats.cache_hits.values())
                        if dispatcher.stats.cache_misses:
                            misses.add(name + "." + dispatcher.py_func.__name__)
        print(json.dumps({{"misses": sorted(misses), "hits": hits}}))
    """).format(out=str(tmp_path) + "/")
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, env=env,
                          cwd=str(Path(EXAMPLES).parent))
    assert done.returncode == 0, done.stderr
    seen = json.loads(done.stdout.strip().splitlines()[-1])
    assert seen["misses"] == [] and seen["hits"] > 0, seen


# -- the background warm-up (a stand-in that sleeps instead of compiling) -------------------
def _until(condition, seconds: float = 60.0) -> bool:
    import time

    end = time.monotonic() + seconds
    while time.monotonic() < end:
        if condition():
            return True
        time.sleep(0.05)
    return False


def test_background_warm_up_starts_once_and_leaves_a_marker(tmp_path, monkeypatch):
    """One detached process at a time takes the lock, writes the marker when done; then
    nothing starts again."""
    from impactmaps._compile import background_warm_up as background

    monkeypatch.delenv(DISABLE_ENV, raising=False)
    assert background.start_background(tmp_path, ["--sleep", "1.5"])
    assert _until(lambda: background.is_running(tmp_path), 30)  # the child holds the lock
    assert not background.start_background(tmp_path, ["--sleep", "1.5"])  # one at a time
    assert _until(lambda: background.is_warm(tmp_path), 60)
    assert _until(lambda: not background.is_running(tmp_path), 30)
    assert not background.start_background(tmp_path, ["--sleep", "1.5"])  # warm: nothing to do
    log = next(tmp_path.glob("warm-up-*.log")).read_text()
    assert log.count("warm-up started") == 1 and "warm-up done" in log


def test_a_failed_background_warm_up_is_not_started_again(tmp_path, monkeypatch):
    from impactmaps._compile import background_warm_up as background

    monkeypatch.delenv(DISABLE_ENV, raising=False)
    assert background.start_background(tmp_path, ["--sleep", "-1"])
    assert _until(lambda: list(tmp_path.glob("*.failed")), 60)
    assert _until(lambda: not background.is_running(tmp_path), 30)
    assert not background.start_background(tmp_path, ["--sleep", "0"]) and not background.is_warm(tmp_path)
    assert "a failing stand-in" in next(tmp_path.glob("*.log")).read_text()


def test_background_warm_up_is_off_by_environment_or_option(tmp_path, monkeypatch):
    from impactmaps._compile import background_warm_up as background

    monkeypatch.setenv(DISABLE_ENV, "1")
    assert not background.start_background(tmp_path, ["--sleep", "0"])
    assert list(tmp_path.iterdir()) == []
    started = []
    monkeypatch.setattr(background, "start_background", lambda *a, **k: started.append(1))
    monkeypatch.delenv(DISABLE_ENV)
    assert main(["materials"]) == 0 and started == [1]  # any command starts it, after its output
    assert main(["--no-background-warm-up", "materials"]) == 0 and started == [1]
    assert main(["materials", "--bad-option"]) == 2 and started == [1]  # a command line refused: nothing
