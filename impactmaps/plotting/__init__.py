"""Matplotlib charts, each taking ``ax=None`` and returning the Axes: the (ζ, λ) maps
(:mod:`~impactmaps.plotting.map_charts`) and single impacts
(:mod:`~impactmaps.plotting.histories`).
"""

from __future__ import annotations

from .histories import (
    plot_force_history,
    plot_impact_history,
    plot_restitution,
    plot_scaling,
    save_impact_history,
)
from .studies import STUDY_QUANTITIES, plot_study
from .map_charts import (
    FMAX_LABELS,
    PLASTIC_PANELS,
    REGIME_COLOURS,
    NORMALISATION_NOTES,
    SENSITIVE_ALPHA,
    plot_fmax_chart,
    plot_plastic_chart,
    plot_regime_map,
    plot_regime_strip,
    structure_label,
)

__all__ = [
    "plot_fmax_chart",
    "plot_plastic_chart",
    "plot_regime_strip",
    "plot_regime_map",
    "plot_force_history",
    "plot_impact_history",
    "save_impact_history",
    "plot_scaling",
    "plot_restitution",
    "plot_study",
    "STUDY_QUANTITIES",
    "FMAX_LABELS",
    "PLASTIC_PANELS",
    "REGIME_COLOURS",
    "SENSITIVE_ALPHA",
    "NORMALISATION_NOTES",
    "structure_label",
]
