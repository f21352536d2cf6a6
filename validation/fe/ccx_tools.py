"""Shared helpers of the CalculiX cross-checks: gmsh meshes, ccx decks, .dat parsing.

Nothing here is part of the toolkit: these scripts only produce reference numbers
(committed under ``validation/fe/results/``) that the default test suite compares
with the current toolkit.  Units are SI throughout (m, kg, s, N, Pa).
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
# The scripts run as ``python validation/fe/<script>.py``: put the repository root
# first on the path so that ``import impactmaps`` is this checkout's package.
if str(HERE.parents[1]) not in sys.path:
    sys.path.insert(0, str(HERE.parents[1]))
RESULTS = HERE / "results"
WORK = HERE.parent / "work" / "fe"          # git-ignored (validation/work/)

# gmsh 20-node hexahedron -> Abaqus/CalculiX C3D20 node order (corners identical;
# gmsh lists the edges (0,1),(0,3),(0,4),(1,2),(1,5),(2,3),(2,6),(3,7),(4,5),(4,7),
# (5,6),(6,7); Abaqus (0,1),(1,2),(2,3),(3,0),(4,5),(5,6),(6,7),(7,4),(0,4),(1,5),
# (2,6),(3,7)).
HEX20_GMSH_TO_CCX = np.array([0, 1, 2, 3, 4, 5, 6, 7,
                              8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15])
# gmsh 10-node tetrahedron: corners, then edges (0,1),(1,2),(2,0),(0,3),(2,3),(1,3);
# Abaqus C3D10: corners, then (0,1),(1,2),(2,0),(0,3),(1,3),(2,3).
TET10_GMSH_TO_CCX = np.array([0, 1, 2, 3, 4, 5, 6, 7, 9, 8])


def ccx_version() -> str:
    """Version string printed by ``ccx -v`` (e.g. ``"2.20"``)."""
    out = subprocess.run(["ccx", "-v"], capture_output=True, text=True).stdout
    match = re.search(r"Version\s+(\S+)", out)
    return match.group(1) if match else out.strip()


def gmsh_version() -> str:
    import gmsh
    return gmsh.__version__


@dataclass
class Mesh:
    """Nodes (ids 1..n, coordinates [m]) and solid elements in CalculiX order."""

    coords: np.ndarray          # (n, 3)
    elements: np.ndarray        # (e, nodes per element), 1-based node ids
    element_type: str           # "C3D20R", "C3D20", "C3D10"

    def nodes_where(self, mask) -> np.ndarray:
        """1-based ids of the nodes selected by a boolean mask over ``coords``."""
        return np.flatnonzero(mask) + 1


def structured_box(lx, ly, lz, nx, ny, nz, element_type="C3D20R") -> Mesh:
    """Structured 20-node hexahedral mesh of the box [0,lx]×[0,ly]×[0,lz] made by gmsh.

    ``nx, ny, nz`` elements along each side (transfinite, recombined, serendipity
    second order).
    """
    import gmsh
    gmsh.initialize(["-noenv"])
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add("box")
        gmsh.model.occ.addBox(0, 0, 0, lx, ly, lz)
        gmsh.model.occ.synchronize()
        for dim, tag in gmsh.model.getEntities(1):
            xmin, ymin, zmin, xmax, ymax, zmax = gmsh.model.getBoundingBox(dim, tag)
            spans = np.array([xmax - xmin, ymax - ymin, zmax - zmin])
            n = (nx, ny, nz)[int(np.argmax(spans))]
            gmsh.model.mesh.setTransfiniteCurve(tag, n + 1)
        for dim, tag in gmsh.model.getEntities(2):
            gmsh.model.mesh.setTransfiniteSurface(tag)
            gmsh.model.mesh.setRecombine(dim, tag)
        for dim, tag in gmsh.model.getEntities(3):
            gmsh.model.mesh.setTransfiniteVolume(tag)
        gmsh.option.setNumber("Mesh.SecondOrderIncomplete", 1)
        gmsh.option.setNumber("Mesh.ElementOrder", 2)
        gmsh.model.mesh.generate(3)
        return _collect(gmsh, 17, HEX20_GMSH_TO_CCX, element_type)
    finally:
        gmsh.finalize()


def _collect(gmsh, gmsh_type, order, element_type) -> Mesh:
    """Renumber the gmsh nodes 1..n and return the elements of ``gmsh_type``."""
    return collect_indexed(gmsh, gmsh_type, order, element_type)[0]


def collect_indexed(gmsh, gmsh_type, order, element_type) -> tuple[Mesh, np.ndarray]:
    """As :func:`_collect`, also returning ``index``: gmsh node tag -> mesh node id
    (0 for a tag used by no element of ``gmsh_type``)."""
    tags, xyz, _ = gmsh.model.mesh.getNodes()
    xyz = xyz.reshape(-1, 3)
    etypes, _, enodes = gmsh.model.mesh.getElements(3)
    k = list(etypes).index(gmsh_type)
    conn = np.asarray(enodes[k], dtype=np.int64).reshape(-1, len(order))[:, order]
    coords, index = renumber_nodes(tags, xyz, conn)
    return Mesh(coords=coords, elements=index[conn], element_type=element_type), index


def renumber_nodes(tags, xyz, conn) -> tuple[np.ndarray, np.ndarray]:
    """The nodes the elements ``conn`` (gmsh tags) use, numbered 1..n in tag order: their
    coordinates (n, 3) [m] and ``index`` (gmsh tag -> node id, 0 for an unused tag), from
    gmsh's node ``tags`` and coordinates ``xyz`` (len(tags), 3)."""
    used = np.unique(conn)
    index = np.zeros(int(tags.max()) + 1, dtype=np.int64)
    index[used] = np.arange(1, used.size + 1)
    lookup = np.zeros(int(tags.max()) + 1, dtype=np.int64)
    lookup[tags.astype(np.int64)] = np.arange(tags.size)
    return xyz[lookup[used]], index


