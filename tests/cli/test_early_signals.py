"""Every signal ends every command at once, from the program's start (the brief; issue 40).

The command line took Ctrl-C and SIGTERM over only once its imports (NumPy, the commands:
about half a second on a loaded machine) and its option parsing were done: a SIGTERM in that
window killed the process by the signal (status -15, not the documented 130) and a Ctrl-C
printed a ``KeyboardInterrupt`` traceback. :mod:`impactmaps.cli._signals` now installs its
handlers at the top of :mod:`impactmaps.cli`, before those imports, when the import starts
the program. These tests send the signal as soon as the process catches SIGTERM (read from
``/proc/PID/status``, no sleeping), and check the order of the imports.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

import impactmaps

PACKAGE_ROOT = str(Path(impactmaps.__file__).resolve().parents[1])  # this package, not another install
ENV = dict(os.environ, IMPACTMAPS_NO_BACKGROUND_WARMUP="1",
           PYTHONPATH=os.pathsep.join([PACKAGE_ROOT, os.environ.get("PYTHONPATH", "")]))
#: A generous bound on a process that starts, imports and ends [s] (not a timing assertion).
TIMEOUT_S = 120

needs_proc = pytest.mark.skipif(not Path("/proc/self/status").exists(), reason="reads /proc/PID/status (Linux)")


def _catches(pid: int, number: int) -> bool:
    """Whether process ``pid`` has a handler for signal ``number`` (its SigCgt mask)."""
    try:
        status = Path(f"/proc/{pid}/status").read_text()
    except OSError:
        return False
    mask = next(line.split()[1] for line in status.splitlines() if line.startswith("SigCgt:"))
    return bool(int(mask, 16) >> (number - 1) & 1)


def _signal_at_start(command: list[str], how: signal.Signals) -> tuple[subprocess.CompletedProcess, bool]:
    """Run ``command``, stop it the moment it catches SIGTERM (the first handler the program
    installs), send ``how`` and let it go on; its status and output, and whether NumPy was not
    loaded yet when the signal was sent (then it lands in the imports)."""
    process = subprocess.Popen(command, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                               preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    deadline = time.monotonic() + TIMEOUT_S
    while not _catches(process.pid, signal.SIGTERM) and process.poll() is None and time.monotonic() < deadline:
        time.sleep(0.001)
    process.send_signal(signal.SIGSTOP)
    assert process.poll() is None, "the command ended before it caught SIGTERM"
    in_imports = "_multiarray_umath" not in Path(f"/proc/{process.pid}/maps").read_text()
    process.send_signal(how)
    process.send_signal(signal.SIGCONT)
    out, err = process.communicate(timeout=TIMEOUT_S)
    return subprocess.CompletedProcess(command, process.returncode, out, err), in_imports


@needs_proc
@pytest.mark.parametrize("how", [signal.SIGTERM, signal.SIGINT])
def test_a_signal_right_after_start_exits_130_without_a_traceback(how):
    """``python -m impactmaps.cli``: a signal in the imports (before NumPy is loaded: -15 or a
    traceback before) exits with the documented status and one line. The process catches SIGTERM
    before NumPy is loaded; three tries leave room for a scheduler that lets it run on past its
    imports before the test sees the handler."""
    command = [sys.executable, "-m", "impactmaps.cli", "classify", "--zeta", "1", "--lambda", "1", "--kind", "plate",
               "--json"]
    landed = []
    for _ in range(3):
        done, in_imports = _signal_at_start(command, how)
        assert done.returncode == 130, done.stderr
        assert "Traceback" not in done.stderr and "interrupted" in done.stderr
        assert len(done.stderr.strip().splitlines()) == 1, done.stderr
        assert done.stdout.strip() == '{"error": "interrupted"}', done.stdout
        landed.append(in_imports)
        if in_imports:
            assert done.stderr.strip() == "impactmaps: interrupted"
            break
    assert any(landed), "SIGTERM was never caught before NumPy was loaded"


@needs_proc
def test_the_console_script_takes_the_signals_from_its_start(tmp_path):
    """The ``impactmaps`` console script (pip's launcher, as installed) is the program too."""
    script = tmp_path / "impactmaps"
    script.write_text("import sys\nfrom impactmaps.cli import main\nif __name__ == '__main__':\n"
                      "    sys.exit(main())\n")
    done, _ = _signal_at_start([sys.executable, str(script), "asymptote", "quasi-static", "--lambda", "1"],
                               signal.SIGTERM)
    assert done.returncode == 130 and "Traceback" not in done.stderr, done.stderr


def test_the_handlers_are_installed_before_numpy_is_imported():
    """The order that makes the window small: :mod:`impactmaps.cli._signals` (which installs the
    handlers at once) is imported before NumPy, the first heavy import of the command line."""
    done = subprocess.run([sys.executable, "-X", "importtime", "-m", "impactmaps.cli", "--version"], env=ENV,
                          capture_output=True, text=True, timeout=TIMEOUT_S)
    assert done.returncode == 0, done.stderr
    order = [line.rsplit("|", 1)[-1].strip() for line in done.stderr.splitlines() if line.startswith("import time:")]
    assert order.index("impactmaps.cli._signals") < order.index("numpy")


def test_a_library_import_leaves_the_handlers_alone():
    """Importing :mod:`impactmaps.cli` from Python (tests, a notebook, ``multiprocessing``'s
    re-import of the main module) changes no signal handler; ``main(argv)`` restores them."""
    code = ("import signal, impactmaps.cli as cli\n"
            "before = (signal.getsignal(signal.SIGINT), signal.getsignal(signal.SIGTERM))\n"
            "assert before == (signal.default_int_handler, signal.SIG_DFL), before\n"
            "assert cli.main(['asymptote', 'quasi-static', '--lambda', '1']) == 0\n"
            "assert (signal.getsignal(signal.SIGINT), signal.getsignal(signal.SIGTERM)) == before\n")
    done = subprocess.run([sys.executable, "-c", code], env=ENV, capture_output=True, text=True, timeout=TIMEOUT_S,
                          preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    assert done.returncode == 0, done.stderr
