"""The second core during the first integrating command: a helper process compiles with it.

On an empty numba cache, :func:`start` launches a helper that compiles
:data:`HELPER_CALLEES` while this process runs; :func:`await_variant` compiles
:data:`FOREGROUND_CALLEES` and waits for it. Answers are bit for bit the same; the
helper never outlives this process. How and why: docs/_cold_start.rst.
"""

from __future__ import annotations

import atexit
import os
import sys
import threading
import time
from pathlib import Path

from .._compile_switch import DISABLE_ENV, switched_off

__all__ = ["WAIT_S", "start", "await_variant", "enabled", "child_environment",
           "variant_cached", "register_integrator", "end_with_parent", "seed_user_cache", "copy_shipped_cache"]

#: The longest wait for a helper [s], from its start; then this process compiles itself.
WAIT_S = 120.0
#: The polling interval of the wait [s].
_POLL_S = 0.02

#: The helper (``python -c _CHILD PARENT_PID share``, or ``sleep:S`` / ``fail`` for the
#: tests' stand-ins instead of ``share``).
_CHILD = ("import importlib, sys; sys.argv[1] and importlib.import_module(sys.argv[1]); "
          "from impactmaps._compile.compile_helper import helper_main; sys.exit(helper_main(sys.argv[2:]))")

_lock = threading.Lock()
_state = {"decided": False, "process": None, "variants": (), "started": 0.0, "share": False}
#: The integrator this plumbing compiles for, registered by the module that defines it
#: (:func:`register_integrator`): nothing here imports the solvers.
_integrator = {"kernel": None, "callees": dict, "module": ""}


def register_integrator(kernel, callee_signatures, module: str) -> None:
    """Register the exact-step integrator (a :class:`~impactmaps._compile.lazy_kernel.LazyKernel`),
    its callees' signatures (``name → (dispatcher, argument types)``) and its module's name.
    """
    _integrator.update(kernel=kernel, callees=callee_signatures, module=module)


def child_environment() -> tuple[dict, str]:
    """``(env, cwd)`` of a ``python -c`` child that imports this very package and starts no
    compiling process of its own (:data:`~impactmaps._compile_switch.DISABLE_ENV` set, the package's parent first).
    """
    package_parent = str(Path(__file__).resolve().parents[2])
    env = dict(os.environ, **{DISABLE_ENV: "1"})
    env["PYTHONPATH"] = os.pathsep.join(filter(None, (package_parent, os.environ.get("PYTHONPATH"))))
    return env, package_parent


def enabled() -> bool:
    """Whether this process may start a helper: not turned off (the background warm-up's
    switch), and not a ``multiprocessing`` worker."""
    if switched_off():
        return False
    import multiprocessing

    return multiprocessing.parent_process() is None


def start(variants, arguments: list[str] | None = None) -> bool:
    """Start the helper if numba's cache lacks one of the integrator ``variants`` (the
    ``exact_phase`` values, None or True) a run may need; True if started. Only a process's
    first call decides; never raises. ``arguments`` replaces the helper's (tests).
    """
    if _state["decided"]:
        return False
    with _lock:
        if _state["decided"]:
            return False
        _state["decided"] = True
        try:
            seed_user_cache()
            if switched_off():
                return False
            if arguments is None:  # the cache first: on a warm one, nothing more is imported
                variants = tuple(variant for variant in variants if not variant_cached(variant))
                if not variants:
                    return False
                arguments = ["share"]
            return enabled() and _launch(tuple(variants), arguments)
        except Exception:  # noqa: BLE001 (no helper: the run compiles itself)
            return False


def seed_user_cache() -> int:
    """Copy the kernels a wheel shipped compiled into numba's user-wide cache (when the
    package's directories are read-only); the number of files copied. Never raises.
    """
    try:
        from numba.core.caching import UserWideCacheLocator

        integrate_impact = _integrator["kernel"]
        locator = integrate_impact.dispatcher._cache._impl.locator
        if type(locator) is not UserWideCacheLocator:
            return 0
        base = Path(locator.get_cache_path()).parent
        # the package's directory as numba sees its modules (not resolved: the cache path hashes it)
        depth = len(_integrator["module"].split(".")) - 2
        package = Path(integrate_impact.dispatcher.py_func.__code__.co_filename).parents[depth]
        return copy_shipped_cache(package, lambda folder: base / UserWideCacheLocator.get_suitable_cache_subpath(
            str(folder / "__init__.py")))
    except Exception:  # noqa: BLE001 (numba's internals changed, or a file error: numba compiles)
        return 0


def copy_shipped_cache(package, destination) -> int:
    """Copy numba's cache files from the ``__pycache__`` directories under ``package`` to
    ``destination(folder)``, each by an atomic rename, skipping indexes already there;
    the number of files copied.
    """
    import glob
    import shutil

    copied = 0
    for index in sorted(Path(package).glob("**/__pycache__/*.nbi")):
        target = Path(destination(index.parent.parent))
        if (target / index.name).exists():
            continue
        target.mkdir(parents=True, exist_ok=True)
        stem = glob.escape(index.name[:-len(".nbi")])
        for source in [*sorted(index.parent.glob(f"{stem}.*.nbc")), index]:  # the index last: numba
            temporary = target / f"{source.name}.tmp.{os.getpid()}"        # reads what it lists
            shutil.copyfile(source, temporary)
            os.replace(temporary, target / source.name)
            copied += 1
    return copied


