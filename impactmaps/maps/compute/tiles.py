"""Map tiles: small maps on a global lattice, built on demand and cached on disk.

A tile is 4 points a side of its family's global log lattice
(:attr:`~impactmaps.maps.family.map_family.MapFamily.tile_lattice`) around a point, for one
structure and law, solved and read exactly as the shipped maps. The tile of a plate with an
edge that is not simply supported, or of an orthotropic or laminated plate (:func:`refined_cell`),
is instead one cell of the lattice
twice as fine (the shipped maps' grid, 40 ζ and 20 λ per decade), split into four by points
at its centre and the middles of its edges as the shipped maps' refinements split a cell:
its interpolation error is measured (the surpluses of those points), not modelled from
second differences (docs/accuracy.rst); a patch-loaded cell's points follow ``simulate``'s
heavy-impactor cut-off (:func:`with_corner_cutoff`). A tile is a pure function
of its :class:`TileKey`; the cache keeps one verified NetCDF file per key (at most
:data:`~impactmaps.maps.files.tile_files.MAX_CACHED_TILES`, least recently used removed), giving the same bits as a fresh tile.
"""

from __future__ import annotations

import itertools
import math
import os
import warnings
from dataclasses import asdict, dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ... import _files
from ...jsonio import dumps
from ...contact.contact_scale import reference_contact_stiffness
from ...solvers.modal_settings import CORNER_MAX_MODES, CORNER_MULTIPLE, ModalSettings, corner_ratios
from ...targets.shear_range import beyond_shear_theory
from ..family.accuracy import AccuracyControl
from ...solvers.mode_budget import frequency_cap
from .points import SOLVER_REVISION, capped_resolvable, map_cap, solve_map_points
from .workers import solve_tile_points
from ..family.map_family import map_family
from ..family.accuracy import STATUSES, stated_error
from ..family.refinement import REFINEMENT_VARIABLES, SURPLUS_SAFETY, Refinement, refine
from ..files.data_io import MapArrays
from ..files.tile_files import data_digest, prune_tiles, read_tile
from ..files.store import fingerprint, save_atomic
from ..family.structures import MAX_MODES, BasisTable, MapStructure

if TYPE_CHECKING:
    import xarray as xr

#: Revision of the contact-patch model in a patch tile's key (absent before 1: the Mindlin near
#: field of :mod:`impactmaps.targets.plates.near_field`), so a cached tile never answers for
#: another model.
PATCH_MODEL_REVISION = 1

__all__ = ["LATTICE_STEPS", "CACHE_ENV", "TILE_POINTS", "TileKey", "cache_directory",
           "lattice_steps", "refined_cell", "tile_for", "with_corner_cutoff", "build_tile", "tile_refinement", "cached_tile"]

#: (Δ log10 ζ, Δ log10 λ) of the tiles' lattice (:func:`lattice_steps`).
LATTICE_STEPS = (0.05, 0.1)

#: Environment variable naming the cache directory of the tiles.
CACHE_ENV = _files.CACHE_ENV
#: Lattice points per axis of a tile.
TILE_POINTS = 4
#: Version of the tile files (part of the fingerprint): their layout and the point rules
#: SOLVER_REVISION does not cover (2: patch-loaded points on a plate of the general Ritz
#: basis share the basis resolving the cap, :mod:`impactmaps.targets.plates.shared_basis`;
#: a tile without a patch, whose points that rule does not touch, keeps format 1).
_TILE_FORMAT = 2
_POINT_LOAD_TILE_FORMAT = 1
#: Version of a refined-cell tile's file (:func:`refined_cell`; 3: the first; 4: a point whose
#: cut-off the Ritz basis cannot resolve is answered as ``simulate`` answers it, on the modes up
#: to the basis's resolved frequency, checked by halving that cap: :func:`~.points.capped_resolvable`).
_CELL_TILE_FORMAT = 4
#: Depth of a refined-cell tile's split (its leaves: 1/2 of its cell per axis).
_CELL_LEVELS = 1
#: Prefix of a refined-cell tile's refinement variables (dimension ``refinement_point``).
_REFINED = "refinement_"


