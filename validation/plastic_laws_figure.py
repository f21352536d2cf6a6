"""Figure: restitution, peak force and dent of a half-space impact against V/V_y, for
the axisymmetric FE (quasi-static), Thornton's 1997 model, and the registered plastic
laws (Yigit–Christoforou, Stronge, epp).

Scales (docs/physics_contract.md §2, c_y = 1.6): δ_y = R (π c_y Y/(2E*))², F_y = (4/3) E* R^{1/2}
δ_y^{3/2}, and V_y with ½ m V_y² = (2/5) F_y δ_y (the Hertz impact that just reaches
δ_y).  The laws are run through :func:`impactmaps.closed_forms.halfspace.halfspace_impact`
for the issue's example (a 12.7 mm steel ball on an aluminium half-space, Y = 275 MPa).
FE points: ``validation/fe/results/axisym_runs.csv`` (rigid sphere, ν = 0.3, every
Y/E*; the reference runs of the calibration: small strain up to δ_m = 0.012 R, NLGEOM
up to 0.05 R): a run to δ_m is the quasi-static impact whose kinetic energy equals the work
absorbed, V/V_y = sqrt(W_abs/((2/5) F_y δ_y)), with e² = W_rec/W_abs.
Thornton (1997), as docs/physics_contract.md §2 defines it: Hertz to δ_y, then
F = F_y + π p_y R (δ − δ_y) with p_y = c_y Y, unloading Hertzian with
R_p = (4/3) E* a_m³/F_m, a_m² = R δ_m; its energies have closed forms (below).

Run: ``python validation/plastic_laws_figure.py`` → ``figures/plastic_laws.png``
(``--smoke``: 4 speeds, into a temporary directory).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
from impactmaps.contact import ContactPair, contact_law_class, effective_modulus  # noqa: E402
from impactmaps.contact.plastic.first_yield import first_yield_force, first_yield_indentation  # noqa: E402
from impactmaps.closed_forms.halfspace import halfspace_impact  # noqa: E402

sys.path.insert(0, str(ROOT / "validation"))
from _script_options import parse  # noqa: E402

C_Y = 1.6
RADIUS = 6.35e-3
E_STAR = float(effective_modulus(200e9, 0.3, 70e9, 0.33))
YIELD = 275e6
MASS = 7800 * 4 / 3 * np.pi * RADIUS ** 3
LAWS = ("yigit-christoforou", "stronge", "epp")
STYLE = {"yigit-christoforou": ("tab:blue", "--"), "stronge": ("tab:orange", "-."),
         "epp": ("tab:green", "-"), "thornton": ("tab:gray", ":")}


def scales():
    delta_y = float(first_yield_indentation(E_STAR, RADIUS, YIELD, C_Y))
    force_y = float(first_yield_force(E_STAR, RADIUS, delta_y))
    v_y = np.sqrt(0.8 * force_y * delta_y / MASS)
    return delta_y, force_y, v_y


def thornton(ratio):
    """(e, F_m/F_y, δ_r/δ_y) of Thornton's model at V/V_y = ``ratio`` (closed forms in
    units δ_y, F_y: loading work 2/5 + (x − 1) + (3/4)(x − 1)², since π p_y R δ_y/F_y = 3/2
    for p_y = c_y Y; unloading Hertzian about δ_r with δ_m − δ_r = (3/4) F_m/(E* a_m))."""
    work = 0.4 * ratio ** 2
    excess = np.clip(work - 0.4, 0, None)
    x = np.where(excess > 0, 1 + 2 * excess / (1 + np.sqrt(1 + 3 * excess)), ratio ** 0.8)
    force = np.where(x > 1, 1 + 1.5 * (x - 1), x ** 1.5)
    recovery = np.where(x > 1, force / np.sqrt(x), x)      # (3F_m/(4E* a_m))/δ_y
    recovered = 0.4 * force * recovery
    return np.sqrt(recovered / work), force, x - recovery


def law_curves(ratios):
    delta_y, force_y, v_y = scales()
    pair = ContactPair(E_STAR, RADIUS, YIELD)
    out = {}
    for name in LAWS:
        law = contact_law_class(name).from_contact_pair(pair)
        rows = []
        for r in ratios:
            res = halfspace_impact(law, MASS, r * v_y)
            rows.append((res.restitution, res.peak_force / force_y,
                         res.permanent_indentation / delta_y))
        out[name] = np.array(rows)
    return out


def fe_points():
    runs = pd.read_csv(ROOT / "validation" / "fe" / "results" / "axisym_runs.csv")
    nlgeom = runs["nlgeom"].astype(str) == "True"
    depth = runs["delta_m_over_R"]
    reference = (nlgeom & (depth <= 0.05)) | (~nlgeom & (depth <= 0.012 * (1 + 1e-6)))
    runs = runs[(runs["stiffness_ratio"] >= 100) & (runs["nu_flat"] == 0.3) & reference]
    return (np.sqrt(runs["absorbed_over_FyDy"] / 0.4), np.sqrt(runs["e2"]), runs["F_over_Fy"],
            runs["dent_over_dm"] * runs["x_m"])


def main(argv=None):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    args = parse(__doc__.splitlines()[0], argv, default_out=ROOT / "figures")
    out = args.out_dir / "plastic_laws.png"
    ratios = np.geomspace(1.05, 3000, 4 if args.smoke else 40)
    curves = law_curves(ratios)
    curves["thornton"] = np.column_stack(thornton(ratios))
    v, e, f, dent = fe_points()
    fig, axes = plt.subplots(1, 3, figsize=(13, 4.2))
    for name, values in curves.items():
        colour, dash = STYLE[name]
        for k, ax in enumerate(axes):
            ax.plot(ratios, values[:, k], color=colour, linestyle=dash,
                    label="Thornton 1997" if name == "thornton" else name)
    for ax, pts in zip(axes, (e, f, dent)):
        ax.plot(v, pts, "ko", ms=4, mfc="none", label="CalculiX axisymmetric (quasi-static)")
        ax.set_xscale("log")
        ax.set_xlabel("V / V_y")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("restitution e")
    axes[1].set_ylabel("peak force / F_y")
    axes[1].set_yscale("log")
    axes[2].set_ylabel("permanent indentation / δ_y")
    axes[2].set_yscale("log")
    axes[2].set_ylim(1e-2, None)
    axes[0].legend(fontsize=8)
    fig.suptitle("Rigid sphere on an elastic–perfectly plastic half-space: laws vs FE")
    fig.tight_layout()
    fig.savefig(out, dpi=130)
    print(out)


if __name__ == "__main__":
    main()
