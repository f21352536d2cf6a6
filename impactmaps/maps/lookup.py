"""Design-rule lookups from the shipped maps: F̄max and regime without a simulation.

The package ships precomputed maps (``impactmaps/maps/data/*.nc``, built by
``validation/build_default_maps.py``) for simply supported structures struck at the
centre: SS Euler and Timoshenko beams (L/h = 20), SS square Kirchhoff and Mindlin
plates (a/h = 20), each for the linear contact law (``NAME.nc``, axes ζ, λ) and for the
Hertz law (``NAME-hertz.nc``, axes ζ_h, λ_h, F̄max = F_max/F_hs:
:mod:`impactmaps.hertz_similarity`). :func:`lookup` interpolates F̄max linearly in
(log ζ, log λ); the interpolation error against direct simulation is measured by
``validation/lookup_error.py`` and quoted in the README. A map is read only as the law
it was swept with (:func:`impactmaps.maps.sweep.map_law`): a Hertz map is never read as
a linear one, nor the reverse. The shear-deformable maps also ship at other slendernesses
(:mod:`impactmaps.maps.families`); a physical case finds its map in
:mod:`impactmaps.maps.case_lookup`.
"""

from __future__ import annotations

import functools
import warnings
from dataclasses import dataclass, replace
from importlib import resources

import numpy as np
import xarray as xr

from .._checks import describe_outside, require_choice, require_positive
from ..targets.options import STRUCTURE_KINDS
from .accuracy import AccuracyControl
from .plastic_points import PLASTIC_LAWS
from .refinement import Refinement, interpolate
from .regimes import classify, quasi_static_peak
from .structures import FAMILY_SLENDERNESSES, structure_from_name
from .sweep import MAP_LAWS, map_law, warn_point_loaded_mindlin

__all__ = ["SHIPPED_MAPS", "SHIPPED_SLENDERNESS", "BAND_TOLERANCE", "map_file_stem", "LookupResult", "load_shipped_map",
           "require_map_law", "shipped_structure_name", "load_shipped_refinement", "refinement_of", "lookup",
           "read_map", "answer_status", "corner_status", "status_notes", "interpolation_error", "design_formula",
           "markdown_table"]

#: Every law a shipped map can be swept with: the (ζ, λ) laws and the elastic-plastic (β, ζ, λ) ones.
ALL_MAP_LAWS = MAP_LAWS + tuple(PLASTIC_LAWS)

SHIPPED_MAPS = {
    ("beam", "euler"): "beam-ss-euler",
    ("beam", "timoshenko"): "beam-ss-timoshenko-s20",
    ("plate", "kirchhoff"): "plate-ssss-kirchhoff",
    ("plate", "mindlin"): "plate-ssss-mindlin-s20",
}


def map_file_stem(structure_name: str, law: str = "linear") -> str:
    """File name (without ``.nc``) of the shipped map of a structure for a contact law.

    The linear maps keep the structure's name (``plate-ssss-kirchhoff``); a map of
    another law carries it as a suffix (``plate-ssss-kirchhoff-hertz``).
    """
    require_choice("law", law, ALL_MAP_LAWS)
    return structure_name if law == "linear" else f"{structure_name}-{law}"


