"""Convergence of the modal solver in the mode cut-off and the time step, and the
long-structure limit (SS Euler beam / SS square Kirchhoff plate → infinite structure).

Writes figures/convergence_modes_timestep.png, figures/long_structure_limit.png and
prints the tables quoted in docs/validation.rst.

    python validation/convergence_study.py [--out-dir DIR]
    python validation/convergence_study.py --smoke    # one case, short ladders (seconds)
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from impactmaps.plotting.chart import CHART_STRUCTURES
from impactmaps.maps.family.regimes import infinite_structure_peak
from impactmaps.solvers.modal import ModalSettings, simulate_normalised

from _script_options import parse

FIGURES = Path(__file__).resolve().parents[1] / "figures"
CASES = ((0.425, 0.038), (0.425, 1.198), (0.425, 11.3))
CUTOFFS = (5.0, 10.0, 20.0, 40.0, 80.0, 160.0)
STEPS = (0.1, 0.05, 0.025, 0.0125, 0.00625, 0.003125)
DEFAULT_STEP = 3  # STEPS[3] = ModalSettings().time_step_ratio
DEFAULT_CUTOFF = 3  # CUTOFFS[3] = ModalSettings().cutoff_ratio


def main(argv=None) -> None:
    args = parse(__doc__.splitlines()[0], argv, default_out=FIGURES)
    # smoke: one case, the cut-offs up to the default (40) and the steps down to 0.00625
    cases = CASES[1:2] if args.smoke else CASES
    cutoffs = CUTOFFS[:DEFAULT_CUTOFF + 1] if args.smoke else CUTOFFS
    steps = STEPS[:-1] if args.smoke else STEPS
    figure, axes = plt.subplots(1, 2, figsize=(12, 4.5))
    print("| structure | λ | ζ | F̄max (default) | max change, cut-off 40→160 | max change, ωΔt 0.0125→0.003125 |")
    print("|---|---|---|---|---|---|")
    for structure, style in zip(CHART_STRUCTURES, ("--", "-")):
        target = structure.build()
        for (lam, zeta), colour in zip(cases, ("C0", "C1", "C2")):
            by_cutoff = [simulate_normalised(target, zeta, lam, settings=ModalSettings(cutoff_ratio=c), record=False)
                         .fmax_normalised for c in cutoffs]
            # every step bound scaled together: ωΔt = s, ω_topΔt = 20 s, force content ∝ s²
            by_step = [simulate_normalised(target, zeta, lam, settings=ModalSettings(
                time_step_ratio=s, resolve_ratio=20 * s, force_resolution=1e-5 * (s / 0.0125) ** 2),
                record=False).fmax_normalised for s in steps]
            label = f"{structure.kind}, ζ = {zeta}"
            axes[0].semilogx(cutoffs, by_cutoff, style, marker="o", color=colour, label=label)
            reference = by_step[-1]
            axes[1].loglog(steps[:-1], np.abs(np.array(by_step[:-1]) - reference) + 1e-16, style, marker="o",
                           color=colour, label=label)
            default = by_cutoff[DEFAULT_CUTOFF]
            print(f"| {structure.name} | {lam} | {zeta} | {default:.4f} | "
                  f"{max(abs(v - default) for v in by_cutoff[DEFAULT_CUTOFF:]):.1e} | "
                  f"{max(abs(v - by_step[DEFAULT_STEP]) for v in by_step[DEFAULT_STEP:]):.1e} |")
    axes[0].set_xlabel("cut-off Ω_max = ω_max/ω")
    axes[0].set_ylabel("F̄max")
    axes[0].set_title("Convergence in modes (residual flexibility on)")
    axes[1].loglog(steps[:-1], 0.5 * np.array(steps[:-1]) ** 2, "k:", label="∝ Δt²")
    axes[1].set_xlabel("ωΔt")
    axes[1].set_ylabel("|F̄max − F̄max(ωΔt = 0.003125)|")
    axes[1].set_title("Convergence in the time step")
    for ax in axes:
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    figure.tight_layout()
    figure.savefig(args.out_dir / "convergence_modes_timestep.png", dpi=120)
    plt.close(figure)

    zetas = np.geomspace(0.01, 1.0, 2 if args.smoke else 9)
    figure, ax = plt.subplots(figsize=(7, 4.5))
    print("\n| structure | λ | max relative difference to infinite structure, ζ ∈ [0.01, 1] |")
    print("|---|---|---|")
    for structure, lam, style in ((CHART_STRUCTURES[0], 1e-3, "--"), (CHART_STRUCTURES[1], 1e-2, "-")):
        target = structure.build()
        values = np.array([simulate_normalised(target, z, lam, record=False).fmax_normalised for z in zetas])
        exact = infinite_structure_peak(zetas, structure.kind)
        ax.semilogx(zetas, values, "o", mfc="none", color="C3" if structure.kind == "beam" else "C0",
                    label=f"{structure.name}, λ = {lam:g} (modal)")
        dense = np.geomspace(0.01, 1.0, 200)
        ax.semilogx(dense, infinite_structure_peak(dense, structure.kind), style, color="k",
                    label=f"infinite {structure.kind} (closed form)")
        print(f"| {structure.name} | {lam:g} | {np.max(np.abs(values / exact - 1)):.1e} |")
    ax.set_xlabel("loss factor ζ")
    ax.set_ylabel("F̄max")
    ax.set_title("Long structures reproduce the infinite-structure asymptotes")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    figure.tight_layout()
    figure.savefig(args.out_dir / "long_structure_limit.png", dpi=120)
    plt.close(figure)


if __name__ == "__main__":
    main()
