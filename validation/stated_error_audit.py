"""Does a map point's stated error bound its error? Random converged and refined points of the plane
against a run three refinement levels finer.

Reads a plane solved by ``validation/plane_equivalence.py --solve`` (every point's F̄max,
``fmax_error``, status, impacts and modes), draws ``--points`` random converged or refined
modal points per structure with at most ``--max-modes`` modes in their retained run (the
reference integrates 8× as many), and runs each once at three refinement levels above the
base (cut-off and mode floor ×8, step /8: ``ModalSettings().refined()`` three times, as
``benchmarks/studies/bench_plane.py``'s reference). Per structure, single- and multi-impact points
apart: the points whose |F̄max − reference| exceeds their ``fmax_error`` (×1, ×2) and 1e-3,
and the largest. Writes a CSV of the points off by more than 10× their stated error or by
more than 1e-3 (``--all``: every point drawn).

    python validation/plane_equivalence.py --solve --out /tmp/today.npz
    python validation/stated_error_audit.py /tmp/today.npz [--points 600] [--seed 7] [--all]
    python validation/stated_error_audit.py --smoke    # a 3 × 2 plane, 2 points per structure

The CSV is ``stated_error_audit.csv`` in ``--out-dir`` (default ``validation/``).
"""

from __future__ import annotations

import os
import pathlib
import sys
import warnings

if __name__ == "__main__":  # one BLAS thread, set before NumPy loads
    from _script_options import one_blas_thread

    one_blas_thread()

import numpy as np  # noqa: E402  (after the BLAS thread limits)

ROOT = pathlib.Path(__file__).resolve().parents[1]
STRUCTURES = ("beam-ss-euler", "plate-ssss-kirchhoff")
TOLERANCE = 1e-3
#: The CSV keeps (unless ``--all``) the points off by more than this many times their
#: stated error, or by more than the tolerance.
SEVERE = 10.0


def audit(plane: str, points: int, seed: int, max_modes: int, out: str, every: bool = False) -> list[str]:
    """Run the references and return the Markdown summary lines (module docstring)."""
    from impactmaps.maps.compute.linear_points import LINEAR
    from impactmaps.maps.compute.points import basis_table, table_runner
    from impactmaps.maps.family.structures import MAX_MODES
    from impactmaps.solvers.mode_budget import frequency_cap
    from impactmaps.maps.family.structures import structure_from_name
    from impactmaps.solvers.modal_settings import ModalSettings

    data = np.load(plane)
    zetas, lambdas = data["zeta"], data["lambda_"]
    reference = ModalSettings().refined().refined().refined()
    rng = np.random.default_rng(seed)
    rows = ["structure,zeta,lambda,status,impacts,n_modes,fmax,fmax_error,reference,reference_impacts"]
    lines = ["| structure | points | impacts | beyond fmax_error | beyond 2× fmax_error | beyond 1e-3 "
             "| max abs(F̄max − reference) |", "|---|---|---|---|---|---|---|"]
    for name in STRUCTURES:
        structure = structure_from_name(name)
        target, cap = structure.build(), frequency_cap(structure.build(), MAX_MODES)
        table = basis_table(structure, ModalSettings().min_modes)
        status, modes = data[f"{name}/status"], data[f"{name}/n_modes"]
        fmax, error, impacts = data[f"{name}/fmax_normalised"], data[f"{name}/fmax_error"], data[f"{name}/impacts"]
        pool = np.argwhere((status < 2) & (data[f"{name}/method"] == 0) & (modes <= max_modes))
        drawn = pool[rng.choice(len(pool), size=min(points, len(pool)), replace=False)]
        found = []
        for i, j in drawn:
            point = (float(zetas[j]), float(lambdas[i]))
            run = table_runner(LINEAR, target, table, cap, point, LINEAR.realise(target, point), [])
            result = run(reference, 1.0)
            found.append((abs(fmax[i, j] - result.fmax_normalised), error[i, j], impacts[i, j]))
            if not (every or found[-1][0] > max(SEVERE * error[i, j], 0.0) or found[-1][0] > TOLERANCE):
                continue
            rows.append(f"{name},{point[0]:.6g},{point[1]:.6g},{int(status[i, j])},{int(impacts[i, j])},"
                        f"{int(modes[i, j])},{fmax[i, j]:.9g},{error[i, j]:.3g},{result.fmax_normalised:.9g},"
                        f"{result.impacts}")
        found = np.array(found)
        for label, chosen in (("1", found[:, 2] == 1), ("> 1", found[:, 2] > 1)):
            part = found[chosen]
            if not part.size:
                continue
            lines.append(f"| {name} | {len(part)} | {label} | {int((part[:, 0] > part[:, 1]).sum())} "
                         f"| {int((part[:, 0] > 2 * part[:, 1]).sum())} | {int((part[:, 0] > TOLERANCE).sum())} "
                         f"| {part[:, 0].max():.1e} |")
        print(lines[-2] + "\n" + lines[-1], flush=True)
    pathlib.Path(out).write_text("\n".join(rows) + "\n")
    return lines


def main(argv=None) -> None:
    from _script_options import parse

    def options(parser):
        parser.add_argument("plane", nargs="?", help=".npz of plane_equivalence.py --solve")
        parser.add_argument("--points", type=int, default=600, help="points per structure (default 600)")
        parser.add_argument("--seed", type=int, default=7)
        parser.add_argument("--max-modes", type=int, default=1000, help="skip points whose retained run has more modes")
        parser.add_argument("--all", action="store_true", help="every point drawn in the CSV")

    args = parse(__doc__.splitlines()[0], argv, default_out=ROOT / "validation", add_arguments=options)
    sys.path.insert(0, str(ROOT))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        plane, points = args.plane, args.points
        if args.smoke:
            from plane_equivalence import solve

            plane, points = args.out_dir / "plane_smoke.npz", 2
            solve(ROOT, plane, "smoke")
        elif not plane:
            raise SystemExit("give the .npz of plane_equivalence.py --solve (or --smoke)")
        lines = audit(plane, points, args.seed, args.max_modes, args.out_dir / "stated_error_audit.csv", args.all)
    print("\n".join(lines))
    print(f"load average {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
