"""Level 6, laminate impact: spring-coupled impact on the composite-shell modes of a clamped
quasi-isotropic laminate, and what dropping D16/D26 changes (issue 39).

Plates (CCCC, AS4/3501-6 of the catalogue, 16 plies of 0.125 mm, h = 2 mm):

* ``qi0``  — ``[0/45/-45/90]2s``, 150 × 100 mm (the issue's layup; level 6's shell frequencies);
* ``qi45`` — ``[45/0/-45/90]2s``, 125 × 75 mm (``examples/drop_weight_quasi_isotropic.toml``).

Struck at the centre by a steel sphere R = 8 mm (the example's 16 mm tup) at 1.907 m/s (the
example's 10 J at 5.5 kg), masses 0.0168 (the solid sphere), 0.1, 1 and 5.5 kg; Hertz law of the
toolkit (Tan & Sun's ``1/E2`` for the struck ply).

**Reference: the composite shell.** 8-node shells S8R with ``*SHELL SECTION, COMPOSITE`` (one
layer per ply; ccx expands each into a 20-node brick through the thickness), ply data as level 6's
shell frequencies, all edge nodes held in all six degrees of freedom. It is the like-for-like
reference of the toolkit's laminate (first-order shear plate with the full D and A44/A55 under
the Hertz patch, no near-field weights: those exist for isotropic plates only): the same
kinematics to first order, D16/D26 and shear included, independent discretisation and code. The
shell has no half-space near field, so the FE spring carries the *whole* Hertz law (``c = 0``);
a per-ply 3D solid would add the laminate's 3D near field, a second-order effect on these thin
plates (a/h 62 and 75: the Mindlin patch compliance moves by ≈ 1 % between patch radii 0.3 and
1.2 mm, against a structural compliance 14–50 × the local Hertz compliance); not run.

The load is the toolkit's: a Hertz pressure ``∝ sqrt(1 − r²/a²)`` on a disc at the centre, with
``a`` the toolkit's contact radius at its peak force (``sqrt(R α_max)``) for each mass; its
consistent nodal forces (∫ p N_i dA over the serendipity shape functions, polar Gauss quadrature
with ``r = a sin t``) load the shell nodes. Per radius the FE gives the static compliance (work
conjugate: ``Σ f_i u_i`` per unit force) and the participations ``Σ f_i φ_i`` of the mass-
normalised modes. The mesh is structured, graded from the centre (size ``s_c`` there, growing by
``ratio`` per element up to ``s_far``), two meshes.

Run from the repository root, one ccx at a time (scratch files in a temporary directory)::

    OMP_NUM_THREADS=2 FE_THREADS=2 nice -n 10 python validation/fe/level6_laminate_impact.py fe --layup qi0 --mesh coarse
    ... fe --layup qi0 --mesh fine ; ... fe --layup qi45 --mesh coarse ; ... fe --layup qi45 --mesh fine
    python validation/fe/level6_laminate_impact.py impact        # seconds, no ccx

Results: ``results/level6_laminate_modes_<layup>_<mesh>.npz`` + ``.json`` (frequencies,
participations and static compliances per patch radius, mesh, wall time, command) and
``results/level6_laminate_impact.json`` (per plate and mass: the FE spring model on both meshes,
half step, half modes; the toolkit with and without D16/D26).
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import shutil
import sys
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import ccx_tools as ct  # noqa: E402
from spring_integrator import SpringLaw, integrate  # noqa: E402

import impactmaps  # noqa: E402

PLY = impactmaps.material("as4-3501-6")
STEEL = impactmaps.material("structural-steel")
PLY_THICKNESS = 0.125e-3
NU23 = 0.4                                  # as level6_plates.py (hardly enters bending)
LAYUPS = {"qi0": ("[0/45/-45/90]2s", [0, 45, -45, 90, 0, 45, -45, 90], (0.150, 0.100)),
          "qi45": ("[45/0/-45/90]2s", [45, 0, -45, 90, 45, 0, -45, 90], (0.125, 0.075))}
RADIUS = 0.008                              # m, steel sphere (16 mm tup)
VELOCITY = 1.907                            # m/s (10 J at 5.5 kg)
MASSES = (None, 0.1, 1.0, 5.5)              # kg; None = the solid steel sphere
# centre element size [m], growth per element, far size [m]
MESHES = {"coarse": (0.30e-3, 1.20, 5.0e-3), "fine": (0.15e-3, 1.12, 3.0e-3)}
N_MODES = 200
REFERENCE, COARSE = "fine", "coarse"
IMPACT_JSON = ct.RESULTS / "level6_laminate_impact.json"


def laminate(layup):
    return impactmaps.Laminate.from_layup(PLY, LAYUPS[layup][1], symmetric=True)


def plate(layup, couplings=True):
    """The toolkit's CCCC Mindlin laminate; ``couplings=False``: D16 = D26 = 0 (all else equal)."""
    lx, ly = LAYUPS[layup][2]
    p = impactmaps.Plate.from_laminate(lx, ly, laminate(layup), theory="mindlin", edges="CCCC")
    return p if couplings else dataclasses.replace(p, D16=0.0, D26=0.0)


