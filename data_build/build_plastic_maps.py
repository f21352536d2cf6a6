"""Build the elastic-plastic maps shipped in impactmaps/maps/data/ (axes β, λ, ζ).

For the Yigit–Christoforou law, the refined Stronge law (default constants) and the
``epp`` law (default options: the flat's ν = 0.3, a rigid sphere) on the SS
Euler and Timoshenko (L/h = 20) beams and the SSSS square Kirchhoff plate, impact at the
centre (:mod:`impactmaps.maps.compute.plastic_points`: β the impact number, ζ and λ the linear
numbers at the linearised stiffness K_y). Grid: β from 1 to 10^3.5 at 2 per decade; ζ
from 1e-3 to 10 at 6 per decade; λ from 1e-3 (plate: 1e-2) to 10^1.5 at 5 per decade.
Files ``NAME-yc.nc``, ``NAME-stronge.nc`` and ``NAME-epp.nc`` (an ``epp`` map states the
law options it was built at as attributes ``law_option_poisson_ratio`` and
``law_option_sphere_compliance``). The Mindlin plate has no plastic map: its
pressure patch depends on the sphere radius, a fourth number.

    nice -n 19 python data_build/build_plastic_maps.py [--workers 2] [--only NAME …] [--laws yc stronge epp]
    python data_build/build_plastic_maps.py --smoke    # 2 β × 2 ζ × 2 λ, one map, into a temporary directory

Each map is a :func:`impactmaps.maps.compute.sweep.sweep` of the plastic family, so an
interrupted build resumes (the sweep's file is ``validation/work/NAME-LAW.sweep.nc``, or
``work/`` under ``--out-dir``). Prints the points and the CPU seconds of each map (the
cost the README quotes: this process's and its finished workers').
"""

from __future__ import annotations

import resource
import sys
import time
from pathlib import Path

import numpy as np

from impactmaps.maps.family.accuracy import STATUSES
from impactmaps.maps.files.shipped import map_file_stem
from impactmaps.maps.family.builtin_families import PLASTIC_LAWS
from impactmaps.maps.family.map_family import map_family
from impactmaps.maps.files.store import save_atomic
from impactmaps.maps.family.structures import DEFAULT_STRUCTURES
from impactmaps.maps.compute.sweep import sweep

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "validation"))  # _script_options
from _script_options import parse  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "impactmaps" / "maps" / "data"
WORK = ROOT / "validation" / "work"
#: Impact numbers: 1 (nearly elastic) to 10^3.5 (steel balls at metres per second), 2 per decade.
BETAS = np.logspace(0.0, 3.5, 8)
#: Loss factors ζ(m, K_y): 1e-3 to 10, 6 per decade.
ZETAS = np.logspace(-3.0, 1.0, 25)
#: Relative stiffnesses K_st/K_y, 5 per decade: beams from 1e-3, the plate from 1e-2 (below,
#: heavy balls on flexible plates re-impact 20 times over 10⁴ modes: seconds per point).
BEAM_LAMBDAS = np.logspace(-3.0, 1.5, 23)
PLATE_LAMBDAS = np.logspace(-2.0, 1.5, 18)
#: The structures with plastic maps (the Mindlin plate has none, see the module docstring).
PLASTIC_STRUCTURES = tuple(s for s in DEFAULT_STRUCTURES if s.theory != "mindlin")


def _options(parser) -> None:
    parser.add_argument("--only", nargs="*", default=None, help="build only these structure names")
    parser.add_argument("--laws", nargs="*", default=list(PLASTIC_LAWS), choices=list(PLASTIC_LAWS))
    parser.add_argument("--workers", type=int, default=2, help="worker processes (default 2)")


def _cpu_seconds() -> float:
    """CPU seconds of this process and of its finished child processes."""
    return sum(resource.getrusage(who).ru_utime + resource.getrusage(who).ru_stime
               for who in (resource.RUSAGE_SELF, resource.RUSAGE_CHILDREN))


def build(structure, law, betas, zetas, lambdas, workers: int, work: Path):
    """The map dataset of ``structure`` for ``law`` over the grid (resumable in ``work``), and its CPU seconds."""
    start = _cpu_seconds()
    dataset = sweep([structure], zetas, lambdas, law=law, axes={"beta": betas}, max_workers=workers,
                    path=work / f"{map_file_stem(structure.name, law)}.sweep.nc", progress=workers > 1)
    return dataset, _cpu_seconds() - start


def main(argv=None) -> None:
    args = parse(__doc__.splitlines()[0], argv, default_out=DATA, add_arguments=_options)
    structures = [s for s in PLASTIC_STRUCTURES if args.only is None or s.name in args.only]
    work = WORK if args.out_dir == DATA else args.out_dir / "work"
    if args.smoke:
        structures, args.laws, args.workers = structures[:1], args.laws[:1], 1
    total = 0.0
    for structure in structures:
        lambdas = PLATE_LAMBDAS if structure.kind == "plate" else BEAM_LAMBDAS
        betas, zetas = BETAS, ZETAS
        if args.smoke:
            betas, zetas, lambdas = BETAS[[2, 4]], ZETAS[[10, 14]], lambdas[[10, 14]]
        for law in args.laws:
            start = time.perf_counter()
            dataset, cpu = build(structure, law, betas, zetas, lambdas, args.workers, work)
            wall = time.perf_counter() - start
            dataset.attrs["build_cpu_seconds"] = round(cpu, 1)
            for name, value in map_family(law).law_options.items():
                dataset.attrs[f"law_option_{name}"] = float(value)
            stem = map_file_stem(structure.name, law)
            save_atomic(dataset, args.out_dir / f"{stem}.nc")
            total += cpu
            counts = np.bincount(dataset["status"].values.ravel(), minlength=len(STATUSES))
            print(f"{stem}: {int(dataset['done'].sum())} points, {cpu:.1f} s CPU ({wall:.1f} s wall); status "
                  + ", ".join(f"{name} {count}" for name, count in zip(STATUSES, counts)))
    print(f"all plastic maps: {total:.1f} s CPU")


if __name__ == "__main__":
    main()
