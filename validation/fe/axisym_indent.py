"""Quasi-static load–unload of an elastic sphere on an elastic–perfectly plastic flat:
the axisymmetric CalculiX reference that calibrates the ``epp`` contact law.

The model (mesh, deck, post-processing) is :mod:`axisym_model`; this script runs its
convergence studies and the calibration sweep and writes

* ``results/axisym_runs.csv`` — one row per sweep run: the case (δ_m/δ_y, Y/E*, ν of the
  flat, E_sphere/E_flat, NLGEOM) and the normalised results F_m/F_y, δ_0/δ_m (approach
  where the unloading force vanishes), the residual dent on the axis δ_r/δ_m (the
  permanent indentation), e² = recovered/absorbed work, absorbed work/(F_y δ_y), the
  contact radius, ccx wall time;
* ``results/axisym_curves.csv`` — normalised loading/unloading curves of the largest δ_m
  of each material;
* ``results/axisym_convergence.json`` — the studies (elastic Hertz check, first yield,
  block size, mesh, penalty, hardening, increments, NLGEOM) with the reference case and
  the relative changes.

Run (a run takes ≈ 20 s of CPU; ``nice``, one ccx thread; several sweeps may run at
once, each case is claimed by a lock file)::

    OMP_NUM_THREADS=1 nohup nice -n 19 python validation/fe/axisym_indent.py --sweep base &
    (then --sweep nu, --sweep equal, --sweep deep, --study all)
    python validation/fe/axisym_indent.py --rebuild      # CSVs from the runs on disk

Small-strain cases deeper than ``SMALL_STRAIN_DEPTH`` × R are skipped by the sweeps and
run with NLGEOM by ``--sweep deep``.  The sweep is resumable: rows already in the CSV
are skipped.
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import axisym_model as am
import ccx_tools as ct

RUNS_CSV = ct.RESULTS / "axisym_runs.csv"
CURVES_CSV = ct.RESULTS / "axisym_curves.csv"
STUDY_JSON = ct.RESULTS / "axisym_convergence.json"
WORK = ct.WORK / "axisym"

X_M = np.round(np.logspace(0, 3, 8), 3)            # δ_m/δ_y: 1 … 1000, log-spaced
Y_OVER_ESTAR = (1e-3, 2.2e-3, 4.6e-3, 1e-2)
MAX_DEPTH = 0.1                                     # largest δ_m/R of the sweep
# the sweeps: name -> (Y/E* values, ν of the flat, E_sphere/E_flat, δ_m/δ_y values)
SWEEPS = {"base": (Y_OVER_ESTAR, 0.3, 1e3, X_M),
          "nu": ((2.2e-3,), 0.45, 1e3, X_M),
          "equal": ((2.2e-3,), 0.3, 1.0, X_M[1::2]),
          "steel-al": ((2.2e-3,), 0.3, 3.0, X_M[1::2])}
KEYS = ("x_m", "y_over_estar", "nu_flat", "stiffness_ratio", "nlgeom")
COLUMNS = KEYS + ("delta_m_over_R", "F_over_Fy", "d0_over_dm", "dent_over_dm", "e2",
                  "absorbed_over_FyDy", "contact_radius_over_ay", "tail_exponent",
                  "n_elements", "wall_s")
REFERENCE = am.Case(x_m=100.0, y_over_estar=2.2e-3)


def job_name(case: am.Case) -> str:
    return (f"x{case.x_m:g}_y{case.y_over_estar:g}_nu{case.nu_flat:g}_k{case.stiffness_ratio:g}"
            f"_p{case.per_radius:g}_b{case.block:g}_pen{case.penalty:g}_h{case.hardening:g}"
            f"_n{case.n_load}-{case.n_unload}_{case.element}{'_nl' if case.nlgeom else ''}"
            f"{'' if case.plastic else '_el'}{'_map' if case.mapped else ''}")


def run(case: am.Case, reuse=True):
    os.environ.setdefault("FE_THREADS", "1")
    rec, curve = am.run(case, WORK, job_name(case), reuse=reuse)
    rec["delta_m_over_R"] = case.delta_m / case.radius
    return rec, curve


#: Largest δ_m/R at which small strain is kept: beyond it geometric nonlinearity moves
#: F_m or e² by more than 1 % (the nlgeom study) and the runs are repeated with NLGEOM.
SMALL_STRAIN_DEPTH = 0.012


def sweep_cases(name):
    if name == "deep":      # the cases of the other sweeps deeper than small strain allows
        deep = [replace(case, nlgeom=True) for other in ("base", "nu", "equal")
                for case in sweep_cases(other) if case.delta_m > SMALL_STRAIN_DEPTH * case.radius]
        yield from sorted(deep, key=lambda c: c.delta_m / c.radius)
        return
    ys, nu, ratio, xs = SWEEPS[name]
    for y in ys:
        for x in xs:
            case = am.Case(x_m=float(x), y_over_estar=y, nu_flat=nu, stiffness_ratio=ratio)
            if case.delta_m <= MAX_DEPTH * case.radius * (1 + 1e-9):
                yield case


def done_keys():
    if not RUNS_CSV.exists():
        return set()
    with RUNS_CSV.open() as f:
        return {(float(f"{float(row['x_m']):.5g}"), float(f"{float(row['y_over_estar']):.5g}"),
                 float(row["nu_flat"]), float(row["stiffness_ratio"]), row["nlgeom"] == "True")
                for row in csv.DictReader(f)}


def key_of(case):
    return (float(f"{case.x_m:.5g}"), float(f"{case.y_over_estar:.5g}"), float(case.nu_flat),
            float(case.stiffness_ratio), bool(case.nlgeom))


def append_row(rec):
    new = not RUNS_CSV.exists()
    with RUNS_CSV.open("a", newline="") as f:
        w = csv.DictWriter(f, fieldnames=COLUMNS, extrasaction="ignore")
        if new:
            w.writeheader()
        w.writerow({k: (f"{rec[k]:.6g}" if isinstance(rec.get(k), float) else rec.get(k, ""))
                    for k in COLUMNS})


def append_curve(case, curve):
    new = not CURVES_CSV.exists()
    with CURVES_CSV.open("a") as f:
        if new:
            f.write("x_m,y_over_estar,nu_flat,stiffness_ratio,loading,delta_over_dy,F_over_Fy\n")
        for d, F, load in zip(curve["delta"], curve["force"], curve["loading"]):
            if F < 0 or (not load and F <= 0):
                continue
            f.write(f"{case.x_m:g},{case.y_over_estar:g},{case.nu_flat:g},"
                    f"{case.stiffness_ratio:g},{int(load)},{d / case.delta_y:.6g},"
                    f"{F / case.force_y:.6g}\n")


def claim(case) -> bool:
    """True if this process may run ``case``: not in the CSV and no other process
    holds its lock file (several sweeps may run at once)."""
    if key_of(case) in done_keys():
        return False
    WORK.mkdir(parents=True, exist_ok=True)
    try:
        os.close(os.open(WORK / f"{job_name(case)}.lock", os.O_CREAT | os.O_EXCL))
    except FileExistsError:
        return False
    return True


def _largest(cases) -> dict:
    """The last of ``cases`` (the deepest, in sweep order) of each material (Y/E*, ν, E ratio)."""
    return {(case.y_over_estar, case.nu_flat, case.stiffness_ratio): case for case in cases}


def _append(case, rec, curve, largest) -> None:
    """Append a finished run's row, and its curve if it is its material's deepest case."""
    append_row(rec)
    if case is largest[(case.y_over_estar, case.nu_flat, case.stiffness_ratio)]:
        append_curve(case, curve)


def rebuild():
    """Rewrite the CSVs from the runs already on disk (no ccx): every sweep's cases whose
    run finished are re-read and re-summarised."""
    for path in (RUNS_CSV, CURVES_CSV):
        path.unlink(missing_ok=True)
    for name in ("base", "nu", "equal", "deep"):
        cases = list(sweep_cases(name))
        largest = _largest(cases)
        for case in cases:
            if not (WORK / f"{job_name(case)}.log").exists():
                continue
            try:
                rec, curve = run(case, reuse=True)
            except RuntimeError as err:
                print(f"FAILED {job_name(case)}: {str(err).splitlines()[0]}", flush=True)
                continue
            _append(case, rec, curve, largest)


def sweep(name, reverse=False):
    ct.RESULTS.mkdir(parents=True, exist_ok=True)
    cases = list(sweep_cases(name))
    largest = _largest(cases)
    for case in (cases[::-1] if reverse else cases):
        if not case.nlgeom and case.delta_m > SMALL_STRAIN_DEPTH * case.radius:
            continue        # the deep sweep runs it with NLGEOM
        if not claim(case):
            continue
        try:
            rec, curve = run(case)
        except RuntimeError as err:
            print(f"FAILED {job_name(case)}: {str(err)[-300:]}", flush=True)
            continue
        _append(case, rec, curve, largest)
        print(json.dumps({k: rec.get(k) for k in COLUMNS}), flush=True)


# -- convergence studies ---------------------------------------------------------
QUANTITIES = ("F_over_Fy", "d0_over_dm", "dent_over_dm", "e2")


def compare(ref, other):
    """Relative change of each quantity of ``other`` against ``ref``."""
    return {q: (other[q] / ref[q] - 1.0) for q in QUANTITIES
            if q in ref and q in other and ref[q]}


def study_variants(name):
    base = REFERENCE
    big = am.Case(x_m=1000.0, y_over_estar=1e-3)
    if name == "size":
        return base, [replace(base, block=b) for b in (20.0, 80.0)]
    if name == "mesh":
        return base, [replace(base, per_radius=p) for p in (4.0, 9.0, 12.0)]
    if name == "mesh1000":
        return big, [replace(big, per_radius=9.0)]
    if name == "mesh7":
        small = am.Case(x_m=7.197, y_over_estar=2.2e-3)
        return small, [replace(small, per_radius=9.0)]
    if name == "penalty":
        return base, [replace(base, penalty=p) for p in (8e-3, 5e-4)]
    if name == "hardening":
        return base, [replace(base, hardening=h) for h in (0.1, 0.01)]
    if name == "increments":
        return base, [replace(base, n_load=2 * base.n_load, n_unload=2 * base.n_unload)]
    if name == "increments1000":
        return big, [replace(big, n_load=2 * big.n_load, n_unload=2 * big.n_unload)]
    if name == "nlgeom":
        cases = [am.Case(x_m=x, y_over_estar=1e-2) for x in (7.197, 19.307, 51.795)]
        return None, [(c, replace(c, nlgeom=True)) for c in cases]
    raise ValueError(name)


def elastic_check():
    """Loading curve of an elastic flat against Hertz, rigid and equal spheres."""
    out = {}
    for ratio in (1e3, 1.0):
        case = am.Case(x_m=4.0, y_over_estar=2.2e-3, stiffness_ratio=ratio, plastic=False)
        rec, curve = run(case)
        d, F = curve["delta"], curve["force"]
        sel = curve["loading"] & (d > 0.1 * case.delta_m)
        hertz = 4 / 3 * case.e_star * np.sqrt(case.radius) * d[sel] ** 1.5
        err = F[sel] / hertz - 1.0
        out[f"stiffness_ratio_{ratio:g}"] = dict(
            max_abs_error=float(np.max(np.abs(err))), error_at_max=float(err[-1]),
            recovered_over_absorbed=rec["e2"], wall_s=rec["wall_s"])
    return out


def first_yield():
    """Elastic flat loaded to 2 δ_y: the largest von Mises stress below the contact gives
    the Hertz peak pressure at first yield: p0 ∝ δ^{1/2} is 1.6 √2 Y at 2 δ_y, so
    c_y^FE = 1.6 √2 Y / σ_vM,max."""
    out = {}
    for nu in (0.3, 0.45):
        case = am.Case(x_m=2.0, y_over_estar=2.2e-3, nu_flat=nu, plastic=False,
                       print_stress=True)
        rec, _ = run(case)
        text = (WORK / f"{job_name(case)}.dat").read_text()
        sigma = am.max_von_mises(text)
        out[f"nu_{nu:g}"] = dict(max_von_mises_over_Y=sigma / case.yield_strength,
                                 c_y_fe=1.6 * np.sqrt(2.0) * case.yield_strength / sigma,
                                 wall_s=rec["wall_s"])
    return out


def committed_unstructured(data, case):
    """The committed unstructured-mesh result of ``case`` (a sweep row of RUNS_CSV or the
    reference of the mesh study), or None."""
    if case == REFERENCE and "mesh" in data:
        return data["mesh"]["reference"]
    if RUNS_CSV.exists():
        with RUNS_CSV.open() as f:
            for row in csv.DictReader(f):
                if (np.isclose(float(row["x_m"]), case.x_m) and np.isclose(float(row["y_over_estar"]), case.y_over_estar)
                        and float(row["nu_flat"]) == case.nu_flat and float(row["stiffness_ratio"]) == case.stiffness_ratio
                        and row["nlgeom"] == "False"):
                    return {q: float(row[q]) for q in QUANTITIES}
    return None


def studies(names):
    data = json.loads(STUDY_JSON.read_text()) if STUDY_JSON.exists() else {}
    for name in names:
        if name == "elastic":
            data[name] = elastic_check()
        elif name == "firstyield":
            data[name] = first_yield()
        elif name == "mesh12":
            rows = []
            for x in (7.197, 51.795, 372.759):
                case = am.Case(x_m=x, y_over_estar=1e-3)
                a, b = run(case)[0], run(replace(case, per_radius=12.0))[0]
                rows.append(dict(x_m=x, y_over_estar=1e-3, per_radius=[6.0, 12.0],
                                 change=compare(a, b), wall_s=[a["wall_s"], b["wall_s"]]))
            data[name] = rows
        elif name == "mapped":
            rows = []
            for x, y, pers in ((100.0, 2.2e-3, (6.0, 12.0, 9.0)), (372.759, 1e-3, (6.0, 12.0)),
                               (7.197, 1e-3, (6.0, 12.0))):
                base = am.Case(x_m=x, y_over_estar=y)
                mapped = [run(replace(base, mapped=True, per_radius=p))[0] for p in pers]
                free = committed_unstructured(data, base) or run(base)[0]
                rows.append(dict(
                    x_m=x, y_over_estar=y, per_radius=list(pers),
                    mapped={q: [m[q] for m in mapped] for q in QUANTITIES},
                    unstructured_6={q: free[q] for q in QUANTITIES},
                    mapped_over_unstructured_6=[compare(free, m) for m in mapped],
                    refinement_change=[compare(mapped[0], m) for m in mapped[1:]],
                    n_elements=[m["n_elements"] for m in mapped],
                    wall_s=[m["wall_s"] for m in mapped]))
                data[name] = rows
                STUDY_JSON.write_text(json.dumps(data, indent=1))
            data[name] = rows
        elif name == "nlgeom":
            rows = []
            for small, large in study_variants(name)[1]:
                try:
                    a, b = run(small)[0], run(large)[0]
                except RuntimeError as err:
                    rows.append(dict(x_m=small.x_m, y_over_estar=small.y_over_estar,
                                     delta_m_over_R=small.delta_m / small.radius,
                                     failed=str(err).splitlines()[0]))
                    continue
                rows.append(dict(x_m=small.x_m, y_over_estar=small.y_over_estar,
                                 delta_m_over_R=small.delta_m / small.radius,
                                 small_strain={q: a[q] for q in QUANTITIES if q in a},
                                 nlgeom_change=compare(a, b), wall_s=[a["wall_s"], b["wall_s"]]))
            data[name] = rows
        else:
            ref_case, variants = study_variants(name)
            ref = run(ref_case)[0]
            data[name] = dict(
                reference={k: ref[k] for k in QUANTITIES + ("x_m", "y_over_estar", "per_radius",
                                                             "block", "penalty", "hardening",
                                                             "n_load", "n_unload", "n_elements",
                                                             "wall_s") if k in ref},
                variants=[])
            for case in variants:
                rec = run(case)[0]
                changed = {k: getattr(case, k) for k in ("per_radius", "block", "penalty",
                                                          "hardening", "n_load", "n_unload")
                           if getattr(case, k) != getattr(ref_case, k)}
                data[name]["variants"].append(dict(changed=changed, n_elements=rec["n_elements"],
                                                   wall_s=rec["wall_s"],
                                                   change=compare(ref, rec)))
        data["ccx_version"] = ct.ccx_version()
        STUDY_JSON.write_text(json.dumps(data, indent=1))
        print(name, json.dumps(data[name], indent=1), flush=True)


ALL_STUDIES = ("elastic", "firstyield", "increments1000", "mesh7", "mesh12", "size", "mesh", "penalty", "hardening", "increments", "mesh1000",
               "nlgeom", "mapped")


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--sweep", choices=(*SWEEPS, "deep"))
    p.add_argument("--study", nargs="+", choices=ALL_STUDIES + ("all",))
    p.add_argument("--reverse", action="store_true", help="run the sweep's cases last first")
    p.add_argument("--rebuild", action="store_true",
                   help="rewrite the CSVs from the finished runs on disk (no ccx)")
    a = p.parse_args(argv)
    if a.study:
        studies(ALL_STUDIES if "all" in a.study else a.study)
    if a.sweep:
        sweep(a.sweep, a.reverse)
    if a.rebuild:
        rebuild()


if __name__ == "__main__":
    main()
