r"""Similarity of Hertz impacts: the two numbers a Hertz response depends on.

Scales
------
A sphere of mass m striking a rigid half-space at V0 with ``F = K_h α^{3/2}`` reaches
``α_m = (5 m V0²/(4 K_h))^{2/5}`` (all the kinetic energy stored: ``(2/5) K_h α_m^{5/2} =
½ m V0²``). Take ``α_m`` as the length, ``t* = α_m/V0`` as the time and
``F_hs = K_h α_m^{3/2}`` as the force scale, and write ``ᾱ = α/α_m``, ``τ = t/t*``,
``F̄ = F/F_hs``.

Derivation
----------
*Impactor.* ``m ẍ = −F`` becomes ``x̄'' = −(F_hs t*²/(m α_m)) F̄`` and
``F_hs t*²/(m α_m) = K_h α_m^{5/2}/(m V0²) = 5/4``: the impactor equation has **no**
parameter left, ``x̄'' = −(5/4) ᾱ^{3/2}``, ``x̄(0) = 0``, ``x̄'(0) = 1``. This is where the
homogeneity of the law is used: for a law with its own length scale (a yield indentation
α_y) the ratio ``α_m/α_y`` (the impact number β) would remain.

*Structure.* A linear structure of a given family (shape ratios, supports, relative
impact point, theory, Poisson ratio, slenderness, damping ratio all fixed) has a
point receptance fixed by a mass ``M_s`` and a frequency ``Ω_s`` (plate: ``M_s = ρh a²``,
``Ω_s = sqrt(D/ρh)/a²``; beam: ``m'L``, ``sqrt(EI/m')/L²``): its impulse response is
``g(t) = (1/M_s) ĝ(Ω_s t)``. In the scaled variables
``w̄(τ) = (F_hs t*/(α_m M_s)) ∫ ĝ(Ω_s t* (τ − s)) F̄(s) ds`` and ``F_hs t*²/α_m = (5/4) m``:
the response depends on ``m/M_s`` and ``Ω_s t*`` only — two numbers.

*The choice of the two numbers.* Any two independent combinations do; the natural ones
reuse the linear definitions (docs/physics_contract.md §1, §7) with the secant stiffness that stores
the impact energy at α_m,

    K_eq = m V0²/α_m²  (ω_eq = sqrt(K_eq/m) = V0/α_m = 1/t*),

the **Hertz loss factor** ``ζ_h = ζ(m, K_eq)`` (plate ``(1/16) sqrt(m K_eq/(ρh D*))``, beam
the corrected ``ζ_b`` of docs/physics_contract.md §1) and the **Hertz relative stiffness**
``λ_h = K_st/K_eq``. For the plate ``ζ_h = (1/16)(m/M_s)/(Ω_s t*)`` and
``λ_h = c Ω_s² t*² M_s/m`` (``K_st = c D/a²``, c fixed by the family), a one-to-one map of
``(m/M_s, Ω_s t*)``; the beam is the same with its own exponents. So two physically
different Hertz impacts on one structure family with equal ``(ζ_h, λ_h)`` have equal
``F_max/F_hs``, ``t_c/t*`` and restitution (the test checks it to 1e-6 with the modal
solver), and one Hertz map over ``(ζ_h, λ_h)`` serves the whole family.

Relation to Zener's parameter (infinite plate)
---------------------------------------------
On the infinite plate the struck point is a dashpot, ``ẇ = F/Z``, ``Z = 8 sqrt(ρh D*)``
(seed 001 eq 30); with Hertz contact this is Zener's model (Zener, Phys. Rev. 59, 1941,
669). In the scaled variables ``ᾱ' = x̄' − μ F̄`` with

    μ = F_hs t*/(Z α_m) = K_h α_m^{3/2}/(Z V0) = (5/4)^{3/5} (K_h² m³ V0)^{1/5}/Z,

the model's single parameter (the inelasticity parameter, up to the numerical constant
of whichever normalisation one prefers; :func:`zener_parameter` returns the constant-free
combination ``(K_h² m³ V0)^{1/5}/Z``). Since ``2ζ_h = sqrt(m K_eq)/Z = m V0/(α_m Z)`` and
``K_h α_m^{5/2} = (5/4) m V0²``, ``μ = (5/2) ζ_h`` exactly: the Hertz loss factor *is*
Zener's parameter up to a constant, and ``λ_h`` drops out on the infinite plate.

Patch-loaded targets: the patch number
--------------------------------------
Where the modal solver spreads the force over the Hertz contact patch (Mindlin SSSS
plates by default, :attr:`impactmaps.solvers.modal.ModalSettings.contact_patch`), the
load is a Hertz pressure over the disc of radius ``a = sqrt(R α_max)`` (R the effective
radius of the pair, :attr:`HertzContact.effective_radius`): each mode's participation
is multiplied by the patch's transform ``T(k a)`` and the residual compliance is the one
under the patch. In the scaled variables ``a = sqrt(R α_m) sqrt(ᾱ_max)`` and the
wavenumbers of the family scale as ``k = κ/L`` (κ fixed by the family, L the span), so

    k a = κ (h/L) P sqrt(ᾱ_max),    P = sqrt(R α_m)/h,

and the structure's receptance under the patch is ``ĝ`` of the point load with each term
weighted by functions of ``k a``: with the slenderness L/h fixed by the family, the
response is a function of ``(ζ_h, λ_h, P)``. R enters nowhere else — K_h already holds
it (``(4/3) sqrt(R) E*``) and is scaled out — so ``P``, the **patch number** (the
half-space contact radius ``a_m = sqrt(R α_m)`` over the thickness, :func:`patch_number`),
is the one number a patch adds. The fixed-point iteration of the patch radius is
scale-free too (it starts from the half-space radius ``P h`` and stops on a relative
change), so two patch-loaded impacts with equal ``(ζ_h, λ_h, P)`` on one family give
equal ``F_max/F_hs``, ``t_c/t*`` and restitution, run for run (the test checks it to
1e-9). A point of a patch-loaded map is realised with :func:`unit_speed_stiffness` as K_h
and ``R = (P h)²/α_m`` (:func:`radius_for_patch_number`).
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
    """An impactor that realises given Hertz numbers on a target.

    Attributes
    ----------
    mass : float
        Impactor mass m [kg].
    velocity : float
        Impact velocity V0 [m/s].
    numbers : HertzNumbers
        The numbers and scales of (target, law, m, V0).
    """

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
    """The Hertz loss factor ζ_h and relative stiffness λ_h of an impact (module docstring).

    Parameters
    ----------
    target : Plate or Beam
        Needs ``loss_factor(m, K)`` and ``static_compliance()``.
    law : HertzContact or float
        The Hertz law, or K_h [N/m^1.5].
    mass : float
        Impactor mass m > 0 [kg].
    velocity : float
        Impact velocity V0 > 0 [m/s].

    Returns
    -------
    HertzNumbers
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
    """Impactor mass and velocity that give the Hertz numbers (ζ_h, λ_h) on ``target``.

    ``K_eq = K_st/λ_h``; ``m`` from the target's loss factor at K_eq
    (``target.impactor_mass_for(ζ_h, K_eq)``); then ``K_eq = m V0²/α_m²`` with
    ``α_m = (5 m V0²/(4K_h))^{2/5}`` is ``K_eq = m^{1/5} V0^{2/5} (4K_h/5)^{4/5}``, so
    ``V0 = (K_eq/(m^{1/5} (4K_h/5)^{4/5}))^{5/2}``.

    Parameters
    ----------
    target : Plate or Beam
        Needs ``impactor_mass_for(ζ, K)``, ``loss_factor(m, K)``, ``static_compliance()``.
    zeta_h : float
        Hertz loss factor ζ_h > 0 [-].
    lambda_h : float
        Hertz relative stiffness λ_h > 0 [-].
    law : HertzContact or float
        The Hertz law, or K_h [N/m^1.5].

    Returns
    -------
    HertzRealisation
    """
    require_positive("zeta_h", zeta_h)
    require_positive("lambda_h", lambda_h)
    stiffness = _hertz_stiffness(law)
    equivalent = 1.0 / (float(target.static_compliance()) * float(lambda_h))
    mass = float(target.impactor_mass_for(float(zeta_h), equivalent))
    velocity = (equivalent / (mass**0.2 * (0.8 * stiffness) ** 0.8)) ** 2.5
    return HertzRealisation(mass, velocity, hertz_numbers(target, stiffness, mass, velocity))


