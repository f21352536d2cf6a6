"""Compile the modal solver's kernels into numba's on-disk cache ahead of the first run.

:func:`warm_up` (``impactmaps warm-up``) compiles the integrator's two variants in two
processes, then every other kernel a run compiles; :func:`compile_into_package` does the
same into the package when a wheel is built. No answer changes (docs/install.rst).
"""

from __future__ import annotations

import concurrent.futures
import multiprocessing
import time

import numpy as np

from .._compile.compile_helper import seed_user_cache, variant_cached

__all__ = ["warm_up", "cache_directory", "run_background", "compile_into_package", "CACHE_PATTERNS"]

#: numba's cache files (index, data) and what its saves leave beside them (the save lock of
#: :mod:`impactmaps._compile.lazy_kernel`, an interrupted write's temporary file).
CACHE_PATTERNS = ("*.nbi", "*.nbc", "*.nbi.lock", "*.tmp.*")

#: The integrator variants (``exact_phase`` argument), compiled one per process.
_VARIANTS = (None, True)


def _compile_variant(variant) -> float:
    """Compile (or load) one variant of the integrator; its wall time [s]."""
    from .integrator.exact_step import integrate_impact

    start = time.perf_counter()
    integrate_impact.compile_variant(variant)
    return time.perf_counter() - start


def _tiny_impacts() -> None:
    """Two impacts on a three-mode basis, a linear and a Hertz law: a run's Python path and
    the small kernels it compiles (time step, coupled top frequency, law evaluation)."""
    from ..contact import available_contact_laws, contact_law_class, evaluate_kernel
    from ..contact.base import kernel_pointer
    from ..contact.hertz import HertzContact
    from ..contact.linear import LinearContact
    from ..targets.base import ModalBasis
    from .modal import simulate

    basis = ModalBasis(np.array([2e3, 9e3, 4e4]), np.array([3.0, 2.0, 1.0]), 1e-9)
    for law in (LinearContact(1e7), HertzContact(1e9)):
        simulate(basis, law, 0.01, 1.0, record=True)
    for name in available_contact_laws():
        kernel = contact_law_class(name).kernel
        kernel_pointer(kernel)
        evaluate_kernel(kernel, np.ones((13, 1)), np.zeros(1), np.zeros(1))


def cache_directory() -> str:
    """Where numba keeps the integrator's compiled code (the cache :func:`warm_up` fills)."""
    from .integrator.exact_step import integrate_impact

    return str(integrate_impact.dispatcher._cache._cache_path)


def warm_up(workers: int = 2) -> dict:
    """Compile every kernel of a modal run into numba's cache (or load what is there), the
    integrator's two variants in ``workers`` ≥ 1 processes; idempotent. Returns
    ``compiled_variants``, ``integrator_s``, ``rest_s``, ``total_s`` (wall times [s]) and
    ``cache_directory``.
    """
    from .._checks import require_in_range
    from .integrator import exact_step  # noqa: F401 (registers the integrator with the compile helper)

    require_in_range("workers", workers, 1, 64)
    start = time.perf_counter()
    seed_user_cache()  # a read-only installation: what the wheel shipped, into numba's user-wide cache
    missing = [variant for variant in _VARIANTS if not variant_cached(variant)]
    if workers > 1 and len(missing) > 1:
        context = multiprocessing.get_context("spawn")
        with concurrent.futures.ProcessPoolExecutor(min(int(workers), len(_VARIANTS)), mp_context=context) as pool:
            list(pool.map(_compile_variant, missing))
    for variant in _VARIANTS:  # loads what the workers wrote (compiles a variant whose index entry was lost)
        _compile_variant(variant)
    middle = time.perf_counter()
    _tiny_impacts()
    end = time.perf_counter()
    return {"compiled_variants": len(missing), "integrator_s": middle - start, "rest_s": end - middle,
            "total_s": end - start, "cache_directory": cache_directory()}


def compile_into_package() -> dict:
    """Compile every kernel of a modal run into numba's cache beside this package's modules
    (shipped in the wheel); returns :func:`warm_up`'s dict with ``files`` and ``bytes``.

    Raises
    ------
    ValueError
        If ``NUMBA_CACHE_DIR`` is set (the cache would not be beside the modules).
    """
    import os
    from pathlib import Path

    if os.environ.get("NUMBA_CACHE_DIR"):
        raise ValueError(f"NUMBA_CACHE_DIR = {os.environ['NUMBA_CACHE_DIR']!r}: compile_into_package needs it unset "
                         "(numba's cache beside the package's modules)")
    package = Path(__file__).resolve().parents[1]
    for stale in package_cache_files(package):  # a build tree kept from an earlier build
        stale.unlink()
    done = warm_up(2)
    for leftover in package_cache_files(package):
        if not leftover.name.endswith((".nbi", ".nbc")):
            leftover.unlink()
    files = package_cache_files(package)
    return {**done, "files": len(files), "bytes": sum(path.stat().st_size for path in files)}


def package_cache_files(package) -> list:
    """numba's cache files (:data:`CACHE_PATTERNS`) in the ``__pycache__`` directories under
    the directory ``package``."""
    from pathlib import Path

    return [path for pattern in CACHE_PATTERNS for path in Path(package).glob(f"**/__pycache__/{pattern}")]


def run_background(directory, sleep_s: float | None = None) -> int:
    """The background warm-up process: at low priority, under the lock of the state
    ``directory``, run :func:`warm_up` (tests: sleep ``sleep_s`` [s], fail if negative) and
    write the marker; the exit status (0).
    """
    import json
    import os

    from .._compile.background_warm_up import hold_lock, mark_warm

    _lower_priority(10)
    handle, _ = hold_lock(directory)
    if handle is None:
        return 0
    with handle:  # the lock file names the process holding it
        handle.seek(0)
        handle.truncate()
        handle.write(json.dumps({"pid": os.getpid(), "started": time.time()}))
        handle.flush()
        print(f"{time.strftime('%Y-%m-%d %H:%M:%S')} warm-up started (pid {os.getpid()})", flush=True)
        try:
            if sleep_s is None:
                done = warm_up(2)
            elif sleep_s < 0:  # tests: a warm-up that fails
                raise RuntimeError("a failing stand-in of the warm-up")
            else:
                time.sleep(sleep_s)
                done = {"total_s": sleep_s}
        except Exception as error:  # noqa: BLE001 (recorded: no command starts it again)
            mark_warm({"error": f"{type(error).__name__}: {error}"}, directory, "failed")
            raise
        mark_warm(done, directory)
        print(f"{time.strftime('%Y-%m-%d %H:%M:%S')} warm-up done: {json.dumps(done, default=str)}", flush=True)
    return 0


def _lower_priority(nice: int) -> None:
    """Run this process (and its workers) at ``nice``, and its session's scheduling group
    (Linux autogroups); best effort.
    """
    import os

    try:
        os.nice(nice)
    except (OSError, AttributeError):  # pragma: no cover (no nice on this system)
        pass
    try:
        with open("/proc/self/autogroup", "w") as group:
            group.write(str(nice))
    except OSError:
        pass

