"""The whole (ζ, λ) plane of ``benchmarks/studies/bench_plane.py``, point by point, against another checkout.

Two steps:

    python validation/plane_equivalence.py --solve --root /tmp/base --out /tmp/base.npz
    python validation/plane_equivalence.py --solve --out /tmp/this.npz
    python validation/plane_equivalence.py --compare /tmp/base.npz /tmp/this.npz --summary plane_equivalence
    python validation/plane_equivalence.py --smoke     # a 3 × 2 grid solved and compared with itself

``--solve`` solves the 200 × 50 grid (ζ × λ over [1e-3, 1e3]²) of ``beam-ss-euler`` and
``plate-ssss-kirchhoff`` serially in this process, one point per call of
:func:`impactmaps.maps.compute.points.solve_map_points` (what a sweep's worker computes), with the
checkout given by ``--root`` first on the path (default: this one), and stores every
point's map variables and its CPU time (``time.process_time``) in an ``.npz``.
``--compare`` reads two such files (today's first) and writes, per structure and method of
the new points: points, CPU of each, points whose F̄max differs, the largest difference,
and the points where it exceeds the old point's stated error (``fmax_error``, at least
1e-12) or lies outside its band ``[fmax_low, fmax_high]``; status and impact-count changes
counted. ``--summary NAME`` writes ``NAME.md`` and ``NAME.csv`` into ``--out-dir`` (default
``validation/``; one row per point beyond today's error or band, or whose status or impact
count changed). ``--referee NAME.csv`` (with ``--compare``, into ``--out-dir``) says which
plane is right where they differ beyond the old stated error: a run three refinement
levels finer at each such point.
"""

from __future__ import annotations

import os
import pathlib
import sys
import time
import warnings

if __name__ == "__main__":  # one BLAS thread, set before NumPy loads (not when a test imports this)
    from _script_options import one_blas_thread

    one_blas_thread()

import numpy as np  # noqa: E402  (after the BLAS thread limits)

ROOT = pathlib.Path(__file__).resolve().parents[1]
STRUCTURES = ("beam-ss-euler", "plate-ssss-kirchhoff")
VARIABLES = ("fmax_normalised", "fmax_error", "fmax_low", "fmax_high", "status", "method", "impacts",
             "n_modes", "contact_time_normalised", "energy_transferred_fraction")


#: ζ and λ counts of the grids: the plane, ``--quick``, ``--smoke``.
GRIDS = {"plane": (200, 50), "quick": (40, 10), "smoke": (3, 2)}


def grid(size: str = "plane"):
    """ζ and λ of the plane [-] (log grids over [1e-3, 1e3], counts :data:`GRIDS`)."""
    zetas, lambdas = GRIDS[size]
    return np.geomspace(1e-3, 1e3, zetas), np.geomspace(1e-3, 1e3, lambdas)


def solve(root: pathlib.Path, out, size: str = "plane", contact_phase: str | None = None) -> None:
    """Solve the plane with the package of ``root``; store the variables and CPU per point."""
    sys.path.insert(0, str(root))
    from impactmaps.maps.compute.linear_points import LINEAR
    from impactmaps.maps.compute.points import solve_map_points
    from impactmaps.maps.family.structures import structure_from_name
    from impactmaps.solvers.modal_settings import ModalSettings

    zetas, lambdas = grid(size)
    stored = {"zeta": zetas, "lambda_": lambdas}
    settings = ModalSettings() if contact_phase is None else ModalSettings(contact_phase=contact_phase)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for name in STRUCTURES:
            structure = structure_from_name(name)
            solve_map_points(LINEAR, structure, [(1.0, 1.0)], settings)  # warm: tables, kernels
            values = {v: np.full((lambdas.size, zetas.size), np.nan) for v in VARIABLES}
            cpu = np.zeros((lambdas.size, zetas.size))
            start = time.process_time()
            for i, lam in enumerate(lambdas):
                for j, zeta in enumerate(zetas):
                    t0 = time.process_time()
                    row = solve_map_points(LINEAR, structure, [(float(zeta), float(lam))], settings)[0]
                    cpu[i, j] = time.process_time() - t0
                    for v in VARIABLES:
                        values[v][i, j] = row[v]
            print(f"{name}: {time.process_time() - start:.1f} CPU-s, load {os.getloadavg()[0]:.1f}", flush=True)
            stored |= {f"{name}/{v}": a for v, a in values.items()} | {f"{name}/cpu": cpu}
    np.savez(out, **stored)


