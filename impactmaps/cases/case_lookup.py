"""The one lookup: a point of any map family, a slenderness, or a physical case, without a simulation.

:func:`lookup` (``impactmaps.lookup``) answers numbers from the shipped maps
(:func:`impactmaps.maps.read.lookup.point_answer`) and a case from the map that describes it.
:func:`map_for_case` reads from a case everything that selects a map — structure kind,
theory, supports, impact point, aspect ratio, slenderness, contact law — and names the
map family that describes it exactly, or refuses with the reason (never the nearest
map); the map's answer is then scaled to newtons with its band. A case that no shipped map describes but whose target names a
reference structure (:meth:`Target.map_structure <impactmaps.targets.base.Target.map_structure>`)
is answered from a map tile built on demand and cached (:mod:`impactmaps.cases.on_demand`),
for the linear, Hertz and elastic-plastic laws alike.
"""

from __future__ import annotations

from dataclasses import replace

from ..maps.family.builtin_families import MEMBER_SLENDERNESSES, PLANE_LAWS, PLASTIC_LAWS, family_layout
from ..maps.files.shipped import SHIPPED_SLENDERNESS
from ..maps.read.lookup import point_answer
from ..maps.read.reader import OutsideMapError, UnresolvedPointError
from ..maps.read.slenderness import shipped_for
from ..targets.options import default_theory

__all__ = ["lookup", "case_slenderness", "map_for_case"]


def lookup(*numbers, case=None, kind: str | None = None, theory: str | None = None, law: str | None = None,
           slenderness: float | None = None, tolerance: float = 0.1, local_tolerance: float = 0.1,
           build: bool = True, cache_dir=None, notify=None, progress=None):
    """F̄max with its band and status from the maps, without a simulation: at a point, or for a case.

    Parameters
    ----------
    *numbers : float or array_like
        The point [-]: (ζ, λ) for the linear law, (ζ_h, λ_h) for the Hertz law, (β, ζ, λ) for an
        elastic-plastic law, inside the shipped map's range. None with ``case``.
    case : impactmaps.cases.Case, optional
        A physical case, answered from the map that describes it (:func:`map_for_case`), else
        from a map tile built on demand and cached (:mod:`impactmaps.cases.on_demand`).
    kind : {"beam", "plate"}
        Default "plate".
    theory : str
        "euler" or "timoshenko" (beams), "kirchhoff" or "mindlin" (plates); default the
        kind's classical theory.
    law : {"linear", "hertz", "yc", "stronge", "epp"}
        The map's contact law; default "linear".
    slenderness : float, optional
        Timoshenko/Mindlin, linear or Hertz law: span/thickness ≥ 10 (default the shipped 20),
        interpolated in 1/s between the slenderness members.
    tolerance, local_tolerance : float
        Regime criteria (:func:`impactmaps.maps.family.regimes.classify`).
    build : bool
        A case no shipped map describes: answer it from an on-demand tile (False: refuse it).
    cache_dir : path-like, optional
        A case's tile cache (default :func:`impactmaps.maps.compute.tiles.cache_directory`).
    notify, progress : callable, optional
        A case's tile build: ``notify(line)`` before it, ``progress(done, total)`` while it runs.

    Returns
    -------
    LookupResult, PlasticLookup or dict
        At a point: a :class:`~impactmaps.maps.read.lookup.LookupResult`, or a
        :class:`~impactmaps.maps.read.lookup.PlasticLookup` for an elastic-plastic law.
        For a case: a dict with ``peak_force_N`` and its band ``peak_force_error_N``,
        ``fmax_normalised``, ``fmax_error``, ``status``, ``zeta``, ``lambda``, ``map``, ``law``,
        ``force_scale_N`` (``regime`` for a linear or Hertz law; ``beta``, ``restitution`` and
        ``absorbed_energy_J`` with their bands for an elastic-plastic one; ``cache_file`` for a tile).

    Raises
    ------
    ValueError
        Numbers outside the map or next to an ``unresolved`` point, a value no map has, or a case
        no map describes (a :class:`~impactmaps.cases.case_answer.NoMapError` naming why).
    """
    if case is None:
        if cache_dir is not None or notify is not None or progress is not None:
            raise ValueError("cache_dir, notify and progress are for the map tile of a case (give case=...)")
        kind = "plate" if kind is None else kind
        theory = default_theory(kind) if theory is None else theory
        return point_answer(*numbers, kind=kind, theory=theory, law=law or "linear", slenderness=slenderness,
                            tolerance=tolerance, local_tolerance=local_tolerance)
    given = [name for name, value in (("numbers", numbers or None), ("kind", kind), ("theory", theory), ("law", law),
                                      ("slenderness", slenderness)) if value is not None]
    if given:
        raise ValueError(f"{', '.join(given)} with case: the case gives its numbers and the map that describes it "
                         "(leave them out)")
    return _case_answer(case, build=build, cache_dir=cache_dir, notify=notify, progress=progress)

