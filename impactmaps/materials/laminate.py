"""Laminates (stacks of :class:`~impactmaps.materials.ply.Ply`) with the stiffness matrices of classical lamination theory.

Conventions: docs/physics.rst, "Laminates".
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass, field

import numpy as np

from .._checks import require_finite
from ._common import SPECIALLY_ORTHOTROPIC_RTOL, optional_yield_strength
from .isotropic import IsotropicMaterial
from .ply import Ply

__all__ = [ "Laminate"]


# ---------------------------------------------------------------------------------
# Laminate
# ---------------------------------------------------------------------------------
def _read_only(array: np.ndarray) -> np.ndarray:
    array.setflags(write=False)
    return array


@dataclass(frozen=True)
class Laminate:
    """A stack of plies, described by classical lamination theory.

    Parameters
    ----------
    plies : sequence of Ply
        Plies from the struck face (z = −h/2) to the back face (z = +h/2) (an isotropic
        plate: one isotropic ply, :meth:`from_isotropic`).
    name : str, optional
        Label.
    yield_strength : float, optional
        Strength S_y [Pa] used by the elastic–plastic contact laws (for composites
        Christoforou & Yigit 1998 take ``S_y = 2 S_u``); ``None`` if not given.

    Notes
    -----
    ``A = Σ Q̄_k (z_k − z_{k−1})``, ``B = ½ Σ Q̄_k (z_k² − z_{k−1}²)``,
    ``D = ⅓ Σ Q̄_k (z_k³ − z_{k−1}³)`` (Jones 1999, eq. 4.28); transverse shear
    ``A44 = Σ Q̄44_k t_k``, ``A55 = Σ Q̄55_k t_k`` (no shear correction factor).
    """

    plies: tuple
    name: str = ""
    yield_strength: float | None = None
    _cache: dict = field(default_factory=dict, init=False, repr=False, compare=False)

    def __post_init__(self):
        plies = tuple(self.plies) if isinstance(self.plies, Iterable) else (self.plies,)
        if len(plies) == 0:
            raise ValueError("plies must contain at least one Ply, got an empty sequence")
        for index, ply in enumerate(plies):
            if not isinstance(ply, Ply):
                raise ValueError(f"plies[{index}] = {ply!r} is not a Ply")
        object.__setattr__(self, "plies", plies)
        object.__setattr__(self, "yield_strength", optional_yield_strength(self.yield_strength))

    # -- constructors -------------------------------------------------------------------
    @classmethod
    def from_layup(cls, ply: Ply, angles_deg, symmetric: bool = True, name: str = "",
                   yield_strength: float | None = None) -> "Laminate":
        """Laminate of identical plies at the given angles.

        Parameters
        ----------
        ply : Ply
            The ply material and thickness (its own angle is ignored).
        angles_deg : sequence of float
            Fibre angles [degrees] from the struck face: to the mid-plane when ``symmetric``
            (then mirrored: ``[0, 90]`` gives ``[0/90/90/0]``), else through the thickness.
        symmetric : bool, optional
            Mirror the angles about the mid-plane (default True).
        name, yield_strength : optional
            As for :class:`Laminate`.
        """
        if not isinstance(ply, Ply):
            raise ValueError(f"ply = {ply!r} is not a Ply")
        angles = [float(a) for a in np.atleast_1d(np.asarray(angles_deg, dtype=float))]
        if not angles:
            raise ValueError("angles_deg must contain at least one angle, got none")
        require_finite("angles_deg", angles, "deg")
        if symmetric:
            angles = angles + angles[::-1]
        return cls(tuple(ply.rotated(a) for a in angles), name=name,
                   yield_strength=yield_strength)

    @classmethod
    def from_isotropic(cls, material: IsotropicMaterial, thickness: float,
                       name: str = "") -> "Laminate":
        """A homogeneous isotropic plate of thickness ``thickness`` [m] as a one-ply laminate (with
        the material's yield strength).
        """
        if not isinstance(material, IsotropicMaterial):
            raise ValueError(f"material = {material!r} is not an IsotropicMaterial")
        return cls((material.as_ply(thickness),), name=name or material.name,
                   yield_strength=material.yield_strength)

    # -- geometry and mass --------------------------------------------------------------
    @property
    def thickness(self) -> float:
        """Total thickness h [m]."""
        return float(sum(p.thickness for p in self.plies))

    @property
    def interfaces(self) -> np.ndarray:
        """Ply interface coordinates z_0 = −h/2, …, z_n = +h/2 [m], shape (n+1,)."""
        if "z" not in self._cache:
            z = np.concatenate(([0.0], np.cumsum([p.thickness for p in self.plies])))
            self._cache["z"] = _read_only(z - 0.5 * z[-1])
        return self._cache["z"]

    @property
    def angles_deg(self) -> tuple:
        """Fibre angles of the plies [degrees], struck face first."""
        return tuple(p.angle_deg for p in self.plies)

    @property
    def mass_per_area(self) -> float:
        """Mass per unit area ρh = Σ ρ_k t_k [kg/m²]."""
        return float(sum(p.density * p.thickness for p in self.plies))

    @property
    def density(self) -> float:
        """Thickness-averaged density (mass_per_area / thickness) [kg/m³]."""
        return self.mass_per_area / self.thickness

    @property
    def rotary_inertia_per_area(self) -> float:
        """Rotary inertia per unit area Σ ρ_k (z_k³ − z_{k−1}³)/3 [kg] (= ρh³/12 if homogeneous)."""
        z = self.interfaces
        return float(sum(p.density * (z[k + 1] ** 3 - z[k] ** 3) / 3.0
                         for k, p in enumerate(self.plies)))

    # -- stiffness ----------------------------------------------------------------------
    def _stiffness(self):
        if "A" not in self._cache:
            z = self.interfaces
            a = np.zeros((3, 3))
            b = np.zeros((3, 3))
            d = np.zeros((3, 3))
            shear = np.zeros((2, 2))
            for k, ply in enumerate(self.plies):
                qbar = ply.transformed_reduced_stiffness
                a += qbar * (z[k + 1] - z[k])
                b += qbar * (z[k + 1] ** 2 - z[k] ** 2) / 2.0
                d += qbar * (z[k + 1] ** 3 - z[k] ** 3) / 3.0
                shear += ply.transverse_shear_stiffness * (z[k + 1] - z[k])
            self._cache.update(A=_read_only(a), B=_read_only(b), D=_read_only(d),
                               S=_read_only(shear))
        return self._cache

    @property
    def A(self) -> np.ndarray:  # noqa: N802 (the standard CLT symbol)
        """Extensional stiffness matrix A (x, y, xy), 3×3 [N/m]."""
        return self._stiffness()["A"]

    @property
    def B(self) -> np.ndarray:  # noqa: N802
        """Extension–bending coupling matrix B, 3×3 [N]."""
        return self._stiffness()["B"]

    @property
    def D(self) -> np.ndarray:  # noqa: N802
        """Bending stiffness matrix D, 3×3 [N·m]."""
        return self._stiffness()["D"]

    @property
    def transverse_shear_stiffness(self) -> np.ndarray:
        """[[A44, A45], [A45, A55]] [N/m], without the shear correction factor."""
        return self._stiffness()["S"]

    @property
    def D11(self) -> float:  # noqa: N802
        """Bending stiffness D11 [N·m]."""
        return float(self.D[0, 0])

    @property
    def D22(self) -> float:  # noqa: N802
        """Bending stiffness D22 [N·m]."""
        return float(self.D[1, 1])

    @property
    def D12(self) -> float:  # noqa: N802
        """Bending stiffness D12 [N·m]."""
        return float(self.D[0, 1])

    @property
    def D66(self) -> float:  # noqa: N802
        """Twisting stiffness D66 [N·m]."""
        return float(self.D[2, 2])

    @property
    def A44(self) -> float:  # noqa: N802
        """Transverse shear stiffness in the y–z plane, Σ Q̄44 t [N/m]."""
        return float(self.transverse_shear_stiffness[0, 0])

    @property
    def A55(self) -> float:  # noqa: N802
        """Transverse shear stiffness in the x–z plane, Σ Q̄55 t [N/m]."""
        return float(self.transverse_shear_stiffness[1, 1])

    @property
    def A45(self) -> float:  # noqa: N802
        """Transverse shear coupling Σ Q̄45 t [N/m] (zero for cross-ply or G13 = G23)."""
        return float(self.transverse_shear_stiffness[0, 1])

    @property
    def effective_bending_stiffness(self) -> float:
        """Effective plate stiffness D* = ½(D12 + 2 D66 + sqrt(D11 D22)) [N·m] (Christoforou & Yigit 1998, eq 31)."""
        return 0.5 * (self.D12 + 2.0 * self.D66 + math.sqrt(self.D11 * self.D22))

    def coupling_ratios(self) -> dict:
        """Relative size [-] of the terms a specially orthotropic model neglects: ``"D16"``,
        ``"D26"`` (``|D16|/sqrt(D11 D22)`` …), ``"B"`` (``max|B_ij| / sqrt(max|A_ij| max|D_ij|)``)
        and ``"A45"`` (``|A45|/sqrt(A44 A55)``).
        """
        d_scale = math.sqrt(self.D11 * self.D22)
        b_scale = math.sqrt(np.max(np.abs(self.A)) * np.max(np.abs(self.D)))
        return {
            "D16": abs(float(self.D[0, 2])) / d_scale,
            "D26": abs(float(self.D[1, 2])) / d_scale,
            "B": float(np.max(np.abs(self.B))) / b_scale,
            "A45": abs(self.A45) / math.sqrt(self.A44 * self.A55),
        }

    @property
    def is_specially_orthotropic(self) -> bool:
        """True if D16, D26, B and A45 vanish to :data:`SPECIALLY_ORTHOTROPIC_RTOL` (where the
        plate and beam equations of Christoforou & Yigit 1998 (13)–(17) are exact).
        """
        return all(v <= SPECIALLY_ORTHOTROPIC_RTOL for v in self.coupling_ratios().values())

    # -- contact ------------------------------------------------------------------------
    @property
    def youngs_modulus(self) -> float:
        """Contact modulus of the struck face [Pa]: E2 of ``plies[0]`` (E for an isotropic ply)."""
        return self.plies[0].transverse_modulus

    @property
    def poisson_ratio(self) -> float:
        """Poisson ratio to use with :attr:`youngs_modulus` in ``1/E*``: 0 for a composite struck
        face (Tan & Sun's ``1/E2``), the ply's own ν for an isotropic one.
        """
        top = self.plies[0]
        return top.poisson_ratio if top.is_isotropic else 0.0


# ---------------------------------------------------------------------------------
# Catalogue
