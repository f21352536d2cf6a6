"""TOML tables onto constructor arguments, with errors that name the key path.

:func:`read_options` maps a table onto the keyword options of a dataclass or
constructor (unknown keys listed with the valid ones, kinds checked); ranges are the
constructor's, whose ``ValueError`` :class:`key_path` prefixes with the key path.
"""

from __future__ import annotations

import dataclasses
import inspect
import math
import re
import typing

from ._checks import require_choice, require_in_range

__all__ = [
    "table",
    "check_keys",
    "number",
    "string",
    "boolean",
    "number_list",
    "key_path",
    "keyword_options",
    "read_options",
]

_NUMBER, _INTEGER, _BOOLEAN, _STRING, _NUMBERS = "number", "integer", "boolean", "string", "numbers"


def _join(path: str, key: str) -> str:
    return f"{path}.{key}" if path else key


def _unit(unit: str) -> str:
    return f" [{unit}]" if unit else ""


_MISSING = object()


def _given(data, key, name, required, unit=""):
    """``data[key]``; if the key is missing, a ValueError naming ``name`` when ``required``, else ``_MISSING``."""
    if key in data:
        return data[key]
    if required:
        raise ValueError(f"{name} is required{_unit(unit)}")
    return _MISSING


def table(value, path: str) -> dict:
    """``value`` if it is a TOML table, else a ValueError naming ``[path]``."""
    if not isinstance(value, dict):
        raise ValueError(f"[{path}] must be a table, got {type(value).__name__} {value!r}")
    return value


def check_keys(data: dict, path: str, allowed, required=()) -> None:
    """Refuse keys not in ``allowed`` (listing the valid ones) and missing ``required`` keys."""
    unknown = sorted(set(data) - set(allowed))
    if unknown:
        names = ", ".join(_join(path, k) for k in unknown)
        where = f"in [{path}]" if path else "at the top level"
        raise ValueError(f"unknown key(s) {names}: valid keys {where} are {', '.join(sorted(allowed))}")
    for key in required:
        if key not in data:
            raise ValueError(f"{path}.{key} is required (missing from [{path}])")


#: Largest value a case-file number of each unit may take, unless its key sets its own
#: range: far beyond any impact the models describe, so that a typing error (1e300) is
#: refused by range instead of overflowing in the physics (a 1e300 m/s impact raised
#: OverflowError). 10 km, 10 km/s, 1e9 kg, 1e13 Pa (diamond: 1.2e12), 1e5 kg/m³ (osmium:
#: 2.3e4).
UNIT_LIMITS = {"m": 1.0e4, "m/s": 1.0e4, "kg": 1.0e9, "Pa": 1.0e13, "kg/m^3": 1.0e5}


def number(data, key, path, unit="", *, default=None, required=False, low=0.0, high=math.inf,
           low_inclusive=False, high_inclusive=True, integer=False):
    """A number from ``data[key]`` validated into a range (ValueError naming the key path);
    without ``high``, bounded by its unit's :data:`UNIT_LIMITS` entry.
    """
    if high == math.inf and unit in UNIT_LIMITS:
        high = UNIT_LIMITS[unit]
    name = _join(path, key)
    value = _given(data, key, name, required, unit)
    if value is _MISSING:
        return default
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ValueError(f"{name} = {value!r} is not a number{_unit(unit)}")
    if integer and isinstance(value, float) and not value.is_integer():  # NaN, ±inf too
        raise ValueError(f"{name} = {value!r} is invalid: must be an integer")
    require_in_range(name, value, low, high, low_inclusive=low_inclusive,
                     high_inclusive=high_inclusive, unit=unit)
    return int(value) if integer else float(value)


def string(data, key, path, *, choices=None, default=None, required=False):
    """A string from ``data[key]``, optionally one of ``choices``."""
    name = _join(path, key)
    value = _given(data, key, name, required)
    if value is _MISSING:
        return default
    if not isinstance(value, str):
        raise ValueError(f"{name} = {value!r} is not a string")
    if choices is not None:
        require_choice(name, value, choices)
    return value


def boolean(data, key, path, *, default=None):
    """A boolean from ``data[key]``."""
    if key not in data:
        return default
    value = data[key]
    if not isinstance(value, bool):
        raise ValueError(f"{_join(path, key)} = {value!r} is not a boolean (true or false)")
    return value


