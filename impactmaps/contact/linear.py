"""Linear contact ``F = K α`` (seed 001 eq 18), the law behind the ζ–λ maps."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numba
import numpy as np

from .._checks import require_positive
from .base import ContactLaw, check_energy, register_contact_law
from .plastic.yigit_christoforou import YigitChristoforouContact

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
    stiffness_unit: ClassVar[str] = "N/m"
    elastic: ClassVar[bool] = True
    needs_yield_strength: ClassVar[bool] = True
    kernel = staticmethod(_linear_kernel)

    def __post_init__(self):
        require_positive("stiffness", self.stiffness, "N/m")

    @classmethod
    def from_contact_pair(cls, pair, **options) -> "LinearContact":
        """``K = K_y = 1.5 K_h sqrt(α_y)`` of the pair (seed 001 eqs 10, 18); no options.

        The linearised Yigit–Christoforou law: it needs the pair's yield strength.
        """
        cls.check_options(options)
        plastic = YigitChristoforouContact.from_contact_pair(pair)
        return cls(float(plastic.linearised_stiffness))

    @property
    def linear_stiffness(self):
        """K [N/m] (a float for a single law, an array for a batch)."""
        if type(self.stiffness) is float:  # noqa: E721 (the common single law, without NumPy: the same float)
            return self.stiffness
        stiffness = np.asarray(self.stiffness, float)
        return float(stiffness) if stiffness.ndim == 0 else stiffness

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
        """Equal to :meth:`loading_energy` [J] (elastic)."""
        return self.loading_energy(max_indentation)

    def indentation_for_energy(self, energy):
        """``α_m = sqrt(2 W / K)`` [m], the inverse of :meth:`loading_energy` at W [J]."""
        return np.sqrt(2.0 * check_energy(energy) / np.asarray(self.stiffness, float))
