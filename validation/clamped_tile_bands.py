"""Bands of `lookup --case` on plates with clamped or free edges (issue 39 item 4).

For random physical cases on isotropic plates whose edges are not all simply supported
(CCCC, CCSS, CSCS, SCSC, CFCF, CCCF, CCFF; Kirchhoff or Mindlin; a steel ball of radius 5–20 mm at
0.5–6 m/s; the Hertz law, and the linear law on one Kirchhoff case in three), each answered
from its on-demand tile (a refined cell, :func:`impactmaps.maps.compute.tiles.refined_cell`),
two checks of the band:

* the case: ``lookup --case`` against ``simulate`` of the same case (and the band in % of
  the answer);
* the cell: ``--inside`` random (ζ, λ) inside the tile's cell, each solved as a map point
  (the tile's own structure, settings and accuracy control) against the tile read there —
  the interpolation and its band, free of ``simulate``'s own cut-off.

A case whose tile holds no value next to it (a point beyond the theory's range or the mode
cap) is counted as refused. Prints a Markdown table and a summary line; writes the rows to
``--csv`` when given.

    python validation/clamped_tile_bands.py [--cases 12] [--inside 4] [--seed 39] [--csv FILE]
    python validation/clamped_tile_bands.py --inside 8 CASE.toml …     # given cases instead of random ones
    python validation/clamped_tile_bands.py --smoke                    # one case, one cell point (seconds)
"""

from __future__ import annotations

import tempfile
from pathlib import Path
import warnings

import numpy as np
from _script_options import parse

from impactmaps import lookup
from impactmaps.cases import load_case, parse_case, run_case
from impactmaps.cases.case_answer import case_map_law
from impactmaps.cases.on_demand import _tile_settings, case_structure
from impactmaps.maps.compute import tiles
from impactmaps.maps.compute.points import solve_map_points
from impactmaps.maps.read.lookup import read_map

#: The seed of --smoke: its first random case is a CSCS Kirchhoff plate with the Hertz law (answered in seconds).
SMOKE_SEED = 24
EDGES = ("CCCC", "CCSS", "CSCS", "SCSC", "CFCF", "CCCF", "CCFF")


def random_case(rng):
    """A random case on a plate with a clamped or free edge (module docstring)."""
    def uniform(low, high):
        return float(rng.uniform(low, high))

    theory = str(rng.choice(["kirchhoff", "mindlin"]))
    law = "linear" if theory == "kirchhoff" and uniform(0, 1) < 1 / 3 else "hertz"
    side, aspect = uniform(0.1, 0.4), uniform(0.5, 1.5)
    slenderness = uniform(20, 80) if theory == "mindlin" else uniform(40, 150)
    metal = str(rng.choice(["structural-steel", "aluminium-6061-t6"]))
    text = (f'[impactor]\nradius = {10 ** uniform(np.log10(0.005), np.log10(0.02))!r}\n'
            f'material = "structural-steel"\nvelocity = {10 ** uniform(np.log10(0.5), np.log10(6.0))!r}\n'
            f'[target]\ntype = "plate"\nlength_x = {side!r}\nlength_y = {side * aspect!r}\n'
            f'thickness = {side / slenderness!r}\nmaterial = "{metal}"\ntheory = "{theory}"\n'
            f'edges = "{rng.choice(EDGES)}"\n[contact]\nlaw = "{law}"\n')
    return parse_case(text)


def inside_cell(case, cache_dir, count: int, rng) -> list[tuple[float, float, float]]:
    """(|tile − point| [-], band [-], point F̄max [-]) at ``count`` random (ζ, λ) in the cell of
    the case's tile, each solved as a map point of the tile's structure."""
    law = case_map_law(case)
    structure, patch = case_structure(case, law)
    answer = lookup(case=case, cache_dir=cache_dir)
    key = tiles.tile_for(structure, law, patch, answer["zeta"], answer["lambda"], _tile_settings(case, patch),
                         cache_dir=cache_dir)
    dataset, _ = tiles.cached_tile(key, cache_dir)
    zetas, lambdas = key.axes
    fractions = rng.random((count, 2))
    points = [(float(zetas[0] * (zetas[-1] / zetas[0]) ** a), float(lambdas[0] * (lambdas[-1] / lambdas[0]) ** b))
              for a, b in fractions]
    family = tiles._family(key)
    table = tiles._table(key, points) if key.structure.build().bounded_modes and family.uses_table() else None
    rows = solve_map_points(family, key.structure, points, key.settings, table, key.control)
    out = []
    for (zeta, lam), row in zip(points, rows):
        found = read_map(dataset, zeta, lam, kind=structure.kind, theory=structure.theory, name=key.name, law=law,
                         refinement=tiles.tile_refinement(dataset))
        out.append((abs(found.fmax_normalised - row["fmax_normalised"]), found.fmax_error, row["fmax_normalised"]))
    return out


