"""Level 2: static Hertz contact of the steel sphere on the beam and on a thick block (CalculiX).

Quarter models (symmetry planes x = 0 and y = 0, the contact point at the origin):

* the sphere: the lower quarter hemisphere of radius R (centre (0, 0, R), pole at the
  origin), its equatorial plane z = R moved down by a prescribed displacement δ(t)
  (uz = −δ, ux/uy free apart from the symmetry planes) — δ is the approach of the
  sphere's centre;
* the target, top face z = 0: (a) ``block``: a cube of side ``--block`` (quarter
  of a 2×side × 2×side × side block), bottom face held in z — a half-space proxy;
  (b) ``beam``: the quarter of the simply supported 500 × 20 × 20 mm beam of level 3
  (x ∈ [0, L/2], end face x = L/2 held in z, the diaphragm support of level 1).

Both bodies are 10-node tetrahedra (C3D10) from one gmsh model, graded with the
distance r from the contact point: size h0 = a_max / ``MESHES[--mesh]`` for
r < 1.5 a_max (a_max the Hertz contact radius at the largest force), growing by
``GROWTH`` per unit distance beyond, up to R/3 in the sphere and ``--far-size`` in the
target.  On the beam the sphere starts ``BEAM_PRELOAD`` into the target (counted in the
approach): with no contact at the start of the first increment, the first Newton
iteration would push the sphere the whole first increment (mostly beam deflection,
0.24 mm) into the undeformed beam, and ccx does not recover from that.  Contact:
``*CONTACT PAIR, TYPE=SURFACE TO SURFACE``, frictionless, the sphere's surface near
the pole the slave, the target's top face near the origin the master, linear
penalty (slope ``PENALTY`` × E / h0; the overclosure at the Hertz peak pressure is
≈ 10⁻³ α).  ``*STATIC`` (small strains, no NLGEOM), ``--increments`` fixed
increments of δ chosen so that the Hertz + beam-theory force grows linearly
(F_i ≈ i F_max / n).

Output per increment (``.dat``): the total reaction force of the sphere's equatorial
plane (× 4 for the full model) and the target's displacements on its axis x = y = 0.
Derived:

* fit δ_rel = (F/K)^{2/3} + c F (linear least squares in K^{-2/3} and c), δ_rel the
  approach of the sphere's centre relative to the block's bottom (block) or to the
  beam's neutral axis under the sphere (beam); K against the toolkit's
  K_h = (4/3) E* √R, c the linear (far-field / structural) remainder;
  also the pure fit F = K α^{3/2} (c = 0) of the same data;
* beam: the deflection of the neutral axis / bottom face under the sphere against
  the toolkit's static point compliance (Timoshenko and Euler), and the sphere's
  total displacement δ against the toolkit's C_st F + (F/K_h)^{2/3}.

Run (full, niced, single-threaded):
``OMP_NUM_THREADS=1 CCX_NPROC_EQUATION_SOLVER=1 nice -n 19 python
validation/fe/level2_static_hertz.py --case block --mesh medium`` (and ``coarse``,
then ``--case beam``; ``--mesh fine`` is the next density); each run adds its entry to
``results/level2_static_hertz.json`` and writes ``results/level2_<case>_<mesh>.csv``.
``--table`` prints the README table from that file.  ``--smoke``: a coarse block with
3 increments (≈ 10 s), written to ``--out-dir`` (a temporary directory by default).
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import ccx_tools as ct  # noqa: E402

import impactmaps  # noqa: E402

STEEL = impactmaps.material("structural-steel")
RADIUS = 0.01                       # sphere radius [m]
BEAM = dict(length=0.5, width=0.02, height=0.02)
GROWTH = 0.3                        # element size growth per unit distance [-]
PENALTY = 50.0                      # contact slope = PENALTY × E / h0 [Pa/m]
FINE_ZONE = 1.5                     # size h0 up to FINE_ZONE × a_max from the contact
BEAM_PRELOAD = 0.5e-6               # initial overclosure on the beam [m] (see docstring)
MESHES = {"medium": 4.5, "coarse": 6.0, "fine": 8.0, "smoke": 2.0}   # a_max / h0


def toolkit_values():
    """K_h [N/m^1.5] of the sphere on steel and the beam's static compliances [m/N]."""
    sphere = impactmaps.Sphere(RADIUS, STEEL)
    law = impactmaps.law_for_sphere("hertz", sphere, STEEL)
    beams = {theory: impactmaps.Beam.rectangular(BEAM["length"], BEAM["width"],
                                                 BEAM["height"], STEEL, theory=theory)
             for theory in ("timoshenko", "euler")}
    return dict(K_h=float(law.stiffness),
                **{f"C_{k}": float(b.static_compliance()) for k, b in beams.items()})


