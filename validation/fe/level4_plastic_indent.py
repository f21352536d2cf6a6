"""Level 4, elastic–plastic target: quasi-static load–unload indentation (CalculiX).

Why not the dynamic run: ccx 2.20's implicit dynamic contact did not run with a
yielding target in any variant tried on the smoke mesh (``level4_contact.py --case
plastic``): perfectly plastic ``*PLASTIC`` gives NaN forces in the first iteration;
with a small hardening (1 MPa per unit strain) and Δt = 2 µs the first increment
converges, then ccx forces a divergence — with fixed increments (``*DYNAMIC, DIRECT``)
that stops the run ("solution seems to diverge"), with automatic incrementation the
increment falls to ≈ 10⁻⁸ s (0.24 µs of the 90 µs event in 5 min); with Δt = 0.2 µs
the first iteration diverges (displacements 10¹⁴⁴).  The forced divergence is
consistent with ccx's energy rule for dynamic contact (``checkimpacts``, called from
``checkconvergence``: an increment whose energy balance drops by more than 0.8 % of the
largest energy while the contact grows is cut to a quarter), which the plastic
dissipation triggers; the rule has no switch in 2.20.

What is run instead (the physics that differs from the elastic case is the contact
law): the elastic sphere pressed into the elastic–perfectly plastic target
(S_y = 235 MPa, von Mises, the sphere elastic) quasi-statically, in the level-2 block
model (quarter of a 60 × 60 × 30 mm block, bottom held in z: a half-space proxy, its
far-field compliance −1.7 × 10⁻¹⁰ m/N, i.e. < 0.2 µm at 1 kN, negligible here), the
sphere's equatorial plane driven down to the toolkit's largest indentation of the
plastic impact (modal, refined Stronge: α_max = 26.5 µm) in ``--load`` increments and
back up to its start in ``--unload`` increments (``*STATIC``, small strains, the level-2
contact pair, C3D10 graded from h0 = a_ref / ``MESHES[--mesh]``, a_ref the Stronge
loading contact radius at α_max).  Compared with the refined Stronge law: the force
at α_max and along the loading curve, the permanent indentation after unloading
(−u_z of the block's top on the axis once the sphere has left), and the energy
dissipated in the cycle.

Run: ``OMP_NUM_THREADS=1 nohup nice -n 19 python validation/fe/level4_plastic_indent.py
--mesh coarse &`` (then ``--mesh fine``); each run adds its entry to
``results/level4_plastic_indent.json`` and writes ``results/level4_indent_<mesh>.csv``
(``--load 20 --unload 20``: the increment check, key ``<mesh>_20x20``).
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import ccx_tools as ct  # noqa: E402
import level2_static_hertz as l2  # noqa: E402
import level4_contact as l4  # noqa: E402

BLOCK = 0.03                       # quarter block side [m] (level 2)
FAR_SIZE = 0.005                   # block far size [m] (level 2)
MESHES = {"coarse": 3.0, "fine": 4.5, "smoke": 1.0}     # a_ref / h0
DEFAULT_INCREMENTS = 10            # load and unload increments (maximum size 1/10)


def stronge_law():
    return l4.impactmaps.law_for_sphere("stronge", l4.sphere(), l4.STEEL)


def build_deck(mesh, faces, h0, delta_max, n_load, n_unload):
    """Two *STATIC steps: the sphere's plane z = R down by ``delta_max`` and back."""
    x, y, z = mesh.coords.T
    tol = 1e-9
    corners = mesh.elements[:, :4] - 1
    in_sphere = z[corners].mean(axis=1) > 0
    F = ct.Deck()
    w = F.write
    ct.write_mesh_parts(F, mesh, [
        ("SPH", in_sphere, "BALL", ct.material_cards(l4.SPHERE_MATERIAL)),
        ("TGT", ~in_sphere, "BLOCK", ct.material_cards(l4.STEEL, l4.STEEL.yield_strength))])
    target = np.ones(len(z), dtype=bool)
    target[mesh.elements[in_sphere].ravel() - 1] = False
    ct.write_nset(F, "STOP", mesh.nodes_where(np.isclose(z, l2.RADIUS, atol=tol)))
    ct.write_nset(F, "SUPPORT", mesh.nodes_where(np.isclose(z, -BLOCK, atol=tol)))
    ct.write_nset(F, "AXIS", mesh.nodes_where(np.isclose(x, 0, atol=tol)
                                              & np.isclose(y, 0, atol=tol) & target))
    ct.write_quarter_contact(F, mesh, faces, l4.PENALTY * l4.STEEL.youngs_modulus / h0)
    w("*BOUNDARY\nXSYM,1,1\nYSYM,2,2\nSUPPORT,3,3\n")
    prints = "*NODE PRINT, NSET=STOP, TOTALS=ONLY\nRF\n*NODE PRINT, NSET=AXIS\nU\n*END STEP\n"
    for n, value in ((n_load, -delta_max), (n_unload, 0.0)):
        w(f"*STEP, INC=1000\n*STATIC\n{1 / n:.8f},1.0,{1e-3 / n:.3e},{1 / n:.8f}\n"
          f"*BOUNDARY\nSTOP,3,3,{value:.12e}\n" + prints)
    return F.text("level 4 plastic indentation")


