"""The Axes a plotting function draws on."""

from __future__ import annotations

__all__ = ["axes_or_new"]


def axes_or_new(ax):
    """``ax``, or the Axes of a new 8 × 5.5 in figure when ``ax`` is ``None``."""
    if ax is None:
        import matplotlib.pyplot as plt

        _, ax = plt.subplots(figsize=(8, 5.5))
    return ax
