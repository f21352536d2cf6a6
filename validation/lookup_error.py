"""Interpolation error of the shipped lookup maps and of the closed-form design formula.

For each shipped map, N log-uniform random (ζ, λ) points inside its range are simulated
directly (the same solver and settings as the map) and compared with
``impactmaps.lookup`` and with ``design_formula``. Prints two Markdown
tables (used in docs/validation.rst: errors per map, and the design formula's error per regime,
i.e. where it holds) and writes validation/lookup_error.csv.

With ``--law hertz`` the same for the shipped Hertz maps over (ζ_h, λ_h)
(:mod:`impactmaps.maps.compute.hertz_points`; the design formula is then the larger of the
Hertz infinite-structure and quasi-static peaks), written to
validation/lookup_error_hertz.csv.

With ``--law yc`` (``stronge`` or ``epp``) the same for the shipped elastic-plastic maps over
(β, ζ, λ) (:mod:`impactmaps.maps.read.lookup`): N log-uniform random points inside each
map's box solved directly (:func:`~impactmaps.maps.compute.plastic_points.solve_plastic_points`)
against the lookup of F̄max, restitution and absorbed energy with their bands, written to
validation/lookup_error_yc.csv (``…_stronge.csv``, ``…_epp.csv``); no design formula.

    python validation/lookup_error.py [--points 200] [--seed 1] [--out-dir DIR] [--law hertz|yc|stronge|epp]
    python validation/lookup_error.py --smoke    # 3 points per map (seconds)
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from impactmaps.maps.family.accuracy import STATUSES
from impactmaps.maps.compute.hertz_points import solve_hertz_points
from impactmaps.maps.read.lookup import design_formula
from impactmaps.maps.files.shipped import ALL_MAP_LAWS, SHIPPED_MAPS, load_shipped_map, map_file_stem
from impactmaps import lookup
from impactmaps.maps.read.lookup import PLASTIC_MAPS
from impactmaps.maps.compute.plastic_points import ERROR_OF, solve_plastic_points
from impactmaps.maps.family.builtin_families import PLASTIC_LAWS
from impactmaps.maps.family.structures import structure_from_name
from impactmaps.maps.compute.linear_points import solve_points
from impactmaps.solvers.modal_settings import ModalSettings

from _script_options import parse

HERE = Path(__file__).resolve().parent


def measure(structure: str, theory: str, points: int, seed: int, law: str = "linear") -> pd.DataFrame:
    """Random-point comparison of lookup and design formula against direct simulation."""
    dataset = load_shipped_map(structure, theory, law)
    rng = np.random.default_rng(seed)
    zeta_range = np.log([dataset["zeta"].min().item(), dataset["zeta"].max().item()])
    lambda_range = np.log([dataset["lambda_"].min().item(), dataset["lambda_"].max().item()])
    zetas = np.exp(rng.uniform(*zeta_range, points))
    lambdas = np.exp(rng.uniform(*lambda_range, points))
    name = SHIPPED_MAPS[(structure, theory)]
    solve = solve_points if law == "linear" else solve_hertz_points
    rows = solve(structure_from_name(name), list(zip(zetas, lambdas)), ModalSettings())
    direct = np.array([r["fmax_normalised"] for r in rows])
    direct_error = np.array([r["fmax_error"] for r in rows])
    looked = []
    for zeta, lam in zip(zetas, lambdas):
        try:
            looked.append(lookup(zeta, lam, kind=structure, theory=theory, law=law))
        except ValueError:  # next to an unresolved map point (beyond a Timoshenko/Mindlin theory): refused
            looked.append(None)
    formula = design_formula(zetas, lambdas, structure, law)
    name = map_file_stem(name, law)

    def column(attribute, missing):
        return [missing if found is None else getattr(found, attribute) for found in looked]

    return pd.DataFrame({
        "map": name, "zeta": zetas, "lambda": lambdas, "direct": direct,
        "lookup": column("fmax_normalised", np.nan), "formula": formula, "regime": column("regime", ""),
        "band": column("fmax_error", np.nan), "direct_error": direct_error, "status": column("status", "refused"),
    })


def _options(parser) -> None:
    parser.add_argument("--points", type=int, default=None, help="random points per map (default 200; smoke 3)")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--maps", nargs="*", default=None)
    parser.add_argument("--law", choices=ALL_MAP_LAWS, default="linear", help="contact law of the maps (default linear)")


def main(argv=None) -> None:
    args = parse(__doc__.splitlines()[0], argv, default_out=HERE, add_arguments=_options)
    if args.points is None:
        args.points = 3 if args.smoke else 200
    if args.law in PLASTIC_LAWS:
        plastic_main(args)
        return
    frames = []
    for (structure, theory), name in SHIPPED_MAPS.items():
        if args.maps and name not in args.maps and map_file_stem(name, args.law) not in args.maps:
            continue
        frames.append(measure(structure, theory, args.points, args.seed, args.law))
    table = pd.concat(frames, ignore_index=True)
    table.to_csv(args.out_dir / ("lookup_error.csv" if args.law == "linear" else f"lookup_error_{args.law}.csv"),
                 index=False)
    print("| map | points (refused) | lookup: median abs error | 95th pct | max | band covers error | median band | "
          "design formula: median | 95th pct | max |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for name, everything in table.groupby("map", sort=False):
        refused = int(np.sum(everything["status"] == "refused"))
        group = everything[(everything["status"] != "refused") & np.isfinite(everything["direct"])]
        lookup_error = np.abs(group["lookup"] - group["direct"])
        covered = int(np.sum(lookup_error <= group["band"] + group["direct_error"]))
        formula_error = np.abs(group["formula"] - group["direct"])
        print(f"| {name} | {len(group)} ({refused}) | {np.median(lookup_error):.4f} | "
              f"{np.percentile(lookup_error, 95):.4f} | "
              f"{lookup_error.max():.4f} | {covered}/{len(group)} | {np.median(group['band']):.4f} | "
              f"{np.median(formula_error):.4f} | {np.percentile(formula_error, 95):.4f} | "
              f"{formula_error.max():.4f} |")
    print()
    print(formula_by_regime(table))


def measure_plastic(structure: str, theory: str, law: str, points: int, seed: int) -> pd.DataFrame:
    """Random-point comparison of a plastic map's lookup against direct solves (all three quantities)."""
    dataset = load_shipped_map(structure, theory, law)
    rng = np.random.default_rng(seed)
    axes = {axis: np.exp(rng.uniform(*np.log([dataset[axis].min().item(), dataset[axis].max().item()]), points))
            for axis in ("beta", "zeta", "lambda_")}
    name = PLASTIC_MAPS[(structure, theory)]
    rows = solve_plastic_points(structure_from_name(name), law, list(zip(axes["beta"], axes["zeta"], axes["lambda_"])))
    frame = pd.DataFrame({"map": map_file_stem(name, law), "beta": axes["beta"], "zeta": axes["zeta"],
                          "lambda": axes["lambda_"]})
    found = []
    for beta, zeta, lam in zip(axes["beta"], axes["zeta"], axes["lambda_"]):
        try:
            found.append(lookup(beta, zeta, lam, kind=structure, theory=theory, law=law))
        except ValueError:  # next to an unresolved map point: refused
            found.append(None)
    for variable, error in ERROR_OF.items():
        frame[f"{variable}_direct"] = [r[variable] for r in rows]
        frame[f"{variable}_direct_error"] = [r[error] for r in rows]
        frame[f"{variable}_lookup"] = [np.nan if f is None else getattr(f, variable) for f in found]
        frame[f"{variable}_band"] = [np.nan if f is None else getattr(f, error) for f in found]
    frame["status"] = ["refused" if f is None else f.status for f in found]
    frame["direct_status"] = [STATUSES[r["status"]] for r in rows]
    return frame


