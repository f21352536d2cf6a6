"""Input validation in one place.

Every public constructor and function validates through these helpers so that bad
input always raises a :class:`ValueError` that names the parameter, the value given
and the valid range.
"""

from __future__ import annotations

import math
import stat
from pathlib import Path

import numpy as np

__all__ = [
    "ModelValidityWarning",
    "range_end_text",
    "require_positive",
    "require_positive_fields",
    "require_nonnegative",
    "require_in_range",
    "require_choice",
    "require_finite",
    "require_instance",
    "MIN_PLATE_SIDE_RATIO",
    "UNUSUAL_SIZES_M",
    "UnusualValueWarning",
    "warn_if_unusual",
    "require_plate_proportions",
]


def _describe(value) -> str:
    array = np.asarray(value)
    if array.ndim == 0:
        return repr(value.item() if hasattr(value, "item") else value)
    bad = array.ravel()
    return f"array of shape {array.shape} (first values {bad[:3].tolist()})"


def describe_outside(value, low: float, high: float) -> str:
    """``value`` for an error message about the elements outside ``[low, high]``: a scalar
    as itself, an array by its shape, how many elements lie outside and the first three
    of them (never the whole array)."""
    array = np.asarray(value, dtype=float)
    if array.ndim == 0:
        return repr(float(array))
    outside = array[(array < low) | (array > high)].ravel()
    return (f"array of shape {array.shape} with {outside.size} value(s) outside "
            f"(first {outside[:3].tolist()})")


def require_finite(name: str, value, unit: str = "") -> None:
    """Raise ``ValueError`` unless every element of ``value`` is a finite real number (a
    string is refused, even one that spells a number)."""
    if isinstance(value, (str, bytes)) or (isinstance(value, np.ndarray) and value.dtype.kind in "USO"):
        raise ValueError(f"{name} = {value!r} is a {type(value).__name__}, not a number{_unit(unit)}")
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} = {value!r} is not a real number{_unit(unit)}") from None
    if not np.all(np.isfinite(array)):
        raise ValueError(f"{name} = {_describe(value)} is invalid: must be finite{_unit(unit)}")


def require_positive(name: str, value, unit: str = "") -> None:
    """Raise ``ValueError`` unless every element of ``value`` is finite and > 0."""
    if _real_scalar(value) and 0.0 < value < math.inf:
        return  # the common scalar case, without NumPy
    if _float_array(value) and 0.0 < value.min() and value.max() < math.inf:
        return  # a float array, in two reductions (a NaN fails both comparisons)
    require_finite(name, value, unit)
    if np.any(np.asarray(value, dtype=float) <= 0):
        raise ValueError(
            f"{name} = {_describe(value)} is invalid: valid range is (0, inf){_unit(unit)}"
        )


def require_positive_fields(instance, units: dict) -> None:
    """:func:`require_positive` on each field of ``instance`` named in ``units`` (field → unit), in order."""
    for name, unit in units.items():
        require_positive(name, getattr(instance, name), unit)


def require_nonnegative(name: str, value, unit: str = "") -> None:
    """Raise ``ValueError`` unless every element of ``value`` is finite and >= 0."""
    if _real_scalar(value) and 0.0 <= value < math.inf:
        return  # the common scalar case, without NumPy
    require_finite(name, value, unit)
    if np.any(np.asarray(value, dtype=float) < 0):
        raise ValueError(
            f"{name} = {_describe(value)} is invalid: valid range is [0, inf){_unit(unit)}"
        )


def require_in_range(
    name: str,
    value,
    low: float,
    high: float,
    *,
    low_inclusive: bool = True,
    high_inclusive: bool = True,
    unit: str = "",
) -> None:
    """Raise ``ValueError`` unless every element of ``value`` lies in ``[low, high]``, each end
    open or closed as requested (``-inf``/``inf`` allowed)."""
    if _real_scalar(value) and _real_scalar(low) and _real_scalar(high) and math.isfinite(value):
        scalar = float(value)  # the common scalar case, without NumPy (NaN, ±inf: the checks below)
        below = scalar < low if low_inclusive else scalar <= low
        above = scalar > high if high_inclusive else scalar >= high
        if not (below or above):
            return
    require_finite(name, value, unit)
    array = np.asarray(value, dtype=float)
    below = array < low if low_inclusive else array <= low
    above = array > high if high_inclusive else array >= high
    if np.any(below) or np.any(above):
        left = "[" if low_inclusive and math.isfinite(low) else "("
        right = "]" if high_inclusive and math.isfinite(high) else ")"
        raise ValueError(
            f"{name} = {_describe(value)} is invalid: valid range is "
            f"{left}{range_end_text(low)}, {range_end_text(high)}{right}{_unit(unit)}"
        )


