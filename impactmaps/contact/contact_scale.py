"""The contact stiffness that sets a run's contact frequency ω = sqrt(K_ref/m).

It depends on the contact law alone (and the impact energy), so every solver, the
any-law asymptotes and the case summaries read it from here, below all of them.
"""

from __future__ import annotations

from .base import ContactLaw

__all__ = ["reference_contact_stiffness"]


def reference_contact_stiffness(law: ContactLaw, impactor_mass: float, velocity: float) -> float:
    """Contact stiffness [N/m] that sets the contact frequency of a run.

    For a linear law its stiffness; otherwise the tangent stiffness on the loading
    curve at the half-space peak indentation (where ``loading_energy = ½ m V0²``),
    the stiffest the contact gets in a rigid-target impact.

    Parameters
    ----------
    law : ContactLaw
        The contact law.
    impactor_mass : float
        Impactor mass m [kg].
    velocity : float
        Impact velocity V0 [m/s].

    Returns
    -------
    float
        K_ref [N/m].

    Raises
    ------
    ValueError
        When the law has no stiffness at the half-space peak indentation.
    """
    linear = law.linear_stiffness or 0.0
    if linear > 0.0:
        return linear
    alpha_peak = float(law.indentation_for_energy(0.5 * impactor_mass * velocity**2))
    stiffness = float(law.tangent_stiffness(alpha_peak, alpha_peak))
    if not stiffness > 0:
        raise ValueError("contact law has zero stiffness at the half-space peak indentation")
    return stiffness