def cache_directory(cache_dir: str | os.PathLike | None = None) -> Path:
    """The tile cache: ``cache_dir`` if given, else ``$IMPACTMAPS_CACHE_DIR``, else
    ``$XDG_CACHE_HOME/impactmaps``, else ``~/.cache/impactmaps`` (:func:`impactmaps._files.cache_directory`)."""
    return _files.cache_directory(cache_dir)


def refined_cell(structure: MapStructure, law: str) -> bool:
    """Whether the tiles of ``structure`` and ``law`` are refined cells (module docstring): a
    plate with an edge other than simply supported, or orthotropic or laminated (its
    ``stiffness`` ratios given: a Navier SSSS laminate too, whose 4 × 4 tile's second-difference
    band was 6.8 % where the points had converged, docs/accuracy.rst), under a (ζ, λ) law. (The
    tiles of beams, of the isotropic SSSS plates and of the elastic-plastic laws keep the
    4 × 4 points of their lattice.)"""
    return (structure.kind == "plate" and (structure.supports != "SSSS" or structure.stiffness is not None)
            and not map_family(law).extra_axes)


def lattice_steps() -> tuple[float, float]:
    """(Δ log10 ζ, Δ log10 λ) = (0.05, 0.1) of the global lattice ``log10 ζ = i Δζ``, the
    grid of the shipped Timoshenko slenderness members.
    """
    return LATTICE_STEPS


@dataclass(frozen=True)
class TileKey:
    """Everything that determines a tile: ``structure``, ``law`` (the map family), ``patch``
    (P = sqrt(R α_m)/h [-] of a patch-loaded Hertz tile; None: point load), ``zeta_index``,
    ``lambda_index`` and ``extra_indices`` (lattice indices of its first values, ``log10 ζ =
    zeta_index · Δζ``), ``settings``, ``control`` and ``cell`` (a refined cell of the lattice
    twice as fine, :func:`refined_cell`).
    """

    structure: MapStructure
    law: str
    patch: float | None
    zeta_index: int
    lambda_index: int
    settings: ModalSettings = ModalSettings()
    control: AccuracyControl = AccuracyControl()
    extra_indices: tuple = ()
    cell: bool = False

    @property
    def lattice(self) -> dict:
        """Axis name → Δ log10 of the tile's lattice: the family's, halved for a refined cell."""
        steps = _family(self).tile_lattice
        return {name: step / 2.0 for name, step in steps.items()} if self.cell else dict(steps)

    @property
    def points_per_axis(self) -> int:
        """Lattice points per axis (:data:`TILE_POINTS`; 2 for a refined cell)."""
        return 2 if self.cell else TILE_POINTS

    @property
    def point_count(self) -> int:
        """The points a build solves (a refined cell: its 4 corners and 5 splitting points)."""
        if self.cell:
            return 4 + 5
        return TILE_POINTS ** (2 + len(self.extra_indices))

    @property
    def axes(self) -> tuple[np.ndarray, np.ndarray]:
        """The tile's ζ and λ lattice values [-], ascending."""
        steps = self.lattice
        return tuple(_values(steps[name], start, self.points_per_axis)
                     for name, start in (("zeta", self.zeta_index), ("lambda_", self.lambda_index)))

    @property
    def extra_axes(self) -> tuple[np.ndarray, ...]:
        """The tile's values on the family's axes before (λ, ζ) (β …) [-], ascending; empty for (ζ, λ)."""
        family = _family(self)
        return tuple(_values(family.tile_lattice[axis.name], start)
                     for axis, start in zip(family.extra_axes, self.extra_indices))

    def description(self) -> dict:
        """JSON-ready description (the fingerprint's input; stored in the tile)."""
        lattice = self.lattice
        extra = {}
        if self.extra_indices:  # (a (ζ, λ) tile's description predates the extra axes)
            extra = {"extra_indices": {axis.name: index for axis, index in
                                       zip(_family(self).extra_axes, self.extra_indices)},
                     "extra_lattice": {axis.name: lattice[axis.name] for axis in _family(self).extra_axes}}
        if self.patch is not None:  # the patch model's revision (1: 3D-consistent near field, near_field)
            extra["patch_model"] = PATCH_MODEL_REVISION
        extra |= self.structure.model_revisions()
        tile_format = _TILE_FORMAT if self.patch is not None else _POINT_LOAD_TILE_FORMAT
        if self.cell:  # a refined cell (format 4): its split and the safety on its surpluses
            extra["refinement"] = {"levels": _CELL_LEVELS, "surplus_safety": SURPLUS_SAFETY}
            tile_format = _CELL_TILE_FORMAT
        return {"structure": self.structure.as_dict(), "law": self.law, "patch_number": self.patch,
                "zeta_index": self.zeta_index, "lambda_index": self.lambda_index,
                "lattice": [lattice["zeta"], lattice["lambda_"]], **extra,
                "points_per_axis": self.points_per_axis, "settings": asdict(self.settings),
                "accuracy": asdict(self.control), "solver_revision": SOLVER_REVISION, "tile_format": tile_format}

    @property
    def fingerprint(self) -> str:
        """:func:`~impactmaps.maps.files.store.fingerprint` of :meth:`description`."""
        return fingerprint(self.description())

    @property
    def name(self) -> str:
        """Label of the tile, e.g. ``on-demand tile plate-ssss-mindlin-s62.5-hertz-P0.0799 ζ 0.09–0.18 λ 0.03–0.06``."""
        zetas, lambdas = self.axes
        stem = map_family(self.law).file_stem(self.structure.name)
        patch = "" if self.patch is None else f"-P{self.patch:.4g}"
        if self.patch is not None and f"-s{self.structure.slenderness:g}" not in self.structure.name:
            patch = f"-s{self.structure.slenderness:g}{patch}"  # a patch scales with the thickness
        extra = "".join(f"{_SYMBOLS.get(axis.name, axis.name)} {values[0]:.3g}–{values[-1]:.3g} "
                        for axis, values in zip(_family(self).extra_axes, self.extra_axes))
        return (f"on-demand tile {stem}{patch} {extra}ζ {zetas[0]:.3g}–{zetas[-1]:.3g} "
                f"λ {lambdas[0]:.3g}–{lambdas[-1]:.3g}")


