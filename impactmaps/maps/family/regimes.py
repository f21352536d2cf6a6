"""Which regime an impact is in: local, infinite-structure, transition or quasi-static.

:func:`classify` compares F̄max with the half-space, infinite-structure and quasi-static
peaks of the linear or the Hertz law (thresholds are parameters); it classifies a run
and a value looked up from a map alike. The criteria: docs/chart.rst, "The regime map".
"""

from __future__ import annotations

import numpy as np

from ..._checks import require_choice, require_in_range, require_positive
from ...targets.options import STRUCTURE_KINDS
from .builtin_families import PLANE_LAWS
from .map_family import available_map_families, map_family

__all__ = ["REGIMES", "MAP_LAWS", "classify", "infinite_structure_peak", "quasi_static_peak"]

#: The built-in (ζ, λ) map families, whose asymptotes :func:`classify` knows.
MAP_LAWS = PLANE_LAWS

REGIMES = ("local", "infinite-structure", "transition", "quasi-static")
_REGIME_ARRAY = np.array(REGIMES)
_LOCAL, _INFINITE, _TRANSITION, _QUASI_STATIC = range(len(REGIMES))


def quasi_static_peak(relative_stiffness, law: str = "linear"):
    """Quasi-static normalised peak force [-]: sqrt(λ/(1+λ)) (eq 28) for the linear law; with
    ``law="hertz"``, F_max/F_hs of the Hertz law in series with the static stiffness at λ_h.
    """
    return _classifying(law).quasi_static_peak(relative_stiffness)


def infinite_structure_peak(loss_factor, kind: str, law: str = "linear"):
    """Normalised peak force of the infinite plate (eq 32) or beam (eq 36) [-]; ``kind``:
    ``"beam"`` or ``"plate"``. With ``law="hertz"``, F_max/F_hs at ζ_h.
    """
    require_choice("kind", kind, STRUCTURE_KINDS)
    return _classifying(law).infinite_peak(loss_factor, kind)


def _classifying(law):
    """The registered map family ``law`` if its points have regimes, else ``ValueError``."""
    if law in available_map_families() and map_family(law).classifies:
        return map_family(law)
    require_choice("law", law, MAP_LAWS)  # names the built-in ones
    return map_family(law)


def classify(
    fmax,
    loss_factor,
    relative_stiffness,
    kind: str,
    *,
    peak_time=None,
    reflection_time=None,
    tolerance: float = 0.1,
    local_tolerance: float = 0.1,
    law: str = "linear",
    peaks=None,
):
    """Regime of each impact from its normalised peak force (vectorised), one of
    :data:`REGIMES` per point (criteria: docs/chart.rst).

    Parameters
    ----------
    fmax : array_like
        Normalised maximum force F̄max [-].
    loss_factor, relative_stiffness : array_like
        ζ and λ [-].
    kind : {"beam", "plate"}
        Which infinite-structure asymptote applies.
    peak_time, reflection_time : array_like, optional
        Normalised peak time and first wave return; when given, the infinite-structure
        regime requires the peak first.
    tolerance : float
        Relative distance to an asymptote that counts as "on" it.
    local_tolerance : float
        ``1 − F̄max`` below which the response is local.
    law : {"linear", "hertz"}
        Whose asymptotes (and numbers).
    peaks : (array_like, array_like), optional
        The infinite-structure and quasi-static peaks when already known (e.g. stored
        with a map).
    """
    require_in_range("tolerance", tolerance, 0.0, 1.0, low_inclusive=False)
    require_in_range("local_tolerance", local_tolerance, 0.0, 1.0, low_inclusive=False)
    fmax, zeta, lam = np.broadcast_arrays(
        np.asarray(fmax, dtype=float), np.asarray(loss_factor, dtype=float), np.asarray(relative_stiffness, dtype=float)
    )
    if np.any(~np.isfinite(fmax)):
        raise ValueError("fmax contains NaN or inf: classify computed points only")
    require_positive("loss_factor", zeta)
    require_positive("relative_stiffness", lam)
    before_reflection = True
    if peak_time is not None and reflection_time is not None:
        before_reflection = _shaped(np.asarray(peak_time) < np.asarray(reflection_time), fmax.shape)
    if peaks is None:  # no peak before its reflection: the infinite structure's peak decides nothing
        needed = np.any(before_reflection)
        peaks = (infinite_structure_peak(zeta, kind, law) if needed else np.full(fmax.shape, np.nan),
                 quasi_static_peak(lam, law))
    infinite, quasi = (_shaped(peak, fmax.shape) for peak in peaks)
    with np.errstate(invalid="ignore"):
        distance_infinite = np.abs(fmax - infinite) / infinite
    distance_quasi = np.abs(fmax - quasi) / quasi
    known_before = False
    if peak_time is not None and reflection_time is not None:
        known_before = before_reflection
    on_infinite = (distance_infinite <= tolerance) & before_reflection
    on_quasi = distance_quasi <= tolerance
    code = np.where(on_quasi, _QUASI_STATIC, _TRANSITION)
    # a peak before the first wave returns cannot be quasi-static (no reflection has
    # reached the contact yet): where the two asymptotes cross, F̄∞(ζ) = sqrt(λ/(1+λ)), the
    # nearer-wins rule alone drew a quasi-static sliver through the infinite-structure area
    code = np.where(on_infinite & (~on_quasi | (distance_infinite <= distance_quasi) | known_before),
                    _INFINITE, code)
    code = np.where((fmax >= 1.0 - local_tolerance) & before_reflection, _LOCAL, code)
    return np.asarray(_REGIME_ARRAY[code])


def _shaped(values, shape) -> np.ndarray:
    """``values`` broadcast to ``shape`` (as they are when they have it already)."""
    values = np.asarray(values)
    values = values if values.dtype == bool else values.astype(float, copy=False)
    return values if values.shape == shape else np.broadcast_to(values, shape)
