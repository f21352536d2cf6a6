"""Similarity of Hertz impacts: the Hertz loss factor ζ_h and relative stiffness λ_h.

The numbers and scales of one impact (:func:`hertz_numbers`), the impactor that realises
given numbers (:func:`realise_hertz`), Zener's parameter and the patch number of a
patch-loaded plate. Derivation: docs/hertz_maps.rst.
"""

from __future__ import annotations

from dataclasses import dataclass

from .._checks import require_positive
from ..contact.base import ContactLaw

__all__ = [
    "ZENER_TO_LOSS_FACTOR",
    "HertzNumbers",
    "HertzRealisation",
    "hertz_numbers",
    "patch_number",
    "radius_for_patch_number",
    "realise_hertz",
    "unit_speed_stiffness",
    "zener_parameter",
]

#: μ/ζ_h: the normalised dashpot coefficient of Zener's model over the Hertz loss factor.
ZENER_TO_LOSS_FACTOR = 2.5


@dataclass(frozen=True)
class HertzNumbers:
    """The similarity numbers and scales of one Hertz impact (SI units).

    Attributes
    ----------
    loss_factor : float
        ζ_h = ζ(m, K_eq) of the target [-].
    relative_stiffness : float
        λ_h = K_st/K_eq [-].
    indentation_scale : float
        α_m = (5 m V0²/(4 K_h))^{2/5} [m].
    time_scale : float
        t* = α_m/V0 [s].
    force_scale : float
        F_hs = K_h α_m^{3/2} [N].
    equivalent_stiffness : float
        K_eq = m V0²/α_m² [N/m].
    """

    loss_factor: float
    relative_stiffness: float
    indentation_scale: float
    time_scale: float
    force_scale: float
    equivalent_stiffness: float


@dataclass(frozen=True)
class HertzRealisation:
    """An impactor (``mass`` m [kg], ``velocity`` V0 [m/s]) realising Hertz ``numbers`` on a target."""

    mass: float
    velocity: float
    numbers: HertzNumbers


def _hertz_stiffness(law) -> float:
    if isinstance(law, ContactLaw) and law.hertzian_stiffness is not None:
        return float(law.hertzian_stiffness)
    if isinstance(law, (int, float)):
        require_positive("law (Hertz stiffness)", float(law), "N/m^1.5")
        return float(law)
    raise ValueError(f"law = {law!r} is not valid: the Hertz similarity needs a HertzContact "
                     "(or its stiffness K_h [N/m^1.5]); a law with a yield indentation adds "
                     "the impact number β as a third parameter")


def hertz_numbers(target, law, mass, velocity) -> HertzNumbers:
    """The Hertz numbers of an impact of ``mass`` m [kg] at ``velocity`` V0 [m/s], both > 0.

    ``law`` is a :class:`HertzContact` or K_h [N/m^1.5]; ``target`` needs
    ``loss_factor(m, K)`` and ``static_compliance()``. Returns :class:`HertzNumbers`.
    """
    from .halfspace import hertz_max_indentation  # scipy's integrators, pandas: on use

    stiffness = _hertz_stiffness(law)
    require_positive("mass", mass, "kg")
    require_positive("velocity", velocity, "m/s")
    m, v = float(mass), float(velocity)
    alpha_m = float(hertz_max_indentation(m, v, stiffness))
    equivalent = m * v**2 / alpha_m**2
    return HertzNumbers(
        loss_factor=float(target.loss_factor(m, equivalent)),
        relative_stiffness=float(1.0 / (target.static_compliance() * equivalent)),
        indentation_scale=alpha_m,
        time_scale=alpha_m / v,
        force_scale=stiffness * alpha_m**1.5,
        equivalent_stiffness=equivalent,
    )


def realise_hertz(target, zeta_h, lambda_h, law) -> HertzRealisation:
    """Impactor mass and velocity giving ``zeta_h`` ζ_h and ``lambda_h`` λ_h (> 0, [-]) on ``target``.

    ``law`` is a :class:`HertzContact` or K_h [N/m^1.5]. Returns :class:`HertzRealisation`.
    """
    require_positive("zeta_h", zeta_h)
    require_positive("lambda_h", lambda_h)
    stiffness = _hertz_stiffness(law)
    equivalent = 1.0 / (float(target.static_compliance()) * float(lambda_h))
    mass = float(target.impactor_mass_for(float(zeta_h), equivalent))
    velocity = (equivalent / (mass**0.2 * (0.8 * stiffness) ** 0.8)) ** 2.5
    return HertzRealisation(mass, velocity, hertz_numbers(target, stiffness, mass, velocity))


def unit_speed_stiffness(target, zeta_h, lambda_h) -> float:
    """The Hertz stiffness K_h [N/m^1.5] at which (ζ_h, λ_h) on ``target`` is struck at 1 m/s."""
    require_positive("zeta_h", zeta_h)
    require_positive("lambda_h", lambda_h)
    equivalent = 1.0 / (float(target.static_compliance()) * float(lambda_h))
    mass = float(target.impactor_mass_for(float(zeta_h), equivalent))
    return 1.25 * (equivalent * mass**-0.2) ** 1.25


def zener_parameter(plate, law, mass, velocity) -> float:
    """Zener's combination ``(K_h² m³ V0)^{1/5} / (8 sqrt(ρh D*))`` [-] on an infinite ``plate``.

    ``mass`` m [kg], ``velocity`` V0 [m/s]; ``μ = (5/4)^{3/5}`` times this equals ``(5/2) ζ_h``.
    """
    stiffness = _hertz_stiffness(law)
    require_positive("mass", mass, "kg")
    require_positive("velocity", velocity, "m/s")
    impedance = 8.0 * (float(plate.mass_per_area) * float(plate.effective_bending_stiffness)) ** 0.5
    return (stiffness**2 * float(mass) ** 3 * float(velocity)) ** 0.2 / impedance


def patch_number(target, law, mass, velocity) -> float:
    """The patch number ``P = sqrt(R α_m)/h`` [-] of a Hertz impact (``mass`` [kg], ``velocity`` [m/s]) on a plate."""
    radius = getattr(law, "effective_radius", None)
    if radius is None:
        raise ValueError(f"law = {law!r} has no effective_radius: the patch number needs the contact "
                         "radius scale R [m] (a Hertz law built from a sphere and a material has it)")
    alpha_m = hertz_numbers(target, law, mass, velocity).indentation_scale
    return float((float(radius) * alpha_m) ** 0.5 / float(target.thickness))


def radius_for_patch_number(target, numbers: HertzNumbers, patch: float) -> float:
    """The effective radius R = (P h)²/α_m [m] giving patch number ``patch`` P [-] on ``target``."""
    require_positive("patch", patch)
    return float((float(patch) * float(target.thickness)) ** 2 / numbers.indentation_scale)
