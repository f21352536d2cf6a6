"""What each lever of issue 30 step 3 would give on the whole (ζ, λ) plane, measured.

Workload: the grid of ``benchmarks/studies/bench_plane.py`` (200 × 50 log grid over
[1e-3, 1e3]², ``beam-ss-euler`` and ``plate-ssss-kirchhoff``), every point solved serially
in this process as a sweep's worker solves it (:func:`impactmaps.maps.compute.points.solve_map_points`,
default settings and error control), with every modal run of a point recorded: its kind
(base, refinement 1 or 2, perturbed), F̄max, impacts and CPU (``time.process_time``). Then,
at every modal point, one extra run a level *coarser* than the base (cut-off, patch
cut-off and mode floor /2, ``time_step_ratio`` and ``resolve_ratio`` ×2,
``force_resolution`` ×4: the step about doubled). From these, with no other run:

1. the CPU by status and kind of run, in runs over 400 modes (the sampled contact phase)
   and at multi-impact points;
2. lever (i), the infinite-structure answer where the first reflection returns after the
   contact and no re-impact can follow: the criterion τ_r ≥ τ_c + (τ_c + Ā)/ē (τ_r =
   ``reflection_time`` ω d²/c, τ_c and ē the infinite structure's contact time and the
   impactor's speed away from it at separation (none: no answer), Ā = sqrt((1 − ē²)/λ)
   the Cauchy–Schwarz bound of the target's free vibration with the energy the impact
   left in it, τ_c bounding the impactor's travel during the contact), its points, their CPU today, and |F̄∞ − F̄max today| against
   the point's stated ``fmax_error``;
3. lever (iii), a coarser level before the base run (the point settles at (coarse, base)
   when they agree within the tolerance with the same impacts; the stored value is then
   the base run, its error |base − coarse|): its CPU, and where that error is smaller
   than |base − refinement 1| (an error estimate that does not bound the error);
4. skipping refinement 2 at points unsettled after refinement 1 with ≥ 5 impacts
   (they become ``sensitive`` at refinement 1): CPU saved, status changes, and where
   refinement 2's value falls outside the band kept (base, refinement 1, refinement 1 ±
   max(its change, tolerance); the perturbed runs, not recorded, can only widen it).

Run: ``python benchmarks/studies/plane_levers.py [--quick] [--root DIR] [--out benchmarks/studies/RESULTS_plane_levers.md]``
(``--root``: the checkout whose impactmaps runs; ``--data FILE.npz`` keeps the runs).
"""

from __future__ import annotations

import argparse
import datetime
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
STRUCTURES = ("beam-ss-euler", "plate-ssss-kirchhoff")
KINDS = ("base", "refinement 1", "refinement 2", "perturbed")
#: Runs over this many modes take the sampled contact phase (modal_run.COUPLED_MAX_MODES).
SAMPLED_ABOVE = 400
SKIP_IMPACTS = 5