def variant_cached(variant) -> bool:
    """Whether numba's cache index lists the integrator ``variant`` (``exact_phase``: None or
    True) for this machine; False when not, or when that cannot be told.
    """
    integrate_impact = _integrator["kernel"]
    try:
        dispatcher = integrate_impact.dispatcher  # numba's cache index, as Dispatcher.compile consults it
        cache = dispatcher._cache
        key = cache._index_key(integrate_impact.signatures[variant], dispatcher.targetctx.codegen())
        return key in cache._cache_file._load_index()
    except Exception:  # noqa: BLE001 (an internal of numba changed: compile rather than guess)
        return False


def _launch(variants: tuple, arguments: list[str]) -> bool:
    import subprocess

    env, cwd = child_environment()
    process = subprocess.Popen([sys.executable, "-c", _CHILD, _integrator["module"], str(os.getpid()), *arguments],
                               stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                               env=env, close_fds=True, cwd=cwd)
    _state.update(process=process, variants=variants, started=time.monotonic(),
                  share=arguments == ["share"])
    _trace("launched")
    atexit.register(_stop)
    return True


def _stop() -> None:
    """End the helper if it still runs (and reap it)."""
    process = _state["process"]
    if process is not None and process.poll() is None:
        process.kill()
        process.wait()


def await_variant(variant, timeout: float | None = None) -> bool:
    """Compile this process's share of the integrator's callees, then wait for the helper (at
    most ``timeout`` [s] from its start, default :data:`WAIT_S`, then end it). True if a
    helper was waited for; on any error the helper is ended and the error raised.
    """
    process = _state["process"]
    if process is None:
        return False
    if variant not in _state["variants"]:
        _stop()
        _state["process"] = None
        return False
    deadline = _state["started"] + (WAIT_S if timeout is None else timeout)
    try:
        if _state["share"]:  # not for the tests' stand-ins
            _trace("share-start")
            _compile_callees(FOREGROUND_CALLEES, lambda: process.poll() is not None)
            _trace("share-end")
        while process.poll() is None and time.monotonic() < deadline:
            time.sleep(_POLL_S)
    except BaseException:
        _stop()
        raise
    _stop()  # late: ended (this process compiles what it lacks)
    _trace("waited")
    _state["process"] = None
    return True


#: The integrator's callees the helper compiles (in this order), and those this process
#: compiles meanwhile; then this process compiles the integrator, which loads the
#: helper's from numba's cache. Chosen by measurement (``benchmarks/studies/RESULTS_cold_start.md``):
#: the two shares take about the same time, and none calls a callee of the other share
#: but ``locate_event`` (``fill_step_coefficients``, ``predict_step``), compiled last here.
HELPER_CALLEES = ("fill_step_coefficients", "predict_step", "free_doublings", "square_free_propagators",
                  "solve_end_force", "damping_work")
FOREGROUND_CALLEES = ("record_free_inside", "no_reimpact_possible", "locate_event")


#: Environment variable naming a file to which both processes append their milestones
#: (``who event time.monotonic()``; ``benchmarks/studies/bench_cold_start.py --helper`` reads it).
TRACE_ENV = "IMPACTMAPS_COMPILE_HELPER_TRACE"


def _trace(event: str) -> None:
    path = os.environ.get(TRACE_ENV)
    if path:
        with open(path, "a") as trace:
            trace.write(f"{os.getpid()} {event} {time.monotonic():.4f}\n")


def _compile_callees(names, stop=lambda: False) -> None:
    """Compile the callees ``names`` into numba's cache, in order, until ``stop()`` (best
    effort: one that fails to compile is left to the integrator's compile)."""
    import warnings

    signatures = _integrator["callees"]()
    for name in names:
        if stop():
            return
        dispatcher, signature = signatures[name]
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                dispatcher.compile(signature)
        except Exception:  # noqa: BLE001 (the integrator's compile compiles it)
            pass


def end_with_parent(signal_number: int, parent: int | None = None) -> bool:
    """Ask Linux to send this process ``signal_number`` when its parent ends
    (``prctl(PR_SET_PDEATHSIG)``; elsewhere nothing); False if ``parent`` (a pid) is given
    and is no longer this process's parent.
    """
    if sys.platform.startswith("linux"):
        try:
            import ctypes

            ctypes.CDLL(None, use_errno=True).prctl(1, int(signal_number), 0, 0, 0)  # 1: PR_SET_PDEATHSIG
        except Exception:  # noqa: BLE001 (the process ends when it is done)
            pass
    return parent is None or os.getppid() == parent


def helper_main(argv: list[str]) -> int:
    """The helper process (``argv``: the parent's pid, then ``share`` or a tests' stand-in);
    returns the exit status (0, 1 for the failing stand-in).
    """
    import signal

    if not end_with_parent(signal.SIGKILL, int(argv[0])):
        return 0
    import warnings

    warnings.simplefilter("ignore")
    for name in argv[1:]:
        if name.startswith("sleep:"):  # tests: a stand-in of the compile
            time.sleep(float(name.split(":", 1)[1]))
        elif name == "fail":
            return 1
        elif name == "share":
            _trace("helper-start")
            _compile_callees(HELPER_CALLEES)
            _trace("helper-share-end")
    return 0
