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
from impactmaps.contact import epp

ORDER = epp._ORDER


def law_values(coef, xm, nu):
    """(F_m/F_y, e, δ_r/δ_m) of the law with coefficients ``coef`` at x_m and the flat's
    Poisson ratio (arrays); F_y, δ_y those of c_y = 1.6."""
    co = dict(zip(ORDER, coef))
    fm, e, rho = [], [], []
    kappa = epp.yield_shift(np.asarray(nu), co["a_nu"])
    for x0, kap in zip(xm, kappa):
        x = x0 / kap
        def load(v):
            return epp._epp_loading(v, co["q"], co["c"], co["r"])[0]
        absorbed = quad(load, 0.0, min(x, 1.0))[0] + (quad(load, 1.0, x, limit=200)[0] if x > 1 else 0.0)
        f = load(x)
        r, n = (epp._epp_unloading_shape(x, co["b"], co["w"], co["v"], co["n_inf"], co["k"])
                if x > 1 else (0.0, 1.5))
        fm.append(f * kap ** 1.5)
        rho.append(r)
        e.append(np.sqrt(f * x * (1.0 - r) / (n + 1.0) / absorbed))
    return np.array(fm), np.array(e), np.array(rho)


#: Small-strain runs are kept up to this δ_m/R; deeper ones are taken with NLGEOM
#: (axisym_indent.SMALL_STRAIN_DEPTH).
SMALL_STRAIN_DEPTH = 0.012


def calibration_runs(runs):
    """The reference: small-strain runs with δ_m ≤ 0.012 R and the NLGEOM runs."""
    nl = runs["nlgeom"].astype(str).str.lower().eq("true")
    keep = nl | (runs["delta_m_over_R"] <= SMALL_STRAIN_DEPTH * (1 + 1e-6))
    return runs[keep].reset_index(drop=True)


def fe_values(runs):
    return (runs["F_over_Fy"].to_numpy(), np.sqrt(runs["e2"].to_numpy()),
            runs["d0_over_dm"].to_numpy())


def residuals(coef, runs):
    fm, e, rho = law_values(coef, runs["x_m"].to_numpy(), runs["nu_flat"].to_numpy())
    f_fe, e_fe, rho_fe = fe_values(runs)
    plastic = rho_fe > 0.02
    return np.concatenate([(fm / f_fe - 1.0) / 0.03, (e / e_fe - 1.0) / 0.03,
                           (rho[plastic] / rho_fe[plastic] - 1.0) / 0.10])


def fit(runs, start=None):
    x0 = np.array([epp.COEFFICIENTS[k] for k in ORDER] if start is None else start)
    lower = [0.0, 0.1, 0.0, 1e-3, 0.2, 0.05, 0.5, 0.0, -3.0]
    upper = [1.4, 50.0, 0.02, 100.0, 5.0, 1.0, 1.5, 2.0, 3.0]
    x0 = np.clip(x0, np.array(lower) + 1e-9, np.array(upper) - 1e-9)
    sol = least_squares(residuals, x0, bounds=(lower, upper), args=(runs,), x_scale="jac")
    return sol.x


def errors(coef, runs):
    fm, e, rho = law_values(coef, runs["x_m"].to_numpy(), runs["nu_flat"].to_numpy())
    f_fe, e_fe, rho_fe = fe_values(runs)
    out = runs[["x_m", "y_over_estar", "nu_flat", "stiffness_ratio"]].copy()
    out["force"], out["e"] = fm / f_fe - 1.0, e / e_fe - 1.0
    out["delta_r"] = np.where(rho_fe > 0.02, rho / np.where(rho_fe > 0, rho_fe, 1) - 1.0, 0.0)
    return out


def main():
    runs = calibration_runs(pd.read_csv(HERE / "results" / "axisym_runs.csv"))
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