def use_background_field(gmsh, field) -> None:
    """Size the elements by the gmsh size field ``field`` alone (not from boundaries, points or curvature)."""
    gmsh.model.mesh.field.setAsBackgroundMesh(field)
    for name in ("MeshSizeExtendFromBoundary", "MeshSizeFromPoints",
                 "MeshSizeFromCurvature"):
        gmsh.option.setNumber(f"Mesh.{name}", 0)


def quarter_contact_mesh(gmsh, sphere_volume, target, size, far_sizes):
    """The C3D10 mesh of the quarter models (levels 2, 4): the sphere (OCC volume dim-tag
    ``sphere_volume``) on the volume ``target`` whose top face lies in z = 0, in the
    current gmsh model, synchronised.

    Element size ``size.format(far=far)`` [m] (a gmsh MathEval formula) in each volume,
    ``far_sizes`` = (sphere's far, target's far); quadratic, optimised tetrahedra.
    Returns the mesh, ``index`` (:func:`collect_indexed`) and the 6-node triangles (mesh
    node ids) of the sphere's curved surface (``"slave"``) and the target's top
    (``"master"``).
    """
    curved = [t for d, t in gmsh.model.getBoundary([sphere_volume], oriented=False)
              if gmsh.model.getType(2, t) == "Sphere"]
    top = [t for d, t in gmsh.model.getBoundary([(3, target)], oriented=False)
           if np.allclose(gmsh.model.getBoundingBox(2, t)[2::3], 0.0, atol=1e-6)]
    if len(curved) != 1 or len(top) != 1:
        raise RuntimeError(f"contact surfaces not found: {curved}, {top}")
    field = gmsh.model.mesh.field
    for k, (volume, far) in enumerate(((sphere_volume[1], far_sizes[0]), (target, far_sizes[1]))):
        field.add("MathEval", 2 * k + 1)
        field.setString(2 * k + 1, "F", size.format(far=far))
        field.add("Restrict", 2 * k + 2)
        field.setNumber(2 * k + 2, "InField", 2 * k + 1)
        field.setNumbers(2 * k + 2, "VolumesList", [volume])
    field.add("Min", 5)
    field.setNumbers(5, "FieldsList", [2, 4])
    use_background_field(gmsh, 5)
    gmsh.option.setNumber("Mesh.ElementOrder", 2)
    gmsh.option.setNumber("Mesh.Optimize", 1)
    gmsh.model.mesh.generate(3)
    mesh, index = collect_indexed(gmsh, 11, TET10_GMSH_TO_CCX, "C3D10")
    tris = {}
    for key, surface in (("slave", curved[0]), ("master", top[0])):
        etypes, _, enodes = gmsh.model.mesh.getElements(2, surface)
        tri = np.asarray(enodes[list(etypes).index(9)], dtype=np.int64).reshape(-1, 6)
        tris[key] = index[tri]
    return mesh, index, tris


# Faces of a C3D10 element (Abaqus labels S1..S4) by their corner nodes (0-based).
TET_FACES = {"S1": (0, 1, 2), "S2": (0, 3, 1), "S3": (1, 3, 2), "S4": (2, 3, 0)}


