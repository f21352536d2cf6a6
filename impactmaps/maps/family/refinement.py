"""Adaptive refinement of a (ζ, λ) map where linear interpolation between its points errs.

A :class:`Refinement` splits grid cells into four children (down to :data:`MAX_LEVEL`
levels) on one integer lattice; :func:`refine` builds it, :func:`locate` and
:func:`interpolate` read it, and each leaf's error is measured from the surpluses of
the added points (:func:`leaf_estimate`). The method: docs/accuracy.rst.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Callable

import numpy as np

from .accuracy import STATUSES

if TYPE_CHECKING:
    import xarray as xr

__all__ = ["MAX_LEVEL", "REFINEMENT_VARIABLES", "SURPLUS_SAFETY", "Refinement", "Leaves", "locate", "interpolate",
           "leaf_estimate", "all_leaves", "refine"]

#: Deepest split: leaf cells down to 1/2^MAX_LEVEL of the map's grid spacing per axis.
MAX_LEVEL = 3
#: Factor on the measured surpluses in a refined leaf's interpolation estimate
#: (:func:`leaf_estimate`). A leaf at least halves its parent's error at a kink (~4× where
#: F̄max is smooth), but a few points alias the quasi-static ripple: with a factor of 2 the
#: band missed 4 of 4427 random lookups (by up to 1.4×), with 3 one, by 1.00×
#: (``validation/refinement_error.py``, ``validation/lookup_error.py``).
SURPLUS_SAFETY = 3.0
#: What each refinement point stores (besides its lattice ``code``), and the dtype: single
#: precision (6e-8 relative, against a tolerance of 1e-3) keeps a map's refinement of
#: ~4·10⁵ points within ~7 MB. The regime's times are read from the map's own grid.
REFINEMENT_VARIABLES = {
    "fmax_normalised": "f4",
    "fmax_error": "f4",
    "status": "i1",
    "surplus": "f4",
}
#: Status codes whose points converged (interpolation between them means something).
_RESOLVED = np.array([STATUSES.index(s) for s in ("converged", "refined", "asymptotic")])


@dataclass(frozen=True)
class Refinement:
    """The points a map's refinement added, on the map's lattice subdivided 2^``max_level`` times.

    Attributes
    ----------
    shape : tuple of int
        The base map's grid (number of λ, number of ζ).
    codes : ndarray of int64
        Sorted lattice keys ``U · width + V`` of the points (λ and ζ positions in
        1/2^max_level of a grid step).
    values : dict of str to ndarray
        :data:`REFINEMENT_VARIABLES` of each point, in the order of ``codes``.
    max_level : int
        Depth of the lattice.
    """

    shape: tuple[int, int]
    codes: np.ndarray = field(repr=False)
    values: dict = field(repr=False)
    max_level: int = MAX_LEVEL

    @classmethod
    def empty(cls, shape, max_level: int = MAX_LEVEL) -> "Refinement":
        """No points added: reads as the base map alone."""
        return cls(tuple(int(n) for n in shape), np.zeros(0, np.int64),
                   {name: np.zeros(0, dtype) for name, dtype in REFINEMENT_VARIABLES.items()}, max_level)

    @property
    def scale(self) -> int:
        """Lattice positions per grid step, 2^max_level."""
        return 1 << self.max_level

    @property
    def width(self) -> int:
        """Number of ζ positions of the lattice (the stride of a code's ``U``)."""
        return (self.shape[1] - 1) * self.scale + 1

    def code(self, u: np.ndarray, v: np.ndarray) -> np.ndarray:
        """Lattice keys of positions (``u`` along λ, ``v`` along ζ; integers)."""
        return np.asarray(u, np.int64) * self.width + np.asarray(v, np.int64)

    def position(self, codes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(U, V) lattice positions of keys."""
        return np.divmod(np.asarray(codes, np.int64), self.width)

    def index(self, codes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(index into ``codes``, whether the point exists) of each key."""
        codes = np.asarray(codes, np.int64)
        where = np.clip(np.searchsorted(self.codes, codes), 0, max(self.codes.size - 1, 0))
        found = self.codes[where] == codes if self.codes.size else np.zeros(codes.shape, bool)
        return where, found

    def creation_level(self, u: np.ndarray, v: np.ndarray) -> np.ndarray:
        """The level whose split adds the lattice position (0: a point of the base map)."""
        u, v = np.asarray(u, np.int64), np.asarray(v, np.int64)
        level = np.full(u.shape, self.max_level)
        for depth in range(self.max_level - 1, -1, -1):
            step = self.scale >> depth
            level = np.where((u % step == 0) & (v % step == 0), depth, level)
        return level

    def values_at(self, base: dict, u: np.ndarray, v: np.ndarray, name: str) -> np.ndarray:
        """Variable ``name`` at lattice positions: from the base map's arrays ``base``
        (name → (λ, ζ) array; ``surplus`` is 0 there) or from the refinement's points."""
        u, v = np.asarray(u, np.int64), np.asarray(v, np.int64)
        on_base = (u % self.scale == 0) & (v % self.scale == 0)
        out = np.zeros(u.shape, float)
        if name in base:
            out[on_base] = base[name][u[on_base] // self.scale, v[on_base] // self.scale]
        if on_base.all():
            return out
        where, found = self.index(self.code(u[~on_base], v[~on_base]))
        if not found.all():
            raise KeyError("a lattice position read from the refinement holds no point")
        out[~on_base] = self.values[name][where]
        return out

    def dataset(self, attrs: dict | None = None) -> xr.Dataset:
        """The refinement as a Dataset (one ``point`` dimension), to store beside its map."""
        import xarray as xr  # only a refinement being stored builds a Dataset (a lookup reads it without)

        variables = {"code": ("point", self.codes.astype(np.int32 if self.codes.size == 0 or self.codes[-1] < 2**31
                                                          else np.int64))}
        variables |= {name: ("point", np.asarray(self.values[name], dtype))
                      for name, dtype in REFINEMENT_VARIABLES.items()}
        out = xr.Dataset(variables)
        out.attrs |= {"lambda_points": self.shape[0], "zeta_points": self.shape[1],
                      "max_level": self.max_level} | dict(attrs or {})
        return out

    @classmethod
    def from_dataset(cls, dataset: xr.Dataset, base_fmax: np.ndarray | None = None) -> "Refinement":
        """The refinement stored by :meth:`dataset`; a packed file's missing ``surplus`` is
        recomputed from ``base_fmax``, the base map's F̄max as a (λ, ζ) array.
        """
        shape = (int(dataset.attrs["lambda_points"]), int(dataset.attrs["zeta_points"]))
        stored = [name for name in REFINEMENT_VARIABLES if name in dataset]
        out = cls(shape, np.asarray(dataset["code"].values, np.int64),
                  {name: np.asarray(dataset[name].values) for name in stored}, int(dataset.attrs["max_level"]))
        if "surplus" in stored:
            return out
        if base_fmax is None:
            raise ValueError("this refinement is stored without its surplus: give base_fmax, the base map's "
                             "fmax_normalised as a (λ, ζ) array, to recompute it")
        return cls(shape, out.codes, out.values | {"surplus": out.recomputed_surplus(base_fmax)}, out.max_level)

    def recomputed_surplus(self, base_fmax: np.ndarray) -> np.ndarray:
        """Each point's surplus as :func:`refine` measured it, from the stored values (float32):
        the same operations as :func:`_add_points`, so the same bits; 1 where not a number.
        """
        u, v = self.position(self.codes)
        half = self.scale >> self.creation_level(u, v)
        centre_u, centre_v = u % (2 * half) == half, v % (2 * half) == half
        own = np.asarray(self.values["fmax_normalised"], float)
        lattice = np.full(((self.shape[0] - 1) * self.scale + 1, self.width), np.nan)  # ~15 MB for a shipped map
        lattice[::self.scale, ::self.scale] = np.asarray(base_fmax, float)
        lattice[u, v] = own

        def at(du, dv, where):
            return lattice[u[where] + du * half[where], v[where] + dv * half[where]]

        interpolated = np.full(u.shape, np.nan)
        c = centre_u & centre_v
        interpolated[c] = (((at(-1, -1, c) + at(1, -1, c)) + at(-1, 1, c)) + at(1, 1, c)) / 4.0
        e = centre_u & ~centre_v  # the middle of an edge along λ
        interpolated[e] = (at(-1, 0, e) + at(1, 0, e)) / 2.0
        e = ~centre_u & centre_v  # along ζ
        interpolated[e] = (at(0, -1, e) + at(0, 1, e)) / 2.0
        return np.nan_to_num(np.abs(own - interpolated), nan=1.0).astype(REFINEMENT_VARIABLES["surplus"])


@dataclass(frozen=True)
class Leaves:
    """Leaf cells: level, lower-corner lattice position (U, V) and side (lattice units)."""

    level: np.ndarray
    u: np.ndarray
    v: np.ndarray
    side: np.ndarray

    def corners(self):
        """The four corners' (U, V): (low, low), (high, low), (low, high), (high, high)."""
        return [(self.u, self.v), (self.u + self.side, self.v), (self.u, self.v + self.side),
                (self.u + self.side, self.v + self.side)]

    def edge_middles(self):
        """The middles of the four edges' (U, V)."""
        half = self.side // 2
        return [(self.u + half, self.v), (self.u + half, self.v + self.side), (self.u, self.v + half),
                (self.u + self.side, self.v + half)]

    def centre(self):
        """The centre's (U, V)."""
        half = self.side // 2
        return self.u + half, self.v + half


def locate(refinement: Refinement, row: np.ndarray, col: np.ndarray) -> Leaves:
    """The leaf holding each (λ, ζ) position, given in grid units (``row`` along λ,
    ``col`` along ζ; 0 … n − 1)."""
    scale = refinement.scale
    u = np.clip(np.floor(row), 0, refinement.shape[0] - 2).astype(np.int64) * scale
    v = np.clip(np.floor(col), 0, refinement.shape[1] - 2).astype(np.int64) * scale
    level = np.zeros(u.shape, int)
    for depth in range(refinement.max_level):
        half = scale >> (depth + 1)
        active = level == depth
        _, split = refinement.index(refinement.code(u + half, v + half))
        split &= active
        if not split.any():
            break
        u = np.where(split & (row * scale >= u + half), u + half, u)
        v = np.where(split & (col * scale >= v + half), v + half, v)
        level = level + split
    return Leaves(level, u, v, scale >> level)


def interpolate(refinement: Refinement, base: dict, base_estimate: np.ndarray, row: np.ndarray, col: np.ndarray,
                names=("fmax_normalised",)):
    """Bilinear interpolation in each position's leaf, with its error and its corners' statuses.

    Parameters
    ----------
    refinement : Refinement
    base : dict of str to ndarray
        The base map's (λ, ζ) arrays (``names``, ``fmax_error``, ``status``).
    base_estimate : ndarray
        The base map's interpolation-error estimate per grid point [-].
    row, col : ndarray
        Positions in grid units (along λ, along ζ).
    names : sequence of str
        The variables to interpolate.

    Returns
    -------
    values : dict of str to ndarray
        Each of ``names`` at the positions.
    error : ndarray
        The band half-width [-]: the corners' largest own error plus the leaf's estimate.
    corner_codes : list of ndarray
        The status code of each corner (``converged`` where it has no weight).
    """
    base = dict(base) | {"surplus": np.zeros(refinement.shape)}
    leaves = locate(refinement, row, col)
    x = np.clip((row * refinement.scale - leaves.u) / leaves.side, 0.0, 1.0)
    y = np.clip((col * refinement.scale - leaves.v) / leaves.side, 0.0, 1.0)
    weights = [(1.0 - x) * (1.0 - y), x * (1.0 - y), (1.0 - x) * y, x * y]
    used = [w > 0 for w in weights]
    corners = leaves.corners()
    values = {}
    for name in names:
        total = np.zeros(x.shape)
        for w, weighs, (cu, cv) in zip(weights, used, corners):
            total = total + np.where(weighs, w * refinement.values_at(base, cu, cv, name), 0.0)
        values[name] = total
    own = np.zeros(x.shape)
    codes = []
    for weighs, (cu, cv) in zip(used, corners):
        own = np.maximum(own, np.where(weighs, refinement.values_at(base, cu, cv, "fmax_error"), 0.0))
        codes.append(np.where(weighs, refinement.values_at(base, cu, cv, "status"), 0).astype(int))
    node = np.sum(used, axis=0) == 1
    error = np.where(node, own, own + leaf_estimate(refinement, leaves, base_estimate, used))
    return values, error, codes


def all_leaves(refinement: Refinement) -> Leaves:
    """Every leaf cell of a refinement: the map's grid cells, each split where its centre is a point."""
    scale = refinement.scale
    rows, cols = np.meshgrid(np.arange(refinement.shape[0] - 1), np.arange(refinement.shape[1] - 1), indexing="ij")
    leaves = Leaves(np.zeros(rows.size, int), rows.ravel() * scale, cols.ravel() * scale,
                    np.full(rows.size, scale, np.int64))
    while True:
        _, split = refinement.index(refinement.code(*leaves.centre()))
        split &= leaves.side > 1
        if not split.any():
            return leaves
        leaves = _children(leaves, split)


def leaf_estimate(refinement: Refinement, leaves: Leaves, base_estimate: np.ndarray, used=None) -> np.ndarray:
    """Interpolation-error estimate of each leaf [-].

    A level-0 leaf: the largest ``base_estimate`` at its corners (those ``used``, when
    given). A deeper leaf: :data:`SURPLUS_SAFETY` times the largest surplus of the points
    that split its parent and the parent's eight neighbours; every leaf also the surplus of
    points on its edge middles.
    """
    scale = refinement.scale
    estimate = np.zeros(leaves.u.shape)
    at_base = leaves.level == 0
    used = [np.ones(leaves.u.shape, bool)] * 4 if used is None else used
    for weighs, (cu, cv) in zip(used, leaves.corners()):
        corner = np.zeros(leaves.u.shape)
        corner[at_base] = base_estimate[cu[at_base] // scale, cv[at_base] // scale]
        estimate = np.maximum(estimate, np.where(weighs, corner, 0.0))
    surplus = np.zeros(leaves.u.shape)
    deep = np.flatnonzero(~at_base)
    if deep.size:
        parent = 2 * leaves.side[deep]
        half = leaves.side[deep]
        low_u, low_v = (leaves.u[deep] // parent) * parent, (leaves.v[deep] // parent) * parent
        for du in (-1, 0, 1):
            for dv in (-1, 0, 1):
                pu, pv = low_u + du * parent, low_v + dv * parent
                for mu, mv in ((pu + half, pv + half), (pu + half, pv), (pu + half, pv + parent), (pu, pv + half),
                               (pu + parent, pv + half)):
                    surplus[deep] = np.maximum(surplus[deep], _surplus_at(refinement, mu, mv))
    deeper = leaves.side > 1
    for mu, mv in leaves.edge_middles():
        surplus = np.maximum(surplus, np.where(deeper, _surplus_at(refinement, mu, mv), 0.0))
    return np.maximum(estimate, SURPLUS_SAFETY * surplus)


def _surplus_at(refinement: Refinement, u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """The surplus of the points at lattice positions (0 where there is none, or outside)."""
    inside = (u >= 0) & (v >= 0) & (u <= (refinement.shape[0] - 1) * refinement.scale) & (v < refinement.width)
    if refinement.codes.size == 0:
        return np.zeros(np.shape(u))
    where, found = refinement.index(refinement.code(np.where(inside, u, 0), np.where(inside, v, 0)))
    return np.where(found & inside, refinement.values["surplus"][where], 0.0)


def refine(base: dict, base_estimate: np.ndarray, coordinates: Callable, solve: Callable, *,
           tolerance: float = 1e-3, max_level: int = MAX_LEVEL, max_points: int | None = None,
           progress: Callable | None = None, split_first: bool = False) -> Refinement:
    """Split the map's cells until linear interpolation is within ``tolerance`` everywhere it can be.

    Parameters
    ----------
    base : dict of str to ndarray
        The base map's ``fmax_normalised``, ``fmax_error`` and ``status`` as (λ, ζ) arrays.
    base_estimate : ndarray
        The base map's interpolation-error estimate per grid point [-].
    coordinates : callable
        ``coordinates(row, col) -> (zeta, lambda_)`` at fractional grid positions.
    solve : callable
        ``solve(zetas, lambdas) -> list of row dicts``: the points of a round, in order.
    tolerance : float
        Largest accepted band of a leaf [-].
    max_level : int
        Deepest split.
    max_points : int, optional
        Cost cap on the points added (the largest bands are split first).
    progress : callable, optional
        ``progress(round, new_points, total_points)`` after each round.
    split_first : bool
        Split every grid cell in the first round, whatever its band and its corners'
        statuses (an on-demand tile of one cell: its interpolation error measured, never
        modelled; :mod:`impactmaps.maps.compute.tiles`).
    """
    shape = base["fmax_normalised"].shape
    refinement = Refinement.empty(shape, max_level)
    scale = refinement.scale
    rows, cols = np.meshgrid(np.arange(shape[0] - 1), np.arange(shape[1] - 1), indexing="ij")
    leaves = Leaves(np.zeros(rows.size, int), rows.ravel() * scale, cols.ravel() * scale,
                    np.full(rows.size, scale, np.int64))
    base = dict(base) | {"surplus": np.zeros(shape)}
    round_number = 0
    while True:
        priority = _split_priority(refinement, base, base_estimate, leaves, tolerance)
        if split_first and round_number == 0:
            priority = np.where(leaves.side > 1, np.inf, 0.0)
        split = priority > 0
        if max_points is not None:
            split = _within_budget(priority, max_points - refinement.codes.size)
        if not split.any():
            return refinement
        chosen = Leaves(leaves.level[split], leaves.u[split], leaves.v[split], leaves.side[split])
        refinement = _add_points(refinement, base, chosen, coordinates, solve)
        leaves = _children(leaves, split)
        round_number += 1
        if progress is not None:
            progress(round_number, int(split.sum()), refinement.codes.size)


def _split_priority(refinement, base, base_estimate, leaves: Leaves, tolerance: float) -> np.ndarray:
    """Band of each leaf (NaN-free), as a priority where it must be split, else 0."""
    own = np.zeros(leaves.u.shape)
    resolved = np.ones(leaves.u.shape, bool)
    for cu, cv in leaves.corners():
        own = np.maximum(own, refinement.values_at(base, cu, cv, "fmax_error"))
        resolved &= np.isin(refinement.values_at(base, cu, cv, "status"), _RESOLVED)
    band = own + leaf_estimate(refinement, leaves, base_estimate)
    wanted = resolved & (leaves.side > 1) & (band > tolerance)
    return np.where(wanted, band, 0.0)


def _within_budget(priority: np.ndarray, budget: int) -> np.ndarray:
    """The leaves to split within ``budget`` new points (≤ 5 each), largest priority first."""
    if budget <= 0:
        return np.zeros(priority.shape, bool)
    order = np.argsort(-priority, kind="stable")
    keep = order[: max(budget // 5, 0)]
    chosen = np.zeros(priority.shape, bool)
    chosen[keep] = priority[keep] > 0
    return chosen


def _add_points(refinement: Refinement, base: dict, chosen: Leaves, coordinates, solve) -> Refinement:
    """The refinement with the centres and edge middles of the ``chosen`` leaves solved."""
    corner_values = [refinement.values_at(base, cu, cv, "fmax_normalised") for cu, cv in chosen.corners()]
    candidates = [(*chosen.centre(), sum(corner_values) / 4.0)]
    low_low, high_low, low_high, high_high = corner_values
    for (mu, mv), ends in zip(chosen.edge_middles(), ((low_low, high_low), (low_high, high_high),
                                                      (low_low, low_high), (high_low, high_high))):
        candidates.append((mu, mv, (ends[0] + ends[1]) / 2.0))
    u = np.concatenate([c[0] for c in candidates])
    v = np.concatenate([c[1] for c in candidates])
    interpolated = np.concatenate([c[2] for c in candidates])
    codes, first = np.unique(refinement.code(u, v), return_index=True)
    _, exists = refinement.index(codes)
    on_base = (u[first] % refinement.scale == 0) & (v[first] % refinement.scale == 0)
    new = ~exists & ~on_base
    codes, first = codes[new], first[new]
    zetas, lambdas = coordinates(u[first] / refinement.scale, v[first] / refinement.scale)
    solved = solve(zetas, lambdas)
    added = {name: np.array([row[name] for row in solved], float) for name in REFINEMENT_VARIABLES if name != "surplus"}
    added["fmax_normalised"] = added["fmax_normalised"].astype(np.float32).astype(float)  # as stored
    # an unresolved point (no value) gets the largest error F̄max ∈ [0, 1] allows: finite,
    # and a cell that has it on an edge is split no further by it (its own corners decide)
    added["surplus"] = np.nan_to_num(np.abs(added["fmax_normalised"] - interpolated[first]), nan=1.0)
    merged_codes = np.concatenate([refinement.codes, codes])
    order = np.argsort(merged_codes, kind="stable")
    values = {name: np.concatenate([refinement.values[name], np.asarray(added[name], dtype)])[order]
              for name, dtype in REFINEMENT_VARIABLES.items()}
    return Refinement(refinement.shape, merged_codes[order], values, refinement.max_level)


def _children(leaves: Leaves, split: np.ndarray) -> Leaves:
    """``leaves`` with each split one replaced by its four children."""
    keep = ~split
    half = leaves.side[split] // 2
    u, v, level = leaves.u[split], leaves.v[split], leaves.level[split] + 1
    return Leaves(np.concatenate([leaves.level[keep], np.tile(level, 4)]),
                  np.concatenate([leaves.u[keep], u, u + half, u, u + half]),
                  np.concatenate([leaves.v[keep], v, v, v + half, v + half]),
                  np.concatenate([leaves.side[keep], np.tile(half, 4)]))