@dataclass(frozen=True)
class LookupResult:
    """Outcome of a map lookup.

    Attributes
    ----------
    fmax_normalised : float or ndarray
        Interpolated F̄max [-].
    regime : str or ndarray of str
        Regime from :func:`impactmaps.maps.regimes.classify` on the interpolated values.
    structure, theory : str
    map_name : str
        The shipped map used.
    fmax_error : float or ndarray
        Error band half-width of ``fmax_normalised`` [-]: over the four corners of the
        cell around (ζ, λ) — a grid cell, or a cell of the map's refinement
        (:mod:`impactmaps.maps.refinement`) — the largest of their own error (refinement,
        or half the spread of a sensitive point) plus the cell's interpolation error
        (estimated from the map's second differences on a grid cell, from the measured
        surpluses on a refined one). Its coverage of the true error is measured by
        ``validation/lookup_error.py`` and ``validation/refinement_error.py`` (README).
    status : str or ndarray of str
        The worst status of those four points (``sensitive`` > ``refined`` >
        ``converged``/``asymptotic``; :mod:`impactmaps.maps.accuracy`): a
        ``sensitive`` answer has no converged value, only the band; and
        ``interpolated`` where those points converged but the band is wider than
        :data:`BAND_TOLERANCE` (:func:`answer_status`): the value is known to ± the band.
        On a map point (of the grid or its refinement) the band is the point's own error.
    law : str
        Contact law of the map: ``"linear"`` (F̄max = F_max/(m_i V0 ω)) or ``"hertz"``
        (F̄max = F_max/F_hs, :mod:`impactmaps.hertz_similarity`).
    """

    fmax_normalised: object
    regime: object
    structure: str
    theory: str
    map_name: str
    fmax_error: object = None
    status: object = None
    law: str = "linear"

    def peak_force(self, impactor_mass, velocity, contact_stiffness):
        """Dimensional peak force F̄max · m_i V0 ω [N] (m_i [kg], V0 [m/s], K [N/m]) of a linear map.

        A Hertz map's F̄max is scaled by F_hs instead
        (:func:`impactmaps.hertz_similarity.hertz_numbers`, ``force_scale``).
        """
        if self.law != "linear":
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


def shipped_structure_name(structure: str, theory: str, slenderness: float | None = None) -> str:
    """Name of the shipped map structure: ``SHIPPED_MAPS``, or a shear-deformable family
    member at ``slenderness`` (one of :data:`~impactmaps.maps.structures.FAMILY_SLENDERNESSES`)."""
    require_choice("structure", structure, STRUCTURE_KINDS)
    require_choice("theory", theory, [t for (s, t) in SHIPPED_MAPS if s == structure])
    name = SHIPPED_MAPS[(structure, theory)]
    if slenderness is None or theory not in ("timoshenko", "mindlin") or slenderness == SHIPPED_SLENDERNESS:
        return name
    require_choice("slenderness", float(slenderness), FAMILY_SLENDERNESSES)
    return replace(structure_from_name(name), slenderness=float(slenderness)).name


@functools.lru_cache(maxsize=32)
def load_shipped_map(structure: str, theory: str, law: str = "linear", slenderness: float | None = None) -> xr.Dataset:
    """The shipped map for ``structure`` in {"beam", "plate"}, its ``theory`` and contact
    ``law`` (a Timoshenko/Mindlin family member at ``slenderness``; default the s = 20 one)."""
    name = map_file_stem(shipped_structure_name(structure, theory, slenderness), law)
    source = resources.files("impactmaps.maps").joinpath("data", f"{name}.nc")
    if not source.is_file():
        raise FileNotFoundError(
            f"shipped map {name}.nc is missing from the installation; rebuild it with "
            f"`python validation/build_default_maps.py --law {law}`"
        )
    with resources.as_file(source) as path, xr.open_dataset(path, engine="scipy") as opened:
        return require_map_law(opened.load(), law, f"shipped map {name}.nc")


def lookup(loss_factor, relative_stiffness, *, structure: str = "plate", theory: str = "kirchhoff",
           tolerance: float = 0.1, local_tolerance: float = 0.1, law: str = "linear",
           slenderness: float | None = None) -> LookupResult:
    """F̄max and regime at (ζ, λ) from the shipped map, without simulating.

    Parameters
    ----------
    loss_factor, relative_stiffness : float or array_like
        ζ and λ [-] (the Hertz numbers ζ_h, λ_h for ``law="hertz"``), inside the map's
        range (else ``ValueError`` with the range).
    structure : {"beam", "plate"}
    theory : str
        "euler" or "timoshenko" for beams, "kirchhoff" or "mindlin" for plates.
    tolerance, local_tolerance : float
        Regime criteria (see :func:`impactmaps.maps.regimes.classify`).
    law : {"linear", "hertz"}
        Contact law of the map (F̄max = F_max/(m_i V0 ω), or F_max/F_hs for Hertz).
    slenderness : float, optional
        Timoshenko/Mindlin only: the family member to read (10, 20 or 50; default 20).
        Any other slenderness ≥ 10: :func:`impactmaps.maps.families.lookup_slenderness`.

    Returns
    -------
    LookupResult
    """
    key = (structure, theory, law, slenderness)
    if theory == "mindlin":
        warn_point_loaded_mindlin("the shipped Mindlin maps strike", stacklevel=3)
    return read_map(load_shipped_map(*key), loss_factor, relative_stiffness, structure=structure, theory=theory,
                    name=map_file_stem(shipped_structure_name(structure, theory, slenderness), law), law=law,
                    tolerance=tolerance, local_tolerance=local_tolerance, error_grid=_interpolation_error_grid(key),
                    refinement=load_shipped_refinement(*key))


