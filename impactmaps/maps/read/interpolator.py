"""A (λ, ζ) map prepared for reading: its refinement's leaves as index tables, and the
interpolation-error estimate of a map's grid (:func:`interpolation_error`).

:func:`impactmaps.maps.family.refinement.interpolate` finds each answer's leaf by descending the
refinement's levels and its corners by binary searches in the refinement's keys, per call.
A :class:`PlaneInterpolator` does that search once, when it is built: every leaf of the
map's refinement (the grid's own cells where it has none) with its four corners as indices
into one table of the map's and the refinement's points, its measured-surplus estimate
(:func:`~impactmaps.maps.family.refinement.leaf_estimate`, read from the surpluses laid out
on the lattice) and, per cell of the finest lattice,
the leaf that holds it. A read is then an index computation, a gather and a weighted sum
with the same operations in the same order as :func:`~impactmaps.maps.family.refinement.interpolate`,
so its answers are bit-identical (``tests/maps/test_lookup_stored.py``). The interpolator holds
copies of what it reads: changing the dataset afterwards does not change it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..family.refinement import SURPLUS_SAFETY, Leaves, Refinement

__all__ = ["PlaneInterpolator", "grid_bilinear", "grid_bilinear_one", "interpolate_line", "interpolate_line_one", "clip", "max_one",
           "INTERPOLATION_SAFETY", "interpolation_error", "slice_estimates"]


class PlaneInterpolator:
    """The leaves of a (λ, ζ) map's refinement as index tables (module docstring).

    Parameters
    ----------
    base : dict of str to ndarray
        The map's ``fmax_normalised``, ``fmax_error``, ``status`` (and any other variable
        to interpolate), each a (λ, ζ) array.
    base_estimate : ndarray
        The map's interpolation-error estimate per grid point [-]
        (:func:`interpolation_error`).
    refinement : Refinement, optional
        The map's refinement (none: the grid's cells are the leaves).
    """

    def __init__(self, base: dict, base_estimate: np.ndarray, refinement: Refinement | None = None):
        shape = np.shape(base["fmax_normalised"])
        refinement = _IndexedRefinement.of(refinement or Refinement.empty(shape))
        self.refinement, self.shape, self.scale = refinement, shape, refinement.scale
        self.cells = ((shape[0] - 1) * self.scale, (shape[1] - 1) * self.scale)
        leaves = _leaves(refinement)
        n_base = int(np.prod(shape))
        self.tables = {name: np.concatenate([np.asarray(values, float).ravel(),
                                             np.asarray(refinement.values[name], float)
                                             if name in refinement.values else np.zeros(refinement.codes.size)])
                       for name, values in base.items()}
        self.estimate = np.concatenate([np.asarray(base_estimate, float).ravel(), np.zeros(refinement.codes.size)])
        corners = []
        for cu, cv in leaves.corners():
            on_base = (cu % self.scale == 0) & (cv % self.scale == 0)
            where, found = refinement.index(refinement.code(cu, cv))
            index = np.where(on_base, (cu // self.scale) * shape[1] + cv // self.scale,
                             np.where(found, where + n_base, -1))
            corners.append(index)
        self.corners = np.stack(corners, axis=1)
        self.leaves = leaves
        self.u, self.v, self.side = leaves.u, leaves.v, leaves.side
        self.at_base = leaves.level == 0
        self.surplus_estimate = _surplus_estimates(refinement, leaves)
        self.cell_leaf = np.full(self.cells, -1, np.int32)
        for side in np.unique(leaves.side):
            ids = np.flatnonzero(leaves.side == side)
            for du in range(int(side)):
                for dv in range(int(side)):
                    self.cell_leaf[leaves.u[ids] + du, leaves.v[ids] + dv] = ids

    def interpolate(self, row: np.ndarray, col: np.ndarray, names=("fmax_normalised",)):
        """Bilinear interpolation in each position's leaf, with its band and corners' statuses.

        Parameters
        ----------
        row, col : ndarray
            Positions in grid units (along λ, along ζ), inside the grid.
        names : sequence of str
            The variables to interpolate.

        Returns
        -------
        values, error, corner_codes
            As :func:`impactmaps.maps.family.refinement.interpolate` returns them.
        """
        scaled_row, scaled_col = row * self.scale, col * self.scale
        leaf = self.cell_leaf[np.minimum(np.floor(scaled_row).astype(np.int64), self.cells[0] - 1),
                              np.minimum(np.floor(scaled_col).astype(np.int64), self.cells[1] - 1)]
        side = self.side[leaf]
        x = clip((scaled_row - self.u[leaf]) / side, 0.0, 1.0)
        y = clip((scaled_col - self.v[leaf]) / side, 0.0, 1.0)
        weights = np.array([(1.0 - x) * (1.0 - y), x * (1.0 - y), (1.0 - x) * y, x * y])
        used = weights > 0
        corners = self.corners[leaf].T
        if np.any(corners < 0):
            raise KeyError("a lattice position read from the refinement holds no point")
        values = {name: _corner_sum(weights, used, self.tables[name][corners]) for name in names}
        zero = np.zeros((1, x.size))
        own = np.max(np.concatenate([zero, np.where(used, self.tables["fmax_error"][corners], 0.0)]), axis=0)
        codes = np.where(used, self.tables["status"][corners], 0).astype(int)  # one row per corner
        at_base = np.where(used & self.at_base[leaf], self.estimate[corners], 0.0)
        estimate = np.max(np.concatenate([zero, at_base]), axis=0)
        node = np.sum(used, axis=0) == 1
        error = np.where(node, own, own + np.maximum(estimate, self.surplus_estimate[leaf]))
        return values, error, codes


    def interpolate_one(self, row: float, col: float, names=("fmax_normalised",)):
        """:meth:`interpolate` of one position (``row``, ``col``: floats), in Python floats:
        the same operations in the same order on the same doubles, so the same bits, at a
        fraction of the cost of NumPy calls on one-element arrays. Returns what
        :meth:`interpolate` returns for one-element arrays."""
        scaled_row, scaled_col = row * self.scale, col * self.scale
        leaf = int(self.cell_leaf[min(math.floor(scaled_row), self.cells[0] - 1),
                                  min(math.floor(scaled_col), self.cells[1] - 1)])
        side = int(self.side[leaf])
        x = min(max((scaled_row - int(self.u[leaf])) / side, 0.0), 1.0)
        y = min(max((scaled_col - int(self.v[leaf])) / side, 0.0), 1.0)
        weights = ((1.0 - x) * (1.0 - y), x * (1.0 - y), (1.0 - x) * y, x * y)
        used = [weight > 0 for weight in weights]
        corners = self.corners[leaf]
        if (corners < 0).any():
            raise KeyError("a lattice position read from the refinement holds no point")
        values = {name: np.array([_corner_sum_one(weights, used, self.tables[name][corners].tolist())])
                  for name in names}
        own = max_one([0.0, *(e if u else 0.0 for e, u in zip(self.tables["fmax_error"][corners].tolist(), used))])
        codes = np.array([[int(c) if u else 0] for c, u in zip(self.tables["status"][corners].tolist(), used)])
        at_base = bool(self.at_base[leaf])
        estimate = max_one([0.0, *(e if u and at_base else 0.0 for e, u in zip(self.estimate[corners].tolist(), used))])
        if sum(used) == 1:
            error = own
        else:
            error = own + max_one([estimate, float(self.surplus_estimate[leaf])])
        return values, np.array([error]), codes


def _corner_sum_one(weights, used, values) -> float:
    """:func:`_corner_sum` of one position (Python floats, the same sum)."""
    terms = [weight * value if use else 0.0 for weight, use, value in zip(weights, used, values)]
    return ((0.0 + terms[0]) + terms[1] + terms[2]) + terms[3]


def max_one(values) -> float:
    """The largest of ``values`` (Python floats), NaN if one is NaN (as ``np.max`` and ``np.maximum``)."""
    return math.nan if any(value != value for value in values) else max(values)


def _surplus_estimates(refinement: Refinement, leaves: Leaves) -> np.ndarray:
    """The measured-surplus part of every leaf's estimate: :func:`leaf_estimate` with no grid
    estimate (``SURPLUS_SAFETY`` × the largest surplus of the points that split the leaf's
    parent and its eight neighbours, and of the middles of its edges), read from the
    surpluses laid out on the lattice (0 where no point is, and beyond it)."""
    scale, pad = refinement.scale, 2 * refinement.scale
    dense = np.zeros(((refinement.shape[0] - 1) * scale + 1 + 2 * pad, refinement.width + 2 * pad))
    u, v = refinement.position(refinement.codes)
    dense[u + pad, v + pad] = refinement.values["surplus"]
    flat, width = dense.ravel(), dense.shape[1]
    surplus = np.zeros(leaves.u.shape)
    for level in range(1, refinement.max_level + 1):
        chosen = np.flatnonzero(leaves.level == level)
        if chosen.size == 0:
            continue
        half = scale >> level
        parent = 2 * half
        # the largest surplus of the five points that split each parent-sized cell, on the grid of
        # those cells from one before the lattice to one after it (cell k starts at (k - 1) parent)
        rows = ((refinement.shape[0] - 1) * scale) // parent + 2
        cols = (refinement.width - 1) // parent + 2

        def points(du, dv):
            start_u, start_v = pad - parent + du, pad - parent + dv
            return dense[start_u:start_u + rows * parent:parent, start_v:start_v + cols * parent:parent]

        split = points(half, half)
        for du, dv in ((half, 0), (half, parent), (0, half), (parent, half)):
            split = np.maximum(split, points(du, dv))
        around = np.zeros_like(split)  # each cell and its eight neighbours
        for du in (-1, 0, 1):
            for dv in (-1, 0, 1):
                around[1:-1, 1:-1] = np.maximum(around[1:-1, 1:-1],
                                                split[1 + du:rows - 1 + du, 1 + dv:cols - 1 + dv])
        surplus[chosen] = around[leaves.u[chosen] // parent + 1, leaves.v[chosen] // parent + 1]
    deeper = leaves.side > 1
    for mu, mv in leaves.edge_middles():
        surplus = np.maximum(surplus, np.where(deeper, flat[(mu + pad) * width + mv + pad], 0.0))
    return np.maximum(0.0, SURPLUS_SAFETY * surplus)


@dataclass(frozen=True)
class _IndexedRefinement(Refinement):
    """A refinement whose points are found through a table over its whole lattice (a gather
    where :meth:`Refinement.index` searches); the same points, the same answers."""

    table: np.ndarray = field(default=None, repr=False)

    @classmethod
    def of(cls, refinement: Refinement) -> "_IndexedRefinement":
        size = refinement.shape[0] and ((refinement.shape[0] - 1) * refinement.scale + 1) * refinement.width
        table = np.full(size, -1, np.int32 if refinement.codes.size < 2**31 else np.int64)
        table[refinement.codes] = np.arange(refinement.codes.size)
        return cls(refinement.shape, refinement.codes, refinement.values, refinement.max_level, table)

    def index(self, codes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        codes = np.asarray(codes, np.int64)
        inside = (codes >= 0) & (codes < self.table.size)
        where = self.table[np.where(inside, codes, 0)].astype(np.int64)
        found = inside & (where >= 0)
        return np.where(found, where, 0), found


def _leaves(refinement: Refinement) -> Leaves:
    """Every leaf of a refinement (the cells :func:`~impactmaps.maps.family.refinement.locate` ends in)."""
    scale = refinement.scale
    u, v = np.meshgrid(np.arange(refinement.shape[0] - 1, dtype=np.int64) * scale,
                       np.arange(refinement.shape[1] - 1, dtype=np.int64) * scale, indexing="ij")
    u, v = u.ravel(), v.ravel()
    found_u, found_v, found_level = [], [], []
    for depth in range(refinement.max_level):
        half = scale >> (depth + 1)
        _, split = refinement.index(refinement.code(u + half, v + half))
        found_u.append(u[~split])
        found_v.append(v[~split])
        found_level.append(np.full((~split).sum(), depth))
        u, v = u[split], v[split]
        u, v = (np.concatenate([u, u + half, u, u + half]), np.concatenate([v, v, v + half, v + half]))
    found_u.append(u)
    found_v.append(v)
    found_level.append(np.full(u.size, refinement.max_level))
    level = np.concatenate(found_level).astype(int)
    return Leaves(level, np.concatenate(found_u), np.concatenate(found_v), scale >> level)


def grid_bilinear(base: dict, row: np.ndarray, col: np.ndarray, names, scale: int) -> dict:
    """Bilinear interpolation of ``names`` on the map's own grid (a corner without weight
    counts 0, whatever it holds): :func:`impactmaps.maps.family.refinement.interpolate` of an
    empty refinement of lattice ``scale``, operation for operation."""
    shape = np.shape(base[names[0]])
    u = clip(np.floor(row), 0, shape[0] - 2).astype(np.int64) * scale
    v = clip(np.floor(col), 0, shape[1] - 2).astype(np.int64) * scale
    x = clip((row * scale - u) / scale, 0.0, 1.0)
    y = clip((col * scale - v) / scale, 0.0, 1.0)
    weights = np.array([(1.0 - x) * (1.0 - y), x * (1.0 - y), (1.0 - x) * y, x * y])
    flat = (u // scale) * shape[1] + v // scale
    corners = np.array([flat, flat + shape[1], flat + 1, flat + shape[1] + 1])
    used = weights > 0
    return {name: _corner_sum(weights, used, np.asarray(base[name], float).ravel()[corners]) for name in names}


def grid_bilinear_one(base: dict, row: float, col: float, names, scale: int) -> dict:
    """:func:`grid_bilinear` of one position (Python floats: the same operations, the same
    bits); one-element arrays, as it returns."""
    shape = np.shape(base[names[0]])
    u = min(max(math.floor(row), 0), shape[0] - 2) * scale
    v = min(max(math.floor(col), 0), shape[1] - 2) * scale
    x = min(max((row * scale - u) / scale, 0.0), 1.0)
    y = min(max((col * scale - v) / scale, 0.0), 1.0)
    weights = ((1.0 - x) * (1.0 - y), x * (1.0 - y), (1.0 - x) * y, x * y)
    flat = (u // scale) * shape[1] + v // scale
    corners = [flat, flat + shape[1], flat + 1, flat + shape[1] + 1]
    used = [weight > 0 for weight in weights]
    return {name: np.array([_corner_sum_one(weights, used, np.asarray(base[name], float).ravel()[corners].tolist())])
            for name in names}


def _corner_sum(weights: np.ndarray, used: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Σ over the four corners of weight × value, in corner order from 0, a corner without
    weight adding 0 (the sum of :func:`impactmaps.maps.family.refinement.interpolate`)."""
    terms = np.where(used, weights * values, 0.0)
    return ((np.zeros(terms.shape[1:]) + terms[0]) + terms[1] + terms[2]) + terms[3]


