"""Contact geometry: the effective modulus and radius of two bodies in contact (seed 001 eq 8)."""

from __future__ import annotations

import numpy as np

from .._checks import require_in_range, require_positive

__all__ = ["contact_radius_function", "effective_modulus", "effective_radius", "require_positive_or_infinite"]


def require_positive_or_infinite(name: str, value, unit: str) -> np.ndarray:
    """``value`` as a float array, or ``ValueError`` unless every element is in (0, inf]."""
    array = np.asarray(value, dtype=float)
    if np.any(np.isnan(array)) or np.any(array <= 0):
        raise ValueError(f"{name} = {value!r} is invalid: valid range is (0, inf] [{unit}]")
    return array


def effective_modulus(
    youngs_modulus_1, poisson_ratio_1, youngs_modulus_2=np.inf, poisson_ratio_2=0.0
):
    """Effective contact modulus E* [Pa], ``1/E* = (1-ν1²)/E1 + (1-ν2²)/E2`` (seed 001 eq 8);
    E [Pa] and ν [-] of the impactor (1) and target (2), ``inf`` for rigid.
    """
    require_positive("youngs_modulus_1", youngs_modulus_1, "Pa")
    require_in_range("poisson_ratio_1", poisson_ratio_1, -1.0, 0.5,
                     low_inclusive=False, high_inclusive=False)
    e2 = require_positive_or_infinite("youngs_modulus_2", youngs_modulus_2, "Pa")
    require_in_range("poisson_ratio_2", poisson_ratio_2, -1.0, 0.5,
                     low_inclusive=False, high_inclusive=False)
    compliance = (1 - np.asarray(poisson_ratio_1) ** 2) / np.asarray(youngs_modulus_1, float)
    compliance = compliance + np.where(np.isinf(e2), 0.0, (1 - np.asarray(poisson_ratio_2) ** 2) / e2)
    return 1.0 / compliance


def effective_radius(radius_1, radius_2=np.inf):
    """Effective contact radius R [m], ``1/R = 1/R1 + 1/R2``; ``radius_2 = inf`` is a flat."""
    require_positive("radius_1", radius_1, "m")
    r2 = require_positive_or_infinite("radius_2", radius_2, "m")
    return 1.0 / (1.0 / np.asarray(radius_1, float) + np.where(np.isinf(r2), 0.0, 1.0 / r2))


def contact_radius_function(law, effective_radius: float | None = None):
    """α [m] → contact radius a [m] of ``law``, or ``None`` when the law has no geometry.

    A law's ``loading_contact_radius`` (Stronge), else ``a = sqrt(R α)`` with R the
    ``effective_radius`` [m] or the law's ``contact_radius_scale``.
    """
    if hasattr(law, "loading_contact_radius"):
        return lambda alpha: float(law.loading_contact_radius(alpha))
    radius = effective_radius if effective_radius is not None else law.contact_radius_scale
    if radius is None:
        return None
    require_positive("effective_radius", radius, "m")
    return lambda alpha: float(np.sqrt(float(radius) * max(float(alpha), 0.0)))
