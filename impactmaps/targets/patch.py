"""Modal transforms of a contact pressure spread over a disc (the contact patch).

A sphere presses on a target over a disc of radius a, not at a point. For a mode whose
shape near the impact point is a sum of plane waves of one wavenumber k (a Navier plate
mode ``sin(px) sin(qy)``, ``k² = p² + q²``, is four of them), the pressure-weighted
average of the mode shape over the disc is the value at the centre times the *modal
transform* ``T(k a)`` of the pressure distribution (its Hankel transform of order 0 over
the total force). That factor multiplies the mode's participation (the generalised force
of the mode and the deflection the contact sees, work-conjugate to the force):

* Hertz pressure ``p(r) ∝ sqrt(1 − r²/a²)``: ``T(x) = 3 (sin x − x cos x)/x³ = 3 j1(x)/x``;
* uniform pressure over the disc: ``T(x) = 2 J1(x)/x``.

Both are 1 at x = 0 and are evaluated from their Taylor series near it (no cancellation).
The averaging is exact when the disc lies inside the plate.
"""

from __future__ import annotations

import numpy as np
import scipy.special

from .._checks import require_choice

__all__ = ["PRESSURES", "hertz_transform", "mean_square_transform", "patch_transform",
           "uniform_transform"]

#: Pressure distributions over the contact disc with a modal transform.
PRESSURES = ("hertz", "uniform")

#: Below this |x| the transforms use their Taylor series (error < 1e-17).
_SERIES_LIMIT = 0.5

# 3 j1(x)/x = Σ_k 3 (−1)^k x^{2k} / (2^k k! (2k + 3)!!)
_HERTZ_SERIES = (1.0, -1.0 / 10.0, 1.0 / 280.0, -1.0 / 15120.0, 1.0 / 1330560.0,
                 -1.0 / 172972800.0, 1.0 / 31135104000.0)
# 2 J1(x)/x = Σ_k (−1)^k (x/2)^{2k} / (k! (k + 1)!)
_UNIFORM_SERIES = (1.0, -1.0 / 8.0, 1.0 / 192.0, -1.0 / 9216.0, 1.0 / 737280.0,
                   -1.0 / 88473600.0, 1.0 / 14863564800.0)


def _even_function(x, closed_form, coefficients):
    """``closed_form(|x|)``, or the series ``Σ c_k x^{2k}`` (Horner) where |x| is small."""
    x = np.abs(np.asarray(x, dtype=float))
    small = x < _SERIES_LIMIT
    closed = closed_form(np.where(small, 1.0, x))
    series = np.zeros_like(x)
    for c in reversed(coefficients):
        series = series * (x * x) + c
    return np.where(small, series, closed)


def hertz_transform(x):
    """Modal transform of the Hertz pressure over a disc, ``3 (sin x − x cos x)/x³`` [-].

    Parameters
    ----------
    x : float or array_like
        k a [-]: the mode's wavenumber [1/m] times the contact radius [m].

    Returns
    -------
    ndarray
        T(x) [-]; 1 at x = 0, ``1 − x²/10 + O(x⁴)``, ``≈ −3 cos x/x²`` for large x.
    """
    return _even_function(x, lambda y: 3.0 * (np.sin(y) - y * np.cos(y)) / y**3, _HERTZ_SERIES)


def uniform_transform(x):
    """Modal transform of a uniform pressure over a disc, ``2 J1(x)/x`` [-].

    Parameters
    ----------
    x : float or array_like
        k a [-]: the mode's wavenumber [1/m] times the disc radius [m].

    Returns
    -------
    ndarray
        T(x) [-]; 1 at x = 0, ``1 − x²/8 + O(x⁴)``.
    """
    return _even_function(x, lambda y: 2.0 * scipy.special.j1(y) / y, _UNIFORM_SERIES)


def patch_transform(x, pressure: str = "hertz"):
    """Modal transform ``T(k a)`` [-] of the named pressure distribution over a disc.

    Parameters
    ----------
    x : float or array_like
        k a [-].
    pressure : {"hertz", "uniform"}
        The distribution (:func:`hertz_transform`, :func:`uniform_transform`).
    """
    require_choice("pressure", pressure, PRESSURES)
    return hertz_transform(x) if pressure == "hertz" else uniform_transform(x)


def mean_square_transform(x, pressure: str = "hertz"):
    """Average of ``T(x)²`` over its oscillation at large x, ``⟨T²⟩`` [-].

    Hertz: ``9/(2x⁴)`` (from ``T ≈ −3 cos x/x²``); uniform: ``4/(π x³)`` (from
    ``J1(x) ≈ sqrt(2/(πx)) cos(x − 3π/4)``). For tails of series in k where ``T²``
    oscillates faster than the rest of the summand varies; valid for x ≳ 100.

    Parameters
    ----------
    x : float or array_like
        k a [-], large.
    pressure : {"hertz", "uniform"}
    """
    require_choice("pressure", pressure, PRESSURES)
    x = np.asarray(x, dtype=float)
    return 4.5 / x**4 if pressure == "hertz" else 4.0 / (np.pi * x**3)
