"""Build the maps shipped in impactmaps/maps/data/ (the design-rule lookup tables).

Simply supported, impact at the centre: SS Euler and Timoshenko beams (L/h = 20), SS
square Kirchhoff and Mindlin plates (a/h = 20). Grid: ζ from 0.005 to 100 at 20 points
per decade, λ from 0.05 to 20 at 10 points per decade; default solver settings.
Resumable: re-running continues an interrupted build.

    python validation/build_default_maps.py [--quiet]
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np
import xarray as xr

from impactmaps.maps.lookup import SHIPPED_MAPS
from impactmaps.maps.store import save_atomic
from impactmaps.maps.structures import DEFAULT_STRUCTURES
from impactmaps.maps.sweep import sweep

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "impactmaps" / "maps" / "data"
WORK = ROOT / "validation" / "work"
ZETAS = np.geomspace(0.005, 100.0, 87)  # 20 per decade
LAMBDAS = np.geomspace(0.05, 20.0, 27)  # 10 per decade


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quiet", action="store_true")
    parser.add_argument("--only", nargs="*", default=None, help="build only these map names")
    args = parser.parse_args()
    DATA.mkdir(parents=True, exist_ok=True)
    wanted = set(args.only or SHIPPED_MAPS.values())
    for structure in DEFAULT_STRUCTURES:
        if structure.name not in wanted:
            continue
        start = time.perf_counter()
        dataset = sweep([structure], ZETAS, LAMBDAS, path=WORK / f"{structure.name}.sweep.nc",
                        progress=not args.quiet)
        elapsed = time.perf_counter() - start
        # log-times for interpolation of the regime criteria
        dataset["log_peak_time"] = np.log(dataset["peak_time_normalised"])
        dataset["log_reflection_time"] = np.log(dataset["reflection_time_normalised"])
        dataset.attrs["build_seconds"] = round(elapsed, 1)
        shipped = dataset.drop_vars("regime")
        save_atomic(shipped, DATA / f"{structure.name}.nc")
        print(f"{structure.name}: {dataset['done'].sum().item()} points in {elapsed:.1f} s")


if __name__ == "__main__":
    main()
