"""Level 6, impact: spring-coupled impact on the 3D modes of a *clamped* (CCCC) square plate.

Level 3's SSSS plate (``level3_plate.py``) with the side faces fully held (the 3D clamp,
PHYSICS.md §3.7): steel plate 200 × 200 × 10 mm (a/h = 20), struck at the centre by a steel
sphere R = 10 mm at 1 m/s, sphere masses 0.1 / 1 / 10 / 100 × the solid sphere's.  Modes and
the static patch compliance (uniform pressure on a disc of radius 0.7 mm, the Hertz contact
radius of these impacts) from

    OMP_NUM_THREADS=1 FE_THREADS=1 nice -n 10 python validation/fe/level3_modes.py --plate --clamped \\
        --tag cccc_a070_coarse --length 0.2 --width 0.2 --height 0.01 --patch-radius 0.0007 \\
        --refine 3 --far-size 0.005 --modes 60
    ... --tag cccc_a070_fine ... --refine 5 --far-size 0.0033 --modes 60

then ``python validation/fe/level6_impact.py`` → ``results/level6_impact.json`` (seconds, no
ccx): the FE spring model (``spring_integrator.py``, as level 3) per mass on both meshes, with
half the step and half the modes, and the toolkit's CCCC Kirchhoff and Mindlin plates.

The thick plate (a/h = 10, h = 20 mm; the same plate, sphere and masses), which checks the
3D-consistent near field of ``impactmaps/targets/plates/near_field.py`` where it moves the answer
most::

    OMP_NUM_THREADS=2 FE_THREADS=2 nice -n 10 python validation/fe/level3_modes.py --plate --clamped \
        --tag cccc_h20_a070_coarse --length 0.2 --width 0.2 --height 0.02 --patch-radius 0.0007 \
        --refine 3 --far-size 0.005 --modes 60
    ... --tag cccc_h20_a070_fine ... --refine 5 --far-size 0.0033 --modes 60
    python validation/fe/level6_impact.py --thickness 0.02 --prefix cccc_h20 \
        --out validation/fe/results/level6_impact_h20.json
"""

from __future__ import annotations

import json
import sys
import time
import warnings
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import ccx_tools as ct  # noqa: E402
import level3_dynamics as l3d  # noqa: E402

import impactmaps  # noqa: E402

STEEL = l3d.STEEL
SIDE, THICKNESS = 0.2, 0.01
MASS_FACTORS = (0.1, 1.0, 10.0, 100.0)


def toolkit(mass, theory, thickness=THICKNESS):
    """First-contact peak and duration of the toolkit's CCCC plate, or the reason it has none."""
    sphere = impactmaps.Sphere(l3d.RADIUS, STEEL, mass=mass)
    law = impactmaps.law_for_sphere("hertz", sphere, STEEL)
    try:
        plate = impactmaps.Plate.isotropic(SIDE, SIDE, thickness, STEEL, theory=theory, edges="CCCC")
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            t0 = time.perf_counter()
            res = impactmaps.simulate(plate, law, mass, l3d.VELOCITY)
            wall = time.perf_counter() - t0
    except ValueError as exc:
        return law, None, dict(theory=theory, available=False, reason=str(exc)[:200])
    iv = res.contact_intervals
    h = res.history
    if h is None:            # an asymptote answers with scalars only (one contact)
        first = res.peak_force
    else:
        first = h[(h["time_s"] >= iv[0, 0]) & (h["time_s"] <= iv[0, 1])]["force_N"].max()
    return law, res, dict(theory=theory, available=True, method=str(getattr(res, "method", "")),
                          peak_force_N=float(res.peak_force),
                          first_peak_N=float(first), first_contact_s=float(iv[0, 1] - iv[0, 0]),
                          impacts=int(len(iv)), restitution=float(res.restitution),
                          end_time_s=float(res.end_time), n_modes=int(res.n_modes),
                          warnings=sorted({str(w.message)[:160] for w in caught}),
                          wall_time_s=wall)


def main(argv=None):
    import argparse
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--thickness", type=float, default=THICKNESS, help="plate thickness [m]")
    parser.add_argument("--prefix", default="cccc", help="modes tags <prefix>_a070_fine/_coarse")
    parser.add_argument("--out", default=str(ct.RESULTS / "level6_impact.json"))
    args = parser.parse_args(argv)
    thickness = args.thickness
    ref_tag, coarse_tag = f"{args.prefix}_a070_fine", f"{args.prefix}_a070_coarse"
    modes = {t: l3d.load_modes(t)[3] for t in (ref_tag, coarse_tag)
             if (ct.RESULTS / f"level3_modes_{t}.npz").exists()}
    reference = ref_tag if ref_tag in modes else coarse_tag
    out = {"inputs": dict(side_m=SIDE, thickness_m=thickness, sphere_radius_m=l3d.RADIUS,
                          velocity_m_s=l3d.VELOCITY, edges="CCCC (3D: side faces fully held)",
                          material=dict(E_Pa=STEEL.youngs_modulus, nu=STEEL.poisson_ratio,
                                        rho_kg_m3=STEEL.density)),
           "command": ("python validation/fe/level6_impact.py " + " ".join(
               argv if argv is not None else sys.argv[1:])).rstrip(),
           "modes": modes, "reference": reference,
           "static_patch_compliance_m_per_N": {t: m["static_compliance_m_per_N"]
                                               for t, m in modes.items()},
           "cases": []}
    kirchhoff = impactmaps.Plate.isotropic(SIDE, SIDE, thickness, STEEL, theory="kirchhoff",
                                           edges="CCCC")
    out["toolkit_kirchhoff_point_compliance_m_per_N"] = kirchhoff.static_compliance()
    # the 3D patch compliance includes the local indentation of the uniform-pressure disc,
    # which the Hertz law carries: the structural part is what a plate theory must match
    local = l3d.halfspace_patch_compliance(modes[reference]["patch_radius_m"], STEEL)
    out["halfspace_patch_compliance_m_per_N"] = local
    out["structural_patch_compliance_m_per_N"] = {
        t: m["static_compliance_m_per_N"] - local for t, m in modes.items()}
    for factor in MASS_FACTORS:
        mass = factor * l3d.SOLID_MASS
        law, res, kir = toolkit(mass, "kirchhoff", thickness)
        _, _, mind = toolkit(mass, "mindlin", thickness)
        t_c = kir["first_contact_s"]
        duration, step = 1.05 * kir["end_time_s"], t_c / 1000
        fe = {"reference": l3d.fe_run(reference, law, mass, duration, step)[1],
              "half_step": l3d.fe_run(reference, law, mass, duration, step / 2)[1],
              "half_modes": l3d.fe_run(reference, law, mass, duration, step, n_modes=30)[1]}
        if reference != coarse_tag and coarse_tag in modes:
            fe[coarse_tag] = l3d.fe_run(coarse_tag, law, mass, duration, step)[1]
        entry = dict(mass_kg=mass, mass_factor=factor, toolkit_kirchhoff=kir,
                     toolkit_mindlin=mind, fe=fe)
        out["cases"].append(entry)
        print(factor, "kirchhoff", {k: kir[k] for k in ("first_peak_N", "first_contact_s", "impacts")},
              "mindlin", mind.get("first_peak_N", mind.get("reason", "")[:60]), flush=True)
        for k, v in fe.items():
            print("   ", k, {q: v[q] for q in ("first_peak_N", "peak_force_N", "first_contact_s",
                                               "impacts", "restitution")}, flush=True)
        Path(args.out).write_text(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