def range_end_text(value: float) -> str:
    """A range end as text: ``%g`` when that is the number, else ten digits (``%g`` would print
    0.4999995 as 0.5, an end the range excludes)."""
    short = f"{value:g}"
    return short if float(short) == value else f"{value:.10g}"


def require_instance(name: str, value, kinds, hint: str = "") -> None:
    """Raise ``TypeError`` unless ``value`` is an instance of ``kinds`` (a type or a tuple of
    types); the message names the parameter, what was given and ``hint`` (how to build
    the right object, e.g. ``"impactmaps.materials.material('steel')"``)."""
    if isinstance(value, kinds):
        return
    wanted = " or ".join(k.__name__ for k in (kinds if isinstance(kinds, tuple) else (kinds,)))
    raise TypeError(f"{name} = {value!r} is a {type(value).__name__}, not {wanted}"
                    f"{': ' + hint if hint else ''}")


def require_flag(name: str, value) -> None:
    """Raise ``ValueError`` unless ``value`` is a boolean (``True``/``False``, a NumPy bool):
    a string such as ``"false"`` is refused, not read as true."""
    if not isinstance(value, (bool, np.bool_)):
        raise ValueError(f"{name} = {value!r} is invalid: valid values are true and false (a boolean, not a "
                         f"{type(value).__name__})")


