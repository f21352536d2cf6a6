"""The contact pair: what every contact law needs to know about the two bodies.

A :class:`ContactPair` holds the effective modulus E*, the effective radius R and the
softer body's yield strength; :class:`Sphere` is the impactor. Materials are duck-typed
(``youngs_modulus`` [Pa], ``poisson_ratio`` [-], ``density`` [kg/m³], optional
``yield_strength`` [Pa]); their checks live here, once.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._checks import require_in_range, require_positive
from .base import (
    LawOption,
    effective_modulus,
    effective_radius,
    require_positive_or_infinite,
)

__all__ = ["ContactPair", "PAIR_OPTIONS", "Sphere", "softer_yield_strength"]

#: Keyword options of :meth:`ContactPair.from_sphere` (and so of ``law_for_sphere``) by name.
PAIR_OPTIONS = {
    "target_radius": LawOption(
        "target_radius", "m", np.inf,
        "radius of curvature of the target at the impact point, 1/R = 1/R_sphere + 1/R_target (inf: a flat)"),
    "yield_strength": LawOption(
        "yield_strength", "Pa", None,
        "yield strength overriding the softer material's (e.g. 2 S_u for composites, seed 001)"),
}

_MISSING_YIELD = (
    "yield_strength is missing: neither the sphere's nor the target's material defines "
    "a yield_strength [Pa] (valid range (0, inf)); set it on a material or pass "
    "yield_strength=... to law_for_sphere"
)


def material_attribute(material, attribute: str, role: str):
    """``material.attribute``, or a ``ValueError`` naming ``role`` and what a material needs."""
    try:
        return getattr(material, attribute)
    except AttributeError:
        raise ValueError(
            f"{role} = {material!r} has no attribute {attribute!r}: a material needs "
            "youngs_modulus [Pa], poisson_ratio [-], density [kg/m^3] and optionally yield_strength [Pa]"
        ) from None


def check_elastic_material(material, role: str, allow_rigid: bool = False) -> None:
    """Validate ``youngs_modulus`` [Pa] (> 0, or ``inf`` if ``allow_rigid``) and ``poisson_ratio`` [-]
    of ``material`` (``ValueError`` naming ``role``)."""
    modulus = material_attribute(material, "youngs_modulus", role)
    if not (allow_rigid and np.all(np.asarray(modulus, dtype=float) == np.inf)):
        require_positive(f"{role}.youngs_modulus", modulus, "Pa")
    require_in_range(f"{role}.poisson_ratio", material_attribute(material, "poisson_ratio", role),
                     -1.0, 0.5, low_inclusive=False, high_inclusive=False)


def _defined_yield_strengths(materials) -> list[float]:
    values = [getattr(m, "yield_strength", None) for m in materials]
    values = [v for v in values if v is not None]
    for value in values:
        require_positive("yield_strength", value, "Pa")
    return values


def softer_yield_strength(*materials) -> float:
    """Smallest yield strength [Pa] among materials that define one (``ValueError`` if none does)."""
    values = _defined_yield_strengths(materials)
    if not values:
        raise ValueError(_MISSING_YIELD)
    return float(min(values))


@dataclass(frozen=True)
class Sphere:
    """A solid spherical impactor.

    Parameters
    ----------
    radius : float
        Sphere radius R [m].
    material : material-like
        Needs ``youngs_modulus`` [Pa], ``poisson_ratio`` [-], ``density`` [kg/m³] (the
        last only if ``mass`` is not given) and optionally ``yield_strength`` [Pa].
    mass : float, optional
        Impactor mass m_i [kg]; default ``ρ (4/3) π R³``. Give it to model a sphere
        carried by a heavier drop-weight.
    """

    radius: float
    material: object
    mass: float | None = None

    def __post_init__(self):
        require_positive("radius", self.radius, "m")
        check_elastic_material(self.material, "material")
        if self.mass is None:
            density = material_attribute(self.material, "density", "material")
            require_positive("material.density", density, "kg/m^3")
            object.__setattr__(self, "mass", float(density) * 4.0 / 3.0 * np.pi * float(self.radius) ** 3)
        else:
            require_positive("mass", self.mass, "kg")

    @property
    def yield_strength(self):
        """Yield strength of the sphere's material [Pa], or ``None``."""
        return getattr(self.material, "yield_strength", None)


@dataclass(frozen=True)
class ContactPair:
    """Two bodies in contact, as the contact laws see them (SI units).

    Parameters
    ----------
    effective_modulus : float
        E* [Pa], ``1/E* = (1-ν1²)/E1 + (1-ν2²)/E2`` (seed 001 eq 8).
    effective_radius : float
        R [m], ``1/R = 1/R1 + 1/R2``.
    yield_strength : float or None
        Yield strength S_y of the softer body [Pa]; ``None`` if neither yields.
    """

    effective_modulus: float
    effective_radius: float
    yield_strength: float | None = None

    def __post_init__(self):
        require_positive("effective_modulus", self.effective_modulus, "Pa")
        require_positive("effective_radius", self.effective_radius, "m")
        if self.yield_strength is not None:
            require_positive("yield_strength", self.yield_strength, "Pa")

    @classmethod
    def from_sphere(cls, sphere, target_material, *, target_radius=np.inf,
                    yield_strength=None) -> "ContactPair":
        """The pair formed by ``sphere`` striking a target of ``target_material``.

        ``target_material``: ``youngs_modulus`` [Pa] (``inf``: rigid), ``poisson_ratio`` [-],
        optional ``yield_strength`` [Pa]; ``target_radius`` [m] (default inf, a flat);
        ``yield_strength`` [Pa] overrides the softer material's.
        """
        if not isinstance(sphere, Sphere):
            raise ValueError(f"sphere = {sphere!r} is not a Sphere")
        check_elastic_material(target_material, "target_material", allow_rigid=True)
        modulus = float(effective_modulus(
            sphere.material.youngs_modulus, sphere.material.poisson_ratio,
            target_material.youngs_modulus, target_material.poisson_ratio,
        ))
        require_positive_or_infinite("target_radius", target_radius, "m")
        radius = float(effective_radius(sphere.radius, target_radius))
        if yield_strength is None:
            defined = _defined_yield_strengths((sphere.material, target_material))
            strength = float(min(defined)) if defined else None
        else:
            require_positive("yield_strength", yield_strength, "Pa")
            strength = float(yield_strength)
        return cls(modulus, radius, strength)

    def required_yield_strength(self) -> float:
        """S_y [Pa] for a law that needs one (``ValueError`` if the pair has none)."""
        if self.yield_strength is None:
            raise ValueError(_MISSING_YIELD)
        return self.yield_strength