def hertz_radius(force, stiffness):
    """Hertz contact radius a = √(R α) [m] at ``force`` [N]."""
    return float(np.sqrt(RADIUS * (force / stiffness) ** (2 / 3)))


def build_mesh(case, h0, r_fine, far_size, block_side, preload=0.0):
    """C3D10 mesh of the quarter sphere (centre lowered by ``preload``) + target."""
    import gmsh
    gmsh.initialize(["-noenv"])
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add("level2")
        occ = gmsh.model.occ
        ball = occ.addSphere(0, 0, RADIUS - preload, RADIUS)
        cut = occ.addBox(0, 0, -preload, RADIUS, RADIUS, RADIUS)
        (sphere_vol,), _ = occ.intersect([(3, ball)], [(3, cut)])
        if case == "beam":
            target = occ.addBox(0, 0, -BEAM["height"], BEAM["length"] / 2,
                                BEAM["width"] / 2, BEAM["height"])
        else:
            target = occ.addBox(0, 0, -block_side, block_side, block_side, block_side)
        occ.synchronize()
        size = f"Min({h0} + {GROWTH}*Max(Sqrt(x*x+y*y+z*z) - {r_fine}, 0), {{far}})"
        mesh, _, tris = ct.quarter_contact_mesh(gmsh, sphere_vol, target, size, (RADIUS / 3, far_size))
    finally:
        gmsh.finalize()
    return mesh, tris


def contact_faces(mesh, tris, radius):
    """Element faces of the slave/master triangles within ``radius`` of the origin."""
    out = {}
    for key, tri in tris.items():
        centre = mesh.coords[tri[:, :3] - 1].mean(axis=1)
        near = tri[np.linalg.norm(centre, axis=1) < radius]
        out[key] = ct.tet_faces_on(mesh, near)
    return out


def ramp(toolkit, case, f_max, n):
    """Times, δ(t) [m] and the nominal forces: F_i = i F_max / n under Hertz + beam theory."""
    forces = f_max * np.arange(1, n + 1) / n
    compliance = toolkit["C_timoshenko"] if case == "beam" else 0.0
    delta = compliance * forces + (forces / toolkit["K_h"]) ** (2 / 3)
    return np.arange(1, n + 1) / n, delta, forces


def build_deck(case, mesh, faces, h0, times, delta, block_side, preload=0.0):
    """The ccx deck: mesh, sets, contact pair, one *STATIC step of len(times) increments."""
    x, y, z = mesh.coords.T
    tol = 1e-9
    F = ct.Deck()
    w = F.write
    ct.write_mesh(F, mesh, STEEL)
    ct.write_nset(F, "STOP", mesh.nodes_where(np.isclose(z, RADIUS - preload, atol=tol)))
    target = np.zeros(len(z), dtype=bool)
    corners = mesh.elements[:, :4] - 1
    target[mesh.elements[z[corners].mean(axis=1) < -preload].ravel() - 1] = True
    ct.write_nset(F, "AXIS", mesh.nodes_where(np.isclose(x, 0, atol=tol)
                                              & np.isclose(y, 0, atol=tol) & target))
    if case == "beam":
        ct.write_nset(F, "SUPPORT", mesh.nodes_where(np.isclose(x, BEAM["length"] / 2,
                                                                atol=tol)))
    else:
        ct.write_nset(F, "SUPPORT", mesh.nodes_where(np.isclose(z, -block_side, atol=tol)))
    ct.write_quarter_contact(F, mesh, faces, PENALTY * STEEL.youngs_modulus / h0)
    w("*AMPLITUDE, NAME=RAMP\n0.,0.\n")
    for t, d in zip(times, delta):
        w(f"{t:.10f},{d / delta[-1]:.12e}\n")
    w("*BOUNDARY\nXSYM,1,1\nYSYM,2,2\nSUPPORT,3,3\n")
    w(f"*STEP, INC=1000\n*STATIC, DIRECT\n{times[0]:.10f},1.0\n")
    w(f"*BOUNDARY, AMPLITUDE=RAMP\nSTOP,3,3,{-delta[-1]:.12e}\n")
    w("*NODE PRINT, NSET=STOP, TOTALS=ONLY\nRF\n*NODE PRINT, NSET=AXIS\nU\n*END STEP\n")
    return F.text("level 2 static Hertz")


