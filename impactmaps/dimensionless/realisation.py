"""From a map point (ζ, λ) to the impactor and contact that realise it on a target.

Also the simply supported Euler beam struck at mid-span, where (ζ, λ) fix every ratio.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._checks import require_positive
from .groups import (
    BEAM_LOSS_CONSTANT,
    contact_frequency,
    contact_stiffness_for_relative_stiffness,
    force_scale,
    halfspace_indentation,
)

__all__ = [
    "Realisation",
    "realise",
    "ss_euler_beam_midspan_mass_ratio",
    "ss_euler_beam_midspan_frequency_ratio",
    "ss_euler_beam_midspan_loss_factor",
]


def _array(value) -> np.ndarray:
    return np.asarray(value, dtype=float)


# ---------------------------------------------------------------------------------
# From (ζ, λ) to an impactor
# ---------------------------------------------------------------------------------
@dataclass(frozen=True)
class Realisation:
    """The impactor and contact that realise a point (ζ, λ) of the map on a target.

    Attributes
    ----------
    impactor_mass : float or ndarray
        m_i [kg].
    contact_stiffness : float or ndarray
        K [N/m].
    contact_frequency : float or ndarray
        ω = sqrt(K/m_i) [rad/s].
    loss_factor : float or ndarray
        ζ [-].
    relative_stiffness : float or ndarray
        λ = K_st/K [-].
    """

    impactor_mass: float
    contact_stiffness: float
    contact_frequency: float
    loss_factor: float
    relative_stiffness: float

    def __post_init__(self):
        require_positive("impactor_mass", self.impactor_mass, "kg")
        require_positive("contact_stiffness", self.contact_stiffness, "N/m")
        require_positive("contact_frequency", self.contact_frequency, "rad/s")
        require_positive("loss_factor", self.loss_factor)
        require_positive("relative_stiffness", self.relative_stiffness)

    @property
    def time_scale(self):
        """1/ω [s]: ``t = τ/ω``."""
        return 1.0 / _array(self.contact_frequency)

    def force_scale(self, velocity):
        """m_i V0 ω [N] for impact velocity ``velocity`` [m/s]: ``F = F̄ · m_i V0 ω``."""
        return force_scale(self.impactor_mass, velocity, self.contact_frequency)

    def indentation_scale(self, velocity):
        """α* = V0/ω [m] for impact velocity ``velocity`` [m/s]: ``w = w̄ · α*``."""
        return halfspace_indentation(velocity, self.contact_frequency)


def realise(target, loss_factor, relative_stiffness) -> Realisation:
    """The impactor mass and contact stiffness giving ``loss_factor`` ζ and ``relative_stiffness``
    λ (> 0 [-], broadcast) on ``target``: ``K = K_st/λ``, ``m_i = target.impactor_mass_for(ζ, K)``.

    Returns
    -------
    Realisation

    Raises
    ------
    RuntimeError
        If the target's loss-factor formulas are not inverse to each other (1e-9 relative).
    """
    require_positive("loss_factor", loss_factor)
    require_positive("relative_stiffness", relative_stiffness)
    zeta, lam = np.broadcast_arrays(_array(loss_factor), _array(relative_stiffness))
    static_stiffness = float(target.static_stiffness())
    require_positive("static stiffness of the target", static_stiffness, "N/m")
    stiffness = contact_stiffness_for_relative_stiffness(static_stiffness, lam)
    mass = _array(target.impactor_mass_for(zeta, stiffness))
    check = _array(target.loss_factor(mass, stiffness))
    if not np.allclose(check, zeta, rtol=1e-9, atol=0.0):
        raise RuntimeError(
            f"{type(target).__name__}.loss_factor(impactor_mass_for(ζ, K), K) does not "
            f"return ζ (got {check!r} for ζ = {zeta!r}): the target's loss-factor formulas "
            "are inconsistent"
        )
    omega = contact_frequency(stiffness, mass)
    if zeta.ndim == 0:
        return Realisation(float(mass), float(stiffness), float(omega), float(zeta),
                           float(lam))
    return Realisation(mass, stiffness, omega, zeta.copy(), lam.copy())


# ---------------------------------------------------------------------------------
# Simply supported Euler beam struck at mid-span: (ζ, λ) fix everything
# ---------------------------------------------------------------------------------
def ss_euler_beam_midspan_mass_ratio(loss_factor, relative_stiffness):
    """Mass ratio ``μ = m_i/(m'L) = (4 sqrt(2π) ζ (λ/48)^{1/4})^{4/3}`` [-] of the mid-span SS
    Euler beam, for ζ_b, λ > 0 [-]."""
    require_positive("loss_factor", loss_factor)
    require_positive("relative_stiffness", relative_stiffness)
    return (BEAM_LOSS_CONSTANT * _array(loss_factor)
            * (_array(relative_stiffness) / 48.0) ** 0.25) ** (4.0 / 3.0)


def ss_euler_beam_midspan_frequency_ratio(loss_factor, relative_stiffness):
    """First beam frequency over contact frequency ``ω_1/ω = sqrt(π⁴ μ λ/48)`` [-] (mid-span SS
    Euler beam; ζ_b, λ > 0 [-])."""
    mu = ss_euler_beam_midspan_mass_ratio(loss_factor, relative_stiffness)
    return np.sqrt(math.pi**4 * mu * _array(relative_stiffness) / 48.0)


def ss_euler_beam_midspan_loss_factor(mass_ratio, relative_stiffness):
    """Loss factor ζ_b [-] of the mid-span SS Euler beam from ``mass_ratio`` μ and λ (> 0 [-])."""
    require_positive("mass_ratio", mass_ratio)
    require_positive("relative_stiffness", relative_stiffness)
    return (_array(mass_ratio) ** 0.75
            / (BEAM_LOSS_CONSTANT * (_array(relative_stiffness) / 48.0) ** 0.25))
