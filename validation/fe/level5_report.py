"""Level 5, report: tables and figure of the committed runs; harvest of a stopped run.

``python validation/fe/level5_report.py table`` prints the markdown tables of
validation/fe/README.md (Level 5) and draws ``results/level5_beam_plastic.png``;
``python validation/fe/level5_report.py harvest --tag <tag> --mesh <mesh>`` stores the
history so far of an FE run that did not reach the end (``results/level5_fe_<tag>_partial.csv``).
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import ccx_tools as ct
from level5_beam_plastic import (
    FE_END,
    FORCE_CSV,
    HEIGHT,
    LENGTH,
    MESHES,
    PAIRS,
    fd_prescribed,
    fe_reference,
    load,
    prescribed_force,
    quarter_mesh,
    save,
    section_weights,
)


def history(tag):
    """(t, w) of an FE run: its full CSV, else the harvested partial one, else None."""
    for name, column in ((f"level5_fe_{tag}.csv", 2), (f"level5_fe_{tag}_partial.csv", 1)):
        path = ct.RESULTS / name
        if path.exists():
            h = np.loadtxt(path, delimiter=",", skiprows=1)
            return h[:, 0], h[:, column]
    return None


def compare(coarser, finer):
    """Over the common time span: largest |finer − coarser| / max|finer|, and the
    change of the maximum deflection (finer/coarser − 1)."""
    a, b = history(coarser), history(finer)
    if a is None or b is None:
        return None
    end = min(a[0][-1], b[0][-1])
    t = b[0][b[0] <= end]
    wa, wb = np.interp(t, *a), b[1][b[0] <= end]
    return {"up_to_s": float(end), "max_history_difference": float(np.abs(wb - wa).max() / wb.max()),
            "max_deflection_change": float(wb.max() / wa[: len(t)].max() - 1)}


def table():
    """The tables of README Level 5, the ``convergence`` entry of the JSON, the figure."""
    data = load()
    runs = data.get("fe_runs", {})
    ref, changes = fe_reference(runs)
    convergence = {name: compare(*pair) for name, pair in PAIRS.items()}
    convergence["patch_end_values"] = changes.get("patch")
    data["convergence"] = convergence
    save(data)
    print("| FE run | nodes | Δt [µs] | c [mm] | load | peak w [mm] | permanent w [mm] | "
          "plastic half-length [mm] | ccx wall [s] |\n|---|---|---|---|---|---|---|---|---|")
    for tag, r in runs.items():
        load_kind = "smoothed 100 µs" if r.get("load_smoothing_window_s") else \
            ("FD force, wide-section model" if r.get("force") == "wide" else "FD force")
        step = f"≤ {r['time_step_s'] * 1e6:g} auto" if r.get("automatic_increments") else \
            f"{r['time_step_s'] * 1e6:g}"
        perm = f"{r['permanent_deflection_m'] * 1e3:.4f}" if r["dynamic_end_s"] >= FE_END - 1e-9 \
            else f"(unloaded at {r['dynamic_end_s'] * 1e3:g} ms)"
        print(f"| {tag} | {r['n_nodes']} | {step} | {r['patch_half_length_m'] * 1e3:.3g} | "
              f"{load_kind} | {r['peak_deflection_m'] * 1e3:.4f} | "
              f"{perm} | "
              f"{(r['plastic_half_length_m'] or 0) * 1e3:.0f} | {r['ccx_wall_time_s']:.0f} |")
    for tag, r in data.get("partial_runs", {}).items():
        print(f"| {tag} (stopped at {r['reached_s'] * 1e3:.2f} ms) | {r['n_nodes']} | | | | "
              f"(max so far {r['max_so_far_m'] * 1e3:.4f}) | | | |")
    print("\nconvergence:", json.dumps(convergence, indent=1))
    print("\n| FD grid N_l×N_h | coupled: peak w [mm] | permanent w [mm] | plastic half-length "
          "[mm] | prescribed load: peak w [mm] |\n|---|---|---|---|---|")
    for key, r in data["fd_grid_study"].items():
        p = data["fd_prescribed_grid_study"].get(key, {}).get("peak_deflection_m")
        print(f"| {key} | {r['peak_deflection_m'] * 1e3:.4f} | "
              f"{r['permanent_deflection_m'] * 1e3:.4f} | {r['plastic_half_length_m'] * 1e3:.0f}"
              f" | {'' if p is None else f'{p * 1e3:.4f}'} |")
    figure(data, runs)


def figure(data, runs):
    """``results/level5_beam_plastic.png``: the force; FD and FE mid-span deflections."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (a0, a1) = plt.subplots(2, 1, figsize=(8, 6.5), sharex=True)
    t, f, w = np.loadtxt(FORCE_CSV, delimiter=",", skiprows=1, unpack=True)
    a0.plot(t * 1e3, f / 1e3, lw=0.6, color="k")
    a0.set_ylabel("prescribed force [kN]")
    times, force = prescribed_force()
    tf, wf = fd_prescribed(times, force, 400, 40)
    a1.plot(tf * 1e3, wf * 1e3, color="k", lw=1.6, label="FD beam 400×40 (uniaxial section), same force")
    tw, ww = fd_prescribed(times, force, width_constraint=True)
    a1.plot(tw * 1e3, ww * 1e3, color="m", lw=1.8, ls="-.", label="FD beam 200×10, wide-section model, same force")
    a1.plot(t * 1e3, w * 1e3, color="0.5", lw=1.0, ls="--", label="FD beam 200×10 (coupled)")
    for tag in list(runs) + list(data.get("partial_runs", {})):
        h = history(tag)
        if h is not None and "smooth" not in tag and runs.get(tag, {}).get("force") != "wide":
            a1.plot(h[0] * 1e3, h[1] * 1e3, lw=0.9, label=f"3D {tag}")
    a1.axhline(data["fd_impact"]["permanent_deflection_m"] * 1e3, color="k", ls=":", lw=0.8,
               label="FD permanent (coupled 200×10)")
    for tag, r in runs.items():
        if "smooth" not in tag and r.get("force") != "wide" and r["dynamic_end_s"] >= FE_END - 1e-9:
            a1.plot([FE_END * 1e3 + 0.2], [r["permanent_deflection_m"] * 1e3], "o", ms=4)
    a1.set_xlabel("time [ms]")
    a1.set_ylabel("mid-span deflection [mm]")
    a1.set_xlim(0, FE_END * 1e3 + 0.5)
    a1.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(ct.RESULTS / "level5_beam_plastic.png", dpi=110)