def tet_faces_on(mesh: Mesh, triangles) -> list[tuple[int, str]]:
    """(element id, face label) of the tetrahedron faces whose corners are ``triangles``.

    ``triangles``: (t, >=3) mesh node ids, corners first (e.g. the 6-node boundary
    triangles of a gmsh surface, renumbered).  Raises if a triangle is no element face.
    """
    lookup = {}
    for e, row in enumerate(mesh.elements, start=1):
        for label, corners in TET_FACES.items():
            lookup[frozenset(int(row[c]) for c in corners)] = (e, label)
    faces = []
    for tri in np.asarray(triangles)[:, :3]:
        key = frozenset(int(v) for v in tri)
        if key not in lookup:
            raise RuntimeError(f"surface triangle {tuple(tri)} is not an element face")
        faces.append(lookup[key])
    return faces


def write_element_surface(f, name, faces):
    """``*SURFACE, TYPE=ELEMENT`` from (element id, face label) pairs."""
    f.write(f"*SURFACE, NAME={name}, TYPE=ELEMENT\n")
    for element, label in faces:
        f.write(f"{element},{label}\n")


def write_mesh(f, mesh: Mesh, material, elset="SOLID"):
    """Write *NODE, *ELEMENT, *MATERIAL and *SOLID SECTION blocks."""
    f.write("*NODE, NSET=NALL\n")
    for i, (x, y, z) in enumerate(mesh.coords, start=1):
        f.write(f"{i},{x:.10e},{y:.10e},{z:.10e}\n")
    f.write(f"*ELEMENT, TYPE={mesh.element_type}, ELSET={elset}\n")
    for i, row in enumerate(mesh.elements, start=1):
        ids = [str(i)] + [str(v) for v in row]
        # at most 16 entries per line in Abaqus format
        lines = [ids[j:j + 16] for j in range(0, len(ids), 16)]
        f.write(",\n".join(",".join(chunk) for chunk in lines) + "\n")
    f.write("*MATERIAL, NAME=MAT\n*ELASTIC\n"
            f"{material.youngs_modulus:.6e},{material.poisson_ratio}\n"
            f"*DENSITY\n{material.density}\n")
    f.write(f"*SOLID SECTION, ELSET={elset}, MATERIAL=MAT\n")


def write_nset(f, name, ids):
    f.write(f"*NSET, NSET={name}\n")
    ids = [str(int(i)) for i in ids]
    for j in range(0, len(ids), 16):
        f.write(",".join(ids[j:j + 16]) + "\n")


def run_ccx(deck_text: str, job: str, workdir: Path) -> tuple[Path, float]:
    """Write ``job.inp`` in ``workdir``, run ccx on it, return (.dat path, wall time [s])."""
    workdir.mkdir(parents=True, exist_ok=True)
    (workdir / f"{job}.inp").write_text(deck_text)
    env = dict(os.environ, OMP_NUM_THREADS=os.environ.get("FE_THREADS", "2"))
    start = time.perf_counter()
    proc = subprocess.run(["ccx", "-i", job], cwd=workdir, capture_output=True,
                          text=True, env=env)
    wall = time.perf_counter() - start
    (workdir / f"{job}.log").write_text(proc.stdout + proc.stderr)
    dat = workdir / f"{job}.dat"
    if proc.returncode != 0 or "*ERROR" in proc.stdout or not dat.exists():
        tail = "\n".join((proc.stdout + proc.stderr).splitlines()[-25:])
        raise RuntimeError(f"ccx failed on {workdir / job}.inp:\n{tail}")
    return dat, wall


def parse_eigenvalues(dat_text: str) -> np.ndarray:
    """Angular frequencies ω [rad/s] of the EIGENVALUE OUTPUT table of a .dat file."""
    block = dat_text.split("E I G E N V A L U E   O U T P U T", 1)[1]
    block = block.split("P A R T I C I P A T I O N", 1)[0]
    omegas = []
    for line in block.splitlines():
        parts = line.split()
        if len(parts) == 5 and parts[0].isdigit():
            omegas.append(float(parts[2]))
    return np.array(omegas)


_HEADER = re.compile(r"displacements \(vx,vy,vz\) for set (\S+) and time\s+(\S+)")


