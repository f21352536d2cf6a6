"""Refinement of a map with axes beyond (λ, ζ): one (λ, ζ) refinement per slice of its extra axes.

A :class:`SlicedRefinement` holds one :class:`~impactmaps.maps.family.refinement.Refinement`
per slice (e.g. per β of an elastic-plastic map, C order of the extra axes), stored as
one dataset with a ``slice`` index per point. Only F̄max is refined.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Callable

import functools
import itertools

import numpy as np

from .refinement import MAX_LEVEL, REFINEMENT_VARIABLES, Refinement, refine

if TYPE_CHECKING:
    import xarray as xr

__all__ = ["SlicedRefinement", "refine_slices", "read_slices"]


@dataclass(frozen=True)
class SlicedRefinement:
    """One :class:`~impactmaps.maps.family.refinement.Refinement` per slice of a map's extra
    axes: ``extra_shape`` (grid values per extra axis) and ``slices`` (C order of the extra
    axes' grid indices).
    """

    extra_shape: tuple
    slices: tuple

    def __post_init__(self):
        if int(np.prod(self.extra_shape)) != len(self.slices):
            raise ValueError(f"a sliced refinement of extra shape {self.extra_shape} needs "
                             f"{int(np.prod(self.extra_shape))} slices, got {len(self.slices)}")

    @property
    def shape(self) -> tuple:
        """The base map's grid: the extra axes' shape, then (number of λ, number of ζ)."""
        return (*self.extra_shape, *self.slices[0].shape)

    @property
    def size(self) -> int:
        """Points added over all slices."""
        return sum(part.codes.size for part in self.slices)

    @classmethod
    def empty(cls, shape, max_level: int = MAX_LEVEL) -> "SlicedRefinement":
        """No point added in any slice of a map of grid ``shape`` (extra axes, λ, ζ)."""
        extra = tuple(int(n) for n in shape[:-2])
        return cls(extra, tuple(Refinement.empty(shape[-2:], max_level) for _ in range(int(np.prod(extra)))))

    def dataset(self, attrs: dict | None = None) -> xr.Dataset:
        """All slices' points as one Dataset (one ``point`` dimension, each point's ``slice``)."""
        first = self.slices[0]
        merged = Refinement(first.shape, np.concatenate([part.codes for part in self.slices]),
                            {name: np.concatenate([np.asarray(part.values[name], dtype) for part in self.slices])
                             for name, dtype in REFINEMENT_VARIABLES.items()}, first.max_level)
        out = merged.dataset({"slice_points": list(self.extra_shape)} | dict(attrs or {}))
        counts = [part.codes.size for part in self.slices]
        return out.assign(slice=("point", np.repeat(np.arange(len(counts), dtype=np.int16), counts)))

    @classmethod
    def from_dataset(cls, dataset: xr.Dataset, base_fmax: np.ndarray | None = None) -> "SlicedRefinement":
        """The refinement stored by :meth:`dataset`; ``base_fmax`` (the base map's F̄max on its
        grid) recomputes a missing surplus.
        """
        extra = tuple(int(n) for n in np.atleast_1d(dataset.attrs["slice_points"]))
        index = np.asarray(dataset["slice"].values, int)
        base = None if base_fmax is None else np.reshape(base_fmax, (-1, *np.shape(base_fmax)[-2:]))
        slices = []
        for k in range(int(np.prod(extra))):
            part = dataset.isel(point=np.flatnonzero(index == k)).drop_vars("slice")
            slices.append(Refinement.from_dataset(part, None if base is None else base[k]))
        return cls(extra, tuple(slices))


def refine_slices(bases: list, estimates: list, coordinates: Callable, solve: Callable, extra_values: list,
                  extra_shape: tuple | None = None, **options) -> SlicedRefinement:
    """Refine every (λ, ζ) slice of a map with extra axes (:func:`~impactmaps.maps.family.refinement.refine`
    each); returns a :class:`SlicedRefinement`.

    Parameters
    ----------
    bases, estimates : list
        Per slice (C order): its ``fmax_normalised``, ``fmax_error``, ``status`` (λ, ζ)
        arrays, and its interpolation-error estimate per grid point [-].
    coordinates : callable
        ``coordinates(row, col) -> (zeta, lambda_)`` of the (λ, ζ) grid.
    solve : callable
        ``solve(zetas, lambdas, extra) -> list of row dicts`` at extra-axis values ``extra``.
    extra_values : list of tuple
        Per slice, the values of its extra axes.
    extra_shape : tuple of int, optional
        The extra axes' grid shape (default: one axis).
    **options
        ``tolerance``, ``max_level``, ``max_points`` (per slice), ``progress``.
    """
    extra_shape = (len(bases),) if extra_shape is None else extra_shape
    slices = []
    for base, estimate, extra in zip(bases, estimates, extra_values):
        def solve_slice(zetas, lambdas, extra=tuple(extra)):
            return solve(zetas, lambdas, extra)

        slices.append(refine(base, estimate, coordinates, solve_slice, **options))
    return SlicedRefinement(tuple(extra_shape), tuple(slices))


def read_slices(planes, shape: tuple, rows: np.ndarray, cols: np.ndarray, brackets: list):
    """F̄max of refined slices at (λ, ζ) positions, interpolated linearly across the extra axes.

    Parameters
    ----------
    planes : sequence of PlaneInterpolator
        Each slice prepared for reading (C order of the extra axes).
    shape : tuple of int
        The extra axes' grid shape.
    rows, cols : ndarray
        Positions in grid units along λ and ζ.
    brackets : list of (ndarray, ndarray, ndarray)
        Per extra axis: grid indices below and above each position and the fraction between.

    Returns
    -------
    fmax, band : ndarray
        The weighted F̄max of the neighbouring slices and their largest band [-].
    deep, between : ndarray of bool
        Whether a slice reads the position in a refined leaf; whether several slices weigh.
    corner_codes : list of ndarray
        The status codes of each slice's leaf corners (0 where one has no weight).
    """
    n = np.size(rows)
    fmax, band, deep, count, corner_codes = np.zeros(n), np.zeros(n), np.zeros(n, bool), np.zeros(n, int), []
    for corner in itertools.product(*(((lower, 1.0 - fraction), (upper, fraction))
                                      for lower, upper, fraction in brackets)):
        indices, weights = zip(*corner)
        weight = functools.reduce(np.multiply, weights)
        used = weight > 0
        index = np.ravel_multi_index(indices, shape)
        value, error, codes = np.zeros(n), np.zeros(n), np.zeros((4, n), int)
        for k in np.unique(index[used]):
            chosen = used & (index == k)
            plane = planes[k]
            read, error[chosen], codes[:, chosen] = plane.interpolate(rows[chosen], cols[chosen])
            value[chosen] = read["fmax_normalised"]
            leaf = plane.cell_leaf[np.minimum(np.floor(rows[chosen] * plane.scale).astype(np.int64), plane.cells[0] - 1),
                                   np.minimum(np.floor(cols[chosen] * plane.scale).astype(np.int64), plane.cells[1] - 1)]
            deep[chosen] |= ~plane.at_base[leaf]
        fmax = fmax + np.where(used, weight * value, 0.0)
        band = np.maximum(band, np.where(used, error, 0.0))
        count += used
        corner_codes.extend(codes)
    return fmax, band, deep, count > 1, corner_codes
