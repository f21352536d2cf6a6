"""The cache files of the on-demand map tiles (:mod:`impactmaps.maps.compute.tiles`): each tile's
digest of its data, its verified reading, and the pruning of the least recently used.
"""

from __future__ import annotations

import hashlib
from pathlib import Path

import numpy as np

from .data_io import MapArrays, read_netcdf_arrays

__all__ = ["MAX_CACHED_TILES", "data_digest", "read_tile", "prune_tiles"]

#: Most tiles the cache keeps (the least recently used beyond it are removed).
MAX_CACHED_TILES = 256


def data_digest(dataset) -> str:
    """SHA-256 of a tile's coordinates and variables (names, dtypes and bytes)."""
    digest = hashlib.sha256()
    for name in ("zeta", "lambda_", *sorted(dataset.data_vars)):
        values = np.ascontiguousarray(dataset[name].values)
        digest.update(f"{name}:{values.dtype.str}:{values.shape}".encode())
        digest.update(values.tobytes())
    return digest.hexdigest()


def read_tile(path: Path, fingerprint: str) -> MapArrays | None:
    """The tile stored at ``path`` if it is the tile of ``fingerprint``, intact; else None. Read
    with NumPy alone (:func:`~impactmaps.maps.files.data_io.read_netcdf_arrays`: the same values
    as xarray, without importing dask)."""
    try:
        dataset = read_netcdf_arrays(path)
    except Exception:  # missing, truncated, not NetCDF: rebuilt
        return None
    if dataset.attrs.get("fingerprint") != fingerprint or dataset.attrs.get("data_digest") != data_digest(dataset):
        return None
    return dataset


def prune_tiles(directory: Path) -> None:
    """Remove the least recently used tiles beyond :data:`MAX_CACHED_TILES`."""
    tiles = sorted(directory.glob("tile-*.nc"), key=lambda p: p.stat().st_mtime_ns, reverse=True)
    for stale in tiles[MAX_CACHED_TILES:]:
        stale.unlink(missing_ok=True)
