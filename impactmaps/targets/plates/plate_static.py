"""Classical static point compliance of a simply supported (SSSS) orthotropic plate.

The Navier double series of docs/physics_contract.md §3.3 with the inner sum in closed form
(:func:`navier_static_compliance`), used by
:meth:`impactmaps.targets.plates.plate.Plate.static_compliance` (directly for SSSS plates, as
the singularity correction of the Ritz value for other edges). Conventions as in
:mod:`impactmaps.targets.plates.plate`: the plate occupies ``0 ≤ x ≤ a``, ``0 ≤ y ≤ b``,
``s_m(x) = sin(mπx/a)``.
"""

from __future__ import annotations

import math
import threading

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

    Sums the Navier double series of docs/physics_contract.md §3.3,
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
    length_x, length_y, D11, D22, D12, D66 : float
        Plate sides a, b [m] and bending stiffnesses [N·m], as in :class:`~impactmaps.targets.plates.plate.Plate`.
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



# ---------------------------------------------------------------------------------
# Static compliance of the Navier pairs under a contact patch
# ---------------------------------------------------------------------------------
#: The patch residual sums the lattice of half-wave pairs up to k a = this, then integrates.
_PATCH_LATTICE_KA = 8.0
#: At most this many half-waves per direction in the lattice part of the patch residual.
_PATCH_LATTICE_TERMS = 500
#: Beyond k a = this the patch residual uses the oscillation average of T².
_PATCH_AVERAGE_KA = 200.0
_GAUSS_NODES, _GAUSS_WEIGHTS = np.polynomial.legendre.leggauss(8)
_ANGLE_NODES, _ANGLE_WEIGHTS = np.polynomial.legendre.leggauss(24)


def pair_static_compliance(p, q, D11, D22, D12, D66, shear_xz=math.inf, shear_yz=math.inf):
    """Static compliance ``1/(g·(S⁻¹ + B⁻¹)⁻¹ g)`` [m²·m/N·…] of the half-wave pair (p, q).

    The load ``F s_m(x) s_n(y)`` on an SSSS plate gives ``w = W s_m s_n`` with
    ``W = F · compliance``; ``g = (p, q)``, B the 2×2 bending block
    ``[[D11 p² + D66 q², (D12 + D66) p q], [(D12 + D66) p q, D66 p² + D22 q²]]`` and
    ``S = diag(kA55, kA44)`` (Mindlin; the static condensation of the 3×3 problem of
    :meth:`impactmaps.targets.plates.plate.Plate.modes`, written without cancellation). With
    infinite shear stiffnesses it is the Kirchhoff
    ``1/(D11 p⁴ + 2(D12 + 2D66) p²q² + D22 q⁴)``.

    Parameters
    ----------
    p, q : array_like
        mπ/a and nπ/b [1/m], > 0 (broadcast together).
    D11, D22, D12, D66 : float
        Bending stiffnesses [N·m].
    shear_xz, shear_yz : float, optional
        Corrected transverse shear stiffnesses kA55 and kA44 [N/m] (default inf: Kirchhoff).

    Returns
    -------
    ndarray
        Compliance per unit modal load amplitude [m/(N/m²)] = [m³/N].
    """
    p = np.asarray(p, dtype=float)
    q = np.asarray(q, dtype=float)
    b00 = D11 * p**2 + D66 * q**2
    b11 = D66 * p**2 + D22 * q**2
    b01 = (D12 + D66) * p * q
    det_b = b00 * b11 - b01**2
    m00 = 1.0 / shear_xz + b11 / det_b
    m11 = 1.0 / shear_yz + b00 / det_b
    m01 = -b01 / det_b
    return (m00 * m11 - m01**2) / (m11 * p**2 - 2.0 * m01 * p * q + m00 * q**2)