def referee(old_path: str, new_path: str, out: str) -> None:
    """Which of two planes is right where they differ beyond the old point's stated error.

    At every converged or refined point of ``old_path`` (status unchanged in ``new_path``)
    whose F̄max the new plane moves beyond the old ``fmax_error``, one run three
    refinement levels finer than the base (cut-off and mode floor ×8, step /8, default
    contact phase) is the reference; writes ``out`` (CSV, one row per point) and prints
    where each plane's value lies from it.
    """
    from impactmaps.maps.compute.linear_points import LINEAR
    from impactmaps.maps.compute.points import basis_table, table_runner
    from impactmaps.maps.family.structures import MAX_MODES
    from impactmaps.solvers.mode_budget import frequency_cap
    from impactmaps.maps.family.structures import structure_from_name
    from impactmaps.solvers.modal_settings import ModalSettings

    old, new = np.load(old_path), np.load(new_path)
    zetas, lambdas = old["zeta"], old["lambda_"]
    reference = ModalSettings().refined().refined().refined()
    rows = ["structure,zeta,lambda,fmax_old,fmax_new,fmax_error_old,reference"]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for name in STRUCTURES:
            structure = structure_from_name(name)
            target, cap = structure.build(), frequency_cap(structure.build(), MAX_MODES)
            table = basis_table(structure, ModalSettings().min_modes)
            f_old, f_new, error = (old[f"{name}/fmax_normalised"], new[f"{name}/fmax_normalised"],
                                   old[f"{name}/fmax_error"])
            status = old[f"{name}/status"]
            chosen = ((np.abs(f_new - f_old) > np.maximum(error, 1e-12)) & (status == new[f"{name}/status"])
                      & (status < 2))
            far_old, far_new, beyond_old = [], [], 0
            for i, j in zip(*np.nonzero(chosen)):
                point = (float(zetas[j]), float(lambdas[i]))
                run = table_runner(LINEAR, target, table, cap, point, LINEAR.realise(target, point), [])
                value = run(reference, 1.0).fmax_normalised
                far_old.append(abs(f_old[i, j] - value))
                far_new.append(abs(f_new[i, j] - value))
                beyond_old += far_old[-1] > error[i, j]
                rows.append(f"{name},{point[0]:.6g},{point[1]:.6g},{f_old[i, j]:.9g},{f_new[i, j]:.9g},"
                            f"{error[i, j]:.3g},{value:.9g}")
            if far_old:
                print(f"{name}: {len(far_old)} points; the old value beyond its stated error from the reference at "
                      f"{beyond_old}; the new one closer at {int(np.sum(np.array(far_new) < np.array(far_old)))}; "
                      f"max |old − reference| {max(far_old):.1e}, max |new − reference| {max(far_new):.1e}")
    pathlib.Path(out).write_text("\n".join(rows) + "\n")