#: How a tile's name writes an axis before (λ, ζ).
_SYMBOLS = {"beta": "β"}


def _values(step: float, start: int, count: int = TILE_POINTS) -> np.ndarray:
    """The ``count`` lattice values ``10^(step (start + i))`` [-]."""
    return 10.0 ** (step * (start + np.arange(count)))


def tile_for(structure: MapStructure, law: str, patch: float | None, loss_factor: float, relative_stiffness: float,
             settings: ModalSettings = ModalSettings(), control: AccuracyControl = AccuracyControl(),
             extra: tuple = (), cache_dir=None) -> TileKey:
    """The key of the tile whose middle cell holds (ζ, λ) = (``loss_factor``, ``relative_stiffness``)
    and, for a family with more axes, their values ``extra`` (β …, in the family's order); a
    refined cell's tile (:func:`refined_cell`): the cell of its lattice that holds them.
    ``cache_dir``: the tile cache (:func:`cache_directory`), where :func:`with_corner_cutoff` keeps
    its ratios."""
    cell = refined_cell(structure, law)
    shape = TileKey(structure, law, patch, 0, 0, cell=cell)  # the lattice and its points per axis
    lattice, points = shape.lattice, shape.points_per_axis
    names = [axis.name for axis in map_family(law).extra_axes]
    if len(extra) != len(names):
        raise ValueError(f"extra = {tuple(extra)!r}: the {law} tiles need a value of each of {names}")
    first = [_first_index(value, lattice[name], points) for value, name in
             zip((*extra, loss_factor, relative_stiffness), (*names, "zeta", "lambda_"))]
    return with_corner_cutoff(TileKey(structure, law, patch, first[-2], first[-1], settings, control,
                                      tuple(first[:-2]), cell), cache_dir)


