"""Yigit–Christoforou elastic-plastic contact law (seed 001 eqs 4–10).

Hertz to the yield indentation α_y, linear (Hertz-tangent) loading beyond, Hertz-shaped
unloading about the permanent indentation. Equations: docs/contact_laws.rst.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numba
import numpy as np

from ..._checks import require_positive
from ...dimensionless import hertz_frequency, impact_number, velocity_for_impact_number
from ..base import ContactLaw, check_energy, register_contact_law
from ..hertz import hertz_stiffness

__all__ = ["YigitChristoforouContact", "yield_indentation"]

#: Coefficient of eq (9), ``α_y = 0.68 π² S_y² R / E*²`` (seed 001, quoted from its ref [5]).
YIELD_INDENTATION_COEFFICIENT = 0.68


def yield_indentation(yield_strength, radius, effective_modulus):
    """Indentation at first yield ``α_y = 0.68 π² S_y² R / E*²`` [m] (seed 001 eq 9).

    ``yield_strength`` S_y [Pa] of the softer material, ``radius`` R [m], ``effective_modulus`` E* [Pa].
    """
    require_positive("yield_strength", yield_strength, "Pa")
    require_positive("radius", radius, "m")
    require_positive("effective_modulus", effective_modulus, "Pa")
    strength = np.asarray(yield_strength, float)
    modulus = np.asarray(effective_modulus, float)
    return YIELD_INDENTATION_COEFFICIENT * np.pi**2 * strength**2 * np.asarray(radius, float) / modulus**2


@numba.njit(cache=True)
def _yigit_christoforou_kernel(alpha, alpha_max, params):
    if alpha <= 0.0:
        return 0.0, 0.0
    hertz = params[0]
    yield_alpha = params[1]
    root = math.sqrt(alpha)
    if alpha >= alpha_max:  # virgin loading, eqs (4)-(5)
        if alpha <= yield_alpha:
            return hertz * alpha * root, 1.5 * hertz * root
        linear = 1.5 * hertz * math.sqrt(yield_alpha)  # K_y, eq (10)
        return linear * (alpha - yield_alpha) + hertz * yield_alpha * math.sqrt(yield_alpha), linear
    if alpha_max <= yield_alpha:  # never yielded: elastic Hertz unloading
        return hertz * alpha * root, 1.5 * hertz * root
    # eq (6) written as K_h (α^{3/2} − α_f^{3/2})
    final15 = (
        alpha_max * math.sqrt(alpha_max)
        - 1.5 * math.sqrt(yield_alpha) * alpha_max
        + 0.5 * yield_alpha * math.sqrt(yield_alpha)
    )
    alpha15 = alpha * root
    if alpha15 <= final15:
        return 0.0, 0.0
    return hertz * (alpha15 - final15), 1.5 * hertz * root


@register_contact_law
@dataclass(frozen=True)
class YigitChristoforouContact(ContactLaw):
    """Elastic-plastic Hertz law with linear post-yield loading (seed 001 eqs 4–10).

    Parameters
    ----------
    hertz_stiffness : float or array_like
        Hertz stiffness K_h [N/m^1.5] (eq 7).
    yield_indentation : float or array_like
        Indentation at first yield α_y [m] (eq 9, :func:`yield_indentation`).
    effective_radius : float, optional
        R [m] of the pair, when known (contact radius ``sqrt(R α)``); not part of the law.
    """

    hertz_stiffness: float
    yield_indentation: float
    effective_radius: float | None = None

    name: ClassVar[str] = "yigit-christoforou"
    elastic: ClassVar[bool] = False
    needs_yield_strength: ClassVar[bool] = True
    kernel = staticmethod(_yigit_christoforou_kernel)

    def __post_init__(self):
        require_positive("hertz_stiffness", self.hertz_stiffness, "N/m^1.5")
        require_positive("yield_indentation", self.yield_indentation, "m")
        if self.effective_radius is not None:
            require_positive("effective_radius", self.effective_radius, "m")

    @classmethod
    def from_properties(cls, effective_modulus, radius, yield_strength) -> "YigitChristoforouContact":
        """Build from E* [Pa] (eq 8), the sphere radius R [m] and S_y [Pa] (eqs 7, 9)."""
        return cls(
            hertz_stiffness(effective_modulus, radius),
            yield_indentation(yield_strength, radius, effective_modulus),
            effective_radius=radius,
        )

    @classmethod
    def from_contact_pair(cls, pair, **options) -> "YigitChristoforouContact":
        """K_h and α_y of the pair (eqs 7, 9), α_y from its yield strength; no options."""
        cls.check_options(options)
        return cls.from_properties(pair.effective_modulus, pair.effective_radius,
                                   pair.required_yield_strength())

    @classmethod
    def from_yield_scales(cls, hertz_stiffness, yield_indentation) -> "YigitChristoforouContact":
        """The law of Hertz stiffness K_h [N/m^1.5] and yield indentation α_y [m]."""
        return cls(hertz_stiffness, yield_indentation)

    # -- derived quantities -------------------------------------------------------
    @property
    def yield_scales(self):
        """``(K_h, α_y)`` [N/m^1.5, m]: the law's own parameters."""
        return self.hertz_stiffness, self.yield_indentation

    @property
    def linearised_stiffness(self):
        """``K_y = 1.5 K_h sqrt(α_y)`` [N/m], the stiffness of the linearised law (eqs 10, 18)."""
        return 1.5 * np.asarray(self.hertz_stiffness, float) * np.sqrt(np.asarray(self.yield_indentation, float))

    @property
    def yield_force(self):
        """Force at first yield ``K_h α_y^{3/2}`` [N]."""
        return np.asarray(self.hertz_stiffness, float) * np.asarray(self.yield_indentation, float) ** 1.5

    def contact_frequency(self, impactor_mass):
        """``ω = sqrt(K_h α_y^{1/2} / m_i)`` [rad/s] (seed 001 eq 12) for m_i [kg]."""
        return hertz_frequency(self.hertz_stiffness, self.yield_indentation, impactor_mass)

    def impact_number(self, impactor_mass, velocity):
        """Normalised impact velocity ``β = V0 / (ω α_y)`` [-] (seed 001 eq 11) for ``impactor_mass``
        m_i [kg] and ``velocity`` V0 [m/s]."""
        return impact_number(velocity, self.hertz_stiffness, self.yield_indentation, impactor_mass)

    def velocity_for_impact_number(self, impactor_mass, impact_number):
        """Impact velocity V0 [m/s] giving the impact number β [-] for mass m_i [kg]."""
        return velocity_for_impact_number(impact_number, self.hertz_stiffness, self.yield_indentation,
                                          impactor_mass)

    # -- ContactLaw interface -----------------------------------------------------
    @property
    def kernel_parameters(self) -> np.ndarray:
        return np.stack(
            np.broadcast_arrays(
                np.asarray(self.hertz_stiffness, float), np.asarray(self.yield_indentation, float)
            )
        )

    def _final15(self, alpha_max):
        """α_f^{3/2} (≥ 0) for α_max > α_y; meaningless (masked by callers) otherwise."""
        yield_alpha = np.asarray(self.yield_indentation, float)
        value = alpha_max**1.5 - 1.5 * np.sqrt(yield_alpha) * alpha_max + 0.5 * yield_alpha**1.5
        return np.clip(value, 0.0, None)

    def permanent_indentation(self, max_indentation):
        """``α_f`` [m] from the zero of eq (6); 0 if ``α_max ≤ α_y``."""
        alpha_max = np.clip(np.asarray(max_indentation, dtype=float), 0.0, None)
        plastic = alpha_max > np.asarray(self.yield_indentation, float)
        return np.where(plastic, self._final15(alpha_max) ** (2.0 / 3.0), 0.0)

    def loading_energy(self, max_indentation, points: int = 0):
        """Work [J] to load from 0 to α_max [m] (closed form)."""
        alpha_max = np.clip(np.asarray(max_indentation, dtype=float), 0.0, None)
        hertz = np.asarray(self.hertz_stiffness, float)
        yield_alpha = np.asarray(self.yield_indentation, float)
        excess = np.clip(alpha_max / yield_alpha - 1.0, 0.0, None)
        elastic = 0.4 * hertz * np.minimum(alpha_max, yield_alpha) ** 2.5
        plastic = hertz * yield_alpha**2.5 * (excess + 0.75 * excess**2)
        return elastic + plastic

    def indentation_for_energy(self, energy):
        """α_m [m] at which the loading work equals W [J] (closed-form inverse)."""
        work = check_energy(energy)
        hertz = np.asarray(self.hertz_stiffness, float)
        yield_alpha = np.asarray(self.yield_indentation, float)
        excess = np.clip(work / (hertz * yield_alpha**2.5) - 0.4, 0.0, None)
        plastic = yield_alpha * (1.0 + 2.0 * excess / (1.0 + np.sqrt(1.0 + 3.0 * excess)))
        return np.where(excess > 0.0, plastic, (2.5 * work / hertz) ** 0.4)

    def recovered_energy(self, max_indentation, points: int = 0):
        """Work [J] returned unloading from α_max to α_f (closed form)."""
        alpha_max = np.clip(np.asarray(max_indentation, dtype=float), 0.0, None)
        hertz = np.asarray(self.hertz_stiffness, float)
        final = np.asarray(self.permanent_indentation(alpha_max))
        return hertz * (0.4 * (alpha_max**2.5 - final**2.5) - final**1.5 * (alpha_max - final))
