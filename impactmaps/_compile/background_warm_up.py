"""The warm-up in the background: the first use of the command line starts it, once.

When a command has printed its output and this installation's cache is not known to be
warm, :func:`start_background` starts :func:`impactmaps.solvers.warm_up.warm_up` in a
detached process at nice 10 and exits. State (a marker per installation, a lock, a log)
lives in :func:`state_directory`. Off with ``IMPACTMAPS_NO_BACKGROUND_WARMUP=1``, and
without ``fcntl``. Where and why: docs/install.rst, docs/_cold_start.rst.
"""

from __future__ import annotations

import hashlib
import json
import os
import sys
from pathlib import Path

from .._compile_switch import switched_off
from . import compile_helper

__all__ = ["state_directory", "installation_key", "is_warm", "is_running", "start_background",
           "mark_warm", "hold_lock"]

#: The sources whose modification times key the marker (numba caches per source file).
_KERNEL_PACKAGES = ("solvers", "solvers/integrator", "contact", "contact/plastic", "closed_forms",
                    "closed_forms/law_asymptotes")

#: The background process (``python -c _CHILD STATE_DIRECTORY [--sleep S]``).
_CHILD = ("import pathlib, sys; from impactmaps.solvers.warm_up import run_background; a = sys.argv[1:]; "
          "sys.exit(run_background(pathlib.Path(a[0]), float(a[2]) if a[1:2] == ['--sleep'] else None))")

try:  # POSIX only: the lock is released by the kernel when its holder ends, however it ends
    import fcntl
except ImportError:  # pragma: no cover (Windows)
    fcntl = None


def disabled() -> bool:
    """Whether the background warm-up is off (:data:`~impactmaps._compile_switch.DISABLE_ENV`, or no ``fcntl``)."""
    return fcntl is None or switched_off()


def state_directory() -> Path:
    """The directory of the markers, locks and logs (module docstring)."""
    if os.environ.get("NUMBA_CACHE_DIR"):
        return Path(os.environ["NUMBA_CACHE_DIR"]) / "impactmaps-warm-up"
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "impactmaps" / "warm-up"


def installation_key() -> str:
    """A hash of what numba's cache of this installation depends on (module docstring)."""
    import importlib.util

    from .. import __version__

    package = Path(__file__).resolve().parents[1]
    newest = 0
    for folder in _KERNEL_PACKAGES:
        with os.scandir(package / folder) as entries:
            newest = max([newest, *(entry.stat().st_mtime_ns for entry in entries if entry.name.endswith(".py"))])
    spec = importlib.util.find_spec("numba")
    numba_file = "" if spec is None or spec.origin is None else spec.origin
    numba_stat = os.stat(numba_file) if numba_file else None
    parts = (__version__, str(package), newest, numba_file, numba_stat and (numba_stat.st_mtime_ns, numba_stat.st_size),
             sys.version, sys.executable)
    return hashlib.sha256(repr(parts).encode()).hexdigest()[:16]


def _paths(directory: Path | None = None, key: str | None = None) -> dict:
    directory = state_directory() if directory is None else Path(directory)
    key = installation_key() if key is None else key
    return {name: directory / f"warm-up-{key}.{name}" for name in ("marker", "failed", "lock", "log")}


def is_warm(directory: Path | None = None) -> bool:
    """Whether a warm-up of this installation has finished (its marker exists)."""
    return _paths(directory)["marker"].exists()


def _try_lock(path: Path):
    """An open file holding the exclusive lock on ``path``, or None if another process holds it."""
    handle = open(path, "a+")  # noqa: SIM115 (kept open while the lock is held)
    try:
        fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError:
        handle.close()
        return None
    return handle


def is_running(directory: Path | None = None) -> bool:
    """Whether a warm-up of this installation is running (its lock is held)."""
    lock = _paths(directory)["lock"]
    if fcntl is None or not lock.exists():
        return False
    handle = _try_lock(lock)
    if handle is None:
        return True
    handle.close()
    return False


def start_background(directory: Path | None = None, command: list[str] | None = None) -> bool:
    """Start the warm-up in a detached, low-priority process if this installation's cache is
    not warm and no warm-up is running; True if one was started. Never raises.

    Parameters
    ----------
    directory : path, optional
        The state directory (default :func:`state_directory`).
    command : list of str, optional
        Arguments of the process after its state directory (tests: ``["--sleep", "S"]``).
    """
    if disabled():
        return False
    try:
        paths = _paths(directory)
        if paths["marker"].exists() or paths["failed"].exists():
            return False
        paths["lock"].parent.mkdir(parents=True, exist_ok=True)
        handle = _try_lock(paths["lock"])
        if handle is None:  # running
            return False
        handle.close()
        import subprocess  # here: a command on a warm cache does not need it

        env, cwd = compile_helper.child_environment()  # the warm-up's processes start no other
        with open(paths["log"], "ab") as log:  # through sh, which starts it and ends at once: reaped here,
            # the warm-up is nobody's child to wait for (no zombie, no "still running" warning)
            started = subprocess.run(["/bin/sh", "-c", '"$@" &', "sh", sys.executable, "-c", _CHILD,
                                      str(paths["lock"].parent), *(command or [])],
                                     stdin=subprocess.DEVNULL, stdout=log, stderr=subprocess.STDOUT, env=env,
                                     start_new_session=True, close_fds=True, cwd=cwd)
        return started.returncode == 0
    except OSError:
        return False


def mark_warm(done: dict, directory: Path | None = None, which: str = "marker") -> None:
    """Write this installation's marker atomically (``done``: what the warm-up reported;
    ``which="failed"``: a failed warm-up's marker); a marker that cannot be written is not.
    """
    try:
        marker = _paths(directory)[which]
        marker.parent.mkdir(parents=True, exist_ok=True)
        temporary = marker.with_name(f"{marker.name}.{os.getpid()}")
        temporary.write_text(json.dumps(done, default=str))
        os.replace(temporary, marker)
    except OSError:
        pass


def hold_lock(directory: Path | None = None):
    """``(lock, paths)``: an open file holding this installation's warm-up lock (None if another
    process holds it or the cache is warm) and the state paths (``marker``, ``lock``, ``log``).
    """
    paths = _paths(directory)
    paths["lock"].parent.mkdir(parents=True, exist_ok=True)
    handle = _try_lock(paths["lock"])
    if handle is not None and paths["marker"].exists():
        handle.close()
        handle = None
    return handle, paths
