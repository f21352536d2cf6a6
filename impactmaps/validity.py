r"""Where the impact model's assumptions fail, said out loud.

:func:`validity_warnings` checks a finished run and returns one sentence per violated
assumption; :func:`warn_if_invalid` issues them as :class:`ModelValidityWarning`. The
checks and their limits: docs/physics.rst, "Model validity checks".
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from ._checks import ModelValidityWarning
from .contact.geometry import contact_radius_function, effective_modulus
from .contact.range_checks import law_warnings
from .contact.plastic.epp import LARGEST_SPHERE_COMPLIANCE
from .targets.shear_range import SHEAR_VALIDITY_FRACTION, beyond_shear_theory, thickness_shear_frequency

__all__ = [
    "DEFLECTION_RATIO_LIMIT",
    "NEAR_FIELD_SHARE_LIMIT",
    "SPEED_RATIO_LIMIT",
    "YIELD_PRESSURE_FACTOR",
    "ForceAnswer",
    "case_warnings",
    "force_answer",
    "hertz_peak_pressure",
    "validity_warnings",
    "warn_if_invalid",
]

YIELD_PRESSURE_FACTOR = 1.6  # mean contact pressure at yield / S_y of the softer body
SPEED_RATIO_LIMIT = 0.01  # V0 / sqrt(E/ρ) of the target
DEFLECTION_RATIO_LIMIT = 0.5  # plate deflection / thickness
INFINITE_STRUCTURE_METHODS = ("infinite-plate", "infinite-beam")
#: Estimated near-field compliance of a plate without a 3D-consistent near field (a laminate) over
#: the contact's secant compliance at the peak force, above which a run warns
#: (:func:`impactmaps.targets.plates.near_field.near_field_estimate`; on isotropic plates the
#: near field moved the peak force by up to 0.7 times this share, docs/contact_patch.rst).
NEAR_FIELD_SHARE_LIMIT = 0.03


def hertz_peak_pressure(force, effective_modulus, radius):
    """Hertz peak pressure ``p0 = (6 F E*²/(π³ R²))^{1/3}`` [Pa] of a force F ≥ 0 [N] (scalar or
    array), E* [Pa] and effective radius R [m].
    """
    force = np.asarray(force, dtype=float)
    return np.cbrt(6.0 * force * effective_modulus**2 / (math.pi**3 * radius**2))


def validity_warnings(sphere, target_material, law, target, result) -> list[str]:
    """The model assumptions a finished run violates, one sentence each (empty: none).

    Parameters
    ----------
    sphere : Sphere
        The impactor (radius [m], material with E [Pa], ν, optional S_y [Pa]).
    target_material : material-like
        ``youngs_modulus`` [Pa], ``poisson_ratio``, optional ``density`` [kg/m³] and
        ``yield_strength`` [Pa].
    law : ContactLaw
        The law the run used.
    target : Plate, Beam or None
        The structure (None for a half-space).
    result : ImpactResult or AsymptoteResult
        Its ``peak_force`` [N], ``max_indentation`` [m], ``velocity`` [m/s], ``method`` and,
        when present, history, displacement and contact times.
    """
    checks = (_pressure(sphere, target_material, law, result), _epp_calibration(sphere, target_material, law),
              *law_warnings(law, result, radius=sphere.radius),
              _speed(target_material, result), _deflection(target, result),
              _structural_theory(target, result), _point_load(target, result), _support_distance(target),
              _contact_radius(target, law, result), _reflections(target, result), _near_field(target, result))
    return [message for message in checks if message]


@dataclass(frozen=True)
class ForceAnswer:
    """A peak force without a run (a map's reading, or the half-space bound), as
    :func:`validity_warnings` reads it: ``peak_force`` [N], ``max_indentation`` on the law's
    loading curve [m], ``velocity`` [m/s], ``method`` (``"map"`` or ``"half-space bound"``).
    """

    peak_force: float
    max_indentation: float
    velocity: float
    method: str
    contact_intervals: tuple = ()
    history: None = None
    max_target_displacement: float | None = None


def force_answer(law, impactor_mass: float, velocity: float, peak_force: float | None = None) -> ForceAnswer:
    """A :class:`ForceAnswer` at ``peak_force`` [N] (a map's), or at the half-space peak force
    when ``None``; the indentation [m] from the law's loading curve.
    """
    from .closed_forms.halfspace import single_law_parameters

    params, kernel = single_law_parameters(law), law.python_kernel
    bound = float(law.indentation_for_energy(0.5 * float(impactor_mass) * float(velocity) ** 2))
    if peak_force is None:
        return ForceAnswer(float(kernel(bound, bound, params)[0]), bound, float(velocity), "half-space bound")
    low, high = 0.0, bound
    while float(kernel(high, high, params)[0]) < peak_force and high < 1e6 * bound:
        high *= 2.0
    for _ in range(80):
        middle = 0.5 * (low + high)
        low, high = (middle, high) if float(kernel(middle, middle, params)[0]) < peak_force else (low, middle)
    return ForceAnswer(float(peak_force), high, float(velocity), "map")


def case_warnings(case, result=None, peak_force: float | None = None) -> list[str]:
    """The validity warnings of a case, the one set every command prints: from its ``result``
    (``simulate``, ``fd``), else from a map's ``peak_force`` [N], else from the half-space
    peak force (an upper bound for an elastic law).
    """
    if result is None:
        result = force_answer(case.law, case.impactor_mass, case.velocity, peak_force)
    target = None if case.target_type == "halfspace" else case.target
    borrowed = _borrowed_yield_strength(case)
    return validity_warnings(case.sphere, case.target_material, case.law, target, result) + (
        [borrowed] if borrowed else [])


def _borrowed_yield_strength(case) -> str | None:
    """A plastic law left to yield at the impactor's strength [Pa] because the target has none
    (a laminate, a brittle solid) while the impactor is the stiffer body, so that which body
    yields first cannot be told (:func:`_softer_body`); None otherwise or when
    ``contact.yield_strength`` is given."""
    impactor, target = case.sphere.material, case.target_material
    if case.law.elastic or "yield_strength" in case.contact_options \
            or getattr(target, "yield_strength", None) is not None or impactor.yield_strength is None \
            or _softer_body(impactor, target) is not None:
        return None
    key = "target.yield_strength" if hasattr(target, "plies") else "contact.yield_strength"
    return (f"yield strength: the {case.law_name} law yields at the impactor's S_y = {float(impactor.yield_strength):.4g} Pa "
            f"({impactor.name}) because the target has none, although the impactor is the stiffer body (a dent in "
            f"the ball, not in the target); give the target's own strength in {key} (for a laminate, Christoforou "
            "& Yigit 1998 take S_y = 2 S_u, S_u the shear strength of the fibres: docs/contact_laws.rst) or "
            "contact.yield_strength")


def target_warnings(target, result) -> list[str]:
    """The checks that need only the structure and the run (its ``contact_intervals`` [s],
    ``method``, ``settings``): a first contact beyond the shear theory's range, a
    non-converging Mindlin point load and a patch-loaded plate without a near field. Empty
    when none fails.
    """
    checks = (_structural_theory(target, result), _point_load(target, result), _near_field(target, result))
    return [message for message in checks if message]


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
    """``(yield strength [Pa], "impactor"|"target")`` of the body whose contact yields first, or
    None when that cannot be told (one strength known and that body not the softer).
    """
    bodies = (("impactor", sphere_material), ("target", target_material))
    known = [(float(m.yield_strength), name) for name, m in bodies if getattr(m, "yield_strength", None) is not None]
    if len(known) == 2:
        return known[1] if known[1][0] <= known[0][0] else known[0]
    if not known:
        return None
    strength, name = known[0]
    moduli = {name: float(getattr(m, "youngs_modulus", math.nan)) for name, m in bodies}
    other = "target" if name == "impactor" else "impactor"
    return (strength, name) if moduli[name] <= moduli[other] else None


def _epp_calibration(sphere, target_material, law):
    """The ``epp`` law's options (ν, sphere_compliance) against the pair it is used for
    (docs/epp_calibration.rst).
    """
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
            elastic_name = "target" if softer[1] == "impactor" else "impactor"
            notes.append(f"it holds poisson_ratio = {nu:g} and sphere_compliance = {share:.2f}, while this pair's "
                         f"yielding {softer[1]} has ν = {pair_nu:g} and the elastic {elastic_name} carries "
                         f"{pair_share:.2f} of the compliance 1/E* (the option sphere_compliance is the elastic "
                         "body's share; steel on steel: 0.3 and 0.50, which raise the peak force ~4 % and the "
                         f"restitution ~5 % over the defaults); set the law options poisson_ratio = {pair_nu:g}, "
                         f"sphere_compliance = {min(pair_share, LARGEST_SPHERE_COMPLIANCE):.2f} ([contact] in a case "
                         "file, --law-option NAME=VALUE on the halfspace command)"
                         + (f" (s above {LARGEST_SPHERE_COMPLIANCE} lies outside the calibration)"
                            if pair_share > LARGEST_SPHERE_COMPLIANCE else ""))
        if softer[1] == "impactor":
            notes.append("the impactor yields first (its yield strength is the lower), while the law's FE "
                         "model is an elastic sphere pressed into a yielding flat: a yielding ball is not what it "
                         "was calibrated on (a harder ball, e.g. the catalogue's bearing-steel-52100, is what "
                         "impact tests use)")
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
    if getattr(target, "kind", None) != "plate" or getattr(result, "method", None) == "half-space bound":
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


def _contact_radius(target, law, result):
    from .targets.options import is_shear_deformable

    if getattr(target, "kind", None) != "plate" or not is_shear_deformable(getattr(target, "theory", "")):
        return None  # a shear-deformable (Mindlin) plate
    radius_of = contact_radius_function(law)  # as the modal solver's patch takes it
    if radius_of is None:
        return None
    radius = radius_of(max(float(result.max_indentation), 0.0))
    if radius <= 0.5 * float(target.thickness):
        return None
    return (f"contact radius: {radius:.4g} m at the largest indentation exceeds half the plate thickness "
            f"{float(target.thickness):.4g} m: Mindlin theory and its omitted thickness-shear branches are not "
            "reliable under such a load")


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


def _near_field(target, result):
    from .targets.plates import near_field

    radius = (getattr(result, "settings", None) or {}).get("contact_radius_m")
    if not radius or getattr(target, "kind", None) != "plate" or not getattr(target, "point_load_diverges", False):
        return None  # a Mindlin plate under the contact patch
    if near_field.isotropic_constants(target) is not None or not result.peak_force > 0.0:
        return None  # isotropic: its near field is built
    contact = float(result.max_indentation) / float(result.peak_force)  # secant compliance at the peak [m/N]
    share = near_field.near_field_estimate(target, float(radius)) / contact
    if share <= NEAR_FIELD_SHARE_LIMIT:
        return None
    return (f"near field: this plate has no 3D-consistent near field under the contact patch (built for isotropic "
            f"plates only), and the isotropic kernel estimates that Mindlin theory counts {share:.0%} of the contact's "
            f"own compliance at the peak force twice there, so the peak force is likely low (on the isotropic plates "
            f"measured, by up to 0.7 times that share): check it against a 3D model (docs/contact_patch.rst)")