def read_map(dataset: xr.Dataset, loss_factor, relative_stiffness, *, structure: str, theory: str, name: str,
             law: str = "linear", tolerance: float = 0.1, local_tolerance: float = 0.1,
             error_grid: np.ndarray | None = None, refinement: Refinement | None = None) -> LookupResult:
    """F̄max, its band, status and regime at (ζ, λ) from any (ζ, λ) map ``dataset``.

    The one reading of a map: :func:`lookup` applies it to the shipped maps,
    :mod:`impactmaps.maps.on_demand` to the tiles it builds. F̄max is interpolated
    bilinearly in (log λ, log ζ) between the four corners of the smallest cell that holds
    (ζ, λ): a cell of the map's grid, or of its ``refinement`` where F̄max needed finer
    cells (:mod:`impactmaps.maps.refinement`). The band is the largest own error of those
    corners plus the cell's interpolation error (on a grid cell the map's second
    differences, :func:`interpolation_error`; on a refined cell the measured surplus of
    its points), the status the worst of the corners' (:class:`LookupResult`).

    Parameters
    ----------
    dataset : xarray.Dataset
        A map as :func:`impactmaps.maps.sweep.sweep` writes it (one structure), with
        ``fmax_normalised``, ``fmax_error`` and ``status``; ``log_peak_time`` and
        ``log_reflection_time`` refine the regime when present.
    loss_factor, relative_stiffness : float or array_like
        ζ and λ [-] (ζ_h, λ_h for a Hertz map), inside the map's range.
    structure, theory : str
        The structure kind ("beam" or "plate", for the regime) and its theory.
    name : str
        The map's name, carried by the result.
    law : {"linear", "hertz"}
        The map's contact law.
    tolerance, local_tolerance : float
        Regime criteria (:func:`impactmaps.maps.regimes.classify`).
    error_grid : ndarray, optional
        :func:`interpolation_error` of the map's F̄max when already known (computed
        otherwise).
    refinement : Refinement, optional
        The points added to the map where its interpolation erred
        (:func:`impactmaps.maps.refinement.refine`); none by default.

    Returns
    -------
    LookupResult

    Raises
    ------
    ValueError
        (ζ, λ) outside the map, or next to an ``unresolved`` point (no value).
    """
    zeta, lam = np.broadcast_arrays(np.asarray(loss_factor, float), np.asarray(relative_stiffness, float))
    require_positive("loss_factor", zeta)
    require_positive("relative_stiffness", lam)
    for label, values, axis in (("loss_factor", zeta, "zeta"), ("relative_stiffness", lam, "lambda_")):
        low, high = float(dataset[axis].min()), float(dataset[axis].max())
        if np.any(values < low * (1 - 1e-12)) or np.any(values > high * (1 + 1e-12)):
            shown = describe_outside(values, low * (1 - 1e-12), high * (1 + 1e-12))
            raise ValueError(
                f"{label} = {shown} is outside the shipped map: valid range is "
                f"[{low:g}, {high:g}]; run a simulation (impactmaps point) instead"
            )
    lam_c = np.clip(lam, float(dataset["lambda_"].min()), float(dataset["lambda_"].max()))
    zeta_c = np.clip(zeta, float(dataset["zeta"].min()), float(dataset["zeta"].max()))
    if error_grid is None:
        error_grid = interpolation_error(dataset["fmax_normalised"].isel(structure=0).values)
    times = [name for name in ("log_peak_time", "log_reflection_time") if name in dataset]
    base = {name: dataset[name].isel(structure=0).values
            for name in ["fmax_normalised", *times, "fmax_error", "status"]}
    grid_only = Refinement.empty(base["fmax_normalised"].shape)
    rows = _grid_position(np.log(dataset["lambda_"].values), np.log(lam_c).ravel())
    cols = _grid_position(np.log(dataset["zeta"].values), np.log(zeta_c).ravel())
    values, error, codes = interpolate(refinement or grid_only, base, error_grid, rows, cols)
    if times:  # the regime's times: from the map's own grid
        values |= interpolate(grid_only, base, error_grid, rows, cols, times)[0]
    error = error.reshape(zeta.shape)
    status = corner_status([c.reshape(zeta.shape) for c in codes], error)
    if np.any(status == "unresolved"):
        bad = np.flatnonzero(np.asarray(status == "unresolved").ravel())[0]
        raise ValueError(
            f"(loss_factor, relative_stiffness) = ({zeta.ravel()[bad]:g}, {lam.ravel()[bad]:g}) lies where "
            f"the {structure} {theory} map holds no value (unresolved: beyond the range of its "
            "structural theory, or no model within the mode cap); run a simulation instead")
    fmax = values["fmax_normalised"].reshape(zeta.shape)
    peak_time = np.exp(values["log_peak_time"].reshape(zeta.shape)) if "log_peak_time" in values else None
    reflection = (np.exp(values["log_reflection_time"].reshape(zeta.shape)) if "log_reflection_time" in values
                  else None)
    regime = classify(fmax, zeta, lam, structure, peak_time=peak_time, reflection_time=reflection,
                      tolerance=tolerance, local_tolerance=local_tolerance, law=law)
    if fmax.ndim == 0:
        fmax, regime, error, status = float(fmax), str(regime), float(error), str(status)
    return LookupResult(fmax, regime, structure, theory, name, error, status, law)


