"""The section of a straight uniform beam, its dispersion and the mode-set interface."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["BeamSection", "ModeSet", "largest_wavenumber", "frequency_at_wavenumber",
           "cutoff_with_min_modes", "as_points"]


# ---------------------------------------------------------------------------------
# Section description and dispersion
# ---------------------------------------------------------------------------------
@dataclass(frozen=True)
class BeamSection:
    """The mechanical description of a uniform beam used by the mode solvers (build with :meth:`effective`).

    Attributes
    ----------
    length : float
        L [m].
    bending_stiffness : float
        bD11 = EI [N·m²].
    shear_stiffness : float
        S = kGA [N]; ``math.inf`` unless Timoshenko.
    mass_per_length : float
        ρA [kg/m].
    rotary_inertia : float
        ρI [kg·m]; 0 for Euler.
    theory, supports : str
        As :data:`~impactmaps.targets.options.BEAM_THEORIES`, :data:`~impactmaps.targets.options.BEAM_SUPPORTS`.
    """

    length: float
    bending_stiffness: float
    shear_stiffness: float
    mass_per_length: float
    rotary_inertia: float
    theory: str
    supports: str

    @classmethod
    def effective(cls, length, bending_stiffness, shear_stiffness, mass_per_length,
                  rotary_inertia, theory, supports) -> "BeamSection":
        """The section as seen by ``theory``: S = ∞ unless Timoshenko, ρI = 0 for Euler."""
        return cls(
            float(length),
            float(bending_stiffness),
            float(shear_stiffness) if theory == "timoshenko" else math.inf,
            float(mass_per_length),
            float(rotary_inertia) if theory != "euler" else 0.0,
            theory,
            supports,
        )

    @property
    def shear_compliance(self) -> float:
        """1/S [1/N] (0 for Euler and Rayleigh)."""
        return 0.0 if math.isinf(self.shear_stiffness) else 1.0 / self.shear_stiffness


def largest_wavenumber(section: BeamSection, angular_frequency):
    """Largest real wavenumber k [rad/m] of free flexural waves at ω [rad/s] (bounds every mode below ω)."""
    omega2 = np.asarray(angular_frequency, dtype=float) ** 2
    EI, rA, rI = section.bending_stiffness, section.mass_per_length, section.rotary_inertia
    if section.theory == "euler":
        return (omega2 * rA / EI) ** 0.25
    if section.theory == "rayleigh":
        k2 = (rI * omega2 + np.sqrt((rI * omega2) ** 2 + 4.0 * EI * rA * omega2)) / (2.0 * EI)
        return np.sqrt(k2)
    S = section.shear_stiffness
    # discriminant written without cancellation: ω⁴(ρI S − ρA EI)² + 4 EI S² ρA ω²
    root = np.sqrt(omega2**2 * (rI * S - rA * EI) ** 2 + 4.0 * EI * S**2 * rA * omega2)
    k2 = (omega2 * (rI * S + rA * EI) + root) / (2.0 * EI * S)
    return np.sqrt(k2)


class ModeSet:
    """Mass-normalised modes of a beam, ascending in frequency (``frequencies`` ω_j [rad/s]).

    ``deflection(points, count=None)`` and ``rotation(points, count=None)`` give W_j
    [kg^-1/2] and Ψ_j [kg^-1/2 m^-1], shape (n_points, count).
    """

    frequencies: np.ndarray

    def __len__(self) -> int:
        return int(self.frequencies.size)

    def _count(self, count):
        return self.frequencies.size if count is None else int(count)

    def deflection(self, points, count=None) -> np.ndarray:  # pragma: no cover - abstract
        raise NotImplementedError

    def rotation(self, points, count=None) -> np.ndarray:  # pragma: no cover - abstract
        raise NotImplementedError


def as_points(points) -> np.ndarray:
    """Points x [m] as a flat float array."""
    return np.atleast_1d(np.asarray(points, dtype=float)).ravel()


def cutoff_with_min_modes(frequencies, max_frequency, min_modes) -> float:
    """max(max_frequency, ω of the min_modes-th mode) [rad/s] for ascending ``frequencies``."""
    cutoff = float(max_frequency)
    if int(min_modes) >= 1 and len(frequencies):
        cutoff = max(cutoff, float(frequencies[min(int(min_modes), len(frequencies)) - 1]))
    return cutoff


def frequency_at_wavenumber(section: BeamSection, wavenumber: float) -> float:
    """Lowest-branch frequency ω(k) [rad/s] of free waves of the infinite beam."""
    EI, rA, rI = section.bending_stiffness, section.mass_per_length, section.rotary_inertia
    k = float(wavenumber)
    if section.theory in ("euler", "rayleigh"):
        return math.sqrt(EI * k**4 / (rA + rI * k**2))
    S = section.shear_stiffness
    a11, a22, a12 = (EI * k**2 + S) / rI, S * k**2 / rA, S * k / math.sqrt(rI * rA)
    upper = 0.5 * (a11 + a22) + math.hypot(0.5 * (a11 - a22), a12)
    return math.sqrt(EI * S * k**4 / (rI * rA) / upper)


