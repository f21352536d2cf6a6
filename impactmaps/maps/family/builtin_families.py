"""What a reader needs of the built-in map families, without their point solvers.

A lookup reads a shipped map by its family's *layout* — its axes, the quantities whose
errors it stores, how it interpolates, which maps ship — and never solves a point. The
families themselves (:mod:`.linear_points`, :mod:`.hertz_points`, :mod:`.plastic_points`)
subclass the layouts defined here and add the point solver, importing the contact laws,
targets and integrators (numba, SciPy, pandas: ~0.8 s). This module imports only NumPy, the
targets' named choices and :mod:`.map_family`, so reading a shipped map (:func:`family_layout`)
costs none of that;
:func:`impactmaps.maps.family.map_family.map_family` imports a built-in family's module when the
family itself is first asked for.
"""

from __future__ import annotations

import numpy as np

from ..._checks import require_choice
from ...targets.options import point_load_diverges
from .map_family import Axis, Interpolation, MapFamily, map_family

__all__ = ["SHIPPED_PLANE_MAPS", "POINT_LOADED_DIVERGENT_THEORIES", "MEMBER_SLENDERNESSES", "HERTZ_AXES", "PLASTIC_LAWS", "PLASTIC_ERROR_OF",
           "LinearLayout", "HertzLayout", "PlasticLayout", "LAYOUTS", "PLANE_LAWS", "CUBE_LAWS", "family_layout", "plastic_law_of"]

#: (kind, theory) → structure name of the shipped (ζ, λ) maps, linear and Hertz alike (the names
#: of :data:`impactmaps.maps.family.structures.DEFAULT_STRUCTURES`, checked there).
SHIPPED_PLANE_MAPS = {
    ("beam", "euler"): "beam-ss-euler",
    ("beam", "timoshenko"): "beam-ss-timoshenko-s20",
    ("plate", "kirchhoff"): "plate-ssss-kirchhoff",
    ("plate", "mindlin"): "plate-ssss-mindlin-s20",
}

#: The theories of the shipped (ζ, λ) maps struck at a point where the point-load deflection diverges
#: (Mindlin): their F̄max depends on the sweep's mode cap, and a reading of them says so.
POINT_LOADED_DIVERGENT_THEORIES = frozenset(theory for _, theory in SHIPPED_PLANE_MAPS if point_load_diverges(theory))

#: Slendernesses (span/thickness) of the slenderness members of the shipped shear-deformable maps; the
#: classical (Euler/Kirchhoff) map is their thin limit, 1/slenderness = 0.
MEMBER_SLENDERNESSES = (10.0, 20.0, 50.0)

#: The axes of a Hertz map: (λ_h, ζ_h) descriptions.
HERTZ_AXES = ("Hertz relative stiffness K_st/K_eq (K_eq = m V0²/α_m²)", "Hertz loss factor ζ(m, K_eq)")

#: Map-law name → registered contact-law name of the elastic-plastic maps.
PLASTIC_LAWS = {"yc": "yigit-christoforou", "stronge": "stronge", "epp": "epp"}

#: The quantities whose error an elastic-plastic map stores, with the name of their error variable.
PLASTIC_ERROR_OF = {"fmax_normalised": "fmax_error", "restitution": "restitution_error",
                    "absorbed_energy_fraction": "absorbed_energy_error"}


def plastic_law_of(law) -> str:
    """The plastic map law (key of :data:`PLASTIC_LAWS`) a contact law belongs to.

    Raises ValueError for a law with other than its default options (another family), naming
    the option, its value and the maps' value.
    """
    name = getattr(law, "name", None)
    map_law = next((key for key, law_name in PLASTIC_LAWS.items() if law_name == name), None)
    if map_law is None:
        raise ValueError(f"law = {type(law).__name__} is not an elastic-plastic law of the maps "
                         f"(valid: {', '.join(PLASTIC_LAWS.values())})")
    defaults = law.options()
    changed = [f"{option} = {_option_text(value)} (the maps' value: {float(defaults[option].default):g})"
               for option, value in law.changed_options().items()]
    if changed:
        raise ValueError(f"contact law {name!r} with {', '.join(changed)}: the normalised response depends on "
                         f"these options and the {map_law} maps are built at their defaults")
    return map_law