def compare(old_path: str, new_path: str, summary: str | None, title: str | None = None) -> int:
    """Print (and write) the point-by-point comparison; the number of points beyond their error."""
    old, new = np.load(old_path), np.load(new_path)
    from impactmaps.maps.family.accuracy import STATUSES
    from impactmaps.maps.compute.points import METHODS

    zetas, lambdas = old["zeta"], old["lambda_"]
    lines = ["| structure | method (new) | points | CPU today [s] | CPU new [s] | F̄max differs | max abs(ΔF̄max) "
             "| beyond today's fmax_error | outside today's band | status changed | impacts changed |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    rows, beyond_total = ["structure,zeta,lambda,fmax_today,fmax_new,fmax_error_today,status_today,status_new,"
                          "impacts_today,impacts_new,method_new"], 0
    for name in STRUCTURES:
        o = {v: old[f"{name}/{v}"] for v in (*VARIABLES, "cpu")}
        n = {v: new[f"{name}/{v}"] for v in (*VARIABLES, "cpu")}
        diff = np.abs(n["fmax_normalised"] - o["fmax_normalised"])
        differs = ~((n["fmax_normalised"] == o["fmax_normalised"])
                    | (np.isnan(n["fmax_normalised"]) & np.isnan(o["fmax_normalised"])))
        beyond = differs & ~(diff <= np.maximum(o["fmax_error"], 1e-12))
        outside = differs & ~((n["fmax_normalised"] >= o["fmax_low"]) & (n["fmax_normalised"] <= o["fmax_high"]))
        status = n["status"] != o["status"]
        impacts = n["impacts"] != o["impacts"]
        beyond_total += int(beyond.sum())
        for code in [*np.unique(n["method"][np.isfinite(n["method"])].astype(int)), None]:
            sel = np.ones_like(differs) if code is None else n["method"] == code
            label = "all" if code is None else METHODS[code]
            lines.append(f"| {name} | {label} | {sel.sum()} | {o['cpu'][sel].sum():.1f} | {n['cpu'][sel].sum():.1f} "
                         f"| {(differs & sel).sum()} | {np.nanmax(np.where(sel, diff, 0.0)):.2e} "
                         f"| {(beyond & sel).sum()} | {(outside & sel).sum()} | {(status & sel).sum()} "
                         f"| {(impacts & sel).sum()} |")
        for i, j in zip(*np.nonzero(beyond | outside | status | impacts)):
            rows.append(f"{name},{zetas[j]:.6g},{lambdas[i]:.6g},{o['fmax_normalised'][i, j]:.9g},"
                        f"{n['fmax_normalised'][i, j]:.9g},{o['fmax_error'][i, j]:.3g},"
                        f"{STATUSES[int(o['status'][i, j])]},{STATUSES[int(n['status'][i, j])]},"
                        f"{int(o['impacts'][i, j])},{int(n['impacts'][i, j])},{METHODS[int(n['method'][i, j])]}")
    text = "\n".join(lines)
    print(text)
    print(f"points beyond today's stated error: {beyond_total}")
    if summary:
        pathlib.Path(f"{summary}.csv").write_text("\n".join(rows) + "\n")
        head = (f"# The plane point by point: `{pathlib.Path(new_path).name}` against today's "
                f"`{pathlib.Path(old_path).name}`\n\n" + (f"{title}\n\n" if title else "") +
                "`python validation/plane_equivalence.py --compare OLD NEW --summary plane_equivalence`"
                f" (grid {zetas.size} ζ × {lambdas.size} λ; CPU: `time.process_time` of each point, serial)\n\n")
        pathlib.Path(f"{summary}.md").write_text(head + text + f"\n\nPoints beyond today's stated error: "
                                                 f"**{beyond_total}**; those points and every status or impact change: "
                                                 f"`{pathlib.Path(summary).name}.csv`.\n")
    return beyond_total


def main(argv=None) -> int:
    from _script_options import parse

    def options(parser):
        parser.add_argument("--solve", action="store_true", help="solve the plane into --out")
        parser.add_argument("--root", default=str(ROOT), help="checkout whose impactmaps solves (default: this)")
        parser.add_argument("--out", help=".npz to write with --solve")
        parser.add_argument("--quick", action="store_true", help="a 40 × 10 grid")
        parser.add_argument("--contact-phase", choices=("auto", "exact", "sampled"),
                            help="solve with this ModalSettings.contact_phase (default: the settings' default)")
        parser.add_argument("--compare", nargs=2, metavar=("TODAY", "NEW"), help="two .npz files of --solve")
        parser.add_argument("--summary", help="write NAME.md and NAME.csv into --out-dir")
        parser.add_argument("--referee", metavar="CSV", help="with --compare: run a reference three levels finer "
                            "at the points the new plane moves beyond the old stated error, into this CSV (--out-dir)")
        parser.add_argument("--title", help="a sentence under the summary's heading: what NEW is")

    args = parse(__doc__.splitlines()[0], argv, default_out=ROOT / "validation", add_arguments=options)
    if args.smoke:  # a tiny plane, solved and compared with itself
        plane = args.out_dir / "plane_smoke.npz"
        solve(ROOT, plane, "smoke", args.contact_phase)
        return compare(plane, plane, args.out_dir / "plane_equivalence", "smoke run")
    if args.solve:
        if not args.out:
            raise SystemExit("--solve needs --out")
        solve(pathlib.Path(args.root).resolve(), args.out, "quick" if args.quick else "plane", args.contact_phase)
        return 0
    if args.compare:
        if args.referee:
            referee(*args.compare, args.out_dir / args.referee)
        summary = args.out_dir / args.summary if args.summary else None
        return 1 if compare(*args.compare, summary, args.title) else 0
    raise SystemExit("give --solve, --compare or --smoke")


if __name__ == "__main__":
    if main():
        sys.exit(1)
