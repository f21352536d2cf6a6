"""How far a point-loaded Mindlin map value lies from ``simulate`` at its own cut-off.

A Mindlin plate struck at a point has a logarithmically divergent point-load deflection
(``docs/physics_contract.md`` §8): a modal sum does not converge in the cut-off. The linear
maps of the Mindlin plate (and ``impactmaps point``) strike a point and hold the shear of
every mode up to the sweep's mode cap (:data:`impactmaps.maps.family.structures.MAX_MODES`); their
error control refines the integration at that cap. ``simulate_normalised`` cuts the same
sum at its own cut-off (``ModalSettings.cutoff_ratio`` × ω). This script measures the
difference the warning of :func:`impactmaps.maps.family.structures.warn_point_loaded_mindlin` quotes:
N random (ζ, λ), log-uniform over the plane [1e-3, 1e3]², on the shipped Mindlin member
(span/thickness 20); points the map leaves ``unresolved`` or answers by an asymptote are
counted, not compared.

Prints a Markdown table and writes ``mindlin_point_load.csv`` and ``.md``.

    python validation/mindlin_point_load.py [--points 300] [--seed 11] [--out-dir DIR]
    python validation/mindlin_point_load.py --smoke    # 4 points (seconds)
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pandas as pd

from impactmaps.maps.family.accuracy import STATUSES
from impactmaps.maps.family.structures import MapStructure
from impactmaps.maps.compute.sweep import METHODS, solve_points
from impactmaps.solvers.modal import ModalSettings, simulate_normalised

from _script_options import parse

HERE = Path(__file__).resolve().parent


def _options(parser) -> None:
    parser.add_argument("--points", type=int, default=300, help="random (ζ, λ) points (default 300)")
    parser.add_argument("--seed", type=int, default=11)


def measure(points: int, seed: int) -> pd.DataFrame:
    """One row per random point: the map value, its error and status, and ``simulate``'s value."""
    structure = MapStructure(kind="plate", theory="mindlin")
    target = structure.build()
    rng = np.random.default_rng(seed)
    zetas, lambdas = 10.0 ** rng.uniform(-3, 3, points), 10.0 ** rng.uniform(-3, 3, points)
    rows = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        mapped = solve_points(structure, list(zip(zetas, lambdas)), ModalSettings())
        for zeta, lam, row in zip(zetas, lambdas, mapped):
            status, method = STATUSES[int(row["status"])], int(row["method"])
            direct = np.nan
            if status not in ("unresolved", "asymptotic") and METHODS[method].startswith("modal"):
                direct = float(simulate_normalised(target, zeta, lam).fmax_normalised)
            rows.append({"zeta": zeta, "lambda": lam, "status": status, "impacts": int(row["impacts"]),
                         "map_fmax": float(row["fmax_normalised"]), "map_error": float(row["fmax_error"]),
                         "simulate_fmax": direct})
    frame = pd.DataFrame(rows)
    frame["relative_difference"] = (frame["simulate_fmax"] - frame["map_fmax"]).abs() / frame["map_fmax"]
    return frame


def summary(frame: pd.DataFrame) -> str:
    """The Markdown table: relative |simulate − map| by number of impacts and status."""
    lines = ["| points | compared | median | 90th percentile | max | beyond 3 % | beyond the map's fmax_error |",
             "|---|---|---|---|---|---|---|"]
    compared = frame[np.isfinite(frame["simulate_fmax"])]
    groups = (("all", compared), ("1 impact", compared[compared["impacts"] == 1]),
              ("> 1 impact", compared[compared["impacts"] > 1]),
              ("status converged or refined", compared[compared["status"].isin(("converged", "refined"))]))
    for name, part in groups:
        if len(part) == 0:
            continue
        d = part["relative_difference"]
        beyond = int(((part["simulate_fmax"] - part["map_fmax"]).abs() > part["map_error"]).sum())
        lines.append(f"| {name} | {len(part)} | {d.median():.2%} | {np.percentile(d, 90):.2%} | {d.max():.2%} | "
                     f"{int((d > 0.03).sum())} | {beyond} |")
    skipped = len(frame) - len(compared)
    lines.append(f"\n{len(frame)} random points; {skipped} not compared (unresolved or asymptotic).")
    return "\n".join(lines)


def main(argv=None) -> None:
    args = parse(__doc__.splitlines()[0], argv, default_out=HERE, add_arguments=_options)
    frame = measure(4 if args.smoke else args.points, args.seed)
    table = summary(frame)
    print(table)
    frame.to_csv(args.out_dir / "mindlin_point_load.csv", index=False)
    (args.out_dir / "mindlin_point_load.md").write_text(table + "\n")


if __name__ == "__main__":
    main()
