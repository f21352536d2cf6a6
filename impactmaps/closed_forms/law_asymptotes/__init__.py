"""Asymptotes of sphere impact for any registered contact law.

Infinite plate (dashpot), infinite beam (convolution quadrature, re-impacts),
quasi-static spring and half-space, each an :class:`AsymptoteResult`; :func:`asymptote`
dispatches by name. Derivations: docs/physics.rst (Closed forms).
"""

from __future__ import annotations

from ..._checks import require_choice
from .beam import beam_mobility_constant, infinite_beam_impact_any_law
from .local import (
    halfspace_asymptote,
    infinite_plate_impact,
    plate_impedance,
    quasi_static_impact,
)
from .result import AsymptoteResult, contact_frequency_of

__all__ = [
    "ASYMPTOTES",
    "AsymptoteResult",
    "asymptote",
    "beam_mobility_constant",
    "contact_frequency_of",
    "halfspace_asymptote",
    "infinite_beam_impact_any_law",
    "infinite_plate_impact",
    "plate_impedance",
    "quasi_static_impact",
]

#: Asymptote names, and the target kind each needs (None: no target).
ASYMPTOTES = {"infinite-plate": "plate", "infinite-beam": "beam", "quasi-static": "any",
              "half-space": None}


def asymptote(kind: str, target, law, impactor_mass, velocity) -> AsymptoteResult:
    """Run the asymptote ``kind`` for a physical case.

    Parameters
    ----------
    kind : {"infinite-plate", "infinite-beam", "quasi-static", "half-space"}
        Which limit.
    target : Plate, Beam or None
        Plate for ``"infinite-plate"``, Beam for ``"infinite-beam"``, any target for
        ``"quasi-static"``; ignored for ``"half-space"``.
    law, impactor_mass, velocity
        One registered contact law, the impactor mass m [kg] and the speed V0 [m/s], both > 0.

    Returns
    -------
    AsymptoteResult
    """
    require_choice("kind", kind, ASYMPTOTES)
    needed = ASYMPTOTES[kind]
    if needed in ("plate", "beam") and getattr(target, "kind", None) != needed:
        raise ValueError(f"target = {type(target).__name__} is not valid for asymptote {kind!r}: "
                         f"valid targets are {needed}s")
    if kind == "infinite-plate":
        return infinite_plate_impact(target, law, impactor_mass, velocity)
    if kind == "infinite-beam":
        return infinite_beam_impact_any_law(target, law, impactor_mass, velocity)
    if kind == "quasi-static":
        return quasi_static_impact(target, law, impactor_mass, velocity)
    return halfspace_asymptote(law, impactor_mass, velocity)
