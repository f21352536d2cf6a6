"""A fixed half-space: the target of a compact-body impact (docs/physics_contract.md §3.1).

No modes, zero static compliance (λ = ∞) and ζ = 0 for every impactor: everything happens
in the contact.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from .._checks import require_nonnegative, require_positive
from .base import ModalBasis, Target

__all__ = ["HalfSpace"]


@dataclass(frozen=True)
class HalfSpace(Target):
    """A fixed, rigid half-space (its surface properties belong to the contact law)."""

    kind: ClassVar[str] = "halfspace"

    @property
    def bounded_modes(self) -> bool:
        """True: a half-space has no modes at all."""
        return True

    def modes(self, max_frequency: float, min_modes: int = 1) -> ModalBasis:
        """An empty basis with zero residual compliance, at any ``max_frequency`` ≥ 0 [rad/s]."""
        require_nonnegative("max_frequency", max_frequency, "rad/s")
        return ModalBasis.from_validated(np.empty(0), np.empty(0), 0.0, np.empty(0))

    def static_compliance(self) -> float:
        """Static point compliance 1/K_st = 0 [m/N]: the surface does not deflect."""
        return 0.0

    def static_stiffness(self) -> float:
        """Static point stiffness K_st = ∞ [N/m]."""
        return math.inf

    def loss_factor(self, impactor_mass, contact_stiffness):
        """Loss factor ζ = 0 [-] (broadcast zeros) for every ``impactor_mass`` [kg] and
        ``contact_stiffness`` [N/m]."""
        require_positive("impactor_mass", impactor_mass, "kg")
        require_positive("contact_stiffness", contact_stiffness, "N/m")
        return np.zeros(np.broadcast_shapes(np.shape(impactor_mass), np.shape(contact_stiffness)))

    def impactor_mass_for(self, loss_factor, contact_stiffness):
        """No impactor mass realises a loss factor on a half-space.

        Raises
        ------
        ValueError
            Always (ζ = 0 for every mass).
        """
        raise ValueError(
            f"loss_factor = {loss_factor!r} cannot be realised on a half-space: its loss "
            "factor is 0 for every impactor mass (valid range: none; use a beam or plate target)"
        )
