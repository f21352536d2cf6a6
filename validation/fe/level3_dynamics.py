"""Level 3, step 2: spring-coupled impact on the 3D modal model against the toolkit.

Reads the 3D modes of the quarter beam written by ``level3_modes.py``
(``results/level3_modes_<tag>.npz``), integrates the impact with
``spring_integrator.integrate`` (Hertz spring with the patch's half-space local
compliance removed) and compares peak force, first-contact duration, number of
impacts and restitution with the toolkit's modal solver (Timoshenko beam, Hertz law)
and its finite-difference solver (Rayleigh beam, elastic, Hertz law).

Evidence written to ``results/level3_dynamics.json`` (and the force histories of the
base case to ``results/level3_history.csv``):

* patch-radius insensitivity (the three coarse meshes a_c = 0.35, 0.7, 1.4 mm);
* mesh convergence (a_c = 0.7 mm, coarse vs fine mesh);
* mode convergence (the first half of the modes vs all, residual always added);
* step convergence (h vs h/2);
* several sphere masses (several (ζ, λ) points) on the reference mesh.

Run: ``python validation/fe/level3_dynamics.py`` from the repository root.
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import ccx_tools as ct  # noqa: E402
from spring_integrator import SpringLaw, halfspace_patch_compliance, integrate  # noqa: E402

import impactmaps  # noqa: E402

STEEL = impactmaps.material("structural-steel")
LENGTH, WIDTH, HEIGHT = 0.5, 0.02, 0.02
RADIUS, VELOCITY = 0.01, 1.0
SOLID_MASS = impactmaps.Sphere(RADIUS, STEEL).mass
MASS_FACTORS = (0.01, 0.1, 0.3, 1.0, 3.0, 10.0, 30.0, 100.0)
REFERENCE = "a070_fine"
HISTORY_MASSES = {1.0: "level3_history.csv", 30.0: "level3_history_mass30.csv"}
PATCHES = {"a035_coarse": 0.35e-3, "a070_coarse": 0.7e-3, "a140_coarse": 1.4e-3}


def load_modes(tag):
    d = np.load(ct.RESULTS / f"level3_modes_{tag}.npz")
    meta = json.loads((ct.RESULTS / f"level3_modes_{tag}.json").read_text())
    return d["omega"], d["participation"], float(d["static_compliance"]), meta


def toolkit(mass, linear_stiffness=None, length=LENGTH):
    """Toolkit modal (Timoshenko) and FD (Rayleigh) runs; Hertz law, or linear law."""
    sphere = impactmaps.Sphere(RADIUS, STEEL, mass=mass)
    law = (impactmaps.law_for_sphere("hertz", sphere, STEEL) if linear_stiffness is None
           else impactmaps.contact_law("linear", stiffness=linear_stiffness))
    beam = impactmaps.Beam.rectangular(length, WIDTH, HEIGHT, STEEL)
    t0 = time.perf_counter()
    impactmaps.simulate(beam, law, mass, VELOCITY)       # compile / cache
    t1 = time.perf_counter()
    res = impactmaps.simulate(beam, law, mass, VELOCITY)
    wall = time.perf_counter() - t1
    k_lin = mass * res.contact_frequency ** 2
    zeta = float(impactmaps.loss_factor_beam(mass, k_lin, beam.mass_per_length,
                                             beam.bending_stiffness))
    lam = float(impactmaps.relative_stiffness(beam.static_stiffness(), k_lin))
    fd_beam = impactmaps.FDBeam(length, WIDTH, HEIGHT, STEEL.youngs_modulus, STEEL.density,
                                STEEL.yield_strength, plastic=False)
    fd = impactmaps.simulate_fd(fd_beam, law, mass, VELOCITY, duration=res.end_time)
    summary = lambda r: dict(peak_force_N=float(r.peak_force),
                             first_peak_N=_first_peak(r.history["time_s"].to_numpy(),
                                                      r.history["force_N"].to_numpy(),
                                                      r.contact_intervals),
                             first_contact_s=float(r.contact_intervals[0, 1]
                                                   - r.contact_intervals[0, 0]),
                             impacts=int(len(r.contact_intervals)),
                             restitution=float(r.restitution))
    return law, res, dict(zeta=zeta, lambda_=lam, contact_frequency=float(res.contact_frequency),
                          modal=dict(**summary(res), end_time_s=float(res.end_time),
                                     n_modes=int(res.n_modes), wall_time_s=wall,
                                     first_call_s=t1 - t0),
                          fd=dict(**summary(fd), n_elements=200, theory="rayleigh (FD)"))


def _first_peak(times, force, intervals):
    """Largest force of the first contact [N]."""
    inside = (times >= intervals[0, 0]) & (times <= intervals[0, 1])
    return float(np.max(force[inside]))


def fe_run(tag, law, mass, duration, step, n_modes=None, patch_radius=None,
           whole_law=False):
    """The FE spring model with the 3D modes ``tag``; ``law`` Hertz or linear."""
    omega, phi, compliance, meta = load_modes(tag)
    if n_modes is not None:
        omega, phi = omega[:n_modes], phi[:n_modes]
    residual = compliance - float(np.sum(phi ** 2 / omega ** 2))
    a_c = patch_radius if patch_radius is not None else meta["patch_radius_m"]
    local = 0.0 if whole_law else halfspace_patch_compliance(a_c, STEEL)
    kind = "linear" if law.name == "linear" else "hertz"
    spring = SpringLaw(kind, law.stiffness, local)
    t0 = time.perf_counter()
    run = integrate(omega, phi, residual, spring, mass, VELOCITY, step, duration)
    wall = time.perf_counter() - t0
    iv = run.contact_intervals
    return run, dict(tag=tag, n_modes=int(len(omega)), time_step_s=step,
                     residual_compliance_m_per_N=residual,
                     local_compliance_c_m_per_N=spring.local, patch_radius_m=a_c,
                     peak_force_N=run.peak_force,
                     first_peak_N=_first_peak(run.time, run.force, iv),
                     first_contact_s=float(iv[0, 1] - iv[0, 0]), impacts=int(len(iv)),
                     restitution=run.restitution, integrator_wall_time_s=wall)


def main():
    import argparse
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--reference", default=REFERENCE, help="modes tag of the reference")
    parser.add_argument("--out", default=str(ct.RESULTS / "level3_dynamics.json"))
    parser.add_argument("--masses", type=float, nargs="*", default=list(MASS_FACTORS),
                        help="sphere masses as multiples of the solid sphere's")
    parser.add_argument("--length", type=float, default=LENGTH, help="beam span [m]")
    parser.add_argument("--prefix", default="",
                        help="prefix of the modes tags (e.g. short_ for the 200 mm beam); "
                             "variants are stored under the unprefixed tag names")
    args = parser.parse_args()
    prefix = args.prefix
    reference = prefix + args.reference
    out = {"inputs": dict(length_m=args.length, width_m=WIDTH, height_m=HEIGHT,
                          sphere_radius_m=RADIUS, velocity_m_s=VELOCITY,
                          solid_sphere_mass_kg=SOLID_MASS,
                          material=dict(E_Pa=STEEL.youngs_modulus, nu=STEEL.poisson_ratio,
                                        rho_kg_m3=STEEL.density),
                          spring="alpha_s(F) = (F/K_h)^(2/3) - c F, c = 16(1-nu^2)/(3 pi^2 a_c E)",
                          supports="3D: end faces held in z (diaphragm); toolkit: ss"),
           "command": "python validation/fe/level3_dynamics.py " + " ".join(sys.argv[1:]),
           "reference": reference,
           "modes": {tag: load_modes(tag)[3]
                     for tag in dict.fromkeys([reference, *(prefix + t for t in PATCHES)])
                     if (ct.RESULTS / f"level3_modes_{tag}.npz").exists()},
           "cases": []}
    for factor in args.masses:
        mass = factor * SOLID_MASS
        law, res, entry = toolkit(mass, length=args.length)
        t_c = entry["modal"]["first_contact_s"]
        duration = 1.05 * entry["modal"]["end_time_s"]
        step = t_c / 1000
        entry.update(mass_kg=mass, mass_factor=factor, fe={})
        fe = entry["fe"]
        run, fe["reference"] = fe_run(reference, law, mass, duration, step)
        _, fe["half_step"] = fe_run(reference, law, mass, duration, step / 2)
        n_all = fe["reference"]["n_modes"]
        _, fe["half_modes"] = fe_run(reference, law, mass, duration, step, n_modes=n_all // 2)
        # the trap of the issue: the whole Hertz law on the spring (c = 0)
        _, fe["whole_law_on_spring"] = fe_run(reference, law, mass, duration, step,
                                              whole_law=True)
        for tag in PATCHES:
            if (ct.RESULTS / f"level3_modes_{prefix + tag}.npz").exists():
                _, fe[tag] = fe_run(prefix + tag, law, mass, duration, step)
        print(json.dumps({k: v for k, v in entry.items() if k != "fe"}), flush=True)
        for k, v in fe.items():
            print("  ", k, {q: v[q] for q in ("peak_force_N", "first_contact_s", "impacts",
                                               "restitution")}, flush=True)
        entry["linear"] = _linear_variant(mass, mass * entry["contact_frequency"] ** 2,
                                          reference, prefix, args.length)
        out["cases"].append(entry)
        if factor in HISTORY_MASSES and reference == REFERENCE and args.length == LENGTH:
            _write_history(run, res, law, mass, HISTORY_MASSES[factor])
        Path(args.out).write_text(json.dumps(out, indent=1))


def _linear_variant(mass, stiffness, reference, prefix, length):
    """The same point with a linear contact law of the Hertz law's linearised stiffness."""
    law, res, entry = toolkit(mass, linear_stiffness=stiffness, length=length)
    t_c = entry["modal"]["first_contact_s"]
    duration, step = 1.05 * entry["modal"]["end_time_s"], t_c / 1000
    fe = {"reference": fe_run(reference, law, mass, duration, step)[1],
          "half_step": fe_run(reference, law, mass, duration, step / 2)[1]}
    for tag in PATCHES:
        if (ct.RESULTS / f"level3_modes_{prefix + tag}.npz").exists():
            fe[tag] = fe_run(prefix + tag, law, mass, duration, step)[1]
    entry.update(stiffness_N_m=stiffness, fe=fe)
    print("   linear", {k: (round(v["peak_force_N"], 1), round(1e6 * v["first_contact_s"], 2))
                        for k, v in fe.items()},
          "modal", round(entry["modal"]["peak_force_N"], 1),
          round(1e6 * entry["modal"]["first_contact_s"], 2), flush=True)
    return entry


def _write_history(run, res, law, mass, name):
    """Force histories of one case (FE spring model, modal, FD) on one CSV."""
    fd_beam = impactmaps.FDBeam(LENGTH, WIDTH, HEIGHT, STEEL.youngs_modulus, STEEL.density,
                                STEEL.yield_strength, plastic=False)
    fd = impactmaps.simulate_fd(fd_beam, law, mass, VELOCITY, duration=res.end_time)
    stride = max(1, len(run.time) // 4000)
    t = run.time[::stride]
    modal = np.interp(t, res.history["time_s"], res.history["force_N"])
    fdf = np.interp(t, fd.history["time_s"], fd.history["force_N"])
    data = np.column_stack([t, run.force[::stride], modal, fdf])
    np.savetxt(ct.RESULTS / name, data, delimiter=",", fmt="%.6e",
               header="time_s,fe_spring_force_N,modal_timoshenko_force_N,fd_rayleigh_force_N",
               comments="")


if __name__ == "__main__":
    main()
