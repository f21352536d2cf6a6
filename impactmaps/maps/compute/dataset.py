"""The map dataset of any family: its layout, its law and its regimes.

A map is an xarray Dataset with dims ``structure`` and the family's axes, its variables
with units, ``done`` marking computed points, and provenance attributes
(``fingerprint``, ``description``, ``contact_law``, ``solver_revision``; no time stamp).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from ... import __version__
from ...jsonio import dumps
from ..family.accuracy import STATUSES
from .points import METHODS, SOLVER_REVISION
from ..family.map_family import ASYMPTOTE_PEAK_VARIABLES, ASYMPTOTE_PEAKS, map_law
from ..family.map_family import map_family
from ..family.regimes import classify

__all__ = ["empty_dataset", "classify_dataset", "tidy_frame"]


def empty_dataset(family, structures, axes: dict, description: dict, digest: str) -> xr.Dataset:
    """A map of ``family`` over ``structures`` and ``axes`` (name → values [-], every axis) with
    no point computed; ``description`` and its fingerprint ``digest`` as attributes.
    """
    dims = ("structure", *family.axis_names)
    shape = (len(structures), *(len(axes[name]) for name in family.axis_names))
    data_vars = {name: (dims, np.full(shape, missing, dtype=dtype), {"units": units, "long_name": text})
                 for name, (dtype, missing, units, text) in family.variables.items()}
    data_vars["method"][2]["flag_values"] = np.arange(len(METHODS), dtype="i1")
    data_vars["method"][2]["flag_meanings"] = " ".join(METHODS)
    data_vars["status"][2]["flag_values"] = np.arange(len(STATUSES), dtype="i1")
    data_vars["status"][2]["flag_meanings"] = " ".join(STATUSES)
    data_vars["done"] = (dims, np.zeros(shape, dtype="i1"), {"long_name": "1 where the point has been computed"})
    coords = {"structure": ("structure", [s.name for s in structures])}
    coords |= {axis.name: (axis.name, np.asarray(axes[axis.name], float), {"long_name": axis.long_name, "units": "1"})
               for axis in family.axes}
    coords |= {
        "kind": ("structure", [s.kind for s in structures]),
        "theory": ("structure", [s.theory for s in structures]),
        "supports": ("structure", [s.supports for s in structures]),
        "aspect_ratio": ("structure", [s.aspect_ratio for s in structures]),
        "slenderness": ("structure", [s.slenderness for s in structures]),
    }
    attrs = {
        "title": family.title,
        "fingerprint": digest,
        "description": dumps(description, sort_keys=True),
        "impactmaps_version": __version__,
        "solver_revision": SOLVER_REVISION,
        "method": family.method_text,
        "contact_law": family.name,
    }
    return xr.Dataset(data_vars, coords=coords, attrs=attrs)


def with_asymptote_peaks(dataset: xr.Dataset) -> xr.Dataset:
    """``dataset`` with the asymptote peaks its regimes are judged by (the family's
    :meth:`~impactmaps.maps.family.map_family.MapFamily.asymptote_peaks`), computed once per
    grid; a map that holds them is returned as is.
    """
    if all(name in dataset for name in ASYMPTOTE_PEAKS):
        return dataset
    family = map_family(map_law(dataset))
    zeta, lam = dataset["zeta"].values, dataset["lambda_"].values
    kinds = [str(kind) for kind in dataset["kind"].values]
    by_kind = {kind: family.asymptote_peaks(kind, zeta, lam) for kind in sorted(set(kinds))}
    out = dataset.copy()
    for name, (axis, units, text) in ASYMPTOTE_PEAK_VARIABLES.items():
        out[name] = (("structure", axis), np.stack([by_kind[kind][name] for kind in kinds]),
                     {"units": units, "long_name": text})
    return out


def classify_dataset(dataset: xr.Dataset, **criteria) -> xr.DataArray:
    """Regime label of every computed point of a (ζ, λ) map; ``""`` where not computed or
    ``unresolved``.
    """
    labels = np.full(dataset["fmax_normalised"].shape, "", dtype=object)
    criteria.setdefault("law", map_law(dataset))
    peaked = with_asymptote_peaks(dataset)
    for s_index, kind in enumerate(dataset["kind"].values):
        fmax = dataset["fmax_normalised"].values[s_index]
        lam, zeta = np.meshgrid(dataset["lambda_"].values, dataset["zeta"].values, indexing="ij")
        infinite = np.broadcast_to(peaked["infinite_structure_peak"].values[s_index], fmax.shape)
        quasi = np.broadcast_to(peaked["quasi_static_peak"].values[s_index][:, None], fmax.shape)
        ok = dataset["done"].values[s_index].astype(bool) & np.isfinite(fmax)  # unresolved: no label
        if ok.any():
            labels[s_index][ok] = classify(
                fmax[ok], zeta[ok], lam[ok], str(kind),
                peak_time=dataset["peak_time_normalised"].values[s_index][ok],
                reflection_time=dataset["reflection_time_normalised"].values[s_index][ok],
                peaks=(infinite[ok], quasi[ok]), **criteria,
            )
    return xr.DataArray(labels.astype(str), dims=("structure", "lambda_", "zeta"),
                        attrs={"long_name": "impact regime (local / infinite-structure / transition / quasi-static)"})


def tidy_frame(dataset):
    """A sweep dataset as a tidy pandas DataFrame (one row per computed point), ``method`` and
    ``status`` as names, not codes.
    """
    frame = dataset.drop_vars(["kind", "theory", "supports", "aspect_ratio", "slenderness"]).to_dataframe().reset_index()
    frame = frame[frame["done"] == 1].drop(columns="done")
    if "method" in frame:
        frame["method"] = [METHODS[int(code)] if code >= 0 else "" for code in frame["method"]]
    if "status" in frame:
        frame["status"] = [STATUSES[int(code)] for code in frame["status"]]
    return frame.rename(columns={"lambda_": "lambda"})