def require_whole(name: str, value) -> None:
    """Raise ``ValueError`` unless ``value`` is a whole number (an int, or a float without a
    fraction; not a boolean)."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer, float, np.floating)) \
            or (isinstance(value, (float, np.floating)) and not float(value).is_integer()):
        raise ValueError(f"{name} = {value!r} is invalid: a whole number is expected")


def require_choice(name: str, value, choices) -> None:
    """Raise ``ValueError`` unless ``value`` is one of ``choices``."""
    choices = list(choices)
    if value not in choices:
        listed = ", ".join(repr(c) for c in choices)
        raise ValueError(f"{name} = {value!r} is not known: valid values are {listed}")


def _real_scalar(value) -> bool:
    """Whether ``value`` is a Python or NumPy float, or a Python int (bool included): a
    scalar the checks may compare without NumPy, as NumPy would compare it as a float."""
    return isinstance(value, float) or (isinstance(value, int) and abs(value) < _EXACT_INTEGER_LIMIT)


def _float_array(value) -> bool:
    """Whether ``value`` is a non-empty float64 ndarray (its ``min``/``max`` then propagate NaN)."""
    return type(value) is np.ndarray and value.dtype == np.float64 and value.size > 0


#: Ints below this size convert to float exactly: the fast paths compare them as NumPy would.
_EXACT_INTEGER_LIMIT = 2**53


def _unit(unit: str) -> str:
    return f" [{unit}]" if unit else ""


def require_isotropic_material(name: str, material) -> tuple[float, float, float]:
    """``(E [Pa], ν [-], ρ [kg/m³])`` of ``material``, validated; ``TypeError`` naming
    ``name`` when it is not a material (e.g. a catalogue name given as a string) and
    ``ValueError`` naming ``name.youngs_modulus`` etc. when a value is out of range."""
    if not all(hasattr(material, key) for key in ("youngs_modulus", "poisson_ratio", "density")):
        raise TypeError(f"{name} = {material!r} is a {type(material).__name__}, not a material with "
                        "youngs_modulus, poisson_ratio and density: use impactmaps.material(NAME)")
    youngs, poisson, density = (float(material.youngs_modulus), float(material.poisson_ratio),
                                float(material.density))
    require_positive(f"{name}.youngs_modulus", youngs, "Pa")
    require_in_range(f"{name}.poisson_ratio", poisson, -1.0, 0.5, low_inclusive=False, high_inclusive=False)
    require_positive(f"{name}.density", density, "kg/m^3")
    return youngs, poisson, density


#: The largest input file read [bytes]: case and sweep files are a few kB (memory stays bounded).
MAX_INPUT_BYTES = 1_000_000


def read_text_input(what: str, value) -> tuple[Path, str]:
    """The path and UTF-8 text of the input file ``value`` (``what``: e.g. ``"case file"``);
    ``ValueError`` naming it if it does not exist, is a directory, cannot be read or is not
    UTF-8 text (a TOML file is expected)."""
    path = Path(value)
    try:
        status = path.stat()
        if stat.S_ISREG(status.st_mode) and status.st_size > MAX_INPUT_BYTES:
            raise ValueError(f"{what} {str(path)!r} is {status.st_size} bytes: valid range is up to "
                             f"{MAX_INPUT_BYTES} bytes (a TOML file is expected)")
        if not stat.S_ISREG(status.st_mode) and not stat.S_ISDIR(status.st_mode):
            raise ValueError(f"{what} {str(path)!r} is not a regular file (a pipe or device): a TOML file is "
                             "expected")
        return path, path.read_bytes().decode("utf-8")
    except FileNotFoundError:
        raise ValueError(f"{what} {str(path)!r} does not exist") from None
    except IsADirectoryError:
        raise ValueError(f"{what} {str(path)!r} is a directory, not a TOML file") from None
    except OSError as error:
        raise ValueError(f"{what} {str(path)!r} cannot be read: {error.strerror or error}") from None
    except UnicodeDecodeError as error:
        raise ValueError(f"{what} {str(path)!r} is not UTF-8 text (byte {error.start}): a TOML file is "
                         "expected") from None


# -- sense checks: sizes that look like a unit slip ------------------------------------------
#: Smallest side/thickness of a plate any plate theory describes (a beam's L/h ≥ 2 likewise,
#: :data:`impactmaps.targets.beams.beam.MIN_SLENDERNESS`): below it the body is a block.
MIN_PLATE_SIDE_RATIO = 2.0
#: Sizes above which a value is announced as unusual [m]: an impactor radius (a steel ball of
#: 0.5 m weighs 4 t) and a plate's thickness or a beam's depth (millimetres typed as metres).
UNUSUAL_SIZES_M = {"radius": 0.5, "thickness": 0.5, "height": 0.5}


class ModelValidityWarning(UserWarning):
    """A physical case lies outside the assumptions of the impact model."""


class UnusualValueWarning(UserWarning):
    """An input the model accepts but that looks like a unit slip (millimetres typed as metres)."""


def warn_if_unusual(name: str, value: float, kind: str, note: str = "", stacklevel: int = 3) -> None:
    """Warn (:class:`UnusualValueWarning`) when a size ``value`` [m] of ``kind`` (a key of
    :data:`UNUSUAL_SIZES_M`) is above its usual range, naming it as the user wrote it
    (``name``); ``note`` adds what the value implies (e.g. the ball's mass)."""
    limit = UNUSUAL_SIZES_M[kind]
    if value > limit:
        import warnings

        extra = f" ({note})" if note else ""
        warnings.warn(f"{name} = {value:g} m is unusually large{extra}: above {limit:g} m; sizes are in metres "
                      f"(did you mean {value:g} mm = {value / 1000:g} m?)", UnusualValueWarning,
                      stacklevel=stacklevel)


def require_plate_proportions(thickness_name: str, thickness: float, side: float) -> None:
    """Refuse a plate whose smaller ``side`` [m] is less than :data:`MIN_PLATE_SIDE_RATIO`
    thicknesses (``ValueError`` naming ``thickness_name`` as the user wrote it and the range)."""
    if side / thickness < MIN_PLATE_SIDE_RATIO:
        raise ValueError(f"{thickness_name} = {thickness:g} m is invalid for a plate whose smaller side is {side:g} m: "
                         f"side/thickness = {side / thickness:.3g} is below {MIN_PLATE_SIDE_RATIO:g}, where no plate "
                         f"theory holds (a block, not a plate); valid range: {thickness_name} ≤ "
                         f"{side / MIN_PLATE_SIDE_RATIO:g} m (sizes are in metres: 3 mm is 0.003)")