def interpolate_line(values: np.ndarray, position: np.ndarray, logs: np.ndarray | None = None) -> np.ndarray:
    """Interpolation of a stored line of positive values (one per grid point of a log axis)
    at fractional grid positions (≥ 0), linear in the log of the values: exact for a power
    law, as the asymptote peaks are in their tails; exactly the stored value on a grid point [-]."""
    lower = np.minimum(position.astype(np.int64), values.size - 2)
    fraction = position - lower
    logs = np.log(values) if logs is None else logs  # the values' logs, when already known
    between = np.exp((1.0 - fraction) * logs[lower] + fraction * logs[lower + 1])
    return np.where(fraction == 0.0, values[lower], np.where(fraction == 1.0, values[lower + 1], between))


def interpolate_line_one(values: np.ndarray, position: float, logs: np.ndarray) -> np.ndarray:
    """:func:`interpolate_line` at one position (its exponential on a one-element array, as
    there): a one-element array."""
    lower = min(int(position), values.size - 2)
    fraction = position - lower
    if fraction == 0.0:
        return np.array([float(values[lower])])
    if fraction == 1.0:
        return np.array([float(values[lower + 1])])
    return np.exp(np.array([(1.0 - fraction) * float(logs[lower]) + fraction * float(logs[lower + 1])]))


