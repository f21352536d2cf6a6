"""Reproduce Figure 1 of seed 001 (Christoforou & Yigit 1998): restitution e versus β.

A rigid sphere strikes a fixed half-space through the Yigit–Christoforou elastic-plastic
contact law (seed 001 eqs 4–10). In units a = α/α_y the law has no parameters, so the
coefficient of restitution depends only on the normalised impact velocity

    β = V0 / (ω α_y),   ω² = K_h α_y^{1/2} / m_i        (seed 001 eqs 11–12).

The curve is the closed-form energy balance (``impactmaps.closed_forms.halfspace.restitution``):
e = 1 for β ≤ sqrt(4/5); above, ½β² = 2/5 + (a_m − 1) + ¾(a_m − 1)² fixes a_m and e² is
the work recovered on the unloading branch over ½β². The markers are time integrations
(``halfspace_impact``) for two physically different impacts — a 12.7 mm steel ball on
aluminium and a 50 mm steel ball on a soft steel — which must fall on the same curve.

Run ``python validation/figure1_restitution.py [--out-dir DIR]``; writes
``figures/figure1_restitution.png`` and prints the largest difference between the
integrations and the closed form. ``--smoke``: 3 integrated impacts per series (seconds).
"""

from __future__ import annotations

from pathlib import Path
from types import SimpleNamespace

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from impactmaps.contact import Sphere, law_for_sphere  # noqa: E402
from impactmaps.closed_forms.halfspace import halfspace_impact, restitution  # noqa: E402

from _script_options import parse  # noqa: E402

FIGURES = Path(__file__).resolve().parents[1] / "figures"
FIGURE_NAME = "figure1_restitution.png"

# Nominal handbook-style properties, only to make two different impacts (β is all that matters).
STEEL_BALL = SimpleNamespace(youngs_modulus=210e9, poisson_ratio=0.30, density=7850.0, yield_strength=1.5e9)
ALUMINIUM = SimpleNamespace(youngs_modulus=70e9, poisson_ratio=0.33, density=2700.0, yield_strength=2.8e8)
MILD_STEEL = SimpleNamespace(youngs_modulus=200e9, poisson_ratio=0.29, density=7850.0, yield_strength=2.5e8)

IMPACTS = (
    ("12.7 mm steel ball on aluminium", Sphere(0.00635, STEEL_BALL), ALUMINIUM, "o"),
    ("50 mm steel ball on mild steel", Sphere(0.025, STEEL_BALL), MILD_STEEL, "s"),
)


def numerical_restitution(sphere, target_material, beta):
    """Restitution from time integration at the impact numbers ``beta`` [-]."""
    law = law_for_sphere("yigit-christoforou", sphere, target_material)
    values = []
    for b in np.atleast_1d(beta):
        velocity = float(law.velocity_for_impact_number(sphere.mass, b))
        values.append(halfspace_impact(law, sphere.mass, velocity).restitution)
    return np.array(values)


def plot_restitution(ax=None, *, points: int = 14):
    """Plot e(β): closed form (line) and time integrations (markers). Returns the Axes.

    Parameters
    ----------
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; a new figure is created when missing.
    points : int
        Number of integrated impacts per marker series.
    """
    if ax is None:
        _figure, ax = plt.subplots(figsize=(6.0, 4.2), constrained_layout=True)
    beta = np.geomspace(0.1, 1000.0, 600)
    ax.semilogx(beta, restitution(beta), color="k", lw=1.4, label="closed form (energy balance)")
    for shift, (label, sphere, target, marker) in enumerate(IMPACTS):
        sample = np.geomspace(0.1, 1000.0, points) * 10 ** (0.06 * shift)
        sample = sample[sample <= 1000.0]
        ax.semilogx(sample, numerical_restitution(sphere, target, sample), marker, mfc="none", ms=6,
                    label=f"time integration: {label}")
    ax.axvline(np.sqrt(0.8), color="0.6", ls=":", lw=1.0)
    ax.annotate(r"yield onset $\beta=\sqrt{4/5}$", (np.sqrt(0.8), 0.05), xytext=(4, 0),
                textcoords="offset points", fontsize=8, color="0.4")
    ax.set_xlim(0.1, 1000.0)
    ax.set_ylim(0.0, 1.05)
    ax.set_xlabel(r"normalised impact velocity $\beta = V_0/(\omega\,\alpha_y)$")
    ax.set_ylabel("coefficient of restitution $e$")
    ax.set_title("Rigid sphere on a half-space, Yigit–Christoforou law (seed 001 Fig. 1)", fontsize=9)
    ax.grid(True, which="both", lw=0.3, alpha=0.5)
    ax.legend(fontsize=8, loc="upper right")
    return ax


def main(argv=None):
    args = parse(__doc__.splitlines()[0], argv, default_out=FIGURES)
    points = 3 if args.smoke else 25
    worst = 0.0
    for _label, sphere, target, _marker in IMPACTS:
        beta = np.geomspace(0.1, 1000.0, points)
        worst = max(worst, float(np.max(np.abs(numerical_restitution(sphere, target, beta) - restitution(beta)))))
    print(f"largest |e_integrated − e_closed_form| over β ∈ [0.1, 1000]: {worst:.2e}")
    ax = plot_restitution(points=3 if args.smoke else 14)
    output = args.out_dir / FIGURE_NAME
    ax.figure.savefig(output, dpi=150)
    plt.close(ax.figure)
    print(f"wrote {output}")


if __name__ == "__main__":
    main()