def mass_of(m):
    return impactmaps.Sphere(RADIUS, STEEL).mass if m is None else float(m)


def law_for(layup, mass):
    return impactmaps.law_for_sphere("hertz", impactmaps.Sphere(RADIUS, STEEL, mass=mass),
                                     laminate(layup))


def cluster_duration(intervals, gap=0.01):
    """Duration [s] of the first contact with the contacts that follow it after a separation
    shorter than ``gap`` × the contact so far merged in (a graze: the force touches zero for a
    moment, which turns one contact into two on a rounding of the force)."""
    start, end = intervals[0]
    for s, e in intervals[1:]:
        if s - end > gap * (end - start):
            break
        end = e
    return float(end - start)


def toolkit(layup, mass, couplings=True):
    """First contact of ``simulate`` on the toolkit plate: peak, duration, contact radius."""
    law = law_for(layup, mass)
    target = plate(layup, couplings)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        t0 = time.perf_counter()
        res = impactmaps.simulate(target, law, mass, VELOCITY)
        wall = time.perf_counter() - t0
    iv = res.contact_intervals
    h = res.history
    inside = (h["time_s"] >= iv[0, 0]) & (h["time_s"] <= iv[0, 1])
    first = float(h[inside]["force_N"].max())
    alpha = (float(res.peak_force) / law.stiffness) ** (2.0 / 3.0)
    return dict(couplings=couplings, D16_N_m=target.D16, D26_N_m=target.D26,
                peak_force_N=float(res.peak_force), first_peak_N=first,
                first_contact_s=float(iv[0, 1] - iv[0, 0]), impacts=int(len(iv)),
                contact_intervals_s=iv.tolist(), first_contact_merged_s=cluster_duration(iv),
                restitution=float(res.restitution), end_time_s=float(res.end_time),
                n_modes=int(res.n_modes),
                contact_radius_at_peak_m=float(np.sqrt(law.effective_radius * alpha)),
                warnings=sorted({str(w.message)[:160] for w in caught}), wall_time_s=wall)


# --------------------------------------------------------------------------- mesh and loads
def graded_lines(length, size_centre, ratio, size_far):
    """Element boundaries on [0, length], symmetric about length/2 (a boundary there), sizes
    ``size_centre · ratio^k`` capped at ``size_far`` from the centre out, scaled to fit."""
    half = length / 2
    sizes = []
    while sum(sizes) < half:
        sizes.append(min(size_centre * ratio ** len(sizes), size_far))
    sizes = np.array(sizes) * half / sum(sizes)
    right = half + np.concatenate([[0.0], np.cumsum(sizes)])
    return np.concatenate([length - right[::-1][:-1], right])


@dataclasses.dataclass
class ShellMesh:
    xs: np.ndarray            # element boundaries along x
    ys: np.ndarray
    coords: np.ndarray        # (n, 3) node coordinates, ids 1..n
    elements: np.ndarray      # (e, 8) S8R connectivity (corners ccw, then mid-sides)
    node_id: np.ndarray       # (2 nx + 1, 2 ny + 1) half-grid -> node id (0: element centre)