def parse_node_prints(dat_text: str, nset: str):
    """All ``displacements`` blocks of ``nset``: list of dicts node -> (ux, uy, uz).

    In a *FREQUENCY step there is one block per mode, in mode order.
    """
    blocks = []
    current = None
    for line in dat_text.splitlines():
        m = _HEADER.search(line)
        if m:
            current = {} if m.group(1).upper() == nset.upper() else None
            if current is not None:
                blocks.append(current)
            continue
        if " for set " in line or "E I G E N" in line or "S T E P" in line:
            current = None
            continue
        parts = line.split()
        if current is not None and len(parts) == 4 and parts[0].isdigit():
            current[int(parts[0])] = tuple(_fortran_float(v) for v in parts[1:])
    return blocks


def parse_node_print_times(dat_text: str, nset: str) -> np.ndarray:
    """Times of the ``displacements`` blocks of ``nset`` (same order as
    :func:`parse_node_prints`)."""
    return np.array([_fortran_float(m.group(2)) for m in _HEADER.finditer(dat_text)
                     if m.group(1).upper() == nset.upper()])


def _fortran_float(text: str) -> float:
    """Parse ccx numbers, including three-digit exponents written without ``E``."""
    try:
        return float(text)
    except ValueError:
        return float(re.sub(r"(\d)([+-]\d{3})$", r"\1E\2", text))


def have_fe_tools() -> tuple[bool, str]:
    """(available, reason) for the ``ccx`` executable and the ``gmsh`` Python module."""
    if shutil.which("ccx") is None:
        return False, "CalculiX `ccx` not on PATH (apt-get install calculix-ccx)"
    try:
        import gmsh  # noqa: F401
    except ImportError:
        return False, "Python module `gmsh` missing (pip install -e '.[fe]')"
    return True, ""


def write_mesh_parts(f, mesh: Mesh, parts):
    """Write *NODE and, per part, *ELEMENT, *MATERIAL and *SOLID SECTION blocks.

    ``parts``: sequence of (elset name, boolean mask over ``mesh.elements``, material
    name, material text) — the material text is the ccx cards that follow
    ``*MATERIAL, NAME=...`` (e.g. from :func:`material_cards`).  Element ids stay those
    of ``mesh.elements`` (1-based rows), so surfaces from :func:`tet_faces_on` hold.
    """
    f.write("*NODE, NSET=NALL\n")
    for i, (x, y, z) in enumerate(mesh.coords, start=1):
        f.write(f"{i},{x:.10e},{y:.10e},{z:.10e}\n")
    for elset, mask, name, cards in parts:
        f.write(f"*ELEMENT, TYPE={mesh.element_type}, ELSET={elset}\n")
        for i in np.flatnonzero(mask):
            ids = [str(i + 1)] + [str(v) for v in mesh.elements[i]]
            lines = [ids[j:j + 16] for j in range(0, len(ids), 16)]
            f.write(",\n".join(",".join(chunk) for chunk in lines) + "\n")
    for elset, _mask, name, cards in parts:
        f.write(f"*MATERIAL, NAME={name}\n{cards}")
        f.write(f"*SOLID SECTION, ELSET={elset}, MATERIAL={name}\n")


def material_cards(material, yield_strength=None) -> str:
    """*ELASTIC and *DENSITY cards of ``material``, plus an elastic–perfectly plastic
    *PLASTIC card (von Mises, no hardening) when ``yield_strength`` [Pa] is given."""
    cards = (f"*ELASTIC\n{material.youngs_modulus:.6e},{material.poisson_ratio}\n"
             f"*DENSITY\n{material.density}\n")
    if yield_strength is not None:
        cards += f"*PLASTIC\n{yield_strength:.6e},0.0\n"
    return cards


