"""``impactmaps sweep CONFIG.toml``: sweeps described in a TOML file.

:func:`load_sweep_config` parses a file once into a :class:`SweepConfig`;
:func:`run_sweep_config` runs it. Every key, its unit and its default: docs/sweeps.rst.
"""

from __future__ import annotations

import itertools
import math
import tomllib
from dataclasses import dataclass, fields, replace
from pathlib import Path

import numpy as np

from ..._checks import read_text_input
from ..._files import written_atomically
from ...materials._tables import laminate
from ...solvers.modal_settings import ModalSettings
from ...targets.options import default_theory
from ...targets.plates.plate import Plate
from ..family.map_family import available_map_families, map_family
from ..family.structures import MapStructure
from .dataset import tidy_frame
from .sweep import SweepGrid, check_axis, run_sweep_grid, sweep_grid

__all__ = ["SweepConfig", "load_sweep_config", "run_sweep_config", "KIND_DEFAULTS"]

_TOP_KEYS = {"output", "law", "grid", "solver", "structure"}
#: The [[structure]] keys that give a laminated plate as a case file's [target] does (a layup of a
#: catalogue ply, or a list of ply tables); its stiffness ratios then come from the laminate.
_LAMINATE_KEYS = ("layup", "plies")
_STRUCTURE_KEYS = {f.name for f in fields(MapStructure)} | set(_LAMINATE_KEYS)
_SOLVER_KEYS = {f.name for f in fields(ModalSettings)}

#: Defaults of a ``[[structure]]`` table that depend on its ``kind``.
KIND_DEFAULTS = {
    "beam": {"theory": default_theory("beam"), "supports": "ss", "impact_fraction": (0.5,)},
    "plate": {"theory": default_theory("plate"), "supports": "SSSS", "impact_fraction": (0.5, 0.5)},
}


def _number(name, value, *, integer=False):
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise ValueError(f"{name} = {value!r} is invalid: give a finite number")
    if integer and value != int(value):
        raise ValueError(f"{name} = {value!r} is invalid: give a whole number ≥ 1")
    return int(value) if integer else float(value)


#: Most values one grid axis of a sweep file may have (a count of 1e9 allocated gigabytes before
#: any check; the whole map is bounded by the sweep, :func:`impactmaps.maps.compute.sweep.sweep`).
MAX_AXIS_VALUES = 10**6


def _grid(family, name, value):
    """The checked values of axis ``name`` of ``family`` from its [grid] table or list (key
    ``lambda`` for the axis ``lambda_``)."""
    key = "lambda" if name == "lambda_" else name
    return check_axis(family, name, _grid_values(key, value), f"grid.{key}", value)


def _grid_values(name, value):
    path = f"grid.{name}"
    if isinstance(value, dict):
        unknown = set(value) - {"min", "max", "count"}
        if unknown or not {"min", "max", "count"} <= set(value):
            raise ValueError(f"{path} = {value!r} is invalid: give min, max and count, or a list of values")
        low, high = _number(f"{path}.min", value["min"]), _number(f"{path}.max", value["max"])
        count = _number(f"{path}.count", value["count"], integer=True)
        if not 1 <= count <= MAX_AXIS_VALUES:
            raise ValueError(f"{path}.count = {value['count']!r} is invalid: valid range is [1, {MAX_AXIS_VALUES}]")
        if low <= 0 or high < low:
            raise ValueError(f"{path} = {{min = {low:g}, max = {high:g}}} is invalid: need 0 < min ≤ max")
        return np.geomspace(low, high, count)
    if isinstance(value, list) and value:
        values = np.array([_number(f"{path}[{k}]", v) for k, v in enumerate(value)])
        if np.any(values <= 0):
            raise ValueError(f"{path} = {value!r} is invalid: every value must be > 0")
        return values
    raise ValueError(f"{path} = {value!r} is invalid: give min, max and count, or a non-empty list of values")


def _impact_fractions(value, where):
    """The impact points of a table: a number, one point [x, y], or a list of points."""
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return [(float(value),)]
    if isinstance(value, list) and value and all(isinstance(v, list) for v in value):
        return [tuple(v) for v in value]
    if isinstance(value, list) and value and not any(isinstance(v, (list, dict)) for v in value):
        return [tuple(value)]
    raise ValueError(f"{where}.impact_fraction = {value!r} is invalid: give a fraction x0/L, a point "
                     "[x0/a, y0/b] or a list of points")


#: The [[structure]] keys that take a name; the others take numbers.
_NAMED_KEYS = ("kind", "theory", "supports")


def _require_structure_value(path: str, key: str, value) -> None:
    """``ValueError`` naming ``path`` unless ``value`` has the type of ``key`` (a string for
    :data:`_NAMED_KEYS`, a number otherwise, a point of numbers for ``impact_fraction``).
    """
    def number(item):
        return isinstance(item, (int, float)) and not isinstance(item, bool)

    if key in _NAMED_KEYS:
        if not isinstance(value, str):
            raise ValueError(f"{path} = {value!r} is invalid: give a name (a string)")
    elif key == "impact_fraction":
        if not all(number(item) for item in value):
            raise ValueError(f"{path} = {list(value)!r} is invalid: give fractions of the span in (0, 1)")
    elif not number(value):
        raise ValueError(f"{path} = {value!r} is invalid: give a number")


