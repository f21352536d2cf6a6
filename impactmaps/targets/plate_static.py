"""Classical static point compliance of a simply supported (SSSS) orthotropic plate.

The Navier double series of PHYSICS.md 3.3 with the inner sum in closed form
(:func:`navier_static_compliance`), used by
:meth:`impactmaps.targets.plate.Plate.static_compliance` (directly for SSSS plates, as
the singularity correction of the Ritz value for other edges). Conventions as in
:mod:`impactmaps.targets.plate`: the plate occupies ``0 ≤ x ≤ a``, ``0 ≤ y ≤ b``,
``s_m(x) = sin(mπx/a)``.
"""

from __future__ import annotations

import math

import numpy as np
import scipy.special

__all__ = ["navier_static_compliance", "sin_pi"]

#: Terms of the outer (single) series of :func:`navier_static_compliance`.
_NAVIER_STATIC_TERMS = 20000


def sin_pi(t):
    """sin(π t) with exact zeros at integer t and argument reduction (mod 2) first.

    Parameters
    ----------
    t : float or array_like
        Argument in half-turns [-] (e.g. ``m x/a`` for the mode ``sin(mπx/a)``).

    Returns
    -------
    ndarray
        sin(π t) [-], exactly 0 where t is an integer.
    """
    t = np.asarray(t, dtype=float)
    reduced = np.remainder(t, 2.0)
    result = np.sin(np.pi * reduced)
    return np.where(reduced == np.round(reduced), 0.0, result)


def _sum_sin_squared_over(c, theta):
    """Σ_{n≥1} sin²(nθ)/(n² + c²) for complex c (Re c > 0) and 0 ≤ θ ≤ π.

    From Σ cos(nx)/(n² + c²) = π cosh(c(π − x))/(2c sinh(cπ)) − 1/(2c²), 0 ≤ x ≤ 2π:
    ``(π/(4c)) (1 − u)(1 − v)/(1 − uv)``, ``u = e^{−2cθ}``, ``v = e^{−2c(π−θ)}``
    (overflow-free and without cancellation).
    """
    one_minus_u = -np.expm1(-2.0 * c * theta)
    one_minus_v = -np.expm1(-2.0 * c * (np.pi - theta))
    one_minus_uv = -np.expm1(-2.0 * c * np.pi)
    return np.pi / (4.0 * c) * one_minus_u * one_minus_v / one_minus_uv


def _derivative_sum_sin_squared_over(c, theta):
    """d/d(c²) of :func:`_sum_sin_squared_over` = −Σ sin²(nθ)/(n² + c²)²."""
    u = np.exp(-2.0 * c * theta)
    v = np.exp(-2.0 * c * (np.pi - theta))
    one_minus_u = -np.expm1(-2.0 * c * theta)
    one_minus_v = -np.expm1(-2.0 * c * (np.pi - theta))
    one_minus_uv = -np.expm1(-2.0 * c * np.pi)
    ratio = one_minus_u * one_minus_v / one_minus_uv
    d_ratio = (
        (2.0 * theta * u * one_minus_v + 2.0 * (np.pi - theta) * v * one_minus_u) / one_minus_uv
        - ratio * 2.0 * np.pi * u * v / one_minus_uv
    )
    d_sum_dc = -np.pi / (4.0 * c**2) * ratio + np.pi / (4.0 * c) * d_ratio
    return d_sum_dc / (2.0 * c)


def _inner_series(p, length_y, y0, D11, D22, H):
    """Σ_{n≥1} s_n(y0)² / (D11 p⁴ + 2H p² q_n² + D22 q_n⁴), q_n = nπ/b, in closed form.

    The denominator factorises as ``D22 (q² + ρ1)(q² + ρ2)`` with
    ``ρ1,2 = p² (H ± sqrt(H² − D11 D22))/D22`` (complex conjugates when H² < D11 D22);
    partial fractions reduce the sum to :func:`_sum_sin_squared_over`. Near the isotropic
    double root (``|H² − D11 D22| < 1e-10 D11 D22``) the divided difference is replaced
    by the derivative at the mean root; the two branches balance truncation against
    cancellation and are accurate to ≲ 5e-11 relative at the switch.
    """
    p = np.asarray(p, dtype=float)
    theta = math.pi * y0 / length_y
    scale = (length_y / math.pi) ** 2  # q_n² + ρ = (π/b)² (n² + ρ b²/π²)
    root = np.sqrt(complex(H * H - D11 * D22))
    separation = abs(root) / math.sqrt(D11 * D22)
    p2 = p**2
    if separation < 1e-5:
        rho_mean = p2 * H / D22
        c = np.sqrt(rho_mean * scale + 0j)
        # Σ s²/((q²+ρ)²) = −dG/dρ with G(ρ) = scale Σ s²/(n² + ρ scale)
        value = -scale**2 * _derivative_sum_sin_squared_over(c, theta)
        return np.real(value) / D22
    rho1 = p2 * (H + root) / D22
    rho2 = p2 * (H - root) / D22
    c1 = np.sqrt(rho1 * scale)
    c2 = np.sqrt(rho2 * scale)
    g1 = scale * _sum_sin_squared_over(c1, theta)
    g2 = scale * _sum_sin_squared_over(c2, theta)
    return np.real((g1 - g2) / (rho2 - rho1)) / D22


def navier_static_compliance(length_x, length_y, D11, D22, D12, D66, impact_point,
                             terms: int = _NAVIER_STATIC_TERMS) -> float:
    """Classical point compliance 1/K_st [m/N] of a simply supported orthotropic plate.

    Sums the Navier double series of PHYSICS.md 3.3,
    ``Σ_m Σ_n (4/(ab)) s_m(x0)² s_n(y0)² / (π⁴[D11 (m/a)⁴ + 2(D12+2D66)(m/a)²(n/b)² + D22 (n/b)⁴])``,
    with the inner series over n in closed form (hyperbolic functions, in the manner of
    Timoshenko & Woinowsky-Krieger, *Theory of Plates and Shells*, §30, extended to
    orthotropy by partial fractions) and the outer series over m summed to ``terms``
    terms plus an asymptotic tail ``½ κ Σ_{m>M} m⁻³`` (the inner sum behaves as
    ``κ/m³``). Relative accuracy ≈ 1e-11 for the default ``terms`` at interior points
    (≈ 1e-10 close to a corner; ≲ 5e-11 within
    ``|H² − D11 D22| ≈ 1e-10 D11 D22`` of isotropy).

    Parameters
    ----------
    length_x, length_y : float
        Plate sides a, b [m].
    D11, D22, D12, D66 : float
        Bending stiffnesses [N·m].
    impact_point : tuple of float
        Load and observation point (x0, y0) [m], inside the plate.
    terms : int, optional
        Terms of the outer series.

    Returns
    -------
    float
        Static compliance [m/N]. Isotropic square plate, centre: ``0.0116008 a²/D``.
    """
    a, b = float(length_x), float(length_y)
    x0, y0 = (float(v) for v in impact_point)
    H = D12 + 2.0 * D66
    m = np.arange(1, int(terms) + 1, dtype=float)
    p = m * np.pi / a
    inner = _inner_series(p, b, y0, D11, D22, H)
    weights = sin_pi(m * x0 / a) ** 2
    total = math.fsum(weights * inner)
    # tail: inner ≈ κ/m³ and s_m² averages to ½
    kappa = inner[-1] * m[-1] ** 3
    tail = 0.5 * kappa * float(scipy.special.zeta(3.0, m[-1] + 1.0))
    return 4.0 / (a * b) * (total + tail)

