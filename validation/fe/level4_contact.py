"""Level 4: full 3D contact dynamics of the steel sphere on the steel beam (CalculiX).

The issue's two cases, a steel sphere (R = 10 mm, elastic) at 1 m/s on the middle of
the simply supported 500 × 20 × 20 mm steel beam (end faces held in z, the support of
levels 1–3):

* ``elastic``: elastic target — against the modal solver with the Hertz law and the
  finite-difference (FD) Rayleigh beam with the Hertz law;
* ``plastic``: the target elastic–perfectly plastic, S_y = 235 MPa (``*PLASTIC``;
  the sphere stays elastic) — against the modal solver and the FD beam with the
  refined Stronge law (S_y of the target) and the modal solver with the
  Yigit–Christoforou law.  Why 235 MPa: the elastic Hertz peak pressure of this impact
  is p_0 = 3F/(2πa²) ≈ 3.5 GPa, nine times the first-yield pressure 1.6 S_y; the refined
  Stronge law then predicts a permanent dent of ≈ 17 µm, 63 % of its largest
  indentation — clearly permanent and far above what the mesh resolves (µm).
  ccx 2.20 does not run this case in implicit dynamics (see
  ``level4_plastic_indent.py``, which runs its contact law quasi-statically instead);
  the deck is kept so that a later ccx can be tried (``--case plastic``).

Model: a quarter model (symmetry planes x = 0 and y = 0, the first contact point at
the origin, the beam's mid-span): the whole quarter sphere (centre (0, 0, R), its true
mass and inertia) and the quarter beam (x ∈ [0, L/2], end face x = L/2 held in z), one
gmsh model of 10-node tetrahedra (C3D10) graded with the distance r from the contact
point: size h0 = a_ref / ``MESHES[--mesh]`` for r < ``FINE_ZONE`` × a_ref (a_ref the
contact radius of the toolkit's peak force: Hertz radius for ``elastic``, the refined
Stronge loading radius for ``plastic``), growing by ``GROWTH`` per unit distance beyond,
up to R/3 in the sphere and ``--far-size`` in the beam.  Contact: the level-2 pair
(``*CONTACT PAIR, TYPE=SURFACE TO SURFACE``, frictionless, linear penalty of slope
``PENALTY`` × E / h0), the sphere's faces near the pole the slave.  Dynamics:
``*DYNAMIC, DIRECT`` (implicit α-method, α = −0.05, fixed increment ``--step``),
small strains (no NLGEOM), the sphere's nodes given −V0 in z at t = 0 (touching the
beam), run until ``END_FACTOR`` × the toolkit's first-contact duration (one impact in
the toolkit for both cases: the sphere leaves for good).

Output per increment (``.dat``): the velocities of the sphere's nodes and the
displacements of the beam's axis x = y = 0.  The contact force is the sphere's momentum
change: with the consistent mass matrix M of the sphere, 1ᵀ M v = Σ_j s_j v_j (s_j the
row sums of M, ``ccx_tools.tet10_mass_weights``), so the centre-of-mass velocity is
exact from the nodal velocities, and F = 4 m_q Δv_cm/Δt is the mean contact force of
each increment (m_q the quarter sphere's meshed mass, F for the full model; the sphere
has no other load in z).  Derived (:func:`fe_quantities`): peak force, first-contact
duration (end of contact extrapolated from the last momentum samples), restitution
e = v_cm(end) / V0 (the sphere moves freely after separation), permanent indentation
= the target's top-minus-bottom shortening on the axis, averaged over the last
``TAIL`` of the run (≈ 0 for the elastic case: the size of that error).

Run (niced, single-threaded, in the background):
``OMP_NUM_THREADS=1 nohup nice -n 19 python validation/fe/level4_contact.py --case
elastic --mesh coarse --step 2.8e-6 &``; each run adds its entry to
``results/level4_contact.json`` and writes ``results/level4_<case>_<mesh>_<step>.csv``
(force history); ``python validation/fe/report.py`` prints the README tables and draws
``figures/fe_level4_force_history.png``.  ``--smoke``: a very coarse mesh and a few increments (seconds),
written to ``--out-dir`` (a temporary directory by default).  ``--toolkit`` computes
and stores the toolkit's side only (modal / FD values, histories and wall times).
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import ccx_tools as ct  # noqa: E402
import level2_static_hertz as l2  # noqa: E402

import impactmaps  # noqa: E402

STEEL = impactmaps.material("structural-steel")          # S_y = 235 MPa
SPHERE_MATERIAL = dataclasses.replace(STEEL, yield_strength=None)   # elastic sphere
RADIUS = l2.RADIUS
BEAM = l2.BEAM
VELOCITY = 1.0                       # impact velocity V0 [m/s]
GROWTH = 0.5                        # element size growth per unit distance [-]
PENALTY = l2.PENALTY
FINE_ZONE = 1.5                      # size h0 up to FINE_ZONE × a_ref from the contact
SLAVE_ZONE = 3.0                     # contact faces within SLAVE_ZONE × a_ref
END_FACTOR = {"elastic": 1.15, "plastic": 1.3}   # run to this × the toolkit's first contact
CONTACT_FRACTION = 0.005             # separated: last force below this × peak force
TAIL_IMPULSE = 3e-3                  # end of contact from the last impulse above this
TAIL = 0.1                           # permanent dent: mean over the last 10 % of the run
MESHES = {"coarse": 3.0, "fine": 4.5, "smoke": 1.0}      # a_ref / h0
FAR_SIZE = {"coarse": 0.005, "fine": 0.005, "smoke": 0.008}
CASES = ("elastic", "plastic")


def sphere():
    return impactmaps.Sphere(RADIUS, SPHERE_MATERIAL)


def toolkit_runs(case):
    """The toolkit's runs of ``case``: name -> (ImpactResult, wall time of a second call [s]).

    ``elastic``: modal (Timoshenko) + Hertz, FD (Rayleigh, elastic) + Hertz.
    ``plastic``: modal + refined Stronge, FD (plastic section) + refined Stronge,
    modal + Yigit–Christoforou.
    """
    ball = sphere()
    beam = impactmaps.Beam.rectangular(BEAM["length"], BEAM["width"], BEAM["height"], STEEL)
    fd_beam = impactmaps.FDBeam(BEAM["length"], BEAM["width"], BEAM["height"],
                                STEEL.youngs_modulus, STEEL.density, STEEL.yield_strength,
                                plastic=case == "plastic")
    laws = (("hertz",) if case == "elastic" else ("stronge", "yigit-christoforou"))
    runs = {}
    for name in laws:
        law = impactmaps.law_for_sphere(name, ball, STEEL)
        modal = _timed(impactmaps.simulate, beam, law, ball.mass, VELOCITY)
        runs[f"modal_{name}"] = modal
        if name != "yigit-christoforou":
            end = 1.5 * float(np.diff(modal[0].contact_intervals[0])[0])
            runs[f"fd_{name}"] = _timed(impactmaps.simulate_fd, fd_beam, law, ball.mass,
                                        VELOCITY, duration=end)
    return runs


def _timed(solver, *args, repeats=5, **kwargs):
    """(result, wall time [s]: the shortest of ``repeats`` calls after a first one that
    compiles the numba kernels and fills the caches — the machine is shared)."""
    result = solver(*args, **kwargs)
    best = np.inf
    for _ in range(repeats):
        start = time.perf_counter()
        result = solver(*args, **kwargs)
        best = min(best, time.perf_counter() - start)
    return result, best


def reference_radius(case):
    """a_ref [m]: contact radius at the toolkit's peak (Hertz / refined Stronge loading)."""
    if case == "elastic":
        law = impactmaps.law_for_sphere("hertz", sphere(), STEEL)
        res = toolkit_runs_cached(case)["modal_hertz"][0]
        return l2.hertz_radius(res.peak_force, law.stiffness)
    law = impactmaps.law_for_sphere("stronge", sphere(), STEEL)
    res = toolkit_runs_cached(case)["modal_stronge"][0]
    return float(law.loading_contact_radius(res.max_indentation))


