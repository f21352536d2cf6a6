"""A resumable, atomic store for sweep results (one NetCDF file).

The file holds the whole result grid; points not yet computed are marked in the
``done`` variable. Every save writes a temporary file beside the target and renames it
over the target (``os.replace``), so a reader never sees a half-written file and an
interrupted sweep loses at most the points in flight. Each file carries the
fingerprint of what produced it (structures, grid, solver settings, solver revision);
resuming with different settings is refused rather than mixing results.
"""

from __future__ import annotations

import hashlib
import os
import tempfile
from pathlib import Path

import xarray as xr

from ..jsonio import dumps

__all__ = ["fingerprint", "save_atomic", "load_matching", "StoreMismatchError"]


class StoreMismatchError(ValueError):
    """An existing result file was made with other settings or is unreadable."""


def fingerprint(description: dict) -> str:
    """SHA-256 of a JSON-serialisable description (sorted keys)."""
    text = dumps(description, sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()


def save_atomic(dataset: xr.Dataset, path: str | os.PathLike) -> Path:
    """Write ``dataset`` to ``path`` (NetCDF3 via scipy) atomically; return the path."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    handle, temporary = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    os.close(handle)
    try:
        dataset.to_netcdf(temporary, engine="scipy", format="NETCDF3_64BIT")
        os.replace(temporary, path)
    except BaseException:
        if os.path.exists(temporary):
            os.unlink(temporary)
        raise
    return path


def load_matching(path: str | os.PathLike, expected_fingerprint: str) -> xr.Dataset | None:
    """Load a result file if it exists and was made by the same sweep description.

    Returns ``None`` if there is no file. Raises :class:`StoreMismatchError` (a
    ``ValueError``) if the file is unreadable or its fingerprint differs.
    """
    path = Path(path)
    if not path.exists():
        return None
    try:
        with xr.open_dataset(path, engine="scipy") as opened:
            dataset = opened.load()
    except Exception as error:  # corrupted, truncated or not NetCDF at all
        raise StoreMismatchError(
            f"result file {str(path)!r} cannot be read as an impactmaps sweep ({error}); "
            "delete it or choose another output path"
        ) from None
    found = dataset.attrs.get("fingerprint")
    if found is None:
        raise StoreMismatchError(
            f"result file {str(path)!r} is not an impactmaps sweep (no fingerprint attribute); "
            "refusing to overwrite or mix it"
        )
    if found != expected_fingerprint:
        raise StoreMismatchError(
            f"result file {str(path)!r} was produced with different structures, grid or solver "
            "settings; refusing to mix results. Use another output path or delete the file."
        )
    return dataset
