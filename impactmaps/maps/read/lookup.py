"""Design-rule lookups from the shipped maps: F̄max and regime without a simulation.

The package ships precomputed maps (``impactmaps/maps/data/*.npz``, built by
``data_build/build_default_maps.py``) for simply supported structures struck at the
centre: SS Euler and Timoshenko beams (L/h = 20), SS square Kirchhoff and Mindlin
plates (a/h = 20), each for the linear contact law (``NAME.npz``, axes ζ, λ) and for the
Hertz law (``NAME-hertz.npz``, axes ζ_h, λ_h, F̄max = F_max/F_hs:
:mod:`impactmaps.closed_forms.hertz_similarity`). :func:`lookup` interpolates F̄max linearly in
(log ζ, log λ); the interpolation error against direct simulation is measured by
``validation/lookup_error.py`` and quoted in the README. A map is read only as the law
it was swept with (:func:`impactmaps.maps.compute.sweep.map_law`): a Hertz map is never read as
a linear one, nor the reverse. The shear-deformable maps also ship at other slendernesses
(:mod:`impactmaps.maps.read.slenderness`); a physical case finds its map in
:mod:`impactmaps.cases.case_lookup`.
"""

from __future__ import annotations

import functools
import os
import warnings
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ..._checks import require_choice, require_positive
from ..._renamed import renamed_keyword
from ...targets.options import STRUCTURE_KINDS, is_shear_deformable, point_load_diverges
from ..family.builtin_families import MEMBER_SLENDERNESSES, PLASTIC_LAWS, family_layout
from .reader import (
    BAND_TOLERANCE,
    PreparedMap,
    answer_status,
    corner_status,
    interpolation_error,
    prepare_map,
    read_values,
    status_notes,
)
from ..files.data_io import read_resource_arrays, read_shipped, shipped_path
from ..family.map_family import ASYMPTOTE_PEAKS, map_law
from ..family.refinement import Refinement
from ..family.slice_refinement import SlicedRefinement
from ..family.regimes import MAP_LAWS, classify, infinite_structure_peak, quasi_static_peak

if TYPE_CHECKING:
    import xarray as xr

__all__ = ["SHIPPED_MAPS", "SHIPPED_SLENDERNESS", "BAND_TOLERANCE", "map_file_stem", "LookupResult", "load_shipped_map",
           "require_map_law", "missing_shipped_map", "shipped_structure_name", "shipped_reader", "load_shipped_refinement", "refinement_of", "lookup",
           "read_map", "answer_status", "corner_status", "status_notes", "interpolation_error", "design_formula",
           "markdown_table"]

#: Every law a shipped map can be swept with: the (ζ, λ) laws and the elastic-plastic (β, ζ, λ) ones.
ALL_MAP_LAWS = MAP_LAWS + tuple(PLASTIC_LAWS)

#: (kind, theory) → structure name of the shipped (ζ, λ) maps (those of the linear family; the
#: Hertz family ships the same structures).
SHIPPED_MAPS = family_layout("linear").shipped


def map_file_stem(structure_name: str, law: str = "linear") -> str:
    """File name (without its suffix) of the shipped map of a structure for a contact law.

    The linear maps keep the structure's name (``plate-ssss-kirchhoff``); a map of
    another law carries it as a suffix (``plate-ssss-kirchhoff-hertz``).
    """
    require_choice("law", law, ALL_MAP_LAWS)
    return family_layout(law).file_stem(structure_name)


