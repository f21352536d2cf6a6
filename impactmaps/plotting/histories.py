"""Plots of single impacts: force and deflection histories, scaling, restitution (each
takes ``ax=None`` and returns the Axes it drew on).
"""

from __future__ import annotations

import numpy as np

from .._files import written_atomically
from .axes import axes_or_new

__all__ = ["plot_force_history", "plot_impact_history", "save_impact_history", "plot_scaling",
           "plot_restitution"]


def plot_force_history(results, *, labels=None, normalised=True, quantity="force", ax=None, styles=None):
    """Contact force (or target deflection) histories of one or more results.

    Parameters
    ----------
    results : ImpactResult or sequence of them
    labels : sequence of str, optional
    normalised : bool
        Plot F̄ against τ (else N against ms).
    quantity : {"force", "deflection"}
        ``deflection``: the target displacement at the impact point.
    ax : matplotlib Axes, optional
    styles : sequence of dict, optional
        Matplotlib keyword arguments per result.
    """
    ax = axes_or_new(ax)
    if not isinstance(results, (list, tuple)):
        results = [results]
    labels = labels or [None] * len(results)
    styles = styles or [{}] * len(results)
    for result, label, style in zip(results, labels, styles):
        if normalised:
            history = result.normalised_history()
            x = history["tau"]
            y = history["force_normalised"] if quantity == "force" else history["target_displacement_normalised"]
        else:
            history = result.history
            x = history["time_s"] * 1e3
            y = history["force_N"] if quantity == "force" else history["target_displacement_m"] * 1e3
        ax.plot(x, y, label=label, **style)
    if normalised:
        ax.set_xlabel("normalised time τ = ωt")
        ax.set_ylabel("F̄ = F/(m_i V0 ω)" if quantity == "force" else "w̄ = w/α*")
    else:
        ax.set_xlabel("time [ms]")
        ax.set_ylabel("contact force [N]" if quantity == "force" else "deflection [mm]")
    ax.grid(True, alpha=0.3)
    if any(labels):
        ax.legend(fontsize=8)
    return ax


def plot_impact_history(result, *, normalised=False, figure=None):
    """Force, indentation and target deflection of one recorded run against time, in three
    stacked panels, contacts shaded and the peak marked; returns the Figure.

    Parameters
    ----------
    result : ImpactResult
        A result with its history (``record=True``).
    normalised : bool
        Plot τ = ωt, F̄ = F/(m_i V0 ω), α/α*, w/α* (else ms, N, µm, µm).
    figure : matplotlib Figure, optional
        Figure to draw into (default: a new one).
    """
    import matplotlib.pyplot as plt

    if result.history is None:
        raise ValueError("result has no history: run the solver with record=True")
    if figure is None:
        figure = plt.figure(figsize=(7.5, 7.5))
    axes = figure.subplots(3, 1, sharex=True)
    if normalised:
        history = result.normalised_history()
        time, scale = history["tau"], result.contact_frequency
        columns = ("force_normalised", "indentation_normalised", "target_displacement_normalised")
        factors, labels = (1.0, 1.0, 1.0), ("F̄ = F/(m$_i$ V$_0$ ω)", "indentation α/α* (< 0: gap)", "deflection w/α*")
        xlabel = "normalised time τ = ωt"
    else:
        history = result.history
        time, scale = history["time_s"] * 1e3, 1e3
        columns = ("force_N", "indentation_m", "target_displacement_m")
        factors, labels = (1.0, 1e6, 1e6), ("contact force [N]", "indentation [µm] (< 0: gap)", "deflection at impact [µm]")
        xlabel = "time [ms]"
    for ax, column, factor, label in zip(axes, columns, factors, labels):
        ax.plot(time, history[column] * factor, color="C0", lw=1.3)
        for start, end in np.asarray(result.contact_intervals, dtype=float).reshape(-1, 2):
            end = end if np.isfinite(end) else float(np.max(time)) / scale
            ax.axvspan(start * scale, end * scale, color="#f6e3c7", alpha=0.7, lw=0, zorder=0)
        ax.axhline(0.0, color="0.6", lw=0.6)
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
    peak = result.peak_force / result.force_scale if normalised else result.peak_force
    axes[0].plot([result.peak_time * scale], [peak], "o", color="C3", ms=5, zorder=4,
                 label=f"peak {peak:.4g}{'' if normalised else ' N'}")
    axes[0].plot([], [], color="#f6e3c7", lw=8, label=f"contact ({result.impacts} impact{'s' * (result.impacts != 1)})")
    # above the panel, never over the curves or the peak marker
    axes[0].legend(fontsize=8, loc="lower left", bbox_to_anchor=(0.0, 1.01), ncol=2, borderaxespad=0.0,
                   frameon=False)
    axes[-1].set_xlabel(xlabel)
    figure.tight_layout()
    return figure


def save_impact_history(result, path, *, normalised=False):
    """Draw :func:`plot_impact_history` into the image file ``path`` (format from its suffix); return the path."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure = plot_impact_history(result, normalised=normalised)
    try:
        with written_atomically(path) as part:
            figure.savefig(part, dpi=120)
    finally:
        plt.close(figure)
    return path


def plot_scaling(plate_result, beam_result, *, quantity="force", asymptote=None, ax=None):
    """Scaling figure (Christoforou & Yigit 1998 Figs 3–8): ``plate_result`` (solid) and
    ``beam_result`` (dashed) with equal (λ, ζ); ``quantity`` "force" or "deflection";
    ``asymptote`` an optional (tau, values, label) reference curve drawn dotted.
    """
    ax = plot_force_history([plate_result, beam_result], labels=["plate", "beam"], quantity=quantity,
                            styles=[{"color": "k", "ls": "-"}, {"color": "k", "ls": "--"}], ax=ax)
    if asymptote is not None:
        tau, values, label = asymptote
        ax.plot(tau, values, color="0.5", ls=":", label=label)
        ax.legend(fontsize=8)
    return ax


def plot_restitution(beta, restitution, *, points=None, ax=None):
    """Coefficient of restitution against the impact number β (Christoforou & Yigit 1998
    Figure 1): the closed-form curve (``beta``, ``restitution``) and optional numerical
    ``points`` (beta, restitution) as markers.
    """
    ax = axes_or_new(ax)
    ax.semilogx(beta, restitution, "k-", label="closed form")
    if points is not None:
        ax.semilogx(points[0], points[1], "o", mfc="none", color="C3", label="numerical")
    ax.set_xlabel("impact number β = V0/(ω α_y)")
    ax.set_ylabel("coefficient of restitution e")
    ax.set_ylim(0, 1.05)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    return ax
