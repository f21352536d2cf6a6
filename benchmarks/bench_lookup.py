"""What a lookup costs, with and without the maps' refinements.

For each shipped linear map: the first lookup in a fresh process (it loads the map and its
refinement), a warm single lookup, and the interpolation with its band of 10 000 random
(ζ, λ) at once (:func:`impactmaps.maps.refinement.interpolate`, the part of a lookup the
refinement changes; the regime classification of a lookup is the same either way), on
the grid alone and refined.

    python benchmarks/bench_lookup.py
"""

from __future__ import annotations

import subprocess
import sys
import time
import warnings

import numpy as np

from impactmaps.maps.lookup import (SHIPPED_MAPS, interpolation_error, load_shipped_map,
                                    load_shipped_refinement, lookup)
from impactmaps.maps.reader import _grid_position
from impactmaps.maps.refinement import Refinement, interpolate

FIRST = ("import time, warnings; warnings.simplefilter('ignore'); t = time.perf_counter(); "
         "from impactmaps.maps.lookup import lookup; lookup(1.0, 0.1, structure={!r}, theory={!r}); "
         "print(time.perf_counter() - t)")


def main() -> None:
    warnings.simplefilter("ignore")  # the Mindlin map's point-load warning, once per lookup
    rng = np.random.default_rng(0)
    zetas, lambdas = 10 ** rng.uniform(-3, 3, 10_000), 10 ** rng.uniform(-3, 3, 10_000)
    print("| map | refinement points | first lookup, fresh process [s] | warm single lookup [ms] "
          "| 10 000 interpolations, grid alone [ms] | refined [ms] |")
    print("|---|---|---|---|---|---|")
    for (structure, theory), name in SHIPPED_MAPS.items():
        first = float(subprocess.run([sys.executable, "-c", FIRST.format(structure, theory)], check=True,
                                     capture_output=True, text=True).stdout)
        dataset = load_shipped_map(structure, theory)
        refinement = load_shipped_refinement(structure, theory)
        lookup(1.0, 0.1, structure=structure, theory=theory)
        start = time.perf_counter()
        for _ in range(20):
            lookup(1.0, 0.1, structure=structure, theory=theory)
        single = (time.perf_counter() - start) / 20 * 1e3
        base = {key: dataset[key].isel(structure=0).values for key in ("fmax_normalised", "fmax_error", "status")}
        estimate = interpolation_error(base["fmax_normalised"])
        rows = _grid_position(np.log(dataset["lambda_"].values), np.log(np.clip(lambdas, 1e-3, 1e3)))
        cols = _grid_position(np.log(dataset["zeta"].values), np.log(np.clip(zetas, 1e-3, 1e3)))
        times = []
        for reading in (Refinement.empty(base["fmax_normalised"].shape), refinement):
            start = time.perf_counter()
            interpolate(reading, base, estimate, rows, cols)
            times.append((time.perf_counter() - start) * 1e3)
        print(f"| {name} | {refinement.codes.size} | {first:.2f} | {single:.1f} | {times[0]:.1f} | {times[1]:.1f} |")


if __name__ == "__main__":
    main()