@dataclass(frozen=True)
class LookupResult:
    """Outcome of a map lookup.

    Attributes
    ----------
    fmax_normalised : float or ndarray
        Interpolated F̄max [-].
    regime : str or ndarray of str
        Regime from :func:`impactmaps.maps.family.regimes.classify` on the interpolated values.
    kind, theory : str
        Beam or plate, and its theory (``structure``: the old name of ``kind``, deprecated).
    map_name : str
        The shipped map used.
    fmax_error : float or ndarray
        Error band half-width of ``fmax_normalised`` [-]: over the four corners of the
        cell around (ζ, λ) — a grid cell, or a cell of the map's refinement
        (:mod:`impactmaps.maps.family.refinement`) — the largest of their own error (refinement,
        or half the spread of a sensitive point) plus the cell's interpolation error
        (estimated from the map's second differences on a grid cell, from the measured
        surpluses on a refined one). Its coverage of the true error is measured by
        ``validation/lookup_error.py`` and ``validation/refinement_error.py`` (README).
    status : str or ndarray of str
        The worst status of those four points (``sensitive`` > ``refined`` >
        ``converged``/``asymptotic``; :mod:`impactmaps.maps.family.accuracy`): a
        ``sensitive`` answer has no converged value, only the band; and
        ``interpolated`` where those points converged but the band is wider than
        :data:`BAND_TOLERANCE` (:func:`answer_status`): the value is known to ± the band.
        On a map point (of the grid or its refinement) the band is the point's own error.
    law : str
        Contact law of the map: ``"linear"`` (F̄max = F_max/(m_i V0 ω)) or ``"hertz"``
        (F̄max = F_max/F_hs, :mod:`impactmaps.closed_forms.hertz_similarity`).
    """

    fmax_normalised: object
    regime: object
    kind: str
    theory: str
    map_name: str
    fmax_error: object = None
    status: object = None
    law: str = "linear"

    @property
    def structure(self) -> str:
        """Deprecated: :attr:`kind`."""
        warnings.warn("LookupResult.structure is now LookupResult.kind (beam or plate); the old name will be removed",
                      FutureWarning, stacklevel=2)
        return self.kind

    def peak_force(self, impactor_mass, velocity, contact_stiffness):
        """Dimensional peak force F̄max · m_i V0 ω [N] (m_i [kg], V0 [m/s], K [N/m]) of a linear map.

        A Hertz map's F̄max is scaled by F_hs instead
        (:func:`impactmaps.closed_forms.hertz_similarity.hertz_numbers`, ``force_scale``).
        """
        if not family_layout(self.law).scaled_by_contact_frequency:
            raise ValueError(f"peak_force scales a linear map; this lookup is from the {self.law} map "
                             f"{self.map_name}: multiply fmax_normalised by hertz_numbers(...).force_scale")
        require_positive("impactor_mass", impactor_mass, "kg")
        require_positive("velocity", velocity, "m/s")
        require_positive("contact_stiffness", contact_stiffness, "N/m")
        omega = np.sqrt(np.asarray(contact_stiffness) / np.asarray(impactor_mass))
        return np.asarray(self.fmax_normalised) * np.asarray(impactor_mass) * np.asarray(velocity) * omega


def require_map_law(dataset: xr.Dataset, law: str, name: str = "the map") -> xr.Dataset:
    """``dataset`` if it was swept with the contact law ``law``, else ``ValueError``.

    A Hertz map read as a linear one (or the reverse) would give a number with the wrong
    force scale and the wrong axes: it is refused, naming both laws.
    """
    require_choice("law", law, ALL_MAP_LAWS)
    found = map_law(dataset)
    if found != law:
        raise ValueError(f"{name} is a map for the {found} contact law, not the {law} law: its axes and "
                         f"force scale differ (refusing to read it as a {law} map)")
    return dataset


def shipped_structure_name(kind: str, theory: str, slenderness: float | None = None) -> str:
    """Name of the shipped map structure: ``SHIPPED_MAPS``, or a shear-deformable slenderness
    member at ``slenderness`` (one of :data:`~impactmaps.maps.family.structures.MEMBER_SLENDERNESSES`)."""
    require_choice("kind", kind, STRUCTURE_KINDS)
    require_choice("theory", theory, [t for (s, t) in SHIPPED_MAPS if s == kind])
    name = SHIPPED_MAPS[(kind, theory)]
    if slenderness is None or not is_shear_deformable(theory) or slenderness == SHIPPED_SLENDERNESS:
        return name
    require_choice("slenderness", float(slenderness), MEMBER_SLENDERNESSES)
    from ..family.structures import structure_from_name  # another slenderness's name: the structure's own rule

    return replace(structure_from_name(name), slenderness=float(slenderness)).name


@functools.lru_cache(maxsize=32)
@renamed_keyword("structure", "kind")
def load_shipped_map(kind: str, theory: str, law: str = "linear", slenderness: float | None = None) -> xr.Dataset:
    """The shipped map for ``kind`` in {"beam", "plate"}, its ``theory`` and contact
    ``law`` (a Timoshenko/Mindlin slenderness member at ``slenderness``; default the s = 20 one),
    named by :func:`_shipped_name` (an elastic-plastic law: the structures its family ships)."""
    name = _shipped_name(kind, theory, law, slenderness)
    dataset = read_shipped(name)
    if dataset is None:
        raise missing_shipped_map(name, law)
    return require_map_law(dataset, law, f"shipped map {name}")


