"""Peak of a sampled force by parabolic refinement (compiled, shared by time steppers).

A force sampled at a uniform step ``h`` is largest at a sample ``F_1`` with neighbours
``F_0`` before and ``F_2`` after; the parabola through the three samples peaks at

    offset = ½ (F_0 − F_2) / (F_0 − 2F_1 + F_2)      (in steps, from the middle sample),
    value  = F_1 − ¼ (F_0 − F_2) · offset,

which cuts the sampling error of the peak from O(h²) to O(h³).
"""

from __future__ import annotations

import numba

__all__ = ["parabolic_peak"]


@numba.njit(cache=True, inline="always")
def parabolic_peak(before, middle, after):
    """Vertex of the parabola through three equally spaced samples.

    Parameters
    ----------
    before, middle, after : float
        Samples at −h, 0, +h (any unit, e.g. force [N]).

    Returns
    -------
    value : float
        The parabola's maximum (same unit as the samples); ``middle`` when the samples
        do not curve downwards (no maximum).
    offset : float
        Its position relative to the middle sample, in steps h [-]; 0 with no maximum.
    """
    curvature = before - 2.0 * middle + after
    if curvature < 0.0:
        offset = 0.5 * (before - after) / curvature
        return middle - 0.25 * (before - after) * offset, offset
    return middle, 0.0