def coarsened(settings):
    """Settings one level coarser than ``settings`` (module docstring, item 3)."""
    return replace(settings, cutoff_ratio=settings.cutoff_ratio / 2, patch_cutoff_ratio=settings.patch_cutoff_ratio / 2,
                   min_modes=max(settings.min_modes // 2, 1), time_step_ratio=min(2 * settings.time_step_ratio, 1.0),
                   resolve_ratio=min(2 * settings.resolve_ratio, 2.0),
                   force_resolution=min(4 * settings.force_resolution, 1e-2))


def solve_plane(name: str, zetas, lambdas) -> dict:
    """Every point of ``name`` with its runs: arrays over (λ, ζ) (module docstring)."""
    from impactmaps.maps.compute import points
    from impactmaps.maps.compute.linear_points import LINEAR
    from impactmaps.maps.family.structures import structure_from_name
    from impactmaps.solvers.modal import ModalSettings
    from impactmaps.maps.family.structures import MAX_MODES
    from impactmaps.solvers.mode_budget import frequency_cap

    base = ModalSettings()
    levels = {base: 0, base.refined(): 1, base.refined().refined(): 2}
    record = []
    original = points.table_runner

    def recording_runner(*args, **kwargs):
        inner = original(*args, **kwargs)

        def run(settings, zeta_factor):
            start = time.process_time()
            result = inner(settings, zeta_factor)
            kind = levels.get(settings, 3) if zeta_factor == 1.0 else 3
            record.append((kind, result.fmax_normalised, result.impacts, result.n_modes, time.process_time() - start))
            return result
        return run

    shape = (lambdas.size, zetas.size)
    out = {key: np.full(shape + (3,), np.nan) for key in ("F", "impacts", "modes")} | {
        "cpu": np.zeros(shape + (4,)), "coarse_cpu": np.zeros(shape), "coarse_F": np.full(shape, np.nan),
        "coarse_impacts": np.full(shape, np.nan)} | {key: np.full(shape, np.nan) for key in (
            "status", "method", "fmax", "fmax_error", "fmax_low", "fmax_high", "reflection")}
    structure = structure_from_name(name)
    target = structure.build()
    table, cap = points.basis_table(structure, base.min_modes), frequency_cap(structure.build(), MAX_MODES)
    coarse = coarsened(base)
    points.table_runner = recording_runner
    try:
        points.solve_map_points(LINEAR, structure, [(1.0, 1.0)], base)  # warm: tables, kernels
        for i, lam in enumerate(lambdas):
            grid = [(float(z), float(lam)) for z in zetas]
            for j, (point, realised) in enumerate(zip(grid, LINEAR.realise_points(target, grid))):
                record.clear()
                row = points.solve_map_points(LINEAR, structure, [point], base)[0]
                for key, var in (("status", "status"), ("method", "method"), ("fmax", "fmax_normalised"),
                                 ("fmax_error", "fmax_error"), ("fmax_low", "fmax_low"),
                                 ("fmax_high", "fmax_high"), ("reflection", "reflection_time_normalised")):
                    out[key][i, j] = row[var]
                for kind, fmax, impacts, modes, cpu in record:
                    out["cpu"][i, j, kind] += cpu
                    if kind < 3:
                        out["F"][i, j, kind], out["impacts"][i, j, kind], out["modes"][i, j, kind] = fmax, impacts, modes
                if row["method"] == 0:
                    run = original(LINEAR, target, table, cap, point, realised, [])
                    start = time.process_time()
                    result = run(coarse, 1.0)
                    out["coarse_cpu"][i, j] = time.process_time() - start
                    out["coarse_F"][i, j], out["coarse_impacts"][i, j] = result.fmax_normalised, result.impacts
    finally:
        points.table_runner = original
    return out


def infinite_criterion(name: str, zetas, lambdas, reflection):
    """(peak F̄∞ per ζ, mask over (λ, ζ) of lever (i)'s criterion) (module docstring, item 2)."""
    from impactmaps.targets import target_class

    impacts = [target_class(name.split("-")[0]).infinite_structure_impact(float(z)) for z in zetas]
    peak = np.array([float(i.peak_force) for i in impacts])
    contact = np.array([float(i.contact_time) for i in impacts])
    # the impactor's speed away from the structure at separation (on the infinite beam above
    # ζ ≈ 0.3 it still moves towards it, the beam receding faster: it follows, and re-impacts)
    rebound = -np.array([float(i.rebound_velocity) for i in impacts])
    rebound[~(rebound > 0.0)] = np.nan
    with np.errstate(invalid="ignore", divide="ignore"):
        bound = np.sqrt((1.0 - rebound[None, :] ** 2) / lambdas[:, None])
        needed = contact[None, :] + (contact[None, :] + bound) / rebound[None, :]
        return peak, np.isfinite(needed) & (reflection >= needed)


def analyse(name: str, d: dict, zetas, lambdas, tolerance: float = 1e-3) -> list[str]:
    """Markdown lines of the four items of the module docstring for one structure."""
    cpu, status, modal = d["cpu"], d["status"], d["method"] == 0
    total = cpu.sum()
    lines = [f"### {name}: {total:.1f} CPU-s in the runs ({int(modal.sum())} modal points)", "",
             "| status | points | base | refinement 1 | refinement 2 | perturbed |", "|---|---|---|---|---|---|"]
    for code, label in enumerate(("converged", "refined", "sensitive", "asymptotic")):
        sel = status == code
        lines.append(f"| {label} | {int(sel.sum())} | " + " | ".join(f"{cpu[sel][:, k].sum():.2f}" for k in range(4)) + " |")
    sampled = sum(cpu[..., k][d["modes"][..., k] > SAMPLED_ABOVE].sum() for k in range(3))
    multi = d["impacts"][..., 0] > 1
    lines += ["", f"- runs over {SAMPLED_ABOVE} modes (sampled contact phase): {sampled:.1f} CPU-s "
              f"({100 * sampled / total:.0f} %); multi-impact points: {cpu[multi].sum():.1f} CPU-s "
              f"({100 * cpu[multi].sum() / total:.0f} %, {int(multi.sum())} points)"]
    # (i) the infinite-structure answer
    peak, take = infinite_criterion(name, zetas, lambdas, d["reflection"])
    take &= modal
    diff = np.abs(peak[None, :] - d["fmax"])
    beyond = take & (diff > np.maximum(d["fmax_error"], 1e-12))
    lines.append(f"- (i) infinite structure where no re-impact can follow: {int(take.sum())} points, "
                 f"{cpu[take].sum():.1f} CPU-s today ({100 * cpu[take].sum() / total:.0f} %); "
                 f"max |F̄∞ − F̄max| {np.max(diff[take], initial=0):.1e}; beyond the stated error at "
                 f"{int(beyond.sum())}, beyond 1e-4 at {int((take & (diff > 1e-4)).sum())}")
    # (iii) a coarser level first
    f_base, coarse = d["F"][..., 0], d["coarse_F"]
    settles = modal & (np.abs(coarse - f_base) <= tolerance) & (d["coarse_impacts"] == d["impacts"][..., 0])
    new = np.where(settles, d["coarse_cpu"] + cpu[..., 0], d["coarse_cpu"] + cpu.sum(axis=2))
    short = settles & (np.abs(coarse - f_base) < np.abs(d["F"][..., 1] - f_base))
    slowest = np.unravel_index(np.argmax(d["coarse_cpu"]), d["coarse_cpu"].shape)
    lines.append(f"- (iii) a coarser level first: settles at {int(settles.sum())} points; CPU {new.sum():.1f} against "
                 f"{total:.1f} (the coarse runs {d['coarse_cpu'].sum():.1f}, the slowest {d['coarse_cpu'].max():.1f} s at "
                 f"ζ = {zetas[slowest[1]]:.3g}, λ = {lambdas[slowest[0]]:.3g}); its error |base − coarse| is smaller "
                 f"than |base − refinement 1| at {int(short.sum())} of them")
    # skipping refinement 2 at likely sensitive points
    unsettled = (status == 1) | (status == 2)
    skip = unsettled & (d["impacts"][..., 1] >= SKIP_IMPACTS)
    width = np.maximum(np.abs(d["F"][..., 1] - f_base), tolerance)
    low = np.minimum(np.minimum(f_base, d["F"][..., 1]), d["F"][..., 1] - width)
    high = np.maximum(np.maximum(f_base, d["F"][..., 1]), d["F"][..., 1] + width)
    outside = skip & ~((d["F"][..., 2] >= low) & (d["F"][..., 2] <= high))
    extra = 5 * cpu[skip & (status == 1)][:, 0].sum()
    lines.append(f"- skip refinement 2 after refinement 1 with ≥ {SKIP_IMPACTS} impacts: {int(skip.sum())} points "
                 f"({int((skip & (status == 1)).sum())} refined → sensitive), saves {cpu[skip][:, 2].sum():.1f} CPU-s less "
                 f"~{extra:.1f} for the new sensitive points' perturbed runs; refinement 2 outside the band kept at "
                 f"{int(outside.sum())}")
    return lines


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="a 40 × 10 grid")
    parser.add_argument("--root", help="the checkout whose impactmaps runs (default: this one)")
    parser.add_argument("--data", help="keep every point's runs in this .npz")
    parser.add_argument("--out", default=str(ROOT / "benchmarks" / "studies" / "RESULTS_plane_levers.md"))
    args = parser.parse_args(argv)
    sys.path.insert(0, str(pathlib.Path(args.root).resolve() if args.root else ROOT))
    zetas, lambdas = (np.geomspace(1e-3, 1e3, 40), np.geomspace(1e-3, 1e3, 10)) if args.quick else (
        np.geomspace(1e-3, 1e3, 200), np.geomspace(1e-3, 1e3, 50))
    load = os.getloadavg()[0]
    lines = [f"# What each lever of issue 30 step 3 would give: {zetas.size} × {lambdas.size} points per structure", "",
             f"`python benchmarks/studies/plane_levers.py {' '.join(sys.argv[1:] if argv is None else argv)}`".replace(" `", "`"),
             f"run {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC, serially in one process, CPU "
             f"time (`time.process_time`) of each run; load average at the start {load:.1f}", ""]
    stored = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for name in STRUCTURES:
            data = solve_plane(name, zetas, lambdas)
            stored |= {f"{name}/{key}": value for key, value in data.items()}
            lines += analyse(name, data, zetas, lambdas) + [""]
            print("\n".join(lines[-8:]), flush=True)
    lines.append(f"Load average at the end: {os.getloadavg()[0]:.1f}.")
    if args.data:
        np.savez(args.data, zeta=zetas, lambda_=lambdas, **stored)
    pathlib.Path(args.out).write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