_RUNS = {}


def toolkit_runs_cached(case):
    if case not in _RUNS:
        _RUNS[case] = toolkit_runs(case)
    return _RUNS[case]


def summary(result, wall):
    """Scalars of a toolkit run compared with FE."""
    interval = result.contact_intervals[0]
    return dict(peak_force_N=float(result.peak_force),
                first_contact_s=float(interval[1] - interval[0]),
                impacts=len(result.contact_intervals),
                restitution=float(result.restitution),
                permanent_indentation_m=float(result.permanent_indentation),
                max_indentation_m=float(result.max_indentation),
                end_time_s=float(result.end_time), time_step_s=float(result.time_step),
                method=result.method, wall_time_s=wall)


def build_mesh(h0, r_fine, far_size):
    """C3D10 mesh of the quarter sphere (centre (0, 0, R)) + quarter beam below z = 0.

    Returns the mesh, the 6-node boundary triangles of the sphere's curved surface
    (``slave``) and of the beam's top face (``master``), and a boolean mask of the
    sphere's elements.
    """
    import gmsh
    gmsh.initialize(["-noenv"])
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add("level4")
        occ = gmsh.model.occ
        ball = occ.addSphere(0, 0, RADIUS, RADIUS)
        cut = occ.addBox(0, 0, 0, RADIUS, RADIUS, 2 * RADIUS)
        (sphere_vol,), _ = occ.intersect([(3, ball)], [(3, cut)])
        target = occ.addBox(0, 0, -BEAM["height"], BEAM["length"] / 2, BEAM["width"] / 2,
                            BEAM["height"])
        occ.synchronize()
        size = f"Min({h0} + {GROWTH}*Max(Sqrt(x*x+y*y+z*z) - {r_fine}, 0), {{far}})"
        mesh, _, tris = ct.quarter_contact_mesh(gmsh, sphere_vol, target, size, (RADIUS / 3, far_size))
        _, sphere_tags, _ = gmsh.model.mesh.getElements(3, sphere_vol[1])
        all_tags = gmsh.model.mesh.getElements(3)[1][0]
        in_sphere = np.isin(all_tags, sphere_tags[0])
    finally:
        gmsh.finalize()
    return mesh, tris, in_sphere