#: Severity of a status when map points (or family members) are combined (worst wins);
#: ``interpolated`` is a lookup's own status (:func:`answer_status`), never a point's.
_SEVERITY = {"asymptotic": 0, "converged": 0, "refined": 1, "interpolated": 2, "sensitive": 3, "unresolved": 4}
#: The status of each severity.
_BY_SEVERITY = np.array(["converged", "refined", "interpolated", "sensitive", "unresolved"])
#: The map points' refinement tolerance (``AccuracyControl().tolerance``): a lookup whose
#: band is wider is ``interpolated``, even where every point around it converged.
BAND_TOLERANCE = AccuracyControl().tolerance


def answer_status(point_status, band):
    """The status of an interpolated answer from its map points' worst status and its band.

    ``interpolated`` where the points converged (``converged``, ``refined``) but the band
    — their own error plus the interpolation (or slenderness) error between them — is wider
    than :data:`BAND_TOLERANCE`: the points are right, the value between them is known only
    to ± the band (near a re-impact kink of F̄max the interpolation errs by up to a few
    1e-2). Otherwise the points' status. Scalars give a ``str``, arrays an array.
    """
    status = np.asarray(point_status)
    widened = np.isin(status, ("converged", "refined")) & (np.asarray(band) > BAND_TOLERANCE)
    out = np.where(widened, "interpolated", status)
    return str(out) if out.ndim == 0 else out


def corner_status(corner_codes, band):
    """The status of an answer read between map points: the worst of the points' statuses
    (``corner_codes``: one array of status codes of :data:`impactmaps.maps.accuracy.STATUSES`
    per corner around the answers), ``interpolated`` where the ``band`` makes it so
    (:func:`answer_status`)."""
    from .accuracy import STATUSES

    severity = np.array([_SEVERITY[name] for name in STATUSES])
    worst = np.max([severity[codes] for codes in corner_codes], axis=0)
    return answer_status(_BY_SEVERITY[worst], band)


