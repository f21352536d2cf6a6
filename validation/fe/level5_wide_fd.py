"""Level 5, the FD beam's wide-section model against the 3D reference (run as
``python validation/fe/level5_wide_fd.py``).

Under the committed force (FORCE_CSV, the uniaxial coupled impact): the FD beam with and
without the wide-section model on six grids against the FE reference; the sensitivity to
the constraint strain (each width's own fit of ``level5_wide_calibration.py``); the
coupled impact with the model (its force is written to FORCE_WIDE_CSV); and, once the FE
run driven by that force (REFERENCE_WIDE_FORCE) is committed, the FD beam under it.
Results: the ``fd_wide`` entry of ``results/level5_beam_plastic.json``.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import ccx_tools as ct
from level5_beam_plastic import (
    FE_END,
    FORCE_WIDE_CSV,
    REFERENCE,
    REFERENCE_WIDE_FORCE,
    fd_impact,
    fd_prescribed,
    fd_summary,
    load,
    prescribed_force,
    save,
)


def constraint_strain_sensitivity(times, force, ref):
    """FD (200 × 10, wide-section model) under the force with n_c = ε_c E/σ_y set to each
    width's own best fit of the calibration (results/level5_wide_calibration.json)."""
    from impactmaps.fd import wide_section

    fitted = json.loads((ct.RESULTS / "level5_wide_calibration.json").read_text())
    out, kept = {}, wide_section.CONSTRAINT_STRAIN_RATIO
    try:
        for tag, n_c in fitted["constraint_strain_ratio_per_width"].items():
            wide_section.CONSTRAINT_STRAIN_RATIO = n_c
            t, w, perm = fd_prescribed(times, force, width_constraint=True, permanent=True)
            out[tag] = dict(n_c=n_c, peak_over_fe=float(w.max() / ref["peak_deflection_m"] - 1),
                            permanent_over_fe=float(perm / ref["permanent_deflection_m"] - 1))
            print("n_c of", tag, out[tag], flush=True)
    finally:
        wide_section.CONSTRAINT_STRAIN_RATIO = kept
    return out


def run_fd_wide(_args):
    """The FD beam with the wide-section model against the 3D reference, same force: grid
    study (prescribed load) and the coupled impact (its own force; information only)."""
    times, force = prescribed_force()
    data = load()
    ref = data["fe_runs"][REFERENCE]
    study = {}
    for nl, nh in ((100, 10), (200, 10), (400, 10), (200, 20), (200, 40), (400, 20)):
        for constrained in (True, False):
            t, w, perm = fd_prescribed(times, force, nl, nh, width_constraint=constrained,
                                       permanent=True)
            key = f"{nl}x{nh}" + ("" if constrained else "_uniaxial")
            study[key] = dict(peak_deflection_m=float(w.max()), permanent_deflection_m=perm,
                              peak_over_fe=float(w.max() / ref["peak_deflection_m"] - 1),
                              permanent_over_fe=float(perm / ref["permanent_deflection_m"] - 1))
            print(key, study[key], flush=True)
    impact = fd_impact(duration=FE_END, width_constraint=True)
    h = impact.history
    np.savetxt(FORCE_WIDE_CSV, np.column_stack([times, *(np.interp(times, h["time_s"], h[c])
                                                          for c in ("force_N",
                                                                    "target_displacement_m"))]),
               delimiter=",", fmt="%.9e", comments="",
               header="time_s,force_N,fd_midspan_deflection_m")
    coupled = fd_summary(impact)
    coupled["peak_over_fe"] = coupled["peak_deflection_m"] / ref["peak_deflection_m"] - 1
    coupled["permanent_over_fe"] = coupled["permanent_deflection_m"] / ref["permanent_deflection_m"] - 1
    print("coupled", coupled)
    sensitivity = constraint_strain_sensitivity(times, force, ref)
    own = data["fe_runs"].get(REFERENCE_WIDE_FORCE)
    if own is not None:     # the second load: the wide-section model's own coupled force
        tw, fw = prescribed_force(csv=FORCE_WIDE_CSV)
        for nl, nh in ((200, 10), (200, 20), (400, 20)):
            for constrained in (True, False):
                t, w, perm = fd_prescribed(tw, fw, nl, nh, width_constraint=constrained, permanent=True)
                key = f"wide_force_{nl}x{nh}" + ("" if constrained else "_uniaxial")
                study[key] = dict(peak_deflection_m=float(w.max()), permanent_deflection_m=perm,
                                  peak_over_fe=float(w.max() / own["peak_deflection_m"] - 1),
                                  permanent_over_fe=float(perm / own["permanent_deflection_m"] - 1))
                print(key, study[key], flush=True)
    data["fd_wide"] = dict(prescribed=study, coupled_own_force=coupled, reference=REFERENCE,
                           constraint_strain_sensitivity=sensitivity,
                           command="python validation/fe/level5_wide_fd.py")
    save(data)


if __name__ == "__main__":
    run_fd_wide(None)
