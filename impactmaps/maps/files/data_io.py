"""Reading and writing map datasets: NetCDF for results, compressed archives for shipped data.

:func:`read_dataset` / :func:`write_dataset` choose the format by suffix: ``.nc``
(NetCDF3 through SciPy, what a sweep, chart or tile writes) or ``.npz``, a packed map
(:func:`pack`: byte planes, derived variables recomputed, optional float32/bfloat16
variables; same dataset, same bytes; docs/install.rst, "Package data").
Shipped files are found by :mod:`impactmaps.maps.files.shipped`.
"""

from __future__ import annotations

import io
import json
import zipfile
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path

from typing import TYPE_CHECKING

import numpy as np


if TYPE_CHECKING:
    import xarray as xr

__all__ = ["MapVariable", "MapArrays", "PACKED_SUFFIX", "DERIVED", "read_dataset", "write_dataset", "pack", "unpack", "unpack_arrays",
           "read_resource", "read_arrays", "read_resource_arrays", "read_netcdf_arrays"]

#: Suffix of a packed dataset (a NumPy ``.npz`` archive with a JSON header).
PACKED_SUFFIX = ".npz"
#: Format tag in a packed file's header.
FORMAT = "impactmaps-packed-1"
#: Variables recomputed from others on reading: name → (operation, inputs). Stored only
#: where the recomputation misses the exact bits (and in full where an input is absent).
DERIVED = {
    "log_peak_time": ("log", ("peak_time_normalised",)),
    "log_reflection_time": ("log", ("reflection_time_normalised",)),
    "fmax_low": ("minus", ("fmax_normalised", "fmax_error")),
    "fmax_high": ("plus", ("fmax_normalised", "fmax_error")),
}
_OPERATIONS = {"log": np.log, "minus": np.subtract, "plus": np.add}
#: Fixed timestamp of every zip entry (the earliest zip can hold): same dataset, same bytes.
_ZIP_TIME = (1980, 1, 1, 0, 0, 0)


def write_dataset(dataset: xr.Dataset, path, *, packed: bool | None = None, single=(), bfloat16_up=(),
                  keep_exact=None) -> Path:
    """Write ``dataset`` to ``path``: packed (:func:`pack`) if ``packed`` (default: a ``.npz``
    path), else NetCDF3. Not atomic. Returns the path.
    """
    path = Path(path)
    if not (path.suffix == PACKED_SUFFIX if packed is None else packed):
        dataset.to_netcdf(path, engine="scipy", format="NETCDF3_64BIT")
        return path
    arrays = pack(dataset, single=single, bfloat16_up=bfloat16_up, keep_exact=keep_exact)
    with zipfile.ZipFile(path, "w", compression=zipfile.ZIP_DEFLATED, compresslevel=9) as archive:
        for name in sorted(arrays):
            buffer = io.BytesIO()
            np.lib.format.write_array(buffer, arrays[name], allow_pickle=False)
            archive.writestr(zipfile.ZipInfo(f"{name}.npy", date_time=_ZIP_TIME), buffer.getvalue(),
                             compress_type=zipfile.ZIP_DEFLATED, compresslevel=9)
    return path


def read_dataset(path) -> xr.Dataset:
    """The dataset in ``path`` (packed ``.npz`` or NetCDF), loaded into memory."""
    path = Path(path)
    if path.suffix == PACKED_SUFFIX:
        return unpack(_packed_arrays(path))
    return _read_netcdf(path)


def read_arrays(path):
    """The map in ``path``: a packed ``.npz`` as :class:`~impactmaps.maps.files.data_io.MapArrays`
    (NumPy alone), a NetCDF file as an ``xarray.Dataset``; the same values either way.
    """
    path = Path(path)
    if path.suffix == PACKED_SUFFIX:
        return unpack_arrays(_packed_arrays(path))
    return _read_netcdf(path)


