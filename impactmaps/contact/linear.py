"""Linear contact ``F = K α`` (seed 001 eq 18), the law behind the ζ–λ maps."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numba
import numpy as np

from .._checks import require_positive
from .base import ContactLaw, register_contact_law

__all__ = ["LinearContact"]


@numba.njit(cache=True)
def _linear_kernel(alpha, alpha_max, params):
    if alpha <= 0.0:
        return 0.0, 0.0
    stiffness = params[0]
    return stiffness * alpha, stiffness


@register_contact_law
@dataclass(frozen=True)
class LinearContact(ContactLaw):
    """Linear elastic contact spring, ``F = K α`` for α > 0, else 0.

    Parameters
    ----------
    stiffness : float or array_like
        Contact stiffness K [N/m] (``K_y`` of seed 001 eq 18).
    """

    stiffness: float

    name: ClassVar[str] = "linear"
    elastic: ClassVar[bool] = True
    kernel = staticmethod(_linear_kernel)

    def __post_init__(self):
        require_positive("stiffness", self.stiffness, "N/m")

    @property
    def kernel_parameters(self) -> np.ndarray:
        return np.asarray(self.stiffness, dtype=float)[None, ...]

    def permanent_indentation(self, max_indentation):
        return np.zeros_like(np.asarray(max_indentation, dtype=float))

    def loading_energy(self, max_indentation, points: int = 0):
        """Stored energy ½ K α_max² [J]."""
        alpha_max = np.asarray(max_indentation, dtype=float)
        return 0.5 * np.asarray(self.stiffness, float) * np.clip(alpha_max, 0, None) ** 2

    def recovered_energy(self, max_indentation, points: int = 0):
        return self.loading_energy(max_indentation)