def unit_speed_stiffness(target, zeta_h, lambda_h) -> float:
    """The Hertz stiffness K_h [N/m^1.5] for which (ζ_h, λ_h) on ``target`` is struck at 1 m/s.

    Any K_h realises the numbers (similarity); the map sweeps take this one so that every
    point runs at V0 = 1 m/s, whatever ζ_h and λ_h (a fixed K_h would need speeds from
    1e-9 to 1e6 m/s over the map range). From :func:`realise_hertz`, V0 = 1 is
    ``(4K_h/5)^{4/5} = K_eq m^{-1/5}``, i.e. ``K_h = (5/4) (K_eq m^{-1/5})^{5/4}``.

    Parameters
    ----------
    target : Plate or Beam
        Needs ``impactor_mass_for(ζ, K)`` and ``static_compliance()``.
    zeta_h, lambda_h : float
        Hertz loss factor and relative stiffness, > 0 [-].

    Returns
    -------
    float
    """
    require_positive("zeta_h", zeta_h)
    require_positive("lambda_h", lambda_h)
    equivalent = 1.0 / (float(target.static_compliance()) * float(lambda_h))
    mass = float(target.impactor_mass_for(float(zeta_h), equivalent))
    return 1.25 * (equivalent * mass**-0.2) ** 1.25


