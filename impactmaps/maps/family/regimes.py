"""Which regime an impact is in: local, infinite-structure, transition or quasi-static.

Criteria (seed 001 §5, made quantitative here; every threshold is a parameter):

1. **local** — the response is that of the half-space: ``F̄max ≥ 1 − local_tolerance``
   (default 0.1; seed 001 calls ζ = 0.038, where F̄max ≈ 0.94, locally dominated) and
   the peak comes before the first wave returns (when the times are known: a heavy
   impactor on a stiff structure also reaches F̄max ≈ 1, but quasi-statically).
2. **infinite-structure** — not local, F̄max within ``tolerance`` (relative, default
   10 %) of the infinite-plate or infinite-beam peak F̄∞(ζ), and the peak occurs before
   the first wave returns from the supports (``peak_time < reflection_time``, when
   those are known): the size of the structure does not matter, ζ alone governs.
3. **quasi-static** — F̄max within ``tolerance`` of ``sqrt(λ/(1+λ))`` (eq 28): λ alone
   governs. (Beams approach it slowly: the seed's "fully global" beam at λ = 0.425,
   ζ = 11.3 is 6.5 % above it, hence the 10 % default.)
4. **transition** — none of the above: both ζ and λ matter.

When both asymptotes are within tolerance the nearer one wins, except that a peak known
to come before the first wave returns is never quasi-static (along the curve where the
two asymptotes cross, F̄∞(ζ) = sqrt(λ/(1+λ)), nearer-wins alone labelled such points
quasi-static: a thin sliver through the infinite-structure area of the regime maps). The same function
classifies a simulated result and, without simulating, a value looked up from a
stored map (:func:`impactmaps.maps.read.lookup.lookup`).

With ``law="hertz"`` the point is a Hertz map point (ζ_h, λ_h, F̄max = F_max/F_hs,
times over t*; :mod:`impactmaps.closed_forms.hertz_similarity`) and the asymptotes are those of the
Hertz law (:func:`impactmaps.maps.compute.hertz_points.hertz_asymptote_peak`): the half-space
is again F̄max = 1, the infinite plate is Zener's model, the infinite beam the
``t^{-1/2}`` mobility and the quasi-static peak solves ``F̄^{5/3} + (25/16) F̄²/λ_h = 1``.
"""

from __future__ import annotations

import numpy as np

from ..._checks import require_choice, require_in_range, require_positive
from ..._renamed import renamed_keyword
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
    """Quasi-static normalised peak force [-] of the map law ``law``'s family: the linear law's is
    the closed form sqrt(λ/(1+λ)) (eq 28, :func:`impactmaps.closed_forms.asymptotes.quasi_static_peak`);
    the Hertz law's F_max/F_hs in series with the static stiffness at λ_h
    (:func:`impactmaps.maps.compute.hertz_points.hertz_asymptote_peak`)."""
    return _classifying(law).quasi_static_peak(relative_stiffness)


@renamed_keyword("structure", "kind")
def infinite_structure_peak(loss_factor, kind: str, law: str = "linear"):
    """Normalised peak force of the infinite plate (eq 32) or beam (eq 36) [-].

    ``kind``: ``"beam"`` or ``"plate"``; the asymptote is the target class's
    (:meth:`impactmaps.targets.Target.infinite_structure_peak`). With ``law="hertz"``,
    F_max/F_hs of the Hertz law on the infinite structure at ζ_h
    (:func:`impactmaps.maps.compute.hertz_points.hertz_asymptote_peak`).
    """
    require_choice("kind", kind, STRUCTURE_KINDS)
    return _classifying(law).infinite_peak(loss_factor, kind)


def _classifying(law):
    """The registered map family ``law`` if its points have regimes, else ``ValueError``."""
    if law in available_map_families() and map_family(law).classifies:
        return map_family(law)
    require_choice("law", law, MAP_LAWS)  # names the built-in ones
    return map_family(law)


@renamed_keyword("structure", "kind")
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
    """Regime of each impact from its normalised peak force (vectorised).

    Parameters
    ----------
    fmax : array_like
        Normalised maximum force F̄max [-].
    loss_factor, relative_stiffness : array_like
        ζ and λ [-].
    kind : {"beam", "plate"}
        Which infinite-structure asymptote applies.
    peak_time, reflection_time : array_like, optional
        Normalised time of the peak and of the first wave return (ω d²/c); when
        given, the infinite-structure regime also requires the peak to come first.
    tolerance : float
        Relative distance to an asymptote that counts as "on" it.
    local_tolerance : float
        ``1 − F̄max`` below which the response is local.
    law : {"linear", "hertz"}
        Whose asymptotes: the linear law's (ζ, λ, F̄max = F_max/(m V0 ω)) or the Hertz
        law's (ζ_h, λ_h, F̄max = F_max/F_hs).
    peaks : (array_like, array_like), optional
        The infinite-structure and quasi-static peaks at these points when already known
        (:func:`infinite_structure_peak` and :func:`quasi_static_peak` of the same numbers,
        e.g. stored with a map); computed otherwise.

    Returns
    -------
    ndarray of str
        One of :data:`REGIMES` per point.
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
    if peaks is None:
        peaks = (infinite_structure_peak(zeta, kind, law), quasi_static_peak(lam, law))
    infinite, quasi = (_shaped(peak, fmax.shape) for peak in peaks)
    distance_infinite = np.abs(fmax - infinite) / infinite
    distance_quasi = np.abs(fmax - quasi) / quasi
    before_reflection = True
    if peak_time is not None and reflection_time is not None:
        before_reflection = _shaped(np.asarray(peak_time) < np.asarray(reflection_time), fmax.shape)
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
