r"""Sphere on an infinite Euler beam by convolution quadrature: separation and re-impact.

The receptance form of the normalised problem (see :mod:`impactmaps.solvers.infinite_beam`)

    ᾱ(τ) = τ − ∫0^τ G(τ − s) F̄(s) ds,    G(τ) = τ + 4ζ sqrt τ

(Laplace ``s^{-2} + 2c s^{-3/2}``, ``c = sqrt(π) ζ``) is discretised by Lubich's
convolution quadrature with the BDF2 generating function (Lubich, Numer. Math. 52, 1988),
second order in the step. With ``F̄ = ᾱ`` it is the linear problem; with
``F̄ = max(ᾱ, 0)`` it follows separation and re-impact (:func:`infinite_beam_impact`).
The march is O(N²) in the number of steps.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numba
import numpy as np

from .._checks import require_positive

__all__ = ["DEFAULT_TIME_STEP", "MAX_CQ_STEPS", "InfiniteBeamImpact", "bdf2_weights", "cq_grid", "cq_march",
           "infinite_beam_impact"]

DEFAULT_TIME_STEP = 0.01  # normalised CQ step; max error ≈ 1.3e-4 on τ ≤ 10 (tests)
MAX_CQ_STEPS = 100_000  # O(N²) convolution; beyond this the step is coarsened (warning)


@numba.njit(cache=True)
def bdf2_weights(exponent, step, count):
    """BDF2 convolution-quadrature weights of K(s) = s^{-exponent} (Lubich 1988).

    Taylor coefficients of ``(δ(ξ)/h)^{-exponent}``, ``δ(ξ) = 3/2 − 2ξ + ξ²/2 = (3/2)g(ξ)``,
    ``g = 1 − 4ξ/3 + ξ²/3``; ``f = g^{-a}`` obeys ``g f' = −a g' f``, a three-term recurrence
    that is stable forwards (the wanted solution is the dominant one).
    """
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
def _march_kernel(weights, tau, prescribed, unilateral):
    """ᾱ_n = τ_n − Σ_{k≤n} W_{n−k} F̄_k with F̄_n = ᾱ_n, or max(ᾱ_n, 0) if unilateral,
    except on the first ``len(prescribed)`` nodes where F̄ is given."""
    count = tau.size
    force = np.zeros(count)
    indentation = np.zeros(count)
    known = prescribed.size
    for n in range(1, count):
        history = 0.0
        for k in range(n):
            history += weights[n - k] * force[k]
        free = tau[n] - history
        if n < known:
            force[n] = prescribed[n]
        else:
            force[n] = free / (1.0 + weights[0])
            if unilateral and force[n] < 0.0:
                force[n] = 0.0
        indentation[n] = free - weights[0] * force[n]
    return force, indentation


def cq_march(loss_factor: float, step: float, count: int, unilateral: bool, prescribed=None):
    """BDF2 CQ of the receptance form on ``count`` steps; returns (τ, F̄, ᾱ) at the nodes.

    ``W`` are the weights of ``s^{-2} + 2c s^{-3/2}``; ``prescribed`` (F̄ at the first nodes)
    replaces the solve there.
    """
    c = math.sqrt(math.pi) * loss_factor
    weights = bdf2_weights(2.0, step, count + 1) + 2.0 * c * bdf2_weights(1.5, step, count + 1)
    tau = step * np.arange(count + 1)
    given = np.zeros(0) if prescribed is None else np.asarray(prescribed, dtype=float)
    force, indentation = _march_kernel(weights, tau, given, unilateral)
    return tau, force, indentation


def cq_grid(duration: float, time_step: float):
    """(step, count) of a CQ grid covering ``duration`` with steps ≤ ``time_step``
    (normalised time), coarsened with a warning beyond :data:`MAX_CQ_STEPS` steps."""
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
        Contact force F̄ = F/(m_i V0 ω) = max(ᾱ, 0) [-].
    indentation : ndarray
        ᾱ = α ω/V0 [-] (negative while separated: the gap).
    impactor_velocity : ndarray
        Impactor velocity / V0 = 1 − ∫F̄ dτ (trapezoidal) [-].
    contacts : ndarray, shape (n, 2)
        Start and end τ of each contact (grid resolution; end = inf if still in contact).
    """

    tau: np.ndarray
    force: np.ndarray
    indentation: np.ndarray
    impactor_velocity: np.ndarray
    contacts: np.ndarray


def infinite_beam_impact(
    loss_factor, duration, *, time_step=DEFAULT_TIME_STEP, prescribed_force=None
):
    """Simulate impact on an infinite beam with separation and re-impact (BDF2 CQ).

    Parameters
    ----------
    loss_factor : float
        Beam loss factor ζ_b [-] (spec section 1), > 0.
    duration : float
        Normalised end time τ_end = ω t_end [-], > 0.
    time_step : float, optional
        Normalised step ω Δt [-]; global error O(step²) while in contact, lower order
        across the kinks of F̄ at separation/re-impact.
    prescribed_force : callable, optional
        ``(tau_array) -> force`` used on the grid nodes before the first node where it
        returns a negative value; used by :func:`infinite_beam_force` to start from the
        exact first contact.

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
