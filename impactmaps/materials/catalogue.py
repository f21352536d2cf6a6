"""The named materials, each with its source."""

from __future__ import annotations

from .._checks import require_choice
from .isotropic import IsotropicMaterial
from ._common import DEFAULT_PLY_THICKNESS
from .ply import Ply

__all__ = ["CATALOGUE", "SOURCES", "available_materials", "material"]


# ---------------------------------------------------------------------------------
#: Isotropic entries, one a row: E [Pa], ν [-], ρ [kg/m³], yield strength S_y [Pa] (``None``: brittle,
#: the plastic laws take the other body's), label. Sources (stored public copies consulted): see each entry.
_ISOTROPIC: dict = {
    # Eurocode 3 structural steel, grade S235 (EN 10025-2), all four numbers from one
    # standard: EN 1993-1-1:2005 §3.2.6 gives E = 210 000 MPa, ν = 0.30, and the
    # density 7850 kg/m³ (unit weight 78.5 kN/m³, EN 1991-1-1 Table A.4); yield
    # f_y = 235 MPa for t ≤ 40 mm (EN 1993-1-1 Table 3.1). Checked against the design
    # table "Eurocode 3 — Table of design material properties for structural steel"
    # (eurocodeapplied.com, reproduced at https://it.scribd.com/document/470650995/stee116).
    # (ASTM A36 would give E = 200 GPa, ν = 0.26, S_y = 250 MPa minimum.)
    "structural-steel": (210e9, 0.30, 7850.0, 235e6, "structural steel S235 (EN 1993-1-1)"),
    # Aluminium 6061-T6: Aluminum Association typical values as listed by MatWeb/ASM:
    # E = 68.9 GPa (average of tension and compression), ν = 0.33, ρ = 2.70 g/cm³,
    # tensile yield 276 MPa. Checked against https://www.mfgproto.com/aluminum-6061-t6-data-sheet/
    # and https://www.glemco.com/capabilities/material-expertise/aluminum-6061-t6/ (same AA data).
    "aluminium-6061-t6": (68.9e9, 0.33, 2700.0, 276e6, "aluminium 6061-T6"),
    # Structural steel S355 (EN 10025-2): E, ν and ρ as S235 above (EN 1993-1-1 §3.2.6, the
    # same for every grade); f_y = 355 MPa for t ≤ 16 mm (EN 10025-2 Table 7, S355JR/J0/J2/K2;
    # 345 MPa for 16 < t ≤ 40 mm), read at https://readle.co.uk/references/steel-grades-eurocodes.php.
    "steel-s355": (210e9, 0.30, 7850.0, 355e6, "structural steel S355 (EN 10025-2, t ≤ 16 mm)"),
    # AISI 304 austenitic stainless, annealed: ASM Material Data Sheet "AISI Type 304 Stainless
    # Steel" (MatWeb; stored copy https://www.scribd.com/document/416534641/304-Stainless-Steel-pdf):
    # ρ = 8.00 g/cm³, tensile yield 215 MPa (0.2 % offset), E = 193–200 GPa (the lower value,
    # also that of https://alloysintl.com/?p=6124), ν = 0.29.
    "stainless-304": (193e9, 0.29, 8000.0, 215e6, "stainless steel AISI 304 (annealed)"),
    # AISI 52100 bearing (chrome) steel, through-hardened balls (HRC 60–67): a ball maker's
    # sheet "AISI 52100 Chrome Steel" (https://ja.scribd.com/document/252517093): E = 29.5e6 psi
    # (203.4 GPa), ρ = 0.283 lb/in³ (7830 kg/m³), yield 295 000 psi (2034 MPa). ν = 0.295 is
    # the value of hardened tool steel in the ASM Metals Handbook Desk Edition's table of
    # elastic constants (reproduced at web.mst.edu/~jthomas/.../al_properties.html); 52100
    # data sheets give 0.27–0.30 (https://www.stindia.com/article/difference-between/
    # difference-between-52100-e52100-steel.html): ν is generic, not measured on 52100.
    "bearing-steel-52100": (203.4e9, 0.295, 7830.0, 2034e6, "bearing steel AISI 52100 (hardened balls)"),
    # AISI 440C martensitic stainless, hardened (1900 °F, oil quench, tempered 600 °F): Rolled
    # Alloys data sheet "440C Stainless" (stored copy https://htpipe.com/product-material/
    # stainless-steel/stainless-steel-440c.html): ρ = 0.275 lb/in³ (7612 kg/m³), dynamic
    # modulus 30.4e6 psi (209.6 GPa), 0.2 % yield 275 ksi (1896 MPa). ν = 0.28 is MakeItFrom's
    # value for annealed 440C (https://makeitfrom.com/material-properties/Annealed-440C-Stainless-Steel):
    # not read for the hardened state.
    "stainless-440c": (209.6e9, 0.28, 7612.0, 1896e6, "stainless steel AISI 440C (hardened)"),
    # Tungsten carbide (WC): MakeItFrom "Tungsten Carbide (WC)"
    # (https://www.makeitfrom.com/material-properties/Tungsten-Carbide-WC): E = 630 GPa,
    # ν = 0.24, ρ = 15 g/cm³. Cemented grades (WC–Co balls) are less stiff and dense (E
    # 530–700 GPa over WC products, Wikipedia "Tungsten carbide"): give the grade's own values
    # for a real ball. Brittle: no yield strength (the plastic laws take the other body's).
    "tungsten-carbide": (630e9, 0.24, 15000.0, None, "tungsten carbide (WC)"),
    # Soda-lime glass: Wikipedia "Soda-lime glass", table of typical properties (container glass,
    # from one large study; stored copy http://www.liquisearch.com/soda-lime_glass/
    # typical_compositions_and_properties): E = 72 GPa, ρ = 2.52 g/cm³ at 20 °C; ν = 0.22 from
    # the same article's 2007 version (E = 7.2e10 Pa there too,
    # http://wikipedia2007.classicistranieri.com/en/s/o/d/Soda-lime_glass.html). Brittle: no
    # yield strength.
    "soda-lime-glass": (72e9, 0.22, 2520.0, None, "soda-lime glass"),
    # Sintered alumina, ≥ 99.5 % Al2O3: NIST SRD 30 property summary (R. G. Munro, J. Am.
    # Ceram. Soc. 80 (1997) 1919; https://srdata.nist.gov/CeramicDataPortal/Pds/Scdaos):
    # E = 416 GPa, ρ = 3.984 g/cm³ at 20 °C. ν UNVERIFIED: the NIST table was not read that
    # far; 0.23 is the middle of MakeItFrom's 0.22–0.24 over alumina grades
    # (http://www.makeitfrom.com/material-properties/Alumina-Aluminum-Oxide-Al2O3/). Brittle:
    # no yield strength.
    "alumina-99.5": (416e9, 0.23, 3984.0, None, "alumina 99.5 % (sintered)"),
    # Aluminium 2024-T3: ASM Material Data Sheet "Aluminum 2024-T3" (AA typical values; stored
    # copy https://vi.scribd.com/document/274873614/Material-2024): E = 73.1 GPa, tensile
    # yield 345 MPa, ρ = 2.78 g/cm³; ν = 0.33 from TU Delft's table (AA 2024-T3: E 72 GPa,
    # σ_y 345 MPa, ν 0.33, ρ 2.78; courses.edx.org DelftX AE1x material tables).
    "aluminium-2024-t3": (73.1e9, 0.33, 2780.0, 345e6, "aluminium 2024-T3"),
    # Aluminium 7075-T6: Wikipedia "7075 aluminium alloy" infobox (A7075-T6: ρ = 2.81 g/cm³,
    # E = 71.7 GPa, ν = 0.33); tensile yield 503 MPa (T6, T651) from SubsTech "Wrought
    # aluminum-zinc-magnesium alloy 7075" (substech.com).
    "aluminium-7075-t6": (71.7e9, 0.33, 2810.0, 503e6, "aluminium 7075-T6"),
    # Ti-6Al-4V (grade 5), annealed bar: ASM Material Data Sheet via MatWeb
    # (http://asm.matweb.com/search/SpecificMaterial.asp?bassnum=MTP644): ρ = 4.43 g/cm³,
    # tensile yield 830 MPa, E = 114 GPa (average of tension and compression), ν = 0.33.
    "ti-6al-4v": (114e9, 0.33, 4430.0, 830e6, "titanium Ti-6Al-4V (grade 5, annealed)"),
}

