"""Parabolic refinement of a force peak sampled at fixed time steps (compiled, scalar).

An explicit integrator samples the contact force at ``t_n = n Δt``; the largest sample
``F_k`` misses the true maximum between steps by ``O(Δt²)``. The parabola through the
three samples ``F_{k−1}, F_k, F_{k+1}`` has its vertex at the offset

    ``s = ½ (F_{k−1} − F_{k+1}) / (F_{k−1} − 2F_k + F_{k+1})``  (in steps, |s| ≤ ½)

with value ``F_k − ¼ (F_{k−1} − F_{k+1}) s``, which brings the sampling error down to
``O(Δt³)``. Used by the finite-difference beam loop (:mod:`impactmaps.fd._loop`); kept
on its own so that other fixed-step integrators can share it.
"""

from __future__ import annotations

import numba

__all__ = ["parabolic_peak"]


@numba.njit(cache=True, inline="always")
def parabolic_peak(before, peak, after, peak_time, time_step):
    """Refine a sampled maximum with the parabola through its two neighbours.

    Parameters
    ----------
    before, peak, after : float
        Samples ``F_{k−1}``, ``F_k`` (the largest) and ``F_{k+1}`` [N].
    peak_time : float
        Time of the sample ``F_k`` [s].
    time_step : float
        Sampling interval Δt [s].

    Returns
    -------
    peak, peak_time : float
        The vertex of the parabola [N] and its time [s]; the sample unchanged when the
        three samples do not bracket a strict maximum with both neighbours in contact
        (``before > 0``, ``after > 0``, negative second difference). The caller checks
        that both neighbours exist.
    """
    curvature_of_peak = before - 2.0 * peak + after
    if curvature_of_peak < 0.0 and before > 0.0 and after > 0.0:
        offset = 0.5 * (before - after) / curvature_of_peak
        peak -= 0.25 * (before - after) * offset
        peak_time += offset * time_step
    return peak, peak_time