def map_for_case(case, law: str | None = None) -> tuple[str, str]:
    """The shipped map that describes ``case`` exactly, as ``(structure, theory)``.

    A shipped map stands for a structure family (the targets of one map structure) with a
    linear or a Hertz contact law (:func:`case_map_law`): simply supported beams and SSSS square plates struck at
    the centre, Euler and Kirchhoff theory (any size: the normalised response depends on
    ζ and λ only) or Timoshenko and Mindlin at span/thickness 20. The elastic-plastic laws
    (Yigit–Christoforou, default Stronge, default ``epp``) have maps for the same structures
    except the Mindlin plate (:data:`impactmaps.maps.read.lookup.PLASTIC_MAPS`). The
    target names its reference structure (:meth:`Target.map_structure
    <impactmaps.targets.base.Target.map_structure>`); a case whose structure is no shipped
    map's is refused, never looked up in the nearest map.

    Parameters
    ----------
    case : impactmaps.cases.Case
    law : str, optional
        The case's map law when already known (default :func:`case_map_law` of the case).

    Returns
    -------
    (str, str)
        ``structure`` and ``theory`` of the map.

    Raises
    ------
    NoMapError
        (a ``ValueError``) naming what no shipped map covers (supports, impact point,
        aspect, theory, slenderness, patch load) and suggesting ``impactmaps simulate``;
        a ``ValueError`` for a contact law no map describes (:func:`case_map_law`).
    """
    from ..maps.family.structures import structure_from_name  # the targets: loaded for a case
    from ..targets.map_structure import isotropic_refusal
    from .case_answer import CASE_MATCH_RTOL, NoMapError, case_loads_a_patch, case_map_law

    def refuse(what: str):
        raise NoMapError(case, what)

    def same(value, wanted) -> bool:
        return abs(float(value) - wanted) <= CASE_MATCH_RTOL * abs(wanted)

    law = case_map_law(case) if law is None else law
    if case.solver_kind != "modal":
        refuse(f"solver.kind = {case.solver_kind!r} (the finite-difference beam has a plastic cross-section "
               "and Rayleigh theory; the maps are of elastic structures solved modally)")
    target = case.target
    key = target.map_structure()
    if key is None:
        refuse(target.map_structure_refusal())
    if key.stiffness is not None:  # an orthotropic or laminated plate: its own on-demand tile only
        refuse(isotropic_refusal(target))
    maps = family_layout(law).shipped  # the layout: the family's point solver not loaded
    shipped = [structure_from_name(name) for (kind, _), name in maps.items() if kind == key.kind]
    if not shipped:
        refuse(f"target type {key.kind!r} (maps for the {law} law: " + ", ".join(sorted({k for k, _ in maps})) + ")")
    reference = shipped[0]  # every shipped map of a kind has its supports, impact point and aspect
    beam = key.kind == "beam"
    if key.supports != reference.supports:
        refuse(f"beam supports {key.supports!r} (maps: simply supported {reference.supports!r})" if beam
               else f"plate edges {key.supports!r} (maps: {reference.supports!r})")
    if not all(same(f, wanted) for f, wanted in zip(key.impact_fraction, reference.impact_fraction)):
        refuse(f"impact at x0 = {target.impact_position:g} m of a {target.length:g} m span (maps: mid-span)" if beam
               else f"impact at {target.impact_point} m (maps: the plate centre)")
    if not same(key.aspect_ratio, reference.aspect_ratio):
        refuse(f"plate aspect ratio {key.aspect_ratio:g} (maps: square)")
    if (key.kind, key.theory) not in maps:
        refuse(f"{key.kind} theory {key.theory!r} (maps{'' if law in PLANE_LAWS else f' for the {law} law'}: "
               + ", ".join(t for s, t in maps if s == key.kind) + ")")
    if family_layout(law).patch_loadable and case_loads_a_patch(case):
        refuse(f"a Hertz impact on a {key.theory.capitalize()} plate, which simulate loads over the contact patch "
               "(the maps are point-loaded, and the patch radius is a third number, the patch number P = sqrt(R α_m)/h)")
    slenderness = key.slenderness
    if slenderness is not None and not same(slenderness, SHIPPED_SLENDERNESS):
        members = shipped_for(key.kind, key.theory, law)
        if not members or slenderness < min(MEMBER_SLENDERNESSES) * (1 - CASE_MATCH_RTOL):
            refuse(f"{key.theory} {key.kind} of slenderness {slenderness:.4g} (maps: "
                   + (f"slenderness ≥ {min(MEMBER_SLENDERNESSES):g}, interpolated between the slenderness members "
                      f"{', '.join(f'{v:g}' for v in MEMBER_SLENDERNESSES)} and the thin limit"
                      if members else f"{SHIPPED_SLENDERNESS:g}") + ")")
    wanted = replace(structure_from_name(maps[(key.kind, key.theory)]), slenderness=slenderness or SHIPPED_SLENDERNESS)
    groups = wanted.build().similarity_groups()
    for name, value in target.similarity_groups().items():
        if not (same(value, groups[name]) if groups[name] else value == 0.0):
            refuse(f"{name} = {value:.6g} (maps: {groups[name]:.6g}; another Poisson ratio of a shear-deformable "
                   "target is another family)")
    return key.kind, key.theory


