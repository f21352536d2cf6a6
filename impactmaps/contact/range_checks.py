"""The contact law's own range checks: the indentation against the sphere radius and a
law's calibrated range (the warnings :func:`impactmaps.closed_forms.halfspace.halfspace_impact`
and :func:`impactmaps.validity.validity_warnings` both give)."""

from __future__ import annotations

import numpy as np

__all__ = ["INDENTATION_RATIO_LIMIT", "law_warnings"]

INDENTATION_RATIO_LIMIT = 0.1  # α_max / R


def law_warnings(law, result, radius=None) -> list[str]:
    """The checks of :func:`impactmaps.validity.validity_warnings` that need only the contact law and the run:
    the indentation against the sphere radius and the ``epp`` law's calibrated range.

    Parameters
    ----------
    law : ContactLaw
        The law the run used.
    result : ImpactResult
        The run (its ``max_indentation`` [m]).
    radius : float, optional
        Sphere radius R [m]; default the law's own (its ``contact_radius_scale``; the
        indentation check is skipped for a law without one).

    Returns
    -------
    list of str
        Empty when no check fails.
    """
    radius = law.contact_radius_scale if radius is None else radius
    note = getattr(law, "calibration_note", None)
    checks = (None if radius is None or np.ndim(radius) else _indentation(float(radius), result),
              note(result.max_indentation) if note is not None and np.ndim(law.yield_strength) == 0 else None)
    return [message for message in checks if message]


def _indentation(radius, result):
    ratio = float(result.max_indentation) / radius
    if not ratio > INDENTATION_RATIO_LIMIT:
        return None
    return (f"indentation: the largest indentation {float(result.max_indentation):.4g} m is "
            f"{ratio:.3g} sphere radii (limit {INDENTATION_RATIO_LIMIT}): Hertz-type contact "
            "laws assume a contact radius small against the sphere radius")
