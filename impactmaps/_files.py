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
(:mod:`impactmaps.targets.plates.basis_cache`) are kept there.
"""

from __future__ import annotations

import contextlib
import os
import secrets
from pathlib import Path

__all__ = ["CACHE_ENV", "cache_directory", "written_atomically"]

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