def with_corner_cutoff(key: TileKey, cache_dir=None) -> TileKey:
    """``key`` with the patch cut-off of its points raised by ``simulate``'s heavy-impactor rule.

    A patch-loaded tile's points run under the patch up to ``patch_cutoff_ratio`` ω and refine
    it (×2, ×4), where ``simulate`` integrates up to the corner of the contact against the
    plate's local impedance, 4 ζ_p ω (:func:`~impactmaps.solvers.modal_settings.corner_ratios`;
    docs/plates_any_edges.rst, "The patch cut-off of heavy impactors"): at 20–80 ω a heavy
    impactor's points read up to 1.2 % low (docs/accuracy.rst). The ratio becomes the largest
    any of the tile's points asks for (its corners and, for a refined cell, its splitting
    points), rounded up to two significant digits, but no higher than the cut-off the plate's
    basis resolves for every point that the base ratio leaves uncapped (rounded down): the
    raise turns no point into a capped one. Refined cells only (:func:`refined_cell`, where it
    was measured): a key of a 4 × 4 tile (an isotropic SSSS plate's), of a point-load tile, or
    whose points ask for no more, is returned as given (the same tile, the same bits). The ratio
    of a key is computed once and kept in the tile cache ``cache_dir`` (:func:`cache_directory`).
    """
    if key.patch is None or not key.cell:
        return key
    rule = f"r{SOLVER_REVISION}-{CORNER_MULTIPLE:g}-{CORNER_MAX_MODES}-{MAX_MODES}"  # the file: the rule's revision
    ratio, = _files.stored_floats(cache_directory(cache_dir) / f"tile-cutoff-ratios-{rule}.json", [key.fingerprint],
                                  lambda _: _corner_ratio(key))
    return key if ratio <= key.settings.patch_cutoff_ratio else replace(
        key, settings=replace(key.settings, patch_cutoff_ratio=ratio))


def _corner_ratio(key: TileKey) -> float:
    """The patch cut-off ratio [-] of :func:`with_corner_cutoff` (kept on disk: it counts a Navier
    plate's modes, a cost measured in docs/plates_any_edges.rst)."""
    settings, target, family = key.settings, key.structure.build(), _family(key)
    zetas, lambdas = key.axes
    points = [(float(zeta), float(lam)) for lam in lambdas for zeta in zetas] + _splitting_points(key)
    realised = [impact for impact in family.realise_points(target, points)
                if not beyond_shear_theory(target, impact.omega)]
    base = settings.patch_cutoff_ratio
    wanted = max((corner_ratios(settings, target, impact.mass,
                                reference_contact_stiffness(impact.law, impact.mass, impact.velocity))[0]
                  for impact in realised), default=base)
    if wanted <= base:
        return base
    cap = map_cap(target) if family.capped_points else frequency_cap(target, MAX_MODES)
    resolved = min((cap / impact.omega for impact in realised if cap >= base * impact.omega), default=base)
    return min(_two_digits(wanted, math.ceil), _two_digits(resolved, math.floor))


def _two_digits(value: float, rounding) -> float:
    """``value`` (> 0) rounded to two significant digits by ``rounding`` (``math.ceil``, ``math.floor``)."""
    scale = 10.0 ** (math.floor(math.log10(value)) - 1)
    return float(rounding(value / scale) * scale)


