"""What the shipped refinements buy: lookups with and without them against direct simulation.

For each refined linear map (``data_build/build_refinements.py``), N log-uniform random
(ζ, λ) points over the whole map are simulated directly (the map's solver and settings,
:func:`impactmaps.maps.compute.linear_points.solve_points`) and read from the map twice: from its grid
alone (:func:`impactmaps.maps.read.lookup.read_map` without a refinement) and as ``lookup``
reads it (with the shipped refinement). Prints a Markdown table (docs/validation.rst, "What the refinements buy"):
per map, over the answered non-sensitive points, the share whose error exceeds 1e-3,
the share whose band does (status ``interpolated``), how many bands cover the error, and
the largest error; writes validation/refinement_error.csv, which
``tests/maps/test_refinement.py`` re-reads against the current maps.

    python validation/refinement_error.py [--points 1000] [--seed 5] [--out-dir DIR]
    python validation/refinement_error.py --smoke    # 4 points of one map (seconds)
"""

from __future__ import annotations

import warnings
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np
import pandas as pd

from impactmaps.maps.family.accuracy import STATUSES
from impactmaps.maps.read.lookup import read_map
from impactmaps.maps.files.shipped import SHIPPED_MAPS, load_shipped_map
from impactmaps import lookup
from impactmaps.maps.family.structures import structure_from_name
from impactmaps.maps.compute.linear_points import solve_points
from impactmaps.maps.compute.workers import init_worker
from impactmaps.solvers.modal_settings import ModalSettings

from _script_options import parse

HERE = Path(__file__).resolve().parent
CHUNK = 25


def _solve(name, points):
    return solve_points(structure_from_name(name), points, ModalSettings())


def read_both(structure: str, theory: str, zetas, lambdas) -> dict:
    """Lookups of the map's grid alone and of the map with its refinement (NaN where refused)."""
    dataset = load_shipped_map(structure, theory)
    out = {f"{kind}_{field}": [] for kind in ("grid", "refined") for field in ("lookup", "band", "status")}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the Mindlin map's point-load warning, once per lookup
        _read_points(structure, theory, dataset, zetas, lambdas, out)
    return out


def _read_points(structure, theory, dataset, zetas, lambdas, out) -> None:
    for zeta, lam in zip(zetas, lambdas):
        for kind in ("grid", "refined"):
            try:
                found = (read_map(dataset, zeta, lam, kind=structure, theory=theory, name="grid")
                         if kind == "grid" else lookup(zeta, lam, kind=structure, theory=theory))
                answer = (found.fmax_normalised, found.fmax_error, found.status)
            except ValueError:  # next to an unresolved point: refused
                answer = (np.nan, np.nan, "refused")
            for field, value in zip(("lookup", "band", "status"), answer):
                out[f"{kind}_{field}"].append(value)


def measure(structure: str, theory: str, points: int, seed: int, executor) -> pd.DataFrame:
    """Direct runs at random points of one map, and both lookups."""
    name = SHIPPED_MAPS[(structure, theory)]
    dataset = load_shipped_map(structure, theory)
    rng = np.random.default_rng(seed)
    zetas = np.exp(rng.uniform(*np.log([dataset["zeta"].min().item(), dataset["zeta"].max().item()]), points))
    lambdas = np.exp(rng.uniform(*np.log([dataset["lambda_"].min().item(), dataset["lambda_"].max().item()]),
                                 points))
    pairs = list(zip(zetas, lambdas))
    chunks = [pairs[k:k + CHUNK] for k in range(0, points, CHUNK)]
    solved = executor.map(_solve, [name] * len(chunks), chunks) if executor else map(_solve, [name] * len(chunks), chunks)
    rows = [row for chunk in solved for row in chunk]
    return pd.DataFrame({
        "map": name, "zeta": zetas, "lambda": lambdas,
        "direct": [r["fmax_normalised"] for r in rows], "direct_error": [r["fmax_error"] for r in rows],
        "direct_status": [STATUSES[r["status"]] for r in rows],
    } | read_both(structure, theory, zetas, lambdas))


def summary(table: pd.DataFrame) -> str:
    """The Markdown table of docs/validation.rst."""
    lines = ["| map | answered, non-sensitive | error > 1e-3: grid alone | refined | band > 1e-3 (`interpolated`): grid alone | refined | band covers the error: grid alone | refined | max error: grid alone | refined |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for name, group in table.groupby("map", sort=False):
        kept = group[(group["refined_status"].isin(["converged", "refined", "interpolated"]))
                     & (group["grid_status"] != "sensitive") & (group["direct_status"] != "sensitive")]
        cells = [name, str(len(kept))]
        stats = {}
        for kind in ("grid", "refined"):
            error = (kept[f"{kind}_lookup"] - kept["direct"]).abs()
            stats[kind] = (f"{100 * np.mean(error > 1e-3):.1f} %", f"{100 * np.mean(kept[f'{kind}_band'] > 1e-3):.1f} %",
                           f"{int(np.sum(error <= kept[f'{kind}_band'] + kept['direct_error']))}/{len(kept)}",
                           f"{error.max():.4f}")
        for k in range(4):
            cells += [stats["grid"][k], stats["refined"][k]]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def main(argv=None) -> None:
    def add_arguments(parser):
        parser.add_argument("--points", type=int, default=None, help="random points per map (default 1000)")
        parser.add_argument("--seed", type=int, default=5)

    args = parse(__doc__.splitlines()[0], argv, default_out=HERE, add_arguments=add_arguments)
    keys = list(SHIPPED_MAPS)[:1] if args.smoke else list(SHIPPED_MAPS)
    points = args.points or (4 if args.smoke else 1000)
    if args.smoke:
        table = pd.concat([measure(*key, points, args.seed, None) for key in keys], ignore_index=True)
    else:
        with ProcessPoolExecutor(initializer=init_worker, initargs=(False,)) as executor:
            table = pd.concat([measure(*key, points, args.seed, executor) for key in keys], ignore_index=True)
    args.out_dir.mkdir(parents=True, exist_ok=True)
    table.to_csv(args.out_dir / "refinement_error.csv", index=False)
    print(summary(table))


if __name__ == "__main__":
    main()
