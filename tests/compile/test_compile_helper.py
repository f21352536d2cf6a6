"""The compile helper (:mod:`impactmaps._compile.compile_helper`): the second core compiles
part of the integrator during the first cold integrating run.

The mechanism is tested with stand-ins of the compile (a helper that sleeps or fails), as
``tests/compile/test_startup.py`` tests the background warm-up: started once per process, off by
the environment switch, waited for, ended when late, when the run needs another variant,
on Ctrl-C while waiting and when its parent is killed. The slow test compiles for real on
an empty numba cache: the callees' signatures are those the integrator types, and a run
with the helper loads the helper's share of them from the cache and gives the answer bit
for bit.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

import impactmaps
from impactmaps._compile import compile_helper
from impactmaps._compile_switch import DISABLE_ENV

PACKAGE_ROOT = str(Path(impactmaps.__file__).resolve().parents[1])


@pytest.fixture
def helper(monkeypatch):
    """The module with its state reset and the switch on; its helper ended afterwards."""
    monkeypatch.delenv(DISABLE_ENV, raising=False)
    monkeypatch.setitem(compile_helper._state, "decided", False)
    monkeypatch.setitem(compile_helper._state, "process", None)
    yield compile_helper
    process = compile_helper._state["process"]
    if process is not None and process.poll() is None:
        process.kill()
        process.wait()


def test_started_once_then_waited_for(helper):
    assert helper.start((None,), ["sleep:0.2"])
    process = helper._state["process"]
    assert not helper.start((None,), ["sleep:0.2"])  # one helper per process
    assert helper.await_variant(None)
    assert process.returncode == 0
    assert not helper.await_variant(None)  # nothing left to wait for


def test_off_by_the_environment_switch(helper, monkeypatch):
    monkeypatch.setenv(DISABLE_ENV, "1")
    assert not helper.start((None,), ["sleep:0.2"])
    assert helper._state["process"] is None


def test_a_late_or_failing_helper_is_ended_and_not_waited_for_again(helper):
    assert helper.start((None,), ["sleep:30"])
    process = helper._state["process"]
    assert helper.await_variant(None, timeout=0.3)
    assert process.returncode is not None and process.returncode != 0  # killed
    helper._state["decided"] = False
    assert helper.start((None,), ["fail"])
    process = helper._state["process"]
    assert helper.await_variant(None)
    assert process.returncode == 1


def test_a_run_needing_another_variant_ends_the_helper(helper):
    assert helper.start((None,), ["sleep:30"])
    process = helper._state["process"]
    assert not helper.await_variant(True)
    assert process.returncode is not None


def test_ctrl_c_while_waiting_ends_the_helper(helper, monkeypatch):
    assert helper.start((None,), ["sleep:30"])
    process = helper._state["process"]

    def interrupted(_seconds):
        raise KeyboardInterrupt

    monkeypatch.setattr(helper.time, "sleep", interrupted)
    with pytest.raises(KeyboardInterrupt):
        helper.await_variant(None)
    assert process.returncode is not None


def _ended(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/stat") as stat:
            return stat.read().rsplit(")", 1)[1].split()[0] in ("Z", "X")
    except FileNotFoundError:
        return True


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="PR_SET_PDEATHSIG is Linux's")
def test_the_helper_ends_when_its_parent_is_killed():
    script = ("import os, signal, sys, time; from impactmaps._compile import compile_helper as c; "
              "assert c.start((None,), ['sleep:30']); time.sleep(0.5); "
              "print(c._state['process'].pid, flush=True); os.kill(os.getpid(), signal.SIGKILL)")
    env = dict(os.environ, PYTHONPATH=PACKAGE_ROOT)
    env.pop(DISABLE_ENV, None)
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, env=env)
    assert done.returncode == -signal.SIGKILL
    pid = int(done.stdout.split()[0])
    for _ in range(100):
        if _ended(pid):
            break
        time.sleep(0.05)
    assert _ended(pid)


_COLD_RUN = """
    import json, numpy as np
    from impactmaps.contact import contact_law
    from impactmaps._compile import compile_helper
    from impactmaps.solvers.integrator import exact_step
    from impactmaps.solvers.modal import simulate
    from impactmaps.targets.base import ModalBasis
    basis = ModalBasis(np.array([2e3, 9e3, 4e4]), np.array([3.0, 2.0, 1.0]), 1e-9)
    result = simulate(basis, contact_law("hertz", stiffness=1e9), 0.01, 1.0, record=True)
    callees = exact_step.callee_signatures()
    loaded = [name for name in compile_helper.HELPER_CALLEES if sum(callees[name][0].stats.cache_hits.values())]
    print(json.dumps({"peak": result.peak_force, "loaded": loaded,
                      "rows": result.history.to_numpy().tolist()}))