def _laminated(structure: MapStructure, key: str, value, where: str) -> MapStructure:
    """``structure`` carrying the stiffness ratios of the laminate ``value`` given as ``key``
    (``layup`` or ``plies``, read as a case file reads them) at the structure's slenderness:
    the plate of span ``slenderness`` × the plies' thickness and the structure's aspect ratio,
    edges, theory and impact point (:meth:`~impactmaps.targets.base.Target.map_structure`).
    """
    if structure.kind != "plate":
        raise ValueError(f"{where}.{key} is invalid for a {structure.kind}: a laminate is given for kind = 'plate'")
    built = laminate({key: value}, where)
    span = structure.slenderness * float(built.thickness)
    width = span * structure.aspect_ratio
    point = (structure.impact_fraction[0] * span, structure.impact_fraction[1] * width)
    try:
        plate = Plate.from_laminate(span, width, built, theory=structure.theory, edges=structure.supports,
                                    impact_point=point)
    except ValueError as error:
        raise ValueError(f"{where}.{key}: {error}") from None
    found = plate.map_structure()
    if found is None:
        raise ValueError(f"{where}.{key}: no map structure describes this laminate: {plate.map_structure_refusal()}")
    if found.stiffness is None:  # a laminate isotropic in bending (one isotropic ply): its Poisson ratio
        return replace(structure, poisson_ratio=float(found.poisson_ratio or structure.poisson_ratio))
    return replace(structure, stiffness=found.stiffness)


def _structures(table, index):
    where = f"[[structure]] #{index + 1}"
    if not isinstance(table, dict):
        raise ValueError(f"{where} = {table!r} is invalid: give a table of MapStructure keys")
    unknown = set(table) - _STRUCTURE_KEYS
    if unknown:
        raise ValueError(f"unknown key(s) {sorted(unknown)} in {where}: allowed keys are {sorted(_STRUCTURE_KEYS)}")
    given = [key for key in _LAMINATE_KEYS if key in table]
    if len(given) > 1:
        raise ValueError(f"{where}.layup and {where}.plies are exclusive: give the laminate once")
    for key in ("stiffness", "poisson_ratio"):
        if given and key in table:
            raise ValueError(f"{where}.{key} = {table[key]!r} is set by the laminate {where}.{given[0]}: remove it")
    swept = {k: (v if isinstance(v, list) else [v]) for k, v in table.items() if k not in ("impact_fraction", "plies")}
    if "plies" in table:  # a list of ply tables is one laminate
        swept["plies"] = [table["plies"]]
    if "impact_fraction" in table:
        swept["impact_fraction"] = _impact_fractions(table["impact_fraction"], where)
    out = []
    for combination in itertools.product(*swept.values()):
        values = dict(zip(swept, combination))
        layers = {key: values.pop(key) for key in given}
        for key, value in values.items():
            _require_structure_value(f"{where}.{key}", key, value)
        kind = values.get("kind", "plate")
        if kind not in KIND_DEFAULTS:
            raise ValueError(f"{where}.kind = {kind!r} is invalid: choose 'beam' or 'plate'")
        if kind == "beam" and len(values.get("impact_fraction", (0.5,))) != 1:
            raise ValueError(f"{where}.impact_fraction = {table['impact_fraction']!r} is invalid for a beam: give "
                             "one fraction x0/L, or a list of them as [[0.3], [0.9]]")
        values = KIND_DEFAULTS[kind] | values
        try:
            structure = MapStructure(**values)
        except (TypeError, ValueError) as error:
            raise ValueError(f"{where}: {error}") from None
        for key, value in layers.items():
            structure = _laminated(structure, key, value, where)
        try:
            structure.build()  # supports and theory are checked by the target: fail before any output
        except (TypeError, ValueError) as error:
            raise ValueError(f"{where}: {error}") from None
        out.append(structure)
    return out


@dataclass(frozen=True)
class SweepConfig:
    """A sweep file, parsed and checked (:func:`load_sweep_config`): its ``output`` directory,
    ``law`` and checked ``grid``; it unpacks as ``structures, zetas, lambdas, settings,
    output, law, axes``."""

    output: Path
    law: str
    grid: SweepGrid

    @property
    def structures(self) -> list:
        """The structures swept."""
        return self.grid.structures

    @property
    def zetas(self) -> np.ndarray:
        """The ζ grid [-]."""
        return self.grid.axes["zeta"]

    @property
    def lambdas(self) -> np.ndarray:
        """The λ grid [-]."""
        return self.grid.axes["lambda_"]

    @property
    def settings(self) -> ModalSettings:
        """The solver settings."""
        return self.grid.settings

    @property
    def axes(self) -> dict:
        """The grids of the law's other axes (name → values [-])."""
        return {name: values for name, values in self.grid.axes.items() if name not in ("zeta", "lambda_")}

    def __iter__(self):
        return iter((self.structures, self.zetas, self.lambdas, self.settings, self.output, self.law, self.axes))


