"""The near field of an isotropic Mindlin plate under a contact patch, made consistent with 3D
elasticity and with the contact law (docs/contact_patch.rst, "The near field").

A Hertz (or other half-space) contact law already carries the local deformation of the
struck surface, the half-space (Boussinesq) response. The structure must then add only what
the plate adds to it. For an isotropic layer of thickness h with a free bottom face, loaded on
its top face by a pressure ``cos(k·x)``, plane-strain elasticity (Airy stress function) gives
the top-face deflection per unit pressure

    C_layer(k) = (1 − ν²)/(E k) · (sinh 4t + 4t)/(sinh² 2t − 4t²),   t = k h/2,

which tends to the half-space ``C_hs(k) = 2(1 − ν²)/(E k)`` for k h → ∞ and to the plate
``1/(D k⁴) · (1 + (k h)²/5 + …)`` for k h → 0. The plate's share is
``C_layer − C_hs`` (≥ 0: a layer is more compliant than the half-space under it); it falls
off like ``exp(−k h)`` beyond k h ≈ 1, where the Mindlin share ``1/(D k⁴) + 1/(k_s G h k²)``
keeps the shear term that makes a point load's deflection diverge. Each Mindlin half-wave
pair (wavenumber k) is weighted by ``ρ(k) = (C_layer − C_hs)/C_Mindlin`` (its participation
by ``sqrt(ρ)``), so that the static compliance under the patch is that of the 3D solid minus
its half-space part: exact for an SSSS plate (a double sine series of a 3D layer is exact for
its diaphragm supports). ``ρ → 1`` for k h → 0 (the low modes keep their Mindlin
participation), ``ρ → 0`` for k h ≫ 1.

Only isotropic plates: the layer kernel of a laminate is not built (their ρ is 1, the Mindlin
patch model as before). :func:`near_field_estimate` estimates what it would remove from a
laminate's compliance under the patch, and :mod:`impactmaps.validity` warns when that is large.
"""

from __future__ import annotations

import numpy as np

__all__ = ["isotropic_constants", "layer_excess_compliance", "near_field_factor", "flexural_wavenumber",
           "residual_change", "isotropic_factor", "near_field_estimate", "ESTIMATE_POISSON_RATIO"]

#: Relative tolerance of the isotropy test on a plate's stiffnesses.
_ISOTROPY_RTOL = 1e-9
#: Below this u = 2t the differences sinh u − u use their Taylor series.
_SERIES_LIMIT = 0.5
#: Poisson ratio of the isotropic weight :func:`near_field_estimate` applies to a laminate
#: (the estimate moves by ±6 % of itself for 0.2–0.4, docs/contact_patch.rst).
ESTIMATE_POISSON_RATIO = 0.3


def _sinh_minus(u):
    """``sinh u − u`` without cancellation for small u."""
    u = np.asarray(u, dtype=float)
    series = u**3 / 6.0 * (1.0 + u**2 / 20.0 * (1.0 + u**2 / 42.0 * (1.0 + u**2 / 72.0 * (1.0 + u**2 / 110.0))))
    with np.errstate(over="ignore"):
        closed = np.sinh(np.maximum(u, _SERIES_LIMIT)) - u
    return np.where(u < _SERIES_LIMIT, series, closed)


