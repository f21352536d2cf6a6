"""On-demand maps: the answer for a case that no shipped map describes.

The shipped maps cover a few structure families (:func:`impactmaps.lookup`). A
case whose target names a reference structure (:meth:`Target.map_structure
<impactmaps.targets.base.Target.map_structure>`: an isotropic, undamped beam or plate of
any supports, impact point, aspect ratio, slenderness and Poisson ratio, or an undamped
orthotropic or symmetric laminated plate, whose reference carries its stiffness ratios;
:func:`case_structure`) is answered from a small tile of the map of exactly that structure
around the case's numbers, built once and cached (:mod:`impactmaps.maps.compute.tiles`): (ζ, λ) for
a linear or Hertz law, (β, ζ, λ) for an elastic-plastic one (Yigit–Christoforou, default
Stronge, default ``epp``; read as the shipped plastic maps,
:func:`impactmaps.maps.read.lookup.read_plastic`). A Hertz impact that ``simulate``
loads over the contact patch (Mindlin SSSS plates by default) has a third number, the
patch number ``P = sqrt(R α_m)/h`` (:mod:`impactmaps.closed_forms.hertz_similarity`); its tile is of
that P. The tile of a plate with a clamped or free edge, or of an orthotropic or laminated
plate, is one cell of the shipped maps' grid
density split into four (:func:`impactmaps.maps.compute.tiles.refined_cell`): its band is
measured from the points that split it, as in the shipped maps' refinements (less the share
of a sensitive point's spread, :func:`impactmaps.maps.compute.tiles.tile_refinement`), and its
points of a heavy impactor use ``simulate``'s patch cut-off
(:func:`impactmaps.maps.compute.tiles.with_corner_cutoff`).

Everything else stays refused with the reason: a target the structure cannot write
(structural damping, a beam section whose shear or rotary
inertia no rectangle of any Poisson ratio has), an elastic-plastic impact on a Mindlin
plate (the sphere radius a fourth number), a tile point next to the case that is
``unresolved`` (beyond the structural theory's range, or more modes than the sweep's cap
of :data:`~impactmaps.maps.family.structures.MAX_MODES` below its cut-off; on a clamped or
mixed-edge plate, a cut-off above what its largest Ritz basis resolves with that resolution
below 8 contact frequencies: a point above the resolution but 8 ω up is answered as
``simulate`` answers it, :func:`impactmaps.maps.compute.points.capped_resolvable`). Never the nearest map.
"""

from __future__ import annotations

from ..closed_forms.hertz_similarity import patch_number
from ..solvers.modal_settings import ModalSettings
from ..solvers.mode_budget import MIN_CAPPED_CUTOFF_RATIO
from ..targets.map_structure import REFERENCE_POISSON, REFERENCE_SLENDERNESS
from .case_answer import NoMapError, case_loads_a_patch, plastic_answer, scaled_answer
from ..maps.read.lookup import read_map
from ..maps.read.lookup import read_plastic
from ..maps.read.reader import prepare_map
from ..maps.family.builtin_families import family_layout
from ..maps.family.structures import MAX_MODES
from ..maps.family.map_family import map_family
from ..maps.family.structures import MapStructure
from ..maps.compute.tiles import cached_tile, tile_for, tile_refinement

__all__ = ["case_structure", "answer_on_demand"]

#: Significant digits kept of a case's shape numbers and patch number: cases that agree
#: to them share a tile (far below CASE_MATCH_RTOL, which the structure is checked to).
_DIGITS = 12


def _rounded(value: float) -> float:
    return float(f"{float(value):.{_DIGITS}g}")


def case_structure(case, law: str) -> tuple[MapStructure, float | None]:
    """The :class:`MapStructure` that describes ``case`` exactly, and its patch number.

    The structure is the one the target names (:meth:`impactmaps.targets.base.Target.map_structure`,
    its numbers rounded to 12 significant digits so that cases that agree to them share a
    tile), with the reference slenderness and Poisson ratio where the response does not
    depend on them.

    Parameters
    ----------
    case : impactmaps.cases.Case
        A case on a beam or a plate.
    law : str
        The case's map law (:func:`impactmaps.cases.case_answer.case_map_law`).

    Returns
    -------
    (MapStructure, float or None)
        The structure and the patch number P of a Hertz case that ``simulate`` loads over
        the contact patch (None otherwise).

    Raises
    ------
    ValueError
        Naming the ratio (shear stiffness, rotary inertia, D22/D11, damping ratio …) in
        which the case differs from every such structure; for a law with more numbers than
        ζ and λ (an elastic-plastic one), a target loaded over the contact patch (its radius
        adds the sphere radius as a number) or one whose point-load deflection diverges.
    """
    family = map_family(law)
    patch = case_loads_a_patch(case)
    target = case.target
    if family.extra_axes and (patch or target.point_load_diverges):
        raise ValueError("an elastic-plastic impact on a target that simulate loads over the contact patch, or whose "
                         "point-load deflection diverges (a Mindlin plate): its response depends on the sphere radius "
                         "as a fourth number")
    patch = patch and family.patch_loadable
    key = target.map_structure(patch_loaded=patch)
    if key is None:
        raise ValueError(target.map_structure_refusal(patch_loaded=patch))
    structure = MapStructure(kind=key.kind, theory=key.theory, supports=key.supports,
                             aspect_ratio=_rounded(key.aspect_ratio),
                             impact_fraction=tuple(_rounded(f) for f in key.impact_fraction),
                             slenderness=REFERENCE_SLENDERNESS if key.slenderness is None else _rounded(key.slenderness),
                             poisson_ratio=REFERENCE_POISSON if key.poisson_ratio is None
                             else _rounded(key.poisson_ratio),
                             stiffness=None if key.stiffness is None else tuple(_rounded(r) for r in key.stiffness))
    number = None
    if patch:
        number = _rounded(patch_number(target, case.law, case.impactor_mass, case.velocity))
    return structure, number


