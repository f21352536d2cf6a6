"""One writer per sweep store: a lock file ``<store>.lock`` (``host pid``, created
atomically) while a sweep writes it; a second writer is refused. A lock left by a dead
process on this host is taken over; another host's lock is respected.
"""

from __future__ import annotations

import contextlib
import os
import socket
from pathlib import Path

__all__ = ["StoreLockedError", "store_lock", "lock_path"]


class StoreLockedError(ValueError):
    """Another live sweep holds the store's lock."""


def lock_path(store) -> Path:
    """The lock file of the store ``store`` (``sweep.nc`` → ``sweep.nc.lock``)."""
    store = Path(store)
    return store.with_name(store.name + ".lock")


def _holder(lock: Path) -> tuple[str, int | None]:
    try:
        host, _, pid = lock.read_text(encoding="utf-8").strip().partition(" ")
        return host, int(pid)
    except (OSError, ValueError):
        return "", None


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # exists, owned by someone else
        return True
    return True


def _stale(lock: Path) -> bool:
    host, pid = _holder(lock)
    return host == socket.gethostname() and pid is not None and not _alive(pid)


@contextlib.contextmanager
def store_lock(store, option: str = "the store"):
    """Hold the lock of the sweep store file ``store`` for the ``with`` block (its directory is
    created); ``option`` names the store's origin in messages (e.g. ``"--out"``).

    Raises
    ------
    StoreLockedError
        A live process holds the lock (naming it and the lock file).
    ValueError
        The store's directory is a file.
    """
    store = Path(store)
    if store.parent.exists() and not store.parent.is_dir():
        raise ValueError(f"{option} = {str(store.parent)!r} is a file, not a directory")
    store.parent.mkdir(parents=True, exist_ok=True)
    lock = lock_path(store)
    for _attempt in range(2):
        try:
            handle = os.open(lock, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o644)
            break
        except FileExistsError:
            if not _stale(lock):
                host, pid = _holder(lock)
                raise StoreLockedError(
                    f"{store} is being written by another sweep (process {pid} on {host or 'an unknown host'}); "
                    f"run one sweep per store at a time, or, if no sweep runs, remove {lock}") from None
            with contextlib.suppress(FileNotFoundError):
                lock.unlink()  # its writer was killed: take the lock over
    else:
        raise StoreLockedError(f"{store}: its lock {lock} was taken by another sweep meanwhile")
    try:
        os.write(handle, f"{socket.gethostname()} {os.getpid()}\n".encode())
    finally:
        os.close(handle)
    try:
        yield lock
    finally:
        with contextlib.suppress(FileNotFoundError):
            lock.unlink()
