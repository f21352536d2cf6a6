"""The named materials, each with its source."""

from __future__ import annotations

from .._checks import require_choice
from .isotropic import IsotropicMaterial
from .ply import Ply

__all__ = ["CATALOGUE", "available_materials", "material"]


# ---------------------------------------------------------------------------------
#: Named materials. Sources (stored public copies consulted; see each entry):
CATALOGUE: dict = {
    # Eurocode 3 structural steel, grade S235 (EN 10025-2), all four numbers from one
    # standard: EN 1993-1-1:2005 §3.2.6 gives E = 210 000 MPa, ν = 0.30, and the
    # density 7850 kg/m³ (unit weight 78.5 kN/m³, EN 1991-1-1 Table A.4); yield
    # f_y = 235 MPa for t ≤ 40 mm (EN 1993-1-1 Table 3.1). Checked against the design
    # table "Eurocode 3 — Table of design material properties for structural steel"
    # (eurocodeapplied.com, reproduced at https://it.scribd.com/document/470650995/stee116).
    # (ASTM A36 would give E = 200 GPa, ν = 0.26, S_y = 250 MPa minimum.)
    "structural-steel": IsotropicMaterial(
        youngs_modulus=210e9, poisson_ratio=0.30, density=7850.0,
        yield_strength=235e6, name="structural steel S235 (EN 1993-1-1)",
    ),
    # Aluminium 6061-T6: Aluminum Association typical values as listed by MatWeb/ASM:
    # E = 68.9 GPa (average of tension and compression), ν = 0.33, ρ = 2.70 g/cm³,
    # tensile yield 276 MPa. Checked against https://www.mfgproto.com/aluminum-6061-t6-data-sheet/
    # and https://www.glemco.com/capabilities/material-expertise/aluminum-6061-t6/ (same AA data).
    "aluminium-6061-t6": IsotropicMaterial(
        youngs_modulus=68.9e9, poisson_ratio=0.33, density=2700.0,
        yield_strength=276e6, name="aluminium 6061-T6",
    ),
    # T300/934 carbon/epoxy as used in the impact literature (Sun & Chen, J. Appl. Mech.
    # 52 (1985); Qian & Swanson, Comput. Struct. 1990): E1 = 120 GPa, E2 = 7.9 GPa,
    # G12 = 5.5 GPa, ν12 = 0.30, ρ = 1580 kg/m³.
    # UNVERIFIED: no stored copy of either paper or of a table with these numbers could
    # be found; other sources give rather different T300/934 data (e.g. E1 = 19 Msi =
    # 131 GPa, E2 = 1.5 Msi = 10.3 GPa). G13 = G23 = G12 by default (see Ply).
    "t300-934": Ply(
        longitudinal_modulus=120e9, transverse_modulus=7.9e9, shear_modulus=5.5e9,
        poisson_ratio=0.30, density=1580.0, name="T300/934 (unverified)",
    ),
    # AS4/3501-6 carbon/epoxy, lamina data of the World-Wide Failure Exercise (Soden,
    # Hinton & Kaddour, Compos. Sci. Technol. 58 (1998) 1011–1022): E1 = 126 GPa,
    # E2 = 11 GPa, G12 = 6.6 GPa, ν12 = 0.28. Verified against two independent stored
    # copies: Anand, Kamrin & Govindjee, Introduction to Mechanics of Solids (OUP 2022),
    # example 23.2 (github.com/sanjayg0/ims, MainBook/ex23_2.m), and Barbero, Introduction
    # to Composite Materials Design, example 7.9. Density 1600 kg/m³ is UNVERIFIED
    # (typical for Vf ≈ 0.6 carbon/epoxy; one secondary source lists 1580).
    "as4-3501-6": Ply(
        longitudinal_modulus=126e9, transverse_modulus=11e9, shear_modulus=6.6e9,
        poisson_ratio=0.28, density=1600.0, name="AS4/3501-6",
    ),
}


def available_materials() -> tuple:
    """Names in :data:`CATALOGUE`, sorted."""
    return tuple(sorted(CATALOGUE))


def material(name: str):
    """The catalogue material ``name`` (an :class:`IsotropicMaterial` or a :class:`Ply`).

    Sources (full citations beside each entry in :data:`CATALOGUE`):

    * ``structural-steel`` — S235, EN 1993-1-1:2005 §3.2.6 and Table 3.1
      (E = 210 GPa, ν = 0.30, S_y = 235 MPa), EN 1991-1-1 Table A.4 (ρ = 7850 kg/m³);
    * ``aluminium-6061-t6`` — Aluminum Association typical values (MatWeb/ASM):
      E = 68.9 GPa, ν = 0.33, ρ = 2700 kg/m³, S_y = 276 MPa;
    * ``t300-934`` — the values used by Sun & Chen (1985) and Qian & Swanson (1990) as
      quoted in the impact literature; **unverified** against the papers (see the entry);
    * ``as4-3501-6`` — World-Wide Failure Exercise lamina data (Soden, Hinton &
      Kaddour, Compos. Sci. Technol. 58 (1998) 1011–1022): E1 = 126 GPa, E2 = 11 GPa,
      G12 = 6.6 GPa, ν12 = 0.28; density 1600 kg/m³ **unverified**.

    Raises
    ------
    ValueError
        If ``name`` is not in :data:`CATALOGUE`; the message lists the known names.
    """
    require_choice("material name", name, available_materials())
    return CATALOGUE[name]
