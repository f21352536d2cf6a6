"""Answers from the shipped maps at a point: F̄max, its band, status and regime without a simulation.

The package ships precomputed maps (:mod:`impactmaps.maps.files.shipped`) for simply
supported structures struck at the centre: SS Euler and Timoshenko beams (L/h = 20), SS
square Kirchhoff and Mindlin plates (a/h = 20), for the linear contact law (axes ζ, λ), the
Hertz law (ζ_h, λ_h; F̄max = F_max/F_hs, :mod:`impactmaps.closed_forms.hertz_similarity`) and
the elastic-plastic laws (β, ζ, λ; :func:`read_plastic`). :func:`point_answer`
reads any of them at a point, and the shear-deformable ones at any slenderness ≥ 10
(:mod:`impactmaps.maps.read.slenderness`); :func:`impactmaps.lookup`
(:func:`impactmaps.cases.case_lookup.lookup`) is the public door, which also answers a
physical case. The interpolation error against direct simulation is measured by
``validation/lookup_error.py`` and quoted in the README.

An elastic-plastic map is interpolated linearly in (log β, log λ, log ζ); each answer's band
is, over the eight map points around it, the largest of their own error plus the local
interpolation error from the map's second differences along the three axes
(:func:`impactmaps.maps.read.interpolator.interpolation_error`), times :data:`BAND_SAFETY`;
its coverage is measured by ``validation/lookup_error.py --law yc`` (``stronge``, ``epp``).
A map may ship with a refinement of each β slice
(:mod:`impactmaps.maps.family.slice_refinement`): F̄max is then read in its refined leaves.
"""

from __future__ import annotations

import functools
import os
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ..._checks import require_positive
from ..family.builtin_families import LAYOUTS, PLASTIC_LAWS, POINT_LOADED_DIVERGENT_THEORIES, family_layout
from ..family.map_family import ASYMPTOTE_PEAKS
from ..family.refinement import Refinement
from ..family.regimes import classify, infinite_structure_peak, quasi_static_peak
from ..files.data_io import read_resource_arrays
from ..files.shipped import missing_shipped_map, refinement_of, require_map_law, shipped_name, shipped_path
from .reader import PreparedMap, prepare_map, read_values

if TYPE_CHECKING:
    import xarray as xr

__all__ = ["LookupResult", "PlasticLookup", "PLASTIC_MAPS", "BAND_SAFETY", "point_answer", "shipped_reader", "read_map",
           "read_plastic", "design_formula", "markdown_table"]


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


#: (kind, theory) → structure name of the shipped plastic maps (no Mindlin plate: its pressure
#: patch depends on the sphere radius, a fourth number).
PLASTIC_MAPS = LAYOUTS["yc"].shipped
#: The interpolation estimate of the plastic maps (:func:`~impactmaps.maps.read.interpolator.interpolation_error`):
#: second differences over one neighbour a side, safety factor 4, and the factor on the
#: whole band (:class:`~impactmaps.maps.family.map_family.Interpolation` of the plastic families).
_YC = LAYOUTS["yc"]
PLASTIC_REACH, PLASTIC_SAFETY, BAND_SAFETY = _YC.interpolation.reach, _YC.interpolation.safety, _YC.interpolation.band_safety


@dataclass(frozen=True)
class PlasticLookup:
    """Outcome of a lookup in a plastic map (scalars or arrays, all [-]).

    Attributes
    ----------
    fmax_normalised, fmax_error : F_max/(m V0 ω_y) and its band half-width.
    restitution, restitution_error : rebound speed / V0 and its band half-width.
    absorbed_energy_fraction, absorbed_energy_error : contact dissipation / ½ m V0² and its band.
    status : str or ndarray of str
        Worst status of the eight map points around the answer (``sensitive`` >
        ``refined`` > ``converged``/``asymptotic``; an ``unresolved`` one is refused), and
        ``interpolated`` where they converged but the F̄max band is wider than the points'
        tolerance (:func:`impactmaps.maps.family.accuracy.answer_status`).
    map_name : str
    law : str
        ``"yc"``, ``"stronge"`` or ``"epp"``.
    """

    fmax_normalised: object
    fmax_error: object
    restitution: object
    restitution_error: object
    absorbed_energy_fraction: object
    absorbed_energy_error: object
    status: object
    map_name: str
    law: str