def shell_mesh(lx, ly, size_centre, ratio, size_far):
    xs = graded_lines(lx, size_centre, ratio, size_far)
    ys = graded_lines(ly, size_centre, ratio, size_far)
    nx, ny = len(xs) - 1, len(ys) - 1
    hx = np.empty(2 * nx + 1)
    hx[0::2], hx[1::2] = xs, 0.5 * (xs[:-1] + xs[1:])
    hy = np.empty(2 * ny + 1)
    hy[0::2], hy[1::2] = ys, 0.5 * (ys[:-1] + ys[1:])
    node_id = np.zeros((2 * nx + 1, 2 * ny + 1), dtype=np.int64)
    coords = []
    for i in range(2 * nx + 1):
        for j in range(2 * ny + 1):
            if i % 2 and j % 2:
                continue
            coords.append((hx[i], hy[j], 0.0))
            node_id[i, j] = len(coords)
    elements = []
    for i in range(nx):
        for j in range(ny):
            c = [(2 * i, 2 * j), (2 * i + 2, 2 * j), (2 * i + 2, 2 * j + 2), (2 * i, 2 * j + 2),
                 (2 * i + 1, 2 * j), (2 * i + 2, 2 * j + 1), (2 * i + 1, 2 * j + 2), (2 * i, 2 * j + 1)]
            elements.append([node_id[a, b] for a, b in c])
    return ShellMesh(xs, ys, np.array(coords), np.array(elements), node_id)


def _serendipity(xi, eta):
    """The 8 shape functions of the serendipity quad at (xi, eta) ∈ [−1, 1]² (S8R order)."""
    corners = np.array([(-1, -1), (1, -1), (1, 1), (-1, 1)], float)
    n = np.empty((len(xi), 8))
    for k, (a, b) in enumerate(corners):
        n[:, k] = 0.25 * (1 + a * xi) * (1 + b * eta) * (a * xi + b * eta - 1)
    n[:, 4] = 0.5 * (1 - xi ** 2) * (1 - eta)
    n[:, 5] = 0.5 * (1 + xi) * (1 - eta ** 2)
    n[:, 6] = 0.5 * (1 - xi ** 2) * (1 + eta)
    n[:, 7] = 0.5 * (1 - xi) * (1 - eta ** 2)
    return n


def hertz_patch_loads(mesh, centre, radius, n_radial=96, n_angular=192):
    """Consistent nodal forces (summing to 1) of a unit Hertz pressure ``∝ sqrt(1 − r²/a²)`` on
    the disc of ``radius`` around ``centre``: (node ids, forces)."""
    t, wt = np.polynomial.legendre.leggauss(n_radial)
    t, wt = np.pi / 4 * (t + 1), np.pi / 4 * wt                      # t ∈ (0, π/2)
    theta = 2 * np.pi * (np.arange(n_angular) + 0.5) / n_angular
    r = radius * np.sin(t)
    # p r dr = a² cos²t sin t dt (times the pressure scale), exact for the sqrt profile
    w_r = wt * radius ** 2 * np.cos(t) ** 2 * np.sin(t)
    x = (centre[0] + np.outer(r, np.cos(theta))).ravel()
    y = (centre[1] + np.outer(r, np.sin(theta))).ravel()
    w = np.repeat(w_r, n_angular) * (2 * np.pi / n_angular)
    i = np.clip(np.searchsorted(mesh.xs, x) - 1, 0, len(mesh.xs) - 2)
    j = np.clip(np.searchsorted(mesh.ys, y) - 1, 0, len(mesh.ys) - 2)
    xi = 2 * (x - mesh.xs[i]) / (mesh.xs[i + 1] - mesh.xs[i]) - 1
    eta = 2 * (y - mesh.ys[j]) / (mesh.ys[j + 1] - mesh.ys[j]) - 1
    shape = _serendipity(xi, eta) * w[:, None]
    ny = len(mesh.ys) - 1
    nodes = mesh.elements[i * ny + j]                                # (q, 8)
    forces = {}
    for node, f in zip(nodes.ravel(), shape.ravel()):
        forces[int(node)] = forces.get(int(node), 0.0) + float(f)
    ids = np.array(sorted(forces))
    f = np.array([forces[k] for k in ids])
    return ids, f / f.sum()


