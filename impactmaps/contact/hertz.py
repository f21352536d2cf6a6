"""Hertz contact ``F = K_h α^{3/2}`` of a sphere on a flat (seed 001 eqs 4, 7, 8).

Elastic, no history: unloading retraces loading and nothing is dissipated.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numba
import numpy as np

from .._checks import require_positive
from .base import ContactLaw, check_energy, register_contact_law
from .geometry import effective_modulus

__all__ = ["HertzContact", "hertz_stiffness"]


def hertz_stiffness(effective_modulus, radius):
    """Hertz contact stiffness ``K_h = (4/3) sqrt(R) E*`` [N/m^1.5] of ``effective_modulus`` E* [Pa]
    and ``radius`` R [m]."""
    require_positive("effective_modulus", effective_modulus, "Pa")
    require_positive("radius", radius, "m")
    return 4.0 / 3.0 * np.sqrt(np.asarray(radius, float)) * np.asarray(effective_modulus, float)


@numba.njit(cache=True)
def _hertz_kernel(alpha, alpha_max, params):
    if alpha <= 0.0:
        return 0.0, 0.0
    stiffness = params[0]
    root = math.sqrt(alpha)
    return stiffness * alpha * root, 1.5 * stiffness * root


@register_contact_law
@dataclass(frozen=True)
class HertzContact(ContactLaw):
    """Hertz elastic contact, ``F = K_h α^{3/2}`` for α > 0, else 0 (seed 001 eq 4).

    Parameters
    ----------
    stiffness : float or array_like
        Hertz stiffness K_h [N/m^1.5].
    effective_radius : float, optional
        R [m] of the pair, when known (contact radius ``sqrt(R α)``); not part of the law.
    """

    stiffness: float
    effective_radius: float | None = None

    name: ClassVar[str] = "hertz"
    stiffness_unit: ClassVar[str] = "N/m^1.5"
    elastic: ClassVar[bool] = True
    needs_yield_strength: ClassVar[bool] = False
    kernel = staticmethod(_hertz_kernel)

    def __post_init__(self):
        require_positive("stiffness", self.stiffness, "N/m^1.5")
        if self.effective_radius is not None:
            require_positive("effective_radius", self.effective_radius, "m")

    @classmethod
    def from_contact_pair(cls, pair, **options) -> "HertzContact":
        """``K_h = (4/3) sqrt(R) E*`` of the pair (seed 001 eqs 7–8); no options."""
        cls.check_options(options)
        return cls(float(hertz_stiffness(pair.effective_modulus, pair.effective_radius)),
                   effective_radius=float(pair.effective_radius))

    @classmethod
    def from_geometry(cls, effective_modulus, radius) -> "HertzContact":
        """Build from the effective modulus E* [Pa] and effective radius R [m]."""
        return cls(hertz_stiffness(effective_modulus, radius), effective_radius=radius)

    @classmethod
    def from_sphere(cls, radius, impactor_material, target_material) -> "HertzContact":
        """Sphere of radius R [m] on a flat target; E* from both materials
        (``youngs_modulus`` [Pa], ``poisson_ratio`` [-])."""
        modulus = effective_modulus(
            impactor_material.youngs_modulus,
            impactor_material.poisson_ratio,
            target_material.youngs_modulus,
            target_material.poisson_ratio,
        )
        return cls.from_geometry(modulus, radius)

    @property
    def kernel_parameters(self) -> np.ndarray:
        return np.asarray(self.stiffness, dtype=float)[None, ...]

    def tangent_stiffness(self, indentation, max_indentation=0.0):
        """Tangent stiffness ``1.5 K_h sqrt(α)`` [N/m] for α > 0 [m], else 0: the kernel's
        arithmetic in NumPy (the same bits), so that reading a Hertz map loads no compiled kernel."""
        alpha = np.asarray(indentation, dtype=float)
        stiffness = np.asarray(self.stiffness, dtype=float)
        with np.errstate(invalid="ignore"):
            values = np.where(alpha <= 0.0, 0.0, 1.5 * stiffness * np.sqrt(alpha))
        shape = np.broadcast_shapes(alpha.shape, np.shape(max_indentation), stiffness.shape)
        return np.array(np.broadcast_to(values, shape))

    @property
    def hertzian_stiffness(self):
        """K_h [N/m^1.5] (:attr:`stiffness`)."""
        return self.stiffness

    def permanent_indentation(self, max_indentation):
        """Zero [m]: the Hertz law is elastic."""
        return np.zeros_like(np.asarray(max_indentation, dtype=float))

    def loading_energy(self, max_indentation, points: int = 0):
        """Stored energy ``(2/5) K_h α_max^{5/2}`` [J] (closed form)."""
        alpha_max = np.clip(np.asarray(max_indentation, dtype=float), 0.0, None)
        return 0.4 * np.asarray(self.stiffness, float) * alpha_max**2.5

    def recovered_energy(self, max_indentation, points: int = 0):
        """Equal to :meth:`loading_energy` [J] (elastic)."""
        return self.loading_energy(max_indentation)

    def indentation_for_energy(self, energy):
        """``α_m = (5 W / (2 K_h))^{2/5}`` [m], the inverse of :meth:`loading_energy` at W [J]."""
        return (2.5 * check_energy(energy) / np.asarray(self.stiffness, float)) ** 0.4
