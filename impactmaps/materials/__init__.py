"""Target materials: isotropic solids, unidirectional plies, laminates, a small catalogue.

SI units (Pa, kg/m³, m). :class:`IsotropicMaterial` (metals; the impactor), :class:`Ply`
(a unidirectional lamina with its fibre angle) and :class:`Laminate` (a stack of plies
with the A, B, D and transverse-shear stiffnesses of classical lamination theory).
Plies are listed from the struck face; the sign conventions and the laminate's contact
modulus: docs/physics.rst, "Laminates".
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
