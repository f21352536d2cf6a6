"""Charts of a parameter study (``impactmaps simulate CASE --vary KEY=…``): its scalars
against the varied key."""

from __future__ import annotations

import numpy as np

__all__ = ["STUDY_QUANTITIES", "plot_study"]

#: Study column → axis label (the quantities drawn by default first).
STUDY_QUANTITIES = {
    "peak_force_N": "peak contact force [N]",
    "restitution": "coefficient of restitution e",
    "first_contact_duration_s": "first contact duration [s]",
    "total_contact_time_s": "total contact time [s]",
    "impacts": "number of impacts",
    "max_indentation_m": "largest indentation [m]",
    "permanent_indentation_m": "permanent indentation [m]",
    "energy_loss_J": "energy lost by the impactor [J]",
    "energy_transferred_J": "energy left in the structure [J]",
    "contact_dissipation_J": "energy dissipated in the contact [J]",
    "max_deflection_m": "largest deflection at the impact point [m]",
    "fmax_normalised": "normalised peak force F̄max",
}


def plot_study(table, key: str, quantities=("peak_force_N", "restitution"), *, log_x=None, axes=None):
    """Quantities of a parameter study against its varied key, one panel each; runs with
    more than one impact (column ``impacts``) are ringed.

    Parameters
    ----------
    table : pandas.DataFrame
        The study's rows (``study.csv``): a column ``key`` and one per quantity.
    key : str
        The varied case-file key (``impactor.velocity``), the x axis.
    quantities : sequence of str
        Columns to draw, one panel each (labels: :data:`STUDY_QUANTITIES`).
    log_x : bool, optional
        Log x axis (default: positive values spanning more than a decade).
    axes : sequence of matplotlib Axes, optional
        One per quantity (default: a new figure with the panels stacked, x shared).

    Returns
    -------
    list of matplotlib.axes.Axes

    Raises
    ------
    ValueError
        If ``key`` or a quantity is not a column of ``table``, or a quantity has no number.
    """
    import matplotlib.pyplot as plt

    columns = list(table.columns)
    for name in (key, *quantities):
        if name not in columns:
            raise ValueError(f"quantity {name!r} is not a column of the study; its columns are {columns}")
    x = np.asarray(table[key], dtype=float)
    if log_x is None:
        positive = x[np.isfinite(x)]
        log_x = bool(positive.size) and bool(np.all(positive > 0)) and positive.max() / positive.min() > 10.0
    if axes is None:
        figure, axes = plt.subplots(len(quantities), 1, figsize=(6.5, 2.6 * len(quantities) + 0.6), sharex=True,
                                    squeeze=False)
        axes = list(axes[:, 0])
    else:
        axes = list(axes)
        if len(axes) != len(quantities):
            raise ValueError(f"axes has {len(axes)} panels for {len(quantities)} quantities")
    order = np.argsort(x)
    several = (np.asarray(table["impacts"].astype(float), dtype=float) > 1) if "impacts" in columns \
        else np.zeros(x.size, dtype=bool)
    for ax, name in zip(axes, quantities):
        y = np.asarray(table[name].astype(float), dtype=float)
        if not np.isfinite(y).any():
            raise ValueError(f"quantity {name!r} has no number in this study (every run gives none)")
        ax.plot(x[order], y[order], "o-", color="C0", lw=1.3, ms=4)
        finite = y[np.isfinite(y)]
        if log_x and finite.size and np.all(finite > 0) and finite.max() / finite.min() > 30.0:
            ax.set_yscale("log")  # a power law over decades: a straight line
        if several.any():
            ax.plot(x[several], y[several], "o", ms=8, mfc="white", mec="C3", mew=1.4, zorder=3,
                    label="more than one impact (the structure struck the ball again)")
            ax.legend(fontsize=7, loc="best")
        ax.set_ylabel(STUDY_QUANTITIES.get(name, name))
        ax.grid(True, which="both", alpha=0.3)
        if log_x:
            ax.set_xscale("log")
    axes[-1].set_xlabel(key + (" (log axis)" if log_x else ""))
    axes[0].set_title(f"study of {key}: {len(x)} runs")
    return axes
