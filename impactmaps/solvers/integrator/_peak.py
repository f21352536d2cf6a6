"""Peak of a sampled force by parabolic refinement (compiled, shared by time steppers): the
parabola through three uniform samples cuts the peak's sampling error from O(h²) to O(h³).
"""

from __future__ import annotations

import numba

__all__ = ["parabolic_peak"]


@numba.njit(cache=True, inline="always")
def parabolic_peak(before, middle, after):
    """Vertex ``(value, offset)`` of the parabola through three equally spaced samples
    ``before``, ``middle``, ``after`` (at −h, 0, +h; any unit): its maximum (unit of the
    samples) and position from the middle sample in steps h [-]; ``(middle, 0)`` when they do
    not curve down.
    """
    curvature = before - 2.0 * middle + after
    if curvature < 0.0:
        offset = 0.5 * (before - after) / curvature
        return middle - 0.25 * (before - after) * offset, offset
    return middle, 0.0
