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
    fe_reference,
    load,
    quarter_mesh,
    save,
    section_weights,
)


def table():
    """Markdown table of the committed runs against the FD beam, and the figure."""
    data = load()
    fd, runs = data["fd_impact"], data["fe_runs"]
    rows = ["| FE run | nodes | Δt [µs] | patch c [mm] | peak w [mm] | FD − FE | "
            "permanent w [mm] | FD − FE | plastic half-length [mm] | wall [s] |",
            "|---|---|---|---|---|---|---|---|---|---|"]
    for tag, r in runs.items():
        rows.append(
            f"| {tag} | {r['n_nodes']} | {r['time_step_s'] * 1e6:g} | "
            f"{r['patch_half_length_m'] * 1e3:.3g} | {r['peak_deflection_m'] * 1e3:.4f} | "
            f"{(fd['peak_deflection_m'] / r['peak_deflection_m'] - 1) * 100:+.2f} % | "
            f"{r['permanent_deflection_m'] * 1e3:.4f} | "
            f"{(fd['permanent_deflection_m'] / r['permanent_deflection_m'] - 1) * 100:+.2f} % | "
            f"{(r['plastic_half_length_m'] or 0) * 1e3:.0f} | {r['ccx_wall_time_s']:.0f} |")
    rows.append(f"| FD {data['case']['fd_grid'][0]}×{data['case']['fd_grid'][1]} (coupled) | | | | "
                f"{fd['peak_deflection_m'] * 1e3:.4f} | | {fd['permanent_deflection_m'] * 1e3:.4f}"
                f" | | {fd['plastic_half_length_m'] * 1e3:.0f} | |")
    print("\n".join(rows))
    ref, changes = fe_reference(runs)
    print("\nFE changes (finer − coarser)/finer:", json.dumps(changes, indent=1))
    print("\n| FD grid N_l×N_h | coupled: peak w [mm] | permanent w [mm] | plastic half-length "
          "[mm] | prescribed load: peak w [mm] |\n|---|---|---|---|---|")
    for key, r in data["fd_grid_study"].items():
        p = data["fd_prescribed_grid_study"].get(key, {}).get("peak_deflection_m")
        print(f"| {key} | {r['peak_deflection_m'] * 1e3:.4f} | "
              f"{r['permanent_deflection_m'] * 1e3:.4f} | {r['plastic_half_length_m'] * 1e3:.0f}"
              f" | {'' if p is None else f'{p * 1e3:.4f}'} |")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (a0, a1) = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    t, f, w = np.loadtxt(FORCE_CSV, delimiter=",", skiprows=1, unpack=True)
    a0.plot(t * 1e3, f / 1e3, lw=0.6, color="k")
    a0.set_ylabel("contact force [kN]")
    a1.plot(t * 1e3, w * 1e3, color="k", lw=1.5, label="FD beam (coupled, 200×10)")
    for tag in runs:
        h = np.loadtxt(ct.RESULTS / f"level5_fe_{tag}.csv", delimiter=",", skiprows=1)
        a1.plot(h[:, 0] * 1e3, h[:, 2] * 1e3, lw=0.9, label=f"3D FE {tag}")
    a1.axhline(fd["permanent_deflection_m"] * 1e3, color="k", ls=":", lw=0.8,
               label="FD permanent")
    for tag, r in runs.items():
        a1.plot([FE_END * 1e3], [r["permanent_deflection_m"] * 1e3], "o", ms=4)
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
