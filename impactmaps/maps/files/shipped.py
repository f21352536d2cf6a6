"""The one loader of the package's shipped data: maps, their refinements and sweep results.

The shipped maps (``data/NAME.npz``: the linear maps keep the structure's name, a map of
another law carries it as a suffix, ``NAME-hertz``, ``NAME-yc``) are built by
``data_build/build_default_maps.py`` and ``build_plastic_maps.py``; a map's refinement
(``data/refinements/NAME.npz``, :mod:`impactmaps.maps.family.refinement`) by
``build_refinements.py``; the results of the sweeps behind the default charts
(``data/results/<fingerprint>.npz``) by ``build_default_chart.py``. A sweep whose fingerprint
names a shipped result starts from it as from a finished run to resume; any other grid,
setting or solver revision has another fingerprint and is computed. A map is read only as the
law it was swept with (:func:`require_map_law`), and a refinement only with the map it was
built from (:func:`refinement_of`).
"""

from __future__ import annotations

import functools
import warnings
from dataclasses import replace
from importlib import resources
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ..._checks import require_choice
from ...targets.options import STRUCTURE_KINDS, is_shear_deformable
from ..family.builtin_families import MEMBER_SLENDERNESSES, PLANE_LAWS, PLASTIC_LAWS, family_layout
from ..family.map_family import map_law
from ..family.refinement import Refinement
from ..family.slice_refinement import SlicedRefinement
from .data_io import PACKED_SUFFIX, read_resource

if TYPE_CHECKING:
    import xarray as xr

__all__ = ["ALL_MAP_LAWS", "SHIPPED_MAPS", "SHIPPED_SLENDERNESS", "SHIPPED_RESULTS", "shipped_path", "read_shipped",
           "map_file_stem", "shipped_structure_name", "shipped_name", "load_shipped_map", "load_shipped_refinement",
           "missing_shipped_map", "require_map_law", "refinement_of", "shipped_result_path", "load_shipped_result"]

#: Every law a shipped map can be swept with: the (ζ, λ) laws and the elastic-plastic (β, ζ, λ) ones.
ALL_MAP_LAWS = (*PLANE_LAWS, *PLASTIC_LAWS)
#: (kind, theory) → structure name of the shipped (ζ, λ) maps (the Hertz family ships the same).
SHIPPED_MAPS = family_layout("linear").shipped
#: Slenderness of the shipped shear-deformable maps (span/height, span/thickness).
SHIPPED_SLENDERNESS = 20.0
#: Folder of the shipped sweep results, one packed file per fingerprint.
SHIPPED_RESULTS = Path(str(resources.files("impactmaps.maps").joinpath("data", "results")))


def shipped_path(*parts: str):
    """The shipped data file ``data/<parts>`` (``parts`` end in the stem) as an importlib
    resource, or None. A ``.nc`` (rebuilt and not yet packed) is read before the ``.npz``."""
    folder = resources.files("impactmaps.maps").joinpath("data", *parts[:-1])
    for suffix in (".nc", PACKED_SUFFIX):
        source = folder.joinpath(parts[-1] + suffix)
        if source.is_file():
            return source
    return None


def read_shipped(*parts: str) -> xr.Dataset | None:
    """The shipped dataset ``data/<parts>`` (:func:`shipped_path`), or None if there is none."""
    source = shipped_path(*parts)
    return None if source is None else read_resource(source)


def map_file_stem(structure_name: str, law: str = "linear") -> str:
    """File stem of the shipped map of a structure for a contact law (``plate-ssss-kirchhoff``,
    ``plate-ssss-kirchhoff-hertz``)."""
    require_choice("law", law, ALL_MAP_LAWS)
    return family_layout(law).file_stem(structure_name)


def shipped_structure_name(kind: str, theory: str, slenderness: float | None = None) -> str:
    """Name of the shipped (ζ, λ) map structure of (kind, theory), or of a shear-deformable
    slenderness member (``slenderness`` one of :data:`MEMBER_SLENDERNESSES`)."""
    require_choice("kind", kind, STRUCTURE_KINDS)
    require_choice("theory", theory, [t for (s, t) in SHIPPED_MAPS if s == kind])
    name = SHIPPED_MAPS[(kind, theory)]
    if slenderness is None or not is_shear_deformable(theory) or slenderness == SHIPPED_SLENDERNESS:
        return name
    require_choice("slenderness", float(slenderness), MEMBER_SLENDERNESSES)
    from ..family.structures import structure_from_name  # another slenderness's name: the structure's own rule

    return replace(structure_from_name(name), slenderness=float(slenderness)).name


@functools.lru_cache(maxsize=256)
def shipped_name(kind: str, theory: str, law: str = "linear", slenderness: float | None = None) -> str:
    """File stem of the shipped map of (kind, theory, law, slenderness); ``ValueError`` naming a
    value no shipped map has (an elastic-plastic law: the structures its family ships)."""
    require_choice("law", law, ALL_MAP_LAWS)
    if law in PLASTIC_LAWS:
        shipped = family_layout(law).shipped
        require_choice("(kind, theory)", (kind, theory), tuple(shipped))
        return map_file_stem(shipped[(kind, theory)], law)
    return map_file_stem(shipped_structure_name(kind, theory, slenderness), law)


