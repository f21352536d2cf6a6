"""First yield of a sphere pressed into a flat, and the Yigit–Christoforou impact number
every elastic-plastic law places its impacts by (docs/physics_contract.md §1–2;
docs/contact_laws.rst).
"""

from __future__ import annotations

import math

import numpy as np

from ..hertz import hertz_stiffness
from .yigit_christoforou import YigitChristoforouContact, yield_indentation

__all__ = ["first_yield_force", "first_yield_indentation", "reference_impact_number", "reference_yield_scales",
           "properties_for_yield_scales", "ReferenceYieldScales"]


def first_yield_indentation(effective_modulus, radius, yield_strength, pressure_factor):
    """``δ_y = R (π c_y Y / (2E*))²`` [m] from E* [Pa], R [m], Y [Pa] and ``c_y`` [-]."""
    return np.asarray(radius, float) * (
        np.pi * np.asarray(pressure_factor, float) * np.asarray(yield_strength, float)
        / (2.0 * np.asarray(effective_modulus, float))
    ) ** 2


def first_yield_force(effective_modulus, radius, yield_indentation):
    """``F_y = (4/3) E* R^{1/2} δ_y^{3/2}`` [N] from E* [Pa], R [m] and δ_y [m]."""
    return (4.0 / 3.0 * np.asarray(effective_modulus, float) * np.sqrt(np.asarray(radius, float))
            * yield_indentation**1.5)


def reference_impact_number(effective_modulus, radius, yield_strength, impactor_mass, velocity):
    """β [-] of the Yigit–Christoforou law with these E* [Pa], R [m] and Y [Pa] for an
    impactor of mass m_i [kg] at V0 [m/s]: ``β = V0/(ω α_y)``,
    ``ω = sqrt(K_h α_y^{1/2}/m_i)`` (seed 001 eqs 9, 11, 12)."""
    reference = YigitChristoforouContact.from_properties(effective_modulus, radius, yield_strength)
    return reference.impact_number(impactor_mass, velocity)


def reference_yield_scales(effective_modulus, radius, yield_strength) -> tuple:
    """``(K_h, α_y)`` [N/m^1.5, m] of the Yigit–Christoforou law with these E* [Pa], R [m]
    and Y [Pa] (seed 001 eqs 7, 9): the yield scales of a law given by E*, R, Y."""
    return hertz_stiffness(effective_modulus, radius), yield_indentation(yield_strength, radius, effective_modulus)


def properties_for_yield_scales(hertz: float, alpha_y: float) -> tuple[float, float, float]:
    """``(E*, R, Y)`` [Pa, m, Pa] with R = 1 m whose :func:`reference_yield_scales` are K_h [N/m^1.5] and α_y [m]."""
    radius = 1.0
    modulus = 0.75 * hertz / math.sqrt(radius)
    strength = modulus * math.sqrt(alpha_y / (0.68 * math.pi**2 * radius))
    return modulus, radius, strength


class ReferenceYieldScales:
    """What a law set by (E*, R, Y) says of its yield scales: a mixin of the laws whose
    ``effective_modulus`` [Pa], ``radius`` [m] and ``yield_strength`` [Pa] are their
    properties (``stronge``, ``epp``)."""

    @property
    def yield_scales(self):
        """``(K_h, α_y)`` [N/m^1.5, m] of the Yigit–Christoforou law with the same E*, R, Y
        (:func:`reference_yield_scales`)."""
        return reference_yield_scales(self.effective_modulus, self.radius, self.yield_strength)

    @classmethod
    def from_yield_scales(cls, hertz_stiffness, yield_indentation):
        """The law at its default options whose :attr:`yield_scales` are K_h [N/m^1.5] and α_y [m]
        (R = 1 m: :func:`properties_for_yield_scales`)."""
        return cls(*properties_for_yield_scales(hertz_stiffness, yield_indentation))
