"""Seed 001 Figures 3–8: a plate and a beam with equal (λ, ζ) scale alike.

Simply supported square Kirchhoff plate and SS Euler beam struck at the centre, linear
contact, λ = 0.425 and ζ = 11.3 (fully global, Figs 3–4), 0.038 (local, Figs 5–6; the
paper does not state λ for this pair, 0.425 is assumed) and 1.198 (transition, Figs
7–8). Force and central deflection in normalised form, with the quasi-static solution
(eq 28) for reference. Writes figures/scaling_*.png and prints F̄max of each run.

    python validation/scaling_figures.py [--out-dir DIR]
    python validation/scaling_figures.py --smoke    # the "global" pair only, default step
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from impactmaps.plotting.chart import CHART_STRUCTURES
from impactmaps.plotting import plot_scaling
from impactmaps.closed_forms.asymptotes import quasi_static_force
from impactmaps.solvers.modal import ModalSettings, simulate_normalised

from _script_options import parse

FIGURES = Path(__file__).resolve().parents[1] / "figures"
CASES = (("global", 0.425, 11.3, (3, 4)), ("local", 0.425, 0.038, (5, 6)), ("transition", 0.425, 1.198, (7, 8)))


def main(argv=None) -> None:
    args = parse(__doc__.splitlines()[0], argv, default_out=FIGURES)
    beam_structure, plate_structure = CHART_STRUCTURES
    settings = ModalSettings() if args.smoke else ModalSettings(time_step_ratio=0.01, resolve_ratio=0.1)
    for label, lam, zeta, numbers in CASES[:1] if args.smoke else CASES:
        beam = simulate_normalised(beam_structure.build(), zeta, lam, settings=settings)
        plate = simulate_normalised(plate_structure.build(), zeta, lam, settings=settings)
        end = max(beam.normalised_history()["tau"].max(), plate.normalised_history()["tau"].max())
        tau = np.linspace(0, end, 2000)
        figure, axes = plt.subplots(1, 2, figsize=(12, 4.5))
        plot_scaling(plate, beam, quantity="force", ax=axes[0],
                     asymptote=(tau, quasi_static_force(tau, lam), "quasi-static (eq 28)"))
        axes[0].set_title(f"Fig. {numbers[0]}: force, {label} (λ = {lam}, ζ = {zeta})")
        plot_scaling(plate, beam, quantity="deflection", ax=axes[1])
        axes[1].set_title(f"Fig. {numbers[1]}: central deflection, {label}")
        figure.tight_layout()
        path = args.out_dir / f"scaling_{label}.png"
        figure.savefig(path, dpi=120)
        plt.close(figure)
        print(f"{label:10s} λ={lam} ζ={zeta}: F̄max plate {plate.fmax_normalised:.4f} ({plate.impacts} impacts), "
              f"beam {beam.fmax_normalised:.4f} ({beam.impacts} impacts) → {path.name}")


if __name__ == "__main__":
    main()
