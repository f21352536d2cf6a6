"""Build the maps shipped in impactmaps/maps/data/ (the design-rule lookup tables).

Simply supported, impact at the centre: SS Euler and Timoshenko beams (L/h = 20), SS
square Kirchhoff and Mindlin plates (a/h = 20). Grid: ζ and λ from 1e-3 to 1e3 at 20 ζ and
10 λ per decade, twice that for the four maps at L/h = a/h = 20 (both laws; the Mindlin
slenderness members at a/h = 10 and 50: ζ from 0.005 to 100,
λ from 0.05 to 20; the Hertz maps: ζ_h from 0.005 to 100, λ_h from 1e-3 to 20, the
Mindlin one from 0.05; same densities); default solver settings. Points beyond the range of the Timoshenko/Mindlin
theories are stored ``unresolved``. The shear-deformable slenderness members add slendernesses 10 and
50 on the same grids (``impactmaps.maps.family.structures.MEMBER_STRUCTURES``): Timoshenko beams
for both laws, Mindlin plates for the linear law (a Hertz impact on a Mindlin plate loads
the contact patch, whose radius is a third parameter).
Resumable: re-running continues an interrupted build.

    python data_build/build_default_maps.py [--quiet] [--only NAME …] [--out-dir DIR] [--law hertz]
    python data_build/build_default_maps.py --smoke    # 3 ζ × 2 λ per map, inline, into a temporary directory

With ``--out-dir`` the maps go there (and the resumable sweep stores into its ``work/``),
not into the package. ``--law hertz`` builds the Hertz maps over the Hertz numbers
(ζ_h, λ_h) on the same grid (files ``NAME-hertz.nc``, :mod:`impactmaps.maps.compute.hertz_points`).
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

from impactmaps.maps.files.shipped import SHIPPED_MAPS, map_file_stem
from impactmaps.maps.read.slenderness import shipped_for
from impactmaps.maps.files.store import save_atomic
from impactmaps.maps.family.structures import DEFAULT_STRUCTURES, MEMBER_STRUCTURES
from impactmaps.maps.family.regimes import MAP_LAWS
from impactmaps.maps.compute.sweep import sweep

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "validation"))  # _script_options
from _script_options import parse  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "impactmaps" / "maps" / "data"
WORK = ROOT / "validation" / "work"
#: Linear maps: the whole plane ζ, λ ∈ [1e-3, 1e3], 20 ζ and 10 λ per decade.
ZETAS = np.geomspace(1e-3, 1e3, 121)
LAMBDAS = np.geomspace(1e-3, 1e3, 61)
#: The SS Euler beam and SS Kirchhoff plate maps (the chart's structures, the most read):
#: twice as dense, 40 ζ and 20 λ per decade (29 161 points, ~3 min on 2 cores), which
#: divides their interpolation error by ~4 where F̄max is smooth and by ~2 at its kinks.
#: Since 2026-11-24 the Timoshenko beam and the Mindlin plate (a/h = 20) are as dense, both
#: laws; the slenderness members at a/h = 10 and 50 keep 20 ζ and 10 λ per decade, the tiles'
#: lattice.
DENSE_MAPS = ("beam-ss-euler", "plate-ssss-kirchhoff", "beam-ss-timoshenko-s20", "plate-ssss-mindlin-s20")
DENSE_ZETAS = np.geomspace(1e-3, 1e3, 241)
DENSE_LAMBDAS = np.geomspace(1e-3, 1e3, 121)
#: The linear Mindlin plate map (a/h = 20) covers the whole plane too (318 s on 2 cores at revision 7):
#: towards light impactors its contact frequency passes a quarter of the thickness-shear
#: cut-off, where the model no longer holds, and those points are ``unresolved``
#: (:mod:`impactmaps.targets.shear_range`); towards small λ the points just inside that
#: limit bounce many times on 10⁴ modes (ζ = 10, λ = 0.001: 49 impacts). The
#: Mindlin slenderness members at a/h = 10 and 50 and the Mindlin Hertz map keep
#: ζ ∈ [0.005, 100], λ ∈ [0.05, 20] (cost).
MINDLIN_ZETAS = np.geomspace(0.005, 100.0, 87)
MINDLIN_LAMBDAS = np.geomspace(0.05, 20.0, 27)
#: Hertz maps (ζ_h, λ_h): ζ_h ∈ [0.005, 100], λ_h ∈ [1e-3, 20] at the same densities
#: (most steel-ball impacts on beams and plates have λ_h < 0.05); the Mindlin one keeps
#: λ_h ∈ [0.05, 20] (same reason). The Hertz law runs the sampled contact scheme, whose
#: quasi-static corner is still costly.
HERTZ_ZETAS = np.geomspace(0.005, 100.0, 87)
HERTZ_LAMBDAS = np.geomspace(1e-3, 20.0, 44)
#: The Hertz maps of the four structures at a/h = 20 (DENSE_MAPS): twice as dense, like their linear maps.
DENSE_HERTZ_ZETAS = np.geomspace(0.005, 100.0, 173)
DENSE_HERTZ_LAMBDAS = np.geomspace(1e-3, 20.0, 87)
#: The Mindlin plate's Hertz map at that density: λ_h ∈ [0.05, 20].
DENSE_MINDLIN_HERTZ_LAMBDAS = np.geomspace(0.05, 20.0, 53)


def _options(parser) -> None:
    parser.add_argument("--quiet", action="store_true")
    parser.add_argument("--only", nargs="*", default=None, help="build only these map names")
    parser.add_argument("--law", choices=MAP_LAWS, default="linear", help="contact law of the maps (default linear)")


def main(argv=None) -> None:
    args = parse(__doc__.splitlines()[0], argv, default_out=DATA, add_arguments=_options)
    work = WORK if args.out_dir == DATA else args.out_dir / "work"
    members = [s for s in MEMBER_STRUCTURES if shipped_for(s.kind, s.theory, args.law)]
    wanted = set(args.only or [*SHIPPED_MAPS.values(), *(s.name for s in members)])
    for structure in (*DEFAULT_STRUCTURES, *members):
        if structure.name not in wanted:
            continue
        if args.law != "linear" and structure.name in DENSE_MAPS:
            zetas = DENSE_HERTZ_ZETAS
            lambdas = DENSE_MINDLIN_HERTZ_LAMBDAS if structure.theory == "mindlin" else DENSE_HERTZ_LAMBDAS
        elif args.law != "linear":
            zetas, lambdas = HERTZ_ZETAS, (MINDLIN_LAMBDAS if structure.theory == "mindlin" else HERTZ_LAMBDAS)
        elif structure.theory == "mindlin" and structure.slenderness != 20.0:
            zetas, lambdas = MINDLIN_ZETAS, MINDLIN_LAMBDAS
        elif structure.name in DENSE_MAPS:
            zetas, lambdas = DENSE_ZETAS, DENSE_LAMBDAS
        else:
            zetas, lambdas = ZETAS, LAMBDAS
        if args.smoke:
            zetas, lambdas = zetas[[len(zetas) // 4, len(zetas) // 2, 3 * len(zetas) // 4]], lambdas[[0, -1]]
        stem = map_file_stem(structure.name, args.law)
        start = time.perf_counter()
        dataset = sweep([structure], zetas, lambdas, path=work / f"{stem}.sweep.nc",
                        progress=not (args.quiet or args.smoke), max_workers=1 if args.smoke else None,
                        law=args.law)
        elapsed = time.perf_counter() - start
        # log-times for interpolation of the regime criteria
        dataset["log_peak_time"] = np.log(dataset["peak_time_normalised"])
        dataset["log_reflection_time"] = np.log(dataset["reflection_time_normalised"])
        dataset.attrs["build_seconds"] = round(elapsed, 1)
        shipped = dataset.drop_vars("regime")
        save_atomic(shipped, args.out_dir / f"{stem}.nc")
        print(f"{stem}: {dataset['done'].sum().item()} points in {elapsed:.1f} s")


if __name__ == "__main__":
    main()