def tet10_mass_weights(mesh: Mesh, mask, density, order: int = 4) -> np.ndarray:
    """Row sums s_j = ∫ ρ N_j dV [kg] of the consistent mass matrix of the C3D10
    elements in ``mask`` (isoparametric, curved mid-side nodes included).

    Σ_j s_j u_j = 1ᵀ M u is the body's mass times its centre-of-mass displacement,
    exactly.  (For a straight-sided tetrahedron of mass m_e the sums are −m_e/20 at
    the corners and m_e/5 at the mid-side nodes.)  Integrated with a collapsed
    Gauss–Legendre rule of ``order``³ points.  Returns an array over all mesh nodes
    (0 off the selected elements).
    """
    g, gw = np.polynomial.legendre.leggauss(order)
    g, gw = 0.5 * (g + 1.0), 0.5 * gw
    u, v, w = (a.ravel() for a in np.meshgrid(g, g, g, indexing="ij"))
    wu, wv, ww = (a.ravel() for a in np.meshgrid(gw, gw, gw, indexing="ij"))
    l1, l2, l3 = u, v * (1 - u), w * (1 - u) * (1 - v)
    weight = wu * wv * ww * (1 - u) ** 2 * (1 - v)         # sums to 1/6
    lam = np.stack([1 - l1 - l2 - l3, l1, l2, l3])         # (4, q)
    edges = ((0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3))
    shape = np.concatenate([lam * (2 * lam - 1),
                            np.stack([4 * lam[a] * lam[b] for a, b in edges])])   # (10, q)
    dlam = np.array([[-1, -1, -1], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    dshape = np.concatenate(
        [(4 * lam - 1)[:, :, None] * dlam[:, None, :],
         np.stack([4 * (lam[a][:, None] * dlam[b] + lam[b][:, None] * dlam[a])
                   for a, b in edges])])                   # (10, q, 3)
    elements = mesh.elements[np.asarray(mask)] - 1
    xyz = mesh.coords[elements]                            # (e, 10, 3)
    jac = np.einsum("ekx,kqd->eqxd", xyz, dshape)          # (e, q, 3, 3)
    dv = np.abs(np.linalg.det(jac)) * weight               # (e, q)
    rows = density * np.einsum("kq,eq->ek", shape, dv)     # (e, 10)
    weights = np.zeros(len(mesh.coords))
    np.add.at(weights, elements, rows)
    return weights


def write_quarter_contact(f, mesh: Mesh, faces, slope, tol=1e-9):
    """Symmetry sets and the sphere–target contact of the quarter models (levels 2, 4).

    Writes the node sets ``XSYM`` (x = 0) and ``YSYM`` (y = 0), the element surfaces
    ``SSPH`` (``faces["slave"]``) and ``STGT`` (``faces["master"]``), and a frictionless
    ``*CONTACT PAIR, TYPE=SURFACE TO SURFACE`` with a linear penalty of ``slope``
    [Pa/m].  The caller writes ``*BOUNDARY`` (``XSYM,1,1`` / ``YSYM,2,2``).
    """
    x, y, _ = mesh.coords.T
    write_nset(f, "XSYM", mesh.nodes_where(np.isclose(x, 0, atol=tol)))
    write_nset(f, "YSYM", mesh.nodes_where(np.isclose(y, 0, atol=tol)))
    write_element_surface(f, "SSPH", faces["slave"])
    write_element_surface(f, "STGT", faces["master"])
    f.write("*CONTACT PAIR, INTERACTION=SI1, TYPE=SURFACE TO SURFACE\nSSPH,STGT\n"
            "*SURFACE INTERACTION, NAME=SI1\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n"
            f"{slope:.6e}\n")


class Deck:
    """A ccx deck being written: ``write`` appends a card's text; ``text(heading)`` is the deck."""

    def __init__(self):
        self.parts = []

    def write(self, text: str) -> None:
        self.parts.append(text)

    def text(self, heading: str) -> str:
        return f"*HEADING\n{heading}\n" + "".join(self.parts)


def composite_shell_cards(ply, angles, ply_thickness: float, nu23: float, elset: str = "PLATE") -> str:
    """The ``*MATERIAL`` (engineering constants of ``ply``, an impactmaps ply), one ``*ORIENTATION``
    per ply angle [deg] and the ``*SHELL SECTION, COMPOSITE`` of ``elset`` with one line per ply
    of ``angles`` (bottom to top), each ``ply_thickness`` [m] thick; ``nu23`` is the ply's
    transverse Poisson ratio (not in the catalogue)."""
    e1, e2, g12, nu12 = ply.longitudinal_modulus, ply.transverse_modulus, ply.shear_modulus, ply.poisson_ratio
    text = ["*MATERIAL, NAME=PLY\n*ELASTIC, TYPE=ENGINEERING CONSTANTS\n"
            f"{e1:.6e},{e2:.6e},{e2:.6e},{nu12},{nu12},{nu23},{g12:.6e},{ply.transverse_shear_modulus_13:.6e},\n"
            f"{ply.transverse_shear_modulus_23:.6e}\n*DENSITY\n{ply.density}\n"]
    for ang in sorted(set(angles)):
        c, s = np.cos(np.radians(ang)), np.sin(np.radians(ang))
        text.append(f"*ORIENTATION, NAME=OR{ang + 90:.0f}, SYSTEM=RECTANGULAR\n"
                    f"{c:.12f},{s:.12f},0.,{-s:.12f},{c:.12f},0.\n")
    text.append(f"*SHELL SECTION, ELSET={elset}, COMPOSITE\n")
    text.extend(f"{ply_thickness:.6e},,PLY,OR{ang + 90:.0f}\n" for ang in angles)
    return "".join(text)