#: What a lookup's status means for its number, where that needs saying.
_STATUS_NOTES = {
    "interpolated": "the map points around this one converged, but between them F̄max is known only to "
                    "± fmax_error (interpolation across the map's kinks or curvature); `impactmaps point` "
                    "computes this point to 1e-3",
    "sensitive": "no converged value: re-impacts whose order flips with any change of the model; read the band "
                 "(± fmax_error), not the number",
}


def status_notes(status) -> dict:
    """``{"status_note": text}`` for a status whose number needs a word (``interpolated``,
    ``sensitive``), else ``{}``; what the command line prints beside a lookup's status."""
    note = _STATUS_NOTES.get(str(status)) if np.ndim(status) == 0 else None
    return {"status_note": note} if note else {}


#: Safety factor of :func:`interpolation_error` on the leading-order term ``h² |f''| / 8``.
INTERPOLATION_SAFETY = 5.0


def interpolation_error(values: np.ndarray, *, reach: int = 2, safety: float = INTERPOLATION_SAFETY) -> np.ndarray:
    """Local estimate of the linear-interpolation error of a map, per grid point [-].

    ``values`` has one axis per map axis (two for a (λ, ζ) map, three for a plastic
    (β, λ, ζ) map; the sum below runs over all of them). Linear interpolation between
    grid points errs by about ``h² |f''| / 8`` in each direction; with the second
    differences of the map itself (``Δ²f``, in grid units) that is
    ``(|Δ²_λ f| + |Δ²_ζ f|) / 8``, each taken as the largest over the point and its two
    neighbours on each side along its axis: second differences are largest next to kinks,
    which a cell may straddle, and F̄max has ripples shorter than the grid spacing
    (quasi-static regime, ~1e-4) that one point's second differences alias — with one
    neighbour a side the band missed one of 734 random points of the twice-denser Euler
    beam map by 20 %. Near the re-impact kinks of the transition the leading-order term
    underestimates the error by up to 3.3× on maps of 20 ζ and 10 λ per decade (320 random
    points) and by 4.9× at one of 1102 random points of the twice-denser maps (a steep
    change of the impact that carries the peak, within one λ cell), so the estimate
    carries a safety factor of 5: ``5 (|Δ²_λ f| + |Δ²_ζ f|) / 8``. Edges reuse the
    nearest interior difference.

    Parameters
    ----------
    values : ndarray
        The map's values on its grid (NaN where a point holds no value).
    reach : int
        Neighbours on each side over which a second difference is the largest (2 for the
        (ζ, λ) maps; the plastic maps keep the 1 they were validated with).
    safety : float
        Factor on the leading-order term (:data:`INTERPOLATION_SAFETY`; the plastic maps: 4).

    Returns
    -------
    ndarray
        The estimate per grid point [same unit as ``values``].
    """
    f = np.asarray(values, float)
    second = np.zeros_like(f)
    for axis in range(f.ndim):
        if f.shape[axis] < 3:  # no second difference along a 1- or 2-point axis
            continue
        d2 = _nearest_known(np.abs(np.diff(f, n=2, axis=axis)), axis)
        pad = [(0, 0)] * f.ndim
        pad[axis] = (1, 1)
        d2 = np.pad(d2, pad, mode="edge")
        widened = d2.copy()
        for shift in range(1, reach + 1):
            widened = np.maximum(widened, np.maximum(np.roll(d2, shift, axis=axis), np.roll(d2, -shift, axis=axis)))
        second += widened
    return second * (safety / 8.0)


def _nearest_known(d2: np.ndarray, axis: int) -> np.ndarray:
    """``d2`` with each missing entry (a difference that reaches an ``unresolved`` point,
    NaN) replaced by the nearest known one along ``axis`` (the largest known anywhere when
    a whole line is missing)."""
    if not np.isnan(d2).any():
        return d2
    out = np.ascontiguousarray(np.moveaxis(d2, axis, -1))  # a copy: lines are views of it
    fallback = float(np.nanmax(d2)) if np.isfinite(d2).any() else 0.0
    positions = np.arange(out.shape[-1])
    for line in out.reshape(-1, out.shape[-1]):
        known = np.flatnonzero(np.isfinite(line))
        missing = np.flatnonzero(np.isnan(line))
        if missing.size == 0:
            continue
        if known.size == 0:
            line[missing] = fallback
            continue
        nearest = known[np.abs(positions[missing, None] - known[None, :]).argmin(axis=1)]
        line[missing] = line[nearest]
    return np.moveaxis(out, -1, axis)