def build_deck(case, mesh, faces, in_sphere, h0, step, end_time):
    """The ccx deck: two parts, symmetry + support, contact pair, one *DYNAMIC step."""
    x, y, z = mesh.coords.T
    tol = 1e-9
    F = ct.Deck()
    w = F.write
    target_yield = STEEL.yield_strength if case == "plastic" else None
    ct.write_mesh_parts(F, mesh, [
        ("SPH", in_sphere, "BALL", ct.material_cards(SPHERE_MATERIAL)),
        ("TGT", ~in_sphere, "BEAM", ct.material_cards(STEEL, target_yield))])
    sphere_nodes = np.zeros(len(z), dtype=bool)
    sphere_nodes[mesh.elements[in_sphere].ravel() - 1] = True
    ct.write_nset(F, "SUPPORT", mesh.nodes_where(np.isclose(x, BEAM["length"] / 2, atol=tol)))
    ct.write_nset(F, "SPHN", mesh.nodes_where(sphere_nodes))
    ct.write_nset(F, "AXIS", mesh.nodes_where(np.isclose(x, 0, atol=tol)
                                              & np.isclose(y, 0, atol=tol) & ~sphere_nodes))
    ct.write_quarter_contact(F, mesh, faces, PENALTY * STEEL.youngs_modulus / h0)
    w("*BOUNDARY\nXSYM,1,1\nYSYM,2,2\nSUPPORT,3,3\n")
    w(f"*INITIAL CONDITIONS, TYPE=VELOCITY\nSPHN,3,{-VELOCITY:.6e}\n")
    w(f"*STEP, INC=1000000\n*DYNAMIC, DIRECT\n{step:.6e},{end_time:.6e}\n")
    w("*NODE PRINT, NSET=SPHN\nV\n*NODE PRINT, NSET=AXIS\nU\n*END STEP\n")
    return F.text("level 4 full contact dynamics")


