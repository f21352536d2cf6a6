"""Plate bases kept on disk: the expensive arrays of a plate's Ritz basis, computed once.

A Ritz eigen-solution of a clamped Mindlin plate takes seconds (a dense eigenproblem of
up to :data:`~impactmaps.targets.plates.plate_any_edges.MAX_UNKNOWNS` unknowns); a map
sweep's worker, a lookup tile and every new process asked for it again. :func:`cached_arrays`
keeps such arrays in the package's cache directory (:func:`impactmaps._files.cache_directory`,
``$IMPACTMAPS_CACHE_DIR``; the subdirectory :data:`SUBDIRECTORY`), one ``.npz`` file per
set of inputs, named by the SHA-256 of a description of every input that determines them
(floats written exactly, in hexadecimal), :data:`BASIS_REVISION` (bumped when the code
that computes them changes) and the NumPy and SciPy versions (their LAPACK gives the
bits). A file is written atomically (:func:`impactmaps._files.written_atomically`) and is
used only when its stored description equals the one asked for and the SHA-256 of its
arrays matches the one stored with them: a truncated, corrupted or foreign file is
ignored and rebuilt. Arrays are read back bit for bit (``.npz`` stores the raw bytes), so
an answer is the same from a cold cache, the in-process cache and the disk: the same
inputs give the same bits alone, in a sweep, after a resume. At most
:data:`MAX_CACHED_BASES` files are kept (least recently used removed) and none larger
than :data:`MAX_BASIS_BYTES`. A cache that cannot be written changes nothing but the time.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
from pathlib import Path

import numpy as np

from ..._files import cache_directory, written_atomically

__all__ = ["BASIS_REVISION", "MAX_CACHED_BASES", "MAX_BASIS_BYTES", "SUBDIRECTORY", "basis_path", "cached_arrays"]

#: Revision of the code computing the cached arrays (part of every key): bump on any change
#: of their bits (plate_general's matrices and eigen-solution, the static compliances). 2: computed
#: with one BLAS thread (:mod:`impactmaps._blas`); a basis a Python session computed with several
#: threads before holds other bits and is not read. 3: the bases of a rectangular plate have fewer
#: functions across its short side, large bases are solved by block Krylov (:mod:`impactmaps._krylov`).
BASIS_REVISION = 3
#: Most files kept (the least recently used beyond it are removed).
MAX_CACHED_BASES = 64
#: Largest set of arrays written [bytes] (a larger one is recomputed each time).
MAX_BASIS_BYTES = 256 * 2**20
#: Subdirectory of the cache directory holding the bases.
SUBDIRECTORY = "plate-bases"


def _exact(value):
    """``value`` as JSON with every float written exactly (``float.hex``)."""
    if isinstance(value, (float, np.floating)):
        return float(value).hex()
    if isinstance(value, (list, tuple)):
        return [_exact(v) for v in value]
    if isinstance(value, (int, np.integer)):
        return int(value)
    return value


def _description(kind: str, inputs: dict) -> str:
    import scipy

    return json.dumps({"kind": kind, "inputs": {k: _exact(v) for k, v in inputs.items()},
                       "revision": BASIS_REVISION, "numpy": np.__version__, "scipy": scipy.__version__},
                      sort_keys=True)


def _digest(arrays: dict) -> str:
    digest = hashlib.sha256()
    for name in sorted(arrays):
        values = np.ascontiguousarray(arrays[name])
        digest.update(f"{name}:{values.dtype.str}:{values.shape}".encode())
        digest.update(values.tobytes())
    return digest.hexdigest()


def basis_path(kind: str, inputs: dict, cache_dir=None) -> Path:
    """The file of the arrays of ``kind`` with ``inputs`` [path]."""
    name = hashlib.sha256(_description(kind, inputs).encode()).hexdigest()[:32]
    return cache_directory(cache_dir) / SUBDIRECTORY / f"{kind}-{name}.npz"


def _read(path: Path, description: str) -> dict | None:
    try:
        with np.load(path, allow_pickle=False) as stored:
            arrays = {name: stored[name] for name in stored.files}
    except Exception:  # missing, truncated, not an npz: rebuilt
        return None
    key, digest = arrays.pop("__key__", None), arrays.pop("__digest__", None)
    if key is None or digest is None or str(key) != description or str(digest) != _digest(arrays):
        return None
    with contextlib.suppress(OSError):
        os.utime(path)  # recently used: kept longest
    return arrays


def _write(path: Path, description: str, arrays: dict) -> None:
    if sum(np.asarray(a).nbytes for a in arrays.values()) > MAX_BASIS_BYTES:
        return
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        with written_atomically(path) as temporary, open(temporary, "wb") as handle:
            np.savez(handle, __key__=np.array(description), __digest__=np.array(_digest(arrays)), **arrays)
        stored = sorted(path.parent.glob("*.npz"), key=lambda p: p.stat().st_mtime_ns, reverse=True)
        for stale in stored[MAX_CACHED_BASES:]:
            stale.unlink(missing_ok=True)
    except OSError:
        pass  # not kept: the next process computes it again


def cached_arrays(kind: str, inputs: dict, build, cache_dir=None) -> dict:
    """The arrays ``build()`` returns for ``inputs``, from the disk cache when it holds them.

    Parameters
    ----------
    kind : str
        What the arrays are (part of the key and of the file name), e.g. ``"general-modes"``.
    inputs : dict
        Every input that determines the arrays (numbers, strings, tuples of them).
    build : callable
        ``build()`` → dict of name → ndarray (names not starting with ``__``).
    cache_dir : path-like, optional
        The cache directory (default :func:`impactmaps._files.cache_directory`).

    Returns
    -------
    dict of ndarray
        Read-only arrays, bit for bit those ``build()`` gave (now or in an earlier process).
    """
    description = _description(kind, inputs)
    path = basis_path(kind, inputs, cache_dir)
    arrays = _read(path, description)
    if arrays is None:
        arrays = {name: np.asarray(values) for name, values in build().items()}
        _write(path, description, arrays)
    for values in arrays.values():
        values.setflags(write=False)
    return arrays