"""

_SIGNATURES = """
    from impactmaps._compile import compile_helper
    from impactmaps.solvers.integrator import exact_step
    from impactmaps.solvers.integrator.exact_step import integrate_impact
    integrate_impact.compile_variant(None)
    for name, (dispatcher, signature) in exact_step.callee_signatures().items():
        assert dispatcher.signatures == [signature], (name, dispatcher.signatures)
    print("ok")
"""


def _fresh(script: str, cache: Path, helper: bool, trace: Path | None = None) -> str:
    env = dict(os.environ, PYTHONPATH=PACKAGE_ROOT, NUMBA_CACHE_DIR=str(cache))
    env.pop(DISABLE_ENV, None)
    if not helper:
        env[DISABLE_ENV] = "1"
    if trace is not None:
        env[compile_helper.TRACE_ENV] = str(trace)
    done = subprocess.run([sys.executable, "-c", textwrap.dedent(script)], capture_output=True, text=True, env=env)
    assert done.returncode == 0, done.stderr
    return done.stdout.strip().splitlines()[-1]


@pytest.mark.slow
def test_on_an_empty_cache_the_run_loads_what_the_helper_compiled(tmp_path):
    assert _fresh(_SIGNATURES, tmp_path / "alone", helper=False) == "ok"
    trace = tmp_path / "trace"
    helped = json.loads(_fresh(_COLD_RUN, tmp_path / "helped", helper=True, trace=trace))
    events = [line.split()[1] for line in trace.read_text().splitlines()]
    assert events[:1] == ["launched"] and "helper-share-end" in events and events[-1] == "waited"
    assert helped["loaded"] == list(compile_helper.HELPER_CALLEES)  # the helper's share, loaded here
    alone = json.loads(_fresh(_COLD_RUN, tmp_path / "alone", helper=False))
    assert helped["peak"] == alone["peak"] and helped["rows"] == alone["rows"]


def test_an_interrupted_first_compile_raises_the_interrupt():
    import numba

    from impactmaps._compile.lazy_kernel import LazyKernel

    @numba.njit
    def twice(x):
        return 2.0 * x

    kernel = LazyKernel(twice, numba.float64(numba.float64))

    def interrupted(_signature):
        raise KeyboardInterrupt

    kernel.dispatcher.compile = interrupted
    with pytest.raises(KeyboardInterrupt):  # was an AssertionError from numba's disable_compile
        kernel(1.0)
    del kernel.dispatcher.compile
    assert kernel(1.5) == 3.0


def test_cache_saves_of_a_lazy_kernel_wait_for_the_cache_lock(tmp_path):
    """Two processes saving different specialisations of one kernel must not interleave
    (numba names a new data file from the index it read): a save waits for the lock beside
    the index."""
    import fcntl
    import threading
    import types

    from impactmaps.solvers.integrator.exact_step import integrate_impact
    from impactmaps._compile.lazy_kernel import LazyKernel

    assert integrate_impact.dispatcher._cache.save_overload._impactmaps_locked
    saved = []
    index = tmp_path / "kernel.nbi"
    cache = types.SimpleNamespace(_cache_file=types.SimpleNamespace(_index_path=str(index)),
                                  save_overload=lambda sig, data: saved.append((sig, data)))
    fake = types.SimpleNamespace(_cache=cache, py_func=lambda: None)
    LazyKernel(fake, "sig")
    with open(str(index) + ".lock", "a") as held:
        fcntl.flock(held, fcntl.LOCK_EX)  # another process's save in progress
        saver = threading.Thread(target=cache.save_overload, args=("sig", "data"))
        saver.start()
        saver.join(0.3)
        assert saver.is_alive() and not saved
    saver.join(5)
    assert saved == [("sig", "data")]
