"""Would another eigen-solver make the clamped Mindlin laminate fast? (issue 39 item 7).

The drop-weight example (``examples/drop_weight_quasi_isotropic.toml``: CCCC Mindlin
[45/0/-45/90]2s, 125 × 75 mm) asks for a patch cut-off (388 ω) beyond what its largest general
Ritz basis resolves, so ``simulate`` and its first ``lookup --case`` both need the eigen-solution
of that basis: 48 × 48 functions per field of the two symmetry classes a half turn keeps, 3456
unknowns, the 100 modes below its resolved frequency. Today it is a dense ``scipy.linalg.eigh``
(driver ``evr``: a full tridiagonal reduction, ~4/3 n³ flops, half of them memory-bound), most of
the run's time. This study times it against a shift-invert block Krylov solve on the Cholesky factor
of the stiffness matrix, the factor the patch's static compliance computes anyway at the same size,
and compares the two solutions:

* relative differences of the eigenvalues ω² (all modes below the resolved frequency);
* the residual of each, ``|λ A⁻¹ v − v|`` (A the mass-scaled stiffness; A⁻¹ through the factor),
  the accuracy a low mode can have: the dense solver's is bounded by ``eps · ‖A‖ / λ``, ~1e-9 here
  (the largest eigenvalue of A is 2e7 times the lowest).

Run:  PYTHONPATH=. python benchmarks/studies/general_eigen_solvers.py [--blocks-per-mode 8]
(writes nothing; prints Markdown for ``benchmarks/studies/RESULTS_general_eigen.md``, with the load).
"""

from __future__ import annotations

import argparse
import os
import time
import warnings
from pathlib import Path

import numpy as np
import scipy.linalg

ROOT = Path(__file__).resolve().parents[2]


def _timed(function):
    """(result, wall [s], CPU [s]) of ``function()``."""
    wall, cpu = time.perf_counter(), time.process_time()
    result = function()
    return result, time.perf_counter() - wall, time.process_time() - cpu


def block_krylov(apply_inverse, size: int, upper: float, wanted: int, block: int = 64, factor: int = 8,
                 seed: int = 0):
    """(eigenvalues ≤ ``upper``, their vectors) of A from the block Krylov space of A⁻¹
    (``apply_inverse``) grown to ``factor · wanted`` vectors, by Rayleigh–Ritz on A⁻¹ (whose largest
    eigenvalues, the wanted ones, are well conditioned); full reorthogonalisation."""
    basis = np.linalg.qr(np.random.default_rng(seed).standard_normal((size, block)))[0]
    latest = basis
    while basis.shape[1] < factor * max(wanted, 1):
        grown = apply_inverse(latest)
        for _ in range(2):
            grown -= basis @ (basis.T @ grown)
        latest = np.linalg.qr(grown)[0]
        basis = np.hstack([basis, latest])
    projected = basis.T @ apply_inverse(basis)
    mu, vectors = np.linalg.eigh(0.5 * (projected + projected.T))
    eigenvalues, vectors = 1.0 / mu[::-1], basis @ vectors[:, ::-1]
    keep = eigenvalues <= upper
    return eigenvalues[keep], vectors[:, keep]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--blocks-per-mode", type=int, default=8,
                        help="Krylov vectors per wanted mode (default 8)")
    options = parser.parse_args()
    warnings.simplefilter("ignore")
    from impactmaps.cases import load_case
    from impactmaps.targets.plates import plate_any_edges, plate_general

    load = " ".join(f"{v:.1f}" for v in os.getloadavg())
    plate = load_case(ROOT / "examples" / "drop_weight_quasi_isotropic.toml").target
    classes = plate_any_edges.class_groups(plate)[0]
    n = plate_any_edges.max_functions(plate.theory, classes)
    inputs = plate_any_edges._inputs(plate)
    upper = plate_any_edges.resolved_frequency(plate, n, n) ** 2
    matrix, scale = plate_general._standard_problem(*inputs, n, n, classes)
    (dense, dense_vectors), dense_wall, dense_cpu = _timed(
        lambda: scipy.linalg.eigh(matrix, subset_by_value=(-np.inf, upper), driver="evr"))
    stiffness = plate_general._last_stiffness(*inputs[:6], n, n, classes)
    factor, factor_wall, factor_cpu = _timed(lambda: scipy.linalg.cho_factor(stiffness))

    def apply_inverse(x):  # A = S K S: A⁻¹ x = S⁻¹ K⁻¹ S⁻¹ x
        return scipy.linalg.cho_solve(factor, x / scale[:, None], check_finite=False) / scale[:, None]

    (krylov, krylov_vectors), krylov_wall, krylov_cpu = _timed(
        lambda: block_krylov(apply_inverse, matrix.shape[0], upper, dense.size, factor=options.blocks_per_mode))
    count = min(dense.size, krylov.size)
    difference = np.abs(krylov[:count] - dense[:count]) / dense[:count]

    def residual(values, vectors):
        return float(np.max(np.linalg.norm(apply_inverse(vectors) * values - vectors, axis=0)))

    print(f"load average (1, 5, 15 min) before: {load}; after: "
          f"{' '.join(f'{v:.1f}' for v in os.getloadavg())} ({os.cpu_count()} cores, shared)\n")
    print(f"{matrix.shape[0]} unknowns (n = {n}, classes {classes}); {dense.size} modes below the resolved "
          f"frequency (dense), {krylov.size} (Krylov)\n")
    print("| step | wall [s] | CPU [s] |\n|---|---|---|")
    print(f"| dense `eigh` (driver evr, subset by value) | {dense_wall:.2f} | {dense_cpu:.2f} |")
    print(f"| Cholesky factor of K (the static compliance's, needed anyway) | {factor_wall:.2f} | {factor_cpu:.2f} |")
    print(f"| block Krylov on that factor ({options.blocks_per_mode} vectors per mode) | {krylov_wall:.2f} | "
          f"{krylov_cpu:.2f} |")
    print(f"\nω²: largest relative difference {difference.max():.2e}, median {np.median(difference):.2e}; "
          f"largest residual |λ A⁻¹v − v|: dense {residual(dense, dense_vectors):.2e}, "
          f"Krylov {residual(krylov, krylov_vectors):.2e}")


if __name__ == "__main__":
    main()
