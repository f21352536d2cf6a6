"""The map's costliest runs, checkouts side by side: multi-impact map points of the plane.

The runs that dominate the CPU of the (ζ, λ) plane (``benchmarks/studies/RESULTS_plane_levers.md``):
chattering plate points at λ = 0.001 (7–20 impacts on 126–2817 modes, the sampled contact
phase, long stretches of free flight at the base step) and the beam's quasi-static band
(150–190 impacts on 16 modes, the exact contact phase), each at the refinement level the
map's error control runs it. Each checkout (``--root``, repeatable) runs in its own
interpreter with an empty numba cache (``NUMBA_CACHE_DIR`` in a fresh temporary directory:
a cache compiled from other sources cannot stand in for the code measured) and one BLAS
thread; per run: the least CPU time (``time.process_time``) of ``--repeats`` calls after a
warm-up, the steps, impacts, and the peak force and transferred energy with all their
digits (equal digits: the same answer).

Run: ``python benchmarks/studies/bench_map_runs.py --root /tmp/base --root . [--repeats 3]``.
"""

from __future__ import annotations

import argparse
import json
import os
import pathlib
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[2]

#: (structure, ζ, λ, refinement level of the run).
CASES = (("plate-ssss-kirchhoff", 0.966, 0.001, 1), ("plate-ssss-kirchhoff", 1.8, 0.001, 1),
         ("plate-ssss-kirchhoff", 4.45, 0.001, 1), ("plate-ssss-kirchhoff", 27.0, 0.001, 1),
         ("beam-ss-euler", 870.0, 0.001, 2), ("beam-ss-euler", 30.0, 0.002, 2))

_SCRIPT = r"""
import json, sys, time, warnings
warnings.simplefilter("ignore")
from impactmaps.maps.compute.linear_points import LINEAR
from impactmaps.maps.compute.points import basis_table
from impactmaps.maps.family.structures import MAX_MODES
from impactmaps.solvers.mode_budget import frequency_cap
from impactmaps.maps.family.structures import structure_from_name
from impactmaps.solvers.modal import ModalSettings, simulate
repeats, cases = int(sys.argv[1]), json.loads(sys.argv[2])
rows = []
for name, zeta, lam, level in cases:
    structure = structure_from_name(name)
    settings = ModalSettings()
    for _ in range(level):
        settings = settings.refined()
    impact = LINEAR.realise(structure.build(), (zeta, lam))
    basis = basis_table(structure, ModalSettings().min_modes).truncate(
        min(settings.cutoff_ratio * impact.omega, frequency_cap(structure.build(), MAX_MODES)), settings.min_modes)
    run = lambda: simulate(basis, impact.law, impact.mass, impact.velocity, settings=settings, record=False)
    result = run()
    best = float("inf")
    for _ in range(repeats):
        start = time.process_time()
        result = run()
        best = min(best, time.process_time() - start)
    rows.append([name, zeta, lam, level, basis.size, 1e3 * best, result.details.steps, len(result.contact_intervals),
                 repr(result.peak_force), repr(result.energy_transferred)])
print(json.dumps(rows))
"""


def measure(root: pathlib.Path, repeats: int) -> list:
    """The rows of one checkout, measured in a child interpreter on an empty numba cache."""
    with tempfile.TemporaryDirectory() as cache:
        env = dict(os.environ, PYTHONPATH=str(root), NUMBA_CACHE_DIR=cache, OPENBLAS_NUM_THREADS="1",
                   OMP_NUM_THREADS="1")
        out = subprocess.run([sys.executable, "-c", _SCRIPT, str(repeats), json.dumps(CASES)], env=env,
                             cwd=root, capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", type=pathlib.Path, action="append", help="a checkout (repeatable; default this one)")
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args(argv)
    roots = [root.resolve() for root in (args.root or [ROOT])]
    results = {root: measure(root, max(args.repeats, 1)) for root in roots}
    print(f"load average {' '.join(f'{x:.1f}' for x in os.getloadavg())}\n")
    print("| run | modes | " + " | ".join(f"{root.name} CPU [ms]" for root in roots) + " | steps | impacts | same answer |")
    print("|---|---|" + "---|" * len(roots) + "---|---|---|")
    for index, case in enumerate(CASES):
        rows = [results[root][index] for root in roots]
        same = all(row[6:] == rows[0][6:] for row in rows)
        name, zeta, lam, level = case
        print(f"| {name} ζ = {zeta:g}, λ = {lam:g}, level {level} | {rows[0][4]} | "
              + " | ".join(f"{row[5]:.1f}" for row in rows) + f" | {rows[0][6]} | {rows[0][7]} | {'yes' if same else 'NO'} |")


if __name__ == "__main__":
    main()
