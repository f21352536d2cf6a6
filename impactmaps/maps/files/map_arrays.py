"""A map file's arrays without xarray: the read-only part of a Dataset that the map readers use.

A shipped map is a packed ``.npz`` (:mod:`impactmaps.maps.files.data_io`) read with NumPy alone;
:class:`MapArrays` holds its decoded variables and attributes so that a lookup
(:mod:`impactmaps.maps.read.lookup`, :mod:`impactmaps.maps.read.reader`) prepares it without importing
xarray (0.3–0.5 s). It offers only what those readers ask of a dataset — ``name in m``,
``m[name].values``/``.dims``/``.shape``/``.attrs``, ``.isel(structure=0)``, ``m.attrs``,
``m.sizes``, ``m.isel(point=…)``, ``m.drop_vars(name)`` — with the same values an
``xarray.Dataset`` of the file gives, so a map reads to the same bits either way.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

__all__ = ["MapVariable", "MapArrays"]


@dataclass(frozen=True)
class MapVariable:
    """One variable: its dimension names, its values (an ndarray) and its attributes."""

    dims: tuple
    values: np.ndarray
    attrs: dict = field(default_factory=dict)

    @property
    def shape(self) -> tuple:
        """The values' shape."""
        return self.values.shape

    @property
    def dtype(self) -> np.dtype:
        """The values' dtype."""
        return self.values.dtype

    def isel(self, **indexers) -> MapVariable:
        """The variable at integer positions along named dimensions (an int drops the dimension)."""
        values, dims = self.values, list(self.dims)
        index = [slice(None)] * len(dims)
        for dim, position in indexers.items():
            index[dims.index(dim)] = position
        kept = tuple(dim for dim, position in zip(dims, index) if not isinstance(position, (int, np.integer)))
        return MapVariable(kept, values[tuple(index)], self.attrs)


@dataclass(frozen=True)
class MapArrays:
    """A map file's variables (coordinates and data alike) and attributes (module docstring)."""

    variables: dict
    attrs: dict = field(default_factory=dict)
    coord_names: tuple = ()

    def __contains__(self, name) -> bool:
        return name in self.variables

    def __getitem__(self, name) -> MapVariable:
        return self.variables[name]

    @property
    def sizes(self) -> dict:
        """Dimension name → length."""
        out = {}
        for variable in self.variables.values():
            out.update(zip(variable.dims, variable.values.shape))
        return out

    def isel(self, **indexers) -> MapArrays:
        """Every variable at the positions along the named dimensions (those without them as they are)."""
        return MapArrays({name: variable.isel(**{dim: position for dim, position in indexers.items()
                                                  if dim in variable.dims})
                          for name, variable in self.variables.items()}, self.attrs, self.coord_names)

    def drop_vars(self, name: str) -> MapArrays:
        """The same arrays without the variable ``name``."""
        return MapArrays({key: value for key, value in self.variables.items() if key != name}, self.attrs,
                         tuple(key for key in self.coord_names if key != name))
