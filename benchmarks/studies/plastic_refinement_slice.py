"""One β slice of beam-ss-euler-epp refined without a cap, against the capped refinement and the grid.

Reads ``/tmp/prefine_out/beam-ss-euler-epp.nc`` (``data_build/build_refinements.py --law epp
--only beam-ss-euler --max-points 2500 --out-dir /tmp/prefine_out``) and
``/tmp/prefine_full/beam-ss-euler-epp.nc`` (the slice β = 31.6 alone, uncapped: ``build(...,
cells=(slice(3, 4), slice(None), slice(None)))`` of ``data_build/build_refinements.py``) and
compares lookups at 200 random (ζ, λ) at that β with direct solves; prints Markdown rows
(``RESULTS_plastic_refinement.md``).

    python benchmarks/studies/plastic_refinement_slice.py
"""

from __future__ import annotations

import os
import time

import numpy as np

from impactmaps.maps.files.data_io import read_dataset
from impactmaps.maps.files.shipped import refinement_of
from impactmaps.maps.read.lookup import read_plastic
from impactmaps.maps.files.shipped import load_shipped_map
from impactmaps.maps.compute.plastic_points import solve_plastic_points
from impactmaps.maps.family.slice_refinement import SlicedRefinement
from impactmaps.maps.family.structures import structure_from_name

SLICE, POINTS = 3, 200


def main() -> None:
    dataset = load_shipped_map("beam", "euler", "epp")
    capped = refinement_of(read_dataset("/tmp/prefine_out/beam-ss-euler-epp.nc"), dataset)
    alone = SlicedRefinement.from_dataset(read_dataset("/tmp/prefine_full/beam-ss-euler-epp.nc"))
    full = SlicedRefinement(capped.extra_shape, tuple(alone.slices[0] if k == SLICE else part
                                                      for k, part in enumerate(capped.slices)))
    beta = float(dataset["beta"].values[SLICE])
    rng = np.random.default_rng(7)
    zetas = np.exp(rng.uniform(np.log(1e-3), np.log(10.0), POINTS))
    lambdas = np.exp(rng.uniform(np.log(1e-3), np.log(31.62), POINTS))
    start = time.process_time()
    rows = solve_plastic_points(structure_from_name("beam-ss-euler"), "epp",
                                [(beta, zeta, lam) for zeta, lam in zip(zetas, lambdas)])
    print(f"β = {beta:g}: {POINTS} direct solves {time.process_time() - start:.1f} CPU-s; load {os.getloadavg()}")
    direct = np.array([row["fmax_normalised"] for row in rows])
    direct_error = np.array([row["fmax_error"] for row in rows])
    print("| lookup | answered | median err | 95th pct | max | err > 1e-3 | band covers | median band | band > 1e-3 |")
    print("|---|---|---|---|---|---|---|---|---|")
    for label, refinement in (("grid", None), ("capped 2500 a slice", capped), ("slice uncapped", full)):
        values, bands = np.full(POINTS, np.nan), np.full(POINTS, np.nan)
        for k in range(POINTS):
            try:
                found = read_plastic(dataset, "epp", (beta, zetas[k], lambdas[k]), name="map", where="map",
                                     refinement=refinement)
            except ValueError:
                continue
            values[k], bands[k] = found.fmax_normalised, found.fmax_error
        kept = np.isfinite(values) & np.isfinite(direct)
        error, band = np.abs(values - direct)[kept], bands[kept]
        print(f"| {label} | {kept.sum()} | {np.median(error):.2e} | {np.percentile(error, 95):.2e} | "
              f"{error.max():.2e} | {np.mean(error > 1e-3):.1%} | {np.sum(error <= band + direct_error[kept])}/"
              f"{kept.sum()} | {np.median(band):.2e} | {np.mean(band > 1e-3):.1%} |")


if __name__ == "__main__":
    main()
