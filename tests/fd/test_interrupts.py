"""Every signal ends every command at once (issue 40, item 1).

A compiled loop does not see signals (Python handles them between bytecodes): the
finite-difference beam's loop ignored Ctrl-C and SIGTERM for its whole run (minutes) and
then crashed. It now runs in a worker thread that a stop flag ends at the next step
(:mod:`impactmaps._compile.interruptible`); these tests send the interrupt while the loop runs.
"""

from __future__ import annotations

import _thread
import os
import signal
import subprocess
import sys
import threading
import time
import warnings
from pathlib import Path

import pytest

from impactmaps.contact import HertzContact
from impactmaps.fd import FDBeam, simulate_fd

ROOT = Path(__file__).resolve().parents[2]


def _interrupt_when_running(thread_name: str, seen: list) -> None:
    for _ in range(60000):
        if any(t.name == thread_name for t in threading.enumerate()):
            seen.append(True)
            time.sleep(0.05)  # well inside the loop
            _thread.interrupt_main()
            return
        time.sleep(0.001)


def test_ctrl_c_stops_the_finite_difference_loop_and_leaves_no_thread():
    """A run of ~10⁶ steps (a minute or more) is stopped by Ctrl-C: KeyboardInterrupt once the
    loop has returned, and no loop thread is left running."""
    beam = FDBeam(0.78, 0.06, 0.0278, 206e9, 7850.0, 235e6, n_elements=100)
    seen = []
    watcher = threading.Thread(target=_interrupt_when_running, args=("impactmaps-fd-loop", seen))
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        watcher.start()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            with pytest.raises(KeyboardInterrupt):
                simulate_fd(beam, HertzContact(1e10), 1.0, 0.5, duration=2.0, history_stride=1000)
        watcher.join()
    finally:
        signal.signal(signal.SIGINT, previous)
    assert seen == [True]
    assert not any(t.name == "impactmaps-fd-loop" and t.is_alive() for t in threading.enumerate())


def test_a_loop_that_is_not_interrupted_gives_the_same_bits_with_and_without_the_thread():
    """The thread changes nothing in the arithmetic: a run where Ctrl-C is ignored (direct call)
    and one in the worker thread agree bit for bit."""
    beam = FDBeam(0.78, 0.06, 0.0278, 206e9, 7850.0, 235e6, n_elements=40)
    law = HertzContact(1e10)
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        threaded = simulate_fd(beam, law, 1.0, 0.5, duration=2e-4)
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        direct = simulate_fd(beam, law, 1.0, 0.5, duration=2e-4)
    finally:
        signal.signal(signal.SIGINT, previous)
    assert threaded.peak_force == direct.peak_force
    assert threaded.history["force_N"].equals(direct.history["force_N"])


FD_CASE = """
name = "long fd run"
[impactor]
radius = 0.00635
material = "structural-steel"
velocity = 0.5
[target]
type = "beam"
length = 0.78
width = 0.06
height = 0.0278
material = "structural-steel"
supports = "ss"
impact_position = 0.39
[contact]
law = "stronge"
[solver]
kind = "fd"
duration = 10
[fd]
n_elements = 200
n_half_layers = 10
history_stride = 20
"""


@pytest.mark.slow
@pytest.mark.parametrize("how", [signal.SIGTERM, signal.SIGINT])
def test_a_signal_ends_the_fd_command_with_130(tmp_path, how):
    """The issue's reproducer: ``impactmaps fd`` on a 10 s duration (about 90 s of work) ended by
    SIGTERM or Ctrl-C exits 130 with one line, long before its run would end (it ignored both
    for 34–42 s and then crashed with a segmentation fault)."""
    case = tmp_path / "fd.toml"
    case.write_text(FD_CASE, encoding="utf-8")
    process = subprocess.Popen([sys.executable, "-m", "impactmaps.cli", "fd", str(case), "--out",
                                str(tmp_path / "out")], cwd=tmp_path, stderr=subprocess.PIPE, text=True,
                               env=os.environ | {"PYTHONPATH": str(ROOT)},
                               preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    err = ""
    while "about" not in err and process.poll() is None:  # the run's announcement: the loop starts
        err += process.stderr.readline()
    time.sleep(1.0)
    process.send_signal(how)
    err += process.communicate(timeout=30)[1]
    assert process.returncode == 130, err
    assert "interrupted" in err and "Traceback" not in err