def navier_patch_residual(length_x, length_y, stiffnesses, impact_point, contact_radius,
                          transform, retained_m=(), retained_n=(), *, mean_square=None, factor=None) -> float:
    """Static compliance [m/N] of the half-wave pairs *not* retained, under a contact patch.

    ``Σ_{(m,n) not retained} (4/(ab)) s_m(x0)² s_n(y0)² T(k a)² C(p, q)`` with
    ``C`` of :func:`pair_static_compliance` (Kirchhoff or Mindlin), ``k² = p² + q²``,
    ``T`` the modal transform of the patch pressure: the deflection of the
    pressure-weighted mean under the patch load, minus the retained pairs. The pairs with
    ``k ≤ K`` are summed (K from k a = 8, at most 500 half-waves per direction, and
    beyond every retained pair); the rest is the integral
    ``(1/π²) ∫∫_{k>K} T² C dp dq`` (``s²`` averages ½), by Gauss–Legendre quadrature in
    angle and in k a (T² averaged over its oscillation beyond k a = 200). For a → 0 the
    Kirchhoff value tends to the point residual; the Mindlin one diverges as ln(1/a).

    Parameters
    ----------
    length_x, length_y : float
        Plate sides a, b [m].
    stiffnesses : tuple of float
        (D11, D22, D12, D66) [N·m] and optionally (kA55, kA44) [N/m] (Mindlin).
    impact_point : tuple of float
        Centre of the patch (x0, y0) [m].
    contact_radius : float
        Patch radius [m], > 0.
    transform : callable
        T(k a) [-], vectorised (:mod:`impactmaps.targets.patch`).
    retained_m, retained_n : array_like of int
        The retained half-wave pairs (left out of the sum).
    mean_square : callable, optional
        ⟨T²⟩(k a) for large k a (default: T² itself).
    factor : callable, optional
        Weight ρ(k) [-] of each pair's compliance (default 1;
        :func:`~impactmaps.targets.plates.near_field.near_field_factor`).

    Returns
    -------
    float
        Residual compliance [m/N], ≥ 0.
    """
    a, b = float(length_x), float(length_y)
    x0, y0 = (float(v) for v in impact_point)
    radius = float(contact_radius)
    retained_m = np.asarray(retained_m, dtype=np.int64)
    retained_n = np.asarray(retained_n, dtype=np.int64)

    def compliance(p, q):
        if factor is None:
            return pair_static_compliance(p, q, *stiffnesses)
        return pair_static_compliance(p, q, *stiffnesses) * factor(np.hypot(p, q))

    def lattice_compliance(rows, p, q):  # the pairs' compliances: radius-free, kept per plate (the same bits)
        if factor is not None:
            return compliance(np.broadcast_to(p, (p.shape[0], q.size)), np.broadcast_to(q[None, :], (p.shape[0], q.size)))
        return _lattice(a, b, tuple(float(v) for v in stiffnesses), int(rows[-1]), q.size)[rows[0] - 1:rows[-1], :]

    cap = _PATCH_LATTICE_TERMS * math.pi / max(a, b)
    k_lattice = min(_PATCH_LATTICE_KA / radius, cap)
    if retained_m.size:
        k_lattice = max(k_lattice, 1.25 * float(np.max(np.hypot(retained_m * math.pi / a,
                                                                 retained_n * math.pi / b))))
    m_count = int(k_lattice * a / math.pi)
    n_count = int(k_lattice * b / math.pi)
    n = np.arange(1, n_count + 1, dtype=np.int64)
    q = n * math.pi / b
    weight_n = sin_pi(n * y0 / b) ** 2
    retained_keys = np.sort(retained_m * (n_count + 1) + retained_n)
    total = 0.0
    for start in range(1, m_count + 1, 256):
        m = np.arange(start, min(start + 256, m_count + 1), dtype=np.int64)[:, None]
        p = m * math.pi / a
        k = np.hypot(p, q[None, :])
        keep = (k <= k_lattice) & ~np.isin(m * (n_count + 1) + n[None, :], retained_keys)
        terms = sin_pi(m * x0 / a) ** 2 * weight_n[None, :] * transform(k * radius) ** 2 * lattice_compliance(
            m[:, 0], p, q)
        total += float(np.sum(np.where(keep, terms, 0.0)))
    tail = _patch_tail(k_lattice * radius, radius, compliance, transform, mean_square or transform)
    return 4.0 / (a * b) * total + tail