def read_netcdf_arrays(path):
    """The NetCDF3 map in ``path`` as :class:`MapArrays`, read with SciPy alone (no xarray,
    whose opening imports dask): the values, dtypes and attributes ``xarray.open_dataset``
    decodes, for a file whose variables need no CF decoding beyond byte order and text
    (an on-demand tile); any other file through xarray (an ``xarray.Dataset``).
    """
    from scipy.io import netcdf_file

    try:
        with netcdf_file(path, "r", mmap=False) as opened:
            raw = {name: (variable.dimensions, variable.data, dict(variable._attributes))
                   for name, variable in opened.variables.items()}
            attrs = {key: _netcdf_attr(value) for key, value in opened._attributes.items()}
    except AttributeError:  # SciPy's reader without the attribute tables xarray reads too
        return _read_netcdf(Path(path))
    if any(not _plain_netcdf(values, variable_attrs) for _, values, variable_attrs in raw.values()):
        return _read_netcdf(Path(path))
    variables, coords = {}, []
    for name, (dims, values, variable_attrs) in raw.items():
        encoding = variable_attrs.pop("_Encoding", None)
        if values.dtype.kind == "S":  # characters along the last dimension: one text each
            text = np.array([b"".join(row).decode(_netcdf_attr(encoding or b"utf-8")) for row in
                             values.reshape(-1, values.shape[-1])], dtype=object)
            values, dims = text.reshape(values.shape[:-1]), dims[:-1]
        else:
            values = values.astype(values.dtype.newbyteorder("="))
        if variable_attrs.get("_FillValue") is not None:  # a NaN fill: nothing masked (as xarray)
            variable_attrs.pop("_FillValue")
        variables[name] = MapVariable(tuple(dims), values, {k: _netcdf_attr(v) for k, v in variable_attrs.items()})
        if dims == (name,):
            coords.append(name)
    return MapArrays(variables, attrs, tuple(coords))


def _plain_netcdf(values: np.ndarray, attrs: dict) -> bool:
    """Whether a NetCDF variable reads as its stored values (no scaling, offset, mask or time
    decoding; a NaN ``_FillValue`` masks nothing)."""
    if {"scale_factor", "add_offset", "missing_value", "calendar"} & set(attrs):
        return False
    if "since" in str(_netcdf_attr(attrs.get("units", ""))):
        return False
    fill = attrs.get("_FillValue")
    return fill is None or (values.dtype.kind == "f" and bool(np.isnan(fill)))


def _netcdf_attr(value):
    """A NetCDF attribute as xarray gives it (text as ``str``)."""
    return value.decode("utf-8") if isinstance(value, bytes) else value


def _packed_arrays(path: Path) -> dict:
    with np.load(path, allow_pickle=False) as archive:
        return {name: archive[name] for name in archive.files}


def _read_netcdf(path: Path) -> xr.Dataset:
    import xarray as xr  # only a NetCDF file needs it (a sweep's, or a shipped file not yet packed)

    with xr.open_dataset(path, engine="scipy") as opened:
        return opened.load()


def read_resource(source) -> xr.Dataset:
    """:func:`read_dataset` of a path or a package resource (an importlib ``Traversable``)."""
    with resources.as_file(source) as path:
        return read_dataset(path)


def read_resource_arrays(source):
    """:func:`read_arrays` of a path or a package resource (an importlib ``Traversable``)."""
    with resources.as_file(source) as path:
        return read_arrays(path)


# -- a map's arrays without xarray --------------------------------------------------------
# A shipped map is read with NumPy alone: MapArrays holds its decoded variables and attributes,
# offering only what the readers ask of a dataset, with the values xarray would give.


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

    @property
    def data_vars(self) -> tuple:
        """The names of the variables that are not coordinates."""
        return tuple(name for name in self.variables if name not in self.coord_names)

    def drop_vars(self, name: str) -> MapArrays:
        """The same arrays without the variable ``name``."""
        return MapArrays({key: value for key, value in self.variables.items() if key != name}, self.attrs,
                         tuple(key for key in self.coord_names if key != name))


