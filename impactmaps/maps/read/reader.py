"""The one map reader: a value, its band and its status at any point of any family's map.

A map holds values on a regular grid in the logarithms of its axes (λ, ζ; β first for
an elastic-plastic family). :func:`read_values` reads every family's map through the
same steps: the numbers are checked against the map's range (a ``ValueError`` names the
number as the caller called it, its value and the range), the answer interpolates
linearly in the log axes between the 2ᴺ corners of the cell that holds it, its band is
the corners' own error plus the interpolation error there, its status the corners' worst
(``interpolated`` where the band is wider than :data:`BAND_TOLERANCE`), and a point next
to an ``unresolved`` corner is refused — never a number without its band.

How the cell and its interpolation error are found depends on what the map has: a
(λ, ζ) map may carry a :class:`~impactmaps.maps.family.refinement.Refinement` whose leaves are
finer cells with measured surpluses (:func:`impactmaps.maps.family.refinement.interpolate`);
a map with more axes is read on its grid, the band of each quantity the largest over the
2ᴺ corners of (own error + second-difference estimate) times the family's
``band_safety`` (:class:`~impactmaps.maps.family.map_family.Interpolation`), except that with a
:class:`~impactmaps.maps.family.slice_refinement.SlicedRefinement` F̄max is read in each
neighbouring (λ, ζ) slice's refined leaf where there is one, then across the extra axes.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from ..._checks import describe_outside, require_positive
from ..family.accuracy import PointStatus, stated_error
from .interpolator import (
    PlaneInterpolator,
    clip,
    grid_bilinear,
    grid_bilinear_one,
    interpolate_line,
    interpolate_line_one,
    max_one,
)
from ..family.map_family import ASYMPTOTE_PEAK_VARIABLES
from ..family.refinement import MAX_LEVEL, Refinement
from ..family.slice_refinement import SlicedRefinement, read_slices
from ..family.accuracy import corner_status
from .interpolator import interpolation_error, slice_estimates

if TYPE_CHECKING:
    import xarray as xr

__all__ = ["first_structure", "OutsideMapError", "UnresolvedPointError", "Reading", "PreparedMap", "prepare_map", "read_values", "band_grid"]


def first_structure(dataset, name: str) -> np.ndarray:
    """The values of the variable ``name`` of a map's first structure: NumPy indexing of its
    values (an xarray ``isel`` would import dask), the same numbers."""
    variable = dataset[name]
    return np.asarray(variable.values)[(slice(None),) * variable.dims.index("structure") + (0,)]


def _grid_position(grid: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Fractional index of each value on the (ascending) ``grid``: exact on a grid point."""
    lower, upper = _bracket(grid, values)
    span = np.where(upper > lower, grid[upper] - grid[lower], 1.0)
    return lower + np.where(upper > lower, (values - grid[lower]) / span, 0.0)


def _bracket(grid: np.ndarray, values: np.ndarray):
    """Indices of the grid points just below and just above each value."""
    upper = clip(np.searchsorted(grid, values, side="left"), 0, grid.size - 1)
    lower = clip(upper - 1, 0, grid.size - 1)
    exact = np.abs(grid[upper] - values) <= 1e-12  # np.isclose(rtol=0, atol=1e-12) of finite numbers
    return np.where(exact, upper, lower), upper


class OutsideMapError(ValueError):
    """A number lies outside a map: ``parameter`` (as the caller named it), its ``value`` (the
    offending values, shown) and the map's ``valid_range`` ``(low, high)``."""

    def __init__(self, message: str, parameter: str, value: str, valid_range: tuple[float, float]):
        super().__init__(message)
        self.parameter, self.value, self.valid_range = parameter, value, valid_range


class UnresolvedPointError(ValueError):
    """A point lies next to an ``unresolved`` map point: the map holds no value there."""


class Reading(NamedTuple):
    """What :func:`read_values` read: ``values`` and ``errors`` (name → array of the numbers'
    shape), ``status`` (array of str) and the numbers' broadcast ``shape``."""

    values: dict
    errors: dict
    status: np.ndarray
    shape: tuple


def band_grid(dataset: xr.Dataset, family, variable: str) -> np.ndarray:
    """Per grid point of a map with more than two axes: the own error of ``variable`` plus its
    second-difference interpolation estimate (NaN where missing) [-]."""
    values = first_structure(dataset, variable)
    own = first_structure(dataset, family.errors[variable])
    settings = family.interpolation
    return own + interpolation_error(values, reach=settings.reach, safety=settings.safety)


