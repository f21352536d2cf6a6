"""Closed forms of the coupled oscillators of a linear contact phase (numba).

F = Σ c_k η_k and its rate at any instant, their roots (Illinois method), exact
propagation, the force amplitudes and the content step they set, and exact recorded
rows inside a step; the stepping loops are in :mod:`.coupled_stepping`.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from .history_rows import record_row

__all__ = ["SAMPLED_PHASE"]

#: Largest Ω_k h of the coupled mode that carries the most force (25 samples per period) [rad].
SAMPLED_PHASE = 0.25
#: Iterations of the Illinois root searches (each halves the bracket at least every
#: third iteration; 200 reach round-off from any bracket).
_ROOT_ITERATIONS = 200


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _force(frequencies, force_row, eta, rate, s):
    """F(s) [N] a time s [s] after the state (η, η̇)."""
    total = 0.0
    for k in range(eta.shape[0]):
        x = frequencies[k] * s
        total += force_row[k] * (eta[k] * math.cos(x) + rate[k] / frequencies[k] * math.sin(x))
    return total


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _force_rate(frequencies, force_row, eta, rate, s, count):
    """dF/dt(s) [N/s] a time s [s] after the state (η, η̇), of the first ``count`` (sampled)
    coupled modes.
    """
    total = 0.0
    for k in range(count):
        x = frequencies[k] * s
        total += force_row[k] * (rate[k] * math.cos(x) - eta[k] * frequencies[k] * math.sin(x))
    return total


@numba.njit(cache=True, no_cfunc_wrapper=True)
def _root(frequencies, force_row, eta, rate, start, length, derivative, count):
    """Root in (start, length) of F (or, if ``derivative``, of the rate of its first
    ``count`` coupled modes) from the state (η, η̇), given a sign change over the interval
    (Illinois method) [s]."""
    a = start
    b = length
    if derivative:
        fa = _force_rate(frequencies, force_row, eta, rate, a, count)
        fb = _force_rate(frequencies, force_row, eta, rate, b, count)
    else:
        fa = _force(frequencies, force_row, eta, rate, a)
        fb = _force(frequencies, force_row, eta, rate, b)
    side = 0
    for _ in range(_ROOT_ITERATIONS):
        if fa == fb:
            break
        c = (a * fb - b * fa) / (fb - fa)
        if not (a < c < b):
            c = 0.5 * (a + b)
        fc = _force_rate(frequencies, force_row, eta, rate, c, count) if derivative else \
            _force(frequencies, force_row, eta, rate, c)
        if (fc > 0.0) == (fa > 0.0):
            a, fa = c, fc
            if side == -1:
                fb *= 0.5
            side = -1
        else:
            b, fb = c, fc
            if side == 1:
                fa *= 0.5
            side = 1
        if b - a <= 1e-14 * length or fc == 0.0:
            break
    # F: the end of the bracket where F ≤ 0 (the state after a separation has no force);
    # F': its middle
    return 0.5 * (a + b) if derivative else b


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _first_positive(frequencies, force_row, eta, rate, length):
    """An instant in (0, length] [s] where F > 0, by halving from ``length``; 0 if none is found
    down to length/2⁶⁰.
    """
    s = length
    for _ in range(60):
        if _force(frequencies, force_row, eta, rate, s) > 0.0:
            return s
        s *= 0.5
    return 0.0


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _clear_gap(from_coupled, frequencies, eta, rate, phi, s, length, eta_s, rate_s, q, v):
    """The separation instant ``s`` [s], moved later by the least round-off that makes the
    physical gap strictly open (else the flight would find the same instant again); returns
    it with w_i [m] and v_i [m/s] there (modes in q, v; coupled state in η_s, η̇_s).
    """
    shift = 1e-14 * length
    wi = 0.0
    vi = 0.0
    for _ in range(60):
        _advance(frequencies, eta, rate, s, eta_s, rate_s)
        wi, vi = _to_physical(from_coupled, eta_s, rate_s, q, v)
        gap = wi
        for j in range(q.shape[0]):
            gap -= phi[j] * q[j]
        if gap < 0.0:
            break
        s += shift
        shift *= 2.0
    return s, wi, vi


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _advance(frequencies, eta, rate, s, eta_out, rate_out):
    """Exact propagation of every coupled oscillator over s [s]."""
    for k in range(eta.shape[0]):
        x = frequencies[k] * s
        cx = math.cos(x)
        sx = math.sin(x)
        eta_out[k] = eta[k] * cx + rate[k] / frequencies[k] * sx
        rate_out[k] = rate[k] * cx - eta[k] * frequencies[k] * sx


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _amplitudes(frequencies, force_row, eta, rate):
    """A_k [N]: the amplitude of each coupled mode's share of F for the state (η, η̇);
    constant through a contact (every coupled mode is an undamped oscillator)."""
    amplitude = np.empty(eta.shape[0])
    for k in range(eta.shape[0]):
        amplitude[k] = abs(force_row[k]) * math.sqrt(eta[k] ** 2 + (rate[k] / frequencies[k]) ** 2)
    return amplitude


@numba.njit(cache=True, no_cfunc_wrapper=True)
def _content_step(frequencies, force_row, eta, rate, resolution):
    """The contact step [s] for the state (η, η̇): :data:`SAMPLED_PHASE`/Ω of the largest
    amplitude's mode, at most 1/Ω of the fastest sampled mode; 0 when no force is carried.
    """
    amplitude = _amplitudes(frequencies, force_row, eta, rate)
    total = 0.0
    for k in range(eta.shape[0]):
        total += amplitude[k]
    if total == 0.0:
        return 0.0
    dominant = np.argmax(amplitude)
    tail = 0.0
    fastest = 0
    for k in range(eta.shape[0] - 1, -1, -1):
        tail += amplitude[k]
        if 2.0 * tail > resolution * total:
            fastest = k
            break
    return min(SAMPLED_PHASE / frequencies[dominant], 1.0 / frequencies[fastest])


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _to_physical(from_coupled, eta, rate, q, v):
    """(w_i, v_i) and the modal state (q, v) of the coupled state (η, η̇)."""
    n = eta.shape[0]
    wi = 0.0
    vi = 0.0
    for k in range(n):
        wi += from_coupled[0, k] * eta[k]
        vi += from_coupled[0, k] * rate[k]
    for j in range(1, n):
        qj = 0.0
        vj = 0.0
        for k in range(n):
            qj += from_coupled[j, k] * eta[k]
            vj += from_coupled[j, k] * rate[k]
        q[j - 1] = qj
        v[j - 1] = vj
    return wi, vi


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _record_inside(modes, rows, start, t, length, q, v, history, rec):
    """Record exact rows at most ``rows[0]`` [s] apart inside a step of ``length`` [s] from t [s]
    and ``start`` = (η, η̇); ``modes`` = (Ω, c, from_coupled), ``rows`` = (spacing [s], ω, φ,
    residual [m/N]). Returns the history and the next row.
    """
    frequencies, force_row, from_coupled = modes
    spacing, omega, phi, residual = rows
    eta, rate = start
    count = int(math.ceil(length / spacing))
    if count <= 1:
        return history, rec
    n = eta.shape[0]
    eta_s = np.empty(n)
    rate_s = np.empty(n)
    for i in range(1, count):
        s = length * i / count
        _advance(frequencies, eta, rate, s, eta_s, rate_s)
        force = 0.0
        for k in range(n):
            force += force_row[k] * eta_s[k]
        wi, vi = _to_physical(from_coupled, eta_s, rate_s, q, v)
        history, rec = record_row(history, rec, t + s, max(force, 0.0), wi, vi, residual, omega, phi, q, v)
    return history, rec


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _partial_force(force_row, eta, count):
    """Σ_{k<count} c_k η_k [N]: the force of the ``count`` slowest coupled modes."""
    total = 0.0
    for k in range(count):
        total += force_row[k] * eta[k]
    return total


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _step(frequencies, eta, rate, cos_s, sin_s, eta_out, rate_out):
    """Exact propagation over the step whose cos Ω_k s, sin Ω_k s are given (the
    arithmetic of every stepping loop here, so that two loops reach one sample alike)."""
    for k in range(eta.shape[0]):
        eta_out[k] = eta[k] * cos_s[k] + rate[k] / frequencies[k] * sin_s[k]
        rate_out[k] = rate[k] * cos_s[k] - eta[k] * frequencies[k] * sin_s[k]