#: Ply entries, one a row: E1, E2, G12 [Pa], ν12 [-], ρ [kg/m³], ply thickness [m] (``None``: the
#: default 0.125 mm), G13, G23 [Pa] (``None``: G12, see :class:`Ply`), label.
_PLIES: dict = {
    # T300/934 carbon/epoxy as used in the impact literature (Sun & Chen, J. Appl. Mech.
    # 52 (1985); Qian & Swanson, Comput. Struct. 1990): E1 = 120 GPa, E2 = 7.9 GPa,
    # G12 = 5.5 GPa, ν12 = 0.30, ρ = 1580 kg/m³.
    # UNVERIFIED: no stored copy of either paper or of a table with these numbers could
    # be found; other sources give rather different T300/934 data (e.g. E1 = 19 Msi =
    # 131 GPa, E2 = 1.5 Msi = 10.3 GPa). G13 = G23 = G12 by default (see Ply).
    "t300-934": (120e9, 7.9e9, 5.5e9, 0.30, 1580.0, None, None, None, "T300/934 (unverified)"),
    # AS4/3501-6 carbon/epoxy, lamina data of the World-Wide Failure Exercise (Soden,
    # Hinton & Kaddour, Compos. Sci. Technol. 58 (1998) 1011–1022): E1 = 126 GPa,
    # E2 = 11 GPa, G12 = 6.6 GPa, ν12 = 0.28. Verified against two independent stored
    # copies: Anand, Kamrin & Govindjee, Introduction to Mechanics of Solids (OUP 2022),
    # example 23.2 (github.com/sanjayg0/ims, MainBook/ex23_2.m), and Barbero, Introduction
    # to Composite Materials Design, example 7.9. Density 1600 kg/m³ is UNVERIFIED
    # (typical for Vf ≈ 0.6 carbon/epoxy; one secondary source lists 1580).
    "as4-3501-6": (126e9, 11e9, 6.6e9, 0.28, 1600.0, None, None, None, "AS4/3501-6"),
    # T300/5208 carbon/epoxy, the Tsai & Hahn (Introduction to Composite Materials, 1980)
    # lamina data as used in Anand, Kamrin & Govindjee, Introduction to Mechanics of Solids (OUP
    # 2022), example 23.1 (stored copy github.com/sanjayg0/ims, MainBook/ex23_1.m): E1 = 181 GPa,
    # E2 = 10.3 GPa, G12 = 7.17 GPa, ν12 = 0.28, ply 0.125 mm. Density 1600 kg/m³ UNVERIFIED
    # (not given there; typical of Vf ≈ 0.6 carbon/epoxy). G13 = G23 = G12 by default.
    "t300-5208": (181e9, 10.3e9, 7.17e9, 0.28, 1600.0, None, None, None, "T300/5208"),
    # IM7/8552 carbon/epoxy (Hexcel HexPly 8552, UD tape 35 % resin, 134 gsm): Hexcel product
    # data sheet (stored copy https://www.scribd.com/document/695150302/HexPly-8552-eu-DataSheet):
    # 0° tensile modulus 164 GPa and 90° tensile modulus 12 GPa (25 °C, dry), nominal cured ply
    # thickness 0.131 mm, laminate density 1.57 g/cm³. G12 = 5.29 GPa and ν12 = 0.32 UNVERIFIED:
    # read only in an unattributed FE material library of a public repository (its IM7/8552
    # set: E1 171.42, E2 9.08, G12 5.29 GPa, ν12 0.32, ν23 0.487), not in a primary source;
    # the data sheet gives no G12. G13 = G23 = G12 by default (an assumption: with that
    # library's ν23, G23 = E2/(2(1 + ν23)) would be 4.0 GPa).
    "im7-8552": (164e9, 12e9, 5.29e9, 0.32, 1570.0, 0.131e-3, None, None, "IM7/8552"),
    # E-glass/epoxy, typical unidirectional ply at Vf = 0.55: the material library of NTNU's
    # course TMM4175 (N. P. Vedvik; stored public copy "matlib.py", entry "Typical UD
    # E-glass/Epoxy"): E1 = 40 GPa, E2 = 10 GPa, G12 = G13 = 3.8 GPa, G23 = 3.4 GPa,
    # ν12 = 0.3, ρ = 2000 kg/m³. A typical set, not one product's; ply thickness not given
    # (the default 0.125 mm).
    "eglass-epoxy": (40e9, 10e9, 3.8e9, 0.3, 2000.0, None, 3.8e9, 3.4e9, "E-glass/epoxy (typical UD, Vf 0.55)"),
}

