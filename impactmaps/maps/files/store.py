"""A resumable, atomic store for sweep results (one NetCDF file, or a packed ``.npz``).

The file holds the whole grid, ``done`` marking computed points; every save writes a
temporary and renames it over the file. Each file carries the fingerprint of what
produced it: resuming with other settings is refused, naming the keys that changed.
"""

from __future__ import annotations

import hashlib
import json
import os
from pathlib import Path
from typing import TYPE_CHECKING


from ..._files import written_atomically
from ...jsonio import dumps
from .data_io import PACKED_SUFFIX, read_dataset, write_dataset

if TYPE_CHECKING:
    import xarray as xr

__all__ = ["fingerprint", "save_atomic", "load_matching", "remove_stale_temporaries",
           "StoreMismatchError", "SweepInterrupted"]


class StoreMismatchError(ValueError):
    """An existing result file was made with other settings or is unreadable."""


class SweepInterrupted(KeyboardInterrupt):
    """A sweep was interrupted (Ctrl-C) after saving: ``saved`` of ``total`` grid points are in
    ``path`` (``None`` without a file).
    """

    def __init__(self, saved: int, total: int, path=None):
        super().__init__(f"interrupted: {saved} of {total} points saved")
        self.saved, self.total, self.path = int(saved), int(total), path


def fingerprint(description: dict) -> str:
    """SHA-256 of a JSON-serialisable description (sorted keys)."""
    text = dumps(description, sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()


def save_atomic(dataset: xr.Dataset, path: str | os.PathLike, **options) -> Path:
    """Write ``dataset`` to ``path`` atomically; return the path. NetCDF3 via scipy, or the
    packed format for a ``.npz`` path (``options``: :func:`impactmaps.maps.files.data_io.write_dataset`'s)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with written_atomically(path) as temporary:
        write_dataset(dataset, temporary, packed=path.suffix == PACKED_SUFFIX, **options)
    return path


def remove_stale_temporaries(path: str | os.PathLike) -> list[Path]:
    """Delete the temporaries ``.NAME.XXXX.tmp[.SUFFIX]`` an interrupted save of ``path`` left;
    returns the paths removed.
    """
    path = Path(path)
    if not path.parent.is_dir():
        return []
    removed = []
    for stale in path.parent.glob(f".{path.name}.*.tmp*"):
        stale.unlink(missing_ok=True)
        removed.append(stale)
    return removed


def _differences(old, new, prefix: str = "") -> list[str]:
    """Key paths at which two JSON-like descriptions differ."""
    if isinstance(old, dict) and isinstance(new, dict):
        out = []
        for key in sorted(set(old) | set(new), key=str):
            out += _differences(old.get(key), new.get(key), f"{prefix}.{key}" if prefix else str(key))
        return out
    if isinstance(old, list) and isinstance(new, list) and len(old) == len(new):
        out = []
        for index, (a, b) in enumerate(zip(old, new)):
            out += _differences(a, b, f"{prefix}[{index}]")
        return out
    return [] if old == new else [prefix or "(whole description)"]


def load_matching(path: str | os.PathLike, expected_fingerprint: str,
                  description: dict | None = None) -> xr.Dataset | None:
    """The result file at ``path`` if it exists and was made by the sweep of
    ``expected_fingerprint``; ``None`` without a file.

    Raises
    ------
    StoreMismatchError
        (a ``ValueError``) if the file is unreadable or its fingerprint differs, naming the
        keys of ``description`` that changed when it is given.
    """
    path = Path(path)
    if not path.exists():
        return None
    try:
        dataset = read_dataset(path)
    except Exception as error:  # corrupted, truncated or not NetCDF (or a packed file) at all
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
        changed = ""
        if description is not None:
            try:
                old = json.loads(dataset.attrs.get("description", "{}"))
            except ValueError:
                old = {}
            keys = _differences(old, json.loads(dumps(description, sort_keys=True)))
            if keys:
                shown = ", ".join(keys[:6]) + (f" and {len(keys) - 6} more" if len(keys) > 6 else "")
                changed = f" (changed: {shown})"
        raise StoreMismatchError(
            f"result file {str(path)!r} was produced with different structures, grid or solver "
            f"settings{changed}; refusing to mix results. Use another output path, or overwrite "
            "it (sweep(..., overwrite=True); impactmaps sweep/chart --overwrite)."
        )
    return dataset
