"""Lookups in the shipped elastic-plastic maps: F̄max, restitution and absorbed energy at (β, ζ, λ).

The maps (``impactmaps/maps/data/NAME-yc.nc`` and ``NAME-stronge.nc``, built by
``validation/build_plastic_maps.py``; numbers and scales in
:mod:`impactmaps.maps.plastic_points`) are interpolated linearly in (log β, log λ, log ζ).
Each answer carries a band: over the eight map points around it, the largest of their own
error (refinement, or half the spread of a sensitive point) plus the local interpolation
error estimated from the map's second differences
(:func:`impactmaps.maps.lookup.interpolation_error` along the three axes), times
:data:`BAND_SAFETY`; its coverage is measured by ``validation/lookup_error.py --law yc``.
Next to a point the map holds no value for (``unresolved``: beyond what a Timoshenko
theory holds, or no model within the mode cap) a lookup is refused — never a number
without its band.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from importlib import resources

import numpy as np
import xarray as xr
from scipy.interpolate import RegularGridInterpolator

from .._checks import describe_outside, require_choice, require_positive
from .plastic_points import ERROR_OF, PLASTIC_LAWS

__all__ = ["PLASTIC_MAPS", "BAND_SAFETY", "PlasticLookup", "load_plastic_map", "lookup_plastic", "lookup_plastic_case"]

#: (kind, theory) → structure name of the shipped plastic maps (no Mindlin plate: its pressure
#: patch depends on the sphere radius, a fourth number).
PLASTIC_MAPS = {
    ("beam", "euler"): "beam-ss-euler",
    ("beam", "timoshenko"): "beam-ss-timoshenko-s20",
    ("plate", "kirchhoff"): "plate-ssss-kirchhoff",
}
#: The interpolation estimate of the plastic maps (:func:`~impactmaps.maps.lookup.interpolation_error`):
#: second differences over one neighbour a side, safety factor 4 — what the band below was
#: validated with (the (ζ, λ) maps moved to two neighbours and 5 when their Euler beam and
#: Kirchhoff plate maps became twice as dense).
PLASTIC_REACH, PLASTIC_SAFETY = 1, 4.0
#: Factor on the band (point error + second-difference interpolation estimate). The
#: estimate already carries the safety factor 4 of :data:`PLASTIC_SAFETY`;
#: with no further factor the band covered all 3306 errors of answered points measured by
#: ``validation/lookup_error.py --law yc`` and ``--law stronge`` (200 random points per
#: map and quantity), the largest error/band ratio being 0.67 (YC) and 0.86 (Stronge).
BAND_SAFETY = 1.0


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
        tolerance (:func:`impactmaps.maps.lookup.answer_status`).
    map_name : str
    law : str
        ``"yc"`` or ``"stronge"``.
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


@functools.lru_cache(maxsize=8)
def load_plastic_map(structure: str, theory: str, law: str) -> xr.Dataset:
    """The shipped plastic map of ``structure`` in {"beam", "plate"}, its ``theory``, ``law`` in {"yc", "stronge"}."""
    from .lookup import map_file_stem, require_map_law

    require_choice("law", law, tuple(PLASTIC_LAWS))
    require_choice("(structure, theory)", (structure, theory), tuple(PLASTIC_MAPS))
    name = map_file_stem(PLASTIC_MAPS[(structure, theory)], law)
    source = resources.files("impactmaps.maps").joinpath("data", f"{name}.nc")
    if not source.is_file():
        raise FileNotFoundError(f"shipped map {name}.nc is missing from the installation; rebuild it with "
                                f"`python validation/build_plastic_maps.py --laws {law}`")
    with resources.as_file(source) as path, xr.open_dataset(path, engine="scipy") as opened:
        return require_map_law(opened.load(), law, f"shipped map {name}.nc")


_AXES = ("beta", "lambda_", "zeta")


@functools.lru_cache(maxsize=32)
def _interpolator(structure: str, theory: str, law: str, variable: str):
    dataset = load_plastic_map(structure, theory, law)
    grid = tuple(np.log(dataset[axis].values) for axis in _AXES)
    return RegularGridInterpolator(grid, dataset[variable].isel(structure=0).values, method="linear",
                                   bounds_error=True)


@functools.lru_cache(maxsize=32)
def _band_grid(structure: str, theory: str, law: str, variable: str) -> np.ndarray:
    """Per grid point: own error + second-difference interpolation estimate (NaN where missing)."""
    from .lookup import interpolation_error

    dataset = load_plastic_map(structure, theory, law)
    values = dataset[variable].isel(structure=0).values
    own = dataset[ERROR_OF[variable]].isel(structure=0).values
    return own + interpolation_error(values, reach=PLASTIC_REACH, safety=PLASTIC_SAFETY)


def _corners(dataset: xr.Dataset, points: np.ndarray):
    """Index arrays of the 2³ grid points around each point (log coordinates, columns β, λ, ζ)."""
    from .lookup import _bracket

    brackets = [_bracket(np.log(dataset[axis].values), points[:, k]) for k, axis in enumerate(_AXES)]
    return [(b, l, z) for b in brackets[0] for l in brackets[1] for z in brackets[2]]


def lookup_plastic(beta, loss_factor, relative_stiffness, *, structure: str = "plate", theory: str = "kirchhoff",
                   law: str = "yc") -> PlasticLookup:
    """F̄max, restitution and absorbed energy at (β, ζ, λ) from a shipped plastic map.

    Parameters
    ----------
    beta, loss_factor, relative_stiffness : float or array_like
        β, ζ(m, K_y) and λ = K_st/K_y [-] (:func:`impactmaps.maps.plastic_points.plastic_numbers`),
        inside the map's range.
    structure, theory : str
        A key of :data:`PLASTIC_MAPS`.
    law : {"yc", "stronge"}

    Returns
    -------
    PlasticLookup

    Raises
    ------
    ValueError
        Outside the map's range (naming the number and the range), or where a map point
        around the answer is ``unresolved`` (holds no value).
    """
    from .lookup import corner_status, map_file_stem

    dataset = load_plastic_map(structure, theory, law)
    numbers = np.broadcast_arrays(*(np.asarray(v, float) for v in (beta, relative_stiffness, loss_factor)))
    names = ("beta", "relative_stiffness", "loss_factor")
    for name, values, axis in zip(names, numbers, _AXES):
        require_positive(name, values)
        low, high = float(dataset[axis].min()), float(dataset[axis].max())
        if np.any(values < low * (1 - 1e-12)) or np.any(values > high * (1 + 1e-12)):
            shown = describe_outside(values, low * (1 - 1e-12), high * (1 + 1e-12))
            raise ValueError(f"{name} = {shown} is outside the shipped map: valid range is "
                             f"[{low:g}, {high:g}]; run a simulation (impactmaps simulate) instead")
    shape = numbers[0].shape
    points = np.stack([np.log(np.clip(v, float(dataset[a].min()), float(dataset[a].max()))).ravel()
                       for v, a in zip(numbers, _AXES)], axis=-1)
    corners = _corners(dataset, points)
    out = {}
    for variable, error_name in ERROR_OF.items():
        out[variable] = _interpolator(structure, theory, law, variable)(points)
        band = _band_grid(structure, theory, law, variable)
        out[error_name] = BAND_SAFETY * np.max([band[c] for c in corners], axis=0)
    codes = dataset["status"].isel(structure=0).values
    status = corner_status([codes[c] for c in corners], out["fmax_error"])
    if np.any(status == "unresolved") or not np.all(np.isfinite(out["fmax_normalised"])):
        bad = int(np.flatnonzero((status == "unresolved") | ~np.isfinite(out["fmax_normalised"]))[0])
        raise ValueError(f"(beta, loss_factor, relative_stiffness) = ({np.ravel(numbers[0])[bad]:g}, "
                         f"{np.ravel(numbers[2])[bad]:g}, {np.ravel(numbers[1])[bad]:g}) lies where the {law} map "
                         f"{PLASTIC_MAPS[(structure, theory)]} holds no value (unresolved: beyond the range of its "
                         "structural theory, or no model within the mode cap); run a simulation (impactmaps "
                         "simulate) instead")
    values = {key: value.reshape(shape) for key, value in out.items()}
    if not shape:
        values = {key: float(value) for key, value in values.items()}
        status = str(status[0])
    else:
        status = status.reshape(shape)
    return PlasticLookup(status=status, map_name=map_file_stem(PLASTIC_MAPS[(structure, theory)], law), law=law,
                         **values)


def lookup_plastic_case(case, structure: str, theory: str, law: str) -> dict:
    """:func:`impactmaps.maps.case_lookup.lookup_case` of an elastic-plastic case: the (β, ζ, λ) map of its law.

    Parameters
    ----------
    case : impactmaps.cases.Case
        With a Yigit–Christoforou or default refined Stronge law.
    structure, theory : str
        The family (:func:`impactmaps.maps.case_lookup.map_for_case`).
    law : {"yc", "stronge"}

    Returns
    -------
    dict
        See :func:`impactmaps.maps.case_lookup.lookup_case`.
    """
    from .case_lookup import NoMapError, _answer
    from .plastic_points import plastic_numbers

    numbers = plastic_numbers(case.target, case.law, case.impactor_mass, case.velocity)
    try:
        found = lookup_plastic(numbers.impact_number, numbers.loss_factor, numbers.relative_stiffness,
                               structure=structure, theory=theory, law=law)
    except ValueError as error:
        if "outside the shipped map" not in str(error) and "holds no value" not in str(error):
            raise
        raise NoMapError(case, str(error).split("; run")[0]) from None
    scale, energy = numbers.force_scale, 0.5 * case.impactor_mass * case.velocity**2
    return _answer(found, scale, law, {
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