def load_sweep_config(path) -> SweepConfig:
    """Parse the sweep TOML file at ``path`` (format: docs/sweeps.rst) into a
    :class:`SweepConfig`: ``structures``, ``zetas``, ``lambdas``, ``settings``, ``output``,
    ``law`` and ``axes`` (the law's other grids).

    Raises
    ------
    ValueError
        A missing file, invalid TOML, an unknown key or an invalid value, naming the key.
    """
    path, text = read_text_input("sweep file", path)
    try:
        config = tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise ValueError(f"{path} is not valid TOML: {error}") from None
    unknown = set(config) - _TOP_KEYS
    if unknown:
        raise ValueError(f"unknown key(s) {sorted(unknown)} in {path}: allowed keys are {sorted(_TOP_KEYS)}")
    grid = config.get("grid", {})
    if not isinstance(grid, dict) or "zeta" not in grid or "lambda" not in grid:
        raise ValueError(f"{path}: [grid] needs 'zeta' and 'lambda'")
    law = config.get("law", "linear")
    if not isinstance(law, str) or law not in available_map_families():
        raise ValueError(f"law = {law!r} is invalid: choose one of {', '.join(available_map_families())}")
    family = map_family(law)
    zetas = _grid(family, "zeta", grid["zeta"])
    lambdas = _grid(family, "lambda_", grid["lambda"])
    solver = config.get("solver", {})
    if not isinstance(solver, dict):
        raise ValueError(f"solver = {solver!r} is invalid: give a [solver] table")
    unknown = set(solver) - _SOLVER_KEYS
    if unknown:
        raise ValueError(f"unknown key(s) {sorted(unknown)} in [solver]: allowed keys are {sorted(_SOLVER_KEYS)}")
    try:
        settings = ModalSettings(**solver)
    except (TypeError, ValueError) as error:
        raise ValueError(f"[solver]: {error}") from None
    tables = config.get("structure", [])
    if not isinstance(tables, list):
        tables = [tables]
    structures = [s for index, table in enumerate(tables) for s in _structures(table, index)]
    if not structures:
        raise ValueError(f"{path}: give at least one [[structure]] table")
    output = config.get("output", path.stem + "-output")
    if not isinstance(output, str) or not output or "\x00" in output \
            or any(len(part.encode()) > 255 for part in Path(output).parts):
        raise ValueError(f"output = {output!r} is invalid: give a directory name (no NUL character, each part at "
                         "most 255 bytes)")
    extra = [axis.name for axis in map_family(law).extra_axes]
    unknown = set(grid) - {"zeta", "lambda", *extra}
    if unknown:
        raise ValueError(f"unknown key(s) {sorted(unknown)} in [grid] of the {law} law: allowed keys are "
                         f"{sorted({'zeta', 'lambda', *extra})}")
    if not set(extra) <= set(grid):
        raise ValueError(f"{path}: [grid] of the {law} law needs {', '.join(repr(n) for n in ['zeta', 'lambda', *extra])}")
    axes = {name: _grid(family, name, grid[name]) for name in extra}
    checked = sweep_grid(structures, family, axes | {"lambda_": lambdas, "zeta": zetas}, settings)  # and its size
    return SweepConfig(path.parent / output, law, checked)


def run_sweep_config(config, *, progress: bool = True, overwrite: bool = False, max_workers: int | None = None,
                     executor=None) -> dict:
    """Run the sweep of a TOML file (``config``: a :class:`SweepConfig` or its path); write
    NetCDF and tidy CSV into its output directory and return ``{"netcdf": Path, "csv":
    Path}``. ``overwrite`` replaces a ``sweep.nc`` of another configuration;
    ``max_workers``, ``executor`` and ``progress`` as for
    :func:`~impactmaps.maps.compute.sweep.sweep`.
    """
    if not isinstance(config, SweepConfig):
        config = load_sweep_config(config)
    output = config.output
    if output.exists() and not output.is_dir():
        raise ValueError(f"output = {str(output)!r} is a file, not a directory")
    netcdf, csv = output / "sweep.nc", output / "sweep.csv"
    for path in (netcdf, csv):
        if path.is_dir():
            raise ValueError(f"output = {str(output)!r} holds a directory {path.name!r} where the sweep writes a file")
    dataset = run_sweep_grid(config.grid, path=netcdf, progress=progress, overwrite=overwrite,
                             max_workers=max_workers, executor=executor)
    with written_atomically(csv) as part:
        tidy_frame(dataset).to_csv(part, index=False)
    return {"netcdf": netcdf, "csv": csv}