def missing_shipped_map(name: str, law: str) -> FileNotFoundError:
    """The error for a shipped map ``name`` of the contact law ``law`` that the installation
    lacks, naming the script that rebuilds it."""
    script = "build_plastic_maps.py --laws" if law in PLASTIC_LAWS else "build_default_maps.py --law"
    return FileNotFoundError(f"shipped map {name} is missing from the installation; rebuild it with "
                             f"`python data_build/{script} {law}`")


@renamed_keyword("structure", "kind")
def lookup(loss_factor, relative_stiffness, *, kind: str = "plate", theory: str = "kirchhoff",
           tolerance: float = 0.1, local_tolerance: float = 0.1, law: str = "linear",
           slenderness: float | None = None) -> LookupResult:
    """F̄max and regime at (ζ, λ) from the shipped map, without simulating.

    An interpolation of what the map stores, nothing else: F̄max, its band and status
    (:func:`read_map`) and the asymptote peaks the regime is judged by, stored with the
    map when it was built (:func:`impactmaps.maps.compute.dataset.with_asymptote_peaks`). The
    map is prepared for reading once per file (:func:`shipped_reader`).

    Parameters
    ----------
    loss_factor, relative_stiffness : float or array_like
        ζ and λ [-] (the Hertz numbers ζ_h, λ_h for ``law="hertz"``), inside the map's
        range (else ``ValueError`` with the range).
    kind : {"beam", "plate"}
    theory : str
        "euler" or "timoshenko" for beams, "kirchhoff" or "mindlin" for plates.
    tolerance, local_tolerance : float
        Regime criteria (see :func:`impactmaps.maps.family.regimes.classify`).
    law : {"linear", "hertz"}
        Contact law of the map (F̄max = F_max/(m_i V0 ω), or F_max/F_hs for Hertz).
    slenderness : float, optional
        Timoshenko/Mindlin only: the slenderness member to read (10, 20 or 50; default 20).
        Any other slenderness ≥ 10: :func:`impactmaps.maps.read.slenderness.lookup_slenderness`.

    Returns
    -------
    LookupResult
    """
    if law in PLASTIC_LAWS:
        raise ValueError(f"law = {law!r}: an elastic-plastic map has a third axis β; read it with "
                         "impactmaps.lookup_plastic(beta, zeta, lambda_, ...) (lookup takes law 'linear' or 'hertz')")
    if point_load_diverges(theory):
        from ..family.structures import warn_point_loaded_mindlin  # the Mindlin maps' warning names the sweep's mode cap

        warn_point_loaded_mindlin("the shipped Mindlin maps strike", stacklevel=3)
    prepared, name = shipped_reader(kind, theory, law, slenderness)
    return read_map(None, loss_factor, relative_stiffness, kind=kind, theory=theory, name=name, law=law,
                    tolerance=tolerance, local_tolerance=local_tolerance, prepared=prepared)


def shipped_reader(kind: str, theory: str, law: str = "linear", slenderness: float | None = None):
    """The shipped map of (kind, theory, law, slenderness) prepared for reading
    (:func:`impactmaps.maps.read.reader.prepare_map`: with its refinement and interpolation
    estimate, or an elastic-plastic map's band grids), and its name.

    Prepared once per file: the cache is keyed by the identity of the map's file and its
    refinement's (path, inode, size, modification time), so a file rewritten on disk is
    read again; a file that cannot be identified (not on a file system) is prepared at
    every call. The identity is checked at every call (two ``stat``, ~2 µs each), not once
    per process: installed package data does not change, but a checkout's build scripts
    rewrite the shipped files in place, and a process must not answer from the old ones.
    Returns ``(PreparedMap, name)``.
    """
    name = _shipped_name(kind, theory, law, slenderness)
    identity = _file_identity(name)
    if identity is None:
        return _prepare_shipped((kind, theory, law, slenderness), name, None), name
    return _prepared_shipped((kind, theory, law, slenderness), name, identity), name


@functools.lru_cache(maxsize=256)
def _shipped_name(kind: str, theory: str, law: str, slenderness: float | None) -> str:
    """File stem of the shipped map of (kind, theory, law, slenderness); ``ValueError`` naming
    a value no shipped map has (a refusal is not cached)."""
    require_choice("law", law, ALL_MAP_LAWS)
    if law in PLASTIC_LAWS:
        shipped = family_layout(law).shipped
        require_choice("(kind, theory)", (kind, theory), tuple(shipped))
        return map_file_stem(shipped[(kind, theory)], law)
    return map_file_stem(shipped_structure_name(kind, theory, slenderness), law)


