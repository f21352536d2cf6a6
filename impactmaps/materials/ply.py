"""One unidirectional, transversely isotropic lamina with its fibre angle.

Conventions: docs/physics.rst, "Laminates".
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from .._checks import require_in_range, require_positive
from ._common import DEFAULT_PLY_THICKNESS, require_scalar

__all__ = ["Ply"]


@dataclass(frozen=True)
class Ply:
    """One unidirectional lamina (orthotropic in its plane, plane stress).

    Parameters
    ----------
    longitudinal_modulus : float
        E1, Young's modulus along the fibres [Pa], > 0.
    transverse_modulus : float
        E2, Young's modulus across the fibres [Pa], > 0 (also the out-of-plane E3).
    shear_modulus : float
        G12, in-plane shear modulus [Pa], > 0.
    poisson_ratio : float
        ν12, major Poisson ratio [-], ``ν12² < E1/E2``.
    density : float
        ρ [kg/m³], > 0.
    thickness : float, optional
        Ply thickness t [m], > 0; default :data:`DEFAULT_PLY_THICKNESS` (0.125 mm).
    angle_deg : float, optional
        Fibre angle θ from the laminate x axis [degrees], default 0.
    transverse_shear_modulus_13 : float, optional
        G13 [Pa], > 0. Default ``G12`` (exact for a transversely isotropic ply).
    transverse_shear_modulus_23 : float, optional
        G23 [Pa], > 0. Default ``G12``, a simplifying assumption (for a transversely
        isotropic ply ``G23 = E2 / (2(1 + ν23))``); give it when known.
    name : str, optional
        Label.
    """

    longitudinal_modulus: float
    transverse_modulus: float
    shear_modulus: float
    poisson_ratio: float
    density: float
    thickness: float = DEFAULT_PLY_THICKNESS
    angle_deg: float = 0.0
    transverse_shear_modulus_13: float | None = None
    transverse_shear_modulus_23: float | None = None
    name: str = ""

    def __post_init__(self):
        values = {}
        for attribute, unit in (
            ("longitudinal_modulus", "Pa"),
            ("transverse_modulus", "Pa"),
            ("shear_modulus", "Pa"),
            ("density", "kg/m^3"),
            ("thickness", "m"),
        ):
            value = require_scalar(attribute, getattr(self, attribute), unit)
            require_positive(attribute, value, unit)
            values[attribute] = value
        limit = math.sqrt(values["longitudinal_modulus"] / values["transverse_modulus"])
        poisson = require_scalar("poisson_ratio", self.poisson_ratio)
        # 1 - ν12 ν21 > 0  <=>  |ν12| < sqrt(E1/E2)
        require_in_range("poisson_ratio", poisson, -limit, limit,
                         low_inclusive=False, high_inclusive=False)
        values["poisson_ratio"] = poisson
        values["angle_deg"] = require_scalar("angle_deg", self.angle_deg, "deg")
        for attribute in ("transverse_shear_modulus_13", "transverse_shear_modulus_23"):
            given = getattr(self, attribute)
            if given is None:
                values[attribute] = values["shear_modulus"]
            else:
                value = require_scalar(attribute, given, "Pa")
                require_positive(attribute, value, "Pa")
                values[attribute] = value
        for attribute, value in values.items():
            object.__setattr__(self, attribute, value)

    # -- engineering constants --------------------------------------------------------
    @property
    def minor_poisson_ratio(self) -> float:
        """ν21 = ν12 E2 / E1 [-] (reciprocity)."""
        return self.poisson_ratio * self.transverse_modulus / self.longitudinal_modulus

    @property
    def mass_per_area(self) -> float:
        """ρ t [kg/m²]."""
        return self.density * self.thickness

    @property
    def is_isotropic(self) -> bool:
        """True if E1 = E2, G12 = E1/(2(1 + ν12)) and G13 = G23 = G12 (to 1e-9 relative)."""
        close = lambda a, b: math.isclose(a, b, rel_tol=1e-9)  # noqa: E731
        return (
            close(self.longitudinal_modulus, self.transverse_modulus)
            and close(self.shear_modulus,
                      self.longitudinal_modulus / (2.0 * (1.0 + self.poisson_ratio)))
            and close(self.transverse_shear_modulus_13, self.shear_modulus)
            and close(self.transverse_shear_modulus_23, self.shear_modulus)
        )

    # -- stiffness matrices -------------------------------------------------------------
    @property
    def reduced_stiffness(self) -> np.ndarray:
        """Plane-stress reduced stiffness Q in the ply axes (1, 2, 12), 3×3 [Pa].

        ``Q11 = E1/(1−ν12ν21)``, ``Q22 = E2/(1−ν12ν21)``, ``Q12 = ν12 E2/(1−ν12ν21)``,
        ``Q66 = G12`` (Jones 1999, eq. 2.61).
        """
        e1, e2, nu12 = self.longitudinal_modulus, self.transverse_modulus, self.poisson_ratio
        denominator = 1.0 - nu12 * self.minor_poisson_ratio
        q11 = e1 / denominator
        q22 = e2 / denominator
        q12 = nu12 * e2 / denominator
        return np.array([[q11, q12, 0.0], [q12, q22, 0.0], [0.0, 0.0, self.shear_modulus]])

    @property
    def transformed_reduced_stiffness(self) -> np.ndarray:
        """Reduced stiffness Q̄ in the laminate axes (x, y, xy) for the ply angle, 3×3 [Pa].

        Standard transformation (Jones 1999, eq. 2.85), with m = cos θ, n = sin θ.
        """
        q = self.reduced_stiffness
        q11, q12, q22, q66 = q[0, 0], q[0, 1], q[1, 1], q[2, 2]
        theta = math.radians(self.angle_deg)
        m, n = math.cos(theta), math.sin(theta)
        m2, n2 = m * m, n * n
        qb11 = q11 * m2 * m2 + 2.0 * (q12 + 2.0 * q66) * m2 * n2 + q22 * n2 * n2
        qb22 = q11 * n2 * n2 + 2.0 * (q12 + 2.0 * q66) * m2 * n2 + q22 * m2 * m2
        qb12 = (q11 + q22 - 4.0 * q66) * m2 * n2 + q12 * (m2 * m2 + n2 * n2)
        qb66 = (q11 + q22 - 2.0 * q12 - 2.0 * q66) * m2 * n2 + q66 * (m2 * m2 + n2 * n2)
        qb16 = (q11 - q12 - 2.0 * q66) * m2 * m * n + (q12 - q22 + 2.0 * q66) * m * n2 * n
        qb26 = (q11 - q12 - 2.0 * q66) * m * n2 * n + (q12 - q22 + 2.0 * q66) * m2 * m * n
        return np.array([[qb11, qb12, qb16], [qb12, qb22, qb26], [qb16, qb26, qb66]])

    @property
    def transverse_shear_stiffness(self) -> np.ndarray:
        """Transverse-shear stiffness [[Q̄44, Q̄45], [Q̄45, Q̄55]] in laminate axes [Pa].

        ``Q̄44 = G23 m² + G13 n²`` (y–z), ``Q̄55 = G13 m² + G23 n²`` (x–z),
        ``Q̄45 = (G13 − G23) m n`` (rotation of the shear strains γ13, γ23 by θ).
        """
        theta = math.radians(self.angle_deg)
        m, n = math.cos(theta), math.sin(theta)
        g13, g23 = self.transverse_shear_modulus_13, self.transverse_shear_modulus_23
        q44 = g23 * m * m + g13 * n * n
        q55 = g13 * m * m + g23 * n * n
        q45 = (g13 - g23) * m * n
        return np.array([[q44, q45], [q45, q55]])

    def rotated(self, angle_deg: float) -> "Ply":
        """A copy of this ply with fibre angle ``angle_deg`` [degrees]."""
        return replace(self, angle_deg=angle_deg)
