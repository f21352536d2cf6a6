"""A spherical impactor, and any registered contact law built from sphere + target.

Materials are duck-typed: an object with ``youngs_modulus`` [Pa], ``poisson_ratio``
[-], ``density`` [kg/m³] and optionally ``yield_strength`` [Pa] (``None`` or missing:
the body is taken not to yield), for example
:class:`impactmaps.materials.IsotropicMaterial`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._checks import require_in_range, require_positive
from .base import ContactLaw, contact_law_class, effective_modulus, effective_radius
from .hertz import HertzContact, hertz_stiffness
from .linear import LinearContact
from .stronge import StrongeContact
from .yigit_christoforou import YigitChristoforouContact

__all__ = ["Sphere", "law_for_sphere", "softer_yield_strength"]


def _attribute(material, attribute, role):
    try:
        return getattr(material, attribute)
    except AttributeError:
        raise ValueError(
            f"{role} = {material!r} has no attribute {attribute!r}: a material needs "
            "youngs_modulus [Pa], poisson_ratio [-], density [kg/m^3] and optionally yield_strength [Pa]"
        ) from None


def _check_elastic_material(material, role, allow_rigid=False):
    modulus = _attribute(material, "youngs_modulus", role)
    if allow_rigid and np.all(np.asarray(modulus, dtype=float) == np.inf):
        pass  # a rigid body
    else:
        require_positive(f"{role}.youngs_modulus", modulus, "Pa")
    require_in_range(f"{role}.poisson_ratio", _attribute(material, "poisson_ratio", role), -1.0, 0.5,
                     low_inclusive=False, high_inclusive=False)


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
        _check_elastic_material(self.material, "material")
        if self.mass is None:
            density = _attribute(self.material, "density", "material")
            require_positive("material.density", density, "kg/m^3")
            object.__setattr__(self, "mass", float(density) * 4.0 / 3.0 * np.pi * float(self.radius) ** 3)
        else:
            require_positive("mass", self.mass, "kg")

    @property
    def yield_strength(self):
        """Yield strength of the sphere's material [Pa], or ``None``."""
        return getattr(self.material, "yield_strength", None)


def softer_yield_strength(*materials):
    """Smallest yield strength [Pa] among materials that define one (seed 001 eq 9).

    Materials whose ``yield_strength`` is ``None`` or missing are taken not to yield.
    Raises ``ValueError`` if none of them defines a yield strength.
    """
    values = [getattr(m, "yield_strength", None) for m in materials]
    values = [v for v in values if v is not None]
    if not values:
        raise ValueError(
            "yield_strength is missing: neither the sphere's nor the target's material defines "
            "a yield_strength [Pa] (valid range (0, inf)); set it on a material or pass "
            "yield_strength=... to law_for_sphere"
        )
    for value in values:
        require_positive("yield_strength", value, "Pa")
    return float(min(values))


def law_for_sphere(name: str, sphere: Sphere, target_material, **options) -> ContactLaw:
    """Build the registered contact law ``name`` for ``sphere`` striking a target.

    Parameters
    ----------
    name : str
        A registered law (``impactmaps.contact.available_contact_laws()``).
    sphere : Sphere
        The impactor.
    target_material : material-like
        Target material (``youngs_modulus`` [Pa], ``poisson_ratio`` [-], optional
        ``yield_strength`` [Pa]); ``youngs_modulus = inf`` is a rigid target.
    **options
        ``target_radius`` [m] (default ``inf``, a flat: the target's curvature at the
        impact point, ``1/R = 1/R_sphere + 1/R_target``); ``yield_strength`` [Pa]
        overriding the softer material's (e.g. ``2 S_u`` for composites, seed 001);
        for ``"stronge"`` also ``yield_pressure_factor``, ``plastic_pressure_factor``,
        ``plastic_indentation_ratio``.

    Returns
    -------
    ContactLaw
        ``"hertz"``: ``K_h = (4/3) sqrt(R) E*`` (eqs 7–8). ``"yigit-christoforou"``:
        K_h and ``α_y = 0.68 π² S_y² R/E*²`` (eq 9) with S_y the smaller yield
        strength of the two bodies. ``"linear"``: ``K = K_y = 1.5 K_h sqrt(α_y)`` (eqs
        10, 18), which needs a yield strength. ``"stronge"``: E*, R, S_y and the
        constants.

    Raises
    ------
    ValueError
        Unknown law, a law with no sphere builder, an unknown option, a missing yield
        strength, or invalid material data.
    """
    law_class = contact_law_class(name)  # ValueError listing the known laws
    if not isinstance(sphere, Sphere):
        raise ValueError(f"sphere = {sphere!r} is not a Sphere")
    _check_elastic_material(target_material, "target_material", allow_rigid=True)
    options = dict(options)
    target_radius = options.pop("target_radius", np.inf)
    yield_override = options.pop("yield_strength", None)
    allowed = {"stronge": {"yield_pressure_factor", "plastic_pressure_factor", "plastic_indentation_ratio"}}
    unknown = set(options) - allowed.get(name, set())
    if unknown:
        valid = sorted({"target_radius", "yield_strength"} | allowed.get(name, set()))
        raise ValueError(f"options {sorted(unknown)} are not known for law {name!r}: valid options are {valid}")

    modulus = float(effective_modulus(
        sphere.material.youngs_modulus, sphere.material.poisson_ratio,
        target_material.youngs_modulus, target_material.poisson_ratio,
    ))
    radius = float(effective_radius(sphere.radius, target_radius))

    def strength():
        if yield_override is not None:
            require_positive("yield_strength", yield_override, "Pa")
            return float(yield_override)
        return softer_yield_strength(sphere.material, target_material)

    if law_class is HertzContact:
        return HertzContact(float(hertz_stiffness(modulus, radius)))
    if law_class is YigitChristoforouContact:
        return YigitChristoforouContact.from_properties(modulus, radius, strength())
    if law_class is LinearContact:
        plastic = YigitChristoforouContact.from_properties(modulus, radius, strength())
        return LinearContact(float(plastic.linearised_stiffness))
    if law_class is StrongeContact:
        return StrongeContact(modulus, radius, strength(), **options)
    raise ValueError(
        f"contact law {name!r} has no sphere builder in law_for_sphere: valid values are "
        "'hertz', 'linear', 'stronge', 'yigit-christoforou' (construct other laws directly)"
    )