def parse_velocity_blocks(dat_text, nset):
    """(times, {node: (vx, vy, vz)} per increment) of the ``velocities`` blocks of ``nset``."""
    times, blocks, current = [], [], None
    key = f"velocities (vx,vy,vz) for set {nset.upper()}"
    for line in dat_text.splitlines():
        if " for set " in line:
            if key.lower() in line.lower():
                times.append(ct._fortran_float(line.split()[-1]))
                current = {}
                blocks.append(current)
            else:
                current = None
            continue
        parts = line.split()
        if current is not None and len(parts) == 4 and parts[0].isdigit():
            current[int(parts[0])] = tuple(ct._fortran_float(v) for v in parts[1:])
    return np.array(times), blocks


def force_history(times, blocks, weights):
    """Contact force on the full sphere F(t) [N] from its momentum (see the docstring).

    Returns (t_mid, F) at the mid-points of the increments, with the t = 0 state
    (v = −V0) prepended, and the centre-of-mass velocity history (t, v_cm).
    """
    ids = np.array(sorted(blocks[0]))
    s = weights[ids - 1]
    v_cm = np.array([np.dot(s, [b[i][2] for i in ids]) for b in blocks]) / s.sum()
    t = np.concatenate([[0.0], times])
    v = np.concatenate([[-VELOCITY], v_cm])
    force = 4.0 * s.sum() * np.diff(v) / np.diff(t)
    return 0.5 * (t[1:] + t[:-1]), force, t, v


def fe_quantities(t_mid, force, t, v, dent):
    """Peak force, first-contact duration, restitution and permanent dent of a FE run.

    ``t_mid, force``: increment mid-points and mean forces; ``t, v``: increment ends
    (t = 0 included) and the sphere's centre-of-mass velocity; ``dent``: the target's
    axis shortening at the increment ends (without t = 0).  The peak is the vertex of
    the parabola through the three largest samples.  The end of contact is
    extrapolated from the exact momentum samples: near separation the impulse still
    to come, r ∝ (v_end − v), falls as (t_e − t)^{5/2} (Hertz, α linear in t), so
    r^{2/5} is linear in t; the last two increment ends with r > ``TAIL_IMPULSE``
    (relative to the whole impulse) give t_e.
    """
    k = int(np.argmax(force))
    peak = float(force[k])
    if 0 < k < len(force) - 1:           # parabola through the three samples at the top
        f0, f1, f2 = force[k - 1:k + 2]
        peak = float(f1 + (f2 - f0) ** 2 / (8 * (2 * f1 - f0 - f2)))
    remaining = (v[-1] - v) / (v[-1] - v[0])
    j = int(np.flatnonzero(remaining > TAIL_IMPULSE)[-1])
    x0, x1 = remaining[j - 1] ** 0.4, remaining[j] ** 0.4
    duration = float(t[j] + x1 * (t[j] - t[j - 1]) / (x0 - x1))
    tail = t[1:] >= (1 - TAIL) * t[-1]
    return dict(peak_force_N=peak, first_contact_s=duration,
                restitution=float(v[-1] / VELOCITY),
                separated=bool(force[-1] < CONTACT_FRACTION * peak and duration < t[-1]),
                permanent_indentation_m=float(np.mean(dent[tail])),
                permanent_indentation_spread_m=float(np.ptp(dent[tail])))


