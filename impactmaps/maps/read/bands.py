"""A lookup's band and status: the interpolation-error estimate of a map's grid, the severity of
the map points' statuses, the status of an answer read between them, and the note the command
line prints beside it.

A light module (NumPy and :mod:`.accuracy`) for the map reader (:mod:`.reader`), which
re-exports its names, the slenderness interpolation (:mod:`.slenderness`) and the command line.
"""

from __future__ import annotations

import numpy as np

from ..family.accuracy import STATUSES, AccuracyControl

__all__ = ["SEVERITY", "BAND_TOLERANCE", "INTERPOLATION_SAFETY", "answer_status", "corner_status", "status_notes",
           "interpolation_error", "slice_estimates"]


#: Severity of a status when map points (or slenderness members) are combined (worst wins);
#: ``interpolated`` is a lookup's own status (:func:`answer_status`), never a point's.
SEVERITY = {"asymptotic": 0, "converged": 0, "refined": 1, "interpolated": 2, "sensitive": 3, "unresolved": 4}
#: The status of each severity.
BY_SEVERITY = np.array(["converged", "refined", "interpolated", "sensitive", "unresolved"])
#: Severity of each status code (:data:`impactmaps.maps.family.accuracy.STATUSES`).
CODE_SEVERITY = np.array([SEVERITY[name] for name in STATUSES])
#: The map points' refinement tolerance (``AccuracyControl().tolerance``): a lookup whose
#: band is wider is ``interpolated``, even where every point around it converged.
BAND_TOLERANCE = AccuracyControl().tolerance


def answer_status(point_status, band):
    """The status of an interpolated answer from its map points' worst status and its band.

    ``interpolated`` where the points converged (``converged``, ``refined``) but the band
    — their own error plus the interpolation (or slenderness) error between them — is wider
    than :data:`BAND_TOLERANCE`: the points are right, the value between them is known only
    to ± the band (near a re-impact kink of F̄max the interpolation errs by up to a few
    1e-2). Otherwise the points' status. Scalars give a ``str``, arrays an array.
    """
    status = np.asarray(point_status)
    widened = ((status == "converged") | (status == "refined")) & (np.asarray(band) > BAND_TOLERANCE)
    out = np.where(widened, "interpolated", status)
    return out.item() if out.ndim == 0 else out


def corner_status(corner_codes, band):
    """The status of an answer read between map points: the worst of the points' statuses
    (``corner_codes``: one array of status codes of :data:`impactmaps.maps.family.accuracy.STATUSES`
    per corner around the answers), ``interpolated`` where the ``band`` makes it so
    (:func:`answer_status`)."""
    worst = np.max(CODE_SEVERITY[np.asarray(corner_codes)], axis=0)
    return answer_status(BY_SEVERITY[worst], band)


#: What a lookup's status means for its number, where that needs saying.
_STATUS_NOTES = {
    "interpolated": "the map points around this one converged, but between them F̄max is known only to "
                    "± fmax_error (interpolation across the map's kinks or curvature); a simulation computes "
                    "it to 1e-3 (`impactmaps point` for the linear law, `impactmaps simulate` on a case file for "
                    "any law)",
    "sensitive": "no converged value: re-impacts whose order flips with any change of the model; read the band "
                 "(± fmax_error), not the number",
}


def status_notes(status) -> dict:
    """``{"status_note": text}`` for a status whose number needs a word (``interpolated``,
    ``sensitive``), else ``{}``; what the command line prints beside a lookup's status."""
    note = _STATUS_NOTES.get(str(status)) if np.ndim(status) == 0 else None
    return {"status_note": note} if note else {}


#: Safety factor of :func:`interpolation_error` on the leading-order term ``h² |f''| / 8``.
INTERPOLATION_SAFETY = 5.0