def answer_on_demand(case, law: str, refusal: NoMapError, cache_dir=None, notify=None, progress=None) -> dict:
    """:func:`impactmaps.lookup` of a case no shipped map describes: from a map tile.

    Parameters
    ----------
    case : impactmaps.cases.Case
    law : str
        The case's map law (``"linear"``, ``"hertz"``, ``"yc"``, ``"stronge"``, ``"epp"``).
    refusal : NoMapError
        Why no shipped map describes the case (:func:`~impactmaps.cases.case_lookup.map_for_case`);
        part of the message when no tile can answer either.
    cache_dir : path-like, optional
        The tile cache (:func:`impactmaps.maps.compute.tiles.cache_directory`).
    notify : callable, optional
        Called with one line before a tile is built.
    progress : callable, optional
        Called as ``progress(done, total)`` (points) while a tile is built.

    Returns
    -------
    dict
        The keys of a case's answer (:func:`impactmaps.lookup`) (an elastic-plastic case: with ``restitution``,
        ``absorbed_energy_J`` and their bands), ``map`` naming the tile, plus ``cache_file``
        (the tile's file) and, for a patch-loaded Hertz case, ``patch_number``.

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

    ritz = structure.kind == "plate" and structure.build().bounded_modes
    cap = (f"more modes than the plate's largest Ritz basis resolves, that resolution lying less than "
           f"{MIN_CAPPED_CUTOFF_RATIO:g} contact frequencies up (as simulate refuses it)," if ritz else
           f"more modes than the sweep's cap of {MAX_MODES} modes")

    def unresolved(name, numbers):
        return NoMapError(case, f"{refusal.what}, and the {name} holds no value next to it, at "
                                f"{numbers} (unresolved: the contact frequency lies beyond the range of the "
                                f"{structure.theory} theory, or a point needs {cap} below its cut-off and no "
                                "exact asymptote answers it)")

    def realisable(**numbers):  # a tile around numbers no map point can be realised at answers nothing
        for name, value in numbers.items():
            low, high = map_family(law).axis_range(name)
            if not low <= value <= high:
                symbol = {"zeta": "ζ", "lambda_": "λ", "beta": "β"}.get(name, name)
                raise NoMapError(case, f"{refusal.what}, and no on-demand map reaches its {symbol} = {value:.4g}: "
                                       f"the {law} map points are realised for {symbol} in [{low:g}, {high:g}]")

    if map_family(law).extra_axes:  # an elastic-plastic family: (β, ζ, λ)
        def read(beta, zeta, lam):
            realisable(beta=beta, zeta=zeta, lambda_=lam)
            key = tile_for(structure, law, None, zeta, lam, settings, extra=(beta,), cache_dir=cache_dir)
            dataset, built["path"] = cached_tile(key, cache_dir, notify=notify, progress=progress)
            try:
                return read_plastic(dataset, law, (beta, zeta, lam), name=key.name, where=key.name)
            except ValueError:  # next to an unresolved point
                raise unresolved(key.name, f"(β, ζ, λ) = ({beta:.4g}, {zeta:.4g}, {lam:.4g})") from None

        answer = plastic_answer(case, law, read)
    else:
        def read(zeta, lam):
            realisable(zeta=zeta, lambda_=lam)
            key = tile_for(structure, law, patch, zeta, lam, settings, cache_dir=cache_dir)
            dataset, built["path"] = cached_tile(key, cache_dir, notify=notify, progress=progress)
            refinement = tile_refinement(dataset)  # a refined cell: its re-impact floor relative to F̄max
            try:
                prepared = prepare_map(dataset, family_layout(law), refinement, relative_floor=refinement is not None)
                return read_map(dataset, zeta, lam, kind=structure.kind, theory=structure.theory, name=key.name,
                                law=law, prepared=prepared)
            except ValueError:  # next to an unresolved point
                raise unresolved(key.name, f"(ζ, λ) = ({zeta:.4g}, {lam:.4g})") from None

        answer = scaled_answer(case, law, read)
    answer["cache_file"] = None if built["path"] is None else str(built["path"])
    if patch is not None:
        answer["patch_number"] = patch
    return answer


def _tile_settings(case, patch):
    """The tile's ModalSettings: the shipped maps' defaults, with the case's ``contact_patch``
    for a patch-loaded tile (the load it asks for)."""
    return ModalSettings() if patch is None else ModalSettings(contact_patch=case.settings.contact_patch)