# --------------------------------------------------------------------------- the ccx deck
def deck(layup, mesh, loads, n_modes):
    """*FREQUENCY step (``n_modes``), then one *STATIC step per patch load (``loads``: list of
    (ids, forces)); U printed on the union of the loaded nodes."""
    _, angles, (lx, ly) = LAYUPS[layup]
    full = list(angles) + list(angles)[::-1]
    parts = []
    f = type("F", (), {"write": staticmethod(parts.append)})
    parts.append("*HEADING\nlevel 6 laminate impact, composite shell\n*NODE, NSET=NALL\n")
    for i, (a, b, c) in enumerate(mesh.coords, start=1):
        parts.append(f"{i},{a:.10e},{b:.10e},{c:.10e}\n")
    parts.append("*ELEMENT, TYPE=S8R, ELSET=PLATE\n")
    for i, row in enumerate(mesh.elements, start=1):
        parts.append(f"{i}," + ",".join(str(v) for v in row) + "\n")
    x, y = mesh.coords[:, 0], mesh.coords[:, 1]
    tol = 1e-9
    edge = (np.isclose(x, 0, atol=tol) | np.isclose(x, lx, atol=tol)
            | np.isclose(y, 0, atol=tol) | np.isclose(y, ly, atol=tol))
    ct.write_nset(f, "EDGE", np.flatnonzero(edge) + 1)
    patch = sorted(set().union(*(set(ids.tolist()) for ids, _ in loads)))
    ct.write_nset(f, "PATCH", patch)
    parts.append(ct.composite_shell_cards(PLY, full, PLY_THICKNESS, NU23))
    parts.append("*BOUNDARY\nEDGE,1,6\n")
    parts.append(f"*STEP\n*FREQUENCY\n{n_modes}\n*NODE PRINT, NSET=PATCH\nU\n*END STEP\n")
    for ids, forces in loads:
        parts.append("*STEP\n*STATIC\n*CLOAD, OP=NEW\n")
        parts.extend(f"{n},3,{-v:.12e}\n" for n, v in zip(ids, forces))
        parts.append("*NODE PRINT, NSET=PATCH\nU\n*END STEP\n")
    return "".join(parts), dict(plies=len(full), stacking_full=full, edges="CCCC",
                                edge_dofs_held="1-6", n_patch_nodes=len(patch))


def patch_radii(layup):
    """The toolkit's contact radius at the peak for each mass (the FE patch of that mass)."""
    return [toolkit(layup, mass_of(m))["contact_radius_at_peak_m"] for m in MASSES]