def interpolation_error(values: np.ndarray, *, reach: int = 2, safety: float = INTERPOLATION_SAFETY,
                        axes=None) -> np.ndarray:
    """Local estimate of the linear-interpolation error of a map, per grid point [-].

    ``values`` has one axis per map axis (two for a (λ, ζ) map, three for a plastic
    (β, λ, ζ) map; the sum below runs over all of them). Linear interpolation between
    grid points errs by about ``h² |f''| / 8`` in each direction; with the second
    differences of the map itself (``Δ²f``, in grid units) that is
    ``(|Δ²_λ f| + |Δ²_ζ f|) / 8``, each taken as the largest over the point and its two
    neighbours on each side along its axis: second differences are largest next to kinks,
    which a cell may straddle, and F̄max has ripples shorter than the grid spacing
    (quasi-static regime, ~1e-4) that one point's second differences alias — with one
    neighbour a side the band missed one of 734 random points of the twice-denser Euler
    beam map by 20 %. Near the re-impact kinks of the transition the leading-order term
    underestimates the error by up to 3.3× on maps of 20 ζ and 10 λ per decade (320 random
    points) and by 4.9× at one of 1102 random points of the twice-denser maps (a steep
    change of the impact that carries the peak, within one λ cell), so the estimate
    carries a safety factor of 5: ``5 (|Δ²_λ f| + |Δ²_ζ f|) / 8``. Edges reuse the
    nearest interior difference.

    Parameters
    ----------
    values : ndarray
        The map's values on its grid (NaN where a point holds no value).
    reach : int
        Neighbours on each side over which a second difference is the largest (2 for the
        (ζ, λ) maps; the plastic maps keep the 1 they were validated with).
    safety : float
        Factor on the leading-order term (:data:`INTERPOLATION_SAFETY`; the plastic maps: 4).
    axes : sequence of int, optional
        The axes whose second differences are summed (default all; :func:`slice_estimates`
        splits a plastic map's estimate into its (λ, ζ) part and its β part).

    Returns
    -------
    ndarray
        The estimate per grid point [same unit as ``values``].
    """
    f = np.asarray(values, float)
    second = np.zeros_like(f)
    for axis in range(f.ndim) if axes is None else axes:
        if f.shape[axis] < 3:  # no second difference along a 1- or 2-point axis
            continue
        d2 = _nearest_known(np.abs(np.diff(f, n=2, axis=axis)), axis)
        pad = [(0, 0)] * f.ndim
        pad[axis] = (1, 1)
        d2 = np.pad(d2, pad, mode="edge")
        widened = d2.copy()
        for shift in range(1, reach + 1):
            widened = np.maximum(widened, np.maximum(np.roll(d2, shift, axis=axis), np.roll(d2, -shift, axis=axis)))
        second += widened
    return second * (safety / 8.0)


def slice_estimates(values: np.ndarray, family) -> tuple[np.ndarray, np.ndarray]:
    """A map's interpolation estimate per grid point split by axes: its (λ, ζ) part, what a
    slice's refinement (:mod:`impactmaps.maps.family.slice_refinement`) splits against and reads at
    its unsplit leaves, and the extra axes' part, what interpolating across slices adds [-].
    With the family's ``reach`` and ``safety`` (:func:`interpolation_error` of those axes)."""
    f = np.asarray(values, float)
    settings = family.interpolation
    plane = interpolation_error(f, reach=settings.reach, safety=settings.safety, axes=(f.ndim - 2, f.ndim - 1))
    extra = interpolation_error(f, reach=settings.reach, safety=settings.safety, axes=tuple(range(f.ndim - 2)))
    return plane, extra


def _nearest_known(d2: np.ndarray, axis: int) -> np.ndarray:
    """``d2`` with each missing entry (a difference that reaches an ``unresolved`` point,
    NaN) replaced by the nearest known one along ``axis`` (the largest known anywhere when
    a whole line is missing)."""
    if not np.isnan(d2).any():
        return d2
    out = np.ascontiguousarray(np.moveaxis(d2, axis, -1))  # a copy: lines are views of it
    fallback = float(np.nanmax(d2)) if np.isfinite(d2).any() else 0.0
    positions = np.arange(out.shape[-1])
    for line in out.reshape(-1, out.shape[-1]):
        known = np.flatnonzero(np.isfinite(line))
        missing = np.flatnonzero(np.isnan(line))
        if missing.size == 0:
            continue
        if known.size == 0:
            line[missing] = fallback
            continue
        nearest = known[np.abs(positions[missing, None] - known[None, :]).argmin(axis=1)]
        line[missing] = line[nearest]
    return np.moveaxis(out, -1, axis)