def layer_excess_compliance(k, thickness, youngs_modulus, poisson_ratio):
    """Top-face compliance of a free isotropic layer minus that of the half-space,
    ``C_layer(k) − C_hs(k)`` [m/Pa per unit wavenumber amplitude, i.e. m³/N].

    Parameters
    ----------
    k : float or array_like
        Wavenumber of the pressure ``cos(k·x)`` on the top face [1/m], > 0.
    thickness : float
        Layer thickness h [m].
    youngs_modulus, poisson_ratio : float
        E [Pa], ν [-].

    Returns
    -------
    ndarray
        ``(1 − ν²)/(E k) · (1 − e^{−4t} + 4t + 8t²)/(sinh² 2t − 4t²)``, t = k h/2 (≥ 0;
        ``(1 − ν²)/(E k)·(sinh 4t + 4t)/(sinh² 2t − 4t²) − 2(1 − ν²)/(E k)`` written without
        cancellation).
    """
    k = np.asarray(k, dtype=float)
    t = 0.5 * k * float(thickness)
    u = 2.0 * t
    with np.errstate(over="ignore"):
        denominator = _sinh_minus(u) * (np.sinh(u) + u)  # sinh² u − u²
        numerator = -np.expm1(-2.0 * u) + 2.0 * u + 2.0 * u * u
        ratio = np.where(np.isfinite(denominator), numerator / denominator, 0.0)
    return (1.0 - poisson_ratio**2) / (youngs_modulus * k) * ratio


def isotropic_constants(plate):
    """(E [Pa], ν [-]) of a plate whose stiffnesses are those of an isotropic material
    (:meth:`Plate.isotropic`), else None."""
    h = plate.thickness
    d = plate.D11
    nu = plate.D12 / d
    E = 12.0 * d * (1.0 - nu**2) / h**3
    G = E / (2.0 * (1.0 + nu))
    expected = ((plate.D22, d), (plate.D66, 0.5 * (1.0 - nu) * d), (plate.A44, G * h), (plate.A55, G * h))
    if any(abs(value - want) > _ISOTROPY_RTOL * abs(want) for value, want in expected):
        return None
    if plate.D16 or plate.D26 or plate.A45 or not 0.0 <= nu < 0.5:
        return None
    return E, nu


def isotropic_factor(k, thickness, poisson_ratio, shear_correction):
    """The weight ``ρ(k)`` [-] of an isotropic Mindlin plate of ``thickness`` h [m], Poisson ratio
    ν and shear correction k_s at wavenumber ``k`` [1/m]: ``(C_layer − C_hs)/(1/(D k⁴) + 1/(k_s G h k²))``
    (Young's modulus cancels, so ρ depends on k h, ν and k_s only)."""
    k = np.asarray(k, dtype=float)
    h, nu = float(thickness), float(poisson_ratio)
    mindlin = 12.0 * (1.0 - nu**2) / (h**3 * k**4) + 2.0 * (1.0 + nu) / (shear_correction * h * k**2)
    return layer_excess_compliance(k, h, 1.0, nu) / mindlin


def near_field_factor(plate, k):
    """The weight ``ρ(k)`` [-] of a Mindlin half-wave pair of wavenumber ``k`` [1/m] under the
    contact patch: the 3D layer's compliance beyond the half-space over the Mindlin plate's,
    ``(C_layer − C_hs)/(1/(D k⁴) + 1/(k_s G h k²))``, in (0, 1]. 1 for Kirchhoff plates and
    plates that are not isotropic.
    """
    k = np.asarray(k, dtype=float)
    constants = isotropic_constants(plate) if plate.theory == "mindlin" else None
    if constants is None:
        return np.ones_like(k)
    E, nu = constants
    mindlin = 1.0 / (plate.D11 * k**4) + 1.0 / (plate.shear_correction * plate.A55 * k**2)
    return layer_excess_compliance(k, plate.thickness, E, nu) / mindlin