def plastic_main(args) -> None:
    """``--law yc|stronge|epp``: measure every shipped plastic map, write the CSV, print the table."""
    frames = [measure_plastic(structure, theory, args.law, args.points, args.seed)
              for (structure, theory), name in PLASTIC_MAPS.items()
              if not args.maps or name in args.maps or map_file_stem(name, args.law) in args.maps]
    table = pd.concat(frames, ignore_index=True)
    table.to_csv(args.out_dir / f"lookup_error_{args.law}.csv", index=False)
    print(plastic_table(table))


def plastic_table(table: pd.DataFrame) -> str:
    """Markdown table: per map and quantity, the lookup error against direct solves and the band's coverage."""
    lines = ["| map | quantity | points (refused) | median abs error | 95th pct | max | band covers error | "
             "median band |", "|---|---|---|---|---|---|---|---|"]
    for name, group in table.groupby("map", sort=False):
        refused = int(np.sum(group["status"] == "refused"))
        unanswered = int(np.sum((group["status"] != "refused") & ~np.isfinite(group["fmax_normalised_direct"])))
        if unanswered:  # a looked-up number where the direct solve holds none: never allowed
            lines.append(f"| {name} | ANSWERED WHERE THE DIRECT SOLVE IS UNRESOLVED | {unanswered} | | | | | |")
        for variable in ERROR_OF:
            ok = np.isfinite(group[f"{variable}_direct"]) & np.isfinite(group[f"{variable}_lookup"])
            error = (group[f"{variable}_lookup"] - group[f"{variable}_direct"]).abs()[ok]
            allowed = (group[f"{variable}_band"] + group[f"{variable}_direct_error"])[ok]
            lines.append(f"| {name} | {variable} | {int(ok.sum())} ({refused}) | {np.median(error):.4f} | "
                         f"{np.percentile(error, 95):.4f} | {error.max():.4f} | "
                         f"{int(np.sum(error <= allowed))}/{int(ok.sum())} | {np.median(allowed):.4f} |")
    return "\n".join(lines)


def formula_by_regime(table: pd.DataFrame) -> str:
    """Markdown table: design-formula error by regime (where the formula holds)."""
    lines = ["| map | regime | points | design formula: median abs error | 95th pct | max |",
             "|---|---|---|---|---|---|"]
    table = table[table["status"] != "refused"]
    error = (table["formula"] - table["direct"]).abs()
    for (name, regime), group in error.groupby([table["map"], table["regime"]], sort=False):
        lines.append(f"| {name} | {regime} | {len(group)} | {np.median(group):.4f} | "
                     f"{np.percentile(group, 95):.4f} | {group.max():.4f} |")
    return "\n".join(lines)


if __name__ == "__main__":
    main()