def run_fe(layup, density, n_modes=N_MODES):
    name, _, (lx, ly) = LAYUPS[layup]
    size_centre, ratio, size_far = MESHES[density]
    t0 = time.perf_counter()
    mesh = shell_mesh(lx, ly, size_centre, ratio, size_far)
    radii = patch_radii(layup)
    loads = [hertz_patch_loads(mesh, (lx / 2, ly / 2), a) for a in radii]
    text, meta = deck(layup, mesh, loads, n_modes)
    workdir = Path(tempfile.mkdtemp(prefix="impactmaps_level6_lam_"))
    try:
        dat, wall = ct.run_ccx(text, f"lam_{layup}_{density}", workdir)
        out = dat.read_text()
    finally:
        shutil.rmtree(workdir, ignore_errors=True)
    omega = ct.parse_eigenvalues(out)
    blocks = ct.parse_node_prints(out, "PATCH")
    if len(blocks) != len(omega) + len(loads):
        raise RuntimeError(f"{len(blocks)} PATCH blocks for {len(omega)} modes + {len(loads)} loads")
    modes, statics = blocks[:len(omega)], blocks[len(omega):]
    mean = lambda block, ids, f: float(np.dot(f, [block[int(i)][2] for i in ids]))
    participation = np.array([[mean(b, ids, fr) for b in modes] for ids, fr in loads])
    compliance = np.array([-mean(s, ids, fr) for s, (ids, fr) in zip(statics, loads)])
    tag = f"{layup}_{density}"
    np.savez(ct.RESULTS / f"level6_laminate_modes_{tag}.npz", omega=omega,
             participation=participation, static_compliance=compliance,
             patch_radius=np.array(radii))
    sizes = np.diff(mesh.xs)
    info = dict(tag=tag, layup=name, length_x_m=lx, length_y_m=ly,
                thickness_m=meta["plies"] * PLY_THICKNESS, element_type="S8R composite "
                "(ccx expands to 20-node bricks)", elements=[len(mesh.xs) - 1, len(mesh.ys) - 1],
                element_size_centre_m=float(sizes.min()), element_size_far_m=float(sizes.max()),
                growth_ratio=ratio, n_nodes=len(mesh.coords), n_elements=len(mesh.elements),
                n_modes=len(omega), highest_frequency_hz=float(omega[-1] / (2 * np.pi)),
                patch_radius_m=radii, patch_load="Hertz pressure, consistent nodal forces",
                static_compliance_m_per_N=compliance.tolist(),
                lowest_frequencies_hz=(omega[:8] / (2 * np.pi)).tolist(),
                ccx_version=ct.ccx_version(), ccx_wall_time_s=wall,
                total_time_s=time.perf_counter() - t0, **meta,
                ply=dict(E1_Pa=PLY.longitudinal_modulus, E2_Pa=PLY.transverse_modulus,
                         E3_Pa=PLY.transverse_modulus, nu12=PLY.poisson_ratio,
                         nu13=PLY.poisson_ratio, nu23=NU23, G12_Pa=PLY.shear_modulus,
                         G13_Pa=PLY.transverse_shear_modulus_13,
                         G23_Pa=PLY.transverse_shear_modulus_23, rho_kg_m3=PLY.density,
                         source="impactmaps/materials/catalogue.py 'as4-3501-6'"),
                command=("OMP_NUM_THREADS=2 FE_THREADS=2 nice -n 10 python "
                         "validation/fe/level6_laminate_impact.py fe --layup "
                         f"{layup} --mesh {density} --modes {n_modes}"))
    (ct.RESULTS / f"level6_laminate_modes_{tag}.json").write_text(json.dumps(info, indent=1))
    print(json.dumps({k: info[k] for k in ("tag", "n_nodes", "highest_frequency_hz", "patch_radius_m",
                                           "static_compliance_m_per_N", "lowest_frequencies_hz",
                                           "ccx_wall_time_s")}, indent=1), flush=True)
    return info


# --------------------------------------------------------------------------- the impacts
def load_fe(tag):
    d = np.load(ct.RESULTS / f"level6_laminate_modes_{tag}.npz")
    return d["omega"], d["participation"], d["static_compliance"], d["patch_radius"]


def fe_spring(tag, k, law, mass, duration, step, n_modes=None):
    """The FE spring model on the modes ``tag`` under the patch of mass index ``k``; the spring
    carries the whole Hertz law (the shell has no half-space near field)."""
    omega, phi, compliance, radii = load_fe(tag)
    phi = phi[k]
    if n_modes is not None:
        omega, phi = omega[:n_modes], phi[:n_modes]
    residual = float(compliance[k] - np.sum(phi ** 2 / omega ** 2))
    run = integrate(omega, phi, residual, SpringLaw("hertz", law.stiffness, 0.0), mass,
                    VELOCITY, step, duration)
    iv = run.contact_intervals
    inside = (run.time >= iv[0, 0]) & (run.time <= iv[0, 1])
    return dict(tag=tag, n_modes=int(len(omega)), time_step_s=step,
                patch_radius_m=float(radii[k]), static_compliance_m_per_N=float(compliance[k]),
                residual_compliance_m_per_N=residual, peak_force_N=run.peak_force,
                first_peak_N=float(run.force[inside].max()),
                first_contact_s=float(iv[0, 1] - iv[0, 0]), impacts=int(len(iv)),
                contact_intervals_s=iv.tolist(), first_contact_merged_s=cluster_duration(iv),
                restitution=run.restitution)


