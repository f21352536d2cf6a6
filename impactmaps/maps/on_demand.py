"""On-demand maps: the answer for a case that no shipped map describes.

The shipped maps cover a few structure families (:mod:`impactmaps.maps.case_lookup`). A
case with a linear or Hertz contact law whose target a
:class:`~impactmaps.maps.structures.MapStructure` can write exactly — an isotropic,
undamped beam or plate of any supports, impact point, aspect ratio, slenderness and
Poisson ratio (:func:`case_structure`) — is answered from a small tile of the map of
exactly that structure around the case's (ζ, λ), built once and cached
(:mod:`impactmaps.maps.tiles`). A Hertz impact that ``simulate`` loads over the contact
patch (Mindlin SSSS plates by default) has a third number, the patch number
``P = sqrt(R α_m)/h`` (:mod:`impactmaps.hertz_similarity`); its tile is of that P.

Everything else stays refused with the reason: a target the structure cannot write
(orthotropic or laminated, structural damping, a beam section whose shear or rotary
inertia no rectangle of any Poisson ratio has), a tile point next to the case that is
``unresolved`` (beyond the structural theory's range, or more modes than the sweep's cap
of :data:`~impactmaps.maps.sweep.MAX_MODES` below its cut-off). Never the nearest map.
"""

from __future__ import annotations

from ..hertz_similarity import patch_number
from ..solvers.modal import ModalSettings
from .case_answer import CASE_MATCH_RTOL, NoMapError, case_loads_a_patch, family_groups, scaled_answer
from .lookup import read_map
from .points import MAX_MODES
from .structures import MapStructure
from .tiles import cached_tile, tile_for

__all__ = ["case_structure", "lookup_on_demand"]

#: Significant digits kept of a case's shape numbers and patch number: cases that agree
#: to them share a tile (far below CASE_MATCH_RTOL, which the structure is checked to).
_DIGITS = 12
#: The slenderness given to a structure whose theory does not depend on it (Euler,
#: Kirchhoff under a point load): the shipped maps' value.
_ANY_SLENDERNESS = 20.0
#: The Poisson ratio given to a beam whose response does not depend on it (Euler).
_ANY_POISSON = 0.3


def _rounded(value: float) -> float:
    return float(f"{float(value):.{_DIGITS}g}")


def case_structure(case, law: str) -> tuple[MapStructure, float | None]:
    """The :class:`MapStructure` that describes ``case`` exactly, and its patch number.

    Parameters
    ----------
    case : impactmaps.cases.Case
        A case on a beam or a plate.
    law : {"linear", "hertz"}
        The case's map law (:func:`impactmaps.maps.case_lookup.case_map_law`).

    Returns
    -------
    (MapStructure, float or None)
        The structure (slenderness and Poisson ratio only where they matter: Timoshenko
        and Rayleigh beams, Mindlin plates, plates with other edges than SSSS, a patch
        load) and the patch number P of a Hertz case that ``simulate`` loads over the
        contact patch (None otherwise).

    Raises
    ------
    ValueError
        Naming the ratio (shear stiffness, rotary inertia, D22/D11, damping ratio …) in
        which the case differs from every such structure.
    """
    target = case.target
    patch = law == "hertz" and case_loads_a_patch(case)
    if case.target_type == "beam":
        shear_deformable = target.theory != "euler"
        if shear_deformable and target.slenderness is None:
            raise ValueError(f"a {target.theory} beam without a height (its slenderness is unknown)")
        fields = {"supports": target.supports, "impact_fraction": (_rounded(target.impact_position / target.length),),
                  "slenderness": _rounded(target.slenderness) if shear_deformable else _ANY_SLENDERNESS,
                  # the shear group of a rectangle, S L²/EI = 5 s²/(1 + ν) (k = 5/6): the ν it implies
                  "poisson_ratio": _rounded(5.0 * target.slenderness**2 * target.bending_stiffness
                                            / (target.shear_stiffness * target.length**2) - 1.0)
                  if shear_deformable else _ANY_POISSON}
    else:
        side = target.length_x
        fields = {"supports": target.edges, "aspect_ratio": _rounded(target.length_y / side),
                  "impact_fraction": tuple(_rounded(x / length) for x, length in
                                           zip(target.impact_point, (target.length_x, target.length_y))),
                  "slenderness": _rounded(side / target.thickness) if target.theory == "mindlin" or patch
                  else _ANY_SLENDERNESS}
        if target.theory == "mindlin" or target.edges != "SSSS":  # the Navier SSSS Kirchhoff plate has no ν
            fields["poisson_ratio"] = _rounded(target.D12 / target.D11)
    structure = MapStructure(kind=case.target_type, theory=target.theory, **fields)
    _check_describes(structure, target, "poisson_ratio" in fields)
    number = None
    if patch:
        number = _rounded(patch_number(target, case.law, case.impactor_mass, case.velocity))
    return structure, number


