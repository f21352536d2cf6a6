"""The compiled code's share of a sweep's CPU: issue 30's "kernel ≥ 80 % of a call", per map point.

Workload: the grid of ``benchmarks/studies/bench_plane.py`` (200 × 50 log grid over [1e-3, 1e3]²,
``beam-ss-euler`` and ``plate-ssss-kirchhoff``), solved serially in this one process as a
sweep's worker solves it (:func:`impactmaps.maps.compute.points.solve_map_points`, chunks of 40
points along ζ; ``--stride k``: every k-th λ row). Two light timers (one
``time.process_time`` pair per call, ~1 µs) wrap the compiled integrator
(``integrate_impact``, its numba dispatch included) and the compiled coupled-mode set-up
(``coupled_modes``); everything else is the Python around the runs (a point's plan, its
settings, basis truncation, error control, results). ``benchmarks/studies/profile_plane.py`` sorts
the same CPU by kind of run, with heavier timers.

Run: ``python benchmarks/studies/bench_sweep_share.py [--stride 1]``.
"""

from __future__ import annotations

import argparse
import os
import pathlib
import sys
import time
import warnings

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[2]
if __name__ == "__main__":
    for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ.setdefault(_name, "1")
    sys.path.insert(0, str(ROOT))  # this checkout's impactmaps, not an installed one
STRUCTURES = ("beam-ss-euler", "plate-ssss-kirchhoff")


def _timed(function, cpu: list, slot: int):
    def timed(*args, **kwargs):
        start = time.process_time()
        result = function(*args, **kwargs)
        cpu[slot] += time.process_time() - start
        return result
    for attribute in ("variant_of", "compile"):  # a lazy kernel's methods (modal_run calls them)
        if hasattr(function, attribute):
            setattr(timed, attribute, getattr(function, attribute))
    return timed


def share(name: str, stride: int) -> tuple[float, float, float, int]:
    """(CPU of the grid [s], of the integrator, of the coupled-mode set-up, points) on ``name``."""
    from impactmaps.maps.compute import points
    from impactmaps.maps.compute.linear_points import LINEAR
    from impactmaps.maps.family.structures import structure_from_name
    from impactmaps.solvers import modal_run
    from impactmaps.solvers.modal import ModalSettings

    settings = ModalSettings()
    zetas, lambdas = np.logspace(-3, 3, 200), np.logspace(-3, 3, 50)[::stride]
    structure = structure_from_name(name)
    cpu = [0.0, 0.0]
    originals = (modal_run.integrate_impact, modal_run.coupled_modes)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        points.solve_map_points(LINEAR, structure, [(1.0, 1.0)], settings)  # warm: tables, kernels
        modal_run.integrate_impact = _timed(originals[0], cpu, 0)
        modal_run.coupled_modes = _timed(originals[1], cpu, 1)
        try:
            start = time.process_time()
            for lam in lambdas:
                for first in range(0, zetas.size, 40):
                    points.solve_map_points(LINEAR, structure, [(float(z), float(lam)) for z in zetas[first:first + 40]],
                                            settings)
            total = time.process_time() - start
        finally:
            modal_run.integrate_impact, modal_run.coupled_modes = originals
    return total, cpu[0], cpu[1], zetas.size * lambdas.size


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--stride", type=int, default=1, help="every k-th λ row of the 50 (default 1: all)")
    args = parser.parse_args(argv)
    if not 1 <= args.stride <= 50:
        raise SystemExit(f"--stride = {args.stride} is invalid: valid range is [1, 50]")
    print(f"load average at the start {os.getloadavg()[0]:.1f}\n")
    print("| structure | points | CPU [s] | integrator [s] | coupled set-up [s] | compiled share | Python per point [µs] |")
    print("|---|---|---|---|---|---|---|")
    for name in STRUCTURES:
        total, integrator, setup, count = share(name, args.stride)
        print(f"| {name} | {count} | {total:.2f} | {integrator:.2f} | {setup:.2f} | "
              f"{(integrator + setup) / total:.0%} | {1e6 * (total - integrator - setup) / count:.0f} |")


if __name__ == "__main__":
    main()
