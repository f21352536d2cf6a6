"""What a slice-by-slice refinement of a shipped plastic map costs and buys.

Reads a plastic map's refinement built by ``data_build/build_refinements.py --law LAW``
(``--refinement PATH``, a ``.nc``), prints its size (points per β slice, MB as NetCDF and
packed) and compares lookups with and without it against direct solves
(:func:`~impactmaps.maps.compute.plastic_points.solve_plastic_points`) at N log-uniform random
points: anywhere in the map's (β, ζ, λ) box, and on its β slices (β a grid value, where
only the (λ, ζ) interpolation errs). Prints a Markdown table (``RESULTS_plastic_refinement.md``).

    python benchmarks/studies/plastic_refinement.py --refinement /tmp/out/beam-ss-euler-epp.nc [--points 200] [--seed 1]
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time
from pathlib import Path

import numpy as np

from impactmaps.maps.files.data_io import read_dataset, write_dataset
from impactmaps.maps.files.shipped import refinement_of
from impactmaps.maps.read.lookup import read_plastic
from impactmaps.maps.files.shipped import load_shipped_map
from impactmaps.maps.compute.plastic_points import solve_plastic_points
from impactmaps.maps.family.structures import structure_from_name


def random_points(dataset, count: int, seed: int, on_slices: bool):
    """(β, ζ, λ) log-uniform in the map's box; with ``on_slices`` β is one of the map's grid values."""
    rng = np.random.default_rng(seed)
    axes = {}
    for axis in ("beta", "zeta", "lambda_"):
        grid = dataset[axis].values
        axes[axis] = np.exp(rng.uniform(np.log(grid.min()), np.log(grid.max()), count))
    if on_slices:
        axes["beta"] = rng.choice(dataset["beta"].values, count)
    return axes["beta"], axes["zeta"], axes["lambda_"]


def compare(dataset, refinement, law: str, numbers, rows) -> dict:
    """Errors and bands of F̄max with and without the refinement, at the points read by both."""
    direct = np.array([row["fmax_normalised"] for row in rows])
    direct_error = np.array([row["fmax_error"] for row in rows])
    out = {}
    for label, used in (("grid", None), ("refined", refinement)):
        values, bands = np.full(direct.size, np.nan), np.full(direct.size, np.nan)
        for k, point in enumerate(zip(*numbers)):
            try:
                found = read_plastic(dataset, law, point, name="map", where="map", refinement=used)
            except ValueError:
                continue  # refused: next to an unresolved point
            values[k], bands[k] = found.fmax_normalised, found.fmax_error
        out[label] = (values, bands)
    answered = np.isfinite(out["grid"][0]) & np.isfinite(direct)
    result = {"answered": int(answered.sum())}
    for label, (values, bands) in out.items():
        error = np.abs(values - direct)[answered]
        band = bands[answered]
        result[label] = {"median": np.median(error), "p95": np.percentile(error, 95), "max": error.max(),
                         "over_1e-3": np.mean(error > 1e-3), "covered": int(np.sum(error <= band + direct_error[answered])),
                         "median_band": np.median(band), "band_over_1e-3": np.mean(band > 1e-3)}
    return result


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--refinement", type=Path, required=True)
    parser.add_argument("--points", type=int, default=200)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args(argv)
    stored = read_dataset(args.refinement)
    name = args.refinement.stem
    law = name.rsplit("-", 1)[1]
    structure_name = name.rsplit("-", 1)[0]
    structure, theory = {"beam-ss-euler": ("beam", "euler"), "beam-ss-timoshenko-s20": ("beam", "timoshenko"),
                         "plate-ssss-kirchhoff": ("plate", "kirchhoff")}[structure_name]
    dataset = load_shipped_map(structure, theory, law)
    refinement = refinement_of(stored, dataset, name)
    with tempfile.TemporaryDirectory() as folder:
        packed = Path(folder) / f"{name}.npz"
        write_dataset(stored.drop_vars("surplus"), packed)
        megabytes = (os.path.getsize(args.refinement) / 1e6, os.path.getsize(packed) / 1e6)
    print(f"# {name}: {refinement.size} points, per β slice "
          f"{[part.codes.size for part in refinement.slices]}; {megabytes[0]:.2f} MB NetCDF, "
          f"{megabytes[1]:.2f} MB packed (.npz, no surplus); build {stored.attrs.get('build_seconds')} s wall, "
          f"max_points {stored.attrs.get('max_points')} per slice; load average {os.getloadavg()}")
    print("| points | answered | lookup | median err | 95th pct | max | err > 1e-3 | band covers | median band | "
          "band > 1e-3 |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for on_slices in (False, True):
        numbers = random_points(dataset, args.points, args.seed, on_slices)
        start = time.process_time()
        rows = solve_plastic_points(structure_from_name(structure_name), law, list(zip(*numbers)))
        seconds = time.process_time() - start
        result = compare(dataset, refinement, law, numbers, rows)
        for label in ("grid", "refined"):
            r = result[label]
            print(f"| {'β on slices' if on_slices else 'anywhere'} ({seconds:.0f} CPU-s) | {result['answered']} | "
                  f"{label} | {r['median']:.2e} | {r['p95']:.2e} | {r['max']:.2e} | {r['over_1e-3']:.1%} | "
                  f"{r['covered']}/{result['answered']} | {r['median_band']:.2e} | {r['band_over_1e-3']:.1%} |")


if __name__ == "__main__":
    main()
