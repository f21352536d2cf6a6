"""Sweep results shipped with the package, found by the fingerprint of their sweep.

A sweep is a pure function of its description, whose SHA-256 is its fingerprint; the
package ships the results behind the default charts as ``data/results/<fingerprint>.npz``.
A sweep whose fingerprint names one starts from it as from a finished run; any other
sweep is computed.
"""

from __future__ import annotations

import warnings
from importlib import resources
from pathlib import Path

import xarray as xr

from .data_io import PACKED_SUFFIX
from .store import StoreMismatchError, load_matching

__all__ = ["SHIPPED_RESULTS", "shipped_result_path", "load_shipped_result"]

#: Folder of the shipped sweep results, one packed file per fingerprint.
SHIPPED_RESULTS = Path(str(resources.files("impactmaps.maps").joinpath("data", "results")))


def shipped_result_path(digest: str) -> Path:
    """Where the shipped result of the sweep with fingerprint ``digest`` is (or would be):
    ``<digest>.npz`` (packed, :mod:`.data_io`), or a ``<digest>.nc`` not yet packed."""
    packed = SHIPPED_RESULTS / f"{digest}{PACKED_SUFFIX}"
    legacy = SHIPPED_RESULTS / f"{digest}.nc"
    return legacy if legacy.exists() else packed  # a .nc is read first (data_io.shipped_path)


def load_shipped_result(digest: str, description: dict | None = None) -> xr.Dataset | None:
    """The shipped result of the sweep with fingerprint ``digest``, or ``None`` when none is
    shipped or (with a warning) one cannot be read or does not match; ``description`` names
    the keys that changed.
    """
    try:
        return load_matching(shipped_result_path(digest), digest, description)
    except StoreMismatchError as error:
        warnings.warn(f"the shipped result of this sweep is not usable ({error}); computing it instead",
                      UserWarning, stacklevel=2)
        return None