def run_key(mesh_name, n_load, n_unload):
    """Key of a run in the JSON: the mesh name, with the increments if not the default."""
    default = (n_load, n_unload) == (DEFAULT_INCREMENTS, DEFAULT_INCREMENTS)
    return mesh_name if default else f"{mesh_name}_{n_load}x{n_unload}"


def run(mesh_name, n_load, n_unload, workdir, out_dir):
    """Mesh, run ccx, parse; returns the JSON record of this run."""
    law = stronge_law()
    modal = l4.toolkit_runs_cached("plastic")["modal_stronge"][0]
    alpha_max = float(modal.max_indentation)
    a_ref = float(law.loading_contact_radius(alpha_max))
    h0 = a_ref / MESHES[mesh_name]
    t0 = time.perf_counter()
    mesh, tris = l2.build_mesh("block", h0, l4.FINE_ZONE * a_ref, FAR_SIZE, BLOCK)
    faces = l2.contact_faces(mesh, tris, l4.SLAVE_ZONE * a_ref)
    mesh_time = time.perf_counter() - t0
    deck = build_deck(mesh, faces, h0, alpha_max, n_load, n_unload)
    job = f"level4_indent_{run_key(mesh_name, n_load, n_unload)}"
    dat, wall = ct.run_ccx(deck, job, workdir)
    text = dat.read_text()
    force = -4.0 * l2.parse_totals(text, "STOP")[:, 2]
    n = len(force)
    times = ct.parse_node_print_times(text, "AXIS")
    loading = np.arange(n) < int(np.sum(times <= 1.0 + 1e-9))   # step 1 (total time ≤ 1)
    step_time = np.where(loading, times, times - 1.0)
    delta = alpha_max * np.where(loading, step_time, 1.0 - step_time)
    surface = l2.axis_deflection(ct.parse_node_prints(text, "AXIS"), mesh, 0.0)
    # energy: trapezoid along the path (0, 0) -> loading -> unloading
    d_path, f_path = np.concatenate([[0.0], delta]), np.concatenate([[0.0], force])
    dissipated = float(np.sum(0.5 * (f_path[1:] + f_path[:-1]) * np.diff(d_path)))
    record = dict(mesh=mesh_name, a_ref_m=a_ref, a_ref_over_h0=MESHES[mesh_name],
                  size_at_contact_m=h0, size_far_target_m=FAR_SIZE, block_side_m=BLOCK,
                  n_nodes=len(mesh.coords), n_elements=len(mesh.elements),
                  element_type=mesh.element_type, load_increments=n_load,
                  unload_increments=n_unload, outputs=n, max_indentation_m=alpha_max,
                  force_at_max_N=float(force[loading][-1]),
                  permanent_indentation_m=float(surface[-1]),
                  dissipated_energy_J=dissipated,
                  mesh_time_s=mesh_time, ccx_wall_time_s=wall,
                  newton_iterations=l2._iterations(dat.with_suffix(".sta")),
                  toolkit=dict(force_at_max_N=float(law.loading_force(alpha_max)),
                               permanent_indentation_m=float(law.permanent_indentation(alpha_max)),
                               dissipated_energy_J=float(law.dissipated_energy(alpha_max))))
    columns = dict(approach_m=delta, force_N=force, surface_uz_m=surface,
                   stronge_loading_N=law.loading_force(delta),
                   stronge_unloading_N=law.force(delta, alpha_max))
    csv = out_dir / f"{job}.csv"
    np.savetxt(csv, np.column_stack(list(columns.values())), delimiter=",",
               header=",".join(columns), comments="", fmt="%.9e")
    record["csv"] = csv.name
    return record


