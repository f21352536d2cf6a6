"""Modes of simply supported (SSSS) plates by the Navier solution (docs/physics_contract.md §3.3).

Kirchhoff: closed-form frequencies per half-wave pair (m, n). Mindlin: per (m, n) the
lowest (flexural) branch of the 3×3 eigenproblem of seed 001 eqs (13)–(15), polished by
safeguarded Newton iteration (see :meth:`impactmaps.targets.plates.plate.Plate.modes` for the
equations). The functions take a :class:`~impactmaps.targets.plates.plate.Plate` (its fields
only); conventions as in :mod:`impactmaps.targets.plates.plate`.
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from ..base import ModalBasis
from ..patch import hertz_transform, mean_square_transform
from . import near_field
from .plate_static import navier_patch_residual, pair_static_compliance, sin_pi


__all__ = ["kirchhoff_eigenvalues", "mindlin_flexural", "navier_frequencies", "navier_mode_count",
           "navier_modes", "navier_pairs", "lowest_modes"]

#: Half-wave numbers m counted at once by :func:`navier_mode_count` (bounds its memory).
COUNT_CHUNK = 65536


def kirchhoff_eigenvalues(plate, m, n):
    """ω² [rad²/s²] of the classical SSSS plate for half-wave numbers m, n.

    Parameters
    ----------
    plate : Plate
        The plate (sides, bending stiffnesses and ρh are used).
    m, n : float or array_like
        Half-wave numbers along x and y [-] (broadcast together).

    Returns
    -------
    ndarray
        ``π⁴[D11 (m/a)⁴ + 2(D12+2D66)(m/a)²(n/b)² + D22 (n/b)⁴]/ρh`` [rad²/s²].
    """
    p2 = (np.pi * m / plate.length_x) ** 2
    q2 = (np.pi * n / plate.length_y) ** 2
    H = plate.D12 + 2.0 * plate.D66
    return (plate.D11 * p2**2 + 2.0 * H * p2 * q2 + plate.D22 * q2**2) / plate.mass_per_area


def _mindlin_blocks(plate, p, q):
    """Bending block B (…, 2, 2) and shear stiffnesses kA55, kA44."""
    B = np.empty(p.shape + (2, 2))
    B[..., 0, 0] = plate.D11 * p**2 + plate.D66 * q**2
    B[..., 1, 1] = plate.D66 * p**2 + plate.D22 * q**2
    B[..., 0, 1] = B[..., 1, 0] = (plate.D12 + plate.D66) * p * q
    return B, plate.shear_correction * plate.A55, plate.shear_correction * plate.A44


def _mindlin_matrices(plate, m, n):
    """Stacked 3×3 stiffness matrices K (…, 3, 3) and the mass diagonal (3,)."""
    p = np.pi * np.asarray(m, dtype=float) / plate.length_x
    q = np.pi * np.asarray(n, dtype=float) / plate.length_y
    B, s55, s44 = _mindlin_blocks(plate, p, q)
    K = np.zeros(p.shape + (3, 3))
    K[..., 0, 0] = s55 * p**2 + s44 * q**2
    K[..., 0, 1] = K[..., 1, 0] = s55 * p
    K[..., 0, 2] = K[..., 2, 0] = s44 * q
    K[..., 1:, 1:] = B
    K[..., 1, 1] += s55
    K[..., 2, 2] += s44
    mass = np.array([plate.mass_per_area, plate.rotary_inertia_per_area, plate.rotary_inertia_per_area])
    return K, mass


def mindlin_flexural(plate, m, n):
    """Flexural branch of the Mindlin SSSS plate: ω and the normalised amplitude W.

    Parameters
    ----------
    plate : Plate
        The plate (``theory="mindlin"``; rotary inertia > 0).
    m, n : array_like
        Half-wave numbers along x and y [-] (broadcast together).

    Returns
    -------
    omega : ndarray
        Flexural natural frequencies [rad/s].
    amplitude : ndarray
        W of the mass-normalised mode ``(ρh W² + ρh³/12 (X² + Y²)) ab/4 = 1`` [kg^-1/2].
    """
    m = np.asarray(m, dtype=float)
    n = np.asarray(n, dtype=float)
    p = np.pi * m / plate.length_x
    q = np.pi * n / plate.length_y
    B, s55, s44 = _mindlin_blocks(plate, p, q)
    rho_h, inertia = plate.mass_per_area, plate.rotary_inertia_per_area
    K, mass = _mindlin_matrices(plate, m, n)
    inv_sqrt = 1.0 / np.sqrt(mass)
    estimate = np.linalg.eigvalsh(K * inv_sqrt[:, None] * inv_sqrt[None, :])[..., 0]
    # Kirchhoff with rotary inertia: an upper bound (ψ = −∇w is admissible)
    upper = (kirchhoff_eigenvalues(plate, m, n) * rho_h) / (rho_h + inertia * (p**2 + q**2))
    # lowest eigenvalue of (B + S)/I: the pole of the condensed equation
    d0 = B[..., 0, 0] + s55
    d1 = B[..., 1, 1] + s44
    pole = 0.5 * (d0 + d1 - np.hypot(d0 - d1, 2.0 * B[..., 0, 1])) / inertia
    low = np.zeros_like(upper)
    high = np.minimum(upper, pole * (1.0 - 1e-12))
    lam = np.where((estimate > 0) & (estimate < high), estimate, 0.5 * high)
    sg0, sg1 = s55 * p, s44 * q

    def condensed(lam):
        c00 = B[..., 0, 0] + s55 - lam * inertia
        c11 = B[..., 1, 1] + s44 - lam * inertia
        c01 = B[..., 0, 1]
        det = c00 * c11 - c01**2
        u0 = (c11 * sg0 - c01 * sg1) / det
        u1 = (c00 * sg1 - c01 * sg0) / det
        bg0 = (B[..., 0, 0] - lam * inertia) * p + B[..., 0, 1] * q
        bg1 = B[..., 1, 0] * p + (B[..., 1, 1] - lam * inertia) * q
        value = u0 * bg0 + u1 * bg1 - lam * rho_h
        slope = -rho_h - inertia * (u0**2 + u1**2)
        return value, slope, u0, u1

    # safeguarded Newton (f decreasing and concave on (0, pole), root bracketed)
    for _ in range(200):
        value, slope, _, _ = condensed(lam)
        low = np.where(value > 0, lam, low)
        high = np.where(value <= 0, lam, high)
        new = lam - value / slope
        outside = ~((new > low) & (new < high)) & (value != 0)
        new = np.where(outside, 0.5 * (low + high), new)
        done = np.abs(new - lam) <= 2e-15 * np.abs(lam)
        lam = new
        if np.all(done):
            break
    else:
        warnings.warn("Mindlin flexural frequencies: the Newton polish did not converge to "
                      "machine precision", RuntimeWarning, stacklevel=3)
    _, _, u0, u1 = condensed(lam)
    amplitude = 2.0 / np.sqrt(plate.length_x * plate.length_y * (rho_h + inertia * (u0**2 + u1**2)))
    return np.sqrt(lam), amplitude


def navier_frequencies(plate, m, n):
    """Natural frequencies ω_mn [rad/s] of the SSSS plate (its theory) for half-wave numbers.

    Parameters
    ----------
    plate : Plate
        The plate.
    m, n : array_like
        Half-wave numbers along x and y [-] (broadcast together).

    Returns
    -------
    ndarray
        ω_mn [rad/s] (Mindlin: the flexural branch).
    """
    if plate.theory == "kirchhoff":
        return np.sqrt(kirchhoff_eigenvalues(plate, np.asarray(m, float), np.asarray(n, float)))
    return mindlin_flexural(plate, m, n)[0]


def navier_pairs(plate, max_frequency):
    """All (m, n) with ω_mn ≤ max_frequency [rad/s], as two int arrays.

    Relies on ω_mn increasing in m and in n (true for D12 + 2D66 > 0; checked against
    brute-force enumeration in the tests): the largest m at n = 1 and then, for every
    m at once, the largest n are found by vectorised doubling and bisection.
    """
    def frequency(m, n):
        return navier_frequencies(plate, np.asarray(m, float), np.asarray(n, float))

    if frequency(1, 1) > max_frequency:
        return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
    m_count = int(_last_index_within(lambda k: frequency(k, np.ones_like(k)), 1, max_frequency)[0])
    m_values = np.arange(1, m_count + 1, dtype=np.int64)
    n_counts = _last_index_within(lambda k: frequency(m_values, k), m_count, max_frequency)
    m_pairs = np.repeat(m_values, n_counts)
    offsets = np.repeat(np.cumsum(n_counts) - n_counts, n_counts)
    n_pairs = np.arange(m_pairs.size, dtype=np.int64) - offsets + 1
    return m_pairs, n_pairs


def navier_mode_count(plate, max_frequency: float, limit: int | None = None) -> int:
    """Number of half-wave pairs (m, n) with ω_mn ≤ ``max_frequency`` [rad/s], unbuilt.

    The count of :func:`navier_pairs` by the same searches, without forming the pairs:
    the largest n for :data:`COUNT_CHUNK` values of m at a time, summed. Memory stays
    below ~10 MB whatever the count. Once the count exceeds ``limit`` it stops and
    returns a lower bound above ``limit`` (the pairs (m, 1) and (1, n), or the square of
    pairs up to the largest (k, k), alone bound it from below, so a cut-off far beyond the
    limit costs only three scalar searches).
    """
    def frequency(m, n):
        return navier_frequencies(plate, np.asarray(m, float), np.asarray(n, float))

    if frequency(1, 1) > max_frequency:
        return 0
    m_count = int(_last_index_within(lambda k: frequency(k, np.ones_like(k)), 1, max_frequency)[0])
    n_count = int(_last_index_within(lambda k: frequency(np.ones_like(k), k), 1, max_frequency)[0])
    diagonal = int(_last_index_within(lambda k: frequency(k, k), 1, max_frequency)[0])
    bound = max(m_count + n_count - 1, diagonal**2)
    if limit is not None and bound > limit:
        return bound
    total = 0
    for start in range(1, m_count + 1, COUNT_CHUNK):
        m_values = np.arange(start, min(start + COUNT_CHUNK, m_count + 1), dtype=np.int64)
        total += int(np.sum(_last_index_within(lambda k: frequency(m_values, k), m_values.size,
                                               max_frequency)))
        if limit is not None and total > limit:
            break
    return total


def warn_beyond_thickness_shear(plate, max_frequency: float, stacklevel: int = 2) -> None:
    """Warn when a cut-off [rad/s] passes a Mindlin plate's thickness-shear cut-off.

    ``sqrt(k min(A44, A55)/(ρh³/12))`` [rad/s]
    (:meth:`impactmaps.targets.plates.plate.Plate.thickness_shear_frequency`): the omitted
    thickness-shear branches have modes below it. Kirchhoff plates (and other targets)
    never warn.
    """
    cutoff = plate.thickness_shear_frequency()
    if cutoff is not None and max_frequency > cutoff:
        warnings.warn(
            f"max_frequency = {max_frequency:.6g} rad/s exceeds the thickness-shear "
            f"cut-off {cutoff:.6g} rad/s: the Mindlin thickness-shear branches, which "
            "are omitted, have modes below the cut-off frequency", UserWarning, stacklevel=stacklevel)


def navier_modes(plate, max_frequency: float, min_modes: int, contact_radius: float = 0.0):
    """(:class:`ModalBasis`, mode-shape function of points) of an SSSS plate.

    The modes with ω ≤ ``max_frequency`` [rad/s], at least ``min_modes``, ascending (ties
    by m, then n); the residual compliance as documented in
    :meth:`impactmaps.targets.plates.plate.Plate.modes`. Warns when a Mindlin ``max_frequency``
    exceeds the thickness-shear cut-off (the omitted branches have modes below it). A
    ``contact_radius`` [m] > 0 spreads the load as a Hertz pressure over that disc
    (:func:`_patch_basis`); 0 is the point load.
    """
    if contact_radius > 0.0:
        return _patch_basis(plate, max_frequency, min_modes, contact_radius)
    warn_beyond_thickness_shear(plate, max_frequency, stacklevel=5)
    m, n, omega, amplitude, participation = _lowest_modes(plate, max_frequency, min_modes)
    x0, y0 = plate.impact_point
    a, b = plate.length_x, plate.length_y
    retained = None  # Kirchhoff: Σ φ²/ω² of the modes themselves
    if plate.theory == "mindlin":
        classical = (4.0 / plate.mass) * (sin_pi(m * x0 / a) * sin_pi(n * y0 / b)) ** 2
        retained = float(np.sum(classical / kirchhoff_eigenvalues(plate, m.astype(float), n.astype(float))))
    damping_ratios = np.full(omega.shape, float(plate.damping_ratio))
    basis = ModalBasis.from_modes(omega, participation, plate.static_compliance(),
                                  damping_ratios, retained_compliance=retained)
    return basis, _shape_function(plate, m, n, amplitude)


def _patch_basis(plate, max_frequency: float, min_modes: int, contact_radius: float):
    """The SSSS basis seen by a Hertz pressure over a disc of ``contact_radius`` [m].

    Each participation is multiplied by the modal transform ``T(k a)`` of the Hertz
    pressure (:func:`impactmaps.targets.patch.hertz_transform`, ``k = hypot(mπ/a, nπ/b)``);
    the residual is the static compliance under the same patch of the half-wave pairs
    not retained (:func:`~impactmaps.targets.plates.plate_static.navier_patch_residual`, for
    Mindlin with the shear flexibility, which now converges), plus for Mindlin the
    part of each retained pair's static compliance its flexural mode does not carry
    (that of the omitted thickness-shear branches, ``C_pair − φ²/ω² ≥ 0``), so that
    retained + residual is the exact static patch compliance. Mindlin: instead of the
    thickness-shear cut-off warning of the point load (the patch suppresses the modes
    with k a ≫ 1), a warning when the contact radius exceeds half the thickness.
    """
    if plate.theory == "mindlin" and contact_radius > 0.5 * plate.thickness:
        warnings.warn(
            f"contact radius {contact_radius:.4g} m exceeds half the plate thickness "
            f"{plate.thickness:.4g} m: Mindlin theory and its omitted thickness-shear branches "
            "are not reliable under such a load", stacklevel=4)
    m, n, omega, amplitude, participation = _lowest_modes(plate, max_frequency, min_modes)
    a, b = plate.length_x, plate.length_y
    k = np.hypot(m * math.pi / a, n * math.pi / b)
    participation = participation * hertz_transform(k * contact_radius)
    stiffnesses = (plate.D11, plate.D22, plate.D12, plate.D66)
    residual = 0.0
    factor = None
    if plate.theory == "mindlin" and near_field.isotropic_constants(plate) is not None:
        def factor(wavenumber):
            return near_field.near_field_factor(plate, wavenumber)

        participation = participation * np.sqrt(factor(k))
    if plate.theory == "mindlin":
        stiffnesses += (plate.shear_correction * plate.A55, plate.shear_correction * plate.A44)
        # φ = W s_m s_n T, so (4/(ab)) s_m² s_n² T² = φ² (4/(ab W²))
        static = participation**2 * 4.0 / (a * b * amplitude**2) * pair_static_compliance(
            m * math.pi / a, n * math.pi / b, *stiffnesses)
        residual = max(float(np.sum(static - participation**2 / omega**2)), 0.0)
    residual += navier_patch_residual(a, b, stiffnesses, plate.impact_point, contact_radius,
                                      hertz_transform, m, n, mean_square=mean_square_transform, factor=factor)
    basis = ModalBasis(omega, participation, residual, np.full(omega.shape, float(plate.damping_ratio)))
    return basis, _shape_function(plate, m, n, amplitude)


def _lowest_modes(plate, max_frequency: float, min_modes: int):
    """(m, n, ω, W, φ) of the modes with ω ≤ ``max_frequency`` (at least ``min_modes``),
    ascending; φ = W s_m(x0) s_n(y0) the point-load participation."""
    cutoff_frequency = max_frequency
    m, n = navier_pairs(plate, cutoff_frequency)
    while m.size < min_modes:
        cutoff_frequency = max(2.0 * cutoff_frequency, 1.5 * float(navier_frequencies(plate, 1, 1)))
        m, n = navier_pairs(plate, cutoff_frequency)
    if plate.theory == "kirchhoff":
        omega = np.sqrt(kirchhoff_eigenvalues(plate, m.astype(float), n.astype(float)))
        amplitude = np.full(omega.shape, 2.0 / math.sqrt(plate.mass))
    else:
        omega, amplitude = mindlin_flexural(plate, m, n)
    order = np.lexsort((n, m, omega))
    keep = order[: max(int(np.sum(omega <= max_frequency)), min_modes)]
    m, n, amplitude = m[keep], n[keep], amplitude[keep]
    x0, y0 = plate.impact_point
    participation = amplitude * sin_pi(m * x0 / plate.length_x) * sin_pi(n * y0 / plate.length_y)
    return m, n, omega[keep], amplitude, participation


def lowest_modes(plate, count: int):
    """(m, n, ω [rad/s]) of the ``count`` lowest modes of an SSSS plate, ascending (ties by m,
    then n): the labels and frequencies of ``impactmaps modes``."""
    m, n, omega, _, _ = _lowest_modes(plate, 0.0, int(count))
    return m, n, omega


def _shape_function(plate, m, n, amplitude):
    """Mode shapes w_j(points) [kg^-1/2] of the half-wave pairs (m, n) with amplitudes W."""
    a, b = plate.length_x, plate.length_y

    def shape_function(points):
        return amplitude[None, :] * sin_pi(points[:, :1] * m[None, :] / a) * sin_pi(
            points[:, 1:] * n[None, :] / b)

    return shape_function


def _last_index_within(frequency_of_index, size, limit):
    """Largest k ≥ 1 (array of ``size``) with ``frequency_of_index(k) ≤ limit``.

    ``frequency_of_index`` maps an int array of shape (size,) to frequencies and must be
    increasing in k, with ``frequency_of_index(1) ≤ limit``.
    """
    low = np.ones(size, dtype=np.int64)
    high = np.full(size, 2, dtype=np.int64)
    while True:
        inside = frequency_of_index(high) <= limit
        if not np.any(inside):
            break
        low = np.where(inside, high, low)
        high = np.where(inside, 2 * high, high)
    while np.any(high - low > 1):
        middle = (low + high) // 2
        inside = frequency_of_index(middle) <= limit
        low = np.where(inside, middle, low)
        high = np.where(inside, high, middle)
    return low