#: Named materials: the rows above as :class:`IsotropicMaterial` and :class:`Ply`.
CATALOGUE: dict = {
    **{name: IsotropicMaterial(*row) for name, row in _ISOTROPIC.items()},
    **{name: Ply(*moduli, thickness=DEFAULT_PLY_THICKNESS if thickness is None else thickness,
                 transverse_shear_modulus_13=g13, transverse_shear_modulus_23=g23, name=label)
       for name, (*moduli, thickness, g13, g23, label) in _PLIES.items()},
}


#: Per entry: its source (short), the values read in it, and each value not read with the reason.
#: Field names are those of :class:`IsotropicMaterial` and :class:`Ply`.
_ISO = ("youngs_modulus", "poisson_ratio", "density", "yield_strength")
_PLY = ("longitudinal_modulus", "transverse_modulus", "shear_modulus", "poisson_ratio", "density")
SOURCES: dict = {
    "structural-steel": ("S235: EN 1993-1-1:2005 §3.2.6 and Table 3.1, EN 1991-1-1 Table A.4", _ISO, {}),
    "steel-s355": ("S355: EN 1993-1-1 §3.2.6 (E, ν, ρ); EN 10025-2 Table 7 (f_y, t ≤ 16 mm)", _ISO, {}),
    "stainless-304": ("ASM Material Data Sheet, AISI Type 304 (MatWeb)", _ISO, {}),
    "bearing-steel-52100": (
        "AISI 52100 chrome-steel ball sheet (E, ρ, yield); ASM Metals Handbook Desk Edition (ν of hardened "
        "tool steel)", ("youngs_modulus", "density", "yield_strength"),
        {"poisson_ratio": "the handbook's hardened tool steel, not 52100 (52100 sheets: 0.27-0.30)"}),
    "stainless-440c": (
        "Rolled Alloys 440C data sheet, hardened and tempered 600 °F (E, ρ, yield); MakeItFrom (ν, annealed)",
        ("youngs_modulus", "density", "yield_strength"),
        {"poisson_ratio": "read for annealed 440C only"}),
    "tungsten-carbide": ("MakeItFrom, Tungsten Carbide (WC)", _ISO[:3],
                         {"yield_strength": "brittle: none (the plastic laws take the other body's)"}),
    "soda-lime-glass": ("Wikipedia, Soda-lime glass: typical properties table (E, ρ), 2007 version (ν)", _ISO[:3],
                        {"yield_strength": "brittle: none"}),
    "alumina-99.5": ("NIST SRD 30, sintered alumina (Munro 1997)", ("youngs_modulus", "density"),
                     {"poisson_ratio": "not read in the NIST table; middle of MakeItFrom's 0.22-0.24",
                      "yield_strength": "brittle: none"}),
    "aluminium-2024-t3": ("ASM Material Data Sheet, Aluminum 2024-T3 (E, ρ, yield); TU Delft table (ν)", _ISO, {}),
    "aluminium-6061-t6": ("Aluminum Association typical values (MatWeb/ASM)", _ISO, {}),
    "aluminium-7075-t6": ("Wikipedia, 7075 aluminium alloy (E, ν, ρ); SubsTech (yield, T6/T651)", _ISO, {}),
    "ti-6al-4v": ("ASM Material Data Sheet, Ti-6Al-4V grade 5 annealed bar (MatWeb MTP644)", _ISO, {}),
    "as4-3501-6": ("World-Wide Failure Exercise lamina data (Soden, Hinton & Kaddour, Compos. Sci. Technol. 58 "
                   "(1998) 1011-1022), via Anand, Kamrin & Govindjee (2022) ex. 23.2 and Barbero ex. 7.9", _PLY[:4],
                   {"density": "typical Vf 0.6 carbon/epoxy, not in the sources",
                    "thickness": "the nominal 0.125 mm of the sources' examples",
                    "transverse_shear_modulus_13": "G12 (transverse isotropy)",
                    "transverse_shear_modulus_23": "G12 (an assumption)"}),
    "t300-934": ("values used by Sun & Chen (1985) and Qian & Swanson (1990) as quoted in the impact literature",
                 (), {field: "no stored copy of either paper could be read"
                      for field in _PLY + ("thickness", "transverse_shear_modulus_13",
                                           "transverse_shear_modulus_23")}),
    "t300-5208": ("Tsai & Hahn data via Anand, Kamrin & Govindjee (2022) ex. 23.1", _PLY[:4] + ("thickness",),
                  {"density": "not in the source; typical Vf 0.6 carbon/epoxy",
                   "transverse_shear_modulus_13": "G12 (transverse isotropy)",
                   "transverse_shear_modulus_23": "G12 (an assumption)"}),
    "im7-8552": ("Hexcel HexPly 8552 product data sheet (IM7 UD tape)",
                 ("longitudinal_modulus", "transverse_modulus", "density", "thickness"),
                 {"shear_modulus": "read only in an unattributed FE material library",
                  "poisson_ratio": "read only in an unattributed FE material library",
                  "transverse_shear_modulus_13": "G12 (transverse isotropy)",
                  "transverse_shear_modulus_23": "G12 (an assumption)"}),
    "eglass-epoxy": ("NTNU TMM4175 material library (N. P. Vedvik), typical UD E-glass/epoxy, Vf 0.55",
                     _PLY + ("transverse_shear_modulus_13", "transverse_shear_modulus_23"),
                     {"thickness": "not given: the default 0.125 mm"}),
}


def available_materials() -> tuple:
    """Names in :data:`CATALOGUE`, sorted."""
    return tuple(sorted(CATALOGUE))


def material(name: str):
    """The catalogue material ``name`` (an :class:`IsotropicMaterial` or a :class:`Ply`).

    Each entry's sources: :data:`SOURCES` (``impactmaps materials``; docs/cases.rst).

    Raises
    ------
    ValueError
        If ``name`` is not in :data:`CATALOGUE`; the message lists the known names.
    """
    require_choice("material name", name, available_materials())
    return CATALOGUE[name]