ITEMS = (("force at α_max [N]", "force_at_max_N", 1.0),
         ("permanent indentation [µm]", "permanent_indentation_m", 1e6),
         ("energy dissipated in the cycle [mJ]", "dissipated_energy_J", 1e3))


def reference(data):
    """(reference key, mesh-variant key or None, increment-variant key or None): the
    reference is the fine mesh with the most increments committed."""
    keys = [k for k in ("fine_20x20", "fine", "coarse_20x20", "coarse") if k in data]
    if not keys:
        return None, None, None
    ref = keys[0]
    mesh = ref.replace("fine", "coarse") if "fine" in ref else None
    inc = ref.split("_")[0] if "_" in ref else f"{ref}_20x20"
    return ref, mesh if mesh in data else None, inc if inc in data else None


def table(data):
    """Markdown rows: FE reference with its mesh and increment differences, refined
    Stronge, difference."""
    ref_key, mesh_key, inc_key = reference(data)
    if ref_key is None:
        return ""
    ref = data[ref_key]
    head = (f"| quantity (α_max = {ref['max_indentation_m'] * 1e6:.2f} µm) | FE ({ref_key}) | "
            f"FE mesh Δ (coarse − fine) | FE increments Δ (10 + 10 − 20 + 20) | "
            "refined Stronge | Stronge − FE |")
    rows = [head, "|---|---|---|---|---|---|"]
    for label, key, scale in ITEMS:
        fe, law = ref[key], ref["toolkit"][key]
        inc_pair = (inc_key, ref_key) if "_" in ref_key else (ref_key, inc_key)   # 10 vs 20
        cells = ["—" if other is None else f"{100 * (data[a][key] / data[b][key] - 1):+.1f} %"
                 for other, (a, b) in ((mesh_key, (mesh_key, ref_key)), (inc_key, inc_pair))]
        rows.append(f"| {label} | {fe * scale:.4g} | {cells[0]} | {cells[1]} | "
                    f"{law * scale:.4g} | {100 * (law / fe - 1):+.1f} % |")
    return "\n".join(rows)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--mesh", choices=tuple(MESHES), default="coarse")
    p.add_argument("--load", type=int, default=DEFAULT_INCREMENTS, help="loading increments")
    p.add_argument("--unload", type=int, default=DEFAULT_INCREMENTS,
                   help="unloading increments")
    p.add_argument("--threads", default="1", help="ccx threads (FE_THREADS)")
    p.add_argument("--out-dir", type=Path, default=None)
    p.add_argument("--table", action="store_true", help="print the README table")
    a = p.parse_args(argv)
    if a.table:
        print(table(json.loads((ct.RESULTS / "level4_plastic_indent.json").read_text())))
        return None
    os.environ["FE_THREADS"] = a.threads
    out_dir = a.out_dir or ct.RESULTS
    out_dir.mkdir(parents=True, exist_ok=True)
    record = run(a.mesh, a.load, a.unload, ct.WORK / "level4", out_dir)
    record.update(command="python validation/fe/level4_plastic_indent.py "
                  + " ".join(argv if argv is not None else sys.argv[1:]),
                  ccx_version=ct.ccx_version(), gmsh_version=ct.gmsh_version(),
                  threads=a.threads)
    path = out_dir / "level4_plastic_indent.json"
    data = json.loads(path.read_text()) if path.exists() else {}
    data[run_key(a.mesh, a.load, a.unload)] = record
    path.write_text(json.dumps(data, indent=1))
    print(json.dumps(record, indent=1))
    return record


if __name__ == "__main__":
    main()
