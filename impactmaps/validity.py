r"""Where the impact model's assumptions fail, said out loud.

The solvers model an elastic sphere on a linear structure through a point contact law.
:func:`validity_warnings` checks a finished run against the assumptions behind that
picture and returns one sentence per violated assumption (empty: none found);
:func:`warn_if_invalid` issues them as :class:`ModelValidityWarning` (a ``UserWarning``).

Checks (each sentence starts with its tag):

``contact pressure``
    Elastic law only. Hertz peak pressure ``p0 = (6 F E*²/(π³ R²))^{1/3}`` (Johnson,
    *Contact Mechanics*, 1985, §4.2) above the mean pressure at full plasticity, taken as
    ``1.6 S_y`` of the softer body (the yield-pressure factor of seed 001 eq 9's
    derivation): the contact yields, a plastic law should be used. The softer body is
    the one of lower yield strength; when only one strength is known, that body counts
    only if it is also the elastically softer one (a steel ball's strength says nothing
    about a composite laminate of unknown strength under it).
``epp calibration``
    The ``epp`` law only: its options (the yielding body's Poisson ratio ν, the elastic
    body's share s of the compliance; defaults ν = 0.3 and a rigid sphere, the shipped epp
    maps' values) differ from what this pair's materials give, or ν lies outside the
    calibrated 0.3–0.45 (what the pair's own values change: ``docs/epp_calibration.rst``).
``indentation``
    ``α_max > 0.1 R``: Hertz theory assumes a contact radius small against R
    (``a = sqrt(Rα)``, so ``a/R = sqrt(α/R) > 0.3``).
``impact speed``
    ``V0 > 0.01 c_0`` with ``c_0 = sqrt(E/ρ)`` the target's bar wave speed: the quasi-static
    contact and the slender-structure theories need impact speeds small against the
    wave speeds (stress-wave effects, plastic waves, penetration).
``plate deflection``
    Plate deflection above half the thickness: membrane stretching (large deflection)
    stiffens the plate, which linear plate theory ignores.
``structural theory``
    A Timoshenko beam or Mindlin plate struck at a contact frequency ω = π/t_c (t_c the
    first contact's duration) above a quarter of its thickness-shear cut-off
    (:func:`impactmaps.targets.shear_range.beyond_shear_theory`): the impact excites
    waves as short as the thickness, which those theories do not describe (the maps mark
    such points ``unresolved``).
``point load``
    A Mindlin plate loaded at a point (a linear law, a Hertz law given by its stiffness
    alone, or ``contact_patch="point"``): its point-load deflection diverges
    logarithmically, so the peak force falls with every doubling of the mode cut-off and
    has no converged value — the number depends on the cut-off (how much, between the map's
    cut-off and ``simulate``'s: ``validation/mindlin_point_load.md``). A contact law with a geometry (a
    sphere's Hertz or plastic law, Yigit–Christoforou's too) is spread over the contact
    patch and converges (``docs/contact_patch.rst``). :func:`impactmaps.simulate` issues
    this and the ``structural theory`` check (:func:`target_warnings`).
``support``
    The impact point closer to a clamped or simply supported end or edge than the
    structure's depth (a beam's height, a plate's thickness; skipped when not known):
    beam and plate theories put the point load and the support reaction on one line
    there, while the real section carries them by local shear and bearing stresses
    (Saint-Venant: the theories hold a few depths away from such concentrations).
``reflections``
    An infinite-structure asymptote (``method`` ``"infinite-plate"``/``"infinite-beam"``)
    is exact only until flexural waves reflected from the nearest edge return. Their
    group velocity ``2 sqrt(ω) (D*/ρh)^{1/4}`` (plate) or ``2 sqrt(ω) (EI/m')^{1/4}``
    (Euler beam) is evaluated at ``ω = 2π/t_c``, the upper end of the force pulse's main
    lobe, and the round trip ``2d/c_g`` compared with the contact time.
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from .contact.base import effective_modulus
from .targets.shear_range import SHEAR_VALIDITY_FRACTION, beyond_shear_theory, thickness_shear_frequency

__all__ = [
    "DEFLECTION_RATIO_LIMIT",
    "INDENTATION_RATIO_LIMIT",
    "SPEED_RATIO_LIMIT",
    "YIELD_PRESSURE_FACTOR",
    "ModelValidityWarning",
    "hertz_peak_pressure",
    "validity_warnings",
    "warn_if_invalid",
]

YIELD_PRESSURE_FACTOR = 1.6  # mean contact pressure at yield / S_y of the softer body
INDENTATION_RATIO_LIMIT = 0.1  # α_max / R
SPEED_RATIO_LIMIT = 0.01  # V0 / sqrt(E/ρ) of the target
DEFLECTION_RATIO_LIMIT = 0.5  # plate deflection / thickness
INFINITE_STRUCTURE_METHODS = ("infinite-plate", "infinite-beam")


class ModelValidityWarning(UserWarning):
    """A physical case lies outside the assumptions of the impact model."""


def hertz_peak_pressure(force, effective_modulus, radius):
    """Hertz peak pressure ``p0 = (6 F E*²/(π³ R²))^{1/3}`` [Pa].

    Parameters
    ----------
    force : float or array_like
        Contact force F ≥ 0 [N].
    effective_modulus : float
        E* [Pa].
    radius : float
        Effective radius R [m].
    """
    force = np.asarray(force, dtype=float)
    return np.cbrt(6.0 * force * effective_modulus**2 / (math.pi**3 * radius**2))


def validity_warnings(sphere, target_material, law, target, result) -> list[str]:
    """The model assumptions a finished run violates, one sentence each.

    Parameters
    ----------
    sphere : Sphere
        The impactor (radius R [m], material with E [Pa], ν, optional S_y [Pa]).
    target_material : material-like
        ``youngs_modulus`` [Pa], ``poisson_ratio``, optional ``density`` [kg/m³] and
        ``yield_strength`` [Pa].
    law : ContactLaw
        The law the run used (the pressure check applies to elastic laws).
    target : Plate, Beam or None
        The structure (None for a half-space).
    result : ImpactResult or AsymptoteResult
        Needs ``peak_force`` [N], ``max_indentation`` [m], ``velocity`` [m/s],
        ``method``; optionally a ``history`` with ``target_displacement_m``,
        ``max_target_displacement`` [m], ``contact_time`` or ``contact_intervals`` [s].

    Returns
    -------
    list of str
        Empty when no check fails.
    """
    checks = (_pressure(sphere, target_material, law, result), _epp_calibration(sphere, target_material, law),
              _indentation(sphere, result),
              _speed(target_material, result), _deflection(target, result),
              _structural_theory(target, result), _point_load(target, result), _support_distance(target),
              _reflections(target, result))
    return [message for message in checks if message]


def target_warnings(target, result) -> list[str]:
    """The checks of :func:`validity_warnings` that need only the structure and the run:
    a first contact beyond the shear theory's range, and a point load whose answer does not
    converge (a Mindlin plate struck without a contact patch). :func:`impactmaps.simulate`
    issues them; a case run (:func:`impactmaps.cases.run_case`) issues all checks.

    Parameters
    ----------
    target : Target
        The structure.
    result : ImpactResult
        The run (its ``contact_intervals`` [s], ``method`` and ``settings``).

    Returns
    -------
    list of str
        Empty when no check fails.
    """
    return [message for message in (_structural_theory(target, result), _point_load(target, result)) if message]


def warn_if_invalid(sphere, target_material, law, target, result, *, stacklevel=2) -> list[str]:
    """Issue each of :func:`validity_warnings` as a :class:`ModelValidityWarning`; return them.

    Parameters are those of :func:`validity_warnings`; ``stacklevel`` as in
    :func:`warnings.warn` (2: the caller's line).
    """
    messages = validity_warnings(sphere, target_material, law, target, result)
    for message in messages:
        warnings.warn(message, ModelValidityWarning, stacklevel=stacklevel + 1)
    return messages


def _softer_body(sphere_material, target_material):
    """``(yield strength [Pa], "impactor"|"target")`` of the body whose contact yields first,
    or None when that cannot be told.

    With both strengths known, the lower one. With one known, only if that body is also
    the elastically softer one (lower Young's modulus; a laminate: its transverse
    modulus): a body of unknown strength that is softer — a composite laminate under a
    steel ball — may yield (or crush) first, so the other body's strength says nothing.
    """
    bodies = (("impactor", sphere_material), ("target", target_material))
    known = [(float(m.yield_strength), name) for name, m in bodies if getattr(m, "yield_strength", None) is not None]
    if len(known) == 2:
        return min(known)
    if not known:
        return None
    strength, name = known[0]
    moduli = {name: float(getattr(m, "youngs_modulus", math.nan)) for name, m in bodies}
    other = "target" if name == "impactor" else "impactor"
    return (strength, name) if moduli[name] <= moduli[other] else None


def _epp_calibration(sphere, target_material, law):
    """The ``epp`` law's options against the pair it is used for: the yielding body's ν and the
    elastic body's share s of the compliance (``docs/epp_calibration.rst``; the FE calibration
    holds ν 0.3–0.45 and s ≤ 0.75), both options with defaults (ν = 0.3, a rigid sphere) that
    the shipped epp maps hold."""
    if not {"poisson_ratio", "sphere_compliance"} <= set(law.options()):  # the law calibrated on them (epp)
        return None
    softer = _softer_body(sphere.material, target_material)
    nu, share = float(law.poisson_ratio), float(law.sphere_compliance)
    notes = []
    if not 0.3 <= nu <= 0.45:
        notes.append(f"its poisson_ratio {nu:g} lies outside the calibrated 0.3–0.45 (an extrapolation)")
    if softer is not None:
        yielding, elastic = ((sphere.material, target_material) if softer[1] == "impactor"
                             else (target_material, sphere.material))
        modulus = float(effective_modulus(sphere.material.youngs_modulus, sphere.material.poisson_ratio,
                                          target_material.youngs_modulus, target_material.poisson_ratio))
        pair_share = modulus * (1.0 - float(elastic.poisson_ratio) ** 2) / float(elastic.youngs_modulus)
        pair_nu = float(yielding.poisson_ratio)
        if abs(pair_nu - nu) > 0.005 or abs(pair_share - share) > 0.02:
            notes.append(f"it holds poisson_ratio = {nu:g} and sphere_compliance = {share:.2f}, while this pair's "
                         f"yielding {softer[1]} has ν = {pair_nu:g} and the elastic body carries "
                         f"{pair_share:.2f} of the compliance (steel on steel: 0.3 and 0.50, which raise the peak "
                         "force ~4 % and the restitution ~5 % over the defaults); set the [contact] options "
                         f"poisson_ratio = {pair_nu:g}, sphere_compliance = {min(pair_share, 0.75):.2f}"
                         + (" (s above 0.75 lies outside the calibration)" if pair_share > 0.75 else ""))
    if not notes:
        return None
    return "epp calibration: " + "; ".join(notes)


def _pressure(sphere, target_material, law, result):
    softer = _softer_body(sphere.material, target_material)
    if not law.elastic or softer is None:
        return None
    strength, body = softer
    modulus = float(effective_modulus(sphere.material.youngs_modulus, sphere.material.poisson_ratio,
                                      target_material.youngs_modulus, target_material.poisson_ratio))
    pressure = float(hertz_peak_pressure(result.peak_force, modulus, float(sphere.radius)))
    limit = YIELD_PRESSURE_FACTOR * strength
    if pressure <= limit:
        return None
    return (f"contact pressure: the elastic Hertz peak pressure {pressure:.4g} Pa exceeds the "
            f"yield pressure {limit:.4g} Pa ({YIELD_PRESSURE_FACTOR} S_y, with S_y = {strength:.4g} Pa of the "
            f"{body}, the softer body): the contact yields; use a plastic law ('epp', calibrated on finite elements; or 'stronge', 'yigit-christoforou')")


def _indentation(sphere, result):
    ratio = float(result.max_indentation) / float(sphere.radius)
    if not ratio > INDENTATION_RATIO_LIMIT:
        return None
    return (f"indentation: the largest indentation {float(result.max_indentation):.4g} m is "
            f"{ratio:.3g} sphere radii (limit {INDENTATION_RATIO_LIMIT}): Hertz-type contact "
            "laws assume a contact radius small against the sphere radius")


def _speed(target_material, result):
    density = getattr(target_material, "density", None)
    if density is None:
        return None
    wave_speed = math.sqrt(float(target_material.youngs_modulus) / float(density))
    ratio = float(result.velocity) / wave_speed
    if not ratio > SPEED_RATIO_LIMIT:
        return None
    return (f"impact speed: V0 = {float(result.velocity):.4g} m/s is {ratio:.3g} of the target's "
            f"bar wave speed sqrt(E/ρ) = {wave_speed:.4g} m/s (limit {SPEED_RATIO_LIMIT}): the "
            "model assumes impact speeds small against the wave speeds (no stress-wave, "
            "plastic-wave or penetration effects)")


def _target_displacement(target, result):
    history = getattr(result, "history", None)
    if history is not None and "target_displacement_m" in history:
        return float(np.max(np.abs(history["target_displacement_m"])))
    if getattr(result, "max_target_displacement", None) is not None:
        return float(result.max_target_displacement)
    details = getattr(result, "details", None)  # an infinite-structure answer: its own displacement
    if getattr(details, "max_target_displacement", None) is not None:
        return float(details.max_target_displacement)
    return float(result.peak_force) * float(target.static_compliance())  # quasi-static estimate


def _deflection(target, result):
    if getattr(target, "kind", None) != "plate":
        return None
    deflection = _target_displacement(target, result)
    ratio = deflection / float(target.thickness)
    if not ratio > DEFLECTION_RATIO_LIMIT:
        return None
    return (f"plate deflection: the struck point moves {deflection:.4g} m, {ratio:.3g} plate "
            f"thicknesses (limit {DEFLECTION_RATIO_LIMIT}): large deflection, membrane "
            "stiffening is not modelled")


def _contact_time(result):
    value = getattr(result, "contact_time", None)
    if value is None:
        intervals = np.asarray(result.contact_intervals, dtype=float)
        value = float(intervals[-1, 1] - intervals[0, 0]) if intervals.size else 0.0
    return float(value)


def _structural_theory(target, result):
    intervals = np.asarray(getattr(result, "contact_intervals", np.empty((0, 2))), dtype=float).reshape(-1, 2)
    if target is None or intervals.size == 0 or not np.all(np.isfinite(intervals[0])):
        return None
    first = float(intervals[0, 1] - intervals[0, 0])
    if first <= 0.0:
        return None
    frequency = math.pi / first
    if not beyond_shear_theory(target, frequency):
        return None
    cutoff = thickness_shear_frequency(target)
    return (f"structural theory: the first contact ({first:.4g} s) excites {frequency:.4g} rad/s, above "
            f"{SHEAR_VALIDITY_FRACTION:g} × the thickness-shear cut-off {cutoff:.4g} rad/s of this "
            f"{target.theory} {target.kind}: waves as short as the thickness, which the theory does "
            "not describe")


def _point_load(target, result):
    if not getattr(target, "point_load_diverges", False) or not str(getattr(result, "method", "")).startswith("modal"):
        return None
    if (getattr(result, "settings", None) or {}).get("contact_radius_m"):
        return None  # spread over the contact patch
    return ("point load: a Mindlin plate struck at a point has a logarithmically divergent point-load "
            "deflection, so this peak force falls with every doubling of the mode cut-off and has "
            "no converged value; a contact law with a geometry (the sphere's Hertz law) spreads the force over "
            "the contact patch and converges")


def _support_distance(target):
    depth = getattr(target, "section_depth", None)
    if target is None or depth is None:
        return None
    distance = target.distance_to_nearest_support()
    if distance >= depth:
        return None
    return (f"support: the impact point is {distance:.4g} m from a supported {target.kind} boundary, "
            f"closer than the {target.kind}'s depth {depth:.4g} m: the {target.theory} theory's point "
            "load and support reaction overlap there (local shear and bearing stresses, not described); "
            "strike at least one depth away from supports")


def _reflections(target, result):
    if getattr(result, "method", None) not in INFINITE_STRUCTURE_METHODS or target is None:
        return None
    distance = target.wave_return_distance()
    contact = _contact_time(result)
    if math.isinf(contact):
        return (f"reflections: the contact never ends on the infinite {target.kind}, so waves "
                f"reflected {distance:.4g} m away always return during it: simulate the finite "
                f"{target.kind}")
    group_velocity = target.flexural_group_velocity(2.0 * math.pi / contact)  # at the contact's frequency
    round_trip = 2.0 * distance / group_velocity
    if round_trip >= contact:
        return None
    return (f"reflections: flexural waves reflected {distance:.4g} m away return after "
            f"{round_trip:.4g} s, before the contact ends ({contact:.4g} s): the infinite-"
            f"{target.kind} asymptote does not hold; simulate the finite {target.kind}")