def zener_parameter(plate, law, mass, velocity) -> float:
    """Zener's combination ``(K_h² m³ V0)^{1/5} / (8 sqrt(ρh D*))`` [-] (module docstring).

    The normalised dashpot coefficient of the infinite-plate Hertz problem is
    ``μ = (5/4)^{3/5}`` times this, and ``μ = (5/2) ζ_h`` (:data:`ZENER_TO_LOSS_FACTOR`).

    Parameters
    ----------
    plate : Plate
        ρh [kg/m²] and D* [N m] of the infinite plate.
    law : HertzContact or float
        The Hertz law, or K_h [N/m^1.5].
    mass : float
        m > 0 [kg].
    velocity : float
        V0 > 0 [m/s].
    """
    stiffness = _hertz_stiffness(law)
    require_positive("mass", mass, "kg")
    require_positive("velocity", velocity, "m/s")
    impedance = 8.0 * (float(plate.mass_per_area) * float(plate.effective_bending_stiffness)) ** 0.5
    return (stiffness**2 * float(mass) ** 3 * float(velocity)) ** 0.2 / impedance


def patch_number(target, law, mass, velocity) -> float:
    """The patch number ``P = sqrt(R α_m)/h`` of a Hertz impact on a plate [-] (module docstring).

    The half-space contact radius ``a_m = sqrt(R α_m)`` over the plate thickness: with
    (ζ_h, λ_h) it fixes the response of a patch-loaded plate family.

    Parameters
    ----------
    target : Plate
        Needs ``thickness`` h [m].
    law : HertzContact
        The Hertz law with its ``effective_radius`` R [m].
    mass, velocity : float
        The impactor's mass m [kg] and speed V0 [m/s], both > 0.

    Returns
    -------
    float
    """
    radius = getattr(law, "effective_radius", None)
    if radius is None:
        raise ValueError(f"law = {law!r} has no effective_radius: the patch number needs the contact "
                         "radius scale R [m] (a Hertz law built from a sphere and a material has it)")
    alpha_m = hertz_numbers(target, law, mass, velocity).indentation_scale
    return float((float(radius) * alpha_m) ** 0.5 / float(target.thickness))


def radius_for_patch_number(target, numbers: HertzNumbers, patch: float) -> float:
    """The effective radius R [m] that gives the patch number ``patch`` to an impact on ``target``.

    ``R = (P h)²/α_m``, the inverse of :func:`patch_number` at the impact's indentation
    scale α_m (``numbers.indentation_scale``).

    Parameters
    ----------
    target : Plate
        Needs ``thickness`` h [m].
    numbers : HertzNumbers
        The Hertz numbers of the impact (:func:`hertz_numbers`).
    patch : float
        Patch number P > 0 [-].

    Returns
    -------
    float
    """
    require_positive("patch", patch)
    return float((float(patch) * float(target.thickness)) ** 2 / numbers.indentation_scale)
