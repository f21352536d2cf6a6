"""Build the refinements of the shipped linear maps (impactmaps/maps/data/refinements/).

Each dense map (``build_default_maps.DENSE_MAPS``) is refined where linear interpolation
between its points errs by more than the tolerance (1e-3, the points' own): cells are
split into four, down to 8× finer per axis, and the new points are solved exactly as the
map's own (:func:`impactmaps.maps.compute.points.solve_map_points` of the map's family, default
settings and accuracy control; with ``--law hertz`` the Hertz maps ``NAME-hertz.nc``). See :mod:`impactmaps.maps.family.refinement`.
With ``--law yc``, ``stronge`` or ``epp`` the plastic maps (``PlasticFamily.shipped``) are
refined slice by slice: each β of the map's grid as a (λ, ζ) map, its new points solved at
that β (:mod:`impactmaps.maps.family.slice_refinement`; ``--max-points`` caps each slice).
Each round's new points are kept in ``validation/work/NAME.refine.npz`` as they are solved,
so an interrupted build resumes without recomputing them.

    python data_build/build_refinements.py [--quiet] [--only NAME …] [--max-points N] [--law hertz|yc|stronge|epp]
    python data_build/build_refinements.py --smoke    # a few cells of one map, into a temporary directory
"""

from __future__ import annotations

import os
import resource
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np
import xarray as xr

from impactmaps.maps.read.interpolator import interpolation_error
from impactmaps.maps.files.shipped import map_file_stem
from impactmaps.maps.read.interpolator import slice_estimates
from impactmaps.maps.family.refinement import MAX_LEVEL, refine
from impactmaps.maps.family.slice_refinement import refine_slices
from impactmaps.maps.files.data_io import read_dataset
from impactmaps.maps.files.store import save_atomic
from impactmaps.maps.family.structures import structure_from_name
from impactmaps.maps.compute.points import solve_map_points
from impactmaps.maps.family.builtin_families import PLASTIC_LAWS
from impactmaps.maps.family.map_family import map_family
from impactmaps.maps.compute.workers import init_worker
from impactmaps.solvers.modal_settings import ModalSettings

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "validation"))  # _script_options
from _script_options import parse  # noqa: E402
from build_default_maps import DENSE_MAPS  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "impactmaps" / "maps" / "data"
WORK = ROOT / "validation" / "work"
#: Points solved per task (one structure; the worker's basis table is reused).
CHUNK = 40
#: The base map's variables the refinement reads.
BASE_VARIABLES = ("fmax_normalised", "fmax_error", "status", "log_peak_time", "log_reflection_time")
#: Row values kept for a resumed build (what the refinement stores, before logs).
KEPT = ("fmax_normalised", "fmax_error", "status", "peak_time_normalised", "reflection_time_normalised")


def grid_coordinates(lambdas: np.ndarray, zetas: np.ndarray):
    """``coordinates(row, col) -> (zeta, lambda_)`` at fractional grid positions (log-linear)."""
    def along(grid, position):
        logs = np.log(grid)
        low = np.clip(np.floor(position).astype(int), 0, grid.size - 2)
        return np.exp(logs[low] + (position - low) * (logs[low + 1] - logs[low]))

    return lambda row, col: (along(zetas, np.asarray(col, float)), along(lambdas, np.asarray(row, float)))


class Solver:
    """Solve scattered points of one structure on a process pool, remembering every row
    (on disk, after each round) so that a resumed build recomputes none."""

    def __init__(self, structure, law: str, executor, checkpoint: Path | None):
        self.structure, self.law, self.executor, self.checkpoint = structure, law, executor, checkpoint
        self.known = {}
        if checkpoint is not None and checkpoint.exists():
            with np.load(checkpoint) as stored:
                arrays = {name: stored[name] for name in ("zeta", "lambda_", *KEPT)}
                extra = stored["extra"] if "extra" in stored else np.zeros((arrays["zeta"].size, 0))
            columns = [arrays[name].tolist() for name in KEPT]
            for k, key in enumerate(zip(*(column.tolist() for column in extra.T), arrays["zeta"].tolist(),
                                        arrays["lambda_"].tolist())):
                self.known[key] = {name: column[k] for name, column in zip(KEPT, columns)}

    def __call__(self, zetas, lambdas, extra=()) -> list[dict]:
        """The rows of the points (ζ, λ) at the extra axes' values ``extra`` (β of a plastic map)."""
        keys = [(*(float(value) for value in extra), float(z), float(lam)) for z, lam in zip(zetas, lambdas)]
        todo = [key for key in dict.fromkeys(keys) if key not in self.known]
        chunks = [todo[k:k + CHUNK] for k in range(0, len(todo), CHUNK)]
        arguments = ([self.structure] * len(chunks), [self.law] * len(chunks), chunks)
        solved = self.executor.map(_solve_chunk, *arguments) if self.executor else map(_solve_chunk, *arguments)
        for chunk, rows in zip(chunks, solved):
            for key, row in zip(chunk, rows):
                self.known[key] = {name: row.get(name, np.nan) for name in KEPT}
        self.save()
        return [self.known[key] for key in keys]

    def save(self) -> None:
        if self.checkpoint is None:
            return
        keys = list(self.known)
        arrays = {"zeta": np.array([k[-2] for k in keys]), "lambda_": np.array([k[-1] for k in keys]),
                  "extra": np.array([k[:-2] for k in keys], float).reshape(len(keys), -1)}
        arrays |= {name: np.array([self.known[k][name] for k in keys], float) for name in KEPT}
        partial = self.checkpoint.with_suffix(".partial.npz")
        np.savez(partial, **arrays)
        os.replace(partial, self.checkpoint)