class PreparedMap(NamedTuple):
    """A map's arrays ready for :func:`read_values` (:func:`prepare_map`): plain NumPy copies,
    so that reading it again costs no dataset access.

    Attributes
    ----------
    axes : tuple of str
        The map's axes in the order of a point's numbers, ``(…, "zeta", "lambda_")``.
    ranges : dict
        Axis → (lowest, highest) grid value [-].
    grids : dict
        Axis → log of its grid values.
    tables : dict
        Variable → its values on the grid (the family's axis order, structure dropped).
    plane : PlaneInterpolator or None
        The leaves of a (λ, ζ) map (its refinement's, else its grid's).
    times : tuple of str
        The regime's log-time variables a (λ, ζ) map holds, read on its grid.
    lines : dict
        Stored lines a (λ, ζ) map is read along one axis: variable → (axis, values, their
        logs) (the asymptote peaks, :data:`impactmaps.maps.family.map_family.ASYMPTOTE_PEAK_VARIABLES`).
    band_grids : dict
        Variable → :func:`band_grid` of a map with more axes.
    slices : tuple of PlaneInterpolator
        The refined (λ, ζ) slices of a map with more axes (C order of its extra axes;
        empty without a refinement).
    extra_estimate : ndarray or None
        The extra axes' part of its F̄max estimate (:func:`slice_estimates`), with ``slices``.
    """

    axes: tuple
    ranges: dict
    grids: dict
    tables: dict
    plane: PlaneInterpolator | None
    times: tuple
    lines: dict
    band_grids: dict
    slices: tuple = ()
    extra_estimate: np.ndarray | None = None


def prepare_map(dataset: xr.Dataset, family, refinement: Refinement | SlicedRefinement | None = None,
                error_grid: np.ndarray | None = None,
                band_grids: dict | None = None, relative_floor: bool = False) -> PreparedMap:
    """A map of ``family`` (one structure) prepared for :func:`read_values` (:class:`PreparedMap`).

    Parameters are those of :func:`read_values`; the result reads exactly as the dataset.
    ``relative_floor``: its points' re-impact error floor is relative to their F̄max (a
    refined-cell tile's, :func:`impactmaps.maps.family.accuracy.stated_error` with ``fmax``).
    """
    axes = (*(axis.name for axis in family.extra_axes), "zeta", "lambda_")
    coordinates = {axis: np.asarray(dataset[axis].values, float) for axis in axes}
    ranges = {axis: (float(values.min()), float(values.max())) for axis, values in coordinates.items()}
    grids = {axis: np.log(values) for axis, values in coordinates.items()}
    if len(axes) == 2:
        times = tuple(name for name in ("log_peak_time", "log_reflection_time") if name in dataset)
        tables = {name: np.array(first_structure(dataset, name))
                  for name in ["fmax_normalised", *times, "fmax_error", "status"]}
        # a map stored before the error floor states its points' bare change: floored here (idempotent)
        tables["fmax_error"] = stated_error(tables["fmax_error"], tables["status"],
                                            first_structure(dataset, "impacts") if "impacts" in dataset else None,
                                            tables["fmax_normalised"] if relative_floor else None)
        if refinement is not None and refinement.codes.size:
            refinement = dataclasses.replace(refinement, values=refinement.values | {"fmax_error": stated_error(
                refinement.values["fmax_error"], refinement.values["status"])})
        if error_grid is None:
            error_grid = interpolation_error(tables["fmax_normalised"])
        plane = PlaneInterpolator({name: tables[name] for name in ("fmax_normalised", "fmax_error", "status")},
                                  error_grid, refinement)
        lines = {name: (axis, np.array(first_structure(dataset, name), float))
                 for name, (axis, _units, _text) in ASYMPTOTE_PEAK_VARIABLES.items() if name in dataset}
        lines = {name: (axis, values, np.log(values)) for name, (axis, values) in lines.items()}
        return PreparedMap(axes, ranges, grids, tables, plane, times, lines, {})
    names = {*family.errors, "status"}
    tables = {name: np.array(first_structure(dataset, name)) for name in names}
    if band_grids is None:
        band_grids = {variable: band_grid(dataset, family, variable) for variable in family.errors}
    if refinement is None:
        return PreparedMap(axes, ranges, grids, tables, None, (), {}, dict(band_grids))
    slices, extra_estimate = _slice_planes(dataset, tables, family, refinement)
    return PreparedMap(axes, ranges, grids, tables, None, (), {}, dict(band_grids), slices, extra_estimate)