def read_plastic(dataset: xr.Dataset | None, law: str, numbers, *, name: str, where: str,
                 band_grids: dict | None = None, prepared=None, refinement=None) -> PlasticLookup:
    """A plastic map (shipped, or an on-demand tile) read at ``numbers`` = (β, ζ, λ) [-].

    Parameters
    ----------
    dataset : xarray.Dataset or None
        A map of the plastic family ``law`` over (β, λ, ζ) (None when ``prepared`` is given).
    law : {"yc", "stronge", "epp"}
    numbers : (β, ζ, λ)
        Floats or arrays [-].
    name, where : str
        The map's name (the answer's ``map_name``) and how a refusal names it.
    band_grids : dict, optional
        :func:`~impactmaps.maps.read.reader.band_grid` of each interpolated quantity, when known.
    prepared : PreparedMap, optional
        The map already prepared (:func:`~impactmaps.maps.read.reader.prepare_map`).
    refinement : SlicedRefinement, optional
        The refinement of each β slice of ``dataset``
        (:mod:`impactmaps.maps.family.slice_refinement`): F̄max is read in the slices' refined leaves.

    Returns
    -------
    PlasticLookup

    Raises
    ------
    ValueError
        Outside the map's range (naming the number and the range), or where a map point
        around the answer is ``unresolved`` (holds no value).
    """
    reading = read_values(dataset, family_layout(law), numbers, ("beta", "loss_factor", "relative_stiffness"),
                          where=where, hints=(" (impactmaps simulate)",) * 2, band_grids=band_grids,
                          prepared=prepared, refinement=refinement)
    values = reading.values | reading.errors
    status = reading.status
    if not reading.shape:
        values = {key: float(value) for key, value in values.items()}
        status = str(status)
    return PlasticLookup(status=status, map_name=name, law=law, **values)


def point_answer(*numbers, kind: str = "plate", theory: str = "kirchhoff", law: str = "linear",
                 slenderness: float | None = None, tolerance: float = 0.1, local_tolerance: float = 0.1):
    """The shipped map's answer at a point: what :func:`impactmaps.lookup` returns for numbers.

    Parameters
    ----------
    *numbers : float or array_like
        The point in the order of the map's axes [-]: (ζ, λ) for the linear law, (ζ_h, λ_h) for
        the Hertz law, (β, ζ, λ) for an elastic-plastic law; inside the map's range (else
        ``ValueError`` with the range).
    kind : {"beam", "plate"}
    theory : str
        "euler" or "timoshenko" for beams, "kirchhoff" or "mindlin" for plates.
    law : {"linear", "hertz", "yc", "stronge", "epp"}
    slenderness : float, optional
        Timoshenko/Mindlin, linear or Hertz law: span/thickness ≥ 10, interpolated in 1/s
        between the slenderness members (:mod:`impactmaps.maps.read.slenderness`); default the
        shipped 20.
    tolerance, local_tolerance : float
        Regime criteria (:func:`impactmaps.maps.family.regimes.classify`).

    Returns
    -------
    LookupResult or PlasticLookup
        A :class:`PlasticLookup` for an elastic-plastic law.

    Raises
    ------
    ValueError
        A point outside the map or next to an ``unresolved`` point, a value no shipped map has.
    """
    size = 3 if law in PLASTIC_LAWS else 2
    if len(numbers) != size:
        axes = "(beta, zeta, lambda)" if size == 3 else "(zeta, lambda)"
        raise ValueError(f"law = {law!r}: a point of its maps is {size} numbers {axes}, not {len(numbers)}")
    if size == 3:
        if slenderness is not None:
            raise ValueError(f"slenderness = {slenderness!r}: the {law} maps are at slenderness 20 only (leave it out)")
        prepared, name = shipped_reader(kind, theory, law)
        return read_plastic(None, law, numbers, name=name, where=f"{law} map {PLASTIC_MAPS[(kind, theory)]}",
                            prepared=prepared)
    if slenderness is not None:
        from .slenderness import read_slenderness

        def member(theory, slenderness):
            return _plane_answer(*numbers, kind, theory, law, slenderness, tolerance, local_tolerance)

        return read_slenderness(member, *numbers, kind=kind, theory=theory, slenderness=slenderness, law=law)
    return _plane_answer(*numbers, kind, theory, law, None, tolerance, local_tolerance)


def _plane_answer(loss_factor, relative_stiffness, kind, theory, law, slenderness, tolerance, local_tolerance):
    """The shipped (ζ, λ) map of (kind, theory, law), at a slenderness member, read at (ζ, λ)."""
    if theory in POINT_LOADED_DIVERGENT_THEORIES:
        from ..family.structures import warn_point_loaded_mindlin  # the Mindlin maps' warning names the sweep's mode cap

        warn_point_loaded_mindlin("the shipped Mindlin maps strike", stacklevel=4)
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
    name = shipped_name(kind, theory, law, slenderness)
    identity = _file_identity(name)
    if identity is None:
        return _prepare_shipped((kind, theory, law, slenderness), name, None), name
    return _prepared_shipped((kind, theory, law, slenderness), name, identity), name


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
    (:func:`~impactmaps.maps.files.shipped.shipped_path`; "" where there is none)."""
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

    The one reading of a map: :func:`point_answer` applies it to the shipped maps,
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