def patch_compliance(target, radius):
    """The toolkit plate's static compliance under the Hertz patch [m/N]."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        basis = target.modes(1e5, contact_radius=radius)
    return float(basis.retained_compliance + basis.residual_compliance)


def impact():
    out = {"inputs": dict(sphere_radius_m=RADIUS, sphere_material="structural-steel",
                          velocity_m_s=VELOCITY, ply="as4-3501-6",
                          ply_thickness_m=PLY_THICKNESS, edges="CCCC",
                          spring="alpha_s(F) = (F/K_h)^(2/3): the whole Hertz law of the toolkit "
                                 "(the shell has no half-space near field)",
                          fe_reference_mesh=REFERENCE),
           "command": "python validation/fe/level6_laminate_impact.py impact",
           "plates": {}}
    for layup, (name, _, (lx, ly)) in LAYUPS.items():
        ref, coarse = f"{layup}_{REFERENCE}", f"{layup}_{COARSE}"
        meta = json.loads((ct.RESULTS / f"level6_laminate_modes_{ref}.json").read_text())
        coarse_meta = json.loads((ct.RESULTS / f"level6_laminate_modes_{coarse}.json").read_text())
        full, bare = plate(layup), plate(layup, couplings=False)
        entry = dict(layup=name, length_x_m=lx, length_y_m=ly, D16_N_m=full.D16,
                     D26_N_m=full.D26, D11_N_m=full.D11, D22_N_m=full.D22,
                     fe_meshes={m["tag"]: {k: m[k] for k in (
                         "elements", "element_size_centre_m", "element_size_far_m", "growth_ratio",
                         "n_nodes", "n_modes", "highest_frequency_hz", "ccx_wall_time_s", "command")}
                         for m in (meta, coarse_meta)},
                     frequencies_hz=dict(fe_fine_lowest=meta["lowest_frequencies_hz"],
                                         fe_coarse_lowest=coarse_meta["lowest_frequencies_hz"],
                                         toolkit=full.natural_frequencies_hz(8).tolist(),
                                         toolkit_without_D16_D26=bare.natural_frequencies_hz(8).tolist()),
                     static=[], cases=[])
        _, _, c_ref, radii = load_fe(ref)
        _, _, c_coarse, _ = load_fe(coarse)
        for k, a in enumerate(radii):
            entry["static"].append(dict(patch_radius_m=float(a), fe_fine_m_per_N=float(c_ref[k]),
                                        fe_coarse_m_per_N=float(c_coarse[k]),
                                        toolkit_m_per_N=patch_compliance(full, a),
                                        toolkit_without_D16_D26_m_per_N=patch_compliance(bare, a)))
        for k, m in enumerate(MASSES):
            mass = mass_of(m)
            law = law_for(layup, mass)
            tk, tk0 = toolkit(layup, mass), toolkit(layup, mass, couplings=False)
            duration, step = 1.05 * tk["end_time_s"], tk["first_contact_s"] / 2000
            fe = {"reference": fe_spring(ref, k, law, mass, duration, step),
                  "half_step": fe_spring(ref, k, law, mass, duration, step / 2),
                  "half_modes": fe_spring(ref, k, law, mass, duration, step,
                                          n_modes=meta["n_modes"] // 2),
                  coarse: fe_spring(coarse, k, law, mass, duration, step)}
            entry["cases"].append(dict(mass_kg=mass, toolkit=tk, toolkit_without_D16_D26=tk0, fe=fe))
            r = fe["reference"]
            print(f"{layup} {mass:.4g} kg: FE {r['first_peak_N']:.2f} N {1e3 * r['first_contact_s']:.4f} ms"
                  f" | toolkit {100 * (tk['first_peak_N'] / r['first_peak_N'] - 1):+.2f} %"
                  f" {100 * (tk['first_contact_s'] / r['first_contact_s'] - 1):+.2f} %"
                  f" | no D16/D26 {100 * (tk0['first_peak_N'] / r['first_peak_N'] - 1):+.2f} %"
                  f" {100 * (tk0['first_contact_s'] / r['first_contact_s'] - 1):+.2f} %", flush=True)
        out["plates"][layup] = entry
    IMPACT_JSON.write_text(json.dumps(out, indent=1))
    return out


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="what", required=True)
    pf = sub.add_parser("fe", help="run ccx: modes and static patch compliances")
    pf.add_argument("--layup", required=True, choices=sorted(LAYUPS))
    pf.add_argument("--mesh", required=True, choices=sorted(MESHES))
    pf.add_argument("--modes", type=int, default=N_MODES)
    sub.add_parser("impact", help="the FE spring model and the toolkit (no ccx)")
    args = parser.parse_args(argv)
    if args.what == "fe":
        run_fe(args.layup, args.mesh, args.modes)
    else:
        impact()


if __name__ == "__main__":
    main()
