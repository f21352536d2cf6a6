"""Interpolation in slenderness between the shipped shear-deformable map families.

For each family (Timoshenko beams: linear and Hertz laws; Mindlin plates: linear law;
members at span/thickness 10, 20, 50 and the classical thin limit,
:mod:`impactmaps.maps.read.slenderness`):

1. the leave-one-out error on the grid (s = 20 predicted from s = 10 and 50, s = 50 from
   the thin limit and s = 20; :func:`~impactmaps.maps.read.slenderness.slenderness_error_grid`):
   median, 90th percentile and maximum;
2. N random (ζ, λ, s) points with s log-uniform in [10, 100], solved directly on the
   structure of that slenderness (the same solver and settings as the maps) and looked
   up by :func:`impactmaps.lookup` (``slenderness=``): |lookup − direct| against
   the lookup's band, refusals counted (next to ``unresolved`` points).

Prints a Markdown table and writes validation/slenderness_interpolation.csv.

    python validation/slenderness_interpolation.py [--points 60] [--seed 3] [--out-dir DIR]
    python validation/slenderness_interpolation.py --smoke    # 2 points per family (seconds)
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pandas as pd

from impactmaps.maps.read.slenderness import slenderness_error_grid
from impactmaps import lookup
from impactmaps.maps.compute.hertz_points import solve_hertz_points
from impactmaps.maps.files.shipped import SHIPPED_MAPS, load_shipped_map
from impactmaps.maps.family.builtin_families import MEMBER_SLENDERNESSES
from impactmaps.maps.family.structures import structure_from_name
from impactmaps.maps.compute.linear_points import solve_points
from impactmaps.solvers.modal_settings import ModalSettings

from _script_options import parse

HERE = Path(__file__).resolve().parent
FAMILIES = (("beam", "timoshenko", "linear"), ("beam", "timoshenko", "hertz"), ("plate", "mindlin", "linear"))


def measure(structure: str, theory: str, law: str, points: int, seed: int) -> pd.DataFrame:
    """Random (ζ, λ, s) points: direct solve against the slenderness lookup and its band."""
    # the (ζ, λ) box every slenderness member covers (the s = 20 maps may cover more)
    members = [load_shipped_map(structure, theory, law, slenderness=s) for s in MEMBER_SLENDERNESSES]
    box = {axis: (max(m[axis].min().item() for m in members), min(m[axis].max().item() for m in members))
           for axis in ("zeta", "lambda_")}
    rng = np.random.default_rng(seed)
    zetas = np.exp(rng.uniform(*np.log(box["zeta"]), points))
    lambdas = np.exp(rng.uniform(*np.log(box["lambda_"]), points))
    slendernesses = np.exp(rng.uniform(np.log(10.0), np.log(100.0), points))
    solve = solve_points if law == "linear" else solve_hertz_points
    base = structure_from_name(SHIPPED_MAPS[(structure, theory)])
    rows = []
    for zeta, lam, slenderness in zip(zetas, lambdas, slendernesses):
        (direct,) = solve(replace(base, slenderness=float(slenderness)), [(zeta, lam)], ModalSettings())
        row = {"family": f"{structure}-{theory}-{law}", "zeta": zeta, "lambda": lam, "slenderness": slenderness,
               "direct": direct["fmax_normalised"], "direct_error": direct["fmax_error"]}
        try:
            found = lookup(zeta, lam, kind=structure, theory=theory, slenderness=slenderness,
                                       law=law)
        except ValueError:
            row.update(lookup=np.nan, band=np.nan, refused=True)
        else:
            row.update(lookup=found.fmax_normalised, band=found.fmax_error, refused=False)
        rows.append(row)
    frame = pd.DataFrame(rows)
    frame["error"] = (frame["lookup"] - frame["direct"]).abs()
    return frame


def _options(parser) -> None:
    parser.add_argument("--points", type=int, default=60, help="random points per family (default 60)")
    parser.add_argument("--seed", type=int, default=3)


def main(argv=None) -> None:
    args = parse(__doc__.splitlines()[0], argv, default_out=HERE, add_arguments=_options)
    points = 2 if args.smoke else args.points
    lines = ["| family | leave-one-out error: median / p90 / max | random points answered | refused "
             "| |lookup − direct|: median / max | largest error / band | inside the band |",
             "|---|---|---|---|---|---|---|"]
    frames = []
    for structure, theory, law in FAMILIES:
        _, _, errors = slenderness_error_grid(structure, theory, law)
        known = errors[np.isfinite(errors)]
        frame = measure(structure, theory, law, points, args.seed)
        frames.append(frame)
        answered = frame[~frame["refused"] & np.isfinite(frame["direct"])]
        inside = int((answered["error"] <= answered["band"] + answered["direct_error"]).sum())
        ratio = (answered["error"] / answered["band"]).max() if len(answered) else np.nan
        lines.append(
            f"| {structure} {theory}, {law} | {np.median(known):.1e} / {np.percentile(known, 90):.1e} / "
            f"{known.max():.1e} | {len(answered)} of {len(frame)} | {int(frame['refused'].sum())} | "
            f"{answered['error'].median():.1e} / {answered['error'].max():.1e} | {ratio:.2f} | "
            f"{inside} of {len(answered)} |")
    table = "\n".join(lines)
    print(table)
    pd.concat(frames).to_csv(args.out_dir / "slenderness_interpolation.csv", index=False)
    (args.out_dir / "slenderness_interpolation.md").write_text(table + "\n")


if __name__ == "__main__":
    main()