def quantities_from_csv(path):
    """:func:`fe_quantities` of a committed force-history CSV."""
    h = np.loadtxt(path, delimiter=",", skiprows=1)
    return fe_quantities(h[:, 0], h[:, 1], np.r_[0.0, h[:, 2]], np.r_[-VELOCITY, h[:, 3]],
                         h[:, 4])


def run_fe(case, mesh_name, step, workdir, out_dir, end_time=None):
    """Mesh, run ccx, parse; returns (record, history columns)."""
    tk = {k: summary(*v) for k, v in toolkit_runs_cached(case).items()}
    a_ref = reference_radius(case)
    h0 = a_ref / MESHES[mesh_name]
    if end_time is None:
        key = "modal_hertz" if case == "elastic" else "modal_stronge"
        end_time = END_FACTOR[case] * tk[key]["first_contact_s"]
    t0 = time.perf_counter()
    mesh, tris, in_sphere = build_mesh(h0, FINE_ZONE * a_ref, FAR_SIZE[mesh_name])
    faces = l2.contact_faces(mesh, tris, SLAVE_ZONE * a_ref)
    mesh_time = time.perf_counter() - t0
    deck = build_deck(case, mesh, faces, in_sphere, h0, step, end_time)
    job = f"level4_{case}_{mesh_name}_{step * 1e9:.0f}ns"
    dat, wall = ct.run_ccx(deck, job, workdir)
    text = dat.read_text()
    weights = ct.tet10_mass_weights(mesh, in_sphere, SPHERE_MATERIAL.density)
    times, blocks = parse_velocity_blocks(text, "SPHN")
    t_mid, force, t, v = force_history(times, blocks, weights)
    axis = ct.parse_node_prints(text, "AXIS")
    ids = np.array(sorted(axis[0]))
    zs = mesh.coords[ids - 1, 2]
    top, bottom = ids[np.argmax(zs)], ids[np.argmin(zs)]
    dent = np.array([b[bottom][2] - b[top][2] for b in axis])     # top moves down: > 0
    record = dict(case=case, mesh=mesh_name, a_ref_m=a_ref, a_ref_over_h0=MESHES[mesh_name],
                  size_at_contact_m=h0, size_far_target_m=FAR_SIZE[mesh_name],
                  size_far_sphere_m=RADIUS / 3, growth_per_m_per_m=GROWTH,
                  fine_zone_radius_m=FINE_ZONE * a_ref,
                  contact_faces_slave=len(faces["slave"]),
                  contact_faces_master=len(faces["master"]), n_nodes=len(mesh.coords),
                  n_elements=len(mesh.elements), n_sphere_elements=int(in_sphere.sum()),
                  element_type=mesh.element_type,
                  penalty_slope_Pa_per_m=PENALTY * STEEL.youngs_modulus / h0,
                  time_step_s=step, end_time_s=end_time, increments=len(times),
                  sphere_mesh_mass_kg=4.0 * float(weights.sum()),
                  sphere_mass_kg=float(sphere().mass),
                  target_yield_strength_Pa=STEEL.yield_strength if case == "plastic" else None,
                  mesh_time_s=mesh_time, ccx_wall_time_s=wall,
                  newton_iterations=l2._iterations(dat.with_suffix(".sta")),
                  **fe_quantities(t_mid, force, t, v, dent))
    columns = dict(time_s=t_mid, force_N=force, increment_end_time_s=t[1:],
                   sphere_velocity_m_s=v[1:], axis_shortening_m=dent)
    csv = out_dir / f"{job}.csv"
    np.savetxt(csv, np.column_stack(list(columns.values())), delimiter=",",
               header=",".join(columns), comments="", fmt="%.9e")
    record["csv"] = csv.name
    return record


def toolkit_record(case):
    """The toolkit's scalars of ``case`` and the modal wall time (for the speed ratio)."""
    return {k: summary(*v) for k, v in toolkit_runs_cached(case).items()}


