"""Level 6: natural frequencies of plates with any edges (issue 39) — 3D solid and composite shell.

Two kinds of CalculiX runs, the first 8 *bending* modes of each:

* ``solid`` — isotropic square steel plates (S235 of the catalogue: E 210 GPa, ν 0.3,
  ρ 7850 kg/m³), h = 10 mm, a/h = 10 and 20, 20-node hexahedra C3D20R (structured, gmsh),
  two meshes (16×16×2 and 24×24×3).  Edges as the toolkit names them (``edges`` = the
  edges x = 0, y = 0, x = a, y = b in that order), following PHYSICS.md §3.7:

  - ``C`` — the whole edge face held (ux = uy = uz = 0): the 3D clamp;
  - ``S`` — the "hard" simple support: the tangential displacement held on the whole
    edge face, and the *thickness-averaged* uz held per node column of the face (one
    ``*EQUATION`` per column, weights = the exact integral of the element's interpolation
    along z: Simpson on columns through corner nodes, trapezoid on mid-side columns);
  - ``F`` — free.

  Bending modes are those whose mid-surface in-plane displacement is negligible against
  uz (zero for flexure of a symmetric plate; the in-plane modes have uz = 0 there).  The
  mid-surface uz of each of the first 8 bending modes on the 9 × 9 grid x, y = a·i/8 is
  stored (``results/level6_plate_shapes.npz``, best mesh) so that a plate theory's modes
  can be paired by shape (MAC), not by order.

* ``shell`` — CCCC composite plates 150 × 100 mm of AS4/3501-6 (catalogue values), 16
  plies of 0.125 mm (h = 2 mm), ``[0/45/-45/90]2s`` and ``[0/90]4s``, 8-node shells S8R
  with ``*SHELL SECTION, COMPOSITE`` (one layer per ply), two meshes; all edge nodes held
  in all six degrees of freedom.  Transverse shear moduli G13 = G23 = G12 (the toolkit
  ply's default), E3 = E2, ν13 = ν12, ν23 = 0.4 (an assumption; it hardly enters bending).

Run from the repository root (one ccx at a time; ``FE_THREADS`` sets ccx's threads)::

    OMP_NUM_THREADS=1 FE_THREADS=1 nice -n 10 python validation/fe/level6_plates.py solid --case CCCC-20
    ... solid --case SCSC-20 --case CFFF-20 --case CCCC-10 --case SCSC-10 --case CFFF-10
    ... shell --layup qi --layup cp

Results: ``validation/fe/results/level6_plates.json`` (each case with its exact command,
meshes, wall times, all modes and the bending ones) and the shapes npz.  Scratch files in
``validation/work/fe/level6`` (git-ignored).
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import ccx_tools as ct  # noqa: E402

import impactmaps  # noqa: E402

STEEL = impactmaps.material("structural-steel")
PLY = impactmaps.material("as4-3501-6")
THICKNESS = 0.010                   # m, solid plates
SOLID_MESHES = {"coarse": (16, 2), "fine": (24, 3), "finest": (32, 4)}
N_BENDING = 8
N_EIGEN = 30                        # eigenvalues asked from ccx (bending + in-plane)
GRID = 9                            # shape grid: x, y = a i/8, i = 0..8
SHELL_SIZE = (0.150, 0.100)         # m
PLY_THICKNESS = 0.125e-3            # m
LAYUPS = {"qi": ("[0/45/-45/90]2s", [0, 45, -45, 90, 0, 45, -45, 90]),
          "cp": ("[0/90]4s", [0, 90, 0, 90, 0, 90, 0, 90])}
SHELL_MESHES = {"coarse": (24, 16), "fine": (48, 32)}      # grid x, y = L i/8 on nodes
NU23 = 0.4
JSON = ct.RESULTS / "level6_plates.json"
SHAPES = ct.RESULTS / "level6_plate_shapes.npz"
WORKDIR = ct.WORK / "level6"


class _Deck:
    def __init__(self):
        self._parts = []

    def write(self, s):
        self._parts.append(s)

    @property
    def text(self):
        return "".join(self._parts)


def _column_weights(z, quadratic):
    """Weights of ∫ uz dz / h over a node column at heights ``z`` (sorted): Simpson per element
    on a column through corner nodes (``quadratic``: 2 nz + 1 nodes, uz quadratic in z),
    trapezoid on a mid-side column (nz + 1 nodes: the serendipity face is linear in z there)."""
    z = np.asarray(z)
    n = z.size
    w = np.zeros(n)
    if quadratic:
        for k in range(0, n - 2, 2):
            he = z[k + 2] - z[k]
            w[k:k + 3] += he / 6 * np.array([1.0, 4.0, 1.0])
    else:
        for k in range(n - 1):
            he = z[k + 1] - z[k]
            w[k:k + 2] += he / 2
    return w / w.sum()


def solid_deck(edges, ratio, n_in_plane, nz):
    """CalculiX deck, metadata, mesh and the ids of the 9×9 mid-surface grid nodes."""
    h = THICKNESS
    a = ratio * h
    mesh = ct.structured_box(a, a, h, n_in_plane, n_in_plane, nz)
    x, y, z = mesh.coords.T
    tol = 1e-9 * a
    faces = [np.isclose(x, 0, atol=tol), np.isclose(y, 0, atol=tol),
             np.isclose(x, a, atol=tol), np.isclose(y, a, atol=tol)]
    normal_dof = [1, 2, 1, 2]          # x = const faces: normal x; tangential y (dof 2)
    clamped = np.zeros(len(x), bool)
    for e, face in zip(edges, faces):
        if e == "C":
            clamped |= face
    # corner-node columns carry 2 nz + 1 nodes, mid-side columns nz + 1
    corner_xy = set()
    for row in mesh.elements:
        for v in row[:8]:
            corner_xy.add((round(x[v - 1] / tol), round(y[v - 1] / tol)))
    tangential = {1: set(), 2: set()}
    equations = []
    done_columns = set()
    for e, face, ndof in zip(edges, faces, normal_dof):
        if e != "S":
            continue
        ids = np.flatnonzero(face & ~clamped) + 1
        tangential[3 - ndof].update(ids.tolist())
        keys = {}
        for i in ids:
            keys.setdefault((round(x[i - 1] / tol), round(y[i - 1] / tol)), []).append(i)
        for key, col in keys.items():
            if key in done_columns:
                continue
            done_columns.add(key)
            col = sorted(col, key=lambda i: z[i - 1])
            zc = z[np.array(col) - 1]
            expect = 2 * nz + 1 if key in corner_xy else nz + 1
            if len(col) != expect:
                raise RuntimeError(f"column {key}: {len(col)} nodes, expected {expect}")
            w = _column_weights(zc, key in corner_xy)
            # dependent term first: the mid-height node (largest weight)
            order = np.argsort(-w, kind="stable")
            equations.append([(col[k], w[k]) for k in order])
    mid = np.isclose(z, h / 2, atol=1e-9 * h)
    grid_ids = np.zeros((GRID, GRID), dtype=int)
    for i in range(GRID):
        for j in range(GRID):
            hit = np.flatnonzero(mid & np.isclose(x, a * i / (GRID - 1), atol=tol)
                                 & np.isclose(y, a * j / (GRID - 1), atol=tol))
            if hit.size != 1:
                raise RuntimeError(f"grid node ({i}, {j}) not found uniquely")
            grid_ids[i, j] = hit[0] + 1
    f = _Deck()
    f.write(f"*HEADING\nlevel 6 plate {edges} a/h {ratio}\n")
    ct.write_mesh(f, mesh, STEEL)
    ct.write_nset(f, "MID", np.flatnonzero(mid) + 1)
    ct.write_nset(f, "GRID", grid_ids.ravel())
    bc = []
    if clamped.any():
        ct.write_nset(f, "CLAMP", np.flatnonzero(clamped) + 1)
        bc.append("CLAMP,1,3")
    for dof, ids in tangential.items():
        if ids:
            ct.write_nset(f, f"TAN{dof}", sorted(ids))
            bc.append(f"TAN{dof},{dof},{dof}")
    if bc:
        f.write("*BOUNDARY\n" + "\n".join(bc) + "\n")
    if equations:
        f.write("*EQUATION\n")
        for eq in equations:
            f.write(f"{len(eq)}\n")
            terms = [f"{n},3,{c:.12e}" for n, c in eq]
            for k in range(0, len(terms), 4):
                f.write(",".join(terms[k:k + 4]) + "\n")
    f.write(f"*STEP\n*FREQUENCY\n{N_EIGEN}\n*NODE PRINT, NSET=MID\nU\n*END STEP\n")
    meta = dict(length_x_m=a, length_y_m=a, thickness_m=h, edges=edges,
                elements=[n_in_plane, n_in_plane, nz], element_type=mesh.element_type,
                n_nodes=len(mesh.coords), n_elements=len(mesh.elements),
                n_equations=len(equations))
    return f.text, meta, grid_ids


def classify(blocks):
    """Per mode: (in-plane rms / uz rms on the mid-surface nodes)."""
    ratios = []
    for block in blocks:
        u = np.array(list(block.values()))
        rms = np.sqrt((u ** 2).mean(axis=0))
        ratios.append(float(np.hypot(rms[0], rms[1]) / max(rms[2], 1e-300)))
    return ratios


def grid_shapes(blocks, grid_ids, keep):
    """Mid-surface uz of the modes ``keep`` on the grid, each scaled to max |uz| = 1."""
    out = []
    for k in keep:
        uz = np.array([[blocks[k][int(n)][2] for n in row] for row in grid_ids])
        out.append(uz / np.abs(uz).max())
    return np.array(out)


def run_solid(edges, ratio, density):
    n, nz = SOLID_MESHES[density]
    deck, meta, grid_ids = solid_deck(edges, ratio, n, nz)
    return _bending_modes(deck, f"solid_{edges}_{ratio}_{density}", "MID", grid_ids, dict(mesh=density, **meta))


def _bending_modes(deck, job, node_set, grid_ids, labels):
    """Run ``deck`` and keep its first N_BENDING bending modes (in-plane/uz rms < 0.05 on
    ``node_set``): ``(entry, shapes)``, the entry labelled ``case=job`` and ``labels``."""
    dat, wall = ct.run_ccx(deck, job, WORKDIR)
    text = dat.read_text()
    omegas = ct.parse_eigenvalues(text)
    blocks = ct.parse_node_prints(text, node_set)
    ratios = classify(blocks)
    bending = [k for k, r in enumerate(ratios) if r < 0.05]
    if len(bending) < N_BENDING:
        raise RuntimeError(f"{job}: only {len(bending)} bending modes among {len(omegas)}")
    keep = bending[:N_BENDING]
    shapes = grid_shapes(blocks, grid_ids, keep)
    entry = dict(case=job, **labels,
                 fe_bending_hz=[float(omegas[k] / (2 * np.pi)) for k in keep],
                 fe_bending_index=keep,
                 all_modes_hz=[float(w / (2 * np.pi)) for w in omegas],
                 inplane_to_uz_rms=ratios, wall_time_s=wall)
    return entry, shapes


# --------------------------------------------------------------------------- composite shell
def shell_deck(angles, nx, ny):
    """S8R CCCC composite plate deck (full laminate = angles + mirror)."""
    import gmsh
    lx, ly = SHELL_SIZE
    gmsh.initialize(["-noenv"])
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add("shell")
        gmsh.model.occ.addRectangle(0, 0, 0, lx, ly)
        gmsh.model.occ.synchronize()
        for dim, tag in gmsh.model.getEntities(1):
            xmin, ymin, _, xmax, ymax, _ = gmsh.model.getBoundingBox(dim, tag)
            gmsh.model.mesh.setTransfiniteCurve(tag, (nx if xmax - xmin > ymax - ymin else ny) + 1)
        for dim, tag in gmsh.model.getEntities(2):
            gmsh.model.mesh.setTransfiniteSurface(tag)
            gmsh.model.mesh.setRecombine(dim, tag)
        gmsh.option.setNumber("Mesh.SecondOrderIncomplete", 1)
        gmsh.option.setNumber("Mesh.ElementOrder", 2)
        gmsh.model.mesh.generate(2)
        tags, xyz, _ = gmsh.model.mesh.getNodes()
        xyz = xyz.reshape(-1, 3)
        etypes, _, enodes = gmsh.model.mesh.getElements(2)
        k = list(etypes).index(16)                     # 8-node quadrangle
        conn = np.asarray(enodes[k], dtype=np.int64).reshape(-1, 8)
    finally:
        gmsh.finalize()
    coords, index = ct.renumber_nodes(tags, xyz, conn)
    elements = index[conn]                 # gmsh and Abaqus 8-node quad orders agree
    # all elements with normal +z
    p = coords[elements[:, :3] - 1]
    normal = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])[:, 2]
    flip = normal < 0
    elements[flip] = elements[flip][:, [0, 3, 2, 1, 7, 6, 5, 4]]
    x, y = coords[:, 0], coords[:, 1]
    tol = 1e-9
    edge = (np.isclose(x, 0, atol=tol) | np.isclose(x, lx, atol=tol)
            | np.isclose(y, 0, atol=tol) | np.isclose(y, ly, atol=tol))
    full = list(angles) + list(angles)[::-1]
    f = _Deck()
    f.write("*HEADING\nlevel 6 composite shell\n*NODE, NSET=NALL\n")
    for i, (a, b, c) in enumerate(coords, start=1):
        f.write(f"{i},{a:.10e},{b:.10e},{c:.10e}\n")
    f.write("*ELEMENT, TYPE=S8R, ELSET=PLATE\n")
    for i, row in enumerate(elements, start=1):
        f.write(f"{i}," + ",".join(str(v) for v in row) + "\n")
    ct.write_nset(f, "EDGE", np.flatnonzero(edge) + 1)
    gx = np.isclose((x / (lx / 8)) % 1, 0, atol=1e-6) | np.isclose((x / (lx / 8)) % 1, 1, atol=1e-6)
    gy = np.isclose((y / (ly / 8)) % 1, 0, atol=1e-6) | np.isclose((y / (ly / 8)) % 1, 1, atol=1e-6)
    grid = gx & gy
    ct.write_nset(f, "GRID", np.flatnonzero(grid) + 1)
    f.write(ct.composite_shell_cards(PLY, full, PLY_THICKNESS, NU23))
    f.write("*BOUNDARY\nEDGE,1,6\n")
    f.write(f"*STEP\n*FREQUENCY\n{N_EIGEN}\n*NODE PRINT, NSET=GRID\nU\n*END STEP\n")
    gids = np.flatnonzero(grid) + 1
    order = np.lexsort((coords[gids - 1, 1], coords[gids - 1, 0]))
    grid_ids = gids[order].reshape(GRID, GRID)
    meta = dict(length_x_m=lx, length_y_m=ly, thickness_m=len(full) * PLY_THICKNESS,
                plies=len(full), ply_thickness_m=PLY_THICKNESS, stacking_full=full,
                edges="CCCC", elements=[nx, ny], element_type="S8R (ccx expands to C3D20R)",
                n_nodes=len(coords), n_elements=len(elements), edge_dofs_held="1-6",
                ply=dict(E1_Pa=PLY.longitudinal_modulus, E2_Pa=PLY.transverse_modulus, E3_Pa=PLY.transverse_modulus,
                         nu12=PLY.poisson_ratio, nu13=PLY.poisson_ratio, nu23=NU23, G12_Pa=PLY.shear_modulus,
                         G13_Pa=PLY.transverse_shear_modulus_13, G23_Pa=PLY.transverse_shear_modulus_23,
                         rho_kg_m3=PLY.density,
                         source="impactmaps/materials/catalogue.py 'as4-3501-6'"))
    return f.text, meta, grid_ids


def run_shell(layup, density):
    name, angles = LAYUPS[layup]
    nx, ny = SHELL_MESHES[density]
    deck, meta, grid_ids = shell_deck(angles, nx, ny)
    return _bending_modes(deck, f"shell_{layup}_{density}", "GRID", grid_ids,
                          dict(mesh=density, layup=name, **meta))


# --------------------------------------------------------------------------- bookkeeping
def _load():
    record = json.loads(JSON.read_text()) if JSON.exists() else {"cases": {}}
    shapes = dict(np.load(SHAPES)) if SHAPES.exists() else {}
    return record, shapes


def _save(record, shapes):
    JSON.parent.mkdir(parents=True, exist_ok=True)
    JSON.write_text(json.dumps(record, indent=1))
    np.savez_compressed(SHAPES, **shapes)


def _finish(entry, densities):
    """Best mesh = the finest run; ``mesh_difference`` = (second-best − best) / best per mode."""
    best, second = densities[-1], densities[-2]
    f = np.array(entry[best]["fe_bending_hz"])
    c = np.array(entry[second]["fe_bending_hz"])
    entry["best_mesh"] = best
    entry["mesh_pair"] = [second, best]
    entry["mesh_difference"] = ((c - f) / f).tolist()


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="kind", required=True)
    ps = sub.add_parser("solid")
    ps.add_argument("--case", action="append", required=True,
                    help="EDGES-RATIO, e.g. CCCC-20 (edges x=0, y=0, x=a, y=b)")
    ps.add_argument("--finest", action="store_true",
                    help="add the 32×32×4 mesh; the convergence pair is then fine/finest "
                         "(coarse and fine are re-run unless --reuse)")
    ps.add_argument("--reuse", action="store_true",
                    help="keep the committed coarse/fine runs of the case, run only the new mesh")
    pl = sub.add_parser("shell")
    pl.add_argument("--layup", action="append", required=True, choices=sorted(LAYUPS))
    args = parser.parse_args(argv)
    command = ("OMP_NUM_THREADS=1 FE_THREADS=1 nice -n 10 python validation/fe/level6_plates.py "
               + " ".join(argv if argv is not None else sys.argv[1:]))
    record, shapes = _load()
    record.update(ccx_version=ct.ccx_version(), gmsh_version=ct.gmsh_version(),
                  steel=dict(E_Pa=STEEL.youngs_modulus, nu=STEEL.poisson_ratio,
                             rho_kg_m3=STEEL.density))
    jobs = ([("solid", c) for c in args.case] if args.kind == "solid"
            else [("shell", c) for c in args.layup])
    for kind, name in jobs:
        densities = ("coarse", "fine") + (("finest",) if getattr(args, "finest", False) else ())
        key = f"solid-{name}" if kind == "solid" else f"shell-{name}"
        entry = {"command": command}
        todo = densities
        if getattr(args, "reuse", False) and key in record["cases"]:
            old = record["cases"][key]
            entry = dict(old, command=old["command"] + " ; " + command)
            todo = [d for d in densities if d not in old]
        for density in todo:
            t0 = time.perf_counter()
            if kind == "solid":
                edges, ratio = name.split("-")
                e, s = run_solid(edges, int(ratio), density)
                key = f"solid-{edges}-{ratio}"
            else:
                e, s = run_shell(name, density)
                key = f"shell-{name}"
            entry[density] = e
            if density == densities[-1]:
                shapes[key] = s.astype(np.float32)
            print(f"{key} {density}: {np.round(e['fe_bending_hz'], 1)} bending idx "
                  f"{e['fe_bending_index']} (ccx {e['wall_time_s']:.0f} s, total "
                  f"{time.perf_counter() - t0:.0f} s)", flush=True)
        _finish(entry, densities)
        print(f"   mesh difference {'-'.join(entry['mesh_pair'])} [%]: {np.round(100 * np.array(entry['mesh_difference']), 3)}",
              flush=True)
        record["cases"][key] = entry
        _save(record, shapes)
    return record


if __name__ == "__main__":
    main()