def main(argv=None) -> None:
    def arguments(parser):
        parser.add_argument("--cases", type=int, default=12)
        parser.add_argument("--inside", type=int, default=4)
        parser.add_argument("--seed", type=int, default=39)
        parser.add_argument("--csv")
        parser.add_argument("case_files", nargs="*", help="case files (default: --cases random cases)")

    options = parse(__doc__.splitlines()[0], argv, default_out=Path(__file__).resolve().parent,
                    add_arguments=arguments)
    if options.smoke:  # one random case (a Kirchhoff plate), one point inside its cell, the CSV in --out-dir
        options.cases, options.inside, options.seed = 1, 1, SMOKE_SEED
        options.csv = options.csv or str(options.out_dir / "clamped_tile_bands.csv")
    rng = np.random.default_rng(options.seed)
    lines, rows = [], []
    answered = refused = cell_points = cell_inside = case_inside = 0
    largest_band, largest_ratio = 0.0, 0.0
    with tempfile.TemporaryDirectory() as cache, warnings.catch_warnings():
        warnings.simplefilter("ignore")
        cases = ([load_case(path) for path in options.case_files] if options.case_files
                 else (random_case(rng) for _ in range(options.cases)))
        for index, case in enumerate(cases):
            target = case.target
            label = (f"{target.edges} {target.theory} {target.length_x * 1e3:.0f}×{target.length_y * 1e3:.0f}×"
                     f"{target.thickness * 1e3:.2f} mm, {case.law_name}, V0 {case.velocity:.2f} m/s")
            try:
                found = lookup(case=case, cache_dir=cache)
            except ValueError as error:
                refused += 1
                lines.append(f"| {index} | {label} | refused: {str(error).split(', and ')[-1][:90]}… | | | |")
                continue
            _, summary = run_case(case)
            force, band, direct = found["peak_force_N"], found["peak_force_error_N"], summary["peak_force_N"]
            inside = abs(force - direct) <= band
            cell = inside_cell(case, cache, options.inside, rng)
            answered += 1
            case_inside += inside
            cell_points += len(cell)
            cell_inside += sum(error <= bound for error, bound, _ in cell)
            largest_band = max(largest_band, band / force)
            largest_ratio = max([largest_ratio, *(error / bound for error, bound, _ in cell)])
            lines.append(f"| {index} | {label} | {force:.1f} ± {band:.1f} N ({100 * band / force:.2f} %, "
                         f"{found['status']}) | {direct:.1f} N, {summary['impacts']} impacts | "
                         f"{'yes' if inside else 'NO'} | {sum(e <= b for e, b, _ in cell)}/{len(cell)} "
                         f"(largest error/band {max(e / b for e, b, _ in cell):.2f}) |")
            rows.append({"case": index, "label": label, "lookup_N": force, "band_N": band, "simulate_N": direct,
                         "impacts": summary["impacts"], "status": found["status"],
                         "cell_errors": ";".join(f"{e:.3e}" for e, _, _ in cell),
                         "cell_bands": ";".join(f"{b:.3e}" for _, b, _ in cell)})
    print("| # | case | lookup --case | simulate | inside | cell points inside their band |")
    print("|---|---|---|---|---|---|")
    print("\n".join(lines))
    print(f"\n{answered} answered, {refused} refused (a tile point next to the case unresolved); simulate inside "
          f"the band: {case_inside}/{answered}; random cell points inside their band: {cell_inside}/{cell_points} "
          f"(largest error/band {largest_ratio:.2f}); widest band {100 * largest_band:.2f} % of the answer")
    if options.csv:
        import pandas as pd

        pd.DataFrame(rows).to_csv(options.csv, index=False)


if __name__ == "__main__":
    main()