def harvest(args):
    """The history so far of an FE run still going (or stopped) from its .dat file:
    ``results/level5_fe_<tag>_partial.csv`` and a ``partial_runs`` entry."""
    patch = args.patch * 1e-3 if args.patch else HEIGHT / 8
    mesh, _ = quarter_mesh(patch=patch, **MESHES[args.mesh])
    text = (ct.WORK / "level5" / f"level5_{args.tag}.dat").read_text()
    blocks = ct.parse_node_prints(text, "MID")
    t_fe = ct.parse_node_print_times(text, "MID")
    n = min(len(blocks), len(t_fe)) - 1          # the last block may be incomplete
    ids = mesh.nodes_where(np.isclose(mesh.coords[:, 0], 0.5 * LENGTH, atol=1e-9))
    mean = np.array([[-blocks[j][i][2] for i in ids] for j in range(n)]) @ section_weights(mesh, ids)
    t_fe = t_fe[:n]
    np.savetxt(ct.RESULTS / f"level5_fe_{args.tag}_partial.csv", np.column_stack([t_fe, mean]),
               delimiter=",", fmt="%.6e", comments="", header="time_s,fe_section_mean_m")
    data = load()
    data.setdefault("partial_runs", {})[args.tag] = dict(
        mesh=args.mesh, **MESHES[args.mesh], n_nodes=len(mesh.coords), patch_half_length_m=patch,
        reached_s=float(t_fe[-1]), max_so_far_m=float(mean.max()),
        note="run stopped before the end of the dynamic step (machine time); history so far")
    save(data)
    print(args.tag, "reached", t_fe[-1], "max", mean.max())


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = p.add_subparsers(dest="what", required=True)
    sub.add_parser("table")
    hv = sub.add_parser("harvest")
    hv.add_argument("--tag", required=True)
    hv.add_argument("--mesh", required=True, choices=sorted(MESHES))
    hv.add_argument("--patch", type=float, default=None)
    a = p.parse_args(argv)
    if a.what == "table":
        table()
    else:
        harvest(a)


if __name__ == "__main__":
    main()