def case_slenderness(case) -> float | None:
    """span/thickness of a case's target where its normalised response depends on it (a
    Timoshenko or Rayleigh beam, a Mindlin plate: :meth:`~impactmaps.targets.base.Target.map_structure`) [-];
    None otherwise (or when no reference structure describes the target)."""
    key = case.target.map_structure()
    return None if key is None else key.slenderness


def _point_loaded_mindlin(case) -> bool:
    """Whether ``simulate`` strikes this case's target at a point (no contact patch) where its
    point-load deflection diverges (a Mindlin plate: :attr:`Target.point_load_diverges
    <impactmaps.targets.base.Target.point_load_diverges>`)."""
    from .case_answer import case_loads_a_patch

    return case.target.point_load_diverges and case.solver_kind == "modal" and not case_loads_a_patch(case)


def _case_answer(case, build: bool = True, cache_dir=None, notify=None, progress=None) -> dict:
    """Peak force of a physical case from the map that describes it, or refuse (:func:`lookup`).

    A shipped map (:func:`map_for_case`) answers if one describes the case and holds its
    numbers. Otherwise (or when the numbers lie beyond the shipped map) a
    case whose target names a reference structure (isotropic, undamped beams and plates of
    any supports, impact point, aspect and slenderness; a Hertz impact under the contact
    patch adds its patch number; an elastic-plastic law its β, except on a Mindlin plate)
    is answered from an on-demand map tile, built once and cached
    (:func:`impactmaps.cases.on_demand.answer_on_demand`); anything else is refused.

    Parameters
    ----------
    case : impactmaps.cases.Case
    build : bool
        Answer a case no shipped map describes from an on-demand tile (False: refuse it,
        as without on-demand maps, whatever the cache holds).
    cache_dir : path-like, optional
        The tile cache (default :func:`impactmaps.maps.compute.tiles.cache_directory`).
    notify : callable, optional
        Called with one line of text before a tile is built (the command line prints it
        on stderr).
    progress : callable, optional
        Called as ``progress(done, total)`` (points) while a tile is built (the command line
        prints it on stderr).

    Returns
    -------
    dict
        ``peak_force_N`` with its band ``peak_force_error_N``, ``fmax_normalised`` and
        ``fmax_error``, ``status``, ``regime``, ``zeta``, ``lambda``, ``map``, ``law``.
        For a Hertz case ``zeta`` and ``lambda`` are the Hertz numbers ζ_h, λ_h and
        ``fmax_normalised`` is F_max/F_hs (``force_scale_N`` = F_hs). For an elastic-plastic
        case (Yigit–Christoforou, default Stronge) ``beta``, ``zeta``, ``lambda`` are the
        numbers of :func:`impactmaps.maps.compute.plastic_points.plastic_numbers`,
        ``fmax_normalised`` is F_max/(m V0 ω_y), and the answer adds ``restitution`` and
        ``absorbed_energy_J`` (contact dissipation), each with its ``…_error`` band; it has
        no ``regime``. An on-demand answer names its tile in ``map`` and adds
        ``cache_file`` (and ``patch_number`` for a patch-loaded Hertz case).

    Raises
    ------
    ValueError
        When no map describes the case (:func:`map_for_case`; a :class:`NoMapError`
        naming what no map covers), or its numbers lie outside the map or next to an
        unresolved point (the message names them and suggests ``impactmaps simulate``).
    """
    from .case_answer import CASE_MATCH_RTOL, NoMapError, case_map_law, plastic_case_answer, scaled_answer

    law = case_map_law(case)
    if law in PLANE_LAWS and _point_loaded_mindlin(case):
        # no map and no tile can be right: the answer depends on where the divergent
        # point-load deflection is cut (simulate: the classical residual beyond its cut-off;
        # the maps: the shear of every mode up to the sweep's mode cap). Measured on
        # 7 random cases of shipped structures: lookup below simulate by 0.2–2 % of F̄max, against
        # bands of 2e-5–3e-3
        raise NoMapError(case, "a Mindlin plate loaded at a point (a linear law, or a law without a contact radius, "
                               "or contact_patch = 'point'): its point-load deflection diverges, so the peak force "
                               "has no converged value and depends on the mode cut-off (the maps and simulate differ "
                               "by up to ~2 %); give the contact the sphere's geometry (law = \"hertz\" with the "
                               "impactor's radius) so that the force spreads over the contact patch, or use "
                               "theory = \"kirchhoff\"")
    try:
        structure, theory = map_for_case(case, law)
    except NoMapError as refusal:
        if not build or case.solver_kind != "modal" or case.target.map_structure_refusal() is not None:
            raise  # what no on-demand map can describe either
        return _answer_on_demand(case, law, refusal, cache_dir=cache_dir, notify=notify, progress=progress)
    if law in PLASTIC_LAWS:
        try:
            return plastic_case_answer(case, structure, theory, law)
        except NoMapError as error:
            if not build:
                raise
            # beyond the shipped plastic map, or next to a point it could not resolve: a tile answers or refuses
            beyond = NoMapError(case, f"its numbers lie outside the shipped {structure} {theory} {law} map or next "
                                      f"to a point it could not resolve ({error.what})")
        return _answer_on_demand(case, law, beyond, cache_dir=cache_dir, notify=notify, progress=progress)
    slenderness = case_slenderness(case)
    if slenderness is None or abs(slenderness - SHIPPED_SLENDERNESS) <= CASE_MATCH_RTOL * SHIPPED_SLENDERNESS:
        slenderness = None  # the shipped map

    def read(zeta, lam):
        return point_answer(zeta, lam, kind=structure, theory=theory, law=law, slenderness=slenderness)
    try:
        return scaled_answer(case, law, read)
    except (OutsideMapError, UnresolvedPointError) as error:
        if not build:
            raise
        # the case's structure has a shipped map, but its numbers lie beyond it or next to a
        # point the slenderness member could not resolve: a tile of the case's own structure
        # answers (its points solved exactly as the shipped map's) or refuses in turn
        beyond = NoMapError(case, f"its numbers lie outside the shipped {structure} {theory} map or next to a point "
                                  f"it could not resolve ({error})")
    return _answer_on_demand(case, law, beyond, cache_dir=cache_dir, notify=notify, progress=progress)


def _answer_on_demand(case, law: str, refusal, **options) -> dict:
    """:func:`impactmaps.cases.on_demand.answer_on_demand`, imported when a case needs a tile (it
    reaches the build side of the maps: tiles, point solvers)."""
    from .on_demand import answer_on_demand

    return answer_on_demand(case, law, refusal, **options)
