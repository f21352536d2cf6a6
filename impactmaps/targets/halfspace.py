"""A fixed half-space: the target of a compact-body impact (docs/physics_contract.md §3.1).

The struck body is so large and stiff that it does not move: its surface point has no
modes, no static compliance and takes no energy from the sphere; everything happens in
the contact. Seen through the :class:`~impactmaps.targets.base.Target` protocol it has
an empty modal basis with zero residual compliance, an infinite static stiffness
(λ = K_st/K = ∞) and a loss factor ζ = 0 for every impactor. The modal solver then
integrates ``m_i α'' = −F(α; α_max)`` alone; :func:`impactmaps.closed_forms.halfspace.halfspace_impact`
solves the same problem with an adaptive Runge–Kutta method and closed forms.
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
    """A fixed, rigid half-space: the target does not move at the impact point.

    The contact properties of its surface (modulus, yield strength) belong to the
    contact law, not to the target.
    """

    kind: ClassVar[str] = "halfspace"

    @property
    def bounded_modes(self) -> bool:
        """True: a half-space has no modes at all."""
        return True

    def modes(self, max_frequency: float, min_modes: int = 1) -> ModalBasis:
        """No modes at any frequency: an empty basis with zero residual compliance.

        Parameters
        ----------
        max_frequency : float
            Cut-off ω_max [rad/s], ≥ 0 (no mode lies below any cut-off).
        min_modes : int, optional
            Ignored: a half-space has no modes to retain.

        Returns
        -------
        ModalBasis
            ``size == 0``, ``residual_compliance == 0`` [m/N].
        """
        require_nonnegative("max_frequency", max_frequency, "rad/s")
        return ModalBasis.from_validated(np.empty(0), np.empty(0), 0.0, np.empty(0))

    def static_compliance(self) -> float:
        """Static point compliance 1/K_st = 0 [m/N]: the surface does not deflect."""
        return 0.0

    def static_stiffness(self) -> float:
        """Static point stiffness K_st = ∞ [N/m]."""
        return math.inf

    def loss_factor(self, impactor_mass, contact_stiffness):
        """Loss factor ζ = 0 [-] for every impactor: no energy leaves through the target.

        Parameters
        ----------
        impactor_mass : float or array_like
            m_i [kg], > 0.
        contact_stiffness : float or array_like
            K [N/m], > 0.

        Returns
        -------
        ndarray
            Zeros of the broadcast shape of the inputs.
        """
        require_positive("impactor_mass", impactor_mass, "kg")
        require_positive("contact_stiffness", contact_stiffness, "N/m")
        return np.zeros(np.broadcast_shapes(np.shape(impactor_mass), np.shape(contact_stiffness)))

    def impactor_mass_for(self, loss_factor, contact_stiffness):
        """No impactor mass realises a loss factor on a half-space (ζ = 0 for all masses).

        Raises
        ------
        ValueError
            Always: the valid range of ``loss_factor`` on a half-space is {0}, which
            every mass gives.
        """
        raise ValueError(
            f"loss_factor = {loss_factor!r} cannot be realised on a half-space: its loss "
            "factor is 0 for every impactor mass (valid range: none; use a beam or plate target)"
        )
