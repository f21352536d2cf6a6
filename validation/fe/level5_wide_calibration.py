"""Level 5, calibration of the FD beam's wide-section model on the 3D static bending runs.

Reads the committed static runs of ``level5_static_bending.py`` (quarter beams, C3D20R,
elastic–perfectly plastic, strip-loaded 3-point bending, b/h = 0.36 … 8.63) and fits the
two constants of :mod:`impactmaps.fd.wide_section`:

1. λ (``EDGE_LENGTH``): the 3D limit loads ``P_lim(b/h) = P_0 (1 + (2/√3 − 1) φ(b/h))``,
   ``φ = 1 − tanh(u)/u``, ``u = (b/h)/(2λ)``, least squares over every width (P_0 free:
   the 3D strip-loaded beam's own excess over beam theory as b → 0);
2. n_c (``CONSTRAINT_STRAIN_RATIO``, ε_c = n_c σ_y/E): the 3D static load–deflection
   curves of the wide beams (b/h > 1) up to 1.5 P_y, where the narrow 3D beam follows
   beam theory (within 1.3 %), against the static deflection of the FD section with the
   fitted λ (monotonic M(κ) of :class:`impactmaps.fd.LayeredSection`, N_h = 40, integrated
   by virtual work under the same strip load); least squares on the relative deflection.

Run: ``python validation/fe/level5_wide_calibration.py`` (seconds; no ccx) → prints the
fit and writes ``results/level5_wide_calibration.json``. ``--smoke``: a coarse fit into a
temporary directory.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np
from scipy.optimize import least_squares, minimize_scalar

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
import ccx_tools as ct
from _script_options import parse
from level5_beam_plastic import HEIGHT, LENGTH, STEEL, load

from impactmaps.fd import LayeredSection
from impactmaps.fd import wide_section as ws

#: The static runs used: (tag in the JSON's static_runs, CSV name) — the finest across the
#: width where two exist.
LIMIT_RUNS = ("static_b10mm_nz4_ny1_p1.7", "static_b27.8mm_nz4_ny1_p1.8",
              "static_b60mm_nz4_ny2_p1.8", "static_b120mm_nz4_ny2_p1.8",
              "static_b240mm_nz4_ny4_p1.8")
CURVE_MAX_LOAD = 1.5                    # P/P_y: upper end of the curve fit
CSV_NAME = "level5_{tag}.csv"


def restraint(ratio, edge_length):
    """φ(b/h) = 1 − tanh(u)/u, u = (b/h)/(2λ) (vectorised)."""
    u = np.asarray(ratio, float) / (2.0 * edge_length)
    return 1.0 - np.tanh(u) / u


def fit_limit_loads(ratios, limits):
    """(P_0 [P_y], λ [h], fitted limits): least squares of the limit-load form."""
    gain = ws.PLANE_STRAIN_FACTOR - 1.0
    fit = least_squares(lambda p: p[0] * (1 + gain * restraint(ratios, p[1])) - limits,
                        [1.5, 0.6], bounds=([1.0, 0.05], [2.0, 10.0]))
    p0, lam = fit.x
    return float(p0), float(lam), p0 * (1 + gain * restraint(ratios, lam))


def fd_static_deflection(width, loads_over_py, saturation, strain, n_half_layers=40):
    """Mid-span deflection [m] of the FD section's beam under the strip load P (statics:
    monotonic M(κ) of the layered section with the width constraint, virtual work)."""
    e, sy = STEEL.youngs_modulus, STEEL.yield_strength
    section = LayeredSection(width, HEIGHT, e, sy, 0.0, n_half_layers, saturation * sy,
                             1.0 / strain if saturation > 0 else 0.0)
    kappa_y = 2 * sy / (e * HEIGHT)
    kappa = kappa_y * np.concatenate([np.linspace(0.0, 1.0, 40)[:-1], np.geomspace(1.0, 200.0, 1500)])
    moment = section.moment_curvature(-kappa)
    patch, p_y = HEIGHT / 8, 4 * sy * width * HEIGHT**2 / 6 / LENGTH
    x = np.linspace(0.0, 0.5 * LENGTH, 2001)
    shape = 0.5 * x - np.clip(x - (0.5 * LENGTH - patch), 0, None) ** 2 / (4 * patch)
    out = []
    for p in np.asarray(loads_over_py) * p_y:
        m = p * shape
        out.append(np.inf if m.max() >= moment.max() else
                   float(np.trapezoid(np.interp(m, moment, kappa) * x, x)))
    return np.array(out)


def calibrate(runs, csv_dir, smoke=False):
    """The fit: a dict for the JSON."""
    height = HEIGHT
    ratios = np.array([runs[t]["width_m"] / height for t in LIMIT_RUNS])
    limits = np.array([runs[t]["last_converged_load_over_Py"] for t in LIMIT_RUNS])
    p0, lam, fitted = fit_limit_loads(ratios, limits)
    gain = ws.PLANE_STRAIN_FACTOR - 1.0
    curves = []
    for tag, ratio in zip(LIMIT_RUNS, ratios):
        if ratio <= ws.NARROW_RATIO + 1e-6:
            continue
        rows = np.loadtxt(csv_dir / CSV_NAME.format(tag=tag), delimiter=",", skiprows=1)
        keep = (rows[:, 0] > 0.9) & (rows[:, 0] <= CURVE_MAX_LOAD + 1e-9)
        rows = rows[keep][:: 4 if smoke else 1]
        saturation = gain * (restraint(ratio, lam) - restraint(ws.NARROW_RATIO, lam))
        curves.append((tag, ratio, saturation, rows))
    yield_strain = STEEL.yield_strength / STEEL.youngs_modulus

    def misfit(log_nc, only=None):
        errors = []
        for tag, ratio, saturation, rows in curves:
            if only is not None and tag != only:
                continue
            fd = fd_static_deflection(ratio * height, rows[:, 0], saturation,
                                      np.exp(log_nc) * yield_strain)
            errors.append(fd / rows[:, 1] - 1.0)
        e = np.concatenate(errors)
        return float(np.sum(np.where(np.isfinite(e), e, 1.0) ** 2))

    bounds = (np.log(0.05), np.log(20.0))
    n_c = float(np.exp(minimize_scalar(misfit, bounds=bounds, method="bounded").x))
    per_width = {tag: float(np.exp(minimize_scalar(misfit, bounds=bounds, method="bounded",
                                                   args=(tag,)).x)) for tag, *_ in curves}
    curve_errors = {}
    for tag, ratio, saturation, rows in curves:
        fd = fd_static_deflection(ratio * height, rows[:, 0], saturation, n_c * yield_strain)
        uniaxial = fd_static_deflection(ratio * height, rows[:, 0], 0.0, 1.0)
        curve_errors[tag] = dict(
            load_over_Py=[float(v) for v in rows[:, 0]],
            fe_m=[float(v) for v in rows[:, 1]],
            fd_wide_over_fe=[float(v) for v in fd / rows[:, 1]],
            fd_uniaxial_over_fe=[float(v) for v in uniaxial / rows[:, 1]],
            saturation_over_yield=float(saturation))
    return dict(
        edge_length_over_h=lam, strip_baseline_limit_over_Py=p0,
        constraint_strain_ratio=n_c, constraint_strain_ratio_per_width=per_width,
        limit_loads=[dict(run=t, width_over_height=float(r), fe_limit_over_Py=float(f),
                          fit_over_Py=float(g), fit_error=float(g / f - 1))
                     for t, r, f, g in zip(LIMIT_RUNS, ratios, limits, fitted)],
        beam_theory_limit_over_Py=float(LENGTH / (LENGTH - HEIGHT / 8) * 1.5),
        curve_fit_max_load_over_Py=CURVE_MAX_LOAD, curves=curve_errors,
        module_constants=dict(EDGE_LENGTH=ws.EDGE_LENGTH,
                              CONSTRAINT_STRAIN_RATIO=ws.CONSTRAINT_STRAIN_RATIO),
        command="python validation/fe/level5_wide_calibration.py")


def main(argv=None):
    args = parse(__doc__.splitlines()[0], argv, default_out=ct.RESULTS)
    runs = load().get("static_runs", {})
    missing = [t for t in LIMIT_RUNS if t not in runs]
    if missing:
        print(f"static runs not committed: {missing} (level5_static_bending.py)")
        (args.out_dir / "level5_wide_calibration.json").write_text("{}\n")
        return
    result = calibrate(runs, ct.RESULTS, smoke=args.smoke)
    (args.out_dir / "level5_wide_calibration.json").write_text(json.dumps(result, indent=1) + "\n")
    print(f"lambda = {result['edge_length_over_h']:.4f} h, P_0 = {result['strip_baseline_limit_over_Py']:.4f} P_y, "
          f"n_c = {result['constraint_strain_ratio']:.3f} (per width: "
          + ", ".join(f"{k}: {v:.3f}" for k, v in result["constraint_strain_ratio_per_width"].items()) + ")")
    for row in result["limit_loads"]:
        print(f"  b/h {row['width_over_height']:.2f}: FE limit {row['fe_limit_over_Py']:.4f} P_y, "
              f"fit {row['fit_over_Py']:.4f} ({row['fit_error']:+.2%})")
    for tag, c in result["curves"].items():
        print(f"  {tag}: FD wide / FE up to {CURVE_MAX_LOAD} P_y: "
              + " ".join(f"{p:.2f}:{r:.3f}" for p, r in zip(c["load_over_Py"], c["fd_wide_over_fe"])
                         if p >= 1.2))


if __name__ == "__main__":
    main()