def clip(values, low, high):
    """``np.clip`` (the same numbers), at a fraction of its cost on small arrays."""
    return np.minimum(np.maximum(values, low), high)


#: Safety factor of :func:`interpolation_error` on the leading-order term ``h² |f''| / 8``.
INTERPOLATION_SAFETY = 5.0


def interpolation_error(values: np.ndarray, *, reach: int = 2, safety: float = INTERPOLATION_SAFETY,
                        axes=None) -> np.ndarray:
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
    axes : sequence of int, optional
        The axes whose second differences are summed (default all; :func:`slice_estimates`
        splits a plastic map's estimate into its (λ, ζ) part and its β part).

    Returns
    -------
    ndarray
        The estimate per grid point [same unit as ``values``].
    """
    f = np.asarray(values, float)
    second = np.zeros_like(f)
    for axis in range(f.ndim) if axes is None else axes:
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


def slice_estimates(values: np.ndarray, family) -> tuple[np.ndarray, np.ndarray]:
    """A map's interpolation estimate per grid point split by axes: its (λ, ζ) part, what a
    slice's refinement (:mod:`impactmaps.maps.family.slice_refinement`) splits against and reads at
    its unsplit leaves, and the extra axes' part, what interpolating across slices adds [-].
    With the family's ``reach`` and ``safety`` (:func:`interpolation_error` of those axes)."""
    f = np.asarray(values, float)
    settings = family.interpolation
    plane = interpolation_error(f, reach=settings.reach, safety=settings.safety, axes=(f.ndim - 2, f.ndim - 1))
    extra = interpolation_error(f, reach=settings.reach, safety=settings.safety, axes=tuple(range(f.ndim - 2)))
    return plane, extra


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
