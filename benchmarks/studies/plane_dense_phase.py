"""Would the exact contact phase pay on the plate's dense runs if its set-up cost nothing?

Reads the runs of ``benchmarks/studies/plane_levers.py --data FILE.npz``, draws ``--runs`` of the
plate's runs with 400–1600 modes (weighted by their CPU today, so the costly ones), and
runs each twice: as today (``contact_phase="auto"``: the sampled phase above
``COUPLED_MAX_MODES`` = 400) and with the exact phase (``contact_phase="exact"`` and the
module's ``COUPLED_MAX_MODES`` raised to 1600 for the run), timing the coupled modes'
set-up (``coupled_modes``, an (n + 1)² eigen-decomposition) apart. CPU is
``time.process_time``. Nothing of the package is changed on disk.

Run: ``python benchmarks/studies/plane_dense_phase.py --data FILE.npz [--runs 20] [--seed 3]``.
"""

from __future__ import annotations

import argparse
import os
import pathlib
import sys
import time
import warnings
from dataclasses import replace

if __name__ == "__main__":
    for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ.setdefault(_name, "1")

import numpy as np  # noqa: E402  (after the BLAS thread limits)

ROOT = pathlib.Path(__file__).resolve().parents[2]
NAME = "plate-ssss-kirchhoff"


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--data", required=True, help=".npz of plane_levers.py --data")
    parser.add_argument("--runs", type=int, default=20)
    parser.add_argument("--seed", type=int, default=3)
    args = parser.parse_args(argv)
    sys.path.insert(0, str(ROOT))
    import impactmaps.solvers.modal_run as modal_run
    from impactmaps.maps.compute.linear_points import LINEAR
    from impactmaps.maps.compute.points import basis_table, table_runner
    from impactmaps.maps.family.structures import MAX_MODES
    from impactmaps.solvers.mode_budget import frequency_cap
    from impactmaps.maps.family.structures import structure_from_name
    from impactmaps.solvers.modal import ModalSettings

    data = np.load(args.data)
    zetas, lambdas, modes, cpu = data["zeta"], data["lambda_"], data[f"{NAME}/modes"], data[f"{NAME}/cpu"]
    candidates = [index for index in zip(*np.nonzero((modes > 400) & (modes <= 1600)))]
    weights = np.array([cpu[index] for index in candidates])
    picked = np.random.default_rng(args.seed).choice(len(candidates), size=min(args.runs, len(candidates)),
                                                     replace=False, p=weights / weights.sum())
    structure = structure_from_name(NAME)
    target, cap = structure.build(), frequency_cap(structure.build(), MAX_MODES)
    table = basis_table(structure, ModalSettings().min_modes)
    levels = [ModalSettings(), ModalSettings().refined(), ModalSettings().refined().refined()]
    set_up, original, limit = [0.0], modal_run.coupled_modes, modal_run.COUPLED_MAX_MODES

    def timed(*call):
        start = time.process_time()
        result = original(*call)
        set_up[0] += time.process_time() - start
        return result

    totals = np.zeros(3)
    print("| ζ | λ | level | modes | impacts | sampled [ms] | exact [ms] | of which set-up [ms] | ΔF̄max |")
    print("|---|---|---|---|---|---|---|---|---|")
    modal_run.coupled_modes = timed
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            for pick in picked:
                i, j, k = candidates[pick]
                point = (float(zetas[j]), float(lambdas[i]))
                realised = LINEAR.realise(target, point)
                runs = []
                for phase, most in (("auto", limit), ("exact", 1600)):
                    modal_run.COUPLED_MAX_MODES, set_up[0] = most, 0.0
                    run = table_runner(LINEAR, target, table, cap, point, realised, [])
                    start = time.process_time()
                    result = run(replace(levels[k], contact_phase=phase), 1.0)
                    runs.append((result, time.process_time() - start, set_up[0]))
                (today, t_today, _), (exact, t_exact, t_setup) = runs
                totals += (t_today, t_exact, t_setup)
                print(f"| {point[0]:.3g} | {point[1]:.3g} | {k} | {today.n_modes} | {today.impacts} | "
                      f"{1e3 * t_today:.0f} | {1e3 * t_exact:.0f} | {1e3 * t_setup:.0f} | "
                      f"{abs(today.fmax_normalised - exact.fmax_normalised):.1e} |", flush=True)
    finally:
        modal_run.coupled_modes, modal_run.COUPLED_MAX_MODES = original, limit
    print(f"\n{len(picked)} runs of {len(candidates)}: sampled {totals[0]:.2f} CPU-s, exact {totals[1]:.2f} "
          f"(set-up {totals[2]:.2f}, the rest {totals[1] - totals[2]:.2f}); load average {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
