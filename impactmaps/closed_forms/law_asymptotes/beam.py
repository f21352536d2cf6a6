"""Impact on an infinite Euler beam with any contact law (convolution quadrature).

The indentation ``α(t) = V0 t − ∫0^t G(t − s) F(s) ds``, ``G(t) = t/m + 2A sqrt(t/π)``,
marched by BDF2 convolution quadrature with a safeguarded Newton solve per step, through
every re-impact. Derivation and scheme: docs/physics.rst (Closed forms).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from ..._checks import require_positive
from ...contact.base import KERNEL_TYPE, ContactLaw, kernel_pointer
from ..halfspace import single_law_parameters
from ..infinite_beam_cq import bdf2_weights, blocked_march, causal_convolution, weights_size
from ..._compile.lazy_kernel import LazyKernel
from .result import (
    AsymptoteResult,
    contact_frequency_of,
    contact_intervals_from_samples,
)

__all__ = ["beam_mobility_constant", "infinite_beam_impact_any_law"]

DEFAULT_STEP = 0.01  # in units of 1/ω (contact frequency); peak error ~1e-4 (tests)
DEFAULT_DURATION = 100.0  # in units of 1/ω
_NEWTON_ITERATIONS = 60


def beam_mobility_constant(mass_per_length, bending_stiffness) -> float:
    """``A = 1/(2 sqrt(2) m'^{3/4} (EI)^{1/4})`` [m/(N s^{1/2})] of ``mass_per_length`` m' [kg/m] and
    ``bending_stiffness`` EI [N m²], both > 0."""
    require_positive("mass_per_length", mass_per_length, "kg/m")
    require_positive("bending_stiffness", bending_stiffness, "N m^2")
    return 1.0 / (2.0 * math.sqrt(2.0) * float(mass_per_length) ** 0.75
                  * float(bending_stiffness) ** 0.25)


def infinite_beam_impact_any_law(beam, law: ContactLaw, impactor_mass, velocity, *,
                                 time_step=DEFAULT_STEP, duration=DEFAULT_DURATION
                                 ) -> AsymptoteResult:
    """Impact on an infinite Euler beam, through every re-impact, with any contact law.

    Parameters
    ----------
    beam : Beam
        Its ``mass_per_length`` m' [kg/m] and ``bending_stiffness`` EI [N m²] (span,
        supports and theory are ignored).
    law : ContactLaw
        A single registered contact law.
    impactor_mass : float
        m > 0 [kg].
    velocity : float
        V0 > 0 [m/s].
    time_step : float, optional
        Step in units of 1/ω [-].
    duration : float, optional
        Longest run in units of 1/ω [-]; reaching it sets ``time_limit_reached``.

    Returns
    -------
    AsymptoteResult
        ``method = "infinite-beam"``; contact times resolved to the step.
    """
    require_positive("impactor_mass", impactor_mass, "kg")
    require_positive("velocity", velocity, "m/s")
    require_positive("time_step", time_step)
    require_positive("duration", duration)
    params = single_law_parameters(law)
    mass, speed = float(impactor_mass), float(velocity)
    omega = contact_frequency_of(law, mass, speed)
    step = float(time_step) / omega
    count = max(math.ceil(float(duration) / float(time_step)), 2)
    mobility = beam_mobility_constant(beam.mass_per_length, beam.bending_stiffness)
    size = weights_size(count)
    beam_weights = mobility * bdf2_weights(1.5, step, size)
    weights = bdf2_weights(2.0, step, size) / mass + beam_weights
    force, alpha, last = _march(law.kernel, params, weights, step, speed, mass, count)
    time = step * np.arange(last + 1)
    force, alpha = force[: last + 1], alpha[: last + 1]
    impulse = np.concatenate(([0.0], np.cumsum(0.5 * step * (force[1:] + force[:-1]))))
    impactor_velocity = speed - impulse / mass
    deflection = causal_convolution(beam_weights, force, last + 1)
    # the clearance is read only either side of a contact edge: the law's permanent
    # indentation (a Python loop for some laws) is evaluated there only
    edges = np.flatnonzero(np.diff((force > 0.0).astype(int)))
    near = np.union1d(edges, edges + 1)
    clearance = np.zeros_like(alpha)
    if near.size:
        clearance[near] = alpha[near] - np.asarray(
            law.permanent_indentation(np.maximum.accumulate(alpha)[near]), dtype=float).reshape(-1)
    intervals = contact_intervals_from_samples(time, force, clearance)
    peak_index = int(np.argmax(force))
    peak_force, peak_time = _refined_peak(time, force, peak_index)
    finished = force[-1] == 0.0 and impactor_velocity[-1] <= 0.0
    alpha_max = float(np.max(alpha))
    return AsymptoteResult(
        method="infinite-beam",
        peak_force=peak_force,
        peak_time=peak_time,
        contact_time=intervals[-1][1] - intervals[0][0] if finished else math.inf,
        restitution=max(-float(impactor_velocity[-1]), 0.0) / speed if finished else 0.0,
        fmax_normalised=peak_force / (mass * speed * omega),
        impacts=len(intervals),
        contact_intervals=intervals,
        max_indentation=alpha_max,
        permanent_indentation=float(law.permanent_indentation(alpha_max)),
        max_target_displacement=float(np.max(deflection)),
        impactor_mass=mass,
        velocity=speed,
        contact_frequency=omega,
        time_limit_reached=not finished,
    )


def _march(kernel, params, weights, step, speed, mass, count):
    """CQ steps until the sphere has separated and moves away, or ``count`` steps:
    (force, indentation, index of the last step)."""
    force = np.zeros(count + 1)
    alpha = np.zeros(count + 1)
    # running state of the march: α_max, impulse, touched (0/1), step, V0, m
    state = np.array([0.0, 0.0, 0.0, step, speed, mass])
    pointer = kernel_pointer(kernel)

    def solve_block(history, lo, hi):
        return _law_block(pointer, params, weights, history, force, alpha, state, lo, hi)

    last = blocked_march(weights, force, solve_block)
    return force, alpha, count if last < 0 else last


@numba.njit(cache=True)
def _law_block_kernel(kernel, params, weights, history, force, alpha, state, lo, hi):
    """Steps ``lo ≤ n < hi`` of ``α_n + W_0 F_n = V0 t_n − history[n] − Σ_{lo≤k<n} W_{n−k} F_k``
    (``state`` updated in place); returns the step where the sphere moves away, or −1."""
    alpha_max, impulse, touched = state[0], state[1], state[2] > 0.0
    step, speed, mass = state[3], state[4], state[5]
    stop = -1
    for n in range(lo, hi):
        local = 0.0
        for k in range(lo, n):
            local += weights[n - k] * force[k]
        free = speed * step * n - (history[n] + local)
        alpha[n], force[n] = _solve_step(kernel, params, weights[0], free, alpha_max)
        alpha_max = max(alpha_max, alpha[n])
        impulse += 0.5 * step * (force[n] + force[n - 1])
        touched = touched or force[n] > 0.0
        if touched and force[n] == 0.0 and speed - impulse / mass <= 0.0:
            stop = n
            break
    state[0], state[1], state[2] = alpha_max, impulse, 1.0 if touched else 0.0
    return stop


_VECTOR = numba.types.Array(numba.types.float64, 1, "C")
# Compiled (or loaded from numba's cache) on the first march, not at import.
_law_block = LazyKernel(_law_block_kernel, numba.types.int64(
    KERNEL_TYPE, _VECTOR, _VECTOR, _VECTOR, _VECTOR, _VECTOR, _VECTOR, numba.types.int64, numba.types.int64))


@numba.njit(cache=True)
def _solve_step(kernel, params, implicit_weight, free, alpha_max):
    """Root α of ``α + W0 F(α; max(α_max, α)) = free`` and its force (safeguarded Newton)."""
    if free <= 0.0:
        return free, 0.0
    force = kernel(free, max(alpha_max, free), params)[0]
    if force <= 0.0:
        return free, 0.0
    high, low = free, free - implicit_weight * force  # residual ≥ 0 at high, ≤ 0 at low
    alpha = high
    for _ in range(_NEWTON_ITERATIONS):
        force, stiffness = kernel(alpha, max(alpha_max, alpha), params)
        residual = alpha + implicit_weight * force - free
        if residual > 0.0:
            high = alpha
        else:
            low = alpha
        trial = alpha - residual / (1.0 + implicit_weight * stiffness)
        if not low <= trial <= high:
            trial = 0.5 * (low + high)
        if abs(trial - alpha) <= 1e-15 * abs(free):
            alpha = trial
            break
        alpha = trial
    force = kernel(alpha, max(alpha_max, alpha), params)[0]
    return alpha, force


def _refined_peak(time, force, index):
    """Peak of the parabola through the largest sample and its neighbours (force [N], time [s])."""
    if index == 0 or index == force.size - 1:
        return float(force[index]), float(time[index])
    left, middle, right = force[index - 1], force[index], force[index + 1]
    curvature = left - 2.0 * middle + right
    if curvature >= 0.0:
        return float(middle), float(time[index])
    shift = 0.5 * (left - right) / curvature
    step = time[1] - time[0]
    return float(middle - 0.25 * (left - right) * shift), float(time[index] + shift * step)