def parse_totals(dat_text, nset):
    """Total reaction forces (fx, fy, fz) of ``nset`` per increment, shape (n, 3)."""
    rows, take = [], False
    for line in dat_text.splitlines():
        if "total force" in line:
            take = f"SET {nset.upper()} " in line.upper()
            continue
        parts = line.split()
        if take and len(parts) == 3:
            rows.append([ct._fortran_float(v) for v in parts])
            take = False
    return np.array(rows)


def fit_hertz(force, approach):
    """Least-squares fits of approach = (F/K)^{2/3} + c F and of approach = (F/K)^{2/3}.

    Returns (K [N/m^1.5], c [m/N], K_pure [N/m^1.5], rms residual of the 2-term fit [m]).
    """
    f23 = force ** (2 / 3)
    (p, c), *_ = np.linalg.lstsq(np.column_stack([f23, force]), approach, rcond=None)
    p_pure = float(np.dot(f23, approach) / np.dot(f23, f23))
    resid = approach - p * f23 - c * force
    return float(p ** -1.5), float(c), float(p_pure ** -1.5), float(np.sqrt(np.mean(resid ** 2)))


def axis_deflection(blocks, mesh, depth):
    """−uz of the target's axis x = y = 0 at ``depth`` below the top (linear interpolation)."""
    ids = sorted(blocks[0])
    z = mesh.coords[np.array(ids) - 1, 2]
    order = np.argsort(z)
    return np.array([np.interp(-depth, z[order], [-b[ids[i]][2] for i in order])
                     for b in blocks])


