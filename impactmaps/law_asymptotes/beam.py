r"""Impact on an infinite Euler beam with any contact law (convolution quadrature).

The point mobility of an infinite Euler beam (docs/physics_contract.md §1, correction of seed 001
eq 35) is a convolution with the ``t^{-1/2}`` kernel,

    ẇ(t) = A ∫0^t F(s) / sqrt(π (t − s)) ds,   A = 1 / (2 sqrt(2) m'^{3/4} (EI)^{1/4}),

i.e. ``ẇ = A/sqrt(π) ∫ F/sqrt(t − s)`` = ``1/(2 sqrt(2π) m' c^{1/2}) ∫ F/sqrt(t − s)``,
``c = sqrt(EI/m')``. (The point *displacement* kernel is ``2A sqrt(t/π)``; its Laplace
transform is ``A s^{-3/2}``: the receptance ``F/(8 EI β³)·…`` of the beam on the
"foundation" ``m' s²`` gives ``w(0) = F s^{-3/2} (m'/(4EI))^{1/4}/(2m')``, the same A.)
With the impactor ``m ẍ = −F`` the indentation ``α = x − w`` is

    α(t) = V0 t − ∫0^t G(t − s) F(s) ds,   G(t) = t/m + 2A sqrt(t/π),

(Laplace ``Ĝ(s) = s^{-2}/m + A s^{-3/2}``). With ``F = Kα`` this is the fractional
oscillator of :mod:`impactmaps.solvers.infinite_beam` with ζ_b of docs/physics_contract.md §1
(the tests check the constant this way, against ``infinite_beam_peak``).

Scheme
------
Lubich's BDF2 convolution quadrature of ``Ĝ`` (the weights of
:mod:`impactmaps.solvers.infinite_beam`), ``α_n = V0 t_n − Σ_{k≤n} W_{n−k} F_k``: at each
step the implicit term ``W_0 F_n`` makes ``α_n + W_0 F(α_n; max(α_max, α_n)) = free_n`` a
scalar equation with a unique root (its left side increases in α, every law's force
being non-decreasing in α), solved by safeguarded Newton. Second order in the step
while the force is smooth; the kinks at separation, re-impact and yield lower the order
locally (the tests measure the convergence).

The run stops once the sphere has separated and moves away (``ẋ ≤ 0``): the beam point
then only moves further into the beam (``ẇ ≥ 0`` since ``F ≥ 0``), so there is no
re-impact. If the sphere still moves forward at separation it strikes again (linear
contact: for ``ζ_r < ζ_b < ζ_crit``, :mod:`impactmaps.solvers.infinite_beam`).
"""

from __future__ import annotations

import math

import numpy as np

from .._checks import require_positive
from ..contact.base import ContactLaw
from ..solvers.halfspace import single_law_parameters
from ..solvers.infinite_beam_cq import bdf2_weights
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
    """``A = 1/(2 sqrt(2) m'^{3/4} (EI)^{1/4})`` [m/(N s^{1/2})] of ``ẇ = A ∫F/sqrt(π(t−s))``.

    Parameters
    ----------
    mass_per_length : float
        m' [kg/m], > 0.
    bending_stiffness : float
        EI = bD11 [N m²], > 0.
    """
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
        Its ``mass_per_length`` m' [kg/m] and ``bending_stiffness`` EI [N m²] define the
        infinite Euler beam (span, supports and theory are ignored: exact for an Euler
        beam until reflections return, see :mod:`impactmaps.validity`).
    law : ContactLaw
        A single registered contact law.
    impactor_mass : float
        m > 0 [kg].
    velocity : float
        V0 > 0 [m/s].
    time_step : float, optional
        Step in units of 1/ω [-] (ω: :func:`~impactmaps.law_asymptotes.result.contact_frequency_of`).
    duration : float, optional
        Longest run in units of 1/ω [-]; reaching it sets ``time_limit_reached``.

    Returns
    -------
    AsymptoteResult
        ``method = "infinite-beam"``. Contact times are resolved to the step.
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
    beam_weights = mobility * bdf2_weights(1.5, step, count + 1)
    weights = bdf2_weights(2.0, step, count + 1) / mass + beam_weights
    force, alpha, last = _march(law.kernel, params, weights, step, speed, mass, count)
    time = step * np.arange(last + 1)
    force, alpha = force[: last + 1], alpha[: last + 1]
    impulse = np.concatenate(([0.0], np.cumsum(0.5 * step * (force[1:] + force[:-1]))))
    impactor_velocity = speed - impulse / mass
    deflection = np.convolve(beam_weights[: last + 1], force)[: last + 1]
    running_max = np.maximum.accumulate(alpha)
    clearance = alpha - np.asarray(law.permanent_indentation(running_max), dtype=float)
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
    """CQ steps until the sphere has separated and moves away, or ``count`` steps.

    Returns (force, indentation, index of the last step taken).
    """
    force = np.zeros(count + 1)
    alpha = np.zeros(count + 1)
    alpha_max = 0.0
    impulse = 0.0
    touched = False
    for n in range(1, count + 1):
        free = speed * step * n - float(np.dot(weights[n:0:-1], force[:n]))
        alpha[n], force[n] = _solve_step(kernel, params, weights[0], free, alpha_max)
        alpha_max = max(alpha_max, alpha[n])
        impulse += 0.5 * step * (force[n] + force[n - 1])
        touched = touched or force[n] > 0.0
        if touched and force[n] == 0.0 and speed - impulse / mass <= 0.0:
            return force, alpha, n
    return force, alpha, count


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
