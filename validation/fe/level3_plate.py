"""Level 3 on a plate: spring-coupled impact on the 3D modes of an SSSS square plate.

Steel plate 200 × 200 × 10 mm (span/thickness 20), simply supported (side faces held
in z and tangentially, the support that matches Mindlin's SSSS in level 1), struck at
the centre by a steel sphere R = 10 mm at 1 m/s, several sphere masses.  Modes from

    python validation/fe/level3_modes.py --plate --tag plate_a070_coarse --length 0.2 \\
        --width 0.2 --height 0.01 --patch-radius 0.0007 --refine 3 --far-size 0.005 --modes 60
    python validation/fe/level3_modes.py --plate --tag plate_a070_fine --length 0.2 \\
        --width 0.2 --height 0.01 --patch-radius 0.0007 --refine 5 --far-size 0.0033 --modes 60

then ``python validation/fe/level3_plate.py`` → ``results/level3_plate.json``.  The
toolkit side is the modal solver with the Mindlin plate and the Hertz law (no FD
solver for plates).
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path


sys.path.insert(0, str(Path(__file__).resolve().parent))
import ccx_tools as ct  # noqa: E402
import level3_dynamics as l3d  # noqa: E402

import impactmaps  # noqa: E402

STEEL = l3d.STEEL
SIDE, THICKNESS = 0.2, 0.01
MASS_FACTORS = (0.1, 1.0, 10.0, 100.0)
REFERENCE, COARSE = "plate_a070_fine", "plate_a070_coarse"


def toolkit(mass):
    sphere = impactmaps.Sphere(l3d.RADIUS, STEEL, mass=mass)
    law = impactmaps.law_for_sphere("hertz", sphere, STEEL)
    plate = impactmaps.Plate.isotropic(SIDE, SIDE, THICKNESS, STEEL, theory="mindlin")
    impactmaps.simulate(plate, law, mass, l3d.VELOCITY)
    t0 = time.perf_counter()
    res = impactmaps.simulate(plate, law, mass, l3d.VELOCITY)
    wall = time.perf_counter() - t0
    k_lin = mass * res.contact_frequency ** 2
    zeta = float(impactmaps.loss_factor_plate(mass, k_lin, plate.mass_per_area,
                                              plate.effective_bending_stiffness))
    lam = float(impactmaps.relative_stiffness(plate.static_stiffness(), k_lin))
    iv = res.contact_intervals
    h = res.history
    first = h[(h["time_s"] >= iv[0, 0]) & (h["time_s"] <= iv[0, 1])]["force_N"].max()
    return law, res, dict(zeta=zeta, lambda_=lam, modal=dict(
        peak_force_N=float(res.peak_force), first_peak_N=float(first),
        first_contact_s=float(iv[0, 1] - iv[0, 0]), impacts=int(len(iv)),
        restitution=float(res.restitution), end_time_s=float(res.end_time),
        n_modes=int(res.n_modes), wall_time_s=wall))


def main():
    out = {"inputs": dict(side_m=SIDE, thickness_m=THICKNESS, sphere_radius_m=l3d.RADIUS,
                          velocity_m_s=l3d.VELOCITY, theory="mindlin", edges="SSSS"),
           "command": "python validation/fe/level3_plate.py",
           "modes": {t: l3d.load_modes(t)[3] for t in (REFERENCE, COARSE)
                     if (ct.RESULTS / f"level3_modes_{t}.npz").exists()},
           "cases": []}
    reference = REFERENCE if REFERENCE in out["modes"] else COARSE
    out["reference"] = reference
    for factor in MASS_FACTORS:
        mass = factor * l3d.SOLID_MASS
        law, res, entry = toolkit(mass)
        t_c = entry["modal"]["first_contact_s"]
        duration, step = 1.05 * entry["modal"]["end_time_s"], t_c / 1000
        fe = {"reference": l3d.fe_run(reference, law, mass, duration, step)[1],
              "half_step": l3d.fe_run(reference, law, mass, duration, step / 2)[1],
              "half_modes": l3d.fe_run(reference, law, mass, duration, step, n_modes=30)[1]}
        if reference != COARSE and COARSE in out["modes"]:
            fe[COARSE] = l3d.fe_run(COARSE, law, mass, duration, step)[1]
        entry.update(mass_kg=mass, mass_factor=factor, fe=fe)
        out["cases"].append(entry)
        print(factor, round(entry["zeta"], 4), round(entry["lambda_"], 4), "modal",
              {k: entry["modal"][k] for k in ("first_peak_N", "peak_force_N",
                                              "first_contact_s", "impacts")}, flush=True)
        for k, v in fe.items():
            print("   ", k, {q: v[q] for q in ("first_peak_N", "peak_force_N",
                                               "first_contact_s", "impacts",
                                               "restitution")}, flush=True)
        (ct.RESULTS / "level3_plate.json").write_text(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
