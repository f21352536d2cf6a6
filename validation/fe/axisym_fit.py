"""Fit the coefficients of the ``epp`` contact law to the axisymmetric FE runs.

Reads ``results/axisym_runs.csv`` (written by ``axisym_indent.py``) and fits the
eight coefficients of :mod:`impactmaps.contact.epp` by weighted least squares on the
three quantities the law is judged by, per run (δ_m/δ_y = x_m):

* the force at δ_m, F_m/F_y (weight 1/3 %),
* the restitution of the quasi-static half-space impact, e = sqrt(W_rec/W_abs)
  (weight 1/3 %; W_abs of the law by quadrature of its loading curve),
* the permanent indentation δ_r/δ_m (= the FE's δ_0/δ_m, the approach where the
  unloading force vanishes; weight 1/10 %, runs with δ_r > 0.02 δ_m).

Prints the coefficients as a Python dict (to paste into ``epp.COEFFICIENTS``) and
the worst relative errors.  Run: ``python validation/fe/axisym_fit.py``.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd
from scipy.integrate import quad
from scipy.optimize import least_squares

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1]))
from impactmaps.contact import epp  # noqa: E402

ORDER = epp._ORDER


def law_values(coef, xm):
    """(F_m/F_y, e, δ_r/δ_m) of the law with coefficients ``coef`` at x_m (array)."""
    c, p, q, rho_inf, s, t, n_inf, k = coef

    def load(x):
        if x <= 1.0:
            return x ** 1.5
        return x ** 1.5 * (1.0 + ((x - 1.0) / c) ** p) ** (-q / p)

    fm = np.array([load(x) for x in xm])
    absorbed = np.array([0.4 * min(x, 1.0) ** 2.5 + (quad(load, 1.0, x, limit=200)[0] if x > 1 else 0.0)
                         for x in xm])
    safe = np.maximum(xm, 1.0)
    rho = np.where(xm > 1, rho_inf * (1.0 - safe ** (-s)) ** t, 0.0)
    n = np.where(xm > 1, n_inf + (1.5 - n_inf) * safe ** (-k), 1.5)
    recovered = fm * xm * (1.0 - rho) / (n + 1.0)
    return fm, np.sqrt(recovered / absorbed), rho


def fe_values(runs):
    return (runs["F_over_Fy"].to_numpy(), np.sqrt(runs["e2"].to_numpy()),
            runs["d0_over_dm"].to_numpy())


def residuals(coef, runs):
    fm, e, rho = law_values(coef, runs["x_m"].to_numpy())
    f_fe, e_fe, rho_fe = fe_values(runs)
    plastic = rho_fe > 0.02
    return np.concatenate([(fm / f_fe - 1.0) / 0.03, (e / e_fe - 1.0) / 0.03,
                           (rho[plastic] / rho_fe[plastic] - 1.0) / 0.10])


def fit(runs, start=None):
    x0 = np.array([epp.COEFFICIENTS[k] for k in ORDER] if start is None else start)
    lower = [0.05, 1.0, 0.0, 0.1, 0.01, 0.2, 0.5, 0.0]
    upper = [100.0, 6.0, 1.5, 1.0, 3.0, 5.0, 1.5, 2.0]
    x0 = np.clip(x0, np.array(lower) + 1e-9, np.array(upper) - 1e-9)
    sol = least_squares(residuals, x0, bounds=(lower, upper), args=(runs,), x_scale="jac")
    return sol.x


def errors(coef, runs):
    fm, e, rho = law_values(coef, runs["x_m"].to_numpy())
    f_fe, e_fe, rho_fe = fe_values(runs)
    out = runs[["x_m", "y_over_estar", "nu_flat", "stiffness_ratio"]].copy()
    out["force"], out["e"] = fm / f_fe - 1.0, e / e_fe - 1.0
    out["delta_r"] = np.where(rho_fe > 0.02, rho / np.where(rho_fe > 0, rho_fe, 1) - 1.0, 0.0)
    return out


def main():
    runs = pd.read_csv(HERE / "results" / "axisym_runs.csv")
    runs = runs[~runs["nlgeom"].astype(str).str.lower().eq("true")]
    coef = fit(runs)
    print({k: float(f"{v:.4g}") for k, v in zip(ORDER, coef)})
    err = errors(np.array([float(f"{v:.4g}") for v in coef]), runs)
    pd.set_option("display.width", 200)
    print(err.to_string(float_format=lambda v: f"{v:+.4f}"))
    for q in ("force", "e", "delta_r"):
        i = err[q].abs().idxmax()
        print(f"worst {q}: {err.loc[i, q]:+.4f} at", err.loc[i, ["x_m", "y_over_estar", "nu_flat",
                                                              "stiffness_ratio"]].to_dict())


if __name__ == "__main__":
    main()