def _slice_planes(dataset: xr.Dataset, tables: dict, family, refinement: SlicedRefinement):
    """Each (λ, ζ) slice of a map with more axes as a :class:`PlaneInterpolator` of its
    refinement, and the extra axes' part of the F̄max estimate (:func:`slice_estimates`)."""
    fmax = tables["fmax_normalised"]
    if not isinstance(refinement, SlicedRefinement) or tuple(refinement.shape) != fmax.shape:
        raise ValueError(f"refinement: a map of grid {fmax.shape} takes a SlicedRefinement of that grid, "
                         f"not {getattr(refinement, 'shape', refinement)}")
    plane, extra = slice_estimates(fmax, family)
    own = stated_error(np.asarray(first_structure(dataset, family.errors["fmax_normalised"])), tables["status"])
    flat = {name: np.reshape(values, (-1, *fmax.shape[-2:]))
            for name, values in (("fmax_normalised", fmax), ("fmax_error", own), ("status", tables["status"]))}
    plane = np.reshape(plane, (-1, *fmax.shape[-2:]))
    return tuple(PlaneInterpolator({name: values[k] for name, values in flat.items()}, plane[k], part)
                 for k, part in enumerate(refinement.slices)), extra


def read_values(dataset: xr.Dataset | None, family, numbers, labels, *, where: str, hints: tuple[str, str] = ("", ""),
                refinement: Refinement | None = None, error_grid: np.ndarray | None = None,
                band_grids: dict | None = None, prepared: PreparedMap | None = None) -> Reading:
    """Read a map at ``numbers``: interpolated values, their bands and statuses (module docstring).

    Parameters
    ----------
    dataset : xarray.Dataset
        A map of ``family`` (one structure), as :func:`impactmaps.maps.compute.sweep.sweep` writes it
        (None when ``prepared`` is given).
    family : MapFamily
    numbers : sequence of array_like
        The point's numbers in the order of a map point, ``(…, ζ, λ)`` [-]; broadcast together.
    labels : sequence of str
        What the caller calls each number (the error messages name them).
    where : str
        The map, as a refusal names it ("the beam euler map").
    hints : (str, str)
        What to run instead, appended to "run a simulation" when the numbers lie outside the
        map and when they lie next to an ``unresolved`` point.
    refinement : Refinement or SlicedRefinement, optional
        The finer leaves of a (λ, ζ) map, or of each (λ, ζ) slice of a map with more axes
        (none by default).
    error_grid : ndarray, optional
        The interpolation estimate of a (λ, ζ) map's F̄max when already known.
    band_grids : dict, optional
        :func:`band_grid` of each interpolated variable of a map with more axes, when known.
    prepared : PreparedMap, optional
        The map already prepared (:func:`prepare_map`; then ``refinement``, ``error_grid``
        and ``band_grids`` are those it was prepared with).

    Returns
    -------
    Reading
        A (λ, ζ) map's values also hold its stored asymptote peaks at the numbers
        (``infinite_structure_peak``, ``quasi_static_peak``), interpolated linearly in log
        peak against the log of their axis (:func:`~impactmaps.maps.read.interpolator.interpolate_line`),
        when it stores them.

    Raises
    ------
    OutsideMapError
        (a ``ValueError``) A number outside the map, naming it and the range.
    UnresolvedPointError
        (a ``ValueError``) Next to an ``unresolved`` point.
    """
    if prepared is None:
        prepared = prepare_map(dataset, family, refinement, error_grid, band_grids)
    logs = _one_point_logs(prepared, numbers)
    if logs is None:
        numbers = np.broadcast_arrays(*(np.asarray(value, float) for value in numbers))
        for label, values in zip(labels, numbers):
            require_positive(label, values)
        for label, values, axis in zip(labels, numbers, prepared.axes):
            low, high = prepared.ranges[axis]
            if values.size and (values.min() < low * (1 - 1e-12) or values.max() > high * (1 + 1e-12)):  # no NaN
                shown = describe_outside(values, low * (1 - 1e-12), high * (1 + 1e-12))
                raise OutsideMapError(f"{label} = {shown} is outside the shipped map: valid range is [{low:g}, "
                                      f"{high:g}]; run a simulation{hints[0]} instead", label, shown, (low, high))
        logs = {axis: np.log(clip(values, *prepared.ranges[axis])).ravel() for values, axis in zip(numbers, prepared.axes)}
    shape = np.shape(numbers[0])
    if prepared.plane is not None:
        values, errors, codes = _read_plane(prepared, logs)
    else:
        values, errors, codes = _read_cube(prepared, family, logs)
    status = corner_status(codes, errors["fmax_error"])
    status = np.atleast_1d(status).ravel()
    bad = (status == PointStatus.UNRESOLVED.value) | ~np.isfinite(values["fmax_normalised"])
    if np.any(bad):
        first = int(np.flatnonzero(bad)[0])
        shown = ", ".join(f"{np.ravel(value)[first]:g}" for value in numbers)
        raise UnresolvedPointError(f"({', '.join(labels)}) = ({shown}) lies where the {where} holds no value (unresolved: "
                         "beyond the range of its structural theory, or no model within the mode cap); run a "
                         f"simulation{hints[1]} instead")
    return Reading({name: value.reshape(shape) for name, value in values.items()},
                   {name: value.reshape(shape) for name, value in errors.items()}, status.reshape(shape), shape)


