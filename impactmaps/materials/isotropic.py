"""A homogeneous isotropic solid (metals; the impactor)."""

from __future__ import annotations

from dataclasses import dataclass

from .._checks import require_in_range, require_positive
from ._common import optional_yield_strength, require_scalar
from .ply import Ply

__all__ = ["IsotropicMaterial"]


# ---------------------------------------------------------------------------------
# Isotropic material
# ---------------------------------------------------------------------------------
@dataclass(frozen=True)
class IsotropicMaterial:
    """A homogeneous, linearly elastic, isotropic material.

    Parameters
    ----------
    youngs_modulus : float
        Young's modulus E [Pa], > 0.
    poisson_ratio : float
        Poisson ratio ν [-], −1 < ν < 0.5.
    density : float
        Mass density ρ [kg/m³], > 0.
    yield_strength : float, optional
        Uniaxial yield strength S_y [Pa], > 0 (the plastic contact laws'); ``None``: unknown.
    name : str, optional
        Label.
    """

    youngs_modulus: float
    poisson_ratio: float
    density: float
    yield_strength: float | None = None
    name: str = ""

    def __post_init__(self):
        youngs = require_scalar("youngs_modulus", self.youngs_modulus, "Pa")
        require_positive("youngs_modulus", youngs, "Pa")
        poisson = require_scalar("poisson_ratio", self.poisson_ratio)
        require_in_range("poisson_ratio", poisson, -1.0, 0.5,
                         low_inclusive=False, high_inclusive=False)
        density = require_scalar("density", self.density, "kg/m^3")
        require_positive("density", density, "kg/m^3")
        object.__setattr__(self, "youngs_modulus", youngs)
        object.__setattr__(self, "poisson_ratio", poisson)
        object.__setattr__(self, "density", density)
        object.__setattr__(self, "yield_strength", optional_yield_strength(self.yield_strength))

    @property
    def shear_modulus(self) -> float:
        """Shear modulus G = E / (2(1 + ν)) [Pa]."""
        return self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))

    @property
    def plate_bending_modulus(self) -> float:
        """Plane-stress (plate) modulus E / (1 − ν²) [Pa]; D = this × h³/12."""
        return self.youngs_modulus / (1.0 - self.poisson_ratio**2)

    def as_ply(self, thickness: float, angle_deg: float = 0.0) -> Ply:
        """This material as an isotropic :class:`Ply` of the given thickness [m] (CLT then
        reproduces the isotropic plate)."""
        shear = self.shear_modulus
        return Ply(
            longitudinal_modulus=self.youngs_modulus,
            transverse_modulus=self.youngs_modulus,
            shear_modulus=shear,
            poisson_ratio=self.poisson_ratio,
            density=self.density,
            thickness=thickness,
            angle_deg=angle_deg,
            transverse_shear_modulus_13=shear,
            transverse_shear_modulus_23=shear,
            name=self.name,
        )