def _option_text(value) -> str:
    """A law option's value as the user gave it (a number, or an array's values)."""
    values = np.unique(np.asarray(value, float))
    return f"{values[0]:g}" if values.size == 1 else "[" + ", ".join(f"{v:g}" for v in values) + "]"


class LinearLayout(MapFamily):
    """The linear contact law's maps over (ζ, λ) (:class:`~impactmaps.maps.compute.linear_points.LinearFamily`)."""

    name = "linear"
    axes = (Axis("lambda_", "relative stiffness K_st/K"), Axis("zeta", "loss factor"))
    law_in_description = False
    law_in_file_name = False
    classifies = True
    shipped = SHIPPED_PLANE_MAPS
    exact_command = "impactmaps point"
    scaled_by_contact_frequency = True
    closed_form_asymptotes = True
    labels = MapFamily.labels | {"zeta": "loss factor ζ", "lambda": "relative stiffness λ", "contact": "",
              "fmax": r"normalised maximum force $\bar{F}_{max} = F_{max} / (m_i V_0 \omega)$",
              "table": "# Normalised maximum force F̄max = Fmax/(m_i V0 ω)\n\n"
                       "Linear contact, {structures}; nearest computed grid point.\n"
                       "Peak force in newtons: F̄max · m_i · V0 · sqrt(K/m_i).\n\n"}

    def describes(self, law) -> bool:
        return law.linear_stiffness is not None


class HertzLayout(MapFamily):
    """The Hertz law's maps over (ζ_h, λ_h) (:class:`~impactmaps.maps.compute.hertz_points.HertzFamily`)."""

    name = "hertz"
    axes = (Axis("lambda_", HERTZ_AXES[0]), Axis("zeta", HERTZ_AXES[1]))
    classifies = True
    shipped = SHIPPED_PLANE_MAPS
    patch_loadable = True
    #: λ_h below 1e-5 makes the quasi-static Hertz integration fail (measured: it fails at
    #: λ_h = 1e-6 and answers at 3e-6); ζ_h above 1e3 makes the infinite-plate Hertz
    #: asymptote run for minutes (measured: 1e3 answers, 1e4 does not).
    chart_lambda_min = 1.0e-5
    chart_zeta_max = 1.0e3
    labels = MapFamily.labels | {"zeta": "Hertz loss factor ζ_h = ζ(m, K_eq), K_eq = m V0²/α_m²",
              "lambda": "Hertz relative stiffness λ_h = K_st/K_eq", "contact": "Hertz contact",
              "zeta_name": "Hertz loss factor ζ_h", "lambda_name": "Hertz relative stiffness λ_h",
              "quasi_static": r"quasi-static $\bar{F}^{5/3} + (25/16)\bar{F}^2/\lambda_h = 1$",
              "fmax": r"$\bar{F}_{max} = F_{max}/F_{hs}$, $F_{hs} = K_h \alpha_m^{3/2}$ (Hertz half-space peak)",
              "table": "# Normalised maximum force F̄max = Fmax/F_hs, Hertz contact\n\n"
                       "Hertz contact F = K_h α^1.5, {structures}; rows λ_h, columns ζ_h "
                       "(impactmaps.closed_forms.hertz_similarity); nearest computed grid point.\n"
                       "Peak force in newtons: F̄max · K_h α_m^1.5 with α_m = (5 m_i V0²/(4 K_h))^0.4.\n\n"}

    def describes(self, law) -> bool:
        return law.hertzian_stiffness is not None


