"""Infinite-beam and infinite-plate asymptotes of seed 001 (eqs 32–38, spec 3.5).

The infinite beam obeys the fractional oscillator

    ᾱ'' + 2ζ ∫0^τ ᾱ'(s)/sqrt(τ − s) ds + ᾱ = 0,   ᾱ(0) = 0, ᾱ'(0) = 1,

(Laplace transform 1/(s² + 2 sqrt(π) ζ s^{1/2} + 1)), the infinite plate the damped
oscillator ᾱ'' + 2ζᾱ' + ᾱ = 0. This script

1. evaluates ᾱ(τ) of the beam for several ζ by the three independent methods of
   :mod:`impactmaps.closed_forms.infinite_beam` (Faddeeva closed form, fixed-Talbot inversion,
   BDF2 convolution quadrature) and prints their largest differences;
2. plots the peak force F̄max(ζ) of both infinite structures, with the half-space (1);
3. shows the unilateral force history on the infinite beam below and inside the
   re-impact band ζ_r < ζ < ζ_crit;
4. prints the peaks at ζ = 0.1, 0.3, 1, 3, ζ_crit and ζ_r.

Run: ``python validation/infinite_beam_asymptote.py [--out-dir DIR]`` →
``figures/infinite_beam_asymptote.png``. ``--smoke``: two loss factors, short records.
"""

from __future__ import annotations

import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from impactmaps.closed_forms import asymptotes as asy  # noqa: E402

from _script_options import parse  # noqa: E402

FIGURES = pathlib.Path(__file__).resolve().parents[1] / "figures"
FIGURE_NAME = "infinite_beam_asymptote.png"
LOSS_FACTORS = (0.1, 0.3, 1.0, 3.0)
CQ_STEP = 0.02


def plot_beam_methods(loss_factors=LOSS_FACTORS, tau_end=8.0, ax=None):
    """ᾱ(τ) of the infinite beam by the three methods; returns the Axes and the largest
    |closed form − Talbot| and |closed form − CQ| differences."""
    ax = ax or plt.figure().add_subplot()
    tau = np.linspace(0, tau_end, 801)
    markers = tau[::25]
    worst_talbot = worst_cq = 0.0
    for zeta, colour in zip(loss_factors, plt.cm.viridis(np.linspace(0, 0.85, len(loss_factors)))):
        closed = asy.infinite_beam_indentation(tau, zeta)
        talbot = asy.infinite_beam_indentation(markers, zeta, method="talbot")
        cq = asy.infinite_beam_indentation(tau, zeta, method="cq", time_step=CQ_STEP)
        worst_talbot = max(worst_talbot, np.max(np.abs(talbot - closed[::25])))
        worst_cq = max(worst_cq, np.max(np.abs(cq - closed)))
        ax.plot(tau, closed, color=colour, label=f"ζ = {zeta:g}")
        ax.plot(tau, cq, color=colour, ls="--", lw=2.5, alpha=0.5)
        ax.plot(markers, talbot, "o", color=colour, ms=4, mfc="none")
    ax.plot([], [], "k-", label="closed form (Faddeeva)")
    ax.plot([], [], "ko", mfc="none", label="fixed Talbot")
    ax.plot([], [], "k--", lw=2.5, alpha=0.5, label=f"BDF2 CQ, Δτ = {CQ_STEP:g}")
    ax.axhline(0, color="0.6", lw=0.8)
    ax.set_xlabel("τ = ωt")
    ax.set_ylabel("ᾱ (linear solution) = F̄ while in contact")
    ax.set_title("Infinite beam, eq (36): three methods")
    ax.legend(fontsize=7, ncol=2)
    return ax, worst_talbot, worst_cq


def plot_peak_force(ax=None):
    """F̄max(ζ) of the infinite beam and infinite plate (log ζ axis); returns the Axes."""
    ax = ax or plt.figure().add_subplot()
    zeta = np.geomspace(1e-2, 1e2, 161)
    ax.semilogx(zeta, asy.infinite_plate_peak(zeta), "-", color="C0", label="infinite plate (32)")
    ax.semilogx(zeta, asy.infinite_beam_peak(zeta), "--", color="C3", label="infinite beam (36)")
    critical = asy.critical_beam_loss_factor()
    ax.plot(critical, asy.infinite_beam_peak(critical), "v", color="C3", label=f"beam ζ_crit = {critical:.6f}")
    ax.plot(1.0, asy.infinite_plate_peak(1.0), "v", color="C0", label="plate ζ = 1 (critical damping)")
    ax.axhline(asy.halfspace_peak(), color="0.6", lw=0.8, label="half-space")
    ax.set_xlabel("loss factor ζ")
    ax.set_ylabel("F̄max = Fmax/(m_i V0 ω)")
    ax.set_ylim(0, 1.05)
    ax.set_title("Peak force, infinite structures")
    ax.legend(fontsize=7)
    return ax


def plot_recontact(loss_factors=(0.2, 0.5, 0.8), tau_end=30.0, ax=None):
    """Unilateral force history on the infinite beam, showing re-impacts; returns the Axes."""
    ax = ax or plt.figure().add_subplot()
    tau = np.linspace(0, tau_end, 3001)
    for zeta in loss_factors:
        ax.plot(tau, asy.infinite_beam_force(tau, zeta, time_step=CQ_STEP), label=f"ζ = {zeta:g}")
    ax.set_ylim(0, 0.08)
    ax.set_xlabel("τ = ωt")
    ax.set_ylabel("F̄ (first peak clipped)")
    ax.set_title("Re-impact on an infinite beam (ζ_r < ζ < ζ_crit)")
    ax.legend(title=f"ζ_r = {asy.recontact_beam_loss_factor():.5f}", fontsize=7, title_fontsize=7)
    return ax


def main(argv=None):
    args = parse(__doc__.splitlines()[0], argv, default_out=FIGURES)
    loss_factors = LOSS_FACTORS[1:3] if args.smoke else LOSS_FACTORS
    fig, axes = plt.subplots(1, 3, figsize=(16, 4.8), constrained_layout=True)
    _, worst_talbot, worst_cq = plot_beam_methods(loss_factors, tau_end=2.0 if args.smoke else 8.0, ax=axes[0])
    plot_peak_force(ax=axes[1])
    if args.smoke:
        plot_recontact((0.5,), tau_end=5.0, ax=axes[2])
    else:
        plot_recontact(ax=axes[2])
    figure = args.out_dir / FIGURE_NAME
    fig.savefig(figure, dpi=130)
    plt.close(fig)
    print(f"max |closed form − Talbot| = {worst_talbot:.2e}")
    print(f"max |closed form − CQ(Δτ={CQ_STEP})| = {worst_cq:.2e}")
    print(f"{'ζ':>6} {'F̄max beam':>14} {'F̄max plate':>14} {'τ_c beam':>10} {'τ_c plate':>10}")
    zeta = np.array(loss_factors)
    rows = zip(
        zeta,
        asy.infinite_beam_peak(zeta),
        asy.infinite_plate_peak(zeta),
        asy.infinite_beam_contact_time(zeta),
        asy.infinite_plate_contact_time(zeta),
    )
    for row in rows:
        print("{:>6g} {:>14.10f} {:>14.10f} {:>10.5f} {:>10.5f}".format(*row))
    print(f"critical beam loss factor ζ_crit = {asy.critical_beam_loss_factor():.13f}")
    print(f"re-impact threshold          ζ_r = {asy.recontact_beam_loss_factor():.13f}")
    print(f"saved {figure}")


if __name__ == "__main__":
    main()
