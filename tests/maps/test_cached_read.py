"""What a lookup of a cached tile reads without xarray or an integration: the tile through
SciPy's NetCDF reader (the values, dtypes and attributes xarray gives), and the Hertz
asymptote peaks of its regime from the cache directory (the same bits as integrated)."""

from __future__ import annotations

import numpy as np
import xarray as xr

from impactmaps import _files
from impactmaps.maps.compute import hertz_points
from impactmaps.maps.files.data_io import MapArrays, read_netcdf_arrays
from impactmaps.maps.files.store import save_atomic


def _tile_like() -> xr.Dataset:
    """A one-structure map as a tile stores it: text structure name, NaN where unresolved, ints."""
    shape = (1, 2, 3)
    values = np.arange(6.0).reshape(shape) / 7.0
    values[0, 1, 2] = np.nan
    data = {"fmax_normalised": (("structure", "lambda_", "zeta"), values, {"units": "1"}),
            "status": (("structure", "lambda_", "zeta"), np.ones(shape, np.int8), {"units": "1"}),
            "impacts": (("structure", "lambda_", "zeta"), np.full(shape, 3, np.int32), {"units": "1"}),
            "log_peak_time": (("structure", "lambda_", "zeta"), np.log(values + 1.0))}
    coords = {"structure": ["plate-cccc-mindlin-ar0.666667-s50"], "lambda_": [0.1, 0.2], "zeta": [1.0, 2.0, 4.0]}
    return xr.Dataset(data, coords=coords, attrs={"fingerprint": "abc", "contact_law": "hertz", "solver_revision": 8})


def test_a_netcdf_map_reads_as_xarray_reads_it(tmp_path):
    path = save_atomic(_tile_like(), tmp_path / "tile.nc")
    arrays = read_netcdf_arrays(path)
    with xr.open_dataset(path, engine="scipy") as opened:
        expected = opened.load()
    assert isinstance(arrays, MapArrays)
    assert set(arrays.variables) == set(expected.variables)
    assert sorted(arrays.data_vars) == sorted(expected.data_vars) and set(arrays.coord_names) == set(expected.coords)
    for name in expected.variables:
        mine, theirs = arrays[name], expected[name]
        assert mine.dims == theirs.dims and mine.values.dtype == theirs.values.dtype, name
        if theirs.values.dtype.kind in "fiu":
            assert mine.values.tobytes() == theirs.values.tobytes(), name  # the same bits, NaN included
        else:
            assert list(mine.values.ravel()) == list(theirs.values.ravel()), name
        assert {k: str(v) for k, v in mine.attrs.items()} == {k: str(v) for k, v in theirs.attrs.items()}, name
    assert {k: str(v) for k, v in arrays.attrs.items()} == {k: str(v) for k, v in expected.attrs.items()}


def test_a_netcdf_file_with_cf_decoding_is_left_to_xarray(tmp_path):
    """A scaled or masked variable (what a tile never holds) is read by xarray, decoded."""
    dataset = _tile_like()
    dataset["fmax_normalised"].encoding = {"scale_factor": 0.5, "dtype": "int16", "_FillValue": -1}
    path = save_atomic(dataset, tmp_path / "scaled.nc")
    read = read_netcdf_arrays(path)
    assert isinstance(read, xr.Dataset)
    assert np.allclose(read["fmax_normalised"].values, dataset["fmax_normalised"].values, atol=0.25, equal_nan=True)


def test_hertz_asymptote_peaks_are_kept_on_disk_bit_for_bit(tmp_path, monkeypatch):
    monkeypatch.setenv("IMPACTMAPS_CACHE_DIR", str(tmp_path))
    hertz_points._asymptote_peak.cache_clear()
    zeta = np.array([0.7, 2.4796057354841206])
    integrated = hertz_points.hertz_asymptote_peak("infinite", "plate", zeta_h=zeta)
    path = hertz_points.stored_peaks_path()
    assert path.parent == tmp_path and path.exists()
    _files._stored.clear()  # a new process: nothing in memory
    hertz_points._asymptote_peak.cache_clear()
    monkeypatch.setattr(hertz_points, "_asymptote_peak", None)  # nothing may be integrated now
    read = hertz_points.hertz_asymptote_peak("infinite", "plate", zeta_h=zeta)
    assert read.tobytes() == integrated.tobytes()