def number_list(data, key, path, unit="", *, length=None, low=-math.inf, high=math.inf,
                low_inclusive=True, high_inclusive=True):
    """A non-empty list of numbers from ``data[key]`` (each validated into the range)."""
    name = _join(path, key)
    value = data[key]
    if not isinstance(value, list) or not value:
        raise ValueError(f"{name} = {value!r} is not a non-empty list of numbers{_unit(unit)}")
    if length is not None and len(value) != length:
        raise ValueError(f"{name} = {value!r} must have {length} entries{_unit(unit)}")
    out = []
    for index, item in enumerate(value):
        item_name = f"{name}[{index}]"
        if isinstance(item, bool) or not isinstance(item, (int, float)):
            raise ValueError(f"{item_name} = {item!r} is not a number{_unit(unit)}")
        require_in_range(item_name, item, low, high, low_inclusive=low_inclusive,
                         high_inclusive=high_inclusive, unit=unit)
        out.append(float(item))
    return out


_LEADING_NAME = re.compile(r"[A-Za-z_]\w*")


class key_path:
    """Context manager: a ValueError raised inside names the key path (``path.`` before a
    message starting with one of ``keys``, else ``path: ``).
    """

    def __init__(self, path: str, keys=()):
        self.path = path
        self.keys = frozenset(keys)

    def __enter__(self):
        return self

    def __exit__(self, kind, error, traceback):
        if kind is None or not issubclass(kind, ValueError) or getattr(error, "_case_path", False):
            return False
        message = str(error)
        leading = _LEADING_NAME.match(message)
        if leading and leading.group() in self.keys:
            wrapped = ValueError(f"{self.path}.{message}")
        else:
            wrapped = ValueError(f"{self.path}: {message}")
        wrapped._case_path = True
        raise wrapped from error


def _kind(annotation, default) -> str:
    """The TOML value kind of an option, from its annotation or, failing that, its default."""
    members = [a for a in typing.get_args(annotation) if a is not type(None)]
    if len(members) == 1:  # ``X | None``: an optional X
        annotation = members[0]
    text = str(annotation)
    if annotation is bool or isinstance(default, bool):
        return _BOOLEAN
    if annotation is int or (annotation is inspect.Parameter.empty and type(default) is int):
        return _INTEGER
    if annotation is str or isinstance(default, str):
        return _STRING
    if "tuple" in text or "list" in text or isinstance(default, (tuple, list)):
        return _NUMBERS
    return _NUMBER


def keyword_options(build) -> dict[str, str]:
    """``{name: kind}`` of the keyword options of a dataclass or function ``build`` (also a
    dataclass's options forwarded by ``**kwargs``), kind one of ``"number"``, ``"integer"``,
    ``"boolean"``, ``"string"``, ``"numbers"``.
    """
    if dataclasses.is_dataclass(build) and isinstance(build, type):
        hints = typing.get_type_hints(build)
        return {f.name: _kind(hints.get(f.name, f.type), f.default)
                for f in dataclasses.fields(build)
                if f.init and not f.name.startswith("_")
                and (f.default is not dataclasses.MISSING or f.default_factory is not dataclasses.MISSING)}
    signature = inspect.signature(build)
    try:
        hints = typing.get_type_hints(build)
    except Exception:  # noqa: BLE001 - unresolvable annotations: fall back to the defaults
        hints = {}
    options = {}
    for name, parameter in signature.parameters.items():
        if parameter.kind is inspect.Parameter.VAR_KEYWORD:
            owner = getattr(build, "__self__", None)
            if owner is not None and dataclasses.is_dataclass(owner):
                options.update(keyword_options(owner))
        elif parameter.default is not inspect.Parameter.empty:
            options[name] = _kind(hints.get(name, parameter.annotation), parameter.default)
    return options


def read_options(data: dict, path: str, options: dict[str, str], units=None) -> dict:
    """The values of ``data`` for the keys in ``options``, each checked for its kind (absent
    keys left out; ranges are the constructor's).
    """
    units = units or {}
    out = {}
    for key, kind in options.items():
        if key not in data:
            continue
        unit = units.get(key, "")
        if kind == _BOOLEAN:
            out[key] = boolean(data, key, path)
        elif kind == _STRING:
            out[key] = string(data, key, path)
        elif kind == _NUMBERS:
            out[key] = tuple(number_list(data, key, path, unit))
        else:
            out[key] = number(data, key, path, unit, low=-math.inf, integer=kind == _INTEGER)
    return out
