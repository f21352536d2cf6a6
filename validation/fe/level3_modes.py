"""Level 3, step 1: the 3D modes of the struck beam seen from a loaded patch (CalculiX).

Quarter model of a simply supported steel beam (span L, section b × h) struck at
mid-span: x ∈ [0, L/2] (x = 0 the mid-span plane, ux = 0), y ∈ [0, b/2] (y = 0 the
mid-width plane, uy = 0), z ∈ [−h, 0] (z = 0 the struck top face); the end face
x = L/2 held in z (the diaphragm support that matches the Timoshenko simply supported
end, see level 1).  A quarter disc of radius ``a_c`` centred on the impact point is a
separate surface of the top face; the mesh (10-node tetrahedra C3D10) is graded from
``a_c / refine`` on the patch to ``h / 4`` away from it.

One ccx run, two steps:

1. *STATIC: a uniform pressure on the patch (consistent nodal loads: the mid-side
   nodes of each 6-node face triangle carry a third of its load, the corners none),
   total 1 N on the quarter → the static compliance of the patch (mean deflection,
   the work-conjugate of the uniform pressure).
2. *FREQUENCY: the lowest ``n_modes`` modes (ccx normalises them to unit modal mass
   over the quarter), the patch mean of each.

Full-structure quantities: a mode of the quarter with unit quarter mass is a mode of
the whole beam with mass 4, so the full mass-normalised patch participation is
``p_j = mean_patch(φ_j) / 2``; a total force F on the full patch puts F/4 on the
quarter, so the full static compliance is ``C = u_quarter(1 N) / 4``.

Output: ``validation/fe/results/level3_modes_<tag>.npz`` + a JSON side car (inputs,
mesh, ccx version, wall time, command).
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


def quarter_beam_mesh(length, width, height, patch_radius, refine, far_size):
    """C3D10 mesh of the quarter beam with a quarter-disc patch; returns (mesh, patch tris)."""
    import gmsh
    gmsh.initialize(["-noenv"])
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add("quarter")
        occ = gmsh.model.occ
        box = occ.addBox(0, 0, -height, length / 2, width / 2, height)
        disk = occ.addDisk(0, 0, 0, patch_radius, patch_radius)
        rect = occ.addRectangle(0, 0, 0, 2 * patch_radius, 2 * patch_radius)
        quarter, _ = occ.intersect([(2, disk)], [(2, rect)])
        occ.fragment([(3, box)], quarter)
        occ.synchronize()
        patch = [tag for dim, tag in gmsh.model.getEntities(2)
                 if _inside(gmsh.model.getBoundingBox(dim, tag), patch_radius)]
        if len(patch) != 1:
            raise RuntimeError(f"patch surface not found uniquely: {patch}")
        fine = patch_radius / refine
        gmsh.model.mesh.field.add("Distance", 1)
        gmsh.model.mesh.field.setNumbers(1, "PointsList", [])
        curves = [c for _, c in gmsh.model.getBoundary([(2, patch[0])], oriented=False)]
        gmsh.model.mesh.field.setNumbers(1, "SurfacesList", patch)
        gmsh.model.mesh.field.setNumber(1, "Sampling", 40)
        gmsh.model.mesh.field.add("MathEval", 2)
        # size grows linearly (ratio ~0.35 per unit distance) from the patch outwards
        gmsh.model.mesh.field.setString(2, "F", f"Min({fine} + 0.35*F1, {far_size})")
        gmsh.model.mesh.field.setAsBackgroundMesh(2)
        gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
        gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
        gmsh.option.setNumber("Mesh.ElementOrder", 2)
        gmsh.option.setNumber("Mesh.Optimize", 1)
        gmsh.option.setNumber("Mesh.HighOrderOptimize", 0)
        gmsh.model.mesh.generate(3)
        mesh = ct._collect(gmsh, 11, ct.TET10_GMSH_TO_CCX, "C3D10")
        # patch triangles (6-node), in gmsh node tags -> map to mesh ids by coordinates
        etypes, _, enodes = gmsh.model.mesh.getElements(2, patch[0])
        tags, xyz, _ = gmsh.model.mesh.getNodes()
        tri = np.asarray(enodes[list(etypes).index(9)], dtype=np.int64).reshape(-1, 6)
        pos = dict(zip(tags.astype(np.int64), xyz.reshape(-1, 3)))
        tri_xyz = np.array([[pos[t] for t in row] for row in tri])
        del curves
    finally:
        gmsh.finalize()
    ids = _match_nodes(mesh.coords, tri_xyz.reshape(-1, 3)).reshape(-1, 6)
    return mesh, ids, tri_xyz


def _inside(bbox, radius):
    xmin, ymin, zmin, xmax, ymax, zmax = bbox
    return (abs(zmin) < 1e-6 and abs(zmax) < 1e-6 and xmax <= radius * 1.01
            and ymax <= radius * 1.01)


def _match_nodes(coords, points):
    from scipy.spatial import cKDTree
    dist, idx = cKDTree(coords).query(points)
    if dist.max() > 1e-9:
        raise RuntimeError("patch node not found in the volume mesh")
    return idx + 1


def patch_weights(tri_ids, tri_xyz):
    """Node ids and weights (summing to 1) of the uniform pressure on the patch.

    Consistent loads of a 6-node triangle under uniform traction: corners 0, each
    mid-side node one third of the triangle's load (areas from the straight-sided
    triangle of the corners).
    """
    a, b, c = tri_xyz[:, 0], tri_xyz[:, 1], tri_xyz[:, 2]
    area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)
    weights = {}
    for row, ar in zip(tri_ids, area):
        for node in row[3:]:
            weights[int(node)] = weights.get(int(node), 0.0) + ar / 3
    ids = np.array(sorted(weights))
    w = np.array([weights[i] for i in ids])
    return ids, w / w.sum(), float(area.sum())


def build_deck(mesh, length, height, patch_ids, patch_w, n_modes, plate_width=None,
               clamped=False):
    """Quarter-model deck: static patch load step + *FREQUENCY step.

    Beam (``plate_width`` None): end face x = L/2 held in z.  Plate (square, side
    ``length`` = ``plate_width``): the side faces x = a/2 and y = a/2 held in z and in
    their tangential direction (the hard simple support of level 1); with ``clamped`` the
    side faces held in x, y and z (the 3D clamp of level 6, PHYSICS.md §3.7).
    """
    x, y, z = mesh.coords.T
    tol = 1e-9
    parts = []
    w = parts.append

    class F:
        write = staticmethod(w)
    ct.write_mesh(F, mesh, STEEL)
    ct.write_nset(F, "XSYM", mesh.nodes_where(np.isclose(x, 0, atol=tol)))
    ct.write_nset(F, "YSYM", mesh.nodes_where(np.isclose(y, 0, atol=tol)))
    ct.write_nset(F, "END", mesh.nodes_where(np.isclose(x, length / 2, atol=tol)))
    ct.write_nset(F, "PATCH", patch_ids)
    w("*BOUNDARY\nXSYM,1,1\nYSYM,2,2\nEND,3,3\n")
    if plate_width is not None:
        ct.write_nset(F, "YEND", mesh.nodes_where(np.isclose(y, plate_width / 2, atol=tol)))
        if clamped:
            w("*BOUNDARY\nEND,1,2\nYEND,1,3\n")
        else:
            w("*BOUNDARY\nEND,2,2\nYEND,1,1\nYEND,3,3\n")
    w("*STEP\n*STATIC\n*CLOAD\n")
    for node, weight in zip(patch_ids, patch_w):
        w(f"{node},3,{-weight:.12e}\n")
    w("*NODE PRINT, NSET=PATCH\nU\n*END STEP\n")
    w(f"*STEP\n*FREQUENCY\n{n_modes}\n*NODE PRINT, NSET=PATCH\nU\n*END STEP\n")
    return "*HEADING\nlevel 3 quarter beam modes\n" + "".join(parts)


def run(tag, length, width, height, patch_radius, refine, far_size, n_modes, plate=False,
        clamped=False):
    t0 = time.perf_counter()
    mesh, tri_ids, tri_xyz = quarter_beam_mesh(length, width, height, patch_radius,
                                               refine, far_size)
    mesh_time = time.perf_counter() - t0
    patch_ids, patch_w, patch_area = patch_weights(tri_ids, tri_xyz)
    deck = build_deck(mesh, length, height, patch_ids, patch_w, n_modes,
                      plate_width=width if plate else None, clamped=clamped)
    dat, wall = ct.run_ccx(deck, tag, ct.WORK / "level3")
    text = dat.read_text()
    blocks = ct.parse_node_prints(text, "PATCH")
    static, modes = blocks[0], blocks[1:]
    omega = ct.parse_eigenvalues(text)
    mean = lambda block: float(np.dot(patch_w, [-block[i][2] for i in patch_ids]))
    compliance = mean(static) / 4.0                 # full beam, force into the target
    phi_patch = np.array([mean(b) for b in modes]) / 2.0
    out = ct.RESULTS / f"level3_modes_{tag}.npz"
    np.savez(out, omega=omega, participation=phi_patch, static_compliance=compliance)
    meta = dict(tag=tag, structure=("plate CCCC" if clamped else "plate SSSS") if plate else "beam SS", length_m=length, width_m=width, height_m=height,
                patch_radius_m=patch_radius, patch_area_quarter_m2=patch_area,
                patch_area_exact_quarter_m2=np.pi * patch_radius ** 2 / 4,
                element_type=mesh.element_type, size_on_patch_m=patch_radius / refine,
                size_far_m=far_size, n_nodes=len(mesh.coords),
                n_elements=len(mesh.elements), n_modes=n_modes,
                static_compliance_m_per_N=compliance,
                highest_frequency_hz=float(omega[-1] / 2 / np.pi),
                ccx_version=ct.ccx_version(), gmsh_version=ct.gmsh_version(),
                mesh_time_s=mesh_time, ccx_wall_time_s=wall,
                material=dict(E_Pa=STEEL.youngs_modulus, nu=STEEL.poisson_ratio,
                              rho_kg_m3=STEEL.density),
                command="python validation/fe/level3_modes.py " + " ".join(sys.argv[1:]))
    (ct.RESULTS / f"level3_modes_{tag}.json").write_text(json.dumps(meta, indent=1))
    print(json.dumps(meta, indent=1))
    return meta


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--tag", required=True)
    p.add_argument("--length", type=float, default=0.5)
    p.add_argument("--width", type=float, default=0.02)
    p.add_argument("--height", type=float, default=0.02)
    p.add_argument("--patch-radius", type=float, required=True)
    p.add_argument("--refine", type=float, default=4.0,
                   help="elements across the patch radius")
    p.add_argument("--far-size", type=float, default=0.005)
    p.add_argument("--modes", type=int, default=60)
    p.add_argument("--plate", action="store_true",
                   help="square SSSS plate of side --length (= --width), thickness --height")
    p.add_argument("--clamped", action="store_true",
                   help="with --plate: the side faces fully held (CCCC, the 3D clamp)")
    a = p.parse_args()
    if a.clamped and not a.plate:
        p.error("--clamped needs --plate")
    run(a.tag, a.length, a.width, a.height, a.patch_radius, a.refine, a.far_size, a.modes,
        plate=a.plate, clamped=a.clamped)


if __name__ == "__main__":
    main()
