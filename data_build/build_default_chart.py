"""Build the shipped results of the default charts' sweeps (``impactmaps chart [--law hertz]``).

The chart's sweep — SS Euler beam and SS square Kirchhoff plate
(:data:`impactmaps.plotting.chart.CHART_STRUCTURES`), the 8 λ of
:data:`~impactmaps.plotting.chart.DEFAULT_CHART_LAMBDAS` × 200 log-spaced ζ over
:data:`~impactmaps.plotting.chart.DEFAULT_ZETA_RANGE`, default solver settings, for the linear
law (ζ, λ) and the Hertz law (ζ_h, λ_h) — is computed and stored as
``impactmaps/maps/data/results/<fingerprint>.npz`` (packed, lossless: :mod:`impactmaps.maps.files.data_io`)
(:mod:`impactmaps.maps.files.shipped`); results of other fingerprints (an earlier solver
revision or grid) are deleted. ``impactmaps chart`` then starts from it as from a finished
run (the README's first command draws the chart without compiling the integrator).
Re-run after anything that changes the fingerprint (``SOLVER_REVISION``, the defaults):
``tests/maps/test_shipped_results.py`` fails until it is.

    python data_build/build_default_chart.py [--quiet] [--force] [--out-dir DIR]
    python data_build/build_default_chart.py --smoke   # 3 ζ × 2 λ, into a temporary directory

``--force`` recomputes a result that is already current. A current result without the
asymptote peaks its regimes are judged by (:func:`impactmaps.maps.compute.dataset.with_asymptote_peaks`)
gets them added (the chart then classifies without integrating an asymptote).
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

from impactmaps.maps.family.map_family import ASYMPTOTE_PEAKS
from impactmaps.maps.compute.dataset import with_asymptote_peaks
from impactmaps.plotting.chart import CHART_STRUCTURES, DEFAULT_CHART_LAMBDAS, DEFAULT_ZETA_COUNT, DEFAULT_ZETA_RANGE
from impactmaps.maps.files.shipped import SHIPPED_RESULTS, shipped_result_path
from impactmaps.maps.files.data_io import read_dataset
from impactmaps.maps.files.store import save_atomic
from impactmaps.maps.compute.sweep import log_grid, sweep, sweep_fingerprint

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "validation"))  # _script_options
from _script_options import parse  # noqa: E402


#: The contact laws whose default chart ships its sweep result.
CHART_LAWS = ("linear", "hertz")


def default_chart_grid():
    """(structures, ζ, λ) of the default chart's sweep."""
    return CHART_STRUCTURES, log_grid(*DEFAULT_ZETA_RANGE, DEFAULT_ZETA_COUNT), DEFAULT_CHART_LAMBDAS


def _options(parser) -> None:
    parser.add_argument("--quiet", action="store_true", help="no progress bar")
    parser.add_argument("--force", action="store_true", help="recompute a result that is already current")


def main(argv=None) -> None:
    args = parse(__doc__.splitlines()[0], argv, default_out=SHIPPED_RESULTS, add_arguments=_options)
    structures, zetas, lambdas = default_chart_grid()
    if args.smoke:
        zetas, lambdas = zetas[[50, 100, 150]], lambdas[:2]
    targets = {law: args.out_dir / shipped_result_path(sweep_fingerprint(structures, zetas, lambdas, law=law)).name
               for law in CHART_LAWS}
    for stale in [*args.out_dir.glob("*.nc"), *args.out_dir.glob("*.npz")]:
        if stale not in targets.values() or args.force:
            stale.unlink()
            print(f"removed {stale.name}")
    for law, target in targets.items():
        if target.exists():
            current = read_dataset(target)
            if all(name in current for name in ASYMPTOTE_PEAKS):
                print(f"{law}: {target.name} is current")
            else:
                save_atomic(with_asymptote_peaks(current), target)
                print(f"{law}: {target.name}: asymptote peaks added")
            continue
        start = time.perf_counter()
        dataset = sweep(structures, zetas, lambdas, progress=not args.quiet, law=law)
        save_atomic(dataset.drop_vars("regime"), target)
        print(f"{law}: wrote {target} ({target.stat().st_size / 1e3:.0f} kB, {time.perf_counter() - start:.1f} s)")


if __name__ == "__main__":
    main()