def fe_reference(runs, case):
    """(reference run, mesh-variant run or None, step-variant run or None) of ``case``.

    The reference is the finest mesh at its smallest step; the variants are pairs of
    runs differing in the mesh only / the step only (:func:`convergence`).
    """
    mine = [r for r in runs.values() if r["case"] == case and r["mesh"] != "smoke"
            and r.get("separated")]
    if not mine:
        return None, None, None
    order = {"fine": 0, "coarse": 1}
    ref = min(mine, key=lambda r: (order[r["mesh"]], r["time_step_s"]))
    return ref, convergence(mine, ref, "mesh"), convergence(mine, ref, "time_step_s")


def convergence(runs, ref, what):
    """(finer, coarser): two runs differing only in ``what`` (``"mesh"`` or
    ``"time_step_s"``), at ``ref``'s other setting if there is such a pair, else any
    such pair; None if none."""
    other = "time_step_s" if what == "mesh" else "mesh"
    rank = ((lambda r: r["mesh"] != "fine") if what == "mesh"
            else (lambda r: r["time_step_s"]))
    pairs = [(a, b) for a in runs for b in runs
             if a[other] == b[other] and rank(a) < rank(b)]
    pairs.sort(key=lambda ab: ab[0][other] != ref[other])
    return pairs[0] if pairs else None


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--case", choices=CASES, default="elastic")
    p.add_argument("--mesh", choices=("coarse", "fine"), default="coarse")
    p.add_argument("--step", type=float, default=2.8e-6, help="fixed time increment [s]")
    p.add_argument("--end-time", type=float, default=None,
                   help="end of the run [s] (default END_FACTOR × toolkit first contact)")
    p.add_argument("--threads", default="1", help="ccx threads (FE_THREADS)")
    p.add_argument("--smoke", action="store_true", help="very coarse mesh, 5 increments")
    p.add_argument("--toolkit", action="store_true",
                   help="only compute and store the toolkit's side")
    p.add_argument("--out-dir", type=Path, default=None)
    a = p.parse_args(argv)
    os.environ["FE_THREADS"] = a.threads
    os.environ.setdefault("CCX_NPROC_EQUATION_SOLVER", a.threads)
    if a.smoke:
        out_dir = a.out_dir or Path(tempfile.mkdtemp(prefix="impactmaps-fe-smoke-"))
        a.mesh, a.step, a.end_time = "smoke", 2e-6, 10e-6
    else:
        out_dir = a.out_dir or ct.RESULTS
    out_dir.mkdir(parents=True, exist_ok=True)
    record = None
    if not a.toolkit:
        workdir = out_dir / "work" if a.smoke else ct.WORK / "level4"
        record = run_fe(a.case, a.mesh, a.step, workdir, out_dir, a.end_time)
        record.update(command="python validation/fe/level4_contact.py "
                      + " ".join(argv if argv is not None else sys.argv[1:]),
                      ccx_version=ct.ccx_version(), gmsh_version=ct.gmsh_version(),
                      threads=a.threads)
        print(json.dumps(record, indent=1))
    # read the summary only now: several runs may go on in parallel
    summary_path = out_dir / "level4_contact.json"
    data = json.loads(summary_path.read_text()) if summary_path.exists() else {}
    data["inputs"] = dict(
        sphere_radius_m=RADIUS, velocity_m_s=VELOCITY, beam=BEAM,
        supports="end faces x = ±L/2 held in z (diaphragm)",
        contact="surface-to-surface, frictionless, linear penalty",
        material=dict(E_Pa=STEEL.youngs_modulus, nu=STEEL.poisson_ratio,
                      density=STEEL.density, target_yield_Pa_plastic_case=STEEL.yield_strength),
        sphere="elastic")
    data.setdefault("toolkit", {})[a.case] = toolkit_record(a.case)
    if record is not None:
        data.setdefault("runs", {})[record["csv"][len("level4_"):-len(".csv")]] = record
    summary_path.write_text(json.dumps(data, indent=1))
    return data


if __name__ == "__main__":
    main()
