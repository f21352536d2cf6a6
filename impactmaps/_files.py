"""Output files written whole or not at all.

:func:`written_atomically` gives a writer a temporary file beside the output (with the
output's suffix, from which pandas and matplotlib take the format) and renames it over the
output when the writer is done (``os.replace``): a reader, or a run interrupted while
writing, never sees a half-written file; a failed write leaves no temporary behind, and
one a killed process left (``.NAME.XXXX.tmp.SUFFIX``) is what
:func:`impactmaps.maps.files.store.remove_stale_temporaries` removes. The sweep store's files go
through it too (:func:`impactmaps.maps.files.store.save_atomic`).

:func:`cache_directory` is the one cache directory of the package: the on-demand map tiles
(:mod:`impactmaps.maps.compute.tiles`) and the plate bases
(:mod:`impactmaps.targets.plates.basis_cache`) are kept there; :func:`stored_floats` keeps there
the values of pure functions that cost more to compute than to read (the Hertz asymptote peaks,
the patch cut-off of a tile's points).
"""

from __future__ import annotations

import contextlib
import json
import math
import os
import secrets
from pathlib import Path

__all__ = ["CACHE_ENV", "cache_directory", "written_atomically", "stored_floats"]

#: Environment variable naming the cache directory (tiles, plate bases).
CACHE_ENV = "IMPACTMAPS_CACHE_DIR"


def cache_directory(cache_dir: str | os.PathLike | None = None) -> Path:
    """The cache: ``cache_dir`` if given, else ``$IMPACTMAPS_CACHE_DIR``, else
    ``$XDG_CACHE_HOME/impactmaps``, else ``~/.cache/impactmaps``."""
    if cache_dir is not None:
        return Path(cache_dir)
    if os.environ.get(CACHE_ENV):
        return Path(os.environ[CACHE_ENV])
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "impactmaps"


@contextlib.contextmanager
def written_atomically(path):
    """Yield the temporary path to write ``path`` [file] through; on leaving the block it
    replaces ``path`` in one rename (on an error it is removed and ``path`` is untouched)."""
    path = Path(path)
    temporary = path.with_name(f".{path.name}.{secrets.token_hex(4)}.tmp{path.suffix}")
    try:
        yield temporary
        os.replace(temporary, path)
    finally:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(temporary)


_stored: dict = {}  # file → {key: value}, read once per process


def stored_floats(path, keys, compute, most: int = 4096) -> list[float]:
    """The values of a pure function ``compute(key)`` (positive, finite floats) for ``keys``
    (texts): read from the JSON file ``path`` (once per process; the floats exactly, the same
    bits), the missing ones computed and written there with the others (atomically, the newest
    ``most``; nothing on a write error). A value is what ``compute`` gives, so the file never
    changes an answer; name the file by the revisions of the code that computes the values."""
    path = Path(path)
    if path not in _stored:
        try:
            loaded = json.loads(path.read_text(encoding="utf-8"))
            _stored[path] = {key: value for key, value in loaded.items()
                             if isinstance(value, float) and math.isfinite(value) and value > 0.0}
        except (OSError, ValueError, AttributeError):
            _stored[path] = {}
    stored, missing = _stored[path], [key for key in dict.fromkeys(keys) if key not in _stored[path]]
    for key in missing:
        stored[key] = float(compute(key))
    if missing:
        with contextlib.suppress(OSError):
            path.parent.mkdir(parents=True, exist_ok=True)
            with written_atomically(path) as temporary:
                temporary.write_text(json.dumps(dict(list(stored.items())[-most:])), encoding="utf-8")
    return [stored[key] for key in keys]