def run(case, mesh_name, f_max, n_inc, far_size, block_side, out_dir, workdir, preload=0.0):
    """Mesh, run ccx, parse, fit; returns the JSON record of this run."""
    toolkit = toolkit_values()
    a_max = hertz_radius(f_max, toolkit["K_h"])
    h0 = a_max / MESHES[mesh_name]
    t0 = time.perf_counter()
    mesh, tris = build_mesh(case, h0, FINE_ZONE * a_max, far_size, block_side, preload)
    faces = contact_faces(mesh, tris, 3.0 * a_max)
    mesh_time = time.perf_counter() - t0
    times, delta, _ = ramp(toolkit, case, f_max, n_inc)
    deck = build_deck(case, mesh, faces, h0, times, delta - preload, block_side, preload)
    job = f"level2_{case}_{mesh_name}"
    dat, wall = ct.run_ccx(deck, job, workdir)
    text = dat.read_text()
    force = -4.0 * parse_totals(text, "STOP")[:, 2]        # full model, pressing force
    if len(force) != n_inc:
        raise RuntimeError(f"{len(force)} force outputs for {n_inc} increments")
    blocks = ct.parse_node_prints(text, "AXIS")
    surface = axis_deflection(blocks, mesh, 0.0)
    record = dict(case=case, mesh=mesh_name, a_max_over_h0=MESHES[mesh_name],
                  size_at_contact_m=h0, size_far_target_m=far_size,
                  size_far_sphere_m=RADIUS / 3, growth_per_m_per_m=GROWTH,
                  fine_zone_radius_m=FINE_ZONE * a_max, contact_faces_slave=len(faces["slave"]),
                  contact_faces_master=len(faces["master"]), n_nodes=len(mesh.coords),
                  n_elements=len(mesh.elements), element_type=mesh.element_type,
                  penalty_slope_Pa_per_m=PENALTY * STEEL.youngs_modulus / h0,
                  increments=n_inc, f_max_nominal_N=f_max, a_max_m=a_max,
                  initial_overclosure_m=preload,
                  mesh_time_s=mesh_time, ccx_wall_time_s=wall,
                  newton_iterations=_iterations(dat.with_suffix(".sta")))
    if case == "beam":
        neutral = axis_deflection(blocks, mesh, BEAM["height"] / 2)
        bottom = axis_deflection(blocks, mesh, BEAM["height"])
        K, c, K_pure, rms = fit_hertz(force, delta - neutral)
        Kt, ct_total, _, rms_t = fit_hertz(force, delta)
        toolkit_total = toolkit["C_timoshenko"] * force + (force / toolkit["K_h"]) ** (2 / 3)
        record.update(
            K_fit=K, c_fit_m_per_N=c, K_pure_fit=K_pure, fit_rms_m=rms,
            K_fit_total=Kt, c_fit_total_m_per_N=ct_total, fit_total_rms_m=rms_t,
            neutral_axis_compliance_m_per_N=float(np.polyfit(force, neutral, 1)[0]),
            bottom_compliance_m_per_N=float(np.polyfit(force, bottom, 1)[0]),
            total_vs_toolkit_at_max=float(delta[-1] / toolkit_total[-1] - 1))
        columns = dict(force_N=force, sphere_approach_m=delta, surface_uz_m=surface,
                       neutral_axis_uz_m=neutral, bottom_uz_m=bottom,
                       toolkit_total_m=toolkit_total)
    else:
        K, c, K_pure, rms = fit_hertz(force, delta)
        record.update(K_fit=K, c_fit_m_per_N=c, K_pure_fit=K_pure, fit_rms_m=rms)
        columns = dict(force_N=force, sphere_approach_m=delta, surface_uz_m=surface,
                       toolkit_hertz_m=(force / toolkit["K_h"]) ** (2 / 3))
    record["K_fit_vs_K_h"] = record["K_fit"] / toolkit["K_h"] - 1
    record["K_pure_vs_K_h"] = record["K_pure_fit"] / toolkit["K_h"] - 1
    csv = out_dir / f"{job}.csv"
    np.savetxt(csv, np.column_stack(list(columns.values())), delimiter=",",
               header=",".join(columns), comments="", fmt="%.9e")
    record["csv"] = csv.name
    return record, toolkit


def _iterations(sta: Path):
    """Total Newton iterations from the ccx .sta file (None if absent)."""
    if not sta.exists():
        return None
    total = 0
    for line in sta.read_text().splitlines():
        parts = line.split()
        if len(parts) >= 5 and parts[0].isdigit() and parts[1].isdigit():
            total += int(parts[3])
    return total


def _pct(value):
    return f"{100 * value:+.2f} %"