def _file_identity(name: str):
    """(path, inode, size, mtime) of the map ``name`` and of its refinement (None where it has
    none); None when a file is not on a file system or is missing."""
    out = []
    for index, source in enumerate(_shipped_sources(name)):
        try:
            stat = os.stat(source)
        except OSError:
            if index == 0:  # the map itself: prepared uncached (and refused if missing)
                return None
            out.append(None)  # no refinement
            continue
        out.append((source, stat.st_ino, stat.st_size, stat.st_mtime_ns))
    return tuple(out)


@functools.lru_cache(maxsize=64)
def _shipped_sources(name: str) -> tuple[str, str]:
    """File-system paths of the shipped map ``name`` and of its refinement
    (:func:`~impactmaps.maps.files.data_io.shipped_path`; "" where there is none)."""
    sources = (shipped_path(name), shipped_path("refinements", name))
    return tuple("" if source is None else str(source) for source in sources)


@functools.lru_cache(maxsize=32)
def _prepared_shipped(key: tuple, name: str, identity: tuple):
    """:func:`_prepare_shipped`, once per file identity (:func:`shipped_reader`)."""
    return _prepare_shipped(key, name, identity)


def _prepare_shipped(key: tuple, name: str, identity: tuple | None):
    """The shipped map ``key`` read from its file now, with its refinement, prepared: from the
    files ``identity`` names, or (None) through :mod:`importlib.resources`."""
    law = key[2]
    if identity is None:
        source, stored = shipped_path(name), shipped_path("refinements", name)
        if source is None:
            raise missing_shipped_map(name, law)
        sources = (source, stored)
    else:
        sources = tuple(None if entry is None else Path(entry[0]) for entry in identity)
    dataset = require_map_law(read_resource_arrays(sources[0]), law, f"shipped map {name}")
    refinement = (None if sources[1] is None
                  else refinement_of(read_resource_arrays(sources[1]), dataset, f"the shipped map {name}"))
    return prepare_map(dataset, family_layout(law), refinement)


def read_map(dataset: xr.Dataset | None, loss_factor, relative_stiffness, *, kind: str, theory: str, name: str,
             law: str = "linear", tolerance: float = 0.1, local_tolerance: float = 0.1,
             error_grid: np.ndarray | None = None, refinement: Refinement | None = None,
             prepared: PreparedMap | None = None) -> LookupResult:
    """F̄max, its band, status and regime at (ζ, λ) from any (ζ, λ) map ``dataset``.

    The one reading of a map: :func:`lookup` applies it to the shipped maps,
    :mod:`impactmaps.cases.on_demand` to the tiles it builds. F̄max is interpolated
    bilinearly in (log λ, log ζ) between the four corners of the smallest cell that holds
    (ζ, λ): a cell of the map's grid, or of its ``refinement`` where F̄max needed finer
    cells (:mod:`impactmaps.maps.family.refinement`). The band is the largest own error of those
    corners plus the cell's interpolation error (on a grid cell the map's second
    differences, :func:`interpolation_error`; on a refined cell the measured surplus of
    its points), the status the worst of the corners' (:class:`LookupResult`). The regime
    classifies the interpolated F̄max (and times) against the asymptote peaks the map
    stores, interpolated linearly in log peak against log ζ and log λ
    (:func:`impactmaps.maps.compute.dataset.with_asymptote_peaks`); a map without them (built
    before they were stored) has them computed at (ζ, λ).

    Parameters
    ----------
    dataset : xarray.Dataset or None
        A map as :func:`impactmaps.maps.compute.sweep.sweep` writes it (one structure), with
        ``fmax_normalised``, ``fmax_error`` and ``status``; ``log_peak_time`` and
        ``log_reflection_time`` refine the regime when present. None with ``prepared``.
    loss_factor, relative_stiffness : float or array_like
        ζ and λ [-] (ζ_h, λ_h for a Hertz map), inside the map's range.
    kind, theory : str
        The structure's kind ("beam" or "plate", for the regime) and its theory.
    name : str
        The map's name, carried by the result.
    law : {"linear", "hertz"}
        The map's contact law.
    tolerance, local_tolerance : float
        Regime criteria (:func:`impactmaps.maps.family.regimes.classify`).
    error_grid : ndarray, optional
        :func:`interpolation_error` of the map's F̄max when already known (computed
        otherwise).
    refinement : Refinement, optional
        The points added to the map where its interpolation erred
        (:func:`impactmaps.maps.family.refinement.refine`); none by default.
    prepared : PreparedMap, optional
        The map prepared for reading (:func:`impactmaps.maps.read.reader.prepare_map`) in place
        of ``dataset``, ``error_grid`` and ``refinement``.

    Returns
    -------
    LookupResult

    Raises
    ------
    ValueError
        (ζ, λ) outside the map, or next to an ``unresolved`` point (no value).
    """
    reading = read_values(dataset, family_layout(law), (loss_factor, relative_stiffness),
                          ("loss_factor", "relative_stiffness"), where=f"{kind} {theory} map",
                          hints=(f" ({family_layout(law).exact_command})", ""),
                          refinement=refinement, error_grid=error_grid, prepared=prepared)
    values = reading.values
    fmax, error, status = values["fmax_normalised"], reading.errors["fmax_error"], reading.status
    peak_time = np.exp(values["log_peak_time"]) if "log_peak_time" in values else None
    reflection = np.exp(values["log_reflection_time"]) if "log_reflection_time" in values else None
    peaks = tuple(values[name] for name in ASYMPTOTE_PEAKS) if all(name in values for name in ASYMPTOTE_PEAKS) else None
    regime = classify(fmax, loss_factor, relative_stiffness, kind, peak_time=peak_time, reflection_time=reflection,
                      tolerance=tolerance, local_tolerance=local_tolerance, law=law, peaks=peaks)
    if fmax.ndim == 0:
        fmax, regime, error, status = float(fmax), regime.item(), float(error), np.asarray(status).item()
    return LookupResult(fmax, regime, kind, theory, name, error, status, law)