def _check_describes(structure: MapStructure, target, poisson: bool) -> None:
    """``ValueError`` naming the first dimensionless group in which ``structure`` differs from
    ``target`` (for a plate also D12/D11 if ``poisson``: its response depends on ν)."""
    reference = structure.build()

    def groups(of):
        extra = {"D12/D11": of.D12 / of.D11} if of.structure == "plate" and poisson else {}
        return family_groups(of) | extra

    wanted = groups(reference)
    for name, value in groups(target).items():
        if not (abs(value - wanted[name]) <= CASE_MATCH_RTOL * abs(wanted[name]) if wanted[name] else value == 0.0):
            raise ValueError(f"{name} = {value:.6g} where the isotropic, undamped {structure.name} has "
                             f"{wanted[name]:.6g} (an orthotropic or laminated plate, another beam section or "
                             "structural damping is not a map structure)")


def lookup_on_demand(case, law: str, refusal: NoMapError, cache_dir=None, notify=None) -> dict:
    """:func:`impactmaps.maps.case_lookup.lookup_case` of a case no shipped map describes.

    Parameters
    ----------
    case : impactmaps.cases.Case
    law : {"linear", "hertz"}
    refusal : NoMapError
        Why no shipped map describes the case (:func:`~impactmaps.maps.case_lookup.map_for_case`);
        part of the message when no tile can answer either.
    cache_dir : path-like, optional
        The tile cache (:func:`impactmaps.maps.tiles.cache_directory`).
    notify : callable, optional
        Called with one line before a tile is built.

    Returns
    -------
    dict
        The keys of ``lookup_case``, ``map`` naming the tile, plus ``cache_file`` (the
        tile's file) and, for a patch-loaded Hertz case, ``patch_number``.

    Raises
    ------
    NoMapError
        When no map structure describes the case (:func:`case_structure`) or the tile
        holds no value next to the case's (ζ, λ).
    """
    try:
        structure, patch = case_structure(case, law)
    except ValueError as error:
        raise NoMapError(case, f"{refusal.what}, and no on-demand map describes it: {error}") from None
    settings, built = _tile_settings(case, patch), {}

    def read(zeta, lam):
        key = tile_for(structure, law, patch, zeta, lam, settings)
        dataset, built["path"] = cached_tile(key, cache_dir, notify=notify)
        try:
            return read_map(dataset, zeta, lam, structure=structure.kind, theory=structure.theory, name=key.name,
                            law=law)
        except ValueError:  # next to an unresolved point
            raise NoMapError(case, f"{refusal.what}, and the {key.name} holds no value next to it, at "
                             f"(ζ, λ) = ({zeta:.4g}, {lam:.4g}) (unresolved: the contact frequency lies beyond the "
                             f"range of the {structure.theory} theory, or a point needs more modes than the sweep's "
                             f"cap of {MAX_MODES} modes below its cut-off and no exact asymptote answers it)") from None

    answer = scaled_answer(case, law, read)
    answer["cache_file"] = None if built["path"] is None else str(built["path"])
    if patch is not None:
        answer["patch_number"] = patch
    return answer


def _tile_settings(case, patch):
    """The tile's ModalSettings: the shipped maps' defaults, with the case's ``contact_patch``
    for a patch-loaded tile (the load it asks for)."""
    return ModalSettings() if patch is None else ModalSettings(contact_patch=case.settings.contact_patch)