def _one_point_logs(prepared: PreparedMap, numbers):
    """The logs :func:`read_values` reads a map at, for one point of scalar numbers that lie
    inside the map (checked on Python floats, without NumPy reductions); None for any other
    input (arrays, a number the full checks refuse with their message)."""
    if any(np.ndim(value) != 0 for value in numbers):
        return None
    try:
        values = [float(value) for value in numbers]
    except (TypeError, ValueError, OverflowError):
        return None
    logs = {}
    for value, axis in zip(values, prepared.axes):
        low, high = prepared.ranges[axis]
        if not (0.0 < value < math.inf and low * (1 - 1e-12) <= value <= high * (1 + 1e-12)):
            return None
        logs[axis] = np.log(np.array([min(max(value, low), high)]))
    return logs


def _read_plane(prepared: PreparedMap, logs: dict):
    """A (λ, ζ) map read in the leaves of its refinement (the grid's cells where it has none)."""
    if logs["zeta"].size == 1:
        return _read_plane_one(prepared, logs)
    positions = {axis: _grid_position(prepared.grids[axis], logs[axis]) for axis in ("lambda_", "zeta")}
    rows, cols = positions["lambda_"], positions["zeta"]
    values, error, codes = prepared.plane.interpolate(rows, cols)
    if prepared.times:  # the regime's times: from the map's own grid
        values |= grid_bilinear(prepared.tables, rows, cols, prepared.times, 1 << MAX_LEVEL)
    for name, (axis, line, logs) in prepared.lines.items():
        values[name] = interpolate_line(line, positions[axis], logs)
    return values, {"fmax_error": error}, codes


def _read_plane_one(prepared: PreparedMap, logs: dict):
    """:func:`_read_plane` of one point, in Python floats where NumPy calls on one-element arrays
    cost more than the arithmetic (the same operations in the same order: the same bits)."""
    positions = {axis: _grid_position_one(prepared.grids[axis], float(logs[axis][0])) for axis in ("lambda_", "zeta")}
    row, col = positions["lambda_"], positions["zeta"]
    values, error, codes = prepared.plane.interpolate_one(row, col)
    if prepared.times:
        values |= grid_bilinear_one(prepared.tables, row, col, prepared.times, 1 << MAX_LEVEL)
    for name, (axis, line, line_logs) in prepared.lines.items():
        values[name] = interpolate_line_one(line, positions[axis], line_logs)
    return values, {"fmax_error": error}, codes


def _grid_position_one(grid: np.ndarray, value: float) -> float:
    """:func:`_grid_position` of one value."""
    upper = min(max(int(np.searchsorted(grid, value, side="left")), 0), grid.size - 1)
    lower = min(max(upper - 1, 0), grid.size - 1)
    if abs(float(grid[upper]) - value) <= 1e-12:
        lower = upper
    if upper > lower:
        return lower + (value - float(grid[lower])) / (float(grid[upper]) - float(grid[lower]))
    return lower + 0.0


def _read_cube(prepared: PreparedMap, family, logs: dict):
    """A map of more axes read on its grid: multilinear in the log axes; bands over the 2ᴺ corners."""
    if all(logs[name].size == 1 for name in family.axis_names):
        return _read_cube_one(prepared, family, logs)
    names = family.axis_names
    grids = [prepared.grids[name] for name in names]
    points = [logs[name] for name in names]
    corners = list(itertools.product(*(_bracket(grid, values) for grid, values in zip(grids, points))))
    cell = [_cell(grid, values) for grid, values in zip(grids, points)]
    values, errors = {}, {}
    for variable, error_name in family.errors.items():
        values[variable] = _multilinear(prepared.tables[variable], cell)
        band = prepared.band_grids[variable]
        errors[error_name] = family.interpolation.band_safety * np.max([band[c] for c in corners], axis=0)
    codes = [prepared.tables["status"][c] for c in corners]
    if prepared.slices:
        _read_slices(prepared, family, logs, values, errors, codes, corners)
    return values, errors, codes


