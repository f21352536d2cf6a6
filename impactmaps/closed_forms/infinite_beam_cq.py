"""Sphere on an infinite Euler beam by convolution quadrature: separation and re-impact.

BDF2 convolution quadrature (Lubich 1988) of the receptance form
``ᾱ(τ) = τ − ∫0^τ G(τ − s) F̄(s) ds``, with the history sum by FFT blocks
(:func:`blocked_march`, O(N log² N)). Method and accuracy: docs/physics.rst.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numba
import numpy as np

from .._checks import require_positive

__all__ = ["DEFAULT_TIME_STEP", "LEAF_STEPS", "MAX_CQ_STEPS", "InfiniteBeamImpact", "bdf2_weights",
           "blocked_march", "causal_convolution", "cq_grid", "cq_march", "infinite_beam_impact", "weights_size"]

DEFAULT_TIME_STEP = 0.01  # normalised CQ step; max error ≈ 1.3e-4 on τ ≤ 10 (tests)
MAX_CQ_STEPS = 100_000  # beyond this the step is coarsened (warning)
#: Steps of the blocks whose history :func:`blocked_march` sums directly (compiled); longer
#: stretches get their history from earlier blocks by FFT convolution.
LEAF_STEPS = 256
_DIRECT_PRODUCT = 1 << 16  # a cross-block convolution of at most this many products: np.convolve


@numba.njit(cache=True)
def bdf2_weights(exponent, step, count):
    """BDF2 convolution-quadrature weights of K(s) = s^{-exponent} (Lubich 1988; stable recurrence)."""
    g1 = -4.0 / 3.0
    g2 = 1.0 / 3.0
    f = np.empty(count)
    f[0] = 1.0
    if count > 1:
        f[1] = -g1 * exponent
    for n in range(1, count - 1):
        f[n + 1] = -(g1 * (n + exponent) * f[n] + g2 * (n - 1 + 2.0 * exponent) * f[n - 1])
        f[n + 1] /= n + 1
    return (step / 1.5) ** exponent * f


@numba.njit(cache=True)
def _linear_block(weights, tau, prescribed, unilateral, history, force, indentation, lo, hi):
    """Steps ``lo ≤ n < hi`` of ᾱ_n = τ_n − Σ_{k≤n} W_{n−k} F̄_k (F̄ = ᾱ, or max(ᾱ, 0) if
    unilateral; given on the ``prescribed`` nodes); returns −1."""
    known = prescribed.size
    for n in range(lo, hi):
        local = 0.0
        for k in range(lo, n):
            local += weights[n - k] * force[k]
        free = tau[n] - (history[n] + local)
        if n < known:
            force[n] = prescribed[n]
        else:
            force[n] = free / (1.0 + weights[0])
            if unilateral and force[n] < 0.0:
                force[n] = 0.0
        indentation[n] = free - weights[0] * force[n]
    return -1


def _power_of_two(count: int) -> int:
    return 1 << max(int(count) - 1, 1).bit_length()


def weights_size(steps: int) -> int:
    """Number of CQ weights :func:`blocked_march` reads for ``steps`` steps (a power of two ≥ steps + 1)."""
    return _power_of_two(steps + 1)


def blocked_march(weights, force, solve_block, leaf=None) -> int:
    """Drive a convolution-quadrature march whose history sum is done by FFT blocks.

    ``weights``: CQ weights W_0 … W_{M−1} (M ≥ :func:`weights_size`); ``force``: F_0 … F_N
    (F_0 = 0), filled in place by ``solve_block(history, lo, hi) -> int``, which solves
    steps ``lo ≤ n < hi`` given ``history[n] = Σ_{k<lo} W_{n−k} F_k`` and returns the stop
    step or −1; ``leaf``: longest block [steps] (default :data:`LEAF_STEPS`). Returns the
    step where the march stopped, or −1 if it reached N.
    """
    leaf = LEAF_STEPS if leaf is None else int(leaf)
    history = np.zeros(force.size)
    spectra = {}

    def solve(lo, hi):
        if hi - lo <= leaf:
            return solve_block(history, lo, hi)
        mid = (lo + hi) // 2
        stop = solve(lo, mid)
        if stop >= 0:
            return stop
        history[mid:hi] += _cross_block(weights, force[lo:mid], hi - lo, spectra)
        return solve(mid, hi)

    return solve(1, force.size)


def _cross_block(weights, block, span, spectra):
    """``Σ_i block[i] W_{j−i}`` for ``len(block) ≤ j < span`` (the next stretch's history)."""
    size = block.size
    if size * span <= _DIRECT_PRODUCT:
        return np.convolve(block, weights[:span])[size:span]
    length = _power_of_two(span)
    if length not in spectra:
        spectra[length] = np.fft.rfft(weights[:length])
    return np.fft.irfft(np.fft.rfft(block, length) * spectra[length], length)[size:span]


def causal_convolution(first, second, count):
    """The first ``count`` terms ``c_n = Σ_{k≤n} first_{n−k} second_k`` of a convolution (FFT when long)."""
    first, second = first[:count], second[:count]
    if count * count <= 4 * _DIRECT_PRODUCT:
        return np.convolve(first, second)[:count]
    length = _power_of_two(2 * count)
    return np.fft.irfft(np.fft.rfft(first, length) * np.fft.rfft(second, length), length)[:count]


def cq_march(loss_factor: float, step: float, count: int, unilateral: bool, prescribed=None):
    """BDF2 CQ of the receptance form on ``count`` steps; returns (τ, F̄, ᾱ) at the nodes."""
    c = math.sqrt(math.pi) * loss_factor
    size = weights_size(count)
    weights = bdf2_weights(2.0, step, size) + 2.0 * c * bdf2_weights(1.5, step, size)
    tau = step * np.arange(count + 1)
    given = np.zeros(0) if prescribed is None else np.asarray(prescribed, dtype=float)
    force, indentation = np.zeros(count + 1), np.zeros(count + 1)

    def solve_block(history, lo, hi):
        return _linear_block(weights, tau, given, unilateral, history, force, indentation, lo, hi)

    blocked_march(weights, force, solve_block)
    return tau, force, indentation


def cq_grid(duration: float, time_step: float):
    """(step, count) of a CQ grid covering ``duration`` with steps ≤ ``time_step`` [-]
    (coarsened with a warning beyond :data:`MAX_CQ_STEPS`)."""
    count = max(int(math.ceil(duration / time_step)), 2)
    if count > MAX_CQ_STEPS:
        warnings.warn(
            f"convolution quadrature to τ = {duration:g} with step {time_step:g} needs {count} "
            f"steps; coarsened to {MAX_CQ_STEPS} steps (error grows like step²)",
            stacklevel=3,
        )
        count = MAX_CQ_STEPS
    return duration / count, count


@dataclass(frozen=True)
class InfiniteBeamImpact:
    """Unilateral impact on an infinite beam by convolution quadrature (normalised).

    Attributes
    ----------
    tau : ndarray
        Normalised time ω t [-], uniform grid from 0.
    force : ndarray
        F̄ = F/(m_i V0 ω) = max(ᾱ, 0) [-].
    indentation : ndarray
        ᾱ = α ω/V0 [-] (negative while separated).
    impactor_velocity : ndarray
        Impactor velocity / V0 [-].
    contacts : ndarray, shape (n, 2)
        Start and end τ of each contact (end = inf if still in contact).
    """

    tau: np.ndarray
    force: np.ndarray
    indentation: np.ndarray
    impactor_velocity: np.ndarray
    contacts: np.ndarray


def infinite_beam_impact(
    loss_factor, duration, *, time_step=DEFAULT_TIME_STEP, prescribed_force=None
):
    """Impact on an infinite beam with separation and re-impact (BDF2 CQ).

    Parameters
    ----------
    loss_factor : float
        Beam loss factor ζ_b [-], > 0.
    duration : float
        Normalised end time ω t_end [-], > 0.
    time_step : float, optional
        Normalised step ω Δt [-] (error O(step²) while in contact).
    prescribed_force : callable, optional
        ``(tau_array) -> force`` used before the first node where it is negative.

    Returns
    -------
    InfiniteBeamImpact
    """
    require_positive("loss_factor", loss_factor)
    require_positive("duration", duration)
    require_positive("time_step", time_step)
    step, count = cq_grid(float(duration), float(time_step))
    prescribed = None
    if prescribed_force is not None:
        values = np.asarray(prescribed_force(step * np.arange(count + 1)), dtype=float)
        negative = np.flatnonzero(values[1:] < 0)
        end = negative[0] + 1 if negative.size else count + 1
        prescribed = values[:end]
    tau, force, indentation = cq_march(float(loss_factor), step, count, True, prescribed)
    impulse = np.concatenate([[0.0], np.cumsum(0.5 * step * (force[1:] + force[:-1]))])
    in_contact = force > 0
    edges = np.flatnonzero(np.diff(in_contact.astype(int)))
    starts = [tau[i] for i in edges if not in_contact[i]]
    ends = [tau[i + 1] for i in edges if in_contact[i]]
    if len(ends) < len(starts):
        ends.append(math.inf)
    contacts = np.column_stack([starts, ends]) if starts else np.zeros((0, 2))
    return InfiniteBeamImpact(tau, force, indentation, 1.0 - impulse, contacts)