# -- the packed format ---------------------------------------------------------------------
def pack(dataset: xr.Dataset, *, single=(), bfloat16_up=(), keep_exact=None) -> dict:
    """The arrays of a packed file: ``__header__`` (JSON, as bytes) and one array per stored
    variable. ``single``: variables stored as float32; ``bfloat16_up``: non-negative ones
    stored as the 16 high bits of their float32, rounded up (an error estimate only grows,
    by < 2⁻⁷); ``keep_exact``: where such a variable keeps its float32 value.
    """
    arrays, variables = {}, []
    for name in [*dataset.coords, *dataset.data_vars]:
        item = dataset[name]
        values = np.asarray(item.values)
        entry = {"name": name, "dims": list(item.dims), "shape": list(values.shape), "dtype": values.dtype.str,
                 "attrs": _json_attrs(item.attrs), "coord": name in dataset.coords}
        if values.dtype.kind in "OUS":
            entry |= {"codec": "text", "values": [str(v) for v in values.ravel()]}
        elif name in bfloat16_up:
            entry["codec"] = "bfloat16_up"
            arrays[name] = _shuffle(_bfloat16_up(values))
            exact = np.asarray((keep_exact or {}).get(name, np.zeros(values.shape, bool)), bool)
            if exact.any():
                arrays[name + ".where_exact"] = np.packbits(exact.ravel())
                arrays[name + ".exact"] = _shuffle(np.asarray(values, np.float32)[exact])
        elif name in DERIVED and _derivable(dataset, name, single, bfloat16_up):
            entry["codec"] = "derived"
            exact = _derived(dataset, name).view(np.uint64) == values.view(np.uint64)
            if not exact.all():
                arrays[name + ".where_stored"] = np.packbits(~exact.ravel())
                arrays[name] = _shuffle(values[~exact])
        else:
            stored = values.astype(np.float32) if name in single and values.dtype.kind == "f" else values
            entry |= {"codec": "shuffle", "stored_dtype": stored.dtype.str}
            arrays[name] = _shuffle(stored)
        variables.append(entry)
    header = {"format": FORMAT, "attrs": _json_attrs(dataset.attrs), "variables": variables}
    arrays["__header__"] = np.frombuffer(json.dumps(header, sort_keys=True).encode(), np.uint8)
    return arrays


def unpack(arrays: dict) -> xr.Dataset:
    """The dataset :func:`pack` stored in ``arrays``."""
    import xarray as xr  # the Dataset is built here; a lookup reads :func:`unpack_arrays` without it

    arrays = unpack_arrays(arrays)
    coords, data_vars = {}, {}
    for name, variable in arrays.variables.items():
        target = coords if name in arrays.coord_names else data_vars
        # fastpath: the arrays are NumPy's already (xarray's check of other array types imports dask.array, ~1 s)
        target[name] = xr.Variable(variable.dims, variable.values, variable.attrs, fastpath=True)
    return xr.Dataset(data_vars, coords=coords, attrs=arrays.attrs)