def table(data):
    """Markdown rows (case, FE value with its mesh convergence, toolkit, difference)
    from the summary JSON: the two finest meshes of each case."""
    runs, tk = data["runs"], data["toolkit"]
    rows = ["| case | quantity | FE (finest mesh) | FE mesh Δ (coarser − finer) | toolkit | "
            "toolkit − FE |", "|---|---|---|---|---|---|"]
    for case in ("block", "beam"):
        meshes = [m for m in ("fine", "coarse", "medium") if f"{case}_{m}" in runs][:2]
        if len(meshes) < 2:
            continue
        fine, coarse = runs[f"{case}_{meshes[0]}"], runs[f"{case}_{meshes[1]}"]
        label = f"{case} (a_max/h0 {coarse['a_max_over_h0']:g} → {fine['a_max_over_h0']:g})"
        items = [("K [N/m^1.5], 2-term fit", "K_fit", tk["K_h"]),
                 ("K, pure F = K α^1.5", "K_pure_fit", tk["K_h"])]
        if case == "beam":
            items = [("K [N/m^1.5], fit of the total approach", "K_fit_total", tk["K_h"]),
                     ("linear part c [m/N] of the total approach", "c_fit_total_m_per_N",
                      tk["C_timoshenko"]),
                     ("neutral-axis deflection / F [m/N]", "neutral_axis_compliance_m_per_N",
                      tk["C_timoshenko"]),
                     ("bottom-face deflection / F [m/N]", "bottom_compliance_m_per_N",
                      tk["C_timoshenko"]),
                     ("K, local fit (approach to the neutral axis)", "K_fit", tk["K_h"])]
        for name, key, ref in items:
            rows.append(f"| {label} | {name} | {fine[key]:.5g} | "
                        f"{_pct(coarse[key] / fine[key] - 1)} | {ref:.5g} | "
                        f"{_pct(ref / fine[key] - 1)} |")
        if case == "beam":
            rows.append(f"| {label} | sphere approach at F_max: toolkit C_st F + (F/K_h)^(2/3)"
                        f" vs FE | — | {_pct(coarse['total_vs_toolkit_at_max'] - fine['total_vs_toolkit_at_max'])}"
                        f" | — | {_pct(1 / (1 + fine['total_vs_toolkit_at_max']) - 1)} |")
    return "\n".join(rows)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--case", choices=("block", "beam"), default="block")
    p.add_argument("--mesh", choices=("medium", "coarse", "fine"), default="coarse")
    p.add_argument("--force", type=float, default=2000.0, help="largest force F_max [N]")
    p.add_argument("--increments", type=int, default=8)
    p.add_argument("--far-size", type=float, default=0.005, help="target far size [m]")
    p.add_argument("--block", type=float, default=0.03, help="quarter block side [m]")
    p.add_argument("--preload", type=float, default=None,
                   help="initial overclosure of the sphere [m] (default: beam 0.5 µm, "
                   "block 0)")
    p.add_argument("--threads", default="1", help="ccx threads (FE_THREADS)")
    p.add_argument("--smoke", action="store_true", help="coarse block, 3 increments")
    p.add_argument("--out-dir", type=Path, default=None)
    p.add_argument("--table", action="store_true",
                   help="print the README table from results/level2_static_hertz.json")
    a = p.parse_args(argv)
    if a.table:
        print(table(json.loads((ct.RESULTS / "level2_static_hertz.json").read_text())))
        return None
    os.environ["FE_THREADS"] = a.threads
    os.environ.setdefault("CCX_NPROC_EQUATION_SOLVER", a.threads)
    if a.smoke:
        out_dir = a.out_dir or Path(tempfile.mkdtemp(prefix="impactmaps-fe-smoke-"))
        a.case, a.mesh, a.increments, a.far_size, a.block = "block", "smoke", 3, 0.004, 0.008
    else:
        out_dir = a.out_dir or ct.RESULTS
    out_dir.mkdir(parents=True, exist_ok=True)
    workdir = out_dir / "work" if a.smoke else ct.WORK / "level2"
    if a.preload is None:
        a.preload = BEAM_PRELOAD if a.case == "beam" else 0.0
    record, toolkit = run(a.case, a.mesh, a.force, a.increments, a.far_size, a.block,
                          out_dir, workdir, a.preload)
    record.update(block_side_m=a.block if a.case == "block" else None,
                  command="python validation/fe/level2_static_hertz.py "
                  + " ".join(argv if argv is not None else sys.argv[1:]),
                  ccx_version=ct.ccx_version(), gmsh_version=ct.gmsh_version(),
                  threads=a.threads)
    summary = out_dir / "level2_static_hertz.json"
    data = json.loads(summary.read_text()) if summary.exists() else {}
    data.setdefault("inputs", dict(
        sphere_radius_m=RADIUS, beam=BEAM, contact="surface-to-surface, frictionless, "
        "linear penalty", material=dict(E_Pa=STEEL.youngs_modulus, nu=STEEL.poisson_ratio)))
    data["toolkit"] = toolkit
    data.setdefault("runs", {})[f"{a.case}_{a.mesh}"] = record
    summary.write_text(json.dumps(data, indent=1))
    print(json.dumps(record, indent=1))
    return record


if __name__ == "__main__":
    main()