@functools.lru_cache(maxsize=32)
def load_shipped_refinement(kind: str, theory: str, law: str = "linear",
                            slenderness: float | None = None) -> Refinement | None:
    """The refinement shipped with a map (``data/refinements/NAME.npz``,
    :mod:`impactmaps.maps.family.refinement`), or None where the map has none.

    A refinement built for another version of the map (its ``base_fingerprint`` is not
    the map's fingerprint) is not used: a warning says so and the map is read alone.
    """
    name = _shipped_name(kind, theory, law, slenderness)
    stored = read_shipped("refinements", name)
    if stored is None:
        return None
    return refinement_of(stored, load_shipped_map(kind, theory, law, slenderness), f"the shipped map {name}")


def refinement_of(stored: xr.Dataset, dataset: xr.Dataset, name: str = "the map") -> Refinement | None:
    """The refinement ``stored`` (:meth:`Refinement.dataset`; a
    :class:`~impactmaps.maps.family.slice_refinement.SlicedRefinement` for a map with extra axes) if it
    was built from the map ``dataset`` (its ``base_fingerprint`` is the map's fingerprint and its
    lattice the map's grid); else None, with a warning: the map is then read alone."""
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


@renamed_keyword("structure", "kind")
def design_formula(loss_factor, relative_stiffness, kind: str, law: str = "linear"):
    """Closed-form design estimate F̄max ≈ max(F̄∞(ζ), sqrt(λ/(1+λ))) [-].

    The larger of the infinite-structure peak (exact until waves return) and the
    quasi-static peak. Exact in the local, infinite-structure and quasi-static regimes
    by construction; in the transition it misses the re-impact peaks. Its error over
    the shipped maps is tabulated by ``validation/lookup_error.py``. With
    ``law="hertz"`` the same with the Hertz asymptotes over (ζ_h, λ_h), in F_max/F_hs
    (not closed forms: each is an asymptote run, :mod:`impactmaps.maps.compute.hertz_points`).
    """
    return np.maximum(infinite_structure_peak(loss_factor, kind, law),
                      quasi_static_peak(relative_stiffness, law))


def markdown_table(dataset: xr.Dataset, structure: str, *, lambdas=None, zetas=None, digits: int = 3) -> str:
    """F̄max of one structure as a Markdown table (rows λ, columns ζ), nearest grid values."""
    data = dataset["fmax_normalised"].sel(structure=structure)
    lambdas = data["lambda_"].values if lambdas is None else lambdas
    zetas = data["zeta"].values if zetas is None else zetas
    data = data.sel(lambda_=list(lambdas), zeta=list(zetas), method="nearest")
    header = "| λ \\ ζ | " + " | ".join(f"{z:.3g}" for z in data["zeta"].values) + " |"
    rule = "|---|" + "---|" * data.sizes["zeta"]
    rows = [
        f"| {lam:.3g} | " + " | ".join(f"{v:.{digits}f}" for v in row) + " |"
        for lam, row in zip(data["lambda_"].values, data.values)
    ]
    return "\n".join([f"**{structure}** — F̄max", "", header, rule, *rows])


#: Slenderness of the shipped shear-deformable maps (span/height, span/thickness).
SHIPPED_SLENDERNESS = 20.0
