"""Sweep results shipped with the package, found by the fingerprint of their sweep.

A sweep (:func:`impactmaps.maps.compute.sweep.sweep`) is a pure function of its description —
structures, grid, solver settings, contact law and solver revision — whose SHA-256 is
the result's fingerprint (:func:`impactmaps.maps.files.store.fingerprint`). The package ships
the results of the sweeps behind the default charts (``impactmaps chart`` and
``impactmaps chart --law hertz`` with no other option: SS Euler beam and SS square
Kirchhoff plate, 8 λ × 200 ζ; built by ``data_build/build_default_chart.py``) as
``data/results/<fingerprint>.npz`` (:mod:`.data_io`). A sweep whose
fingerprint names a shipped result starts from it as from a finished run to resume: no
point is computed again, and the values are those the same code computed (a default test
recomputes a sample of its points; the slow test all of them). Any other grid, setting or
solver revision has another fingerprint and is computed: a shipped result never answers
for a sweep it was not made by.
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
    """The shipped result of the sweep with fingerprint ``digest``, or ``None``.

    Parameters
    ----------
    digest : str
        Fingerprint of the sweep description.
    description : dict, optional
        The description itself (a mismatch names the keys that changed).

    Returns
    -------
    xarray.Dataset or None
        ``None`` when the package ships no result for this sweep — or ships one that cannot
        be read or does not match its name (a damaged installation): then a warning says
        so and the sweep computes its points, as for any other sweep.
    """
    try:
        return load_matching(shipped_result_path(digest), digest, description)
    except StoreMismatchError as error:
        warnings.warn(f"the shipped result of this sweep is not usable ({error}); computing it instead",
                      UserWarning, stacklevel=2)
        return None