class PlasticLayout(MapFamily):
    """An elastic-plastic law's maps over (β, ζ, λ) (:class:`~impactmaps.maps.compute.plastic_points.PlasticFamily`).

    Parameters
    ----------
    name : str
        The map law (a key of :data:`PLASTIC_LAWS`).
    """

    axes = (Axis("beta", "impact number β = V0/(ω_h α_y) (seed 001 eq 11)"),
            Axis("lambda_", "relative stiffness K_st/K_y"), Axis("zeta", "loss factor ζ(m, K_y)"))
    errors = PLASTIC_ERROR_OF
    #: Second differences over one neighbour a side, safety factor 4, no further factor on
    #: the band: what the plastic maps' bands were validated with (``validation/lookup_error.py
    #: --law yc`` and ``--law stronge``: the band covered every error of the answered points,
    #: largest error/band 0.67 (yc) and 0.88 (stronge)).
    interpolation = Interpolation(reach=1, safety=4.0, band_safety=1.0)
    #: No Mindlin plate: its pressure patch depends on the sphere radius, a fourth number.
    shipped = {
        ("beam", "euler"): "beam-ss-euler",
        ("beam", "timoshenko"): "beam-ss-timoshenko-s20",
        ("plate", "kirchhoff"): "plate-ssss-kirchhoff",
    }
    title = "impactmaps normalised elastic-plastic impact map"
    fmax_at_most_one = False
    #: β below 1e-3: β = 1e-6 asked a Stronge or epp law to absorb an energy it cannot within
    #: 1000 m of indentation and made the YC runs last ~1000 s; β = 1e300 failed inside the laws.
    #: Up to 1e6 every law answers (measured on beam-ss-euler at ζ, λ ∈ {1e-3, 1e3}; an epp point
    #: at 1e6 warns of more than 1000 contacts).
    axis_ranges = MapFamily.axis_ranges | {"beta": (1.0e-3, 1.0e6)}
    labels = MapFamily.labels | {"zeta": "loss factor ζ(m, K_y), K_y = 1.5 K_h sqrt(α_y)", "lambda": "relative stiffness λ = K_st/K_y",
              "contact": "elastic-plastic contact",
              "fmax": r"$\bar{F}_{max} = F_{max} / (m_i V_0 \omega_y)$, $\omega_y = \sqrt{K_y/m_i}$",
              "table": "# Normalised maximum force F̄max = Fmax/(m_i V0 ω_y), elastic-plastic contact\n\n"
                       "Nearest computed grid point.\n\n"}
    #: The on-demand tiles' lattice: the shipped plastic maps' grid (2 β, 6 ζ, 5 λ per decade),
    #: on which their bands were validated.
    tile_lattice = {"beta": 0.5, "zeta": 1.0 / 6.0, "lambda_": 0.2}

    def __init__(self, name: str):
        require_choice("map_law", name, tuple(PLASTIC_LAWS))
        self.name = name

    def __reduce__(self):
        return (type(self), (self.name,))

    def describes(self, law) -> bool:
        return getattr(law, "name", None) == PLASTIC_LAWS[self.name] and plastic_law_of(law) == self.name


#: The built-in families' layouts by map law, in registration order.
LAYOUTS = {"linear": LinearLayout(), "hertz": HertzLayout(), **{name: PlasticLayout(name) for name in PLASTIC_LAWS}}
#: The built-in families over (ζ, λ) alone, and those with axes before them (β).
PLANE_LAWS = tuple(name for name, layout in LAYOUTS.items() if len(layout.axes) == 2)
CUBE_LAWS = tuple(name for name, layout in LAYOUTS.items() if len(layout.axes) > 2)


def family_layout(name) -> MapFamily:
    """What a map reader needs of the family ``name`` (axes, errors, interpolation, shipped maps):
    a built-in family's layout (its point solver not imported), any other registered family
    itself, a family object as is; ``ValueError`` for an unknown name."""
    if isinstance(name, MapFamily):
        return name
    if name in LAYOUTS:
        return LAYOUTS[name]
    return map_family(name)