def flexural_wavenumber(plate, omega):
    """Wavenumber [1/m] of the flexural branch of an isotropic Mindlin plate at circular
    frequency ``omega`` [rad/s]: the positive root k² of
    ``(S k² − I0 ω²)(D k² + S − I2 ω²) = S² k²`` (S = k_s G h, I0 = ρh, I2 = ρh³/12).
    In the interior of a plate with any edges a mode of frequency ω is a sum of such waves
    (the evanescent parts decay from the edges)."""
    omega = np.asarray(omega, dtype=float)
    s, d = plate.shear_correction * plate.A55, plate.D11
    i0, i2 = plate.mass_per_area, plate.rotary_inertia_per_area
    w2 = omega**2
    # S D k⁴ + [S(S − I2 ω²) − I0 ω² D − S²] k² − I0 ω² (S − I2 ω²) = 0
    qa = s * d
    qb = -s * i2 * w2 - i0 * w2 * d
    qc = -i0 * w2 * (s - i2 * w2)
    root = (-qb + np.sqrt(qb * qb - 4.0 * qa * qc)) / (2.0 * qa)
    return np.sqrt(np.maximum(root, 0.0))


def residual_change(plate, contact_radius: float, wavenumber: float) -> float:
    """Change [m/N] of the patch residual compliance of an isotropic Mindlin plate with any
    edges when its modes are weighted by :func:`near_field_factor`: that of the SSSS plate of
    the same size over the half-wave pairs with wavenumber above ``wavenumber`` [1/m] (the
    retained modes' flexural wavenumber), ``Σ (ρ − 1) C_pair T² (4/(ab)) s_m² s_n²`` (≤ 0).
    Those pairs have k above the retained modes', where the field under the load does not
    see the edges."""
    from ..patch import hertz_transform, mean_square_transform
    from .plate_static import navier_patch_residual

    a, b = plate.length_x, plate.length_y
    m = np.arange(1, int(wavenumber * a / np.pi) + 2)
    n = np.arange(1, int(wavenumber * b / np.pi) + 2)
    mm, nn = np.meshgrid(m, n, indexing="ij")
    keep = np.hypot(mm * np.pi / a, nn * np.pi / b) <= wavenumber
    retained = mm[keep], nn[keep]
    stiffnesses = (plate.D11, plate.D22, plate.D12, plate.D66,
                   plate.shear_correction * plate.A55, plate.shear_correction * plate.A44)
    args = (a, b, stiffnesses, plate.impact_point, contact_radius, hertz_transform, *retained)
    weighted = navier_patch_residual(*args, mean_square=mean_square_transform,
                                     factor=lambda k: near_field_factor(plate, k))
    return weighted - navier_patch_residual(*args, mean_square=mean_square_transform)


def near_field_estimate(plate, contact_radius: float, poisson_ratio: float = ESTIMATE_POISSON_RATIO) -> float:
    """Estimated compliance [m/N] that a 3D-consistent near field would remove from a Mindlin
    plate's static compliance under the Hertz patch of ``contact_radius`` [m], for a plate that
    has none (a laminate): the isotropic weight :func:`isotropic_factor` (``poisson_ratio``, the
    plate's thickness and shear correction) applied to the plate's own half-wave pairs of its
    simply supported twin, ``Σ (1 − ρ) C T² (4/(ab)) s_m² s_n²`` (:func:`navier_patch_residual
    <impactmaps.targets.plates.plate_static.navier_patch_residual>` over every pair: the part
    removed lies at k h ≳ 1, where the edges do not matter). An estimate: the layer kernel of
    an anisotropic, layered plate is not built; on an isotropic plate with its own ν it is that
    plate's near-field correction (SSSS).
    """
    from ..patch import hertz_transform, mean_square_transform
    from .plate_static import navier_patch_residual

    stiffnesses = (plate.D11, plate.D22, plate.D12, plate.D66,
                   plate.shear_correction * plate.A55, plate.shear_correction * plate.A44)
    none = np.zeros(0, dtype=np.int64)
    args = (plate.length_x, plate.length_y, stiffnesses, plate.impact_point, float(contact_radius), hertz_transform,
            none, none)
    whole = navier_patch_residual(*args, mean_square=mean_square_transform)
    weighted = navier_patch_residual(*args, mean_square=mean_square_transform, factor=lambda k: isotropic_factor(
        k, plate.thickness, poisson_ratio, plate.shear_correction))
    return float(whole - weighted)
