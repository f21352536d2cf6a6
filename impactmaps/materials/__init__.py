"""Target materials: isotropic solids, unidirectional plies, laminates, a small catalogue.

Everything is in SI units (Pa, kg/m³, m). Three kinds of object:

* :class:`IsotropicMaterial` — a homogeneous isotropic solid (metals; the impactor).
* :class:`Ply` — one unidirectional, transversely isotropic lamina with its fibre angle.
* :class:`Laminate` — a stack of plies, with the stiffness matrices of classical
  lamination theory (CLT) that the beam and plate equations of Christoforou & Yigit 1998 (13)–(17) need:
  ``A``, ``B``, ``D`` (3×3) and the transverse-shear stiffnesses ``A44``, ``A55``.

Conventions
-----------
* Plies are listed from the **struck face** to the back face. The thickness coordinate
  ``z`` is measured from the mid-plane *in the direction of impact*: the struck face is
  ``z = −h/2`` and ``plies[0]`` occupies ``[−h/2, −h/2 + t_0]`` (z positive "downward",
  ply 1 at the top, as in Jones, *Mechanics of Composite Materials*, 2nd ed., 1999, §4.2).
  Only the sign of ``B`` depends on this choice.
* Ply angle θ is measured from the laminate x axis to the fibre direction 1, positive
  anticlockwise seen from the struck face. Engineering shear strains (γ = 2ε).
* Transverse shear: index 4 is the y–z plane, index 5 the x–z plane (A44 pairs with ψ_y
  and A55 with ψ_x, Christoforou & Yigit 1998 (13)–(15)). The shear correction factor k is *not* included;
  the targets apply it.

Contact with a sphere
---------------------
A laminate is transversely isotropic through the thickness only approximately; for the
Hertz contact stiffness the usual engineering model (Yang & Sun 1982, ASTM STP 787;
Tan & Sun, J. Appl. Mech. 52 (1985) 6–12) treats the laminate as a transversely isotropic
half-space whose contact compliance is ``1/E_2`` (the transverse modulus of the ply),
i.e. ``K_h = (4/3) sqrt(R) / [(1 − ν_s²)/E_s + 1/E_2]``. This is the isotropic formula
(Christoforou & Yigit 1998, eq 8) with ``E_t = E_2`` and ``ν_t = 0``, which is what
:attr:`Laminate.youngs_modulus` and :attr:`Laminate.poisson_ratio` return.
Independent support: Wu & Yen (J. Appl. Mech. 61 (1994) 60–66), from an exact 3-D
anisotropic Green's function, find the force–indentation relation "approximately
proportional to the out-of-plane Young's modulus" and insensitive to in-plane moduli
and stacking sequence (abstract, https://acnpsearch.tweb-dev.unibo.it/singlejournalindex/40457165).
(The Tan & Sun formula itself was not checked against a stored copy of the paper.)
"""

from __future__ import annotations

from ._common import DEFAULT_PLY_THICKNESS, SPECIALLY_ORTHOTROPIC_RTOL
from .catalogue import CATALOGUE, SOURCES, available_materials, material
from .isotropic import IsotropicMaterial
from .laminate import Laminate
from .ply import Ply

__all__ = [
    "DEFAULT_PLY_THICKNESS",
    "SPECIALLY_ORTHOTROPIC_RTOL",
    "IsotropicMaterial",
    "Ply",
    "Laminate",
    "CATALOGUE",
    "SOURCES",
    "material",
    "available_materials",
]