@functools.lru_cache(maxsize=32)
def load_shipped_refinement(structure: str, theory: str, law: str = "linear",
                            slenderness: float | None = None) -> Refinement | None:
    """The refinement shipped with a map (``data/refinements/NAME.nc``,
    :mod:`impactmaps.maps.refinement`), or None where the map has none.

    A refinement built for another version of the map (its ``base_fingerprint`` is not
    the map's fingerprint) is not used: a warning says so and the map is read alone.
    """
    name = map_file_stem(shipped_structure_name(structure, theory, slenderness), law)
    source = resources.files("impactmaps.maps").joinpath("data", "refinements", f"{name}.nc")
    if not source.is_file():
        return None
    with resources.as_file(source) as path, xr.open_dataset(path, engine="scipy") as opened:
        stored = opened.load()
    return refinement_of(stored, load_shipped_map(structure, theory, law, slenderness), f"the shipped map {name}")


def refinement_of(stored: xr.Dataset, dataset: xr.Dataset, name: str = "the map") -> Refinement | None:
    """The refinement ``stored`` (:meth:`Refinement.dataset`) if it was built from the map
    ``dataset`` (its ``base_fingerprint`` is the map's fingerprint and its lattice the
    map's grid); else None, with a warning: the map is then read alone."""
    shape = (dataset.sizes["lambda_"], dataset.sizes["zeta"])
    if (stored.attrs.get("base_fingerprint") != dataset.attrs.get("fingerprint")
            or (stored.attrs.get("lambda_points"), stored.attrs.get("zeta_points")) != shape):
        warnings.warn(f"the refinement of {name} was built for another version of the map; reading the map "
                      "without it (rebuild with `python validation/build_refinements.py`)", UserWarning, stacklevel=3)
        return None
    return Refinement.from_dataset(stored)


@functools.lru_cache(maxsize=32)
def _interpolation_error_grid(key: tuple) -> np.ndarray:
    """:func:`interpolation_error` of the shipped map ``key`` = (structure, theory, law, slenderness)."""
    dataset = load_shipped_map(*key)
    return interpolation_error(dataset["fmax_normalised"].isel(structure=0).values)


def _grid_position(grid: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Fractional index of each value on the (ascending) ``grid``: exact on a grid point."""
    lower, upper = _bracket(grid, values)
    span = np.where(upper > lower, grid[upper] - grid[lower], 1.0)
    return lower + np.where(upper > lower, (values - grid[lower]) / span, 0.0)


def _bracket(grid: np.ndarray, values: np.ndarray):
    """Indices of the grid points just below and just above each value."""
    upper = np.clip(np.searchsorted(grid, values, side="left"), 0, grid.size - 1)
    lower = np.clip(upper - 1, 0, grid.size - 1)
    exact = np.isclose(grid[upper], values, rtol=0, atol=1e-12)
    return np.where(exact, upper, lower), upper


def design_formula(loss_factor, relative_stiffness, structure: str, law: str = "linear"):
    """Closed-form design estimate F̄max ≈ max(F̄∞(ζ), sqrt(λ/(1+λ))) [-].

    The larger of the infinite-structure peak (exact until waves return) and the
    quasi-static peak. Exact in the local, infinite-structure and quasi-static regimes
    by construction; in the transition it misses the re-impact peaks. Its error over
    the shipped maps is tabulated by ``validation/lookup_error.py``. With
    ``law="hertz"`` the same with the Hertz asymptotes over (ζ_h, λ_h), in F_max/F_hs
    (not closed forms: each is an asymptote run, :mod:`impactmaps.maps.hertz_points`).
    """
    from .regimes import infinite_structure_peak

    return np.maximum(infinite_structure_peak(loss_factor, structure, law),
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