@functools.lru_cache(maxsize=32)
def load_shipped_map(kind: str, theory: str, law: str = "linear", slenderness: float | None = None) -> xr.Dataset:
    """The shipped map of ``kind`` ("beam" or "plate"), ``theory`` and contact ``law``, at a
    shear-deformable ``slenderness`` member (default 20) (:func:`shipped_name`).

    Raises
    ------
    ValueError
        A value no shipped map has; FileNotFoundError when the installation lacks the file.
    """
    name = shipped_name(kind, theory, law, slenderness)
    dataset = read_shipped(name)
    if dataset is None:
        raise missing_shipped_map(name, law)
    return require_map_law(dataset, law, f"shipped map {name}")


@functools.lru_cache(maxsize=32)
def load_shipped_refinement(kind: str, theory: str, law: str = "linear", slenderness: float | None = None):
    """The refinement shipped with a map (a :class:`Refinement`, or a :class:`SlicedRefinement`
    for a map with extra axes), or None where it has none or it belongs to another version of
    the map (:func:`refinement_of`)."""
    name = shipped_name(kind, theory, law, slenderness)
    stored = read_shipped("refinements", name)
    if stored is None:
        return None
    return refinement_of(stored, load_shipped_map(kind, theory, law, slenderness), f"the shipped map {name}")


def missing_shipped_map(name: str, law: str) -> FileNotFoundError:
    """The error for a shipped map ``name`` the installation lacks, naming the script that rebuilds it."""
    script = "build_plastic_maps.py --laws" if law in PLASTIC_LAWS else "build_default_maps.py --law"
    return FileNotFoundError(f"shipped map {name} is missing from the installation; rebuild it with "
                             f"`python data_build/{script} {law}`")


def require_map_law(dataset: xr.Dataset, law: str, name: str = "the map") -> xr.Dataset:
    """``dataset`` if it was swept with the contact law ``law``, else ``ValueError`` naming both
    laws (a Hertz map read as a linear one would have the wrong axes and force scale)."""
    require_choice("law", law, ALL_MAP_LAWS)
    found = map_law(dataset)
    if found != law:
        raise ValueError(f"{name} is a map for the {found} contact law, not the {law} law: its axes and "
                         f"force scale differ (refusing to read it as a {law} map)")
    return dataset


def refinement_of(stored: xr.Dataset, dataset: xr.Dataset, name: str = "the map"):
    """The refinement ``stored`` if it was built from the map ``dataset`` (its
    ``base_fingerprint`` is the map's fingerprint and its lattice the map's grid); else None,
    with a warning: the map is then read alone."""
    fmax = dataset["fmax_normalised"].isel(structure=0)
    extra = tuple(size for dim, size in zip(fmax.dims, fmax.shape) if dim not in ("lambda_", "zeta"))
    shape = (dataset.sizes["lambda_"], dataset.sizes["zeta"])
    sliced = "slice" in stored
    if (stored.attrs.get("base_fingerprint") != dataset.attrs.get("fingerprint")
            or (stored.attrs.get("lambda_points"), stored.attrs.get("zeta_points")) != shape
            or sliced != bool(extra) or (sliced and tuple(np.atleast_1d(stored.attrs["slice_points"])) != extra)):
        warnings.warn(f"the refinement of {name} was built for another version of the map; reading the map "
                      "without it (rebuild with `python data_build/build_refinements.py`)", UserWarning, stacklevel=3)
        return None
    if sliced:  # one (λ, ζ) refinement per slice of the extra axes (β)
        return SlicedRefinement.from_dataset(stored, fmax.values)
    return Refinement.from_dataset(stored, fmax.values)


def shipped_result_path(digest: str) -> Path:
    """Where the shipped result of the sweep with fingerprint ``digest`` is (or would be):
    ``<digest>.npz``, or a ``<digest>.nc`` not yet packed (read first)."""
    packed = SHIPPED_RESULTS / f"{digest}{PACKED_SUFFIX}"
    legacy = SHIPPED_RESULTS / f"{digest}.nc"
    return legacy if legacy.exists() else packed


def load_shipped_result(digest: str, description: dict | None = None) -> xr.Dataset | None:
    """The shipped result of the sweep with fingerprint ``digest`` (``description``: the sweep's,
    so that a mismatch names the keys that changed), or None: none shipped, or one that cannot be
    read or does not match its name (then a warning says so and the sweep computes its points)."""
    from .store import StoreMismatchError, load_matching  # xarray: the build side only

    try:
        return load_matching(shipped_result_path(digest), digest, description)
    except StoreMismatchError as error:
        warnings.warn(f"the shipped result of this sweep is not usable ({error}); computing it instead",
                      UserWarning, stacklevel=2)
        return None