def _first_index(value: float, step: float, points: int = TILE_POINTS) -> int:
    """Lattice index of the first of ``points`` values whose middle cell holds ``value``."""
    return math.floor(math.log10(float(value)) / step) - (points // 2 - 1)


def build_tile(key: TileKey, progress=None, workers: int | None = None) -> xr.Dataset:
    """Solve the tile's points and return it as a one-structure map dataset.

    The points (a refined cell: its corners and its 5 splitting points) are solved together,
    on one worker process per core (at most ``workers``; :func:`~.workers.solve_tile_points`:
    forked after what they share is built, the same bits as serially). The dataset has the
    family's variables over (``structure``, its extra axes, ``lambda_``, ``zeta``), as the
    shipped maps, and the attributes ``fingerprint``, ``description``, ``data_digest`` and
    ``contact_law``; a refined cell's tile also its refinement (:func:`tile_refinement`).
    ``progress(done, total)``, if given, is called after each (λ, ζ) plane of points (a refined
    cell: after each 4 points and at the end).
    """
    zetas, lambdas = key.axes
    extra = key.extra_axes
    points = [(*(float(v) for v in values), float(zeta), float(lam))
              for values in itertools.product(*extra) for lam in lambdas for zeta in zetas]
    family = _family(key)
    # None: the sweep's own table; patch-loaded points build their modes under each patch
    splitting = _splitting_points(key) if key.cell else []
    table = (_table(key, points + splitting) if key.structure.build().bounded_modes and family.uses_table()
             else None)
    # progress (and a serial call) per (λ, ζ) plane (a point is a pure function of its inputs)
    rows = solve_tile_points(family, key.structure, points + splitting, key.settings, table, key.control, progress,
                             chunk=key.points_per_axis**2, workers=workers)
    rows, presolved = rows[:len(points)], dict(zip(splitting, rows[len(points):]))
    shape = (1, *(values.size for values in extra), lambdas.size, zetas.size)
    dims = ("structure", *(axis.name for axis in family.extra_axes), "lambda_", "zeta")
    data = {name: (dims, np.array([row[name] for row in rows], dtype=spec[0]).reshape(shape), {"units": spec[2]})
            for name, spec in family.variables.items()}
    with np.errstate(invalid="ignore", divide="ignore"):  # unresolved points: NaN stays NaN
        for name in ("peak_time", "reflection_time"):  # log-times, as the shipped maps interpolate them
            dims, values, _ = data[f"{name}_normalised"]
            data[f"log_{name}"] = (dims, np.log(values))
    coords = {"structure": [key.structure.name], **{axis.name: values for axis, values in
                                                     zip(family.extra_axes, extra)}, "lambda_": lambdas, "zeta": zetas}
    import xarray as xr  # building a tile; reading one takes NumPy alone

    dataset = xr.Dataset(data, coords=coords)
    if key.cell:
        dataset = dataset.assign(_split_cell(key, family, table, data, presolved))
    dataset.attrs.update({"title": "impactmaps on-demand map tile", "fingerprint": key.fingerprint,
                          "description": dumps(key.description(), sort_keys=True), "contact_law": key.law,
                          "solver_revision": SOLVER_REVISION, "data_digest": data_digest(dataset)})
    return dataset


def _cell_coordinates(key: TileKey, row, col) -> tuple[np.ndarray, np.ndarray]:
    """(ζ, λ) [-] at fractional positions of a refined cell's tile (``row`` along λ, ``col``
    along ζ, in its lattice steps)."""
    steps = key.lattice
    return (10.0 ** (steps["zeta"] * (key.zeta_index + np.asarray(col, float))),
            10.0 ** (steps["lambda_"] * (key.lambda_index + np.asarray(row, float))))


def _splitting_points(key: TileKey) -> list[tuple[float, float]]:
    """(ζ, λ) of the 5 points that split a refined cell: its centre and its edges' middles."""
    zetas, lambdas = _cell_coordinates(key, [0.5, 0.5, 0.5, 0.0, 1.0], [0.5, 0.0, 1.0, 0.5, 0.5])
    return [(float(zeta), float(lam)) for zeta, lam in zip(zetas, lambdas)]


def _split_cell(key: TileKey, family, table, data: dict, presolved: dict) -> dict:
    """The variables of a refined cell's split (:func:`impactmaps.maps.family.refinement.refine`
    of its one cell, split whatever its band: its leaves' error is the measured surplus of the
    splitting points), each over ``refinement_point``: the lattice code, the
    :data:`~impactmaps.maps.family.refinement.REFINEMENT_VARIABLES` and each point's ``impacts``
    (its error's floor, :func:`~impactmaps.maps.family.accuracy.stated_error`). The splitting
    points' rows are ``presolved`` ((ζ, λ) → row, :func:`_splitting_points`, solved with the
    corners); a point the split asks for that is not among them is solved here."""
    base = {name: np.asarray(data[name][1])[0] for name in ("fmax_normalised", "fmax_error", "status")}
    solved = {}

    def solve(zetas, lambdas):
        points = [(float(zeta), float(lam)) for zeta, lam in zip(zetas, lambdas)]
        missing = [point for point in points if point not in presolved]
        rows = dict(zip(missing, solve_map_points(family, key.structure, missing, key.settings, table, key.control)
                        if missing else []))
        rows = [presolved[point] if point in presolved else rows[point] for point in points]
        solved.update(zip(points, rows))
        return rows

    refinement = refine(base, np.zeros(base["fmax_normalised"].shape), lambda row, col: _cell_coordinates(key, row, col),
                        solve, max_level=_CELL_LEVELS, split_first=True)
    u, v = refinement.position(refinement.codes)
    zetas, lambdas = _cell_coordinates(key, u / refinement.scale, v / refinement.scale)
    impacts = np.array([solved[(float(zeta), float(lam))].get("impacts", np.nan) for zeta, lam in zip(zetas, lambdas)],
                       float)
    dims = ("refinement_point",)
    variables = {f"{_REFINED}{name}": (dims, np.asarray(values, REFINEMENT_VARIABLES[name]))
                 for name, values in refinement.values.items()}
    return variables | {f"{_REFINED}code": (dims, refinement.codes.astype(np.int32)),
                        f"{_REFINED}impacts": (dims, impacts)}


def tile_refinement(dataset: xr.Dataset) -> Refinement | None:
    """The split of a refined cell's tile as a :class:`~impactmaps.maps.family.refinement.Refinement`
    to read it with (:func:`impactmaps.maps.read.lookup.read_map`), each point's ``fmax_error``
    stated with its floor for its impacts and F̄max (:func:`~impactmaps.maps.family.accuracy.stated_error`
    with ``fmax``: the re-impact floor relative to F̄max) and each ``surplus`` less the share of
    it the spread of sensitive points carries (:func:`_sensitive_share`; never below 0); None
    for a tile of the 4 × 4 points. (Applied when the tile is read: the file stores the
    surpluses as measured.)"""
    if f"{_REFINED}code" not in dataset:
        return None
    values = {name: np.asarray(dataset[f"{_REFINED}{name}"].values, dtype) for name, dtype in REFINEMENT_VARIABLES.items()}
    shape = (dataset.sizes["lambda_"], dataset.sizes["zeta"])
    measured = Refinement(shape, np.asarray(dataset[f"{_REFINED}code"].values, np.int64), dict(values), _CELL_LEVELS)
    values["surplus"] = np.asarray(np.maximum(values["surplus"] - _sensitive_share(measured, dataset), 0.0),
                                   REFINEMENT_VARIABLES["surplus"])
    values["fmax_error"] = np.asarray(stated_error(values["fmax_error"], values["status"],
                                                   dataset[f"{_REFINED}impacts"].values, values["fmax_normalised"]),
                                      REFINEMENT_VARIABLES["fmax_error"])
    return Refinement(shape, measured.codes, values, _CELL_LEVELS)


def _sensitive_share(refinement: Refinement, dataset) -> np.ndarray:
    """Per splitting point of a refined cell: how much of its surplus the spread of ``sensitive``
    points can carry [-], the half-spread (``fmax_error``) of the point itself if it is
    sensitive plus that of each sensitive end it was interpolated from, weighted as the
    interpolation weighs it (1/2 an edge's end, 1/4 a centre's corner).

    A sensitive point has no converged value (its number is one of the values seen, its band
    holds them all), so a surplus measured against it cannot tell curvature from that spread
    (the shipped maps' refinement never splits a cell with a sensitive corner, and its surplus
    safety was calibrated without one). Discounting it is not a bound — where the sensitive
    point is in fact accurate the share is real curvature, covered by that point's own error
    in the leaves it is a corner of — but measured: docs/accuracy.rst, "Bands of laminate tiles".
    """
    base = {name: np.asarray(dataset[name].values)[0] for name in ("fmax_error", "status")}
    sensitive = STATUSES.index("sensitive")
    u, v = refinement.position(refinement.codes)
    half = refinement.scale >> refinement.creation_level(u, v)

    def spread(where, du, dv):
        cu, cv = u[where] + du * half[where], v[where] + dv * half[where]
        status = refinement.values_at(base, cu, cv, "status")
        return np.where(status == sensitive, refinement.values_at(base, cu, cv, "fmax_error"), 0.0)

    everywhere = np.ones(u.shape, bool)
    share = spread(everywhere, 0, 0)
    centre_u, centre_v = u % (2 * half) == half, v % (2 * half) == half
    for where, ends in ((centre_u & centre_v, ((-1, -1), (1, -1), (-1, 1), (1, 1))),
                        (centre_u & ~centre_v, ((-1, 0), (1, 0))), (~centre_u & centre_v, ((0, -1), (0, 1)))):
        share[where] += sum(spread(where, du, dv) for du, dv in ends) / len(ends)
    return share


def _table(key: TileKey, points) -> BasisTable:
    """The modes a tile's points of a bounded model truncate from: up to the largest cut-off any
    of them can use (with the perturbed runs' margin (1 + p)/(1 − p)), never past the sweep's
    cap. A smaller table than the sweep's gives the same points to rounding where the point
    compliance is finite; a point-loaded Mindlin plate keeps the sweep's table.
    """
    target = key.structure.build()
    family = _family(key)
    cap = map_cap(target) if family.capped_points else frequency_cap(target, MAX_MODES)
    omegas = [impact.omega for impact in family.realise_points(target, points)]
    p = key.control.perturbation  # the margin of the docstring
    finest = key.settings.cutoff_ratio * 2**key.control.max_refinements * (1.0 + p) / (1.0 - p)
    # a capped point (its cut-off above the cap, answered as simulate answers it) uses the cap
    wanted = [finest * omega for omega in omegas if not beyond_shear_theory(target, omega) and (
        key.settings.cutoff_ratio * omega <= cap or (family.capped_points and capped_resolvable(target, omega, cap)))]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # as basis_table: a point's own cut-off is warned about
        return BasisTable(target, min(max(wanted, default=0.0), cap),
                          key.settings.min_modes * 2**key.control.max_refinements)


def _family(key: TileKey):
    """The map family of a tile's points (patch-loaded Hertz points: its patch number)."""
    family = map_family(key.law)
    return family if key.patch is None else family.with_patch(key.patch)


def tile_path(key: TileKey, cache_dir=None) -> Path:
    """The cache file of a tile [path]."""
    return cache_directory(cache_dir) / f"tile-{key.fingerprint[:32]}.nc"


def cached_tile(key: TileKey, cache_dir=None, notify=None, progress=None) -> tuple[xr.Dataset | MapArrays, Path | None]:
    """The tile of ``key`` (read from the cache as :class:`~impactmaps.maps.files.data_io.MapArrays`) and its cache file (None when it could not be written), from the
    cache ``cache_dir`` (default :func:`cache_directory`) or built and cached; ``notify``
    gets one line before a build, ``progress(done, total)`` the build's points.
    """
    path = tile_path(key, cache_dir)
    dataset = read_tile(path, key.fingerprint)
    if dataset is not None:
        try:
            os.utime(path)  # recently used: kept longest
        except OSError:
            pass
        return dataset, path
    if notify is not None:
        notify(f"building an on-demand map tile of {key.point_count} points for {key.name[len('on-demand tile '):]} "
               f"…; cached in {path}")
    dataset = build_tile(key, progress)
    try:
        save_atomic(dataset, path)
        prune_tiles(path.parent)
    except OSError as error:
        if notify is not None:
            notify(f"the tile could not be cached ({error}); answering from it all the same")
        return dataset, None
    return dataset, path