#: The lattices of :func:`_lattice` kept (the most recently used).
_LATTICES_KEPT = 4
_lattices: dict = {}
_lattices_lock = threading.Lock()


def _lattice(a, b, stiffnesses, m_count, n_count):
    """:func:`pair_static_compliance` of the pairs m ≤ ``m_count``, n ≤ ``n_count`` [m³/N], shape
    (m, n) or larger: one lattice per plate, grown as a smaller patch asks for more pairs. Every
    element is the value a call on any array holding the pair gives (elementwise arithmetic), so
    :func:`navier_patch_residual` keeps its bits; its patch iterations and tile points, which move
    the radius only, stop recomputing it (~250 calls in a laminate's first ``lookup --case``)."""
    with _lattices_lock:
        return _kept_lattice((a, b, stiffnesses), m_count, n_count)[:, :n_count]


def _kept_lattice(key, m_count, n_count):
    a, b, stiffnesses = key
    kept = _lattices.pop(key, None)
    if kept is None or kept.shape[0] < m_count or kept.shape[1] < n_count:
        rows = max(m_count, 0 if kept is None else kept.shape[0])
        columns = max(n_count, 0 if kept is None else kept.shape[1])
        p = np.arange(1, rows + 1, dtype=np.int64)[:, None] * math.pi / a
        q = np.arange(1, columns + 1, dtype=np.int64) * math.pi / b
        kept = pair_static_compliance(np.broadcast_to(p, (rows, columns)), np.broadcast_to(q[None, :], (rows, columns)),
                                      *stiffnesses)
        kept.setflags(write=False)
    _lattices[key] = kept
    while len(_lattices) > _LATTICES_KEPT:
        _lattices.pop(next(iter(_lattices)))
    return kept


def _patch_tail(x_start, radius, compliance, transform, mean_square):
    """``(1/π²) ∫_0^{π/2} dθ ∫_{x_start/r}^∞ k C(k cos θ, k sin θ) T(k r)² dk`` [m/N]."""
    edges = []
    if x_start < 1.0:
        edges.append(np.geomspace(x_start, 1.0, math.ceil(math.log(1.0 / x_start) / math.log(1.5)) + 1))
    low = max(x_start, 1.0)
    if low < _PATCH_AVERAGE_KA:
        edges.append(np.linspace(low, _PATCH_AVERAGE_KA, math.ceil(2.0 * (_PATCH_AVERAGE_KA - low)) + 1))
    oscillating = np.unique(np.concatenate(edges)) if edges else np.zeros(0)
    high = max(x_start, _PATCH_AVERAGE_KA)
    averaged = np.geomspace(high, high * 1e8, 60)
    theta = 0.25 * math.pi * (_ANGLE_NODES + 1.0)
    total = 0.0
    for panel_edges, squared in ((oscillating, lambda x: transform(x) ** 2), (averaged, mean_square)):
        if panel_edges.size < 2:
            continue
        left, right = panel_edges[:-1, None], panel_edges[1:, None]
        x = (0.5 * (left + right) + 0.5 * (right - left) * _GAUSS_NODES[None, :]).ravel()
        wx = (0.5 * (right - left) * _GAUSS_WEIGHTS[None, :]).ravel()
        k = x / radius
        c = compliance(k[None, :] * np.cos(theta)[:, None], k[None, :] * np.sin(theta)[:, None])
        inner = np.sum(c * (k * squared(x) * wx / radius)[None, :], axis=1)
        total += 0.25 * math.pi * float(np.sum(_ANGLE_WEIGHTS * inner))
    return total / math.pi**2