def _solve_chunk(structure, law, points):
    return solve_map_points(map_family(law), structure, points, ModalSettings())  # points: (…extra, ζ, λ)


def build(structure_name: str, data: Path, out_dir: Path, work: Path | None, executor, *, law: str = "linear",
          max_points=None, quiet: bool = False, cells: tuple | None = None) -> xr.Dataset:
    """Refine the map ``data/NAME.nc`` of a structure and law and write ``out_dir/NAME.nc``;
    returns the refinement's Dataset."""
    name = map_file_stem(structure_name, law)
    dataset = read_dataset(next((p for p in (data / f"{name}.nc", data / f"{name}.npz") if p.exists()),
                                data / f"{name}.nc"))
    family = map_family(law)
    if cells is not None:  # smoke: a few cells of the map (λ slice, ζ slice; a plastic map's β slice first)
        dataset = dataset.isel(dict(zip(family.axis_names, cells)))
    coordinates = grid_coordinates(dataset["lambda_"].values, dataset["zeta"].values)
    solver = Solver(structure_from_name(structure_name), law, executor,
                    None if work is None else work / f"{name}.refine.npz")
    start = time.perf_counter()

    def progress(round_number, split, total):
        if not quiet:
            print(f"  {name}: round {round_number}: {split} cells split, {total} points "
                  f"({time.perf_counter() - start:.0f} s)", flush=True)

    cpu = time.process_time()
    if family.extra_axes:
        refinement = refine_sliced(dataset, family, coordinates, solver, max_points=max_points, progress=progress)
    else:
        base = {key: dataset[key].isel(structure=0).values for key in BASE_VARIABLES}
        estimate = interpolation_error(base["fmax_normalised"])
        refinement = refine(base, estimate, coordinates, solver, max_points=max_points, progress=progress)
    elapsed = time.perf_counter() - start
    added = refinement.size if family.extra_axes else refinement.codes.size
    stored = refinement.dataset({
        "title": f"impactmaps refinement of the map {name}",
        "base_fingerprint": dataset.attrs["fingerprint"],
        "tolerance": 1e-3,
        "max_points": -1 if max_points is None else int(max_points),
        "build_seconds": round(elapsed, 1),
    })
    out_dir.mkdir(parents=True, exist_ok=True)
    save_atomic(stored, out_dir / f"{name}.nc")
    print(f"{name}: {added} points added in {elapsed:.1f} s, {time.process_time() - cpu:.1f} CPU-s here "
          f"(deepest level {MAX_LEVEL})")
    return stored


def refine_sliced(dataset: xr.Dataset, family, coordinates, solver, **options):
    """The refinement of each (λ, ζ) slice of a map with extra axes (β), its points solved at the slice's β."""
    table = {key: dataset[key].isel(structure=0).values for key in ("fmax_normalised", "fmax_error", "status")}
    plane, _ = slice_estimates(table["fmax_normalised"], family)
    shape = table["fmax_normalised"].shape
    flat = {key: value.reshape(-1, *shape[-2:]) for key, value in table.items()}
    bases = [{key: value[k] for key, value in flat.items()} for k in range(flat["status"].shape[0])]
    extra_grids = [dataset[axis.name].values for axis in family.extra_axes]
    extra_values = [tuple(float(grid[i]) for grid, i in zip(extra_grids, index)) for index in np.ndindex(shape[:-2])]
    return refine_slices(bases, list(plane.reshape(-1, *shape[-2:])), coordinates, solver, extra_values,
                         extra_shape=shape[:-2], **options)


def main(argv=None) -> None:
    def add_arguments(parser):
        parser.add_argument("--quiet", action="store_true", help="no progress lines")
        parser.add_argument("--only", nargs="+", default=None, help="map names to refine")
        parser.add_argument("--max-points", type=int, default=None, help="cost cap of each map's refinement")
        parser.add_argument("--law", choices=("linear", "hertz", *PLASTIC_LAWS), default="linear",
                            help="the maps' contact law")

    args = parse(__doc__.splitlines()[0], argv, default_out=DATA / "refinements", add_arguments=add_arguments)
    plastic = args.law in PLASTIC_LAWS
    names = args.only or list(map_family(args.law).shipped.values() if plastic else DENSE_MAPS)
    if args.smoke:
        # 3 × 3 cells around the Euler beam's re-impact kink at ζ = 0.33, λ = 0.013; a plastic
        # map: 2 × 2 cells of its two largest β around ζ = 0.1, λ = 0.01
        cells = ((slice(-2, None), slice(5, 8), slice(12, 15)) if plastic else (slice(21, 25), slice(99, 103)))
        build(names[0], DATA, args.out_dir, None, None, law=args.law, max_points=20, quiet=True, cells=cells)
        return
    WORK.mkdir(parents=True, exist_ok=True)
    with ProcessPoolExecutor(max_workers=os.cpu_count(), initializer=init_worker, initargs=(False,)) as executor:
        for name in names:
            build(name, DATA, args.out_dir, WORK, executor, law=args.law, max_points=args.max_points,
                  quiet=args.quiet)
    workers = resource.getrusage(resource.RUSAGE_CHILDREN)
    print(f"worker processes: {workers.ru_utime + workers.ru_stime:.0f} CPU-s; load average {os.getloadavg()}")


if __name__ == "__main__":
    main()
