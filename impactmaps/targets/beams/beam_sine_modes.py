"""Simply supported beams, every theory: closed-form modes (docs/physics_contract.md §3.2)."""

from __future__ import annotations

import math

import numpy as np

from .beam_section import (
    BeamSection,
    ModeSet,
    as_points,
    cutoff_with_min_modes,
    largest_wavenumber,
)

__all__ = ["simply_supported_modes", "simply_supported_count"]


class _SineModes(ModeSet):
    """W_j(x) = A_j sin(k_j x), Ψ_j(x) = B_j cos(k_j x)."""

    def __init__(self, frequencies, wavenumbers, deflection_amplitudes, rotation_amplitudes):
        order = np.argsort(frequencies, kind="stable")
        self.frequencies = np.asarray(frequencies, dtype=float)[order]
        self.wavenumbers = np.asarray(wavenumbers, dtype=float)[order]
        self.deflection_amplitudes = np.asarray(deflection_amplitudes, dtype=float)[order]
        self.rotation_amplitudes = np.asarray(rotation_amplitudes, dtype=float)[order]

    def deflection(self, points, count=None):
        n = self._count(count)
        x = as_points(points)[:, None]
        return self.deflection_amplitudes[:n] * np.sin(self.wavenumbers[:n] * x)

    def rotation(self, points, count=None):
        n = self._count(count)
        x = as_points(points)[:, None]
        return self.rotation_amplitudes[:n] * np.cos(self.wavenumbers[:n] * x)


def simply_supported_modes(section: BeamSection, max_frequency: float,
                           min_modes: int = 1) -> ModeSet:
    """All modes of a simply supported beam with ω ≤ ``max_frequency`` [rad/s] (≥ ``min_modes``).

    Closed form for every theory (Timoshenko: both branches and the n = 0 thickness-shear
    mode, which never takes part in an impact); formulas in docs/physics.rst.
    """
    L = section.length
    EI, rA, rI = section.bending_stiffness, section.mass_per_length, section.rotary_inertia
    n_count = max(_half_wave_count(section, max_frequency), int(min_modes), 1)
    n = np.arange(1, n_count + 1, dtype=float)
    k = n * math.pi / L
    if section.theory in ("euler", "rayleigh"):
        inertia = rA + rI * k**2
        omega = np.sqrt(EI / inertia) * k**2
        W = np.sqrt(2.0 / (L * inertia))
        modes = _SineModes(omega, k, W, -k * W)
    else:
        S = section.shear_stiffness
        lower, upper, a12, half_difference = _timoshenko_eigenvalues(section, k)
        theta = 0.5 * np.arctan2(a12, half_difference)
        c, s = np.cos(theta), np.sin(theta)
        scale = math.sqrt(2.0 / L)
        # upper (shear) branch: v = (cos θ, sin θ); lower (flexural): v = (−sin θ, cos θ)
        frequencies = np.concatenate([np.sqrt(lower), np.sqrt(upper), [math.sqrt(S / rI)]])
        wavenumbers = np.concatenate([k, k, [0.0]])
        W = np.concatenate([c, s, [0.0]]) * scale / math.sqrt(rA)
        Psi = np.concatenate([-s, c, [math.sqrt(0.5)]]) * scale / math.sqrt(rI)
        modes = _SineModes(frequencies, wavenumbers, W, Psi)
    return _trim(modes, max_frequency, min_modes)


def _half_wave_count(section: BeamSection, max_frequency: float) -> int:
    """Half-wave numbers n whose flexural wavenumber nπ/L is within that of ``max_frequency``."""
    k_max = float(largest_wavenumber(section, max_frequency))
    return int(math.floor(k_max * section.length / math.pi * (1.0 + 1e-12)))


def _timoshenko_eigenvalues(section: BeamSection, k):
    """(ω² flexural, ω² shear, a12, (a11 − a22)/2) of the SS Timoshenko beam at wavenumbers k."""
    EI, rA, rI = section.bending_stiffness, section.mass_per_length, section.rotary_inertia
    S = section.shear_stiffness
    a11 = (EI * k**2 + S) / rI
    a22 = S * k**2 / rA
    a12 = S * k / math.sqrt(rI * rA)
    half_difference = 0.5 * (a11 - a22)
    radius = np.hypot(half_difference, a12)
    upper = 0.5 * (a11 + a22) + radius
    lower = (EI * S * k**4 / (rI * rA)) / upper
    return lower, upper, a12, half_difference


def simply_supported_count(section: BeamSection, max_frequency: float) -> int:
    """Number of modes of :func:`simply_supported_modes` with ω ≤ ``max_frequency`` [rad/s], without building them."""
    L, frequency = section.length, float(max_frequency)
    EI, rA, rI = section.bending_stiffness, section.mass_per_length, section.rotary_inertia
    n_count = max(_half_wave_count(section, frequency), 1)

    def last_within(omega_of_k) -> int:
        low, high = 0, n_count + 1  # ω(low) ≤ f (n = 0: none), ω(high) > f (beyond the modes)
        while high - low > 1:
            middle = (low + high) // 2
            if float(omega_of_k(np.array([middle * math.pi / L]))[0]) <= frequency:
                low = middle
            else:
                high = middle
        return low

    if section.theory in ("euler", "rayleigh"):
        return last_within(lambda k: np.sqrt(EI / (rA + rI * k**2)) * k**2)
    flexural = last_within(lambda k: np.sqrt(_timoshenko_eigenvalues(section, k)[0]))
    shear = last_within(lambda k: np.sqrt(_timoshenko_eigenvalues(section, k)[1]))
    return flexural + shear + int(math.sqrt(section.shear_stiffness / rI) <= frequency)


def _trim(modes: _SineModes, max_frequency, min_modes) -> _SineModes:
    """Keep the modes with ω ≤ max(max_frequency, ω of the min_modes-th mode)."""
    cutoff = cutoff_with_min_modes(modes.frequencies, max_frequency, min_modes)
    keep = int(np.searchsorted(modes.frequencies, cutoff, side="right"))
    return _SineModes(modes.frequencies[:keep], modes.wavenumbers[:keep],
                      modes.deflection_amplitudes[:keep], modes.rotation_amplitudes[:keep])

