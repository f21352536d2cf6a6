"""What every answer for a physical case shares: its map law, its refusal, its scaling to newtons.

:func:`impactmaps.lookup` (:mod:`impactmaps.cases.case_lookup`) answers a case from a shipped map or an
on-demand tile (:mod:`impactmaps.cases.on_demand`); both name the case's map law
(:func:`case_map_law`), compare its dimensionless groups with a map structure's
(:meth:`impactmaps.targets.base.Target.similarity_groups`), refuse with a :class:`NoMapError` and scale the reading to
newtons (:func:`scaled_answer`, :func:`plastic_case_answer`) through this module.
"""

from __future__ import annotations

from .numbers import case_dimensionless
from ..closed_forms.hertz_similarity import hertz_numbers
from ..contact.geometry import contact_radius_function
from ..solvers.modal_settings import uses_patch
from ..targets.map_structure import STRUCTURE_MATCH_RTOL
from ..maps.family.accuracy import status_notes
from ..maps.read.lookup import point_answer
from ..maps.family.builtin_families import family_layout
from ..maps.family.map_family import available_map_families
from ..maps.read.reader import OutsideMapError, UnresolvedPointError

__all__ = ["CASE_MATCH_RTOL", "NoMapError", "case_map_law", "case_loads_a_patch", "scaled_answer",
           "answer", "plastic_case_answer", "plastic_answer"]


#: Relative tolerance within which a case "is" a shipped map's structure (impact point,
#: aspect ratio, slenderness, dimensionless groups): beyond it the map does not describe the
#: case (the targets' own tolerance, :data:`impactmaps.targets.map_structure.STRUCTURE_MATCH_RTOL`).
CASE_MATCH_RTOL = STRUCTURE_MATCH_RTOL


class NoMapError(ValueError):
    """No shipped map describes a case: ``what`` names what no map covers.

    The message is ``no shipped map covers this case: WHAT; run `impactmaps simulate
    CASE` instead``.
    """

    def __init__(self, case, what: str):
        self.what = what
        super().__init__(f"no shipped map covers this case: {what}; run `impactmaps simulate "
                         f"{case.source or 'CASE.toml'}` instead")


def case_map_law(case) -> str:
    """The map law of a case's contact law: ``"linear"``, ``"hertz"``, ``"yc"``, ``"stronge"``, ``"epp"``, or ``ValueError``.

    Only laws that a shipped map describes exactly are named: the linear and Hertz laws
    (axes ζ, λ), the Yigit–Christoforou law, the refined Stronge law with its default
    constants and the ``epp`` law with its default options (axes β, ζ, λ:
    :mod:`impactmaps.maps.compute.plastic_points`). Any other law is refused, naming the option
    and the maps' value where it is a mapped law at other options.
    """
    reason = f"contact law {case.law_name!r}"
    try:
        for name in available_map_families():
            if family_layout(name).describes(case.law):  # a built-in family's layout: its point solver not loaded
                return name
    except ValueError as near_miss:  # a family's law with other constants
        reason = str(near_miss)
    raise ValueError(f"no shipped map covers this case: {reason} (the shipped maps are for the linear, Hertz, "
                     "Yigit–Christoforou, default refined Stronge and default epp laws; linearising another law with K_y "
                     f"would be an unconservative guess); run `impactmaps simulate {case.source or 'CASE.toml'}` "
                     "instead")


def case_loads_a_patch(case) -> bool:
    """Whether ``simulate`` spreads this case's contact force over the contact patch: the
    target takes one under ``solver.contact_patch`` and the law has a contact radius."""
    return uses_patch(case.target, case.settings.contact_patch) and contact_radius_function(case.law) is not None


def scaled_answer(case, law: str, read) -> dict:
    """The answer for a case from ``read(ζ, λ) -> LookupResult``, a reading of a
    linear or Hertz map at the case's numbers, scaled to newtons: the Hertz numbers
    (ζ_h, λ_h, F_hs) where the case's law is a Hertz law (its ``hertzian_stiffness``)."""
    if case.law.hertzian_stiffness is not None:
        hertz = hertz_numbers(case.target, case.law, case.impactor_mass, case.velocity)
        zeta, lam = hertz.loss_factor, hertz.relative_stiffness
        found = read(zeta, lam)
        scale = hertz.force_scale
    else:
        numbers = case_dimensionless(case)
        zeta, lam = numbers["zeta"], numbers["lambda"]
        found = read(zeta, lam)
        scale = float(found.peak_force(numbers["impactor_mass_kg"], numbers["velocity_m_s"],
                                       numbers["contact_stiffness_N_m"])) / found.fmax_normalised
    return answer(found, scale, law, {"regime": found.regime, "zeta": zeta, "lambda": lam})


def answer(found, scale: float, law: str, details: dict) -> dict:
    """The dict of a case's answer: peak force [N] with its band, ``details``, the map and scale."""
    return {
        "peak_force_N": found.fmax_normalised * scale,
        "peak_force_error_N": found.fmax_error * scale,
        "fmax_normalised": found.fmax_normalised,
        "fmax_error": found.fmax_error,
        "status": found.status,
        **status_notes(found.status),
        **details,
        "map": found.map_name,
        "law": law,
        "force_scale_N": scale,
    }


def plastic_case_answer(case, kind: str, theory: str, law: str) -> dict:
    """The answer for an elastic-plastic case from the shipped (β, ζ, λ) map of its law.

    Parameters
    ----------
    case : impactmaps.cases.Case
        With a Yigit–Christoforou, default refined Stronge or default ``epp`` law.
    kind, theory : str
        The map structure's kind and theory (:func:`impactmaps.cases.case_lookup.map_for_case`).
    law : {"yc", "stronge", "epp"}

    Returns
    -------
    dict
        See :func:`impactmaps.lookup`.
    """
    def read(beta, zeta, lam):
        try:
            return point_answer(beta, zeta, lam, kind=kind, theory=theory, law=law)
        except (OutsideMapError, UnresolvedPointError) as error:
            raise NoMapError(case, str(error).split("; run")[0]) from None

    return plastic_answer(case, law, read)


def plastic_answer(case, law: str, read) -> dict:
    """The answer of :func:`impactmaps.lookup` for an elastic-plastic case
    from ``read(β, ζ, λ) -> PlasticLookup``, a reading of a plastic map (shipped or a tile) at
    the case's numbers (:func:`impactmaps.maps.compute.plastic_points.plastic_numbers`), scaled to
    newtons and joules."""
    from ..maps.compute.plastic_points import plastic_numbers  # the plastic numbers: loaded for a plastic case

    numbers = plastic_numbers(case.target, case.law, case.impactor_mass, case.velocity)
    found = read(numbers.impact_number, numbers.loss_factor, numbers.relative_stiffness)
    scale, energy = numbers.force_scale, 0.5 * case.impactor_mass * case.velocity**2
    return answer(found, scale, law, {
        "restitution": found.restitution,
        "restitution_error": found.restitution_error,
        "absorbed_energy_J": found.absorbed_energy_fraction * energy,
        "absorbed_energy_error_J": found.absorbed_energy_error * energy,
        "absorbed_energy_fraction": found.absorbed_energy_fraction,
        "absorbed_energy_error": found.absorbed_energy_error,
        "beta": numbers.impact_number,
        "zeta": numbers.loss_factor,
        "lambda": numbers.relative_stiffness,
    })
