"""Level 3, check of the modal integrator against a direct CalculiX dynamic run.

The spring-coupled integrator represents the 3D beam by its ccx modes + a static
residual (``spring_integrator.py``).  Here the same quarter mesh (regenerated from
the parameters recorded in ``results/level3_modes_<tag>.json``) is driven in ccx by
direct implicit time integration (*DYNAMIC, DIRECT, α = 0: trapezoidal rule, no
numerical damping) with the contact force history of the integrator's first contact
applied as a uniform patch pressure (*AMPLITUDE), and the patch mean deflection of the
two is compared over the first contact and a little after.

Run: ``python validation/fe/level3_direct_check.py --tag a070_coarse``.
Output: ``results/level3_direct_check.json`` and ``results/level3_direct_check.csv``.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import ccx_tools as ct  # noqa: E402
import level3_dynamics as l3d  # noqa: E402
import level3_modes as l3m  # noqa: E402
from spring_integrator import step_coefficients  # noqa: E402


def modal_patch_deflection(omega, phi, residual, times, force):
    """Patch mean deflection Σ p_j q_j + r F under a piecewise-linear force history."""
    q = np.zeros_like(omega)
    qd = np.zeros_like(omega)
    out = [0.0]
    for k in range(len(times) - 1):
        h = times[k + 1] - times[k]
        f0, f1 = force[k], force[k + 1]
        c, s, g0, g1, d0, d1 = step_coefficients(omega, h)
        q, qd = (q * c + qd * s / omega + phi * (f0 * (g0 - g1) + f1 * g1),
                 -q * omega * s + qd * c + phi * (f0 * (d0 - d1) + f1 * d1))
        out.append(float(np.dot(phi, q) + residual * f1))
    return np.array(out)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--tag", default="a070_coarse")
    p.add_argument("--step", type=float, default=0.5e-6)
    p.add_argument("--duration", type=float, default=100e-6)
    a = p.parse_args()
    meta = json.loads((ct.RESULTS / f"level3_modes_{a.tag}.json").read_text())
    omega, phi, compliance, _ = l3d.load_modes(a.tag)
    residual = compliance - float(np.sum(phi ** 2 / omega ** 2))
    # the contact force of the base case (solid sphere, 1 m/s) from the integrator
    law, res, entry = l3d.toolkit(l3d.SOLID_MASS)
    t_c = entry["modal"]["first_contact_s"]
    run, _ = l3d.fe_run(a.tag, law, l3d.SOLID_MASS, a.duration, t_c / 1000)
    times = np.arange(0.0, a.duration + 1e-12, a.step)
    force = np.interp(times, run.time, run.force)
    mesh, tri_ids, tri_xyz = l3m.quarter_beam_mesh(
        meta["length_m"], meta["width_m"], meta["height_m"], meta["patch_radius_m"],
        meta["patch_radius_m"] / meta["size_on_patch_m"], meta["size_far_m"])
    if len(mesh.coords) != meta["n_nodes"]:
        raise RuntimeError("regenerated mesh differs from the modal run's mesh")
    patch_ids, patch_w, _ = l3m.patch_weights(tri_ids, tri_xyz)
    deck = l3m.build_deck(mesh, meta["length_m"], meta["height_m"], patch_ids, patch_w, 1)
    deck = deck.split("*STEP", 1)[0]
    amp = "".join(f"{t:.9e},{f / 4:.9e}\n" for t, f in zip(times, force))
    deck += "*AMPLITUDE, NAME=FORCE\n" + amp
    deck += (f"*STEP, INC=100000\n*DYNAMIC, DIRECT, ALPHA=0.0\n{a.step},{a.duration}\n"
             "*CLOAD, AMPLITUDE=FORCE\n")
    deck += "".join(f"{n},3,{-w:.12e}\n" for n, w in zip(patch_ids, patch_w))
    deck += "*NODE PRINT, NSET=PATCH\nU\n*END STEP\n"
    dat, wall = ct.run_ccx(deck, f"direct_{a.tag}", ct.WORK / "level3")
    text = dat.read_text()
    blocks = ct.parse_node_prints(text, "PATCH")
    t_fe = ct.parse_node_print_times(text, "PATCH")
    u_fe = np.array([np.dot(patch_w, [-b[i][2] for i in patch_ids]) for b in blocks])
    u_modal = modal_patch_deflection(omega, phi, residual, times, force)
    u_modal_at = np.interp(t_fe, times, u_modal)
    peak = np.abs(u_fe).max()
    result = dict(tag=a.tag, step_s=a.step, duration_s=a.duration, ccx_wall_time_s=wall,
                  ccx_version=ct.ccx_version(), n_modes=len(omega),
                  residual_compliance_m_per_N=residual,
                  peak_patch_deflection_direct_m=float(peak),
                  peak_patch_deflection_modal_m=float(np.abs(u_modal_at).max()),
                  max_abs_difference_over_peak=float(np.abs(u_fe - u_modal_at).max() / peak),
                  command="python validation/fe/level3_direct_check.py " + " ".join(sys.argv[1:]))
    (ct.RESULTS / "level3_direct_check.json").write_text(json.dumps(result, indent=1))
    np.savetxt(ct.RESULTS / "level3_direct_check.csv",
               np.column_stack([t_fe, np.interp(t_fe, times, force), u_fe, u_modal_at]),
               delimiter=",", fmt="%.6e", comments="",
               header="time_s,force_N,patch_deflection_direct_m,patch_deflection_modal_m")
    print(json.dumps(result, indent=1))


if __name__ == "__main__":
    main()