def _read_slices(prepared: PreparedMap, family, logs: dict, values: dict, errors: dict, codes: list, corners) -> None:
    """Where a neighbouring slice's leaf is refined, F̄max read in each slice's leaf and across the
    extra axes (:func:`~impactmaps.maps.family.slice_refinement.read_slices`; between slices the band adds
    the extra axes' estimate at the grid corners); elsewhere the grid's answer stays, bit for bit."""
    rows, cols = (_grid_position(prepared.grids[axis], logs[axis]) for axis in ("lambda_", "zeta"))
    brackets = []
    for axis in family.extra_axes:
        lower, upper = _bracket(prepared.grids[axis.name], logs[axis.name])
        brackets.append((lower, upper, _grid_position(prepared.grids[axis.name], logs[axis.name]) - lower))
    shape = tuple(prepared.grids[axis.name].size for axis in family.extra_axes)
    fmax, band, deep, between, slice_codes = read_slices(prepared.slices, shape, rows, cols, brackets)
    across = np.where(between, np.max([prepared.extra_estimate[c] for c in corners], axis=0), 0.0)
    values["fmax_normalised"] = np.where(deep, fmax, values["fmax_normalised"])
    errors["fmax_error"] = np.where(deep, family.interpolation.band_safety * (band + across), errors["fmax_error"])
    codes.extend(np.where(deep, code, 0) for code in slice_codes)


def _read_cube_one(prepared: PreparedMap, family, logs: dict):
    """:func:`_read_cube` of one point, in Python floats (the same operations in the same
    order: the same bits); one-element arrays, as it returns."""
    names = family.axis_names
    grids = [prepared.grids[name] for name in names]
    points = [float(logs[name][0]) for name in names]
    corners = list(itertools.product(*(_bracket_one(grid, value) for grid, value in zip(grids, points))))
    cell = [_cell_one(grid, value) for grid, value in zip(grids, points)]
    values, errors = {}, {}
    for variable, error_name in family.errors.items():
        values[variable] = np.array([_multilinear_one(prepared.tables[variable], cell)])
        band = prepared.band_grids[variable]
        errors[error_name] = np.array([family.interpolation.band_safety * max_one([float(band[c]) for c in corners])])
    codes = prepared.tables["status"]
    return values, errors, [codes[c].reshape(1) for c in corners]


def _bracket_one(grid: np.ndarray, value: float) -> tuple[int, int]:
    """:func:`_bracket` of one value."""
    upper = min(max(int(np.searchsorted(grid, value, side="left")), 0), grid.size - 1)
    lower = min(max(upper - 1, 0), grid.size - 1)
    return (upper if abs(float(grid[upper]) - value) <= 1e-12 else lower), upper


def _cell_one(grid: np.ndarray, value: float) -> tuple[int, float]:
    """:func:`_cell` of one value."""
    index = min(max(int(np.searchsorted(grid, value, side="right")) - 1, 0), grid.size - 2)
    return index, (value - float(grid[index])) / (float(grid[index + 1]) - float(grid[index]))


def _multilinear_one(table: np.ndarray, cell) -> float:
    """:func:`_multilinear` of one point."""
    value = 0.0
    for corner in itertools.product(*(((index, 1 - distance), (index + 1, distance)) for index, distance in cell)):
        indices, weights = zip(*corner)
        weight = 1.0
        for w in weights:
            weight = weight * w
        value = value + float(table[indices]) * weight
    return value


def _cell(grid: np.ndarray, values: np.ndarray):
    """(lower index, distance from it in cells) of each value on an ascending grid (a value on the
    last grid point is at distance 1 in the last cell)."""
    index = clip(np.searchsorted(grid, values, side="right") - 1, 0, grid.size - 2)
    return index, (values - grid[index]) / (grid[index + 1] - grid[index])


def _multilinear(table: np.ndarray, cell) -> np.ndarray:
    """Multilinear interpolation of ``table`` at the cells ``cell`` (per axis: index, distance)."""
    value = np.array([0.0])
    for corner in itertools.product(*(((index, 1 - distance), (index + 1, distance)) for index, distance in cell)):
        indices, weights = zip(*corner)
        weight = np.array([1.0])
        for w in weights:
            weight = weight * w
        value = value + np.asarray(table[indices]) * weight
    return value
