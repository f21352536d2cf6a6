"""Exact one-step maps of a damped oscillator under a force linear in time.

For ``q̈ + 2ζωq̇ + ω²q = f(t)``, f linear from ``f0`` to ``f1`` over a step h, the end state
is a linear combination of ``q0, v0, f0, f1`` with eight coefficients of ω, ζ and h:
closed forms (Taylor series below ωh = 1) for undamped modes, the exponential of the
augmented 4×4 system for damped ones.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from .history_rows import zeros_matrix

__all__ = [
    "fill_step_coefficients",
    "oscillator_step_coefficients",
    "predict_step",
    "propagate_free",
    "square_free_propagators",
]

_SERIES_LIMIT = 1.0
#: 4 as an int64, not a literal: :func:`~impactmaps.solvers.integrator.history_rows.zeros_matrix` then compiles once.
_FOUR = np.int64(4)


# Taylor coefficients in x² of sin x/x, (1 − cos x)/x² and (x − sin x)/x³ (ten terms:
# the first omitted one is below 3e-20 for x < 1), for Horner evaluation. Below
# _SERIES_LIMIT they replace sin and cos (no cancellation there, and three times faster).
_SINC = (1.0, -0.16666666666666666, 0.008333333333333333, -0.0001984126984126984, 2.7557319223985893e-06, -2.505210838544172e-08, 1.6059043836821613e-10, -7.647163731819816e-13, 2.8114572543455206e-15, -8.22063524662433e-18)
_COSC = (0.5, -0.041666666666666664, 0.001388888888888889, -2.48015873015873e-05, 2.755731922398589e-07, -2.08767569878681e-09, 1.1470745597729725e-11, -4.779477332387385e-14, 1.5619206968586225e-16, -4.110317623312165e-19)
_SIN3 = (0.16666666666666666, -0.008333333333333333, 0.0001984126984126984, -2.7557319223985893e-06, 2.505210838544172e-08, -1.6059043836821613e-10, 7.647163731819816e-13, -2.8114572543455206e-15, 8.22063524662433e-18, -1.9572941063391263e-20)


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _horner10(c, x2):
    total = c[9]
    for k in range(8, -1, -1):
        total = c[k] + x2 * total
    return total


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _trig_functions(x):
    """S = sin x/x, C1 = (1−cos x)/x², S3 = (x−sin x)/x³, stable for small x."""
    if x < _SERIES_LIMIT:
        x2 = x * x
        return _horner10(_SINC, x2), _horner10(_COSC, x2), _horner10(_SIN3, x2)
    sx = math.sin(x)
    inverse = 1.0 / x
    inverse2 = inverse * inverse
    return sx * inverse, (1.0 - math.cos(x)) * inverse2, (x - sx) * inverse2 * inverse


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _expm4(a):
    """Matrix exponential of a 4×4 matrix by scaling and squaring with Taylor terms."""
    norm = 0.0
    for i in range(4):
        row = 0.0
        for j in range(4):
            row += abs(a[i, j])
        norm = max(norm, row)
    squarings = 0
    if norm > 0.25:
        squarings = int(math.ceil(math.log2(norm / 0.25)))
    scale = 2.0 ** (-squarings)
    scaled = np.empty((4, 4))  # element loops: an array expression compiles a ufunc kernel
    for i in range(4):
        for j in range(4):
            scaled[i, j] = a[i, j] * scale
    result = zeros_matrix(_FOUR, _FOUR)
    term = zeros_matrix(_FOUR, _FOUR)
    for i in range(4):
        result[i, i] = 1.0
        term[i, i] = 1.0
    for k in range(1, 14):
        term = _product4(term, scaled)
        for i in range(4):
            for j in range(4):
                term[i, j] /= k
                result[i, j] += term[i, j]
    for _ in range(squarings):
        result = _product4(result, result)
    return result


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _product4(a, b):
    """The 4×4 matrix product a b (loops: numba's ``@`` compiles a BLAS binding for seconds)."""
    out = zeros_matrix(_FOUR, _FOUR)
    for i in range(4):
        for k in range(4):
            aik = a[i, k]
            for j in range(4):
                out[i, j] += aik * b[k, j]
    return out


@numba.njit(cache=True, inline="always")
def _undamped_coefficients(omega, h, s, c1, s3):
    """The eight step coefficients of an undamped mode from S, C1, S3 of ``_trig_functions``."""
    cosx = 1.0 - (omega * h) ** 2 * c1
    return (cosx, h * s, -omega * omega * h * s, cosx,
            h * h * (c1 - s3), h * h * s3, h * (s - c1), h * c1)


@numba.njit(cache=True, no_cfunc_wrapper=True)
def oscillator_step_coefficients(omega, zeta, h, out):
    """Exact one-step coefficients of ``q̈ + 2ζωq̇ + ω²q = f(t)``, f linear on [0, h].

    ``q(h) = out[0] q0 + out[1] v0 + out[4] f0 + out[5] f1`` and
    ``v(h) = out[2] q0 + out[3] v0 + out[6] f0 + out[7] f1``.
    Works for ω = 0 (free mass) and 0 ≤ ζ < 1.
    """
    if zeta == 0.0:
        s, c1, s3 = _trig_functions(omega * h)
        coefficients = _undamped_coefficients(omega, h, s, c1, s3)
        for k in range(8):
            out[k] = coefficients[k]
        return
    # damped: exponential of the augmented system [q, v, f, ḟ]
    m = zeros_matrix(_FOUR, _FOUR)
    m[0, 1] = h
    m[1, 0] = -omega * omega * h
    m[1, 1] = -2.0 * zeta * omega * h
    m[1, 2] = h
    m[2, 3] = 1.0  # the last state holds d = f1 − f0, so ḟ = d/h and (ḟ)·h = d
    e = _expm4(m)
    out[0] = e[0, 0]
    out[1] = e[0, 1]
    out[2] = e[1, 0]
    out[3] = e[1, 1]
    out[4] = e[0, 2] - e[0, 3]
    out[5] = e[0, 3]
    out[6] = e[1, 2] - e[1, 3]
    out[7] = e[1, 3]


@numba.njit(cache=True, no_cfunc_wrapper=True)
def fill_step_coefficients(omega, zeta, phi, h, coef):
    """Per-mode step coefficients into ``coef[k, j]`` (k = 0…7 as in
    :func:`oscillator_step_coefficients`), force rows pre-multiplied by φ_j (undamped modes
    below ``_SERIES_LIMIT`` in one vectorised loop).
    """
    n = omega.shape[0]
    for j in range(n):
        x2 = (omega[j] * h) ** 2
        c = _undamped_coefficients(omega[j], h, _horner10(_SINC, x2), _horner10(_COSC, x2),
                                   _horner10(_SIN3, x2))
        coef[0, j] = c[0]
        coef[1, j] = c[1]
        coef[2, j] = c[2]
        coef[3, j] = c[3]
        coef[4, j] = c[4] * phi[j]
        coef[5, j] = c[5] * phi[j]
        coef[6, j] = c[6] * phi[j]
        coef[7, j] = c[7] * phi[j]
    tmp = np.empty(8)
    for j in range(n):
        if zeta[j] != 0.0 or not omega[j] * h < _SERIES_LIMIT:
            oscillator_step_coefficients(omega[j], zeta[j], h, tmp)
            for k in range(4):
                coef[k, j] = tmp[k]
            for k in range(4, 8):
                coef[k, j] = tmp[k] * phi[j]


@numba.njit(cache=True, no_cfunc_wrapper=True)
def square_free_propagators(free_coef, free_ready, k):
    """Free-vibration propagators over 2^k h from those over 2^(k−1) h, by squaring (exact,
    damped modes too); ``free_coef`` is (powers, 4, n).
    """
    for p in range(1, k + 1):
        if free_ready[p]:
            continue
        for j in range(free_coef.shape[2]):
            a = free_coef[p - 1, 0, j]
            b = free_coef[p - 1, 1, j]
            c = free_coef[p - 1, 2, j]
            d = free_coef[p - 1, 3, j]
            free_coef[p, 0, j] = a * a + b * c
            free_coef[p, 1, j] = a * b + b * d
            free_coef[p, 2, j] = c * a + d * c
            free_coef[p, 3, j] = c * b + d * d
        free_ready[p] = True


@numba.njit(cache=True, fastmath={"reassoc", "contract"}, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def predict_step(coef, h, mass, wi, vi, q, v, phi, f0, f1, qn, vn):
    """Advance impactor and modes over h with force f0 → f1; return (wi, vi, w_target).
    ``coef`` is (8, n), one row per coefficient (contiguous, SIMD).
    """
    wt = 0.0
    for j in range(q.shape[0]):
        qj = coef[0, j] * q[j] + coef[1, j] * v[j] + coef[4, j] * f0 + coef[5, j] * f1
        vn[j] = coef[2, j] * q[j] + coef[3, j] * v[j] + coef[6, j] * f0 + coef[7, j] * f1
        qn[j] = qj
        wt += phi[j] * qj
    wi_new = wi + vi * h - h * h * (f0 / 3.0 + f1 / 6.0) / mass
    vi_new = vi - 0.5 * h * (f0 + f1) / mass
    return wi_new, vi_new, wt


@numba.njit(cache=True, fastmath={"reassoc", "contract"}, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def propagate_free(rows, h, wi, vi, q, v, phi, qn, vn):
    """Free flight over h (no contact force) with modal rows ``rows`` (4, n); returns the
    impactor displacement and the target displacement Σ φ_j q_j at the end [m].
    """
    wt = 0.0
    for j in range(q.shape[0]):
        qj = rows[0, j] * q[j] + rows[1, j] * v[j]
        vn[j] = rows[2, j] * q[j] + rows[3, j] * v[j]
        qn[j] = qj
        wt += phi[j] * qj
    return wi + vi * h, wt
