"""The light lookup path (issue 30): the built-in families' layouts and the packed maps read without xarray.

What a lookup imports is checked in a fresh interpreter by ``tests/compile/test_startup.py``; here,
that what it reads instead of the families and the xarray Dataset is the same thing.
"""

from __future__ import annotations

import numpy as np
import pytest

from impactmaps.maps.family import builtin_families, map_family as family_module
from impactmaps.maps.files.data_io import read_arrays, read_dataset
from impactmaps.maps.files.shipped import shipped_path
from impactmaps.maps.files.shipped import refinement_of
from impactmaps.maps.read.reader import prepare_map


def test_the_layouts_are_the_families_layouts():
    """Each built-in family is a subclass of its layout, with the same axes, errors,
    interpolation and shipped maps; the registry names them all, in registration order."""
    from impactmaps.maps.family.structures import DEFAULT_STRUCTURES

    assert family_module.available_map_families()[:5] == ("linear", "hertz", "yc", "stronge", "epp")
    for name, layout in builtin_families.LAYOUTS.items():
        family = family_module.map_family(name)
        assert isinstance(family, type(layout)) and family.name == layout.name == name
        for attribute in ("axes", "errors", "interpolation", "shipped", "classifies", "tile_lattice"):
            assert getattr(family, attribute) == getattr(layout, attribute), (name, attribute)
    assert builtin_families.SHIPPED_PLANE_MAPS == {(s.kind, s.theory): s.name for s in DEFAULT_STRUCTURES}
    assert builtin_families.family_layout("linear") is builtin_families.LAYOUTS["linear"]
    with pytest.raises(ValueError, match="law"):
        builtin_families.family_layout("no-such-law")


@pytest.mark.parametrize("name, law", [("plate-ssss-kirchhoff", "linear"), ("beam-ss-euler-hertz", "hertz"),
                                       ("plate-ssss-kirchhoff-yc", "yc")])
def test_a_packed_map_prepares_to_the_same_bits_without_xarray(name, law):
    """:func:`read_arrays` (NumPy only) and the xarray Dataset of the same file prepare to the
    same arrays, refinement included."""
    source, stored = shipped_path(name), shipped_path("refinements", name)
    prepared = []
    for read in (read_arrays, read_dataset):
        dataset = read(source)
        refinement = None if stored is None else refinement_of(read(stored), dataset)
        prepared.append(prepare_map(dataset, builtin_families.family_layout(law), refinement))
    light, full = prepared
    assert type(read_arrays(source)).__name__ == "MapArrays"
    assert light.axes == full.axes and light.ranges == full.ranges and light.times == full.times
    for field in ("grids", "tables", "band_grids"):
        mine, theirs = getattr(light, field), getattr(full, field)
        assert mine.keys() == theirs.keys()
        for key in mine:
            assert np.array_equal(mine[key], theirs[key], equal_nan=True) and mine[key].dtype == theirs[key].dtype
    for key, (axis, values, logs) in full.lines.items():
        assert light.lines[key][0] == axis and np.array_equal(light.lines[key][1], values)
    assert (light.plane is None) == (full.plane is None) and len(light.slices) == len(full.slices)
    for mine, theirs in zip([light.plane, *light.slices], [full.plane, *full.slices]):
        if theirs is not None:
            assert _same(vars(mine), vars(theirs))


def _same(mine, theirs) -> bool:
    """Equal, array by array (NaN equal to NaN, same dtype), through dicts, tuples and objects."""
    if isinstance(theirs, np.ndarray):
        return mine.dtype == theirs.dtype and np.array_equal(mine, theirs, equal_nan=mine.dtype.kind == "f")
    if isinstance(theirs, dict):
        return mine.keys() == theirs.keys() and all(_same(mine[key], theirs[key]) for key in theirs)
    if isinstance(theirs, (tuple, list)):
        return len(mine) == len(theirs) and all(_same(a, b) for a, b in zip(mine, theirs))
    if hasattr(theirs, "__dict__"):
        return type(mine) is type(theirs) and _same(vars(mine), vars(theirs))
    return mine == theirs