def unpack_arrays(arrays: dict) -> MapArrays:
    """The variables and attributes :func:`pack` stored in ``arrays``, as :class:`MapArrays` (no xarray)."""
    header = json.loads(bytes(arrays["__header__"]).decode())
    if header.get("format") != FORMAT:
        raise ValueError(f"not a packed impactmaps dataset (format {header.get('format')!r}, expected {FORMAT!r})")
    decoded, derived = {}, []
    for entry in header["variables"]:
        shape, dtype, codec, name = tuple(entry["shape"]), np.dtype(entry["dtype"]), entry["codec"], entry["name"]
        if codec == "text":
            decoded[name] = np.array(entry["values"], dtype=object if dtype.kind == "O" else dtype).reshape(shape)
        elif codec == "bfloat16_up":
            high = _unshuffle(arrays[name], np.dtype("<u2"), shape)
            single_values = (high.astype(np.uint32) << 16).view(np.float32)
            if name + ".where_exact" in arrays:
                where = np.unpackbits(arrays[name + ".where_exact"], count=single_values.size).astype(bool)
                single_values = single_values.ravel()
                single_values[where] = _unshuffle(arrays[name + ".exact"], np.float32, (int(where.sum()),))
                single_values = single_values.reshape(shape)
            decoded[name] = single_values.astype(dtype)
        elif codec == "derived":
            derived.append(entry)
        else:
            decoded[name] = _unshuffle(arrays[name], np.dtype(entry["stored_dtype"]), shape).astype(dtype)
    for entry in derived:  # their inputs are decoded above
        name, shape = entry["name"], tuple(entry["shape"])
        operation, inputs = DERIVED[name]
        with np.errstate(all="ignore"):
            values = np.asarray(_OPERATIONS[operation](*(decoded[i] for i in inputs)), np.dtype(entry["dtype"]))
        if name + ".where_stored" in arrays:
            where = np.unpackbits(arrays[name + ".where_stored"], count=values.size).astype(bool).reshape(shape)
            values[where] = _unshuffle(arrays[name], values.dtype, (int(where.sum()),))
        decoded[name] = values
    variables = {entry["name"]: MapVariable(tuple(entry["dims"]), decoded[entry["name"]], _python_attrs(entry["attrs"]))
                 for entry in header["variables"]}
    return MapArrays(variables, _python_attrs(header["attrs"]),
                     tuple(entry["name"] for entry in header["variables"] if entry["coord"]))


def _derivable(dataset: xr.Dataset, name: str, single, bfloat16_up) -> bool:
    """Whether ``name`` can be recomputed from inputs that are stored exactly, with its shape and dtype."""
    inputs = DERIVED[name][1]
    return all(i in dataset.data_vars and i not in single and i not in bfloat16_up and i not in DERIVED
               and dataset[i].dims == dataset[name].dims and dataset[i].dtype == dataset[name].dtype
               for i in inputs) and dataset[name].dtype == np.float64


def _derived(dataset: xr.Dataset, name: str) -> np.ndarray:
    operation, inputs = DERIVED[name]
    with np.errstate(all="ignore"):
        return np.asarray(_OPERATIONS[operation](*(dataset[i].values for i in inputs)), np.float64)


def _shuffle(values: np.ndarray) -> np.ndarray:
    """The bytes of ``values`` (little-endian), plane by plane: all first bytes, then all second bytes, …"""
    values = np.ascontiguousarray(values, dtype=values.dtype.newbyteorder("<"))
    return values.view(np.uint8).reshape(-1, values.dtype.itemsize).T.ravel()


def _unshuffle(planes: np.ndarray, dtype: np.dtype, shape) -> np.ndarray:
    dtype = np.dtype(dtype).newbyteorder("<")
    raw = np.ascontiguousarray(np.asarray(planes, np.uint8).reshape(dtype.itemsize, -1).T)
    return raw.view(dtype).reshape(shape).astype(dtype.newbyteorder("="))


def _bfloat16_up(values: np.ndarray) -> np.ndarray:
    """The 16 high bits of float32(values), rounded away from zero (NaN and ±inf kept)."""
    bits = np.asarray(values, np.float32).view(np.uint32)
    high = (bits >> 16).astype(np.uint32)
    finite = np.isfinite(np.asarray(values, np.float32))
    high = np.where(finite & ((bits & 0xFFFF) != 0), high + 1, high)
    return high.astype(np.uint16)


def _json_attrs(attrs: dict) -> dict:
    out = {}
    for key, value in attrs.items():
        if isinstance(value, np.ndarray):
            out[key] = {"__ndarray__": value.tolist(), "dtype": value.dtype.str}
        elif isinstance(value, np.generic):
            out[key] = {"__scalar__": value.item(), "dtype": value.dtype.str}
        else:
            out[key] = value
    return out


def _python_attrs(attrs: dict) -> dict:
    out = {}
    for key, value in attrs.items():
        if isinstance(value, dict) and "__ndarray__" in value:
            out[key] = np.array(value["__ndarray__"], dtype=value["dtype"])
        elif isinstance(value, dict) and "__scalar__" in value:
            out[key] = np.dtype(value["dtype"]).type(value["__scalar__"])
        else:
            out[key] = value
    return out
