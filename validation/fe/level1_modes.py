"""Level 1: natural frequencies of the 3D solid (CalculiX *FREQUENCY) against the toolkit.

Beams (steel, 20 × 20 mm section, span/height 5, 10, 20, 50) are modelled on half
the width (symmetry plane y = 0: uy = 0, which keeps the vertical-bending family and
removes lateral bending and torsion).  Supports of the solid:

* ``face`` — the whole end faces held in z (uz = 0), ux = 0 on the neutral-axis line of
  the x = 0 face only (removes the axial rigid motion; bending puts no axial
  displacement there).  This is the 3D "diaphragm" support, the analogue of a
  Timoshenko simply supported end (w = 0, free rotation and free warping).
* ``edge`` — knife edges under the bottom face: uz = 0 on the bottom edge lines
  (z = 0) at x = 0 and x = L, ux = 0 on the x = 0 line (pin–roller, as a test rig).
* ``clamped`` — both end faces fully held (ux = uy = uz = 0).
* ``clampxz`` — both end faces held in x and z only (the width may contract: no
  lateral Poisson restraint at the clamp).

SSSS square plates (steel, h = 10 mm, span/thickness 10, 20, 50) are the full plate
with the side faces held in z and in the tangential direction (the 3D analogue of the
"hard" simply supported edge of the Navier/Mindlin solution: w = 0, tangential rotation
0), or (``edge``) held in z on the bottom edge lines only, in-plane motion held on the
same lines.

Run ``python validation/fe/level1_modes.py --all`` (or ``--case beam-face-10``) from
the repository root; results go to ``validation/fe/results/level1_modes.json``.
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
BEAM_HEIGHT = 0.020          # m (section 20 × 20 mm)
BEAM_WIDTH = 0.020
PLATE_THICKNESS = 0.010      # m
N_BENDING = 5
BEAM_RATIOS = (5, 10, 20, 50)
PLATE_RATIOS = (10, 20, 50)
# Mesh densities: elements through the depth; the element size is kept ~cubic for the
# beams (depth/nz) and is span/n_in_plane for the plates.
BEAM_MESHES = {"coarse": 2, "fine": 4, "finest": 8}
PLATE_MESHES = {"coarse": (16, 2), "fine": (32, 4)}


def beam_deck(ratio, support, nz):
    """CalculiX deck and metadata of the half-width beam of span/height ``ratio``."""
    h, b = BEAM_HEIGHT, BEAM_WIDTH
    length = ratio * h
    size = h / nz
    nx, ny = int(round(length / size)), max(1, int(round(b / 2 / size)))
    mesh = ct.structured_box(length, b / 2, h, nx, ny, nz)
    x, y, z = mesh.coords.T
    tol = 1e-9
    at0, atL = np.isclose(x, 0, atol=tol), np.isclose(x, length, atol=tol)
    bottom, mid = np.isclose(z, 0, atol=tol), np.isclose(z, h / 2, atol=tol)
    sym = np.isclose(y, 0, atol=tol)
    lines = []
    with _Deck() as f:
        f.write("*HEADING\nlevel 1 beam modes\n")
        ct.write_mesh(f, mesh, STEEL)
        ct.write_nset(f, "SYM", mesh.nodes_where(sym))
        if support == "face":
            ct.write_nset(f, "ENDS", mesh.nodes_where(at0 | atL))
            ct.write_nset(f, "AXIAL", mesh.nodes_where(at0 & mid))
            lines = ["ENDS,3,3", "AXIAL,1,1"]
        elif support == "edge":
            ct.write_nset(f, "ENDS", mesh.nodes_where((at0 | atL) & bottom))
            ct.write_nset(f, "PIN", mesh.nodes_where(at0 & bottom))
            lines = ["ENDS,3,3", "PIN,1,1"]
        elif support == "clamped":
            ct.write_nset(f, "ENDS", mesh.nodes_where(at0 | atL))
            lines = ["ENDS,1,3"]
        elif support == "clampxz":
            ct.write_nset(f, "ENDS", mesh.nodes_where(at0 | atL))
            lines = ["ENDS,1,1", "ENDS,3,3"]
        else:
            raise ValueError(f"support = {support!r} is not known: face, edge, clamped, "
                             "clampxz")
        ct.write_nset(f, "AXIS", mesh.nodes_where(sym & mid))
        f.write("*BOUNDARY\nSYM,2,2\n" + "\n".join(lines) + "\n")
        f.write("*STEP\n*FREQUENCY\n20\n*NODE PRINT, NSET=AXIS\nU\n*END STEP\n")
        deck = f.text
    meta = dict(length_m=length, width_m=b, height_m=h, model="half width (y-symmetry)",
                elements=[nx, ny, nz], element_size_m=size, n_nodes=len(mesh.coords),
                n_elements=len(mesh.elements), element_type=mesh.element_type)
    return deck, meta, mesh


def plate_deck(ratio, support, n_in_plane, nz):
    """CalculiX deck and metadata of the full square plate of span/thickness ``ratio``."""
    h = PLATE_THICKNESS
    a = ratio * h
    mesh = ct.structured_box(a, a, h, n_in_plane, n_in_plane, nz)
    x, y, z = mesh.coords.T
    tol = 1e-9
    xe = np.isclose(x, 0, atol=tol) | np.isclose(x, a, atol=tol)
    ye = np.isclose(y, 0, atol=tol) | np.isclose(y, a, atol=tol)
    bottom, mid = np.isclose(z, 0, atol=tol), np.isclose(z, h / 2, atol=tol)
    with _Deck() as f:
        f.write("*HEADING\nlevel 1 plate modes\n")
        ct.write_mesh(f, mesh, STEEL)
        if support == "face":
            ct.write_nset(f, "XE", mesh.nodes_where(xe))
            ct.write_nset(f, "YE", mesh.nodes_where(ye))
            bc = "XE,2,3\nYE,1,1\nYE,3,3\n"
        elif support == "edge":
            ct.write_nset(f, "XE", mesh.nodes_where(xe & bottom))
            ct.write_nset(f, "YE", mesh.nodes_where(ye & bottom))
            bc = "XE,2,3\nYE,1,1\nYE,3,3\n"
        else:
            raise ValueError(f"support = {support!r} is not known: face, edge")
        grid = np.isclose((x / (a / 8)) % 1, 0, atol=1e-6) | np.isclose((x / (a / 8)) % 1, 1, atol=1e-6)
        gridy = np.isclose((y / (a / 8)) % 1, 0, atol=1e-6) | np.isclose((y / (a / 8)) % 1, 1, atol=1e-6)
        ct.write_nset(f, "MID", mesh.nodes_where(mid & grid & gridy))
        f.write("*BOUNDARY\n" + bc)
        f.write("*STEP\n*FREQUENCY\n14\n*NODE PRINT, NSET=MID\nU\n*END STEP\n")
        deck = f.text
    meta = dict(length_x_m=a, length_y_m=a, thickness_m=h, model="full plate",
                elements=[n_in_plane, n_in_plane, nz], element_size_m=[a / n_in_plane, h / nz],
                n_nodes=len(mesh.coords), n_elements=len(mesh.elements),
                element_type=mesh.element_type)
    return deck, meta, mesh


class _Deck:
    """Tiny string builder with a file-like ``write``."""

    def __enter__(self):
        self._parts = []
        return self

    def __exit__(self, *exc):
        return False

    def write(self, s):
        self._parts.append(s)

    @property
    def text(self):
        return "".join(self._parts)


def classify(blocks, mesh, axis_coord):
    """Per mode: (is bending, number of half-waves along ``axis_coord``) from the prints.

    Bending: the transverse displacement uz is at least the in-plane ones (rms over the
    mid-surface/neutral-axis nodes).  With the bottom-edge supports the flexural modes
    carry an axial rigid motion of the beam (the end sections turn about the support
    line), up to ~0.6 of uz at span/height 5, so no stricter ratio is used.  Half-waves: sign changes of uz along the line
    (beams) + 1.
    """
    out = []
    for block in blocks:
        ids = np.array(sorted(block))
        u = np.array([block[i] for i in ids])
        rms = np.sqrt((u ** 2).mean(axis=0))
        bending = rms[2] >= max(rms[0], rms[1])
        order = np.argsort(mesh.coords[ids - 1, axis_coord])
        uz = u[order, 2]
        big = np.abs(uz) > 1e-3 * np.abs(uz).max()
        signs = np.sign(uz[big])
        out.append((bool(bending), int(np.count_nonzero(np.diff(signs))) + 1))
    return out


def toolkit_beam(ratio, supports, theory):
    beam = impactmaps.Beam.rectangular(ratio * BEAM_HEIGHT, BEAM_WIDTH, BEAM_HEIGHT, STEEL,
                                       theory=theory, supports=supports)
    w = beam.mode_set(0.0, min_modes=N_BENDING).frequencies[:N_BENDING]
    return (np.asarray(w) / (2 * np.pi)).tolist()


def toolkit_plate(ratio, theory):
    a = ratio * PLATE_THICKNESS
    plate = impactmaps.Plate.isotropic(a, a, PLATE_THICKNESS, STEEL, theory=theory)
    w = plate.modes(0.0, min_modes=N_BENDING).frequencies[:N_BENDING]
    return (np.asarray(w) / (2 * np.pi)).tolist()


def run_case(kind, support, ratio, density):
    if kind == "beam":
        deck, meta, mesh = beam_deck(ratio, support, BEAM_MESHES[density])
        axis = 0
    else:
        n, nz = PLATE_MESHES[density]
        deck, meta, mesh = plate_deck(ratio, support, n, nz)
        axis = 0
    job = f"{kind}_{support}_{ratio}_{density}"
    dat, wall = ct.run_ccx(deck, job, ct.WORK / "level1")
    text = dat.read_text()
    omegas = ct.parse_eigenvalues(text)
    nset = "AXIS" if kind == "beam" else "MID"
    info = classify(ct.parse_node_prints(text, nset), mesh, axis)
    bend = [(w, n) for w, (is_b, n) in zip(omegas, info) if is_b]
    if len(bend) < N_BENDING:
        raise RuntimeError(f"{job}: only {len(bend)} bending modes among {len(omegas)}")
    freqs = [float(w / (2 * np.pi)) for w, _ in bend[:N_BENDING]]
    return dict(case=job, kind=kind, support=support, slenderness=ratio, mesh=density,
                **meta, fe_bending_hz=freqs,
                fe_half_waves=[n for _, n in bend[:N_BENDING]] if kind == "beam" else None,
                all_modes_hz=[float(w / (2 * np.pi)) for w in omegas],
                all_modes_bending=[b for b, _ in info],
                wall_time_s=wall)


def all_cases():
    cases = []
    for support in ("face", "edge", "clamped", "clampxz"):
        for r in BEAM_RATIOS:
            cases.append(("beam", support, r))
    for support in ("face", "edge"):
        for r in PLATE_RATIOS:
            cases.append(("plate", support, r))
    return cases


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--case", action="append", default=[],
                        help="kind-support-ratio, e.g. beam-face-10 (repeatable)")
    parser.add_argument("--all", action="store_true")
    parser.add_argument("--finest", action="store_true",
                        help="beams: also 8 elements through the depth; the convergence "
                             "pair is then fine/finest")
    parser.add_argument("--out", default=str(ct.RESULTS / "level1_modes.json"))
    args = parser.parse_args(argv)
    cases = all_cases() if args.all else [
        (c.split("-")[0], c.split("-")[1], int(c.split("-")[2])) for c in args.case]
    out = Path(args.out)
    record = json.loads(out.read_text()) if out.exists() else {"cases": {}}
    record.update(ccx_version=ct.ccx_version(), gmsh_version=ct.gmsh_version(),
                  material=dict(E_Pa=STEEL.youngs_modulus, nu=STEEL.poisson_ratio,
                                rho_kg_m3=STEEL.density),
                  command="python validation/fe/level1_modes.py " + " ".join(
                      argv if argv is not None else sys.argv[1:]))
    for kind, support, ratio in cases:
        entry = {}
        densities = ("coarse", "fine") + (("finest",) if args.finest and kind == "beam" else ())
        for density in densities:
            t0 = time.perf_counter()
            entry[density] = run_case(kind, support, ratio, density)
            print(f"{kind} {support} {ratio} {density}: "
                  f"{np.round(entry[density]['fe_bending_hz'], 2)} "
                  f"({time.perf_counter() - t0:.1f} s)", flush=True)
        best, second = densities[-1], densities[-2]
        c = np.array(entry[second]["fe_bending_hz"])
        fnr = np.array(entry[best]["fe_bending_hz"])
        entry["best_mesh"] = best
        entry["mesh_difference"] = ((c - fnr) / fnr).tolist()     # second-best vs best
        if kind == "beam":
            sup = "cc" if support.startswith("clamp") else "ss"
            entry["toolkit_timoshenko_hz"] = toolkit_beam(ratio, sup, "timoshenko")
            entry["toolkit_euler_hz"] = toolkit_beam(ratio, sup, "euler")
        else:
            entry["toolkit_mindlin_hz"] = toolkit_plate(ratio, "mindlin")
            entry["toolkit_kirchhoff_hz"] = toolkit_plate(ratio, "kirchhoff")
        record["cases"][f"{kind}-{support}-{ratio}"] = entry
        out.parent.mkdir(parents=True, exist_ok=True)
        out.write_text(json.dumps(record, indent=1))
    return record


if __name__ == "__main__":
    main()
