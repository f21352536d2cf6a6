"""The free-flight stage of the exact-step modal integrator (numba).

With no contact force the step doubles up to 2^(:data:`FREE_POWERS` − 1) h while no
touchdown can fit (:func:`free_doublings`), and the run ends once re-impact is impossible
(:func:`no_reimpact_possible`); a recorded run records exact rows inside long steps.
"""

from __future__ import annotations

import math

import numba

from .history_rows import record_row
from .oscillator_step import propagate_free

__all__ = ["FREE_POWERS", "damping_work", "free_damping_work", "free_doublings", "no_reimpact_possible", "out_of_time",
           "record_free_inside"]

#: Longest free-flight step: 2^(FREE_POWERS − 1) = 1024 steps h. (Up to 2026-11-24 64 h:
#: a light impactor's long flights between re-impacts took ~30 % of a plate run's steps.)
FREE_POWERS = 11
#: A recorded run's rows in free flight are at most 2^_RECORD_POWER = 64 steps h apart.
_RECORD_POWER = 6


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def no_reimpact_possible(omega, phi, q, v, wi, vi):
    """True once the impactor moves away and its gap exceeds the largest displacement the free
    vibration can reach at x0, Σ|φ_j| sqrt(q_j² + (v_j/ω_j)²) (docs/physics_contract.md §3.6).
    """
    rigid_w = 0.0
    rigid_v = 0.0
    for j in range(q.shape[0]):  # no chain of additions but for the (few) rigid-body modes
        if omega[j] == 0.0:
            rigid_w += phi[j] * q[j]
            rigid_v += phi[j] * v[j]
    return vi - rigid_v <= 0.0 and wi - rigid_w < -_amplitude_sum(omega, phi, q, v)


@numba.njit(cache=True, fastmath={"reassoc"}, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _amplitude_sum(omega, phi, q, v):
    """Σ |φ_j| sqrt(q_j² + (v_j/ω_j)²) [m] over the elastic modes, in any order (SIMD: a bound
    checked every 8 free steps, whose chain of additions in order cost more than the steps)."""
    bound = 0.0
    for j in range(q.shape[0]):
        if omega[j] != 0.0:
            bound += abs(phi[j]) * math.sqrt(q[j] * q[j] + (v[j] / omega[j]) ** 2)
    return bound


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _damping_power(omega, zeta, v):
    power = 0.0
    for j in range(v.shape[0]):
        power += 2.0 * zeta[j] * omega[j] * v[j] * v[j]
    return power


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def damping_work(omega, zeta, v, vn, length):
    """Work of the modal damping over a step of ``length`` [s] (trapezoidal rule) [J]."""
    return 0.5 * length * (_damping_power(omega, zeta, v) + _damping_power(omega, zeta, vn))


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def free_damping_work(omega, q, v, qn, vn):
    """Work of the modal damping over a free-flight step from (q, v) to (qn, vn) [J], exactly:
    the modal energy lost.
    """
    lost = 0.0
    for j in range(q.shape[0]):
        lost += 0.5 * ((v[j] * v[j] - vn[j] * vn[j]) + omega[j] * omega[j] * (q[j] * q[j] - qn[j] * qn[j]))
    return lost


@numba.njit(cache=True, inline="always")
def out_of_time(t, steps, max_time, max_steps):
    """Whether the run has reached its time limit or its step budget."""
    return t >= max_time or steps >= max_steps


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _closing_speed_bound(omega, phi, q, v, vi):
    """Bound on the speed at which the gap can close in free flight [m/s]:
    ``|v_i| + Σ|φ_j| sqrt(ω_j² q_j² + v_j²)`` (modal amplitudes are constant or decay)."""
    speed_bound = abs(vi)
    for j in range(q.shape[0]):
        speed_bound += abs(phi[j]) * math.sqrt((omega[j] * q[j]) ** 2 + v[j] * v[j])
    return speed_bound


@numba.njit(cache=True, fastmath={"reassoc"}, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _displacement(phi, q):
    """Σ φ_j q_j [m], the target at the impact point, summed in any order (SIMD)."""
    total = 0.0
    for j in range(q.shape[0]):
        total += phi[j] * q[j]
    return total


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def free_doublings(omega, phi, q, v, wi, vi, h, speed_bound):
    """How many times k < :data:`FREE_POWERS` the free-flight step h [s] may double from the
    state (w_i, v_i, q, v) with no touchdown inside (2^k h V < −α), and the closing-speed
    bound V [m/s] (``speed_bound`` < 0: computed here). Returns (k, speed_bound).
    """
    if speed_bound < 0.0:
        speed_bound = _closing_speed_bound(omega, phi, q, v, vi)
    gap = _displacement(phi, q) - wi  # −α
    k = 0
    while k + 1 < FREE_POWERS and (2.0 ** (k + 1)) * h * speed_bound < gap:
        k += 1
    return k, speed_bound


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def record_free_inside(free_coef, k, h, start, modes, scratch, history, rec):
    """Record exact rows every 2^_RECORD_POWER h inside a free-flight step of 2^k h [s] from
    ``start`` = (t [s], w_i, v_i, q, v); ``scratch`` (4, n). Returns the history and the next row.
    """
    if k <= _RECORD_POWER:
        return history, rec
    t, wi, vi, q, v = start
    omega, phi = modes.frequencies, modes.participation
    spacing = 2.0**_RECORD_POWER * h
    q_a, v_a, q_b, v_b = scratch[0], scratch[1], scratch[2], scratch[3]
    for j in range(q.shape[0]):
        q_a[j] = q[j]
        v_a[j] = v[j]
    for i in range(1, 2 ** (k - _RECORD_POWER)):
        propagate_free(free_coef[_RECORD_POWER], spacing, wi, vi, q_a, v_a, phi, q_b, v_b)
        q_a, q_b = q_b, q_a
        v_a, v_b = v_b, v_a
        history, rec = record_row(history, rec, t + i * spacing, 0.0, wi + vi * (i * spacing), vi,
                                  modes.residual, omega, phi, q_a, v_a)
    return history, rec
