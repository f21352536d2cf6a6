"""Level 5, statics: quasi-static 3-point bending of the 3D quarter beam (CalculiX)
against the exact elastic–perfectly plastic beam theory under the same strip load.

This checks the FD beam's section model (uniaxial layers, M(κ) of the rectangle) apart
from any dynamics: the same quarter mesh, material and strip load as the dynamic runs
of ``level5_beam_plastic.py``, ``*STATIC`` to ``--pmax`` × P_y (P_y = 4 M_y / L) in 2 %
steps, the mid-span section-mean deflection against the virtual-work integral of the
beam's exact moment–curvature relation.

Run: ``OMP_NUM_THREADS=1 nice -n 19 python validation/fe/level5_static_bending.py
--width 60`` (and ``--width 10``); writes ``results/level5_static_b<w>mm_nz4_ny1.csv`` and
a ``static_runs`` entry of ``results/level5_beam_plastic.json``.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import ccx_tools as ct
from level5_beam_plastic import (
    HEIGHT,
    LENGTH,
    STEEL,
    WIDTH,
    fe_deck,
    load,
    quarter_mesh,
    save,
    section_weights,
)


def beam_theory_static(load, patch, width):
    """Mid-span deflection [m] of the elastic–perfectly plastic Euler beam (exact
    rectangle M(κ), :func:`impactmaps.fd.rectangular_moment_curvature` inverted) under
    ``load`` [N] spread uniformly over |x − L/2| ≤ ``patch`` (virtual work, 4000 points)."""
    e, sy = STEEL.youngs_modulus, STEEL.yield_strength
    m_y, m_p = sy * width * HEIGHT**2 / 6, sy * width * HEIGHT**2 / 4
    ei, kappa_y = e * width * HEIGHT**3 / 12, 2 * sy / (e * HEIGHT)
    x = np.linspace(0.0, 0.5 * LENGTH, 4001)
    moment = 0.5 * load * x - load / (4 * patch) * np.clip(x - (0.5 * LENGTH - patch), 0, None) ** 2
    if moment.max() >= m_p:
        return np.inf
    kappa = np.where(moment <= m_y, moment / ei,
                     kappa_y / np.sqrt(np.maximum(3 * (1 - moment / m_p), 1e-300)))
    return float(np.trapezoid(kappa * x, x))


def run_static(args):
    """Quasi-static 3-point bending of the quarter beam of width ``--width`` to
    ``--pmax`` × P_y (P_y = 4 M_y / L), against the beam theory of the same load."""
    width = args.width * 1e-3
    patch = HEIGHT / 8
    p_y = 4 * STEEL.yield_strength * width * HEIGHT**2 / 6 / LENGTH
    mesh, knots = quarter_mesh(args.nz, args.ny, patch, width)
    deck, faces = fe_deck(mesh, None, None, None, patch, width=width,
                          static_load=args.pmax * p_y)
    tag = f"static_b{args.width:g}mm_nz{args.nz}_ny{args.ny}" + (f"_p{args.pmax:g}" if args.pmax != 1.4 else "")
    stopped = None
    if args.parse_only:          # re-read the .dat of an earlier run
        dat, wall = ct.WORK / "level5" / f"level5_{tag}.dat", float("nan")
    else:
        try:
            dat, wall = ct.run_ccx(deck, f"level5_{tag}", ct.WORK / "level5")
        except RuntimeError as error:  # beyond the limit load: no equilibrium
            dat, wall, stopped = ct.WORK / "level5" / f"level5_{tag}.dat", float("nan"), str(error)
    if stopped is None and "no convergence" in args.note:
        stopped = args.note
    text = dat.read_text()
    blocks = ct.parse_node_prints(text, "MID")
    t_fe = ct.parse_node_print_times(text, "MID")
    ids = mesh.nodes_where(np.isclose(mesh.coords[:, 0], 0.5 * LENGTH, atol=1e-9))
    mean = np.array([[-b[i][2] for i in ids] for b in blocks]) @ section_weights(mesh, ids)
    loads = t_fe * args.pmax * p_y
    theory = np.array([beam_theory_static(p, patch, width) for p in loads])
    rows = np.column_stack([loads / p_y, mean, theory])
    np.savetxt(ct.RESULTS / f"level5_{tag}.csv", rows, delimiter=",", fmt="%.6e",
               comments="", header="load_over_Py,fe_section_mean_m,beam_theory_m")
    data = load()
    data.setdefault("static_runs", {})[tag] = dict(
        width_m=width, nz=args.nz, ny=args.ny, n_nodes=len(mesh.coords), patch_half_length_m=patch,
        yield_load_N=p_y, ccx_wall_time_s=wall if np.isfinite(wall) else None,
        last_converged_load_over_Py=float(rows[-1, 0]),
        beam_theory_collapse_load_over_Py=float(LENGTH / (LENGTH - patch) * 1.5),
        stopped=None if stopped is None else "ccx stopped: no equilibrium beyond the last load",
        fe_over_theory_at=[[float(a), float(b / c)] for a, b, c in rows[1:]],
        command="python validation/fe/level5_static_bending.py " + " ".join(sys.argv[1:]))
    save(data)
    for a, b, c in rows:
        print(f"P/Py {a:.3f}  FE {b * 1e3:.4f} mm  beam {c * 1e3:.4f} mm  FE/beam {b / c:.4f}")


def main(argv=None):
    st = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    st.add_argument("--width", type=float, default=WIDTH * 1e3, help="beam width b [mm]")
    st.add_argument("--nz", type=int, default=4)
    st.add_argument("--ny", type=int, default=1)
    st.add_argument("--pmax", type=float, default=1.4, help="largest load / P_y")
    st.add_argument("--parse-only", action="store_true", help="re-read an earlier run's .dat")
    st.add_argument("--note", default="")
    run_static(st.parse_args(argv))


if __name__ == "__main__":
    main()
