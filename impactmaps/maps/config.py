"""``impactmaps sweep CONFIG.toml``: sweeps described in a TOML file.

Example::

    output = "my-sweep"                 # directory (relative to the config file)
    [grid]
    zeta = { min = 0.01, max = 10, count = 30 }      # or an explicit list
    lambda = [0.1, 1.0, 10.0]
    [solver]                            # optional ModalSettings fields
    cutoff_ratio = 40
    [[structure]]                       # one table per structure (fields of MapStructure)
    kind = "plate"
    theory = "mindlin"
    supports = "SSSS"
    aspect_ratio = [1.0, 2.0]           # a list sweeps that parameter too
    slenderness = 20
"""

from __future__ import annotations

import itertools
import tomllib
from dataclasses import fields
from pathlib import Path

import numpy as np

from ..solvers.modal import ModalSettings
from .structures import MapStructure

__all__ = ["load_sweep_config", "run_sweep_config"]

_TOP_KEYS = {"output", "grid", "solver", "structure"}
_STRUCTURE_KEYS = {f.name for f in fields(MapStructure)}
_SOLVER_KEYS = {f.name for f in fields(ModalSettings)}


def _grid(name, value):
    if isinstance(value, dict):
        unknown = set(value) - {"min", "max", "count"}
        if unknown or not {"min", "max", "count"} <= set(value):
            raise ValueError(f"grid.{name} = {value!r} is invalid: give min, max and count, or a list of values")
        return np.geomspace(float(value["min"]), float(value["max"]), int(value["count"]))
    if isinstance(value, (list, tuple)) and value:
        return np.asarray(value, dtype=float)
    raise ValueError(f"grid.{name} = {value!r} is invalid: give min, max and count, or a list of values")


def load_sweep_config(path):
    """Parse a sweep TOML file into (structures, zetas, lambdas, settings, output dir)."""
    path = Path(path)
    with open(path, "rb") as handle:
        config = tomllib.load(handle)
    unknown = set(config) - _TOP_KEYS
    if unknown:
        raise ValueError(f"unknown key(s) {sorted(unknown)} in {path}: allowed keys are {sorted(_TOP_KEYS)}")
    grid = config.get("grid", {})
    if "zeta" not in grid or "lambda" not in grid:
        raise ValueError(f"{path}: [grid] needs 'zeta' and 'lambda'")
    zetas, lambdas = _grid("zeta", grid["zeta"]), _grid("lambda", grid["lambda"])
    solver = config.get("solver", {})
    unknown = set(solver) - _SOLVER_KEYS
    if unknown:
        raise ValueError(f"unknown key(s) {sorted(unknown)} in [solver]: allowed keys are {sorted(_SOLVER_KEYS)}")
    settings = ModalSettings(**solver)
    structures = []
    for index, table in enumerate(config.get("structure", [])):
        unknown = set(table) - _STRUCTURE_KEYS
        if unknown:
            raise ValueError(
                f"unknown key(s) {sorted(unknown)} in [[structure]] #{index + 1}: allowed keys are "
                f"{sorted(_STRUCTURE_KEYS)}"
            )
        swept = {k: (v if isinstance(v, list) and k != "impact_fraction" else [v]) for k, v in table.items()}
        if "impact_fraction" in table and table["impact_fraction"] and isinstance(table["impact_fraction"][0], list):
            swept["impact_fraction"] = [tuple(v) for v in table["impact_fraction"]]
        keys = list(swept)
        for combination in itertools.product(*(swept[k] for k in keys)):
            values = dict(zip(keys, combination))
            if "impact_fraction" not in values:
                values["impact_fraction"] = (0.5,) if values.get("kind", "plate") == "beam" else (0.5, 0.5)
            structures.append(MapStructure(**values))
    if not structures:
        raise ValueError(f"{path}: give at least one [[structure]] table")
    output = path.parent / config.get("output", path.stem + "-output")
    return structures, zetas, lambdas, settings, output


def run_sweep_config(path, *, progress: bool = True) -> dict:
    """Run the sweep of a TOML file; write NetCDF and tidy CSV into its output directory."""
    from .chart import tidy_frame
    from .sweep import sweep

    structures, zetas, lambdas, settings, output = load_sweep_config(path)
    output.mkdir(parents=True, exist_ok=True)
    netcdf = output / "sweep.nc"
    dataset = sweep(structures, zetas, lambdas, settings=settings, path=netcdf, progress=progress)
    csv = output / "sweep.csv"
    tidy_frame(dataset).to_csv(csv, index=False)
    return {"netcdf": netcdf, "csv": csv}
